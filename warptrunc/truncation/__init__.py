# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation analysis: contact area A_c(ω) at every truncation depth ω (paper §3).

:func:`truncate` (``api``) is the one entry point; it runs the in-memory path (``curve``: the
curve, the depth grid, the contact index map) or the banded path for WM surfaces larger than
device memory (``stream``). Every public name is importable from ``warptrunc.truncation``.
"""

from .api import truncate
from .curve import (
    TruncationCurve,
    contact_histogram,
    contact_index_device,
    contact_index_map,
    depth_grid,
    height_range,
)
from .stream import StreamedTruncation, fits_in_memory, in_memory_bytes
from .stream import wm_bands as wm_bands  # internal band generator, not in __all__

__all__ = [
    "StreamedTruncation",
    "TruncationCurve",
    "contact_histogram",
    "contact_index_device",
    "contact_index_map",
    "depth_grid",
    "fits_in_memory",
    "height_range",
    "in_memory_bytes",
    "truncate",
]
