# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""All matplotlib figures of warptrunc, in one style.

matplotlib is imported inside the functions, so ``import warptrunc`` stays light. Every
function takes result objects, returns the ``matplotlib.figure.Figure`` and, with ``path=``,
also saves a PNG. Lengths on axes are in µm, as the paper's figures.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

UM = 1e6  # m → µm on axes
FIGSIZE = (5.0, 4.0)
DPI = 150


def _figure(figsize: tuple[float, float] = FIGSIZE, ncols: int = 1, nrows: int = 1):
    """A pyplot-free Figure (renders with Agg, needs no display) and its axes grid."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(figsize[0] * ncols, figsize[1] * nrows), dpi=DPI, layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False)
    return fig, axes


def _finish(fig: Any, path: str | Path | None) -> Any:
    if path is not None:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=DPI)
    return fig


# --- stiffness and load (Fig. 9) ---------------------------------------------------------------


def stiffness_load(
    curves: Any,
    fits: Any = None,
    *,
    labels: Any = None,
    title: str | None = None,
    path: str | Path | None = None,
):
    """E_c/E against F/(E·A) in log–log, with the fitted power laws (the paper's Fig. 9).

    Parameters
    ----------
    curves : StiffnessCurve or sequence of them
        Curves to draw (increments with zero load are skipped).
    fits : PowerLawFit or sequence, optional
        One fit per curve, drawn as a dashed line over its fit range.
    labels : sequence of str, optional
        Legend labels.
    path : path, optional
        Save the figure as PNG here.
    """
    import numpy as np

    curves = list(curves) if isinstance(curves, (list, tuple)) else [curves]
    if fits is not None:
        fits = list(fits) if isinstance(fits, (list, tuple)) else [fits]
    fig, axes = _figure()
    ax = axes[0, 0]
    for i, c in enumerate(curves):
        sel = c.load > 0
        lab = labels[i] if labels is not None else None
        ax.loglog(c.F_over_EA[sel], c.Ec_over_E[sel], "-", lw=1.2, label=lab)
        if fits is not None and fits[i] is not None:
            f = fits[i]
            x = np.geomspace(f.F_over_EA_min, f.F_over_EA_max, 50)
            ax.loglog(
                x, f.beta * x**f.alpha, "--", color="k", lw=1.6, zorder=3,
                label=f"fit α = {f.alpha:.3f}, β = {f.beta:.3g}, r² = {f.r2:.3f}",
            )  # fmt: skip
    ax.set_xlabel("normalised load F/(E·A)")
    ax.set_ylabel("normalised stiffness E$_c$/E")
    ax.grid(True, which="both", alpha=0.3)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=7)
    return _finish(fig, path)


# --- islands (Fig. 8) --------------------------------------------------------------------------


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
        (dotted) and the island-count peak (dash-dotted) are marked in the curve's colour.
    labels : sequence of str, optional
        Legend labels.
    path : path, optional
        Save the figure as PNG here.
    """
    curves = list(curves) if isinstance(curves, (list, tuple)) else [curves]
    if indicators is not None:
        indicators = list(indicators) if isinstance(indicators, (list, tuple)) else [indicators]
    fig, axes = _figure()
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
                if d == d:  # not NaN
                    ax.axvline(
                        100 * d / ind.rt, ls=style, lw=1.0, color=line.get_color(),
                        label=(what if len(curves) > 1 else f"{what}: {100 * d / ind.rt:.1f} % R$_t$")
                        if i == 0 else None,
                    )  # fmt: skip
    ax.set_xlabel("truncation depth ω (% R$_t$)")
    ax.set_ylabel("normalised island number n/n$_{max}$")
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=7)
    return _finish(fig, path)


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
        The islands at a few depths (``IslandCurve.sizes``, from ``snapshot_depths=``).
    min_pixels : int, optional
        Smallest island in the fits (pixels); the curve's own by default, else 10. Smaller
        islands are drawn in grey.
    path : path, optional
        Save the figure as PNG here.
    """
    import numpy as np

    from .islands import MIN_PIXELS, slit_island_fit

    sizes = list(getattr(curve, "sizes", curve))
    if min_pixels is None:
        min_pixels = getattr(curve, "min_pixels", MIN_PIXELS)
    rt = getattr(curve, "rt", None)
    fig, axes = _figure()
    ax = axes[0, 0]
    for sz in sizes:
        if sz.n_islands == 0:
            continue
        big = sz.area_pixels >= min_pixels
        fit = slit_island_fit(sz, min_pixels=min_pixels)
        at = f"ω = {100 * sz.depth / rt:.1f} % R$_t$" if rt else f"ω = {sz.depth * UM:.3g} µm"
        (pts,) = ax.loglog(sz.area[big] * UM**2, sz.perimeter[big] * UM, ".", ms=2.5, alpha=0.6)
        ax.loglog(sz.area[~big] * UM**2, sz.perimeter[~big] * UM, ".", ms=2, color="0.75", zorder=0)
        if fit.exponent == fit.exponent:
            a = np.geomspace(sz.area[big].min(), sz.area[big].max(), 20)
            ax.loglog(
                a * UM**2, 10**fit.intercept * a**fit.exponent * UM, "-",
                color=pts.get_color(), lw=1.4,
                label=f"{at}: exponent {fit.exponent:.3f} (D = {fit.dimension:.2f}, "
                f"r² = {fit.r2:.3f}, {fit.n_islands} islands)",
            )  # fmt: skip
        else:
            pts.set_label(f"{at}: too few islands ≥ {min_pixels} px")
    ax.set_xlabel("island area A (µm²)")
    ax.set_ylabel("island perimeter L (µm)")
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title(title or f"slit islands (grey: < {min_pixels} pixels, not fitted)")
    ax.legend(fontsize=6)
    return _finish(fig, path)


# --- descriptors and fractal dimension (PSD, Fig. 10) ------------------------------------------

# --- height maps and truncated-area fraction ---------------------------------------------------
