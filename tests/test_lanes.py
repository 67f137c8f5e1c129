# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The (row, column) lane walk of grids past 2³¹ − 1 elements (``kernels/lanes.py``:
``lane_start_rc``), against NumPy's int64 divmod: a 32768² map's padded half spectrum has
65536 × 32769 = 2 147 549 184 elements, past int32, where the flat walk overflowed (the solve
diverged at its second iteration on an H100)."""

from __future__ import annotations

import numpy as np
import pytest
import warp as wp

from warptrunc.kernels.lanes import lane_more, lane_next_rc, lane_start_rc


@wp.kernel
def _ends_kernel(stride: int, chunk: int, ny: int, nx: int, out: wp.array2d(dtype=wp.int32)):
    lane = wp.tid()
    iy, ix, sy, sx, ey, ex = lane_start_rc(lane, stride, chunk, ny, nx)
    out[lane, 0] = iy
    out[lane, 1] = ix
    out[lane, 2] = sy
    out[lane, 3] = sx
    out[lane, 4] = ey
    out[lane, 5] = ex


@wp.kernel
def _visit_kernel(stride: int, chunk: int, count: wp.array2d(dtype=wp.int32)):
    lane = wp.tid()
    nx = count.shape[1]
    iy, ix, sy, sx, ey, ex = lane_start_rc(lane, stride, chunk, count.shape[0], nx)
    while lane_more(iy, ix, ey, ex):
        wp.atomic_add(count, iy, ix, 1)
        iy, ix = lane_next_rc(iy, ix, sy, sx, nx)


@pytest.mark.parametrize("gpu_mode", [False, True])
def test_lane_ends_past_int32(gpu_mode):
    ny, nx, lanes = 65536, 32769, 64
    n = ny * nx
    assert n > 2**31 - 1
    chunk = 0 if gpu_mode else -(-n // lanes)
    stride = lanes
    out = wp.zeros((lanes, 6), dtype=wp.int32, device="cpu")
    wp.launch(_ends_kernel, dim=lanes, inputs=[stride, chunk, ny, nx], outputs=[out], device="cpu")
    got = out.numpy().astype(np.int64)
    lane = np.arange(lanes, dtype=np.int64)
    start = lane if gpu_mode else lane * chunk
    end = np.full(lanes, n) if gpu_mode else np.minimum(n, start + chunk)
    step = stride if gpu_mode else 1
    np.testing.assert_array_equal(got[:, 0] * nx + got[:, 1], start)
    np.testing.assert_array_equal(got[:, 4] * nx + got[:, 5], end)
    assert tuple(got[0, 2:4]) == divmod(step, nx)


@pytest.mark.parametrize("shape", [(7, 5), (64, 33), (3, 1000)])
@pytest.mark.parametrize("lanes,gpu_mode", [(1, False), (6, False), (64, False), (6, True), (64, True)])
def test_lane_walk_visits_every_element_once(shape, lanes, gpu_mode):
    n = shape[0] * shape[1]
    chunk = 0 if gpu_mode else max(1, -(-n // lanes))
    count = wp.zeros(shape, dtype=wp.int32, device="cpu")
    wp.launch(_visit_kernel, dim=lanes, inputs=[lanes, chunk], outputs=[count], device="cpu")
    np.testing.assert_array_equal(count.numpy(), np.ones(shape, np.int32))
