# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Image assembly with NumPy and Pillow: tiling panels, text, captions, PNG metadata."""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np

from ..surface import Surface
from .scene import font_file


def tile(images: list[np.ndarray], nrows: int, ncols: int, size) -> np.ndarray:
    w, h = size
    out = np.full((h, w, 3), 255, dtype=np.uint8)
    for i, im in enumerate(images):
        r, c = divmod(i, ncols)
        y0, x0 = r * (h // nrows), c * (w // ncols)
        out[y0 : y0 + im.shape[0], x0 : x0 + im.shape[1]] = im
    return out


def draw_text(img: np.ndarray, text: str, xy, size: int, width: int) -> np.ndarray:
    """Write ``text`` onto ``img`` with Pillow, wrapped to ``width`` pixels (spare panel)."""
    from PIL import Image, ImageDraw, ImageFont

    im = Image.fromarray(img)
    font = font_file()
    f = ImageFont.truetype(font, size) if font else ImageFont.load_default()
    lines: list[str] = []
    for word in text.split():
        if lines and f.getlength(lines[-1] + " " + word) <= width:
            lines[-1] += " " + word
        else:
            lines.append(word)
    ImageDraw.Draw(im).multiline_text(xy, "\n".join(lines), fill=(0, 0, 0), font=f, spacing=5)
    return np.asarray(im).copy()


def grid_layout(n: int, ncols: int | None) -> tuple[int, int]:
    if ncols is None:
        ncols = n if n <= 3 else 3
    ncols = max(1, min(int(ncols), n))
    return -(-n // ncols), ncols


def caption_text(
    surface: Surface, factor: int, shape: tuple[int, int], ve: float, pooling: str = "area"
) -> str:
    s = (
        f"{surface.nx}×{surface.ny} px, {surface.lx * 1e6:.4g}×{surface.ly * 1e6:.4g} µm, "
        f"Rt = {surface.Rt * 1e6:.3g} µm; heights ×{ve:g}"
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


def wrap_text(text: str, width: int) -> str:
    return "\n".join(textwrap.wrap(text, width))


def save_png(img: np.ndarray, path: Path, result_meta: str, caption: str) -> None:
    from PIL import Image
    from PIL.PngImagePlugin import PngInfo

    info = PngInfo()
    info.add_text("Description", caption)
    info.add_text("Software", "warptrunc.render")
    info.add_text("warptrunc", result_meta)
    path.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(img).save(path, pnginfo=info, optimize=True)


def depth_title(d: float, Rt: float, frac: float) -> str:
    return f"ω = {100 * d / Rt:.3g} % Rt = {d * 1e6:.3g} µm\ncontact Ac/A = {100 * frac:.3g} %"
