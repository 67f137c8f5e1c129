# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""All matplotlib figures of warptrunc, in one style.

matplotlib is imported inside the functions, so ``import warptrunc`` stays light. Every
function takes result objects, returns the ``matplotlib.figure.Figure`` and, with ``path=``,
also saves a PNG. Lengths on axes are in µm, as the paper's figures.

Layout: the style and shared helpers in ``_style``; Fig. 9 in ``stiffness``; Fig. 8 in
``islands``; PSD and fractal dimension (Fig. 10) in ``fractal``; height maps in ``maps``;
the elastic cross-check in ``bem``; truncation against elastic contact in ``compare``;
flat-punch indentation (Fig. 6) in ``indent``.
Every figure is importable from ``warptrunc.plot``.
"""

from __future__ import annotations

from ._style import (
    CONTACT_COLOR,
    CONTACT_RGB,
    DPI,
    FIGSIZE,
    HEIGHT_CMAP,
    PAPER_ALPHA_D,
    SPREAD_ALPHA,
    UM,
    show_pngs,
)
from .bem import plot_bem_check
from .compare import alpha_vs_D_routes, ratio_vs_size
from .fractal import calibration_history, d_out_vs_d_in, fractal_fits, psd
from .indent import indentation
from .islands import island_number, slit_islands
from .maps import area_fraction, height_map
from .stiffness import alpha_vs_D, stiffness_load

__all__ = [
    "CONTACT_COLOR",
    "CONTACT_RGB",
    "DPI",
    "FIGSIZE",
    "HEIGHT_CMAP",
    "PAPER_ALPHA_D",
    "SPREAD_ALPHA",
    "UM",
    "alpha_vs_D",
    "alpha_vs_D_routes",
    "area_fraction",
    "calibration_history",
    "d_out_vs_d_in",
    "fractal_fits",
    "height_map",
    "indentation",
    "island_number",
    "plot_bem_check",
    "psd",
    "ratio_vs_size",
    "show_pngs",
    "slit_islands",
    "stiffness_load",
]
