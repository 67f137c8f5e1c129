# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Min/max reduction of a float32 height map.

Launched by ``warptrunc.truncation.height_range``. Grid: ``stride`` threads, each walking the
flattened map with a grid-stride loop (coalesced on the GPU) or a contiguous chunk (on the
CPU), then one atomic min and max per
thread into ``out[0]`` (min) and ``out[1]`` (max). Heights in metres, float32. The caller sets
``out`` to (+inf, -inf). Min and max do not depend on order, so results are identical on every
device.
"""

import warp as wp

from .lanes import lane_range

wp.set_module_options({"enable_backward": False})


@wp.kernel
def min_max_kernel(z: wp.array[wp.float32], stride: int, chunk: int, out: wp.array[wp.float32]):
    """Lanes over the flattened map; ``out = [min, max]``. GPU (``chunk == 0``): grid-stride
    lanes, coalesced. CPU: lane i scans the contiguous chunk [i·chunk, (i+1)·chunk), which is
    cache-friendly where a strided walk is not."""
    i, n, step = lane_range(wp.tid(), stride, chunk, z.shape[0])
    lo = float(3.4e38)
    hi = float(-3.4e38)
    while i < n:
        v = z[i]
        lo = wp.min(lo, v)
        hi = wp.max(hi, v)
        i += step
    wp.atomic_min(out, 0, lo)
    wp.atomic_max(out, 1, hi)


TILE = wp.constant(8192)  # elements per block in min_max_tile_kernel


@wp.kernel
def min_max_tile_kernel(
    z: wp.array[wp.float32], lo: wp.array[wp.float32], hi: wp.array[wp.float32]
):
    """GPU: one tile block per TILE consecutive elements (whole tiles only; the caller reduces
    the remainder): ``lo[b]``, ``hi[b]`` = the tile's min and max (a coalesced, block-wide
    reduction, no atomics)."""
    b = wp.tid()
    t = wp.tile_load(z, shape=(TILE,), offset=(b * TILE,))
    wp.tile_store(lo, wp.tile_min(t), offset=(b,))
    wp.tile_store(hi, wp.tile_max(t), offset=(b,))


@wp.kernel
def validate_kernel(
    z: wp.array[wp.float32],
    stride: int,
    chunk: int,
    out: wp.array[wp.float32],
    bad: wp.array[wp.int64],
):
    """Validation pass of a device-resident height map, lanes as ``min_max_kernel``.

    ``out = [min, max]`` over the finite values (the caller sets (+inf, −inf)); ``bad[0]`` =
    number of NaN/inf values, ``bad[1]`` = smallest flat index of one (the caller sets
    (0, len(z))). Integer atomics and min/max only: identical on every device."""
    i, n, step = lane_range(wp.tid(), stride, chunk, z.shape[0])
    lo = float(3.4e38)
    hi = float(-3.4e38)
    nbad = wp.int64(0)
    first = wp.int64(z.shape[0])
    while i < n:
        v = z[i]
        if wp.isfinite(v):
            lo = wp.min(lo, v)
            hi = wp.max(hi, v)
        else:
            if nbad == wp.int64(0):
                first = wp.int64(i)
            nbad += wp.int64(1)
        i += step
    wp.atomic_min(out, 0, lo)
    wp.atomic_max(out, 1, hi)
    if nbad > wp.int64(0):
        wp.atomic_add(bad, 0, nbad)
        wp.atomic_min(bad, 1, first)


@wp.kernel
def sum_kernel(z: wp.array[wp.float32], stride: int, chunk: int, out: wp.array[wp.float64]):
    """Lanes as ``min_max_kernel``; ``out[0] +=`` the float64 sum of the lane's values (one
    float64 atomic per lane)."""
    i, n, step = lane_range(wp.tid(), stride, chunk, z.shape[0])
    s = wp.float64(0.0)
    while i < n:
        s += wp.float64(z[i])
        i += step
    wp.atomic_add(out, 0, s)


@wp.kernel
def central_moments_kernel(
    z: wp.array[wp.float32],
    stride: int,
    chunk: int,
    mean: wp.float64,
    out: wp.array[wp.float64],
):
    """Lanes as ``min_max_kernel``; ``out[0..3] +=`` Σ|d|, Σd², Σd³, Σd⁴ with d = z − mean,
    accumulated in float64 (one atomic per lane and moment)."""
    i, n, step = lane_range(wp.tid(), stride, chunk, z.shape[0])
    a1 = wp.float64(0.0)
    a2 = wp.float64(0.0)
    a3 = wp.float64(0.0)
    a4 = wp.float64(0.0)
    while i < n:
        d = wp.float64(z[i]) - mean
        d2 = d * d
        a1 += wp.abs(d)
        a2 += d2
        a3 += d2 * d
        a4 += d2 * d2
        i += step
    wp.atomic_add(out, 0, a1)
    wp.atomic_add(out, 1, a2)
    wp.atomic_add(out, 2, a3)
    wp.atomic_add(out, 3, a4)
