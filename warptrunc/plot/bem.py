# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic cross-check figure: F and k against δ by BEM and truncation, and their ratios."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..contact.check import BemCheck

__all__ = ["plot_bem_check"]


def plot_bem_check(res: BemCheck, path: str | Path | None = None, *, title: str | None = None):
    """F and k against δ for both methods, and A'/A_BEM; non-converged rows marked with ×.

    Parameters
    ----------
    res : BemCheck
        The comparison (:func:`warptrunc.bem_check`).
    path : str or Path, optional
        PNG to save the figure to.
    title : str, optional
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ._style import readable_log_ticks

    dum = res.depth * 1e6
    fig, ax = plt.subplots(1, 3, figsize=(13, 4), constrained_layout=True)
    ax[0].plot(dum, res.bem_load, "o-", label="elastic BEM")
    ax[0].plot(dum, res.trunc_load, "s--", label="truncation")
    ax[0].set(xlabel="approach d (µm)", ylabel="load F (N)", yscale="log")
    ax[1].plot(dum, res.bem_stiffness, "o-", label="elastic BEM")
    ax[1].plot(dum, res.trunc_stiffness, "s--", label="truncation")
    ax[1].set(xlabel="approach d (µm)", ylabel="stiffness k (N/m)", yscale="log")
    ax[2].plot(dum, res.area_ratio, "o-", label="A'/A$_{BEM}$")
    ax[2].plot(dum, res.load_ratio, "^-", label="F'/F$_{BEM}$")
    ax[2].plot(dum, res.stiffness_ratio, "v-", label="k'/k$_{BEM}$")
    ax[2].axhline(1.0, color="0.6", lw=0.8)
    ax[2].set(xlabel="approach d (µm)", ylabel="truncation / BEM", yscale="log")
    bad = ~res.converged
    if bad.any():
        for a, y in ((ax[0], res.bem_load), (ax[1], res.bem_stiffness)):
            a.plot(dum[bad], y[bad], "rx", ms=10, label="not converged")
    for a in ax:
        a.legend(fontsize=8)
        a.grid(True, which="both", alpha=0.3)
    # ratios span about a decade around 1: label 1-2-3-5 values, so that the curves below 1
    # (F'/F_BEM, k'/k_BEM of 0.3–0.8) sit between labelled ticks
    ax[2].autoscale_view()
    readable_log_ticks(ax[2].yaxis, max_ticks=8, min_ticks=6)
    if title:
        fig.suptitle(title)
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig
