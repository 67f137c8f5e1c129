# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Contact islands against truncation depth: counts, Euler characteristic, perimeters,
slit-island exponent and the applicable truncation depth (the paper's §4.3, Fig. 8, Table 2).

Writes OUT/islands.csv (one row per depth: depth_m, depth_fraction_of_Rt, n_islands,
euler_characteristic, total_perimeter_m, contact_area_m2, slit_exponent, slit_r2, then
slit_n_islands, n_contact_pixels, normalised_island_number, island_growth_rate),
OUT/indicators.json (the Table 2 depths in % of R_t, with the settings and the surface) and,
unless --no-plot, OUT/island_number.png (Fig. 8a) and OUT/slit_islands.png (Fig. 8b).
All or nothing: the files are moved into OUT only when every one of them is written.
indicators.json is strict JSON (a depth that was not found is null).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from .._support.atomic import staged_output, strict_json
from .._support.provenance import provenance
from ..islands.depths import island_curve
from ..islands.fits import applicable_depth
from ..islands.results import MIN_ISLANDS, MIN_PIXELS, IslandCurve
from ..plausibility import check_dimensions
from ._common import (
    add_device,
    add_out,
    add_surface_source,
    add_truncation,
    add_warnings,
    fraction,
    integer,
    odd_integer,
    real,
    surface_from_args,
    truncation_from_args,
    warnings_of,
)

NAME = "islands"
HELP = "contact islands against depth, slit-island exponent and the applicable depth (Fig. 8)"
DEPTH_OPTIONS = ("increments", "max_depth_fraction", "max_depth")
DEPTH_DEFAULTS = {"max_depth_fraction": 0.5}


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc islands``."""
    add_surface_source(p)
    g = p.add_argument_group("depths and islands")
    add_truncation(g, only=DEPTH_OPTIONS, defaults=DEPTH_DEFAULTS)
    g.add_argument(
        "--connectivity", type=int, choices=[4, 8], default=4,
        help="4: pixels sharing an edge form one island; 8: also pixels sharing a corner",
    )  # fmt: skip
    g.add_argument("--periodic", action="store_true", help="wrap the map around in x and y")
    g.add_argument(
        "--min-pixels", type=integer(1), default=MIN_PIXELS,
        help="smallest island in the slit-island fits (pixels)",
    )  # fmt: skip
    g.add_argument(
        "--counts-only", action="store_true",
        help="island counts, χ and perimeters only (no per-island statistics; fastest)",
    )  # fmt: skip
    g.add_argument(
        "--snapshots", type=fraction(), nargs="*", default=[0.1, 0.2, 0.3, 0.4],
        help="depths (fractions of R_t) whose islands are drawn in slit_islands.png",
    )  # fmt: skip
    i = p.add_argument_group("applicable-depth indicators")
    i.add_argument(
        "--exponent-tolerance", type=real(0.0, 1.0), default=0.05,
        help="relative drop of the slit-island exponent below its plateau that ends fractality",
    )  # fmt: skip
    i.add_argument(
        "--min-islands", type=integer(MIN_ISLANDS), default=50,
        help="fewest fitted islands for a depth's exponent to count",
    )  # fmt: skip
    i.add_argument(
        "--plateau-width", type=fraction(), default=0.1,
        help="width of the plateau window (fraction of R_t)",
    )  # fmt: skip
    i.add_argument(
        "--persist", type=fraction(lo_open=False), default=0.02,
        help="depth span (fraction of R_t) a drop of the exponent must last to count",
    )  # fmt: skip
    i.add_argument(
        "--smooth", type=odd_integer(1), default=5, help="odd smoothing window (depth samples)"
    )
    add_device(p)
    add_out(p)
    p.add_argument("--no-plot", action="store_true", help="skip the PNGs")
    p.add_argument("--progress", action="store_true", help="show a progress bar")


def run(args: argparse.Namespace) -> int:
    """Analyse the islands and write the outputs."""
    t = truncation_from_args(args, DEPTH_DEFAULTS)
    s = surface_from_args(args)
    snaps = [f * s.Rt for f in args.snapshots] if args.snapshots else None
    curve = island_curve(
        s, t.increments, max_depth=t.max_depth,
        max_depth_fraction=t.max_depth_fraction, connectivity=args.connectivity,
        periodic=args.periodic, statistics=not args.counts_only, min_pixels=args.min_pixels,
        snapshot_depths=None if args.counts_only else snaps, progress=args.progress,
        device=args.device,
    )  # fmt: skip
    ind = applicable_depth(
        curve, exponent_tolerance=args.exponent_tolerance, min_islands=args.min_islands,
        plateau_width=args.plateau_width, persist=args.persist, smooth=args.smooth,
    )  # fmt: skip
    if math.isfinite(ind.plateau_exponent):  # D = 2β + 1 of the slit-island plateau
        add_warnings(args, check_dimensions({"slit": 2.0 * ind.plateau_exponent + 1.0}))
    with staged_output(args.out) as out:  # all or nothing
        _write(args, s, curve, ind, out)

    def pct(v: float) -> str:
        return "n/a" if not math.isfinite(v) else f"{100 * v / s.Rt:.2f} % R_t"

    print(
        f"{s.nx}×{s.ny} surface, R_t = {s.Rt * 1e6:.4g} µm; {curve.depth.size - 1} increments to "
        f"ω_max = {curve.depth[-1] * 1e6:.4g} µm; up to {curve.n_islands.max()} islands\n"
        f"max. growth rate of the island number at {pct(ind.max_growth_depth)}; island-count "
        f"peak at {pct(ind.peak_depth)}; slit exponent stays within "
        f"{100 * args.exponent_tolerance:g} % of {_num(ind.plateau_exponent)} down to "
        f"{pct(ind.fractal_depth)}{' (never left it)' if ind.fractal_depth_censored else ''}\n"
        f"wrote {args.out}/islands.csv, indicators.json"
        + (
            ""
            if args.no_plot
            else ", island_number.png" + (", slit_islands.png" if curve.sizes else "")
        )
    )
    return 0


def _num(v: float) -> str:
    return f"{v:.3f}" if math.isfinite(v) else "n/a (too few islands to fit)"


def _write(args: argparse.Namespace, s, curve: IslandCurve, ind, out: Path) -> None:
    """islands.csv, indicators.json and the plots, under ``out``."""
    curve.to_csv(out / "islands.csv")
    info = {
        **ind.to_dict(),
        "connectivity": curve.connectivity,
        "periodic": curve.periodic,
        "min_pixels": curve.min_pixels,
        "increments": int(curve.depth.size - 1),
        "max_depth_m": float(curve.depth[-1]),
        "max_island_count": int(curve.n_islands.max()),
        "surface": s.to_dict(),
        "warnings": warnings_of(args),
        "provenance": provenance(args.device),
    }
    (out / "indicators.json").write_text(strict_json(info))
    if not args.no_plot:
        from .. import plot

        title = f"{s.nx}×{s.ny}, R$_t$ = {s.Rt * 1e6:.3g} µm, {curve.connectivity}-connected"
        plot.island_number(curve, ind, title=title, path=out / "island_number.png")
        if curve.sizes:
            plot.slit_islands(curve, title=title, path=out / "slit_islands.png")
