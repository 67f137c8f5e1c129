# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Height maps with the contact overlay, and the truncated-area fraction."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from .._support.docs import SHARED_DOCS, fill_doc
from ._style import (
    CONTACT_RGB,
    HEIGHT_CMAP,
    SPREAD_ALPHA,
    UM,
    as_list,
    figure_doc,
    finish_axes,
    finish_figure,
    is_group,
    length_axes,
    new_figure,
    shade_band,
)


@figure_doc
@fill_doc(SHARED_DOCS)
def height_map(
    surface: Any,
    *,
    depth: float | None = None,
    depth_fraction: float | None = None,
    max_pixels: int = 1024,
    pooling: str = "area",
    cmap: str | None = None,
    title: str | None = None,
    path: str | Path | None = None,
):
    """Height map z(x, y) in µm with a colour bar, optionally with the contact set in red.

    Parameters
    ----------
    {surface}
    depth : float, optional
        Overlay the contact set z ≥ float32(z_top − ω) at this depth ω (m) in red.
    depth_fraction : float, optional
        The same, with ω given as a fraction of R_t (dimensionless).
    max_pixels : int
        Larger maps are shown in blocks of mean height, and the title says so.
    pooling : {"area", "any"}
        Contact overlay of a block: ``"area"`` (default) red with an opacity equal to the
        fraction of its pixels in contact, so the red measures A_c/A; ``"any"`` (max-pooling)
        opaque red when any pixel touches, which shows every spot but overstates the area.
    cmap : str, optional
        Colour map of the heights (default viridis, grey under a contact overlay).
    {title}
    {path}

    {returns}

    Notes
    -----
    ``imshow(z, origin="lower", extent=(0, Lx, 0, Ly))``: row iy of ``z`` is drawn at
    y = iy·dy, so x runs to the right and y up, as in the 3-D pictures.
    """
    from .pooling import check_pooling, pool_blocks  # Warp's import, for height maps only

    check_pooling(pooling)

    if depth is not None and depth_fraction is not None:
        raise ValueError("give depth or depth_fraction, not both")
    if depth_fraction is not None:
        depth = float(depth_fraction) * surface.Rt
    z = surface.heights
    f = max(1, math.ceil(max(z.shape) / int(max_pixels)))
    shown = pool_blocks(z, f, "mean") if f > 1 else z
    fig, axes = new_figure(figsize=(5.4, 4.4))
    ax = axes[0, 0]
    ext = (0.0, surface.lx * UM, 0.0, surface.ly * UM)
    im = ax.imshow(
        shown * UM,
        origin="lower",
        extent=ext,
        interpolation="nearest",
        cmap=cmap or (HEIGHT_CMAP if depth is None else "gray"),
    )
    fig.colorbar(im, ax=ax, label="height z (µm)", shrink=0.9)
    label = ""
    if depth is not None:
        thr = np.float32(np.float64(z.max()) - float(depth))
        mask = z >= thr  # as truncation.truncate compares
        frac = float(np.count_nonzero(mask)) / mask.size
        if f > 1:
            mask = pool_blocks(mask, f, "max" if pooling == "any" else "mean")
        rgba = np.zeros((*mask.shape, 4))
        rgba[..., :3] = [c / 255 for c in CONTACT_RGB]
        rgba[..., 3] = mask
        ax.imshow(rgba, origin="lower", extent=ext, interpolation="nearest")
        label = f"contact at ω = {depth * UM:.3g} µm ({100 * depth / surface.Rt:.3g} % R$_t$): A$_c$/A = {100 * frac:.3g} %"
    length_axes(ax)
    note = f"{surface.nx}×{surface.ny} px" + (f", shown in {f}×{f} blocks" if f > 1 else "")
    if f > 1 and depth is not None:
        note += (
            " (max-pooling: red where any pixel touches)"
            if pooling == "any"
            else " (red opacity = contact fraction)"
        )
    ax.set_title("\n".join(t for t in (title, label, note) if t), fontsize=8)
    return finish_figure(fig, path)


@figure_doc
def area_fraction(
    curves: Any,
    *,
    labels: Any = None,
    relative: bool = True,
    log: bool = False,
    spread: str = "sd",
    title: str | None = None,
    path: str | Path | None = None,
):
    """Truncated-area fraction A_c/A (%) against truncation depth ω.

    Parameters
    ----------
    curves : TruncationCurve, or sequence of TruncationCurve or of groups
        Curves to draw; a list of curves (the seeds of one case) is drawn as the mean with a
        shaded spread.
    labels : sequence of str, optional
        Legend labels, one per curve or group.
    relative : bool
        Depth as a percentage of R_t; otherwise in µm.
    log : bool
        Logarithmic A_c/A axis (the first, small contacts).
    spread : {"sd", "range"}
        Shaded band of a group: ±1 standard deviation, or min–max.
    {title}
    {path}

    {returns}
    """
    curves = as_list(curves)

    def xy(c):
        x = 100 * c.depth / c.Rt if relative else c.depth * UM
        return x, 100 * c.area_fraction

    fig, axes = new_figure()
    ax = axes[0, 0]
    for i, c in enumerate(curves):
        lab = labels[i] if labels is not None else None
        if is_group(c):
            pts = [xy(g) for g in c]
            x, m, lo, hi = shade_band(
                [p[0] for p in pts], [p[1] for p in pts], log=False, spread=spread
            )
            what = "±1 sd" if spread == "sd" else "min–max"
            (line,) = ax.plot(
                x, m, "-", lw=1.4, label=f"{lab} ({len(c)} seeds, {what})" if lab else None
            )
            ax.fill_between(x, lo, hi, color=line.get_color(), alpha=SPREAD_ALPHA, lw=0)
        else:
            ax.plot(*xy(c), "-", lw=1.2, label=lab)
    ax.set_xlabel("truncation depth ω (% R$_t$)" if relative else "truncation depth ω (µm)")
    ax.set_ylabel("truncated area A$_c$/A (%)")
    if log:
        ax.set_yscale("log")
    return finish_axes(fig, ax, path, title=title, which="both", legend=labels is not None)
