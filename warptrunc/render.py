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
pixels is coloured by ``pooling`` (see :mod:`warptrunc._blocks`): by default (``"area"``) its
share of red is the fraction of its pixels in contact, so the red in the picture measures
A_c/A; ``"any"`` (max-pooling) paints a block red when any of its pixels touches, which shows
every contact spot but overstates the area. The factor f and the pooling are returned and
written into the picture's caption and PNG metadata.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import warp as wp

from ._blocks import POOLING, block_contact, check_depths, check_pooling, contact_masks, pool_blocks
from .surface import Surface

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

#: Depths of the paper's Fig. 7, as fractions of R_t.
DEFAULT_DEPTH_FRACTIONS = (0.1, 0.2, 0.3, 0.4, 0.5)
#: Largest rendered mesh side (blocks) when the image would allow more.
MAX_MESH = 1024
#: Pixel size of one panel when no ``window_size`` is given (width, height).
PANEL_SIZE = (520, 440)

_NEUTRAL = (95, 225)  # grey levels of the lowest and the highest non-contact cells


def _pyvista():
    try:
        import pyvista as pv
    except ImportError as exc:  # pragma: no cover - exercised where pyvista is absent
        raise ImportError(
            "warptrunc.render needs pyvista (and VTK) for 3-D pictures: pip install pyvista"
        ) from exc
    return pv


@contextmanager
def _vtk_quiet():
    """Hide VTK's warnings while rendering (e.g. "bad X server connection" on headless
    machines, where off-screen rendering works regardless), unless verbose
    (:func:`warptrunc._device.set_verbose`, ``warptrunc --verbose``, ``$WARPTRUNC_VERBOSE``).
    The previous global setting of VTK is restored afterwards."""
    from ._device import is_verbose

    if is_verbose():
        yield
        return
    from vtkmodules.vtkCommonCore import vtkObject

    was = vtkObject.GetGlobalWarningDisplay()
    vtkObject.GlobalWarningDisplayOff()
    try:
        yield
    finally:
        vtkObject.SetGlobalWarningDisplay(was)


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
        """One row per depth: depth_m, depth_fraction_of_Rt, area_fraction, and the scalars."""
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


# --- down-sampling ------------------------------------------------------------------------------


def _auto_factor(
    surface: Surface, panel: tuple[int, int], *, top_view: bool, annotate: bool, max_mesh: int
) -> int:
    """Smallest block side that gives every block at least one screen pixel.

    Top view: over the map's footprint in the panel (so a red block always covers a pixel
    centre); oblique view: over the panel's shorter side. Never more than ``max_mesh``
    blocks per side.
    """
    pw, ph = panel
    nx, ny = surface.nx, surface.ny
    if top_view:
        per_m = ph / (2.0 * _top_scale(surface.lx, surface.ly, pw, ph, _fill(annotate)))
        f = max(nx / (surface.lx * per_m), ny / (surface.ly * per_m))
    else:
        f = max(nx, ny) / max(1, min(pw, ph))
    f = max(f, max(nx, ny) / max(1, int(max_mesh)))
    return max(1, math.ceil(f - 1e-9))


def _fill(annotate: bool) -> float:
    """Share of the panel's limiting side taken by the map in the top view."""
    return 0.66 if annotate else 1.0


#: In the annotated top view the map is raised by this share of the panel height, so that the
#: tick labels, the x-axis title and the caption below it do not overlap.
_TOP_RAISE = 0.04


def _top_scale(lx: float, ly: float, w: int, h: int, fill: float) -> float:
    """Parallel scale (half the visible height) that fits an lx × ly map in a w × h panel."""
    return max(ly, lx * h / w) / (2.0 * fill)


def auto_exaggeration(surface: Surface, relief: float = 0.1) -> float:
    """Vertical exaggeration that draws R_t as ``relief`` × the longer side, rounded to 1-2-5.

    Returns 1 when the surface is already that rough (dimensionless).
    """
    rt = surface.rt
    if not rt > 0:
        return 1.0
    v = relief * max(surface.lx, surface.ly) / rt * (1 + 1e-6)  # R_t rescaled to 10 µm → 10
    if v <= 1:
        return 1.0
    e = 10 ** math.floor(math.log10(v))
    return float(max(m * e for m in (1, 2, 5, 10) if m * e <= v))


# --- mesh and drawing ---------------------------------------------------------------------------


class _Scene:
    """The down-sampled mesh (one cell per block, x fastest) and the colours of its cells."""

    def __init__(self, surface: Surface, factor: int, ve: float):
        pv = _pyvista()
        f = factor
        hb = pool_blocks(surface.heights, f, "mean")  # (my, mx) block means (m)
        self.shape = hb.shape
        my, mx = hb.shape
        # corner heights: mean of the (up to four) blocks sharing the corner
        p = np.pad(hb, 1, mode="edge")
        corners = 0.25 * (p[:-1, :-1] + p[1:, :-1] + p[:-1, 1:] + p[1:, 1:])
        top = float(surface.heights.max())
        xe = np.minimum(np.arange(mx + 1) * f, surface.nx) * surface.dx * 1e6  # µm
        ye = np.minimum(np.arange(my + 1) * f, surface.ny) * surface.dy * 1e6
        gx, gy = np.meshgrid(xe, ye)  # (my+1, mx+1), x fastest after ravel
        gz = (corners - top) * 1e6 * ve  # µm, exaggerated, top at 0
        pts = np.column_stack([gx.ravel(), gy.ravel(), gz.ravel()])
        self.grid = pv.StructuredGrid()
        self.grid.points = pts
        self.grid.dimensions = (mx + 1, my + 1, 1)
        lo, hi = float(hb.min()), float(hb.max())
        t = (hb - lo) / (hi - lo) if hi > lo else np.full_like(hb, 0.5)
        g = np.rint(_NEUTRAL[0] + (_NEUTRAL[1] - _NEUTRAL[0]) * t).astype(np.uint8).ravel()
        self.neutral = np.repeat(g[:, None], 3, axis=1)
        from .plot import CONTACT_RGB

        self.red = np.asarray(CONTACT_RGB, dtype=np.uint8)

    def colours(self, weight: np.ndarray) -> np.ndarray:
        """Cell colours: a bool mask paints red; a float weight φ blends grey + φ·(red − grey)."""
        if weight.dtype == bool:
            c = self.neutral.copy()
            c[weight.ravel()] = self.red
            return c
        w = np.clip(weight.ravel().astype(np.float32), 0.0, 1.0)[:, None]
        c = self.neutral.astype(np.float32)
        c += w * (self.red.astype(np.float32) - c)
        return np.rint(c).astype(np.uint8)


def _font_file() -> str | None:
    """DejaVu Sans from matplotlib: VTK's built-in fonts lack ω and µ."""
    import os

    import matplotlib

    p = os.path.join(matplotlib.get_data_path(), "fonts", "ttf", "DejaVuSans.ttf")
    return p if os.path.exists(p) else None


def _text(pl, text: str, position, font_size: int, color: str = "black", name=None):
    return pl.add_text(
        text, position=position, font_size=font_size, color=color, font_file=_font_file(),
        name=name,
    )  # fmt: skip


class _Panel:
    """One off-screen plotter of panel size showing the scene; :meth:`frame` recolours it.

    Panels are rendered one at a time and tiled by NumPy: VTK draws 2-D axis labels (the mode
    that can show µ) in the wrong viewport when a plotter holds several.
    """

    def __init__(self, scene: _Scene, size, *, top_view, lighting, annotate, ve, caption=None):
        pv = _pyvista()
        self.scene, self.annotate = scene, annotate
        # text sizes scale with the panel (VTK sizes are in points at a fixed DPI)
        self.scale = max(0.6, min(1.5, min(size[0] / 520, size[1] / 440)))
        self.pl = pv.Plotter(off_screen=True, window_size=[int(size[0]), int(size[1])])
        pl = self.pl
        pl.set_background("white")
        if top_view:  # one sample per pixel: the picture is a map whose red pixels measure A_c
            pl.disable_anti_aliasing(all_renderers=True)
        self.mesh = scene.grid.copy(deep=False)
        self.mesh.cell_data["rgb"] = scene.neutral
        pl.add_mesh(
            self.mesh, scalars="rgb", rgb=True, preference="cell", lighting=lighting,
            show_scalar_bar=False,
        )  # fmt: skip
        if annotate:
            axes = pl.show_bounds(
                mesh=self.mesh, xtitle="x (µm)", ytitle="y (µm)", ztitle="z",
                show_zaxis=False, show_zlabels=False, font_size=round(12 * self.scale),
                color="black", bold=False, n_xlabels=3, n_ylabels=3, fmt="%.0f",
                location="outer" if top_view else "front", use_3d_text=False, use_2d=True,
            )  # fmt: skip
            font = _font_file()
            if font is not None:
                from vtkmodules.vtkCommonCore import VTK_FONT_FILE

                for i in range(3):
                    for prop in (axes.GetTitleTextProperty(i), axes.GetLabelTextProperty(i)):
                        prop.SetFontFamily(VTK_FONT_FILE)
                        prop.SetFontFile(font)
            if caption:
                self.caption = _text(pl, caption, "lower_left", round(8 * self.scale), "dimgray")
        _camera(pl, top_view, size, fill=_fill(annotate), raise_=_TOP_RAISE if annotate else 0.0)

    def frame(self, mask: np.ndarray, title: str | None, caption: bool = True) -> np.ndarray:
        self.mesh.cell_data["rgb"] = self.scene.colours(mask)
        if self.annotate:
            if title:
                _text(self.pl, title, "upper_edge", round(10 * self.scale), name="title")
            if hasattr(self, "caption"):
                self.caption.SetVisibility(caption)
        self.pl.render()
        return np.asarray(self.pl.screenshot(return_img=True))[..., :3].copy()

    def close(self) -> None:
        self.pl.close()


def _camera(pl, top_view: bool, size, fill: float, raise_: float = 0.0) -> None:
    if top_view:
        # looking down −z, x to the right, y up; the surface spans ``fill`` of the limiting
        # side, so without annotations a k·nx × k·ny window shows each cell as k×k pixels
        pl.view_xy()
        pl.enable_parallel_projection()
        pl.reset_camera()
        b = pl.bounds
        scale = _top_scale(b[1] - b[0], b[3] - b[2], size[0], size[1], fill)
        pl.camera.parallel_scale = scale
        if raise_:  # look at a point below the centre: the map moves up by raise_ × height
            dy = 2.0 * scale * raise_
            fx, fy, fz = pl.camera.focal_point
            px, py, pz = pl.camera.position
            pl.camera.focal_point = (fx, fy - dy, fz)
            pl.camera.position = (px, py - dy, pz)
        return
    # from the −y side, 35° above the horizon, turned so that x runs along the front edge
    b = np.asarray(pl.bounds, dtype=float)
    c = 0.5 * (b[0::2] + b[1::2])
    span = max(b[1] - b[0], b[3] - b[2])
    d = np.array([0.45, -1.0, 0.85])
    pl.camera.focal_point = tuple(c)
    pl.camera.position = tuple(c + 2.2 * span * d / np.linalg.norm(d))
    pl.camera.up = (0.0, 0.0, 1.0)
    pl.reset_camera()
    pl.camera.zoom(1.1)


def _tile(images: list[np.ndarray], nrows: int, ncols: int, size) -> np.ndarray:
    w, h = size
    out = np.full((h, w, 3), 255, dtype=np.uint8)
    for i, im in enumerate(images):
        r, c = divmod(i, ncols)
        y0, x0 = r * (h // nrows), c * (w // ncols)
        out[y0 : y0 + im.shape[0], x0 : x0 + im.shape[1]] = im
    return out


def _draw_text(img: np.ndarray, text: str, xy, size: int, width: int) -> np.ndarray:
    """Write ``text`` onto ``img`` with Pillow, wrapped to ``width`` pixels (spare panel)."""
    from PIL import Image, ImageDraw, ImageFont

    im = Image.fromarray(img)
    font = _font_file()
    f = ImageFont.truetype(font, size) if font else ImageFont.load_default()
    lines: list[str] = []
    for word in text.split():
        if lines and f.getlength(lines[-1] + " " + word) <= width:
            lines[-1] += " " + word
        else:
            lines.append(word)
    ImageDraw.Draw(im).multiline_text(xy, "\n".join(lines), fill=(0, 0, 0), font=f, spacing=5)
    return np.asarray(im).copy()


def _layout(n: int, ncols: int | None) -> tuple[int, int]:
    if ncols is None:
        ncols = n if n <= 3 else 3
    ncols = max(1, min(int(ncols), n))
    return -(-n // ncols), ncols


def _caption(
    surface: Surface, factor: int, shape: tuple[int, int], ve: float, pooling: str = "area"
) -> str:
    s = (
        f"{surface.nx}×{surface.ny} px, {surface.lx * 1e6:.4g}×{surface.ly * 1e6:.4g} µm, "
        f"Rt = {surface.rt * 1e6:.3g} µm; heights ×{ve:g}"
    )
    if factor > 1:
        s += f"; mesh down-sampled ×{factor} ({shape[1]}×{shape[0]} blocks): "
        if pooling == "any":
            s += (
                "max-pooling shows every contact spot (a block is red when any of its pixels "
                "touches), so red overstates Ac/A"
            )
        else:
            s += "a block's share of red is the fraction of its pixels in contact (red = Ac/A)"
    return s + "; red: contact"


def _wrap(text: str, width: int) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width))


def _save_png(img: np.ndarray, path: Path, result_meta: str, caption: str) -> None:
    from PIL import Image
    from PIL.PngImagePlugin import PngInfo

    info = PngInfo()
    info.add_text("Description", caption)
    info.add_text("Software", "warptrunc.render")
    info.add_text("warptrunc", result_meta)
    path.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(img).save(path, pnginfo=info, optimize=True)


def _depth_title(d: float, rt: float, frac: float) -> str:
    return f"ω = {100 * d / rt:.3g} % Rt = {d * 1e6:.3g} µm\ncontact Ac/A = {100 * frac:.3g} %"


def render_truncation(
    surface: Surface,
    path: str | Path | None = None,
    *,
    depth_fractions: Sequence[float] = DEFAULT_DEPTH_FRACTIONS,
    depths: Sequence[float] | None = None,
    top_view: bool = False,
    window_size: tuple[int, int] | None = None,
    ncols: int | None = None,
    vertical_exaggeration: float | None = None,
    downsample: int | None = None,
    pooling: str = "area",
    max_mesh: int = MAX_MESH,
    lighting: bool | None = None,
    annotate: bool = True,
    device: wp.DeviceLike = None,
) -> Rendering:
    """Render truncation sections: the surface with its contact set at each depth in red.

    Parameters
    ----------
    surface : Surface
        The height map (m).
    path : path, optional
        Save the picture as PNG here (with the caption and the result's metadata in PNG text
        chunks).
    depth_fractions : sequence of float
        Depths as fractions of R_t, in (0, 1], one panel each (dimensionless); the paper's
        Fig. 7 uses 0.1–0.5.
    depths : sequence of float, optional
        Depths ω in (0, R_t] (m); override ``depth_fractions``.
    top_view : bool
        View from above with an orthographic (parallel) projection, x to the right and y up
        (as ``imshow(z, origin="lower")``); otherwise an oblique view from the −y side,
        35° above the horizon.
    window_size : (int, int), optional
        Picture size (width, height) in pixels. Default: 520×440 per panel.
    ncols : int, optional
        Panels per row (default: up to 3).
    vertical_exaggeration : float, optional
        Factor on heights (dimensionless); default :func:`auto_exaggeration`.
    downsample : int, optional
        Block side f of the drawn mesh. Default: the smallest f that gives every block at
        least one screen pixel (over the map's footprint in the top view, over the panel's
        shorter side in the oblique view) and at most ``max_mesh`` blocks per side.
    pooling : {"area", "any"}
        How a block of f×f pixels is coloured when f > 1. ``"area"`` (default): its share of
        red is the fraction of its pixels in contact, so the red in the picture measures A_c/A.
        ``"any"``: max-pooling, red when any of its pixels touches; shows every contact spot
        but overstates the area. The caption says which.
    max_mesh : int
        Largest number of blocks per side when ``downsample`` is not given.
    lighting : bool, optional
        Shade the surface by VTK lights. Default: on in the oblique view, off in the top
        view (flat colours, so red pixels measure the contact area).
    annotate : bool
        Draw titles, axes in µm and the caption.
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
    >>> from warptrunc.render import render_truncation
    >>> s = wm_surface(2.5, 100e-6, n=2048, Rt=10e-6, seed=1)
    >>> r = render_truncation(s, "truncation.png")  # doctest: +SKIP
    >>> r.downsample, r.area_fraction  # doctest: +SKIP
    """
    _pyvista()
    depth = check_depths(surface, depth_fractions, depths, upto_rt=True)
    check_pooling(pooling)
    nrows, ncols = _layout(depth.size, ncols)
    if window_size is None:
        window_size = (PANEL_SIZE[0] * ncols, PANEL_SIZE[1] * nrows)
    w, h = (int(v) for v in window_size)
    if w < 16 or h < 16:
        raise ValueError(f"window_size must be at least 16×16 pixels, got {window_size!r}")
    if downsample is None:
        downsample = _auto_factor(
            surface, (w // ncols, h // nrows), top_view=top_view, annotate=annotate,
            max_mesh=max_mesh,
        )  # fmt: skip
    f = int(downsample)
    if f < 1 or f != downsample:
        raise ValueError(f"downsample must be an integer ≥ 1, got {downsample!r}")
    ve = auto_exaggeration(surface) if vertical_exaggeration is None else vertical_exaggeration
    if not (ve > 0 and math.isfinite(ve)):
        raise ValueError(f"vertical_exaggeration must be > 0, got {vertical_exaggeration!r}")
    ve = float(ve)
    if lighting is None:
        lighting = not top_view

    blocks, frac = block_contact(surface, depth, f, pooling, device)
    scene = _Scene(surface, f, ve)
    caption = _caption(surface, f, scene.shape, ve, pooling)
    rt = surface.rt
    pw, ph = w // ncols, h // nrows
    spare = nrows * ncols > depth.size
    with _vtk_quiet():
        panel = _Panel(
            scene, (pw, ph), top_view=top_view, lighting=lighting, annotate=annotate, ve=ve,
            caption=None if spare else _wrap(caption, max(30, pw // 7)),
        )  # fmt: skip
        try:
            images = [
                panel.frame(blocks[i], _depth_title(depth[i], rt, frac[i]), caption=i == 0)
                for i in range(depth.size)
            ]
        finally:
            panel.close()
    img = _tile(images, nrows, ncols, (w, h))
    if annotate and spare:
        r, c = divmod(depth.size, ncols)
        fs = max(10, min(16, pw // 34))
        img = _draw_text(img, caption, (c * pw + 12, r * ph + 14), fs, pw - 24)
    result = Rendering(
        path=None if path is None else Path(path),
        image=img,
        depth=depth,
        depth_fraction=depth / rt,
        area_fraction=np.asarray(frac, dtype=np.float64),
        downsample=f,
        pooling=pooling,
        mesh_shape=scene.shape,
        surface_shape=(surface.ny, surface.nx),
        vertical_exaggeration=ve,
        top_view=bool(top_view),
        caption=caption,
    )
    if path is not None:
        _save_png(img, Path(path), result._metadata(), caption)
    return result


def animate_truncation(
    surface: Surface,
    path: str | Path,
    *,
    max_depth_fraction: float = 0.5,
    n_frames: int = 26,
    fps: float = 8.0,
    top_view: bool = False,
    window_size: tuple[int, int] = (640, 520),
    vertical_exaggeration: float | None = None,
    downsample: int | None = None,
    pooling: str = "area",
    max_mesh: int = MAX_MESH,
    device: wp.DeviceLike = None,
) -> Rendering:
    """Animate the truncation deepening from ω = 0 to ``max_depth_fraction``·R_t.

    Parameters
    ----------
    surface : Surface
        The height map (m).
    path : path
        Output file: ``.gif`` (written with Pillow) or ``.mp4`` (needs
        ``pip install imageio imageio-ffmpeg``).
    max_depth_fraction : float
        Last depth as a fraction of R_t, in (0, 1] (dimensionless).
    n_frames : int
        Number of frames (≥ 2); depths are equally spaced from 0.
    fps : float
        Frames per second.
    top_view, window_size, vertical_exaggeration, downsample, pooling, max_mesh, device
        As in :func:`render_truncation`.

    Returns
    -------
    Rendering
        The last frame, and one depth per frame.
    """
    _pyvista()
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
    n = int(n_frames)
    if n < 2 or n != n_frames:
        raise ValueError(f"n_frames must be an integer ≥ 2, got {n_frames!r}")
    if not 0 < max_depth_fraction <= 1:
        raise ValueError(f"max_depth_fraction must be in (0, 1], got {max_depth_fraction!r}")
    if not fps > 0:
        raise ValueError(f"fps must be > 0, got {fps!r}")
    w, h = (int(v) for v in window_size)
    if downsample is None:
        downsample = _auto_factor(
            surface, (w, h), top_view=top_view, annotate=True, max_mesh=max_mesh
        )
    f = int(downsample)
    ve = (
        auto_exaggeration(surface)
        if vertical_exaggeration is None
        else float(vertical_exaggeration)
    )
    depth = np.linspace(0.0, max_depth_fraction, n) * surface.rt
    blocks, frac = block_contact(surface, depth, f, check_pooling(pooling), device)
    scene = _Scene(surface, f, ve)
    caption = _caption(surface, f, scene.shape, ve, pooling)
    rt = surface.rt
    with _vtk_quiet():
        panel = _Panel(
            scene, (w, h), top_view=top_view, lighting=not top_view, annotate=True, ve=ve,
            caption=_wrap(caption, max(30, w // 7)),
        )  # fmt: skip
        try:
            frames = [
                panel.frame(blocks[i], _depth_title(depth[i], rt, frac[i])) for i in range(n)
            ]
        finally:
            panel.close()
    path.parent.mkdir(parents=True, exist_ok=True)
    if suffix == ".gif":
        from PIL import Image

        ims = [Image.fromarray(fr) for fr in frames]
        ims[0].save(
            path, save_all=True, append_images=ims[1:], duration=round(1000 / fps), loop=0,
            comment=caption.encode(),
        )  # fmt: skip
    else:
        writer = imageio.get_writer(path, fps=fps)
        try:
            for fr in frames:
                writer.append_data(fr)
        finally:
            writer.close()
    return Rendering(
        path=path,
        image=frames[-1],
        depth=depth,
        depth_fraction=depth / rt,
        area_fraction=np.asarray(frac, dtype=np.float64),
        downsample=f,
        pooling=pooling,
        mesh_shape=scene.shape,
        surface_shape=(surface.ny, surface.nx),
        vertical_exaggeration=ve,
        top_view=bool(top_view),
        caption=caption,
    )
