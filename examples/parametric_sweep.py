# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Parametric study, group 2 of the paper (§4.4, Fig. 9b, Table 3): α against D_in at δ = 0.01
===========================================================================================

What it shows
    For D_in ∈ {2.1, 2.3, 2.5, 2.7, 2.9} and several seeds, WM surfaces with δ = R_t/W_r
    (W_r = 100 µm, L = 1 mm) are truncated to ω_max = 0.1·R_t in 200 increments; the power law
    E_c/E = β[F/(E·A)]^α is fitted for several fit ranges (minimum contact pixels), and the
    linear fit α(D_in) is printed next to the paper's α = 0.209·D_in + 0.090.
    The cases go to a result store (OUT/sweep.json, OUT/cases.parquet, and OUT/curves/, a
    partitioned Parquet dataset of one part per shard of cases): running the script again
    resumes an interrupted run instead of starting over, and ``--refit`` fits other ranges
    from the stored curves (``pandas.read_parquet(OUT / "curves")``) without generating
    anything. The summary goes
    to OUT/summary.json and a Fig. 9b-style plot to OUT/alpha_vs_D.png.

Resolution
    Below about 8192² pixels α(D_in) has not converged (§ 3.3 of the paper asks ≥ 8192² for
    resolution-independent results): at the ``--quick`` size of 128², α even *falls* with
    D_in beside the paper's rising line. The figure says so in its title. The resolution
    trend (1024², 2048², 10240²) and the 10240² figure (``docs/alpha_vs_D_10240.png``, 5 seeds,
    four fit ranges) are in :ref:`the method guide <alpha-vs-d-10240>`.

Key steps
    ``SweepGrid`` (D_in × δ × seeds) and ``SweepOptions`` (size, fit ranges) → ``run_sweep``
    into a result store (resumable; in-process, or on Dask workers with ``SweepExecution``) →
    ``alpha_summary`` (α per case and fit range, linear fit α(D_in)) → ``plot.alpha_vs_D``.

Run::

    python examples/parametric_sweep.py --quick --out results/group2   # 128², seconds
    python examples/parametric_sweep.py --n 1024 --seeds 5 --out results/group2
    python examples/parametric_sweep.py --n 10240 --seeds 5 --workers 2   # one worker per GPU
    python examples/parametric_sweep.py --out results/group2 --refit 30 300
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

PAPER = {"slope": 0.209, "intercept": 0.090, "r": 0.940}


def resolution_caveat(n: int) -> str:
    """Title lines that warn about an α-vs-D figure below 8192² (empty from 8192² up)."""
    if n >= 8192:
        return ""
    return (
        f"\n{n}² — below the resolution where α(D) converges\n"
        "(§ 3.3 asks ≥ 8192²); see the 10240² figure in the docs"
    )


def refit(out: Path, min_pixels: list[int]):
    """Fit other ranges from the stored curves (no surface is generated again)."""
    import numpy as np
    import pandas as pd

    from warptrunc.sweep import load

    cases = load(out).drop_duplicates("case_id").set_index("case_id")
    rows = []
    # the store's curves/ folder is a Parquet dataset: pandas reads every part at once
    for cid, c in pd.read_parquet(Path(out) / "curves").groupby("case_id"):
        for mp in min_pixels:
            sel = (c["load_N"] > 0) & (c["n_contact_pixels"] >= mp)
            alpha = np.nan
            if sel.sum() >= 3:
                alpha = np.polyfit(np.log(c["F_over_EA"][sel]), np.log(c["Ec_over_E"][sel]), 1)[0]
            rows.append(
                {"case_id": cid, "D_in": cases.at[cid, "D_in"], "min_pixels": mp, "alpha": alpha}
            )
    return pd.DataFrame(rows)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ...")
    ap.add_argument("--n", type=int, default=1024, help="pixels per side")
    ap.add_argument("--seeds", type=int, default=5, help="surfaces per D_in")
    ap.add_argument("--delta", type=float, default=0.01, help="relative roughness δ = R_t/W_r")
    ap.add_argument(
        "--D", type=float, nargs="+", default=[2.1, 2.3, 2.5, 2.7, 2.9], help="D_in values"
    )
    ap.add_argument(
        "--min-pixels", type=int, nargs="+", default=[1, 10, 100, 1000], help="fit ranges"
    )
    ap.add_argument("--workers", type=int, default=None, help="Dask workers (one per GPU)")
    ap.add_argument("--out", type=Path, default=Path("results/group2"), help="result store")
    ap.add_argument("--overwrite", action="store_true", help="replace a store of another run")
    ap.add_argument(
        "--refit",
        type=int,
        nargs="+",
        default=None,
        metavar="MIN_PIXELS",
        help="only re-fit the stored curves with these fit ranges",
    )
    ap.add_argument("--quick", action="store_true", help="128², 2 seeds, 3 values of D")
    ap.add_argument(
        "--no-show", action="store_true", help="do not open a window (figures are saved)"
    )
    args = ap.parse_args(argv)
    if args.quick:
        args.n, args.seeds, args.D = 128, 2, [2.2, 2.5, 2.8]

    from warptrunc.sweep import SweepExecution, SweepGrid, SweepOptions, alpha_summary, run_sweep

    if args.refit:
        df = refit(args.out, args.refit)
        spec = json.loads((args.out / "sweep.json").read_text())
        args.n, args.seeds = spec["options"]["n"], len(spec["grid"]["seeds"])
        args.delta = spec["grid"]["delta"][0] if len(spec["grid"]["delta"]) == 1 else None
    else:
        grid = SweepGrid(args.D, [args.delta], range(args.seeds))
        options = SweepOptions(n=args.n, min_pixels=tuple(args.min_pixels))
        df = run_sweep(
            grid,
            args.out,
            options=options,
            execution=SweepExecution(workers=args.workers),
            overwrite=args.overwrite,
            device=args.device,
        )
        df = df[df["error"].isna()]
    summary = {
        "n": args.n,
        "seeds": args.seeds,
        "delta": args.delta,
        "paper": PAPER,
        **alpha_summary(df),
    }
    for mp, v in summary["fit_ranges"].items():
        print(f"\nmin_pixels = {mp}:")
        for r in v["per_D"]:
            print(
                f"  D_in = {r['D_in']:.1f}: α = {r['alpha_mean']:.3f} ± {r['alpha_sd']:.3f} "
                f"({r['n']} seeds; {r['n_flagged']} fits not worth reading left out)"
            )
        for line in v["alpha_vs_D"]:
            print(
                f"  α = {line['slope']:.3f}·D_in + {line['intercept']:.3f} (r = {line['r']:.3f});"
                f" paper: α = 0.209·D_in + 0.090 (r = 0.940)"
            )
    name = "summary_refit.json" if args.refit else "summary.json"
    (args.out / name).write_text(json.dumps(summary, indent=2, default=float) + "\n")
    from warptrunc import plot

    png = "alpha_vs_D_refit.png" if args.refit else "alpha_vs_D.png"
    fig = plot.alpha_vs_D(
        summary,
        title=f"δ = {args.delta}, {args.n}², {args.seeds} seeds" + resolution_caveat(args.n),
    )
    fig.axes[0].title.set_fontsize(8)
    fig.savefig(args.out / png)
    print(
        f"\nstore {args.out} (sweep.json, cases.parquet, curves/part-*.parquet); wrote {name}, {png}"
    )
    return 0


if __name__ == "__main__":
    if (status := main()) != 0:
        raise SystemExit(status)
