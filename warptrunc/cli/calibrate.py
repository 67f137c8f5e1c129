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

from .._support.outputs import staged_output, strict_json
from .._support.provenance import provenance
from ..calibrate.settings import CalibrationSettings, CalibrationTarget
from ..params import add_options, from_args
from ._common import (
    add_device,
    add_no_progress,
    add_no_surface,
    add_out,
    add_scan_file,
    add_warnings,
    read_scan,
    warnings_of,
)

NAME = "calibrate"
HELP = "find D_in and R_t' that reproduce a scan's D and R_rms (Fig. 4), then generate"
TARGET_FIELDS = ("D", "Rrms", "Rt", "Wr", "L", "n")
"""The targets that may be typed in (default: measured on FILE)."""
LOOP_FIELDS = (
    "seeds",
    "rtol",
    "D_start",
    "D_bounds",
    "max_iter",
    "max_rounds",
    "M",
    "gamma",
    "cutoff",
)
"""The fields of :class:`CalibrationSettings` that say how the loop runs."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc calibrate``."""
    add_scan_file(p, required=False)
    t = p.add_argument_group("targets (typed in, or overriding those measured on FILE)")
    add_options(t, CalibrationSettings, only=("method", "height_scaling"))
    add_options(
        t,
        CalibrationTarget,
        only=TARGET_FIELDS,
        defaults=dict.fromkeys(TARGET_FIELDS),
        docs={"D": "target fractal dimension D (by --method)"},
    )
    c = p.add_argument_group("loop")
    add_options(c, CalibrationSettings, only=LOOP_FIELDS)
    add_no_progress(c)
    o = p.add_argument_group("output surface")
    add_options(o, CalibrationSettings, only=("n_out", "seed_out"))
    add_no_surface(o, "calibration.json")
    add_out(p)
    add_device(p)


def _target(args: argparse.Namespace, settings: CalibrationSettings) -> CalibrationTarget:
    """The targets: measured on FILE (when given), then those typed in."""
    from ..calibrate.api import target_from_surface

    s = read_scan(args)
    fixed = {"method": settings.method, "method_options": settings.method_options()}
    if s is None:
        missing = [k for k in TARGET_FIELDS if getattr(args, k) is None]
        if missing:
            raise ValueError(
                "without FILE give every target: missing " + ", ".join(f"--{k}" for k in missing)
            )
        return from_args(CalibrationTarget, args, source="given", **fixed)
    t = target_from_surface(s, settings, Wr=args.Wr, device=args.device)
    measured = {k: getattr(t, k) for k in TARGET_FIELDS}
    return from_args(
        CalibrationTarget, args, defaults=measured, source=t.source or str(args.file), **fixed
    )


def run(args: argparse.Namespace) -> int:
    """Calibrate and write the outputs."""
    from ..calibrate.api import calibrate, calibrated_surface
    from ..io import write_height_map
    from ..plausibility import check_dimensions

    settings = from_args(CalibrationSettings, args)
    target = _target(args, settings)
    print(
        f"targets: D_{target.method} = {target.D:.4f}, R_rms = {target.Rrms * 1e6:.4g} µm, "
        f"R_t = {target.Rt * 1e6:.4g} µm, W_r = {target.Wr * 1e6:.4g} µm, "
        f"{target.n[0]}×{target.n[1]} pixels over "
        f"{target.L[0] * 1e6:.4g}×{target.L[1] * 1e6:.4g} µm"
    )
    lo, hi = settings.D_bounds
    cal = calibrate(target, settings=settings, progress=not args.no_progress, device=args.device)
    d = cal.to_dict()
    d = {k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in d.items()}
    if target.source != "given":  # the D measured on the scan
        add_warnings(args, check_dimensions({target.method: target.D}))
    d["warnings"] = warnings_of(args)
    d["provenance"] = provenance(args.device)
    surf = None
    if not args.no_surface:
        surf = calibrated_surface(cal, n=settings.n_out, seed=settings.seed_out, device=args.device)
    with staged_output(args.out) as out:  # all or nothing
        (out / "calibration.json").write_text(strict_json(d))
        if surf is not None:
            write_height_map(surf, out / "surface.npz")
    print(_result_lines(cal, settings))
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


def _result_lines(cal, settings: CalibrationSettings) -> str:
    """D_in' and R_t', every evaluation at D_in' (at R_t in the D loop, at R_t' after the R_t
    loop), the tolerance and its basis, and whether the last evaluation met it."""
    t = cal.target
    at = [i for i in range(cal.iterations) if cal.history_D_in[i] == cal.D_in]
    evals = "; ".join(
        f"R_t = {cal.history_Rt[i] * 1e6:.4g} µm: D_{t.method} = {cal.history_D_out[i]:.4f} ± "
        f"{cal.history_D_out_std[i]:.4f}"
        for i in at
    )
    basis = (
        f"{settings.scatter_sd:g} sd of D_out over the seeds at the first D_in, tighter than "
        f"rtol·D = {cal.rtol * t.D:.4f}"
        if cal.tolerance_basis == "scatter"
        else f"rtol·D, rtol = {cal.rtol:g}"
    )
    miss = abs(cal.D_out - t.D)
    verdict = (
        f"converged: |D_out − D| = {miss:.4f} ≤ {cal.tolerance:.4f}"
        if cal.converged
        else f"NOT converged: |D_out − D| = {miss:.4f} > {cal.tolerance:.4f}; {cal.reason}"
    )
    return (
        f"D_in' = {cal.D_in:.4f}, R_t' = {cal.Rt * 1e6:.4g} µm, R_rms = {cal.Rrms * 1e6:.4g} µm "
        f"({cal.iterations} evaluations × {len(cal.seeds)} seeds)\n"
        f"at D_in': {evals}\n"
        f"target D_{t.method} = {t.D:.4f} ± {cal.tolerance:.4f} ({basis}); {verdict}"
    )
