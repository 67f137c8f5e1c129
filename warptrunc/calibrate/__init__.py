# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Calibration to a scan (Fig. 4): WM inputs (D_in, R_t') that reproduce its descriptors.

Layout: the descriptors to reproduce (:class:`CalibrationTarget`) and how the loop runs
(:class:`CalibrationSettings`; no Warp, the command-line parser reads them) in ``settings``;
the loop (:func:`calibrate`, :class:`Calibration`, :func:`target_from_surface`,
:func:`calibrated_surface`) in ``api``; its 1-D root finder and :class:`CalibrationError` in
``_root_find``. Every public name is importable from ``warptrunc.calibrate`` (imported on first
use); ``warptrunc.calibrate`` itself, at the top of the package, is the function.
"""

from .._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "Calibration": ".api",
        "CalibrationError": "._root_find",
        "CalibrationSettings": ".settings",
        "CalibrationTarget": ".settings",
        "calibrate": ".api",
        "calibrated_surface": ".api",
        "target_from_surface": ".api",
    },
)
