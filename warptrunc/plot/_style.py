# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The shared style (sizes, colours, the contact red) and helpers of every figure."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from .._support.docs import fill_doc

UM = 1e6  # m → µm on axes
FIGSIZE = (5.0, 4.0)
DPI = 150
CONTACT_RGB = (214, 39, 40)  # contact (truncated) areas, as the paper's red; also in render.py
CONTACT_COLOR = "#d62728"  # the same red for matplotlib
SPREAD_ALPHA = 0.25  # shaded spread over seeds
HEIGHT_CMAP = "viridis"  # height maps; "gray" under a red contact overlay
PAPER_ALPHA_D = (0.209, 0.090)  # the paper's α = 0.209·D_in + 0.090 (Table 3, D_in)
FLAGGED_LABEL = "not worth reading (hollow; left out of means and lines)"
"""Legend text of the fits a figure draws hollow: flagged by
:func:`warptrunc.plausibility.check_fit` (``fit_error``), kept in the data, out of every fit."""


FIGURE_DOCS = {
    "{path}": "path : path, optional\n    Save the figure as PNG here.",
    "{title}": "title : str, optional\n    Axes title.",
    "{returns}": (
        "Returns\n-------\nmatplotlib.figure.Figure\n"
        "    The figure, also saved as PNG to ``path`` when given (parent folders created)."
    ),
}
"""Docstring blocks every figure function shares, written once: a line holding only a key is
replaced by its block (at that line's indentation) by :func:`figure_doc`."""


def figure_doc(func: Any) -> Any:
    """Fill the :data:`FIGURE_DOCS` blocks into ``func``'s docstring; returns ``func``."""
    return fill_doc(FIGURE_DOCS)(func)


def new_figure(figsize: tuple[float, float] = FIGSIZE, ncols: int = 1, nrows: int = 1):
    """A pyplot-free Figure (renders with Agg, needs no display) and its axes grid."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(figsize[0] * ncols, figsize[1] * nrows), dpi=DPI, layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False)
    return fig, axes


def _tick_text(v: float) -> str:
    """A log-axis tick label: plain digits from 10⁻³ to 10⁴, else m×10ᵏ in mathtext."""
    if v <= 0 or not np.isfinite(v):
        return ""
    if 1e-3 <= v < 1e4:
        return f"{v:.6g}"
    k = int(np.floor(np.log10(v) + 1e-9))
    m = v / 10.0**k
    return f"$10^{{{k}}}$" if abs(m - 1) < 1e-6 else f"${m:.3g}\\times10^{{{k}}}$"


def readable_log_ticks(axis: Any, max_ticks: int = 6, min_ticks: int = 3) -> None:
    """Give a log-scaled matplotlib axis up to ``max_ticks`` labelled major ticks that do not
    run into each other, at 1–2–5-style values when the range spans less than a few decades and
    at (every n-th) decade otherwise; minor ticks keep their marks but get no labels. The view
    limits are frozen at their current values.

    Parameters
    ----------
    axis : matplotlib.axis.Axis
        A log-scaled axis (``ax.xaxis`` or ``ax.yaxis``) whose view limits are set.
    max_ticks : int
        Most labelled ticks.
    min_ticks : int
        The first of the mantissa sets 1; 1, 3; 1, 2, 5; 1, 2, 3, 5; 1, 1.5, 2, 3, 5, 7; 1, 1.2,
        1.5, 2, 2.5, 3, 4, 5, 6, 7, 8 that gives at least this many ticks inside the view is used
        (the last one otherwise): more labels where a range of under two decades holds the
        data.
    """
    from matplotlib.ticker import (
        FixedLocator,
        FuncFormatter,
        LogLocator,
        NullFormatter,
        NullLocator,
    )

    lo, hi = sorted(axis.get_view_interval())
    if not (lo > 0 and np.isfinite(hi)):
        return
    k0, k1 = int(np.floor(np.log10(lo))), int(np.ceil(np.log10(hi)))
    ticks: list[float] = []
    for mant in (
        (1.0,),
        (1.0, 3.0),
        (1.0, 2.0, 5.0),
        (1.0, 2.0, 3.0, 5.0),
        (1.0, 1.5, 2.0, 3.0, 5.0, 7.0),
        (1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0),
    ):
        vals = [m * 10.0**k for k in range(k0, k1 + 1) for m in mant]
        vals = [v for v in vals if lo * (1 - 1e-9) <= v <= hi * (1 + 1e-9)]
        if len(vals) > max_ticks:
            step = int(np.ceil(len(vals) / max_ticks))
            vals = vals[::step]
        ticks = vals
        if len(vals) >= min_ticks:
            break
    axis.set_major_locator(FixedLocator(ticks))
    axis.set_major_formatter(FuncFormatter(lambda v, _pos: _tick_text(v)))
    wide = k1 - k0 > 4  # many decades: minor marks would only clutter the grid
    axis.set_minor_locator(
        NullLocator() if wide else LogLocator(subs=np.arange(2, 10), numticks=12)
    )
    axis.set_minor_formatter(NullFormatter())
    if axis.axis_name == "x":
        axis.axes.set_xlim(lo, hi)
    else:
        axis.axes.set_ylim(lo, hi)


def _data_points(ax: Any) -> np.ndarray:
    """Display coordinates of what ``ax`` draws as data: the vertices of its lines (straight
    segments sampled at 32 points), markers, error bars and scatter points; (k, 2)."""
    pts = []
    for ln in ax.get_lines():
        xy = np.asarray(ln.get_xydata(), dtype=float)
        if len(xy) == 0 or not ln.get_visible() or ln.get_label() == "_nolegend_axline":
            continue
        if len(xy) == 2 and ln.get_linestyle() not in ("None", "none", ""):
            t = np.linspace(0.0, 1.0, 32)[:, None]
            xy = xy[0] + t * (xy[1] - xy[0])
        pts.append(ln.get_transform().transform(xy))
    for c in ax.collections:
        if not c.get_visible() or type(c).__name__ in (
            "PolyCollection",
            "FillBetweenPolyCollection",
        ):
            continue  # a shaded band may lie under a legend
        off = np.asarray(c.get_offsets(), dtype=float)
        if (
            len(off)
            and c.get_offset_transform() is not None
            and type(c).__name__ == "PathCollection"
        ):
            pts.append(c.get_offset_transform().transform(off))
        for path in c.get_paths() if type(c).__name__ == "LineCollection" else ():
            pts.append(c.get_transform().transform(path.vertices))
    pts = [p[np.all(np.isfinite(p), axis=1)] for p in pts]
    return np.concatenate(pts) if pts else np.empty((0, 2))


def legend_covers_data(ax: Any, legend: Any = None, *, draw: bool = True) -> int:
    """How many data points of ``ax`` (:func:`_data_points`) lie under its legend (display
    coordinates; after a draw of the figure unless ``draw`` is false)."""
    legend = legend if legend is not None else ax.get_legend()
    if legend is None:
        return 0
    if draw:
        ax.figure.draw_without_rendering()
    box = legend.get_window_extent()
    p = _data_points(ax)
    inside = (p[:, 0] >= box.x0) & (p[:, 0] <= box.x1) & (p[:, 1] >= box.y0) & (p[:, 1] <= box.y1)
    return int(inside.sum())


_PLACED = "_warptrunc_placed"
"""Attribute of a legend made by :func:`place_legend`: what it needs to move under its axes."""


def place_legend(ax: Any, *, fontsize: float = 7, ncols: int = 1, **kw: Any) -> Any:
    """A legend for ``ax`` that covers no data: inside the axes where matplotlib's best place
    is clear of every point, line and error bar, else under the axes. The choice is made when
    the figure is laid out for good (:func:`settle_legends`, which :func:`finish_figure`
    calls), since a layout that shrinks the axes moves the data under a legend.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes whose labelled artists are listed.
    fontsize : float
        Legend text size (pt).
    ncols : int
        Columns of the legend when it goes under the axes.
    **kw
        As for :meth:`matplotlib.axes.Axes.legend` (``handles``, ``title``, ...).

    Returns
    -------
    matplotlib.legend.Legend or None
        The legend (None when nothing is labelled).
    """
    handles, labels = kw.pop("handles", None), kw.pop("labels", None)
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    elif labels is None:
        labels = [h.get_label() for h in handles]
    if not handles:
        return None
    leg = ax.legend(handles, labels, fontsize=fontsize, loc="best", **kw)
    setattr(leg, _PLACED, {"handles": handles, "labels": labels, "fontsize": fontsize,
                           "ncols": ncols, "kw": kw, "below": False})  # fmt: skip
    return leg


def _move_below(ax: Any, leg: Any) -> Any:
    """Replace a :func:`place_legend` legend by one under the axes' tick labels and x label
    (the constrained layout makes room for it below; keep it narrower than the figure)."""
    from matplotlib.transforms import ScaledTranslation

    spec = getattr(leg, _PLACED)
    leg.remove()
    fig = ax.figure
    # under the tick labels and the x label: their height in points does not change when the
    # constrained layout shrinks the axes to make room
    below = (ax.get_window_extent().y0 - ax.get_tightbbox().y0) * 72.0 / fig.dpi + 4.0
    anchor = ax.transAxes + ScaledTranslation(0.0, -below / 72.0, fig.dpi_scale_trans)
    new = ax.legend(
        spec["handles"],
        spec["labels"],
        fontsize=spec["fontsize"],
        loc="upper center",
        bbox_to_anchor=(0.5, 0.0),
        bbox_transform=anchor,
        ncols=spec["ncols"],
        borderaxespad=0.0,
        **spec["kw"],
    )
    setattr(new, _PLACED, {**spec, "below": True})
    return new


def settle_legends(fig: Any, rounds: int = 4) -> None:
    """Lay ``fig`` out and move every :func:`place_legend` legend that covers data under its
    axes, until none does (each move changes the layout, so a few rounds).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure, complete but for saving.
    rounds : int
        Most layouts tried.
    """
    placed = [ax for ax in fig.axes if getattr(ax.get_legend(), _PLACED, None)]
    if not placed:
        return
    for _ in range(rounds):
        fig.draw_without_rendering()
        moved = False
        for ax in placed:
            leg = ax.get_legend()
            if leg is None or getattr(leg, _PLACED)["below"]:
                continue
            if legend_covers_data(ax, leg, draw=False):
                _move_below(ax, leg)
                moved = True
        if not moved:
            break  # the saved picture is laid out as this last check was


def finish_figure(fig: Any, path: str | Path | None) -> Any:
    """Settle the legends (:func:`settle_legends`), then save the figure as PNG at ``path``
    (parent folders created) when given; returns ``fig``."""
    settle_legends(fig)
    if path is not None:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=DPI)
    return fig


def finish_axes(
    fig: Any,
    ax: Any,
    path: str | Path | None,
    *,
    title: str | None,
    which: str = "major",
    legend: bool = True,
) -> Any:
    """Grid (``which`` ticks), title and legend (:func:`place_legend`: off the data) of a
    one-axes figure, then :func:`finish_figure`."""
    ax.grid(True, which=which, alpha=0.3)
    if title:
        ax.set_title(title)
    if legend:
        place_legend(ax)
    return finish_figure(fig, path)


def show_pngs(
    paths: Any, *, figsize: tuple[float, float] | None = None, titles: bool = False
) -> None:
    """Open saved PNG figures in matplotlib windows and block until they are closed.

    The last step of the examples (skipped with ``--no-show``); needs a display.

    Parameters
    ----------
    paths : sequence of str or Path
        PNG files, one window each.
    figsize : (float, float), optional
        Window size (inches); matplotlib's default when None.
    titles : bool
        Title each window with its file name.
    """
    import matplotlib.pyplot as plt

    for p in paths:
        plt.figure(figsize=figsize)
        plt.imshow(plt.imread(p))
        plt.axis("off")
        if titles:
            plt.title(Path(p).name)
    plt.show()


def as_list(x: Any) -> list:
    """A single result object or a sequence of them, as a list."""
    return list(x) if isinstance(x, (list, tuple)) else [x]


def is_group(x: Any) -> bool:
    """A group of seeds of one case: a list/tuple of result objects (drawn as mean ± spread)."""
    return isinstance(x, (list, tuple))


def length_axes(ax: Any, x: str = "x", y: str = "y") -> None:
    """Label both axes as lengths in µm."""
    ax.set_xlabel(f"{x} (µm)")
    ax.set_ylabel(f"{y} (µm)")


def shade_band(xs: list, ys: list, *, log: bool, n: int = 200, spread: str = "sd"):
    """Mean and spread over curves (x_i, y_i), on a grid over the x range they all cover.

    In log mode x and y are interpolated and averaged as logarithms (geometric mean and
    sd). Returns (grid, centre, lower, upper); spread "sd" is ±1 sample standard deviation,
    "range" is min–max.
    """

    f = np.log if log else np.asarray
    inv = np.exp if log else np.asarray
    lo = max(float(np.min(x)) for x in xs)
    hi = min(float(np.max(x)) for x in xs)
    if not hi > lo:
        raise ValueError("the curves of a group share no x range; plot them separately")
    grid = np.geomspace(lo, hi, n) if log else np.linspace(lo, hi, n)
    v = np.stack(
        [
            np.interp(f(grid), f(np.asarray(x)), f(np.asarray(y)))
            for x, y in zip(xs, ys, strict=True)
        ]
    )
    c = v.mean(axis=0)
    if spread == "range":
        a, b = v.min(axis=0), v.max(axis=0)
    elif spread == "sd":
        s = v.std(axis=0, ddof=1) if len(xs) > 1 else np.zeros_like(c)
        a, b = c - s, c + s
    else:
        raise ValueError(f"spread must be 'sd' or 'range', got {spread!r}")
    return grid, inv(c), inv(a), inv(b)
