# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Island number and slit-island fits (Fig. 8)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..islands.fits import slit_island_fit
from ..islands.settings import MIN_PIXELS
from ._style import (
    UM,
    as_list,
    figure_doc,
    finish_axes,
    finish_figure,
    new_figure,
)


@figure_doc
def island_number(
    curves: Any,
    indicators: Any = None,
    *,
    labels: Any = None,
    title: str | None = None,
    path: str | Path | None = None,
):
    """Normalised island number against depth, with the indicator depths (the paper's Fig. 8a).

    Parameters
    ----------
    curves : IslandCurve or sequence of them
        Island counts against depth; each is normalised by its maximum.
    indicators : Indicators or sequence, optional
        One per curve: the depth of the largest growth rate (dashed), the fractality depth
        (dotted) and the island-count peak (dash-dotted) are marked in the curve's colour. A
        fractality depth that is censored (the exponent never left its plateau) is labelled
        as the lower bound it is, "≥ x % R_t (never left it)", with an arrow past it.
    labels : sequence of str, optional
        Legend labels.
    {title}
    {path}

    {returns}
    """
    curves = as_list(curves)
    if indicators is not None:
        indicators = as_list(indicators)
    fig, axes = new_figure()
    ax = axes[0, 0]
    marks = (
        ("max_growth_depth", "--", "max. growth rate"),
        ("fractal_depth", ":", "end of constant slit exponent"),
        ("peak_depth", "-.", "island-count peak"),
    )
    for i, c in enumerate(curves):
        lab = labels[i] if labels is not None else None
        (line,) = ax.plot(100 * c.depth_fraction, c.normalised_island_number, lw=1.2, label=lab)
        if indicators is not None and indicators[i] is not None:
            ind = indicators[i]
            for name, style, what in marks:
                d = getattr(ind, name)
                if d != d:  # NaN: not found
                    continue
                x = 100 * d / ind.Rt
                censored = name == "fractal_depth" and getattr(ind, "fractal_depth_censored", False)
                if censored:  # never left the plateau: a lower bound, not an end
                    what = "constant slit exponent to the deepest depth analysed"
                    text = f"{what}: ≥ {x:.1f} % R$_t$ (never left it)"
                else:
                    text = f"{what}: {x:.1f} % R$_t$"
                ax.axvline(
                    x,
                    ls=style,
                    lw=1.0,
                    color=line.get_color(),
                    label=(what if len(curves) > 1 else text) if i == 0 or censored else None,
                )
                if censored:  # an arrow: the plateau goes on past the last depth
                    ax.annotate(
                        "",
                        xy=(x + 0.04 * (ax.get_xlim()[1] - ax.get_xlim()[0]), 0.5),
                        xytext=(x, 0.5),
                        xycoords=("data", "axes fraction"),
                        arrowprops={"arrowstyle": "->", "color": line.get_color(), "lw": 1.0},
                        annotation_clip=False,
                    )
    ax.set_xlabel("truncation depth ω (% R$_t$)")
    ax.set_ylabel("normalised island number n/n$_{max}$")
    ax.set_ylim(bottom=0)
    return finish_axes(fig, ax, path, title=title)


@figure_doc
def slit_islands(
    curve: Any,
    *,
    min_pixels: int | None = None,
    title: str | None = None,
    path: str | Path | None = None,
):
    """Island perimeter against area, log–log, with slit-island fits (the paper's Fig. 8b).

    Parameters
    ----------
    curve : IslandCurve or sequence of IslandSizes
        The islands at a few depths (``IslandCurve.sizes``, from ``IslandSettings.snapshots``).
    min_pixels : int, optional
        Smallest island in the fits (pixels); the curve's own by default, else 10. Smaller
        islands are drawn in grey.
    title : str, optional
        Axes title; default names the smallest fitted island size.
    {path}

    {returns}
    """

    sizes = list(getattr(curve, "sizes", curve))
    if min_pixels is None:
        min_pixels = getattr(curve, "min_pixels", MIN_PIXELS)
    Rt = getattr(curve, "Rt", None)
    fig, axes = new_figure()
    ax = axes[0, 0]
    for sz in sizes:
        if sz.n_islands == 0:
            continue
        big = sz.area_pixels >= min_pixels
        fit = slit_island_fit(sz, min_pixels=min_pixels)
        at = f"ω = {100 * sz.depth / Rt:.1f} % R$_t$" if Rt else f"ω = {sz.depth * UM:.3g} µm"
        (pts,) = ax.loglog(sz.area[big] * UM**2, sz.perimeter[big] * UM, ".", ms=2.5, alpha=0.6)
        ax.loglog(sz.area[~big] * UM**2, sz.perimeter[~big] * UM, ".", ms=2, color="0.75", zorder=0)
        if fit.exponent == fit.exponent:
            a = np.geomspace(sz.area[big].min(), sz.area[big].max(), 20)
            ax.loglog(
                a * UM**2,
                10**fit.intercept * a**fit.exponent * UM,
                "-",
                color=pts.get_color(),
                lw=1.4,
                label=f"{at}: exponent {fit.exponent:.3f} (D = {fit.dimension:.2f}, "
                f"r² = {fit.r2:.3f}, {fit.n_islands} islands)",
            )
        else:
            pts.set_label(f"{at}: too few islands ≥ {min_pixels} px")
    ax.set_xlabel("island area A (µm²)")
    ax.set_ylabel("island perimeter L (µm)")
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title(title or f"slit islands (grey: < {min_pixels} pixels, not fitted)")
    ax.legend(fontsize=6)
    return finish_figure(fig, path)
