# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Image assembly with NumPy and Pillow: tiling panels, text, captions, PNG metadata."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..surface import Surface
from .axes import font_file


def tile(images: list[np.ndarray], nrows: int, ncols: int, size) -> np.ndarray:
    w, h = size
    out = np.full((h, w, 3), 255, dtype=np.uint8)
    for i, im in enumerate(images):
        r, c = divmod(i, ncols)
        y0, x0 = r * (h // nrows), c * (w // ncols)
        out[y0 : y0 + im.shape[0], x0 : x0 + im.shape[1]] = im
    return out


def _font(size: int):
    from PIL import ImageFont

    font = font_file()
    return ImageFont.truetype(font, size) if font else ImageFont.load_default()


def text_lines(text: str, size: int, width: int) -> list[str]:
    """``text`` wrapped at blanks to lines of at most ``width`` pixels in the font of ``size``."""
    f = _font(size)
    lines: list[str] = []
    for word in text.split():
        if lines and f.getlength(lines[-1] + " " + word) <= width:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return lines


def draw_text(img: np.ndarray, text: str, xy, size: int, width: int, fill=(0, 0, 0)) -> np.ndarray:
    """Write ``text`` onto ``img`` with Pillow, wrapped to ``width`` pixels."""
    from PIL import Image, ImageDraw

    im = Image.fromarray(img)
    ImageDraw.Draw(im).multiline_text(
        xy, "\n".join(text_lines(text, size, width)), fill=fill, font=_font(size), spacing=5
    )
    return np.asarray(im).copy()


def caption_strip(text: str, width: int) -> tuple[int, int]:
    """(height, font size) in pixels of a strip that holds ``text`` across ``width`` pixels,
    below the panels of a picture without a spare panel."""
    size = max(10, min(14, width // 60))
    return len(text_lines(text, size, width - 24)) * (size + 5) + 10, size


def with_caption(img: np.ndarray, text: str, strip: int, size: int) -> np.ndarray:
    """``img`` with a white strip of ``strip`` rows below it holding ``text`` (dark grey)."""
    band = np.full((strip, img.shape[1], 3), 255, dtype=np.uint8)
    band = draw_text(band, text, (12, 5), size, img.shape[1] - 24, fill=(80, 80, 80))
    return np.vstack([img, band])


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
        f"Rt = {surface.Rt * 1e6:.3g} µm; heights ×{ve:g}; red: contact"
    )
    if factor > 1:
        s += f"; mesh down-sampled ×{factor} ({shape[1]}×{shape[0]} blocks), "
        if pooling == "any":
            s += "by max-pooling: a block is red when any of its pixels touches (overstates Ac/A)"
        else:
            s += "each block as red as the fraction of its pixels in contact"
    return s


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
