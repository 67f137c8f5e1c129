# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Flat-punch indentation in silico: the paper's nanoindentation experiment (§ 4.1, Fig. 6).

Rigid circular flat punches (--punch-diameter, default the paper's 54.1, 108.7 and 502.6 µm)
press on the surface at increasing peak loads (--peak-loads, default ten levels doubling up to
500 mN); at each peak the unloading stiffness K of the elastic–perfectly-plastic contact
(pressure capped at --hardness) is measured with the plastic state frozen, as Barber's initial
slope and as the secant of a partial unloading by --unload-fraction, and turned into
E_c = √π·K/(2√A) (A the punch area). The elastic solution (H = ∞) and Eq. 2 truncation run on
the same punch disks and placements (--placements random positions per punch, apart, from
--placement-seed).

Writes OUT/indent.csv (one row per punch × placement × peak; SI units in the column names),
OUT/indent.json (settings, the fits E_c/E = β·[F/(E·A)]^α per model, provenance; strict JSON:
a hardness of null is ∞) and OUT/indent.png (E_c/E against F/(E·A), log–log, as Fig. 6). All or
nothing: the files are moved into OUT only when every one of them is written.

Exit status: 0; 2 for bad input (one line naming the option and its allowed range); 3 when a
solve did not converge (the outputs are written and flag it), unless --accept-unconverged.
"""

from __future__ import annotations

import argparse
import re
import sys
import warnings

from .._support.atomic import staged_output
from ..contact.settings import SolverSettings
from ..material import Material
from ..params import add_options, from_args
from ._common import add_run_outputs, add_surface_source, surface_from_args

NAME = "indent"
HELP = "flat-punch indentation with partial unloadings, against truncation (Fig. 6)"
EXIT_NOT_CONVERGED = 3
"""Exit status when any solve did not converge (without --accept-unconverged)."""

_OPTION = {
    "punch_diameter": "--punch-diameter", "punch_diameters": "--punch-diameter",
    "peak_loads": "--peak-loads", "unload_fraction": "--unload-fraction",
    "placements": "--placements", "hardness": "--hardness", "placement_seed": "--placement-seed",
    "truncation_increments": "--truncation-increments",
}  # fmt: skip


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc indent``."""
    from ..indent.protocol import MATERIAL_DEFAULTS, IndentProtocol

    add_surface_source(p)
    add_options(p, IndentProtocol, title="indentation protocol")
    add_options(p, Material, title="material (default: aluminium alloy against diamond)",
                defaults=MATERIAL_DEFAULTS)  # fmt: skip
    add_options(p, SolverSettings, title="contact solver (free half-space on each punch's window)",
                exclude=("substrate",))  # fmt: skip
    p.add_argument(
        "--no-elastic", action="store_true",
        help="skip the elastic solution (H = ∞) on the same punches (its columns are NaN)",
    )  # fmt: skip
    p.add_argument(
        "--accept-unconverged", action="store_true",
        help=f"exit 0 even when a solve did not converge (default: exit {EXIT_NOT_CONVERGED})",
    )  # fmt: skip
    add_run_outputs(p, "indent", "skip indent.png")


def _options(msg: str) -> str:
    """A library message with the parameter names replaced by their option names."""
    return re.sub(r"\b(" + "|".join(_OPTION) + r")\b", lambda m: _OPTION[m.group(1)], msg)


def run(args: argparse.Namespace) -> int:
    """Run the experiment and write the outputs."""
    from .._support.version import __version__
    from .._support.provenance import git_commit
    from ..indent import IndentProtocol, PlacementOverlapWarning, indent
    from ..indent.protocol import MATERIAL_DEFAULTS

    try:
        material = from_args(Material, args, defaults=MATERIAL_DEFAULTS)
        protocol = from_args(IndentProtocol, args)
        settings = from_args(SolverSettings, args, substrate="free")
        s = surface_from_args(args)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", PlacementOverlapWarning)
            res = indent(
                s, punch_diameter=protocol.punch_diameters, peak_loads=protocol.peak_loads,
                unload_fraction=protocol.unload_fraction, material=material,
                placements=protocol.placements, seed=protocol.placement_seed, overlap=protocol.overlap,
                truncation_increments=protocol.truncation_increments, settings=settings,
                elastic=not args.no_elastic, device=args.device,
                progress=not args.no_progress and sys.stderr.isatty(),
            )  # fmt: skip
    except ValueError as exc:
        raise ValueError(_options(str(exc))) from None
    for w in caught:
        if issubclass(w.category, PlacementOverlapWarning):
            print(f"warptrunc {NAME}: warning: {w.message}", file=sys.stderr)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    provenance = {"warptrunc_version": __version__, "git_commit": git_commit(),
                  "command": ["warptrunc", *sys.argv[1:]]}  # fmt: skip
    files = ["indent.csv", "indent.json"]
    with staged_output(args.out) as out:  # all or nothing
        res.to_csv(out / "indent.csv")
        res.to_json(out / "indent.json", provenance=provenance)
        if not args.no_plot:
            from ..plot import indentation

            indentation(res, out / "indent.png",
                        title=f"{s.nx}×{s.ny} over {s.lx * 1e3:.3g} mm, R$_t$ = "
                        f"{s.Rt * 1e6:.3g} µm, H = {_h(material)}")  # fmt: skip
            files.append("indent.png")
    fits = res.fits()
    lines = [
        f"{s.nx}×{s.ny} surface over {s.lx * 1e3:.4g} × {s.ly * 1e3:.4g} mm, R_t = "
        f"{s.Rt * 1e6:.4g} µm; E = {material.E / 1e9:.4g} GPa, E* = "
        f"{material.contact_modulus / 1e9:.4g} GPa, H = {_h(material)}; {res.peak_load.size} "
        f"cycles in {res.settings['seconds']['total_s']:.3g} s"
    ]
    for name, fit in fits.items():
        lines.append(f"  {name:24s} " + ("no fit" if fit is None else
                     f"E_c/E = {fit.beta:.4g}·[F/(E·A)]^{fit.alpha:.4f}  (E Young's modulus; r² = {fit.r2:.4f}, "
                     f"{fit.n_points} rows)"))  # fmt: skip
    print("\n".join(lines))
    print(f"wrote {args.out}/{', '.join(files)}")
    if not res.all_converged or not (args.no_elastic or res.elastic_converged.all()):
        n_bad = int((~res.converged).sum()) + (
            0 if args.no_elastic else int((~res.elastic_converged).sum()))
        print(f"WARNING: {n_bad} cycles did not converge (flagged in indent.csv)", file=sys.stderr)
        if not args.accept_unconverged:
            print(f"warptrunc {NAME}: exit {EXIT_NOT_CONVERGED}: not every solve converged "
                  "(--accept-unconverged to exit 0)", file=sys.stderr)  # fmt: skip
            return EXIT_NOT_CONVERGED
    return 0


def _h(material: Material) -> str:
    return "∞ (elastic)" if material.elastic else f"{material.hardness / 1e9:.4g} GPa"
