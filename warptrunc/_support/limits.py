# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Size limits of Warp arrays and launches, and the row bands that keep every launch inside them.

What is 32-bit in Warp 1.19 (read from its source: ``warp/_src/types.py``,
``warp/_src/context.py``, ``warp/_src/codegen.py``, ``warp/native/array.h``,
``warp/native/builtin.h``, ``warp/native/tile.h``):

- **Per dimension, array shapes**: ``check_array_shape`` (types.py) refuses any dimension
  ≥ 2³¹ ("Array shapes must not exceed the maximum representable value of a signed 32-bit
  integer"); the native ``shape_t`` holds ``int dims[4]``. A *2-D* 65536 × 65536 float32 map
  (2³² elements, 17 GB) is therefore a valid Warp array; its *flattened* 1-D view is not.
  This is what failed at 46400² (2.15·10⁹ > 2³¹ − 1): ``z.flatten()`` in the extremes pass.
- **Strides**: ``array_t::strides`` are ``int`` *bytes* per dimension, so one row of a 2-D
  float32 array may hold at most 2²⁹ values (never reached: a side is ≤ 2²⁰ pixels here).
- **Element addresses are 64-bit**: ``byte_offset(arr, i, j)`` multiplies the int index by a
  ``size_t`` stride, so indexing ``z[iy, ix]`` is correct past 2 GiB; tile loads/stores keep
  the base offset in ``int64_t`` (tile.h: "cumulative bytes; can exceed 2 GiB").
- **wp.tid()**: each coordinate is a signed 32-bit ``int``; a launch extent per dimension may be
  at most 2³¹ (``_TID_MAX_EXTENT`` in codegen.py, checked in ``_validate_kernel_tid_extents``).
- **Launch size in total is 64-bit**: ``launch_bounds_t::size`` is ``size_t`` and the CUDA
  grid-stride loop runs a ``size_t _idx``; a 2-D launch of 65536 × 65536 threads is valid.

So no kernel here needs an int64 flat index as long as (a) 2-D maps are indexed as
``z[iy, ix]`` and (b) every *1-D* (flattened) launch covers fewer than 2³¹ elements. The only
kernels that form flat indices ``iy·nx + ix`` in int32 are the island labelling and Euler
kernels (``kernels/label.py``, ``islands.py``, ``euler.py``), all behind the labelling limit
below. The drivers
split a map into **row bands** (whole rows; a contiguous slice ``z[r0:r1]`` flattened is a
valid 1-D view) of at most :func:`band_pixel_limit` pixels, launch the flat kernels once per
band, and combine the partial results on the host in Python integers (int64 histograms; global
row offsets are Python ints passed as kernel arguments only where a kernel needs them, and a
row index stays below 2²⁰). The same bands drive the streamed path (``warptrunc.truncation.stream``),
where a band is generated, reduced and dropped.

The band limit is 2³⁰ pixels by default (4 GiB of float32 per band, well inside the 32-bit
limits). ``force_band_pixels(n)`` lowers it, so that tests exercise the banded path on small
grids against the single-band result.

Remaining limits (refused before allocating, with the value):
- island labelling keeps flat ``int32`` pixel indices (union-find parents, the radix sort's
  2·N buffers): fewer than 2³⁰ pixels; ``warptrunc.islands`` refuses larger maps before
  allocating, naming the limit and the size. Island counts and areas past it, or beyond
  memory, come from the banded labelling of ``warptrunc.islands.streamed`` (see
  :data:`STREAMING_ISLANDS`).
- a side of a WM surface is at most 2²⁰ pixels (``wm_spec``).
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

import warp as wp

__all__ = [
    "STREAMING_ISLANDS",
    "WARP_MAX_DIM",
    "band_pixel_limit",
    "flat_row_bands",
    "force_band_pixels",
    "row_bands",
]

WARP_MAX_DIM = 2**31 - 1
"""Largest extent of one Warp array dimension and of one ``wp.tid()`` launch dimension."""

_DEFAULT_BAND_PIXELS = 2**30
_band_pixels = _DEFAULT_BAND_PIXELS

STREAMING_ISLANDS = """\
Streaming islands: label each row band on its own (the in-memory labelling, local int32
indices); offset the band's labels by the running label count (int64 on the host); keep the
first and last row of labels of every band (2·nx labels) and merge across each band border by
union-find over the pairs (label above, label below) of touching contact pixels; the smallest
label of each merged set survives (first pixel in raster order) and the areas (int64 pixel
counts, one device histogram per band) of the others are added to it. Memory stays
O(band + number of islands). Built for island counts and areas in
``warptrunc.islands.streamed.streamed_islands``, and for labels, areas and perimeters of a host
mask in ``label_islands(..., band_rows=)`` (the label map and the perimeter count on the host);
not built: periodic wrapping and the union-find forest carried across depths (each depth is
labelled afresh).
"""


def band_pixel_limit() -> int:
    """The largest number of pixels one flat (1-D) launch may cover (≤ 2³¹ − 1)."""
    return _band_pixels


@contextlib.contextmanager
def force_band_pixels(max_pixels: int) -> Iterator[None]:
    """Lower the band limit to ``max_pixels`` for the duration of a ``with`` block (testing:
    runs the banded path, as used above 2³¹ pixels, on a small grid)."""
    global _band_pixels
    if not 1 <= int(max_pixels) <= WARP_MAX_DIM:
        raise ValueError(f"max_pixels must be in [1, {WARP_MAX_DIM}], got {max_pixels!r}")
    old, _band_pixels = _band_pixels, int(max_pixels)
    try:
        yield
    finally:
        _band_pixels = old


def row_bands(
    ny: int, nx: int, *, rows: int | None = None, align: int = 1
) -> list[tuple[int, int]]:
    """Row ranges ``[(r0, r1), ...]`` covering ``0..ny``.

    ``rows`` rows per band (default: as many whole rows as :func:`band_pixel_limit` allows),
    rounded down to a multiple of ``align`` but at least ``align``; the last band may be
    shorter. Every band starts at a multiple of ``align``.
    """
    if rows is None:
        rows = max(1, band_pixel_limit() // max(1, nx))
    rows = max(align, rows // align * align)
    return [(r0, min(ny, r0 + rows)) for r0 in range(0, ny, rows)]


def flat_row_bands(z: wp.array) -> Iterator[tuple[int, int, wp.array]]:
    """``(r0, r1, view)`` for the row bands of a 1-D or 2-D Warp array, ``view`` the flattened
    band (1-D, at most :func:`band_pixel_limit` elements unless 4 rows exceed it). A 1-D array
    is one band."""
    if z.ndim == 1:
        yield 0, z.shape[0], z  # one band (a 1-D Warp array is below 2³¹ by construction)
        return
    if z.ndim != 2:
        raise ValueError(f"expected a 1-D or 2-D array, got shape {z.shape}")
    ny, nx = z.shape
    if ny * nx <= band_pixel_limit():  # the common case: one band, no slicing
        yield 0, ny, z.flatten()
        return
    # bands start at multiples of 4 rows: 16-byte aligned, as the vec4/tile kernels want
    for r0, r1 in row_bands(ny, nx, align=4):
        yield r0, r1, z[r0:r1].flatten()
