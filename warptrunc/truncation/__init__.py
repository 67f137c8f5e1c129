# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation analysis: contact area A_c(ω) at every truncation depth ω (paper §3).

``curve``: the in-memory path (:func:`truncate`, the depth grid, the contact index map);
``stream``: the banded path for WM surfaces larger than device memory. Every name is
importable from ``warptrunc.truncation``.
"""

from .curve import (
    TruncationCurve,
    contact_histogram,
    contact_index_map,
    depth_grid,
    height_range,
    truncate,
)
from .stream import (
    StreamedTruncation,
    fits_in_memory,
    in_memory_bytes,
    stream_truncation,
    truncate_streamed,
    wm_bands,
)

__all__ = [
    "StreamedTruncation",
    "TruncationCurve",
    "contact_histogram",
    "contact_index_map",
    "depth_grid",
    "fits_in_memory",
    "height_range",
    "in_memory_bytes",
    "stream_truncation",
    "truncate",
    "truncate_streamed",
    "wm_bands",
]
