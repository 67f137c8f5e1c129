# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The report's house style, shared by every stage's pages: a figure of panels, its file, and a
number in a table cell.

:mod:`warptrunc.reproduce.figures` and :mod:`warptrunc.reproduce.report` assemble the report
from the stages' figures and sections (:mod:`warptrunc.reproduce.elastic_report`,
:mod:`warptrunc.reproduce.indentation.report`); these helpers sit below all of them.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

__all__ = ["fmt_value", "new_figure", "save_figure"]


def new_figure(ncols: int = 1, nrows: int = 1, w: float = 5.2, h: float = 4.0):
    """A matplotlib figure of ``nrows`` × ``ncols`` panels (no pyplot, constrained layout).

    Parameters
    ----------
    ncols, nrows : int
        Panels per row and rows.
    w, h : float
        Size of one panel (inches).

    Returns
    -------
    fig : matplotlib.figure.Figure
    axes : ndarray of Axes
        The panels, row by row.
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(w * ncols, h * nrows), layout="constrained")
    axs = fig.subplots(nrows, ncols, squeeze=False)
    return fig, axs.ravel()


def save_figure(fig: Any, out: Path, name: str) -> str:
    """Write ``fig`` as ``out/name`` (PNG, 110 dpi).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    out : Path
        Output folder.
    name : str
        File name.

    Returns
    -------
    str
        ``name``.
    """
    fig.savefig(out / name, dpi=110)
    return name


def fmt_value(v: Any, fmt: str = ".3f") -> str:
    """A number for a table cell: ``format(v, fmt)``, or "—" for None, NaN and ±inf.

    Parameters
    ----------
    v : float or None
        The value.
    fmt : str
        Format specification.

    Returns
    -------
    str
    """
    return "—" if v is None or (isinstance(v, float) and not math.isfinite(v)) else format(v, fmt)
