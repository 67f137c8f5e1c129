# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""3-D pictures of truncation sections (the paper's Fig. 7) with pyvista, off-screen.

Layout: :class:`Rendering` and the two drivers in ``sections``; the mesh, panels and camera in
``scene``; tiling, captions and PNG output in ``image``; block pooling of large maps in
:mod:`warptrunc.plot.pooling`. Every name is importable from ``warptrunc.render``.
"""

from ..plot.pooling import POOLING, contact_masks, pool_blocks
from .scene import auto_exaggeration
from .sections import DEFAULT_DEPTH_FRACTIONS, Rendering, animate_truncation, render_truncation

__all__ = [
    "DEFAULT_DEPTH_FRACTIONS",
    "POOLING",
    "Rendering",
    "animate_truncation",
    "auto_exaggeration",
    "contact_masks",
    "pool_blocks",
    "render_truncation",
]
