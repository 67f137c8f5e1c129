# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation analysis: contact area A_c(ω) at every truncation depth ω (paper §3).

:func:`truncate` (``api``) is the one entry point; it runs the in-memory path (``curve``: the
curve, the depth grid, the contact index map) or the banded path for WM surfaces larger than
device memory (``stream``); its parameters are declared in ``settings``, which loads no Warp.
Every public name is importable from ``warptrunc.truncation`` (imported on first use).
"""

from .._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "FitRange": ".settings",
        "StreamedTruncation": ".stream",
        "TruncationCurve": ".curve",
        "TruncationSettings": ".settings",
        "contact_histogram": ".curve",
        "contact_index_device": ".curve",
        "contact_index_map": ".curve",
        "depth_grid": ".curve",
        "fits_in_memory": ".stream",
        "height_range": ".curve",
        "in_memory_bytes": ".stream",
        "truncate": ".api",
    },
)
