# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation (Eq. 2), island-resolved truncation and elastic BEM on the same maps.

At approaches δ/R_t (--fractions), computes F, k and A by Eq. 2 (one flat punch of the whole
truncated area), by island-resolved truncation (one punch per island, k = (2/√π)E*·Σ√A_i) and by
warptrunc's elastic solver (free half-space, Barber stiffness), with the ratios to the elastic
solution and α of k ∝ F^α by the three routes.

On your own map (--input FILE), or on a study of WM surfaces: D (--D), map size L/W_r at a fixed
pixel size (--size-ratios, --pixels-per-wr: size effect), the pixel size halved once at
--refine-ratio (grid convergence on the same surface), --seeds; or exactly the ``elastic`` stage
of a reproduce profile (--profile tiny|quick|paper), which also writes the report section.

Writes into OUT: study.json (the settings, strict JSON) and cases/<case_id>.parquet (one row
per approach, SI units in the column names; a rerun skips the cases already there, so an
interrupted study resumes), ratios.parquet and alpha.parquet (the summary tables, mean/min/max
over seeds), summary.json, elastic_ratio_vs_size.png and elastic_alpha_vs_D.png (unless
--no-plot; not for one map), and with
--profile elastic.md (the report section "How far is truncation from elastic contact?"). Each
file is written whole or not at all. Load the rows with
``warptrunc.compare.load_comparison(OUT)`` or ``pandas.read_parquet(OUT / "cases")``.
"""

from __future__ import annotations

import argparse
import io
import sys
from pathlib import Path

from ..params import add_options
from ..wm_params import WMSpec
from ._common import (
    add_device,
    add_devices,
    add_material,
    add_out,
    add_reader_options,
    check_increments,
    fraction,
    input_file,
    integer,
    material_from_args,
    positive,
    prepare_devices,
    read_input,
    real,
    warnings_of,
)

NAME = "compare"
HELP = "Eq. 2, island-resolved truncation and elastic BEM on the same maps (study)"
STUDY_D = (2.1, 2.5, 2.9)
"""Default fractal dimensions D of the WM study (dimensionless)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc compare``."""
    from ..compare.models import APPROACH_FRACTIONS
    from ..reproduce.profiles import PROFILES

    s = p.add_argument_group("surfaces: your map, a WM study, or a reproduce profile")
    s.add_argument("--input", "-i", type=input_file, default=None,
                   help="your height map (formats as in `analyze`); one case")  # fmt: skip
    add_reader_options(s, scan_rule="read")
    s.add_argument("--profile", choices=sorted(PROFILES), default=None,
                   help="the `elastic` stage of this reproduce profile (overrides the WM study "
                   "options) and its report section elastic.md")  # fmt: skip
    add_options(s, WMSpec, only=("D",), many=("D",), defaults={"D": STUDY_D},
                docs={"D": "fractal dimensions D of the WM study"})  # fmt: skip
    s.add_argument("--size-ratios", type=positive(), nargs="+", default=[1, 3, 10],
                   help="map sizes L/W_r, at a fixed pixel size W_r/(--pixels-per-wr)")  # fmt: skip
    s.add_argument("--pixels-per-wr", type=integer(2), default=32,
                   help="pixels per roll-off wavelength (n = L/W_r × this)")  # fmt: skip
    s.add_argument("--refine-ratio", type=real(0.0, lo_open=False), default=10,
                   help="L/W_r at which the pixel size is halved once (grid convergence); 0: none")  # fmt: skip
    s.add_argument("--seeds", type=integer(1), default=3, help="surfaces per (D, grid)")
    add_options(s, WMSpec, only=("Wr",))
    s.add_argument("--rt-over-wr", type=positive(), default=0.01,
                   help="R_t/W_r (the paper's δ); ratios and α do not depend on it")  # fmt: skip
    m = p.add_argument_group("approaches, material, solver")
    m.add_argument("--fractions", type=fraction(), nargs="+", default=list(APPROACH_FRACTIONS),
                   help="approaches δ/R_t, increasing")  # fmt: skip
    add_material(m)
    m.add_argument("--increments", type=integer(1, 10_000_000), default=400,
                   help="depth increments of the truncation load integrals")  # fmt: skip
    m.add_argument("--connectivity", type=int, choices=(4, 8), default=4,
                   help="island neighbourhood")  # fmt: skip
    m.add_argument("--dtype", choices=("float64", "float32"), default="float64",
                   help="precision of the elastic solver")  # fmt: skip
    m.add_argument("--pressure-tol", type=positive(), default=1e-5,
                   help="elastic solver tolerance on tensile pressure, relative to E*")  # fmt: skip
    m.add_argument("--maxiter", type=integer(1), default=10000, help="CG iterations per solve")
    add_devices(m, "the elastic route")
    add_device(p)
    add_out(p, "compare")
    p.add_argument("--overwrite", action="store_true",
                   help="replace a store in OUT made with other settings")  # fmt: skip
    p.add_argument("--no-plot", action="store_true", help="skip the PNGs")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


def run(args: argparse.Namespace) -> int:
    """Run (or resume) the study and write the summary."""
    check_increments(args.increments, "--increments")
    from .._support.atomic import staged_outputs, strict_json
    from .._support.provenance import provenance
    from ..compare.study import compare_study, study_cases, summarize
    from ..stiffness import Material
    try:
        import pandas  # noqa: F401
        import pyarrow  # noqa: F401
    except ImportError as exc:
        raise ValueError(f"compare stores Parquet with pandas and pyarrow, dependencies of "
                         f"warptrunc that this environment lacks ({exc.name} is missing): "
                         "pip install pandas pyarrow") from None
    if args.input is not None and args.profile is not None:
        raise ValueError("give either --input or --profile, not both")
    prepare_devices(args.devices)
    material = material_from_args(args)
    fractions, dtype, cases, surface = args.fractions, args.dtype, None, None
    prof = None
    if args.profile is not None:
        from ..reproduce.elastic import profile_cases
        from ..reproduce.profiles import PROFILES

        prof = PROFILES[args.profile]
        cases, fractions, dtype = profile_cases(prof), list(prof.elastic_fractions), prof.elastic_dtype
        material = Material()
    elif args.input is not None:
        surface = read_input(args.input, args)
    else:
        cases = study_cases(
            D=list(STUDY_D) if args.D is None else args.D, size_ratios=args.size_ratios,
            pixels_per_Wr=args.pixels_per_wr, refine_ratio=args.refine_ratio or None,
            seeds=args.seeds, Wr=WMSpec().Wr if args.Wr is None else args.Wr,
            Rt_over_Wr=args.rt_over_wr,
        )  # fmt: skip
    out: Path = args.out
    rows = compare_study(
        out, cases, surface=surface, fractions=fractions, material=material,
        increments=args.increments, connectivity=args.connectivity, dtype=dtype,
        pressure_tol=args.pressure_tol, maxiter=args.maxiter, overwrite=args.overwrite,
        progress=not args.no_progress, device=args.device, devices=args.devices,
    )  # fmt: skip
    s = summarize(rows)
    from ..reproduce.elastic import analyse_elastic, summary_from_rows
    from ..reproduce.elastic_report import elastic_figures, elastic_lines

    stage = summary_from_rows(rows, store="cases")
    a = analyse_elastic(stage) if cases is not None else None
    files = ["study.json", f"cases/ ({stage['n_cases']} cases)", "ratios.parquet",
             "alpha.parquet", "summary.json"]  # fmt: skip
    names: list[str] = []
    with staged_outputs() as st:  # the summary files, or none of them (cases/ is the store)
        dest = st.folder(out)
        for name in ("ratios", "alpha"):
            buf = io.BytesIO()
            s[name].to_parquet(buf, index=False)
            (dest / f"{name}.parquet").write_bytes(buf.getvalue())
        doc = {"stage": stage, "analysis": a, "provenance": provenance(args.device),
               "warnings": warnings_of(args)}
        (dest / "summary.json").write_text(strict_json(doc))
        if not args.no_plot and cases is not None:
            names = elastic_figures(stage, dest)
            files += names
        if prof is not None:
            lines = elastic_lines(stage, a, None, names)
            cmd = provenance()["command"]
            (dest / "elastic.md").write_text(f"<!-- {cmd} -->\n" + "\n".join(lines) + "\n")
            files.append("elastic.md")
    _print_summary(s, rows, surface is not None)
    print(f"wrote {out}/: " + ", ".join(files))
    return 0


def _print_summary(s, rows, single: bool) -> None:
    """A short table on stdout: seed-mean k ratios and α by the three routes."""
    r = s["ratios"]
    print("k/k_BEM (seed mean): " + ("" if single else "D, L/W_r, n, δ/R_t: ") + "Eq. 2, islands")
    for _, x in r.iterrows():
        key = "" if single else f"{x['D_in']:g}, {x['size_ratio']:g}, {int(x['n'])}, "
        print(f"  {key}{x['depth_fraction_of_Rt']:g}: {x['eq2_k_ratio_mean']:.3f}, "
              f"{x['islands_k_ratio_mean']:.3f}")  # fmt: skip
    al = s["alpha"][s["alpha"]["range"] == "all"]
    for _, x in al.iterrows():
        key = "" if single else f"D = {x['D_in']:g}, L/W_r = {x['size_ratio']:g}, n = {int(x['n'])}: "
        print(f"α {key}Eq. 2 {x['alpha_eq2_mean']:.3f}, islands {x['alpha_islands_mean']:.3f}, "
              f"BEM {x['alpha_bem_mean']:.3f}")  # fmt: skip
    bad = int((~rows["converged"].astype(bool)).sum())
    if bad:
        print(f"warning: {bad} elastic solves did not converge (converged = False in cases/)",
              file=sys.stderr)  # fmt: skip

