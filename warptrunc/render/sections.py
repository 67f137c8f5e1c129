# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""3-D pictures of truncation sections (the paper's Fig. 7) with pyvista, off-screen.

The surface is drawn as a height field with the contact set at each depth ω in red over a
neutral grey (shaded by height), one panel per depth, and saved as PNG; an animation shows the
truncation deepening. pyvista is imported inside the functions, so ``import warptrunc`` stays
light; without it these functions raise an ImportError naming ``pip install pyvista``.

Each pixel of the height map is one cell of the rendered mesh, so the contact set is drawn
pixel for pixel (no interpolation of the mask across cells). Large maps are down-sampled to at
most about one block per screen pixel (block heights are block means), and a block of f×f
pixels is coloured by ``pooling`` (see :mod:`warptrunc.plot.pooling`): by default (``"area"``) its
share of red is the fraction of its pixels in contact, so the red in the picture measures
A_c/A; ``"any"`` (max-pooling) paints a block red when any of its pixels touches, which shows
every contact spot but overstates the area. The factor f and the pooling are returned and
written into the picture's caption and PNG metadata.

Layout: the mesh, panels and camera in ``scene``; tiling, captions and PNG output in
``image``; :class:`Rendering` and the two drivers here (re-exported by ``warptrunc.render``).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import warp as wp

from .._support.docs import SHARED_DOCS, fill_doc
from .._support.progress import progress_bar
from ..plot.pooling import (
    block_contact,
    check_depths,
    check_pooling,
)
from ..surface import Surface
from .image import (
    caption_strip,
    caption_text,
    depth_title,
    draw_text,
    grid_layout,
    save_png,
    tile,
    with_caption,
)
from .scene import Panel, Scene, auto_exaggeration, auto_factor, import_pyvista, vtk_quiet
from .settings import AnimationSettings, RenderSettings

__all__ = ["Rendering", "animate_truncation", "render_truncation"]

PANEL_SIZE = (520, 440)
"""Pixel size of one panel when no ``window_size`` is given (width, height)."""


@dataclass(frozen=True, eq=False)
class Rendering:
    """A rendered picture (or animation) of truncation sections."""

    path: Path | None
    """File written (PNG, GIF or MP4), or None."""
    image: np.ndarray
    """(height, width, 3) uint8 RGB of the picture (the last frame of an animation)."""
    depth: np.ndarray
    """(k,) float64 truncation depths ω shown, one per panel or frame (m)."""
    depth_fraction: np.ndarray
    """(k,) float64 ω/R_t (dimensionless)."""
    area_fraction: np.ndarray
    """(k,) float64 A_c/A at full resolution (dimensionless)."""
    downsample: int
    """Block size f: the mesh has one cell per f×f pixels (1 = full resolution)."""
    pooling: str
    """How a block is coloured: ``"area"`` (share of red = contact fraction) or ``"any"``
    (red when any pixel touches; max-pooling)."""
    mesh_shape: tuple[int, int]
    """(rows, columns) of cells drawn."""
    surface_shape: tuple[int, int]
    """(ny, nx) pixels of the height map."""
    vertical_exaggeration: float
    """Factor applied to heights in the picture (dimensionless)."""
    top_view: bool
    """True for an orthographic view from above."""
    caption: str
    """Caption drawn on the picture and stored in the PNG metadata."""

    @property
    def image_shape(self) -> tuple[int, int, int]:
        """(height, width, 3) of :attr:`image`."""
        return tuple(self.image.shape)  # type: ignore[return-value]

    def to_dict(self) -> dict[str, Any]:
        """One row per depth: depth_m, depth_fraction_of_Rt, area_fraction, and the scalars.

        Returns
        -------
        dict
            Per-depth columns ``depth_m`` (m), ``depth_fraction_of_Rt`` and ``area_fraction``
            (dimensionless); scalars ``path`` (str or None), ``image_height``,
            ``image_width`` (pixels), ``downsample``, ``pooling``, ``mesh_rows``,
            ``mesh_columns``, ``ny``, ``nx``, ``vertical_exaggeration`` (dimensionless),
            ``top_view`` and ``caption``.
        """

        return {
            "depth_m": self.depth,
            "depth_fraction_of_Rt": self.depth_fraction,
            "area_fraction": self.area_fraction,
            "path": None if self.path is None else str(self.path),
            "image_height": int(self.image.shape[0]),
            "image_width": int(self.image.shape[1]),
            "downsample": self.downsample,
            "pooling": self.pooling,
            "mesh_rows": self.mesh_shape[0],
            "mesh_columns": self.mesh_shape[1],
            "ny": self.surface_shape[0],
            "nx": self.surface_shape[1],
            "vertical_exaggeration": self.vertical_exaggeration,
            "top_view": self.top_view,
            "caption": self.caption,
        }

    def _metadata(self) -> str:
        d = self.to_dict()
        for k in ("depth_m", "depth_fraction_of_Rt", "area_fraction"):
            d[k] = [float(v) for v in d[k]]
        d.pop("path")
        return json.dumps(d)


def _rendering(path, image, depth, frac, f, pooling, scene, surface, ve, top_view, caption):
    """The :class:`Rendering` of a picture or an animation (depths in m)."""
    return Rendering(
        path=None if path is None else Path(path),
        image=image,
        depth=depth,
        depth_fraction=depth / surface.Rt,
        area_fraction=np.asarray(frac, dtype=np.float64),
        downsample=f,
        pooling=pooling,
        mesh_shape=scene.shape,
        surface_shape=(surface.ny, surface.nx),
        vertical_exaggeration=ve,
        top_view=bool(top_view),
        caption=caption,
    )


@fill_doc(SHARED_DOCS)
def render_truncation(
    surface: Surface,
    path: str | Path | None = None,
    *,
    settings: RenderSettings | None = None,
    device: wp.DeviceLike = None,
) -> Rendering:
    """Render truncation sections: the surface with its contact set at each depth in red.

    Parameters
    ----------
    {surface}
    path : path, optional
        Save the picture as PNG here (with the caption and the result's metadata in PNG text
        chunks).
    settings : RenderSettings, optional
        The picture (:class:`~warptrunc.render.settings.RenderSettings`; its defaults when
        None): the depths (``depth_fractions`` of R_t in (0, 1], one panel each, the paper's
        Fig. 7 uses 0.1–0.5; or ``depths`` ω in (0, R_t] (m), which override them); the view
        (``top_view``: from above with an orthographic projection, x to the right and y up, as
        ``imshow(z, origin="lower")``; otherwise an oblique view from the −y side, 35° above
        the horizon); the picture size ``window_size`` (width, height) in pixels (default
        520×440 per panel) and ``ncols`` panels per row (default up to 3); the
        ``vertical_exaggeration`` of heights (default :func:`auto_exaggeration`); the block side
        ``downsample`` f of the drawn mesh (default: the smallest f that gives every block at
        least one screen pixel, over the map's footprint in the top view, over the panel's
        shorter side in the oblique view, and at most ``max_mesh`` blocks per side); the
        ``pooling`` of a block of f×f pixels when f > 1 (``"area"``: its share of red is the
        fraction of its pixels in contact, so the red in the picture measures A_c/A; ``"any"``:
        max-pooling, red when any of its pixels touches, which shows every contact spot but
        overstates the area; the caption says which); ``lighting`` by VTK lights (default on
        in the oblique view, off in the top view: flat colours, so red pixels measure the
        contact area); ``annotate``: titles, axes in µm and the caption.
    device : str, optional
        Warp device for the contact index; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    Rendering
        The image, the depths, the full-resolution A_c/A, the down-sampling factor and the
        vertical exaggeration.

    Notes
    -----
    Each pixel (or block) is one flat-coloured cell; corner heights are means of the adjacent
    cells. A pixel is in contact at ω when z ≥ float32(z_top − ω), as in
    :func:`warptrunc.truncate`. Rendering is off-screen and needs no display.

    In the top view without annotations, a window of k·nx × k·ny pixels per panel shows every
    map pixel as k×k screen pixels, so the red pixels count k²·N_c exactly.

    Examples
    --------
    >>> from warptrunc.wm import wm_surface
    >>> from warptrunc.render import RenderSettings, render_truncation
    >>> s = wm_surface(2.5, 100e-6, n=2048, Rt=10e-6, seed=1)
    >>> r = render_truncation(s, "truncation.png", settings=RenderSettings(top_view=True))  # doctest: +SKIP
    >>> r.downsample, r.area_fraction  # doctest: +SKIP
    """
    o = RenderSettings() if settings is None else settings
    depth_fractions, depths, top_view = o.depth_fractions, o.depths, o.top_view
    window_size, ncols, vertical_exaggeration = o.window_size, o.ncols, o.vertical_exaggeration
    downsample, pooling, max_mesh = o.downsample, o.pooling, o.max_mesh
    lighting, annotate = o.lighting, o.annotate
    import_pyvista()
    depth = check_depths(surface, depth_fractions, depths, upto_rt=True)
    check_pooling(pooling)
    nrows, ncols = grid_layout(depth.size, ncols)
    if window_size is None:
        window_size = (PANEL_SIZE[0] * ncols, PANEL_SIZE[1] * nrows)
    w, h = window_size
    spare = nrows * ncols > depth.size
    # no spare panel: the caption goes in a strip below the panels, sized for its longest form
    longest = caption_text(surface, 2, (surface.ny, surface.nx), 10.0, pooling)
    strip, fs = caption_strip(longest, w) if annotate and not spare else (0, 0)
    strip = min(strip, h // 3)
    pw, ph = w // ncols, (h - strip) // nrows
    if downsample is None:
        downsample = auto_factor(
            surface, (pw, ph), top_view=top_view, annotate=annotate, max_mesh=max_mesh
        )
    f = int(downsample)
    ve = float(
        auto_exaggeration(surface) if vertical_exaggeration is None else vertical_exaggeration
    )
    if lighting is None:
        lighting = not top_view

    blocks, frac = block_contact(surface, depth, f, pooling, device)
    scene = Scene(surface, f, ve)
    caption = caption_text(surface, f, scene.shape, ve, pooling)
    Rt = surface.Rt
    with vtk_quiet():
        panel = Panel(
            scene, (pw, ph), top_view=top_view, lighting=lighting, annotate=annotate, ve=ve
        )
        try:
            images = [
                panel.frame(blocks[i], depth_title(depth[i], Rt, frac[i]))
                for i in range(depth.size)
            ]
        finally:
            panel.close()
    img = tile(images, nrows, ncols, (w, h - strip))
    if strip:
        img = with_caption(img, caption, strip, fs)
    if annotate and spare:
        r, c = divmod(depth.size, ncols)
        fs = max(10, min(16, pw // 34))
        img = draw_text(img, caption, (c * pw + 12, r * ph + 14), fs, pw - 24)
    result = _rendering(path, img, depth, frac, f, pooling, scene, surface, ve, top_view, caption)
    if path is not None:
        save_png(img, Path(path), result._metadata(), caption)
    return result


@fill_doc(SHARED_DOCS)
def animate_truncation(
    surface: Surface,
    path: str | Path,
    *,
    settings: RenderSettings | None = None,
    animation: AnimationSettings | None = None,
    progress: bool = True,
    device: wp.DeviceLike = None,
) -> Rendering:
    """Animate the truncation deepening from ω = 0 to ``max_depth_fraction``·R_t.

    Parameters
    ----------
    {surface}
    path : path
        Output file: ``.gif`` (written with Pillow) or ``.mp4`` (needs
        ``pip install imageio imageio-ffmpeg``).
    settings : RenderSettings, optional
        The view and the mesh, as for :func:`render_truncation`: ``top_view``,
        ``vertical_exaggeration``, ``downsample``, ``pooling`` and ``max_mesh`` are read (the
        frames are annotated, lit in the oblique view only); its defaults when None.
    animation : AnimationSettings, optional
        The last depth as a fraction of R_t in (0, 1] (``max_depth_fraction``, 0.5 by default:
        the deepest of the paper's Fig. 7 sections, :data:`DEFAULT_DEPTH_FRACTIONS`, not
        :func:`warptrunc.truncate`'s 0.1: a picture shows the contact spreading), the number of
        frames (≥ 2, depths equally spaced from 0), frames per second and the frame size
        (:class:`~warptrunc.render.settings.AnimationSettings`; its defaults when None).
    progress : bool
        Report the frames on stderr (a bar on a terminal, else a line every few seconds).
    device : str, optional
        Warp device for the contact index; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    Rendering
        The last frame, and one depth per frame.
    """
    o = RenderSettings() if settings is None else settings
    a = AnimationSettings() if animation is None else animation
    top_view, vertical_exaggeration, downsample = o.top_view, o.vertical_exaggeration, o.downsample
    pooling, max_mesh = o.pooling, o.max_mesh
    max_depth_fraction, n, fps, frame_size = a.max_depth_fraction, a.frames, a.fps, a.frame_size
    import_pyvista()
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".gif", ".mp4"):
        raise ValueError(f"animation path must end in .gif or .mp4, got {str(path)!r}")
    writer = None
    if suffix == ".mp4":
        try:
            import imageio.v2 as imageio
        except ImportError as exc:
            raise ImportError(
                "MP4 animations need imageio and ffmpeg: pip install imageio imageio-ffmpeg "
                "(or write a .gif, which needs only Pillow)"
            ) from exc
    w, h = frame_size
    if downsample is None:
        downsample = auto_factor(
            surface, (w, h), top_view=top_view, annotate=True, max_mesh=max_mesh
        )
    f = int(downsample)
    ve = (
        auto_exaggeration(surface)
        if vertical_exaggeration is None
        else float(vertical_exaggeration)
    )
    bar = progress_bar(total=n + 1, desc="animation", unit="frame", enabled=progress)
    try:
        bar.set_postfix_str("contact of every frame")
        depth = np.linspace(0.0, max_depth_fraction, n) * surface.Rt
        blocks, frac = block_contact(surface, depth, f, check_pooling(pooling), device)
        scene = Scene(surface, f, ve)
        caption = caption_text(surface, f, scene.shape, ve, pooling)
        strip, fs = caption_strip(caption, w)
        strip = min(strip, h // 3)
        Rt = surface.Rt
        with vtk_quiet():
            panel = Panel(
                scene,
                (w, h - strip),
                top_view=top_view,
                lighting=not top_view,
                annotate=True,
                ve=ve,
            )
            bar.set_postfix_str("")
            frames = []
            try:
                for i in range(n):
                    image = panel.frame(blocks[i], depth_title(depth[i], Rt, frac[i]))
                    frames.append(with_caption(image, caption, strip, fs))
                    bar.update()
            finally:
                panel.close()
            bar.set_postfix_str(f"writing {path.name}")
        path.parent.mkdir(parents=True, exist_ok=True)
        if suffix == ".gif":
            from PIL import Image

            ims = [Image.fromarray(fr) for fr in frames]
            ims[0].save(
                path,
                save_all=True,
                append_images=ims[1:],
                duration=round(1000 / fps),
                loop=0,
                comment=caption.encode(),
            )
        else:
            writer = imageio.get_writer(path, fps=fps)
            try:
                for fr in frames:
                    writer.append_data(fr)
            finally:
                writer.close()
        bar.update()
    finally:
        bar.close()
    return _rendering(
        path, frames[-1], depth, frac, f, pooling, scene, surface, ve, top_view, caption
    )
