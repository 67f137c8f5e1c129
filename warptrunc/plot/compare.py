# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation against elastic contact (:mod:`warptrunc.compare`): ratio to BEM against the map
size L/W_r, and α(D) by Eq. 2, island-resolved truncation and BEM."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ._style import PAPER_ALPHA_D, finish_figure, new_figure

POHRT_POPOV = ((2.0, 0.51), (3.0, 0.77))
"""(D, α) ends of Pohrt & Popov's BEM range (PRL 108, 104301, 2012); drawn as the straight
line between them (a linear interpolation, not their fit)."""

_MODEL_STYLE = {
    "eq2": {"label": "Eq. 2 (one punch)", "marker": "o", "ls": "-", "color": "tab:blue"},
    "islands": {"label": "island-resolved", "marker": "s", "ls": "--", "color": "tab:green"},
    "bem": {"label": "elastic BEM", "marker": "^", "ls": ":", "color": "tab:red"},
}


def ratio_vs_size(
    ratios: Any,
    *,
    fractions: Any = None,
    quantity: str = "k",
    band: float = 0.2,
    path: str | Path | None = None,
):
    """Model/BEM ratio against L/W_r at a fixed pixel size, both truncation models, per D.

    Parameters
    ----------
    ratios : pandas.DataFrame
        ``summarize(rows)["ratios"]`` of :mod:`warptrunc.compare`.
    fractions : sequence of float, optional
        Approaches δ/R_t to draw, one panel each; default up to three spread over the stored ones.
    quantity : {"k", "F"}
        Stiffness or load ratio.
    band : float
        Shade 1 ± band (dimensionless).
    path : str or Path, optional
        Save a PNG here.

    Returns
    -------
    matplotlib.figure.Figure
        Log–log axes, ticks at the sizes of the study and at readable ratios; the mean over
        the seeds with min–max bars (the title says how many seeds); the finest grid of each
        size is left out (the base pixel size only). The legend is under the panels.
    """
    from ._style import readable_log_ticks

    df = _base_grid(ratios)
    fr = sorted(df["depth_fraction_of_Rt"].unique())
    if fractions is None:
        fractions = [fr[i] for i in sorted({0, len(fr) // 2, len(fr) - 1})] if fr else []
    fig, axes = new_figure(ncols=max(1, len(fractions)))
    import matplotlib as mpl
    from matplotlib.ticker import FixedLocator, NullFormatter, NullLocator

    cmap = mpl.colormaps["viridis"]
    Ds = sorted(df["D_in"].unique())
    sizes = sorted(df["size_ratio"].unique())
    seeds = sorted({int(v) for v in df["seeds"]}) if "seeds" in df else []
    what = {"k": "stiffness k", "F": "load F"}[quantity]
    for ax, f in zip(axes[0], fractions, strict=False):
        sub = df[np.isclose(df["depth_fraction_of_Rt"], f)]
        ax.axhspan(1 - band, 1 + band, color="0.9", zorder=0, label=f"BEM ±{100 * band:.0f} %")
        ax.axhline(1.0, color="0.5", lw=0.8)
        for i, Dv in enumerate(Ds):
            g = sub[sub["D_in"] == Dv].sort_values("size_ratio")
            c = cmap(i / max(1, len(Ds) - 1) * 0.85)
            for m in ("eq2", "islands"):
                col = f"{m}_{quantity}_ratio"
                y = g[f"{col}_mean"].to_numpy()
                err = [y - g[f"{col}_min"].to_numpy(), g[f"{col}_max"].to_numpy() - y]
                st = _MODEL_STYLE[m]
                ax.errorbar(
                    g["size_ratio"],
                    y,
                    yerr=err,
                    color=c,
                    marker=st["marker"],
                    ls=st["ls"],
                    capsize=2,
                    ms=4,
                    label=f"{st['label']}, D = {Dv:g}",
                )
        ax.set_xscale("log")
        ax.set_yscale("log")
        lo, hi = ax.get_xlim()
        ax.set_xlim(min(lo, sizes[0] / 1.3), max(hi, sizes[-1] * 1.3))
        ax.xaxis.set_major_locator(FixedLocator(sizes))
        ax.xaxis.set_major_formatter(mpl.ticker.FuncFormatter(lambda v, _p: f"{v:g}"))
        ax.xaxis.set_minor_locator(NullLocator())
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.get_ylim()  # autoscaled: the ticks read the data's range
        readable_log_ticks(ax.yaxis, max_ticks=7, min_ticks=4)
        ax.grid(True, which="major", alpha=0.3)
        ax.set_xlabel("map size L/W$_r$ (fixed pixel size)")
        ax.set_ylabel(f"{quantity}$_{{model}}$/{quantity}$_{{BEM}}$")
        ax.set_title(f"approach δ/R$_t$ = {f:g}", fontsize=9)
    if len(fractions):
        n_seeds = (
            f"{seeds[0]}" if len(seeds) == 1 else f"{seeds[0]}–{seeds[-1]}" if seeds else "the"
        )
        fig.suptitle(
            f"Truncation's {what} over the elastic (BEM) solution against the map size: "
            f"mean of {n_seeds} seeds, bars min–max",
            fontsize=9,
        )
        fig.legend(
            *axes[0][0].get_legend_handles_labels(),
            loc="outside lower center",
            fontsize=7,
            ncols=min(4, 1 + 2 * len(Ds)),
            frameon=False,
        )
    return finish_figure(fig, path)


def _base_grid(ratios: Any):
    """Rows at the coarsest pixel size of each map size (the size-effect series)."""
    df = ratios.copy()
    df["_dx"] = df["size_ratio"] / df["n"]
    base = df["_dx"].max()
    return df[np.isclose(df["_dx"], base, rtol=1e-9)]


def alpha_vs_D_routes(
    alpha: Any,
    *,
    size_ratio: float | None = None,
    fit_range: str = "all",
    path: str | Path | None = None,
):
    """α of k ∝ F^α against D by Eq. 2, island-resolved truncation and BEM, with Pohrt &
    Popov's BEM range and the paper's Table 3 line.

    Parameters
    ----------
    alpha : pandas.DataFrame
        ``summarize(rows)["alpha"]`` of :mod:`warptrunc.compare`.
    size_ratio : float, optional
        Map size L/W_r to draw (base pixel size); default the largest stored.
    fit_range : {"all", "low"}
        α over every approach, or over δ/R_t ≤ 0.1 only.
    path : str or Path, optional
        Save a PNG here.

    Returns
    -------
    matplotlib.figure.Figure
        Mean over seeds with min–max error bars per route.
    """
    df = _base_grid(alpha)
    df = df[df["range"] == fit_range]
    if size_ratio is None and len(df):
        size_ratio = float(df["size_ratio"].max())
    df = df[np.isclose(df["size_ratio"], size_ratio)].sort_values("D_in")
    fig, axes = new_figure((5.0, 5.2))
    ax = axes[0][0]
    d = np.linspace(2.0, 3.0, 11)
    (d0, a0), (d1, a1) = POHRT_POPOV
    pp = a0 + (a1 - a0) * (d - d0) / (d1 - d0)
    ax.plot(
        d,
        pp,
        color="goldenrod",
        lw=4,
        alpha=0.5,
        label="Pohrt & Popov 2012, BEM: 0.51 → 0.77 (linear interpolation)",
    )
    ax.plot(
        d,
        PAPER_ALPHA_D[0] * d + PAPER_ALPHA_D[1],
        color="k",
        lw=1.0,
        ls="-.",
        label=f"paper, Table 3: α = {PAPER_ALPHA_D[0]}·D + {PAPER_ALPHA_D[1]:.3f}",
    )
    off = {"eq2": -0.01, "islands": 0.0, "bem": 0.01}
    for m, st in _MODEL_STYLE.items():
        y = df[f"alpha_{m}_mean"].to_numpy()
        err = [y - df[f"alpha_{m}_min"].to_numpy(), df[f"alpha_{m}_max"].to_numpy() - y]
        ax.errorbar(
            df["D_in"] + off[m],
            y,
            yerr=err,
            marker=st["marker"],
            ls=st["ls"],
            color=st["color"],
            capsize=2,
            label=st["label"],
        )
    ax.set_xlabel("D")
    ax.set_ylabel("α  (k ∝ F$^α$)")
    rng = "all approaches" if fit_range == "all" else "δ/R$_t$ ≤ 0.1"
    n = int(df["n"].max()) if len(df) else 0
    ax.set_title(f"L/W$_r$ = {size_ratio:g}, {n}², fit over {rng}", fontsize=9)
    ax.set_xlim(2.0, 3.0)
    ax.grid(True, alpha=0.3)
    # below the axes: inside, five entries cover points wherever they sit (α spans 0.3–1)
    fig.legend(
        *ax.get_legend_handles_labels(),
        loc="outside lower center",
        fontsize=7,
        ncols=1,
        frameon=False,
    )
    return finish_figure(fig, path)
