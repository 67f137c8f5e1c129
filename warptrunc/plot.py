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

# --- islands (Fig. 8) --------------------------------------------------------------------------

# --- descriptors and fractal dimension (PSD, Fig. 10) ------------------------------------------

# --- height maps and truncated-area fraction ---------------------------------------------------
