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
CONTACT_RGB = (214, 39, 40)  # contact (truncated) areas, as the paper's red; also in render.py
CONTACT_COLOR = "#d62728"  # the same red for matplotlib
SPREAD_ALPHA = 0.25  # shaded spread over seeds


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

# --- descriptors and fractal dimension (PSD, Fig. 10) ------------------------------------------

# --- height maps and truncated-area fraction ---------------------------------------------------
