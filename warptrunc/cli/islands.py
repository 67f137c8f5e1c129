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

from .._support.outputs import staged_output, strict_json
from .._support.provenance import provenance
from ..islands.settings import ISLANDS_TRUNCATION, IndicatorSettings, IslandSettings
from ..params import add_options, from_args
from ..truncation.settings import TruncationSettings
from ._common import (
    add_device,
    add_no_plot,
    add_no_progress,
    add_out,
    add_surface_source,
    add_warnings,
    surface_from_args,
    warnings_of,
)

NAME = "islands"
HELP = "contact islands against depth, slit-island exponent and the applicable depth (Fig. 8)"
DEPTH_FIELDS = ("increments", "max_depth_fraction", "max_depth", "connectivity")
"""The fields of :class:`TruncationSettings` that :func:`~warptrunc.islands.island_curve`
reads (defaults: :data:`~warptrunc.islands.settings.ISLANDS_TRUNCATION`)."""
CONNECTIVITY = "4: pixels sharing an edge form one island; 8: also pixels sharing a corner"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc islands``."""
    add_surface_source(p)
    g = p.add_argument_group("depths and islands")
    add_options(
        g,
        TruncationSettings,
        only=DEPTH_FIELDS,
        defaults=ISLANDS_TRUNCATION.to_dict(),
        docs={"connectivity": CONNECTIVITY},
    )
    add_options(g, IslandSettings)
    add_options(p.add_argument_group("applicable-depth indicators"), IndicatorSettings)
    add_device(p)
    add_out(p)
    add_no_plot(p, "the PNGs")
    add_no_progress(p)


def run(args: argparse.Namespace) -> int:
    """Analyse the islands and write the outputs."""
    from ..islands import applicable_depth, island_curve
    from ..plausibility import check_dimensions

    truncation = from_args(TruncationSettings, args, defaults=ISLANDS_TRUNCATION.to_dict())
    settings = from_args(IslandSettings, args)
    indicators = from_args(IndicatorSettings, args)
    s = surface_from_args(args)
    curve = island_curve(
        s,
        truncation=truncation,
        settings=settings,
        progress=not args.no_progress,
        device=args.device,
    )
    ind = applicable_depth(curve, indicators)
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
        f"{100 * indicators.exponent_tolerance:g} % of {_num(ind.plateau_exponent)} down to "
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


def _write(args: argparse.Namespace, s, curve, ind, out: Path) -> None:
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
