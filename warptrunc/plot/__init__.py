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
Every figure is importable from ``warptrunc.plot``; each module is imported on first use.
"""

from __future__ import annotations

import importlib as _importlib
from typing import Any as _Any

_HOME = {
    "CONTACT_COLOR": "_style",
    "CONTACT_RGB": "_style",
    "DPI": "_style",
    "FIGSIZE": "_style",
    "HEIGHT_CMAP": "_style",
    "PAPER_ALPHA_D": "_style",
    "SPREAD_ALPHA": "_style",
    "UM": "_style",
    "show_pngs": "_style",
    "plot_bem_check": "bem",
    "alpha_vs_D_routes": "compare",
    "ratio_vs_size": "compare",
    "calibration_history": "fractal",
    "d_out_vs_d_in": "fractal",
    "fractal_fits": "fractal",
    "psd": "fractal",
    "indentation": "indent",
    "island_number": "islands",
    "slit_islands": "islands",
    "area_fraction": "maps",
    "height_map": "maps",
    "alpha_vs_D": "stiffness",
    "stiffness_load": "stiffness",
}
"""The module of each public name, imported on first use (PEP 562): drawing one figure loads
its own module only (``stiffness_load`` does not load the island figures, which need Warp)."""


def __getattr__(name: str) -> _Any:
    if name not in _HOME:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(_importlib.import_module(f".{_HOME[name]}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_HOME})


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
