# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Banded island labelling (``label_islands(..., band_rows=)``, border merge by union-find) and
streamed islands against scipy.ndimage.label and the one-piece labelling."""

import numpy as np
import pytest
from scipy import ndimage

from warptrunc import label_islands
from warptrunc.islands.streamed import streamed_islands
from warptrunc.wm import wm_surface

STRUCT = {4: ndimage.generate_binary_structure(2, 1), 8: np.ones((3, 3), bool)}


def scipy_areas(mask, connectivity):
    lab, n = ndimage.label(mask, structure=STRUCT[connectivity])
    return np.bincount(lab.ravel(), minlength=n + 1)[1:]


def _masks():
    rng = np.random.default_rng(3)
    yield "random-40%-64x64", rng.random((64, 64)) < 0.4
    yield "random-60%-77x50", rng.random((77, 50)) < 0.6  # percolating: islands span bands
    yield "spiral-33x33", _spiral(33)
    yield "u-shapes-20x30", _u_shapes()
    yield "empty-16x16", np.zeros((16, 16), bool)
    yield "full-16x16", np.ones((16, 16), bool)


def _spiral(n):
    """One island winding through every band (merges found only after many borders)."""
    m = np.zeros((n, n), bool)
    top, left, bottom, right = 0, 0, n - 1, n - 1
    while top <= bottom and left <= right:
        m[top, left : right + 1] = True
        m[top : bottom + 1, right] = True
        m[bottom, left : right + 1] = True
        m[top + 2 : bottom + 1, left] = True
        top, left, bottom, right = top + 2, left + 2, bottom - 2, right - 2
    return m


def _u_shapes():
    """Two arms in one band joined only in a later band; a diagonal-only contact."""
    m = np.zeros((20, 30), bool)
    m[0:15, 2] = m[0:15, 8] = True
    m[14, 2:9] = True
    m[5, 20] = m[6, 21] = True  # 8-connected only
    return m


@pytest.mark.parametrize("name,mask", list(_masks()), ids=[m[0] for m in _masks()])
@pytest.mark.parametrize("band_rows", [1, 3, 7, 16, 1000])
@pytest.mark.parametrize("connectivity", [4, 8])
def test_banded_labels_equal_scipy(device, name, mask, band_rows, connectivity):
    rows = min(band_rows, mask.shape[0])
    got = label_islands(mask, 2e-6, 3e-6, connectivity=connectivity, band_rows=rows, device=device)
    ref = scipy_areas(mask, connectivity)
    assert got.area_pixels.dtype == np.int64
    np.testing.assert_array_equal(got.area_pixels, ref)  # count, sizes and raster order
    assert got.n_islands == ref.size
    np.testing.assert_array_equal(
        got.labels, ndimage.label(mask, structure=STRUCT[connectivity])[0]
    )
    # perimeters and areas: equal to the one-piece labelling (tested against NumPy itself)
    one = label_islands(mask, 2e-6, 3e-6, connectivity=connectivity, device=device)
    for k in ("area", "perimeter", "edges_x", "edges_y"):
        np.testing.assert_array_equal(getattr(got, k), getattr(one, k), err_msg=k)


def test_spiral_merges_across_every_border():
    m = _spiral(33)
    got = label_islands(m, band_rows=2, connectivity=4, device="cpu")
    assert got.n_islands == ndimage.label(m)[1]


@pytest.mark.parametrize("band_rows", [8, 24, None])
@pytest.mark.parametrize("connectivity", [4, 8])
def test_streamed_islands_equal_scipy_on_the_in_memory_map(device, band_rows, connectivity):
    s = wm_surface(2.4, 100e-6, n=(96, 150), seed=5, device=device)
    depths = np.array([0.05, 0.2, 0.45]) * s.Rt
    got = streamed_islands(
        s.params,
        depths,
        band_rows=band_rows,
        connectivity=connectivity,
        device=device,
        progress=False,
    )
    thr = (np.float64(s.heights.max()) - depths).astype(np.float32)
    for g, t, d in zip(got, thr, depths, strict=True):
        np.testing.assert_array_equal(g.area_pixels, scipy_areas(s.heights >= t, connectivity))
        assert g.depth == d


def test_bad_input():
    with pytest.raises(ValueError, match="band_rows"):
        label_islands(np.ones((4, 4), bool), band_rows=0, device="cpu")
    with pytest.raises(ValueError, match="connectivity"):
        label_islands(np.ones((4, 4), bool), band_rows=2, connectivity=6, device="cpu")
    with pytest.raises(ValueError, match="band_rows"):
        label_islands(np.ones((4, 4), bool), band_rows=2, periodic=True, device="cpu")
    with pytest.raises(ValueError, match="depths"):
        streamed_islands({"n": 64}, [-1.0], device="cpu")
