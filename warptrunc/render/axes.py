# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Axes drawn over a rendered panel with Pillow: x and y ticks in µm outside the map, and a
height scale (a vertical bar of a round height in the oblique view, a grey ramp in the top
view).

VTK's own axes put the y title over the surface and let the labels of two axes collide at the
corner they share; here every label is placed outward from its edge (away from the map's
projected centre) and a label that would overlap one already placed is left out.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np


def font_file() -> str | None:
    """DejaVu Sans from matplotlib: VTK's built-in fonts lack ω and µ.

    Returns
    -------
    str or None
        The font file's path, or None when matplotlib does not ship it.
    """
    import matplotlib

    p = os.path.join(matplotlib.get_data_path(), "fonts", "ttf", "DejaVuSans.ttf")
    return p if os.path.exists(p) else None


__all__ = ["draw", "layout"]

_TICK = 6  # tick mark length (px at scale 1)
_GAP = 4  # between a tick and its label (px at scale 1)


def nice_step(length: float, max_ticks: int = 4) -> float:
    """The smallest 1-2-5 step that divides ``length`` into at most ``max_ticks`` intervals.

    Parameters
    ----------
    length : float
        Axis length (any unit), > 0.
    max_ticks : int
        Most intervals.

    Returns
    -------
    float
        Step in the unit of ``length``.
    """
    raw = length / max_ticks
    e = 10.0 ** math.floor(math.log10(raw))
    return next(m * e for m in (1, 2, 5, 10) if m * e >= raw * (1 - 1e-9))


def nice_height(Rt: float) -> float:
    """The largest 1-2-5 height not above ``Rt``: the height the oblique view's bar shows.

    Parameters
    ----------
    Rt : float
        Peak-to-valley height R_t of the map (m), > 0.

    Returns
    -------
    float
        Height (m).
    """
    e = 10.0 ** math.floor(math.log10(Rt))
    return max(m * e for m in (1, 2, 5, 10) if m * e <= Rt * (1 + 1e-6))  # float32 R_t


@dataclass
class Overlay:
    """What :func:`layout` places: lines and texts in image pixels, drawn on every frame."""

    lines: list = field(default_factory=list)
    """``((x0, y0, x1, y1), width)`` of each black line (px)."""
    texts: list = field(default_factory=list)
    """``((x, y), text, anchor, size)`` of each text (Pillow anchor; size in px)."""
    ramp: tuple | None = None
    """``(x0, y0, x1, y1, grey_low, grey_high)`` of the top view's height ramp, or None."""
    boxes: list = field(default_factory=list)
    """``(left, top, right, bottom)`` of each text placed so far (px)."""


def _display(pl, pts: np.ndarray, height: int) -> np.ndarray:
    """World points (µm) → image pixels (x right, y down)."""
    ren = pl.renderer
    out = np.empty((len(pts), 2))
    for i, p in enumerate(pts):
        ren.SetWorldPoint(float(p[0]), float(p[1]), float(p[2]), 1.0)
        ren.WorldToDisplay()
        x, y, _ = ren.GetDisplayPoint()
        out[i] = (x, height - y)
    return out


def _font(size: int):
    from PIL import ImageFont

    f = font_file()
    return ImageFont.truetype(f, size) if f else ImageFont.load_default()


def _box(xy, text: str, anchor: str, size: int):
    from PIL import Image, ImageDraw

    d = ImageDraw.Draw(Image.new("RGB", (1, 1)))
    return d.multiline_textbbox(xy, text, font=_font(size), anchor=anchor)


def _overlaps(a, b, pad: int = 2) -> bool:
    return not (a[2] + pad < b[0] or b[2] + pad < a[0] or a[3] + pad < b[1] or b[3] + pad < a[1])


def _anchor(n: np.ndarray) -> str:
    """Pillow anchor of a label placed along the outward direction ``n`` from its point."""
    if abs(n[0]) > abs(n[1]):
        return "lm" if n[0] > 0 else "rm"
    return "ma" if n[1] > 0 else "md"  # ascender / descender: Pillow's multiline anchors


def _place(ov: Overlay, xy, text: str, anchor: str, size: int, force: bool = False) -> bool:
    box = _box(xy, text, anchor, size)
    if not force and any(_overlaps(box, b) for b in ov.boxes):
        return False
    ov.boxes.append(box)
    ov.texts.append((tuple(xy), text, anchor, size))
    return True


def _num(v: float) -> str:
    return f"{v:g}".replace("-", "−")


def _edge(ov, pl, h, centre, a, b, values, title, scale, size, skip_first=False):
    """Ticks at world points a + t·(b − a) for the tick values (µm along the edge), labels and
    the title outward from the edge; ``skip_first``: no label at the corner the other axis
    labels."""
    L = float(np.linalg.norm(np.asarray(b) - np.asarray(a)))
    pts = [np.asarray(a) + (v / L) * (np.asarray(b) - np.asarray(a)) for v in values]
    scr = _display(pl, np.array([a, b, *pts]), h)
    p0, p1, ticks = scr[0], scr[1], scr[2:]
    d = (p1 - p0) / max(np.linalg.norm(p1 - p0), 1e-9)
    n = np.array([-d[1], d[0]])
    mid = 0.5 * (p0 + p1)
    if np.dot(n, mid - centre) < 0:
        n = -n
    anchor = _anchor(n)
    ov.lines.append(((*p0, *p1), 1))
    reach = 0.0
    for i, (v, t) in enumerate(zip(values, ticks, strict=True)):
        ov.lines.append(((*t, *(t + _TICK * scale * n)), 1))
        xy = t + (_TICK + _GAP) * scale * n
        if not (skip_first and i == 0) and _place(ov, xy, _num(v), anchor, size):
            bx = ov.boxes[-1]
            reach = max(reach, abs(np.dot([bx[2] - bx[0], bx[3] - bx[1]], n)))
    base = (_TICK + 3 * _GAP) * scale + reach
    for k in range(5):  # the title outward of the labels; further out while it hits one
        if _place(ov, mid + (base + k * 0.6 * size) * n, title, anchor, size, force=k == 4):
            break


def layout(pl, scene, size, *, top_view: bool, scale: float) -> Overlay:
    """Axes and height scale of one panel, from the plotter's camera (after a render).

    Parameters
    ----------
    pl : pyvista.Plotter
        The panel's plotter, rendered once (its camera set).
    scene : Scene
        The mesh: extent (µm), its lowest drawn height, the grey levels and height range.
    size : (int, int)
        Panel (width, height) in pixels.
    top_view : bool
        Orthographic view from above (a grey ramp) or oblique view (a vertical bar).
    scale : float
        Text scale of the panel (1 at 520×440 px).

    Returns
    -------
    Overlay
        Lines, texts and the ramp, in image pixels.
    """
    w, h = int(size[0]), int(size[1])
    lx, ly = scene.extent_um
    z0 = 0.0 if top_view else scene.z_low_um
    ov = Overlay()
    corners = np.array([[0, 0, z0], [lx, 0, z0], [lx, ly, z0], [0, ly, z0]], dtype=float)
    centre = _display(pl, corners, h).mean(axis=0)
    size_px = max(9, round(15 * scale))
    xs = np.arange(0.0, lx * (1 + 1e-9), nice_step(lx))
    ys = np.arange(0.0, ly * (1 + 1e-9), nice_step(ly))
    _edge(ov, pl, h, centre, [0, 0, z0], [lx, 0, z0], xs, "x (µm)", scale, size_px)
    yx = 0.0 if top_view else lx  # the y axis on the left (top view) or the right (oblique)
    _edge(
        ov, pl, h, centre, [yx, 0, z0], [yx, ly, z0], ys, "y (µm)", scale, size_px, skip_first=True
    )  # y = 0 is a corner of the x axis too
    if top_view:
        right = _display(pl, np.array([[lx, 0, 0], [lx, ly, 0]]), h)
        x0 = right[:, 0].max() + 0.25 * (w - right[:, 0].max())
        yb, yt = right[:, 1].max(), right[:, 1].min()
        mid, half = 0.5 * (yb + yt), 0.22 * (yb - yt)  # under half the panel's height
        bar = (x0, mid - half, x0 + 10 * scale, mid + half)
        ov.ramp = (*bar, *scene.grey_range)
        lo, hi = scene.height_range_um
        ov.lines.append(((bar[0], bar[1], bar[2], bar[1]), 1))
        _place(
            ov, (bar[2] + 4 * scale, bar[1]), _num(float(f"{hi:.3g}")), "lm", size_px, force=True
        )
        _place(
            ov, (bar[2] + 4 * scale, bar[3]), _num(float(f"{lo:.3g}")), "lm", size_px, force=True
        )
        _place(
            ov, (0.5 * (bar[0] + bar[2]), bar[1] - 6 * scale), "z (µm)", "md", size_px, force=True
        )
    else:
        hz = nice_height(scene.Rt)
        top = _display(pl, np.array([[0, ly, 0.0], [0, ly, hz * 1e6 * scene.ve]]), h)
        (bx, by0), (_, by1) = top
        ov.lines.append(((bx, by0, bx, by1), max(2, round(3 * scale))))
        for y in (by0, by1):
            ov.lines.append(((bx - 4 * scale, y, bx + 4 * scale, y), max(1, round(2 * scale))))
        _place(
            ov,
            (bx - 8 * scale, 0.5 * (by0 + by1)),
            f"height\n{hz * 1e6:g} µm",
            "rm",
            size_px,
            force=True,
        )
    return ov


def draw(img: np.ndarray, ov: Overlay) -> np.ndarray:
    """``img`` with the overlay drawn (black lines and text, the grey ramp).

    Parameters
    ----------
    img : (h, w, 3) uint8 ndarray
        The panel.
    ov : Overlay
        From :func:`layout`.

    Returns
    -------
    (h, w, 3) uint8 ndarray
        A new image.
    """
    from PIL import Image, ImageDraw

    im = Image.fromarray(img)
    d = ImageDraw.Draw(im)
    if ov.ramp is not None:
        x0, y0, x1, y1, g_lo, g_hi = ov.ramp
        n = max(2, round(y1 - y0))
        for i in range(n):  # top: the highest grey, bottom: the lowest
            g = round(g_hi + (g_lo - g_hi) * i / (n - 1))
            d.line([(x0, y0 + i), (x1, y0 + i)], fill=(g, g, g))
        d.rectangle([x0, y0, x1, y1], outline=(0, 0, 0))
    for (x0, y0, x1, y1), width in ov.lines:
        d.line([(x0, y0), (x1, y1)], fill=(0, 0, 0), width=width)
    for xy, text, anchor, size in ov.texts:
        d.multiline_text(
            xy,
            text,
            fill=(0, 0, 0),
            font=_font(size),
            anchor=anchor,
            align="right" if anchor.startswith("r") else "left",
        )
    return np.asarray(im).copy()
