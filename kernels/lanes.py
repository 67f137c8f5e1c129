# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The lane walk shared by the reduction kernels, and their float32/float64 overloads.

Used by ``kernels/contact/cg.py``, ``kernels/contact/plastic.py``,
``kernels/contact/spectral.py``, ``kernels/contact/bccg.py`` and ``kernels/reduce.py``. A launch of ``lanes`` threads walks ``n`` flattened elements: on the GPU
(``chunk == 0``) lane ``i`` takes every ``stride``-th element from ``i`` (coalesced), on the CPU
the contiguous chunk ``[i·chunk, (i+1)·chunk)``. Integer index arithmetic only: the kernels'
floating-point operations and their order are their own.
"""

from typing import Any

import warp as wp

wp.set_module_options({"enable_backward": False})


@wp.func
def lane_range(lane: int, stride: int, chunk: int, n: int):
    """First flat index, end (exclusive) and step of ``lane`` over ``n`` elements."""
    i = lane
    end = n
    step = stride
    if chunk > 0:
        i = lane * chunk
        end = wp.min(n, i + chunk)
        step = 1
    return i, end, step


@wp.func
def lane_start(lane: int, stride: int, chunk: int, n: int, nx: int):
    """``lane_range`` over a map of rows of ``nx``, with the start's (iy, ix) and the step's
    (sy, sx) in rows and columns: ``i, end, step, iy, ix, sy, sx``."""
    i, end, step = lane_range(lane, stride, chunk, n)
    iy = i // nx
    sy = step // nx
    return i, end, step, iy, i - iy * nx, sy, step - sy * nx


@wp.func
def lane_next(i: int, iy: int, ix: int, step: int, sy: int, sx: int, nx: int):
    """The next element of a ``lane_start`` walk: ``i, iy, ix``."""
    iy += sy
    ix += sx
    if ix >= nx:
        ix -= nx
        iy += 1
    return i + step, iy, ix


@wp.func
def lane_start_rc(lane: int, stride: int, chunk: int, ny: int, nx: int):
    """``lane_start`` for grids of more than 2³¹ − 1 elements (a 32768² map's padded half
    spectrum, 65536 × 32769): the walk is kept as (row, column) and ends at the row and column
    ``(ey, ex)`` (exclusive), the flat positions computed in 64 bits. Returns
    ``iy, ix, sy, sx, ey, ex``; go on while :func:`lane_more`, step with :func:`lane_next_rc`."""
    n = wp.int64(ny) * wp.int64(nx)
    i = wp.int64(lane)
    step = wp.int64(stride)
    end = n
    if chunk > 0:
        i = wp.int64(lane) * wp.int64(chunk)
        end = wp.min(n, i + wp.int64(chunk))
        step = wp.int64(1)
    nx64 = wp.int64(nx)
    iy = wp.int32(i / nx64)
    ix = wp.int32(i - wp.int64(iy) * nx64)
    sy = wp.int32(step / nx64)
    sx = wp.int32(step - wp.int64(sy) * nx64)
    ey = wp.int32(end / nx64)
    ex = wp.int32(end - wp.int64(ey) * nx64)
    if i >= end:  # an idle lane
        iy = ey
        ix = ex
    return iy, ix, sy, sx, ey, ex


@wp.func
def lane_more(iy: int, ix: int, ey: int, ex: int):
    """True while (iy, ix) is before the end (ey, ex) of a ``lane_start_rc`` walk."""
    return iy < ey or (iy == ey and ix < ex)


@wp.func
def lane_next_rc(iy: int, ix: int, sy: int, sx: int, nx: int):
    """The next (row, column) of a ``lane_start_rc`` walk."""
    iy += sy
    ix += sx
    if ix >= nx:
        ix -= nx
        iy += 1
    return iy, ix


def declare_overloads(kernels, vec_args=frozenset()) -> None:
    """float32 and float64 instances of every generic kernel (``Any`` arrays become 2-D arrays of
    the scalar, or of vec2 for the (kernel, argument) pairs in ``vec_args``), so that a module
    compiles once."""
    for scalar, vec in ((wp.float32, wp.vec2f), (wp.float64, wp.vec2d)):
        for k in kernels:
            types = {}
            for arg in k.adj.args:
                ty = arg.type
                if wp.types.is_array(ty) and ty.dtype is Any:
                    dt = vec if (k, arg.label) in vec_args else scalar
                    types[arg.label] = wp.array2d(dtype=dt)
                else:
                    types[arg.label] = ty
            wp.overload(k, types)
