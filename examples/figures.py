# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The matplotlib figure set of warptrunc on a small case, in one style
====================================================================

What it shows
    WM surfaces with δ = R_t/W_r = 0.01 (W_r = 100 µm, L = 1 mm, as the paper's group 2) for a
    few D_in and seeds, and the figures of ``warptrunc.plot``:

    - ``height_map.png``: one surface in µm with its contact set at 30 % R_t in red;
    - ``area_fraction.png``: A_c/A against ω/R_t, mean ± sd over seeds for each D_in;
    - ``stiffness_load.png``: E_c/E against F/(E·A) (Fig. 9 style): geometric mean and
      shaded ±1 sd over seeds, with the fitted power laws (mean α ± sd);
    - ``alpha_vs_D.png``: α against D_in with the fitted line and the paper's
      α = 0.209·D_in + 0.090;
    - ``psd.png``: profile power spectra of one surface per D_in, with W_r;
    - ``islands.png`` and ``slit_islands.png`` (Fig. 8) when ``warptrunc.islands`` is
      installed.

    Every figure is a pyplot-free ``Figure`` saved as PNG; ``--no-show`` only skips opening
    them in a window.

Resolution
    Below about 8192² pixels α(D_in) has not converged (§ 3.3 of the paper asks ≥ 8192² for
    resolution-independent results): at the ``--quick`` size of 128², α even *falls* with
    D_in beside the paper's rising line. The figure says so in its title. The resolution
    trend (1024², 2048², 10240²) and the 10240² figure (``docs/alpha_vs_D_10240.png``, 5 seeds,
    four fit ranges) are in :ref:`the method guide <alpha-vs-d-10240>`.

Key steps
    ``wm_surface`` per (D_in, seed) → ``truncate`` → ``stiffness_curve`` → ``fit_power_law``,
    then one ``warptrunc.plot`` function per figure, each given ``path=`` to save it.

Run::

    python examples/figures.py --n 512 --seeds 5 --out results/figures
    python examples/figures.py --quick --out results/figures   # 128², seconds
"""

from __future__ import annotations

import argparse
import importlib.util
from pathlib import Path

import numpy as np

from warptrunc import plot, truncate
from warptrunc.stiffness import fit_power_law, stiffness_curve
from warptrunc.sweep import linear_fit
from warptrunc.wm import wm_surface


def resolution_caveat(n: int) -> str:
    """Title lines that warn about an α-vs-D figure below 8192² (empty from 8192² up)."""
    if n >= 8192:
        return ""
    return (
        f"\n{n}² — below the resolution where α(D) converges\n"
        "(§ 3.3 asks ≥ 8192²); see the 10240² figure in the docs"
    )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ...")
    ap.add_argument("--n", type=int, default=512, help="pixels per side")
    ap.add_argument("--seeds", type=int, default=5, help="surfaces per D_in")
    ap.add_argument("--seed", type=int, default=0, help="first seed")
    ap.add_argument("--D", type=float, nargs="+", default=[2.2, 2.5, 2.8], help="D_in values")
    ap.add_argument("--delta", type=float, default=0.01, help="relative roughness δ = R_t/W_r")
    ap.add_argument("--out", type=Path, default=Path("results/figures"), help="output folder")
    ap.add_argument("--quick", action="store_true", help="128², 3 seeds")
    ap.add_argument("--no-show", action="store_true", help="do not open the figures")
    args = ap.parse_args(argv)
    if args.quick:
        args.n, args.seeds = 128, 3
    args.out.mkdir(parents=True, exist_ok=True)
    Wr = 100e-6
    seeds = range(args.seed, args.seed + args.seeds)
    written = []

    surfaces = {
        D: [
            wm_surface(D, Wr, n=args.n, Rt=args.delta * Wr, seed=s, device=args.device)
            for s in seeds
        ]
        for D in args.D
    }
    first = surfaces[args.D[len(args.D) // 2]][0]

    p = args.out / "height_map.png"
    plot.height_map(
        first, depth_fraction=0.3, title=f"WM surface, D$_{{in}}$ = {first.params['D']}", path=p
    )
    written.append(p)

    deep = {
        D: [truncate(s, 100, max_depth_fraction=0.5, device=args.device) for s in ss]
        for D, ss in surfaces.items()
    }
    p = args.out / "area_fraction.png"
    plot.area_fraction(list(deep.values()), labels=[f"D$_{{in}}$ = {D}" for D in deep], path=p)
    written.append(p)

    # Fig. 9: 200 increments to 0.1 R_t, fits from 10 contact pixels on (the package default)
    curves = {
        D: [
            stiffness_curve(truncate(s, 200, max_depth_fraction=0.1, device=args.device))
            for s in ss
        ]
        for D, ss in surfaces.items()
    }
    fits = {D: [_fit(c) for c in cs] for D, cs in curves.items()}
    p = args.out / "stiffness_load.png"
    plot.stiffness_load(
        list(curves.values()),
        list(fits.values()),
        labels=[f"D$_{{in}}$ = {D}" for D in curves],
        title=f"δ = {args.delta}, {args.n}², {args.seeds} seeds",
        path=p,
    )
    written.append(p)

    per_D = []
    for D, fs in fits.items():
        a = np.array([f.alpha for f in fs if f is not None])
        per_D.append(
            {
                "D_in": D,
                "delta": args.delta,
                "alpha_mean": float(a.mean()) if a.size else float("nan"),
                "alpha_sd": float(a.std(ddof=1)) if a.size > 1 else float("nan"),
                "n": int(a.size),
            }
        )
    ok = [r for r in per_D if r["n"] > 0]
    line = (
        linear_fit([r["D_in"] for r in ok], [r["alpha_mean"] for r in ok]) if len(ok) > 1 else None
    )
    lines = [{"delta": args.delta, **line}] if line else []
    summary = {"fit_ranges": {"10": {"per_D": per_D, "alpha_vs_D": lines}}}
    p = args.out / "alpha_vs_D.png"
    fig = plot.alpha_vs_D(
        summary,
        title=f"δ = {args.delta}, {args.n}², {args.seeds} seeds" + resolution_caveat(args.n),
    )
    fig.axes[0].title.set_fontsize(8)
    fig.savefig(p)
    written.append(p)

    if importlib.util.find_spec("warptrunc.descriptors") and hasattr(plot, "psd"):
        from warptrunc.descriptors import profile_psd

        p = args.out / "psd.png"
        plot.psd(
            [profile_psd(ss[0]) for ss in surfaces.values()],
            labels=[f"D$_{{in}}$ = {D}" for D in surfaces],
            Wr=Wr,
            path=p,
        )
        written.append(p)

    if importlib.util.find_spec("warptrunc.islands") and hasattr(plot, "island_number"):
        from warptrunc import islands

        depths = islands.ISLANDS_TRUNCATION.replace(increments=100)
        snapshots = islands.IslandSettings(snapshots=(0.1, 0.2, 0.3))
        ic = [
            islands.island_curve(ss[0], truncation=depths, settings=snapshots, device=args.device)
            for ss in surfaces.values()
        ]
        p = args.out / "islands.png"
        plot.island_number(ic, labels=[f"D$_{{in}}$ = {D}" for D in surfaces], path=p)
        written.append(p)
        if hasattr(plot, "slit_islands"):
            p = args.out / "slit_islands.png"
            plot.slit_islands(ic[len(ic) // 2], path=p)
            written.append(p)

    print("wrote " + ", ".join(str(w) for w in written))
    if not args.no_show:
        plot.show_pngs(written, figsize=(7, 5.5), titles=True)
    return 0


def _fit(curve):
    try:
        return fit_power_law(curve)
    except ValueError:  # too few increments with ≥ 10 contact pixels: left out, not hidden
        return None


if __name__ == "__main__":
    if (status := main()) != 0:
        raise SystemExit(status)
