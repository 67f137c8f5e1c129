# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Contact islands: how contact spots grow and merge with truncation depth (paper §4.3, Fig. 8)
============================================================================================

What it shows
    WM surfaces (D = 2.5, W_r = 100 µm, L = 1 mm, R_t = 10 µm by default) are truncated to
    0.5·R_t in 200 increments. At every depth the contact islands are counted (one union-find
    forest carried from depth to depth), their areas and perimeters measured, and the
    slit-island exponent of log L against log A fitted (Eq. 5). From these curves come the
    indicators of Table 2: the depth of the largest growth rate of the island number, the depth
    down to which the slit-island exponent stays on its plateau, and the island-count peak.
    Several seeds give a mean and a spread, as the paper's four simulations per surface.

Key steps
    ``island_curve`` (counts, χ, perimeters, slit fits at every depth) → ``applicable_depth``
    (Table 2 indicators) → ``plot.island_number`` (Fig. 8a) and ``plot.slit_islands`` (Fig. 8b).

Outputs (in ``--out``)
    islands_seed<k>.csv per seed, summary.json (indicators per seed, mean and sd; the exponent
    against depth, mean and sd over seeds), island_number.png, slit_islands.png.

Run::

    python examples/contact_islands.py --n 2048 --seeds 5 --out results/islands
    python examples/contact_islands.py --quick --out results/islands   # 128², seconds
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from warptrunc.islands import IndicatorSettings, IslandSettings, applicable_depth, island_curve
from warptrunc.truncation import TruncationSettings
from warptrunc.wm import wm_surface


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ... (default: CUDA if present)")
    ap.add_argument("--n", type=int, default=1024, help="pixels per side")
    ap.add_argument("--seed", type=int, default=0, help="first phase seed")
    ap.add_argument("--seeds", type=int, default=1, help="number of seeds (seed, seed+1, ...)")
    ap.add_argument("--D", type=float, default=2.5, help="fractal dimension D")
    ap.add_argument("--Wr", type=float, default=100e-6, help="roll-off wavelength W_r (m)")
    ap.add_argument("--L", type=float, default=1e-3, help="side length (m)")
    ap.add_argument("--Rt", type=float, default=10e-6, help="peak-to-valley height R_t (m)")
    ap.add_argument("--increments", type=int, default=200, help="depth increments")
    ap.add_argument("--max-depth-fraction", type=float, default=0.5, help="ω_max / R_t")
    ap.add_argument("--connectivity", type=int, default=4, help="4 or 8")
    ap.add_argument("--min-pixels", type=int, default=10, help="smallest fitted island (px)")
    ap.add_argument("--out", type=Path, default=Path("results/islands"), help="output folder")
    ap.add_argument("--quick", action="store_true", help="a 128² surface, 50 increments")
    ap.add_argument("--progress", action="store_true", help="progress bars")
    ap.add_argument(
        "--no-show", action="store_true", help="do not open a window (figures are saved)"
    )
    args = ap.parse_args(argv)
    n, inc = (128, 50) if args.quick else (args.n, args.increments)
    min_islands = 5 if args.quick else 50

    depths = TruncationSettings(
        increments=inc, max_depth_fraction=args.max_depth_fraction, connectivity=args.connectivity
    )
    args.out.mkdir(parents=True, exist_ok=True)
    curves, inds, rows = [], [], []
    for seed in range(args.seed, args.seed + args.seeds):
        t0 = time.perf_counter()
        s = wm_surface(args.D, args.Wr, L=args.L, n=n, Rt=args.Rt, seed=seed, device=args.device)
        snapshots = (0.1, 0.2, 0.3, 0.4) if seed == args.seed else None
        c = island_curve(
            s,
            truncation=depths,
            settings=IslandSettings(min_pixels=args.min_pixels, snapshots=snapshots),
            progress=args.progress,
            device=args.device,
        )
        ind = applicable_depth(c, IndicatorSettings(min_islands=min_islands))
        c.to_csv(args.out / f"islands_seed{seed}.csv")
        curves.append(c)
        inds.append(ind)
        rows.append({"seed": seed, "seconds": time.perf_counter() - t0, **ind.to_dict()})
        print(
            f"seed {seed}: max growth rate at {100 * ind.max_growth_depth / ind.Rt:.2f} % R_t, "
            f"peak at {100 * ind.peak_depth / ind.Rt:.2f} % R_t, exponent plateau "
            f"{ind.plateau_exponent:.3f} kept to {100 * ind.fractal_depth / ind.Rt:.2f} % R_t"
            f"{' (censored)' if ind.fractal_depth_censored else ''}"
            f"  [{rows[-1]['seconds']:.1f} s]"
        )

    def stats(key: str) -> dict:
        v = np.array([r[key] for r in rows if r[key] is not None], float)
        return {"mean": float(v.mean()), "sd": float(v.std(ddof=1)) if v.size > 1 else 0.0}

    frac = curves[0].depth_fraction
    beta = np.array([c.slit_exponent for c in curves])
    ok = np.array([c.slit_n_islands >= min_islands for c in curves])
    beta_ok = np.where(ok, beta, np.nan)
    with np.errstate(invalid="ignore"):
        counted = ok.sum(axis=0)
        mean = np.where(counted > 0, np.nansum(beta_ok, axis=0) / np.maximum(counted, 1), np.nan)
    summary = {
        "D": args.D,
        "Wr_m": args.Wr,
        "L_m": args.L,
        "Rt_m": args.Rt,
        "n": n,
        "increments": inc,
        "connectivity": args.connectivity,
        "min_pixels": args.min_pixels,
        "min_islands": min_islands,
        "seeds": rows,
        "max_growth_rate_depth_percent_Rt": stats("max_growth_rate_depth_percent_Rt"),
        "island_peak_depth_percent_Rt": stats("island_peak_depth_percent_Rt"),
        "fractality_depth_percent_Rt": stats("fractality_depth_percent_Rt"),
        "plateau_exponent": stats("plateau_exponent"),
        "exponent_against_depth": {
            "depth_percent_Rt": (100 * frac).tolist(),
            "mean": [None if not np.isfinite(v) else float(v) for v in mean],
            "seeds_counted": counted.tolist(),
        },
    }
    (args.out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")

    from warptrunc import plot

    title = f"D = {args.D}, {n}², {len(curves)} seed(s)"
    plot.island_number(
        curves,
        inds,
        labels=[f"seed {r['seed']}" for r in rows],
        title=title,
        path=args.out / "island_number.png",
    )
    plot.slit_islands(
        curves[0], title=f"D = {args.D}, {n}², seed {args.seed}", path=args.out / "slit_islands.png"
    )
    print(f"wrote {args.out}/summary.json, islands_seed*.csv, island_number.png, slit_islands.png")
    if not args.no_show:  # pragma: no cover - interactive use only
        plot.show_pngs([args.out / "island_number.png", args.out / "slit_islands.png"])
    return 0


if __name__ == "__main__":
    if (status := main()) != 0:
        raise SystemExit(status)
