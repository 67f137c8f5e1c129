# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""3-D pictures of truncation sections (the paper's Fig. 7) with pyvista, off-screen.

Layout: the parameters of a picture and of an animation (:class:`RenderSettings`,
:class:`AnimationSettings`; no Warp, no pyvista) in ``settings``; :class:`Rendering` and the two
drivers in ``sections``; the mesh, panels and camera in ``scene``; tiling, captions and PNG
output in ``image``; block pooling of large maps in :mod:`warptrunc.plot.pooling`. Every public
name is importable from ``warptrunc.render`` (imported on first use).
"""

from .._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "DEFAULT_DEPTH_FRACTIONS": ".settings",
        "MAX_MESH": ".settings",
        "POOLING": "..plot.pooling",
        "AnimationSettings": ".settings",
        "RenderSettings": ".settings",
        "Rendering": ".sections",
        "animate_truncation": ".sections",
        "auto_exaggeration": ".scene",
        "contact_masks": "..plot.pooling",
        "pool_blocks": "..plot.pooling",
        "render_truncation": ".sections",
    },
)
