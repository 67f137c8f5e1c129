# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation (Eq. 2), island-resolved truncation and elastic BEM on the same maps.

At approaches δ/R_t (--fractions), computes F, k and A by Eq. 2 (one flat punch of the whole
truncated area), by island-resolved truncation (one punch per island, k = (2/√π)E*·Σ√A_i) and by
warptrunc's elastic solver (free half-space, Barber stiffness), with the ratios to the elastic
solution and α of k ∝ F^α by the three routes.

On your own map (--input FILE), or on a study of WM surfaces: D (--D), map size L/W_r at a fixed
pixel size (--size-ratios, --pixels-per-wr: size effect; the sizes listed are the sizes run),
the pixel size halved once more at --refine-ratio, one of the sizes (default 10; none: no
refined grid; grid convergence on the same surface), --seeds (a list: 0-2, 0,3,7); or exactly
the ``elastic`` stage of a reproduce profile (--profile tiny|quick|paper), which also writes
the report section.

Writes into OUT: study.json (the settings, strict JSON) and cases/<case_id>.parquet (one row
per approach, SI units in the column names; a rerun skips the cases already there, so an
interrupted study resumes; beside the three routes, Persson's and Greenwood–Williamson's area,
mean gap and stiffness at the nominal pressure F_BEM/L² of each row, and κ), ratios.parquet and
alpha.parquet (the summary tables, mean/min/max over seeds), summary.json (with the small-load κ
of each case beside Persson's √(8/π) and BGT's √(2π)), elastic_ratio_vs_size.png and
elastic_alpha_vs_D.png (unless --no-plot; not for one map), and with
--profile elastic.md (the report section "How far is truncation from elastic contact?"). Each
file is written whole or not at all. Load the rows with
``warptrunc.compare.load_comparison(OUT)`` or ``pandas.read_parquet(OUT / "cases")``.
"""

from __future__ import annotations

import argparse
import io
import sys
from pathlib import Path

from ..compare.design import MapStudy, StudyDesign
from ..contact.adhesion import Adhesion
from ..contact.settings import ELASTIC_TRUNCATION, SolverSettings
from ..params import add_options, from_args
from ._common import (
    add_device,
    add_devices,
    add_input,
    add_material,
    add_no_plot,
    add_no_progress,
    add_out,
    add_overwrite,
    add_profile,
    add_reader_options,
    add_truncation,
    add_warnings,
    material_from_args,
    prepare_devices,
    read_input,
    truncation_from_args,
    warnings_of,
)

NAME = "compare"
HELP = "Eq. 2, island-resolved truncation and elastic BEM on the same maps (study)"
SOLVER_FIELDS = ("dtype", "pressure_tol", "pentol", "maxiter")
"""The fields of :class:`~warptrunc.contact.SolverSettings` that ``compare`` sets (the
half-space is the free one)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc compare``."""
    s = p.add_argument_group("surfaces: your map, a WM study, or a reproduce profile")
    add_input(s, "your height map (formats as in `analyze`); one case")
    add_reader_options(s, scan_rule="read")
    add_profile(
        s,
        "the `elastic` stage of this reproduce profile (overrides the WM study "
        "options) and its report section elastic.md",
        None,
    )
    add_options(s, StudyDesign, exclude=("fractions", "M", "gamma"))
    m = p.add_argument_group("approaches, material, solver")
    add_options(m, StudyDesign, only=("fractions",))
    add_material(m)
    add_truncation(
        m, only=("increments", "beta_prime", "connectivity"), defaults=ELASTIC_TRUNCATION.to_dict()
    )
    add_options(m, SolverSettings, only=SOLVER_FIELDS)
    add_options(p, Adhesion, title="adhesion (the elastic route; default: none)")
    add_devices(m, "the elastic route")
    add_device(p)
    add_out(p, "compare")
    add_overwrite(p, "a store in OUT made with other settings")
    add_no_plot(p, "the PNGs")
    add_no_progress(p)


def run(args: argparse.Namespace) -> int:
    """Run (or resume) the study and write the summary."""
    design = from_args(StudyDesign, args)
    truncation = truncation_from_args(args, ELASTIC_TRUNCATION.to_dict())
    settings = from_args(SolverSettings, args, adhesion=from_args(Adhesion, args))
    from .._support.outputs import staged_outputs, strict_json
    from .._support.provenance import provenance
    from ..compare.study import compare_study, summarize
    from ..stiffness import Material

    try:
        import pandas  # noqa: F401
        import pyarrow  # noqa: F401
    except ImportError as exc:
        raise ValueError(
            f"compare stores Parquet with pandas and pyarrow, dependencies of "
            f"warptrunc that this environment lacks ({exc.name} is missing): "
            "pip install pandas pyarrow"
        ) from None
    if args.input is not None and args.profile is not None:
        raise ValueError("give either --input or --profile, not both")
    prepare_devices(args.devices)
    material = material_from_args(args)
    study: StudyDesign | MapStudy = design
    prof = None
    if args.profile is not None:
        from ..reproduce.elastic import profile_design
        from ..reproduce.profiles import PROFILES

        prof = PROFILES[args.profile]
        study = profile_design(prof)
        settings = settings.replace(dtype=prof.elastic_dtype)
        material = Material()
    elif args.input is not None:
        study = MapStudy(read_input(args.input, args), fractions=design.fractions)
    if isinstance(study, StudyDesign):
        print(_design_line(study))
    out: Path = args.out
    rows = compare_study(
        out,
        study,
        material=material,
        truncation=truncation,
        settings=settings,
        overwrite=args.overwrite,
        progress=not args.no_progress,
        device=args.device,
        devices=args.devices,
    )
    s = summarize(rows)
    steep = rows.drop_duplicates("case_id")
    steep = steep[steep["slope_rms"] > settings.slope_limit]
    if len(steep):
        from ..plausibility import PlausibilityWarning

        worst = float(steep["slope_rms"].max())
        add_warnings(args, [PlausibilityWarning(
            "slope",
            f"{len(steep)} of {rows['case_id'].nunique()} maps have h′_rms above "
            f"{settings.slope_limit:g} at their pixel (up to {worst:.3g}): outside the small-slope "
            "range of the half-space solution, the BEM columns of those cases are not a physical "
            "model (cases/*.parquet: slope_rms)",
            {"n_cases": len(steep), "max_slope_rms": worst, "limit": settings.slope_limit},
        )])  # fmt: skip
    from ..reproduce.elastic import analyse_elastic, summary_from_rows
    from ..reproduce.elastic_report import elastic_figures, elastic_lines

    wm = isinstance(study, StudyDesign)
    stage = summary_from_rows(rows, store="cases")
    a = analyse_elastic(stage) if wm else None
    files = [
        "study.json",
        f"cases/ ({stage['n_cases']} cases)",
        "ratios.parquet",
        "alpha.parquet",
        "summary.json",
    ]
    names: list[str] = []
    with staged_outputs() as st:  # the summary files, or none of them (cases/ is the store)
        dest = st.folder(out)
        for name in ("ratios", "alpha"):
            buf = io.BytesIO()
            s[name].to_parquet(buf, index=False)
            (dest / f"{name}.parquet").write_bytes(buf.getvalue())
        doc = {
            "stage": stage,
            "analysis": a,
            "kappa": _kappa_by_case(rows),
            "provenance": provenance(args.device),
            "warnings": warnings_of(args),
        }
        (dest / "summary.json").write_text(strict_json(doc))
        if not args.no_plot and wm:
            names = elastic_figures(stage, dest)
            files += names
        if prof is not None:
            lines = elastic_lines(stage, a, None, names)
            cmd = provenance()["command"]
            (dest / "elastic.md").write_text(f"<!-- {cmd} -->\n" + "\n".join(lines) + "\n")
            files.append("elastic.md")
    _print_summary(s, rows, not wm)
    print(f"wrote {out}/: " + ", ".join(files))
    return 0


def _design_line(d: StudyDesign) -> str:
    """The study's grids in one line: the sizes listed, and the one refined grid as its own,
    stated choice."""
    from ..compare.study import study_cases

    sizes = " ".join(f"{r:g}" for r in d.size_ratios)
    refine = (
        "no refined grid (--refine-ratio none)"
        if d.refine_ratio is None
        else f"and L/W_r = {d.refine_ratio:g} once more at dx = W_r/{2 * d.pixels_per_Wr} "
        "(--refine-ratio: grid convergence)"
    )
    return (
        f"study: D {' '.join(f'{x:g}' for x in d.D)} × L/W_r {sizes} at dx = "
        f"W_r/{d.pixels_per_Wr}, {refine}; seeds {' '.join(map(str, d.seeds))}: "
        f"{len(study_cases(d))} maps"
    )


def _kappa_by_case(rows) -> dict:
    """The small-load κ of each case's elastic solves beside Persson's and BGT's
    (:func:`warptrunc.theory.columns.kappa_record`), by case id."""
    from ..theory.columns import kappa_record

    out = {}
    for case, g in rows.groupby("case_id", sort=True):
        if "bem_kappa" not in g or g["bem_kappa"].isna().all():
            continue
        a0 = float(g["L_m"].iloc[0]) ** 2
        px = float(g["dx_m"].iloc[0]) ** 2
        out[str(case)] = kappa_record(g, g["bem_area_m2"], a0, pixel_area=px)
    return out


def _print_summary(s, rows, single: bool) -> None:
    """A short table on stdout: seed-mean k ratios and α by the three routes."""
    r = s["ratios"]
    print("k/k_BEM (seed mean): " + ("" if single else "D, L/W_r, n, δ/R_t: ") + "Eq. 2, islands")
    for _, x in r.iterrows():
        key = "" if single else f"{x['D_in']:g}, {x['size_ratio']:g}, {int(x['n'])}, "
        print(
            f"  {key}{x['depth_fraction_of_Rt']:g}: {x['eq2_k_ratio_mean']:.3f}, "
            f"{x['islands_k_ratio_mean']:.3f}"
        )
    al = s["alpha"][s["alpha"]["range"] == "all"]
    for _, x in al.iterrows():
        key = (
            "" if single else f"D = {x['D_in']:g}, L/W_r = {x['size_ratio']:g}, n = {int(x['n'])}: "
        )
        print(
            f"α {key}Eq. 2 {x['alpha_eq2_mean']:.3f}, islands {x['alpha_islands_mean']:.3f}, "
            f"BEM {x['alpha_bem_mean']:.3f}"
        )
    for case, k in _kappa_by_case(rows).items():
        if k["bem"] is not None:
            print(
                f"κ at small load, {case}: BEM {k['bem']:.3g}, Persson {k['persson']:.3g} "
                f"(√(8/π) = {k['persson_limit']:.3f}; BGT √(2π) = {k['bgt_limit']:.3f})"
            )
    bad = int((~rows["converged"].astype(bool)).sum())
    if bad:
        print(
            f"warning: {bad} elastic solves did not converge (converged = False in cases/)",
            file=sys.stderr,
        )
