# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The pyvista side of the pictures: the down-sampled mesh and its colours, one off-screen panel
with its camera, the down-sampling factor and the vertical exaggeration."""

from __future__ import annotations

import math
from contextlib import contextmanager

import numpy as np

from .._support.device import is_verbose
from ..plot import CONTACT_RGB
from ..plot.pooling import pool_blocks
from ..surface import Surface
from .axes import font_file

_NEUTRAL = (95, 225)  # grey levels of the lowest and the highest non-contact cells


def import_pyvista():
    try:
        import pyvista as pv
    except ImportError as exc:  # pragma: no cover - exercised where pyvista is absent
        raise ImportError(
            "warptrunc.render needs pyvista (and VTK) for 3-D pictures: pip install pyvista"
        ) from exc
    return pv


@contextmanager
def vtk_quiet():
    """Hide VTK's warnings while rendering (e.g. "bad X server connection" on headless
    machines, where off-screen rendering works regardless), unless verbose
    (:func:`warptrunc._support.device.set_verbose`, ``warptrunc --verbose``, ``$WARPTRUNC_VERBOSE``).
    The previous global setting of VTK is restored afterwards."""

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


# --- down-sampling ------------------------------------------------------------------------------


def auto_factor(
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


#: In the annotated top view the map is raised by this share of the panel height, leaving room
#: below it for the tick labels and the x-axis title (the caption is outside the panels).
_TOP_RAISE = 0.02


def _top_scale(lx: float, ly: float, w: int, h: int, fill: float) -> float:
    """Parallel scale (half the visible height) that fits an lx × ly map in a w × h panel."""
    return max(ly, lx * h / w) / (2.0 * fill)


def auto_exaggeration(surface: Surface, relief: float = 0.1) -> float:
    """Vertical exaggeration that draws R_t as ``relief`` × the longer side, rounded to 1-2-5.

    Parameters
    ----------
    surface : Surface
        Height map; its R_t and side lengths Lx, Ly (m) are used.
    relief : float
        Target drawn height of R_t as a fraction of max(Lx, Ly) (dimensionless).

    Returns
    -------
    float
        The largest 1-2-5 value (1, 2, 5, 10, 20, ...) not above relief·max(Lx, Ly)/R_t
        (dimensionless); 1.0 when R_t is 0 or the surface is already that rough.
    """
    Rt = surface.Rt
    if not Rt > 0:
        return 1.0
    v = relief * max(surface.lx, surface.ly) / Rt * (1 + 1e-6)  # R_t rescaled to 10 µm → 10
    if v <= 1:
        return 1.0
    e = 10 ** math.floor(math.log10(v))
    return float(max(m * e for m in (1, 2, 5, 10) if m * e <= v))


# --- mesh and drawing ---------------------------------------------------------------------------


class Scene:
    """The down-sampled mesh (one cell per block, x fastest) and the colours of its cells."""

    def __init__(self, surface: Surface, factor: int, ve: float):
        pv = import_pyvista()
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
        self.extent_um = (float(xe[-1]), float(ye[-1]))
        self.z_low_um = float(gz.min())
        self.Rt, self.ve = surface.Rt, ve
        pts = np.column_stack([gx.ravel(), gy.ravel(), gz.ravel()])
        self.grid = pv.StructuredGrid()
        self.grid.points = pts
        self.grid.dimensions = (mx + 1, my + 1, 1)
        lo, hi = float(hb.min()), float(hb.max())
        self.height_range_um = ((lo - top) * 1e6, (hi - top) * 1e6)  # block means, top at 0
        self.grey_range = _NEUTRAL if hi > lo else (160, 160)
        t = (hb - lo) / (hi - lo) if hi > lo else np.full_like(hb, 0.5)
        g = np.rint(_NEUTRAL[0] + (_NEUTRAL[1] - _NEUTRAL[0]) * t).astype(np.uint8).ravel()
        self.neutral = np.repeat(g[:, None], 3, axis=1)

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


def _text(pl, text: str, position, font_size: int, color: str = "black", name=None):
    return pl.add_text(
        text,
        position=position,
        font_size=font_size,
        color=color,
        font_file=font_file(),
        name=name,
    )


class Panel:
    """One off-screen plotter of panel size showing the scene; :meth:`frame` recolours it.

    Panels are rendered one at a time and tiled by NumPy: VTK draws 2-D axis labels (the mode
    that can show µ) in the wrong viewport when a plotter holds several.
    """

    def __init__(self, scene: Scene, size, *, top_view, lighting, annotate, ve):
        pv = import_pyvista()
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
            self.mesh,
            scalars="rgb",
            rgb=True,
            preference="cell",
            lighting=lighting,
            show_scalar_bar=False,
        )
        _camera(pl, top_view, size, fill=_fill(annotate), raise_=_TOP_RAISE if annotate else 0.0)
        self.size, self.top_view, self.overlay = size, top_view, None

    def frame(self, mask: np.ndarray, title: str | None) -> np.ndarray:
        self.mesh.cell_data["rgb"] = self.scene.colours(mask)
        if self.annotate and title:
            _text(self.pl, title, "upper_edge", round(10 * self.scale), name="title")
        self.pl.render()
        img = np.asarray(self.pl.screenshot(return_img=True))[..., :3].copy()
        if not self.annotate:
            return img
        if self.overlay is None:  # axes and height scale: the same on every frame
            from .axes import layout

            self.overlay = layout(
                self.pl, self.scene, self.size, top_view=self.top_view, scale=self.scale
            )
        from .axes import draw

        return draw(img, self.overlay)

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
