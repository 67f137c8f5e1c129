# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Quickstart: a WM surface, its truncation analysis, and the stiffness–load power law
===================================================================================

What it shows
    The same job as ``warptrunc analyze`` on its defaults, from Python: generate a
    Weierstrass–Mandelbrot surface (D = 2.5, W_r = 100 µm, L = 1 mm, R_t = 10 µm), truncate it
    to 0.1·R_t in 200 increments, turn areas into stiffness and load (Eqs. 2–3), fit
    E_c/E = β[F/(E·A)]^α, and write curve.csv, fit.json and a Fig. 9-style PNG.

Key steps
    ``wm_surface`` → ``truncate`` (areas A_c(ω) from an atomic histogram) →
    ``stiffness_curve`` (k and F from A_c, with a ``Material``) → ``fit_power_law`` (over a
    stated fit range) → ``plot.stiffness_load``.

Run::

    python examples/quickstart.py --out results/quickstart
    python examples/quickstart.py --n 256 --device cpu --out results/quickstart   # seconds
"""

from __future__ import annotations

import argparse
from pathlib import Path

import warptrunc as wt
from warptrunc.stiffness import Material, fit_power_law, stiffness_curve
from warptrunc.wm import wm_surface


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ... (default: CUDA if present)")
    ap.add_argument("--n", type=int, default=1024, help="pixels per side")
    ap.add_argument("--seed", type=int, default=0, help="phase seed")
    ap.add_argument("--out", type=Path, default=Path("results/quickstart"), help="output folder")
    ap.add_argument("--quick", action="store_true", help="a 256² surface")
    ap.add_argument(
        "--no-show", action="store_true", help="do not open a window (figures are saved)"
    )
    args = ap.parse_args(argv)
    n = 256 if args.quick else args.n

    surface = wm_surface(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6, seed=args.seed, device=args.device)
    curve = wt.truncate(surface, 200, max_depth_fraction=0.1, device=args.device)
    sc = stiffness_curve(curve, Material(E=70e9, nu=0.33))  # aluminium on a rigid flat
    fit = fit_power_law(sc, min_pixels=3 if args.quick else 10)

    args.out.mkdir(parents=True, exist_ok=True)
    sc.to_csv(args.out / "curve.csv")
    fit.to_json(args.out / "fit.json")
    from warptrunc import plot

    plot.stiffness_load(
        sc, fit, labels=[f"D = 2.5, seed {args.seed}"], path=args.out / "stiffness.png"
    )
    print(
        f"α = {fit.alpha:.4f}, β = {fit.beta:.4g}, r² = {fit.r2:.4f} over {fit.n_points} increments"
    )
    print(f"wrote {args.out}/curve.csv, fit.json, stiffness.png")
    if not args.no_show:  # pragma: no cover - interactive use only
        plot.show_pngs([args.out / "stiffness.png"])
    return 0


if __name__ == "__main__":
    if (status := main()) != 0:
        raise SystemExit(status)
