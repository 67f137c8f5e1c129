# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Calibrate WM inputs (D_in, R_t') to a scan's descriptors (Fig. 4) and generate the surface.

Targets come from FILE (or ``--input FILE``; D by --method, R_rms, R_t, W_r, size and resolution) or are typed in
(--D, --Rrms, --Rt, --Wr, --L, --n); typed-in values override those of FILE. Writes
OUT/calibration.json (the calibrated inputs, the targets and every evaluation) and
OUT/surface.npz (the calibrated surface at --n-out pixels per side, default the scan's).
All or nothing: both files are moved into OUT only when both are written; calibration.json is
strict JSON (a value that could not be computed is null).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from .._support.atomic import staged_output, strict_json
from .._support.provenance import provenance
from ..calibrate import CalibrationTarget, calibrate, calibrated_surface, target_from_surface
from ..fractal import METHODS
from ..io import write_height_map
from ..params import add_options
from ..plausibility import check_dimensions
from ..wm_params import WMSpec
from ._common import add_device, add_warnings, integer, output_dir, positive, real, warnings_of
from .describe import (
    add_height_scaling,
    add_scan_arguments,
    method_options,
    read_scan_args,
    scan_file,
)

NAME = "calibrate"
HELP = "find D_in and R_t' that reproduce a scan's D and R_rms (Fig. 4), then generate"
TARGET_FIELDS = ("D", "Wr", "L", "n", "Rt")
"""The targets typed in with the options of :class:`WMSpec` (default: measured on FILE)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc calibrate``."""
    add_scan_arguments(p, required=False)
    t = p.add_argument_group("targets (typed in, or overriding those measured on FILE)")
    t.add_argument("--method", choices=list(METHODS), default="tri", help="fractal method matched")
    add_height_scaling(t)
    t.add_argument("--Rrms", type=positive("m"), default=None, help="target R_rms (m)")
    add_options(
        t, WMSpec, only=TARGET_FIELDS, defaults=dict.fromkeys(TARGET_FIELDS),
        docs={"D": "target fractal dimension (by --method)", "Rt": "scan's R_t, input of the D loop",
              "Wr": "roll-off wavelength W_r", "L": "scan side L, or Lx Ly",
              "n": "scan pixels per side, or nx ny"},
    )  # fmt: skip
    c = p.add_argument_group("loop")
    c.add_argument(
        "--seeds", type=integer(0), nargs="+", default=[0, 1, 2], help="seeds per evaluation"
    )
    c.add_argument("--rtol", type=real(0.0, 1.0), default=0.05, help="relative tolerance on D")
    c.add_argument("--max-iter", type=integer(2, 1000), default=12, help="evaluations per D loop")
    c.add_argument(
        "--D-bounds", type=real(2.0, 3.0), nargs=2, default=[2.02, 2.98], metavar=("LO", "HI"),
        help="search interval of D_in, inside (2, 3); a result on a bound is reported as such",
    )  # fmt: skip
    c.add_argument("--no-progress", action="store_true", help="no progress bar")
    o = p.add_argument_group("output surface")
    o.add_argument(
        "--n-out", type=integer(2), nargs="+", default=None,
        help="output pixels per side (or nx ny)",
    )
    o.add_argument("--seed-out", type=integer(0), default=0, help="seed of the output surface")
    o.add_argument("--no-surface", action="store_true", help="write calibration.json only")
    p.add_argument("--out", type=output_dir, default=Path("out"), help="output folder")
    add_device(p)


def _pair(v, option: str):
    if v is None:
        return None
    if len(v) == 1:
        return (v[0], v[0])
    if len(v) == 2:
        return (v[0], v[1])
    raise ValueError(f"{option} takes one or two values, got {len(v)}: {v!r}")


def run(args: argparse.Namespace) -> int:
    """Calibrate and write the outputs."""

    if scan_file(args) is not None:
        s = read_scan_args(args)
        opts = method_options(args.method, args.height_scaling)
        t = target_from_surface(
            s, args.method, Wr=args.Wr, method_options=opts, device=args.device
        )
        fields = t.to_dict()
        target = CalibrationTarget(
            D=args.D if args.D is not None else t.D,
            method=args.method,
            Rrms=args.Rrms if args.Rrms is not None else t.Rrms,
            Rt=args.Rt if args.Rt is not None else t.Rt,
            Wr=t.Wr,
            L=_pair(args.L, "--L") or t.L,
            n=_pair(args.n, "--n") or t.n,
            source=fields["source"] or str(args.file),
            method_options=opts,
        )
    else:
        missing = [k for k in ("D", "Rrms", "Rt", "Wr", "L", "n") if getattr(args, k) is None]
        if missing:
            raise ValueError(
                "without FILE give every target: missing " + ", ".join(f"--{k}" for k in missing)
            )
        target = CalibrationTarget(
            D=args.D, method=args.method, Rrms=args.Rrms, Rt=args.Rt, Wr=args.Wr,
            L=_pair(args.L, "--L"), n=_pair(args.n, "--n"), source="given",
            method_options=method_options(args.method, args.height_scaling),
        )  # fmt: skip
    print(
        f"targets: D_{target.method} = {target.D:.4f}, R_rms = {target.Rrms * 1e6:.4g} µm, "
        f"R_t = {target.Rt * 1e6:.4g} µm, W_r = {target.Wr * 1e6:.4g} µm, "
        f"{target.n[0]}×{target.n[1]} pixels over "
        f"{target.L[0] * 1e6:.4g}×{target.L[1] * 1e6:.4g} µm"
    )
    lo, hi = args.D_bounds
    if not lo < hi:
        raise ValueError(f"--D-bounds must be LO < HI inside (2, 3), got {lo:g} {hi:g}")
    cal = calibrate(
        target, seeds=args.seeds, rtol=args.rtol, max_iter=args.max_iter, D_bounds=(lo, hi),
        progress=not args.no_progress, device=args.device,
    )  # fmt: skip
    d = cal.to_dict()
    d = {k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in d.items()}
    if target.source != "given":  # the D measured on the scan
        add_warnings(args, check_dimensions({target.method: target.D}))
    d["warnings"] = warnings_of(args)
    d["provenance"] = provenance(args.device)
    surf = None
    if not args.no_surface:
        n_out = _pair(args.n_out, "--n-out")
        surf = calibrated_surface(cal, n=n_out, seed=args.seed_out, device=args.device)
    with staged_output(args.out) as out:  # all or nothing
        (out / "calibration.json").write_text(strict_json(d))
        if surf is not None:
            write_height_map(surf, out / "surface.npz")
    print(
        f"D_in' = {cal.D_in:.4f}, R_t' = {cal.Rt * 1e6:.4g} µm → D_{target.method} = "
        f"{cal.D_out:.4f} ± {cal.D_out_std:.4f}, R_rms = {cal.Rrms * 1e6:.4g} µm "
        f"({cal.iterations} evaluations × {len(cal.seeds)} seeds)"
    )
    if cal.bound is not None:
        print(
            f"note: D_in' is the {cal.bound} bound of --D-bounds ({lo:g}, {hi:g}): the target is "
            "met within --rtol only there, not at an interior D_in (widen --D-bounds if the "
            "WM model allows it)"
        )
    written = [str(args.out / "calibration.json")]
    if surf is not None:
        written.append(str(args.out / "surface.npz"))
    print("wrote " + ", ".join(written))
    return 0
