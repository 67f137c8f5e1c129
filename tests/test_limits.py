# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The banded (> 2³¹ pixels) path, forced on small grids, against NumPy and the one-band path;
limits refused with a message naming them."""

import itertools

import numpy as np
import pytest
import warp as wp

from warptrunc import contact_index_map, from_heights, truncate
from warptrunc._support.limits import WARP_MAX_DIM, band_pixel_limit, force_band_pixels, row_bands
from warptrunc.cli import main
from warptrunc.truncation import height_range
from warptrunc.wm import wm_spec, wm_surface


def numpy_counts(z, thresholds):
    return np.array([np.count_nonzero(z >= t) for t in thresholds])


@pytest.mark.parametrize("ny,nx", [(64, 64), (100, 96), (256, 256), (37, 91)])
@pytest.mark.parametrize("cap", [1, 50, 3 * 91 + 5, 4096])
def test_row_bands_cover_the_map_within_the_cap(ny, nx, cap):
    with force_band_pixels(cap):
        bands = row_bands(ny, nx)
    assert bands[0][0] == 0 and bands[-1][1] == ny
    assert all(a[1] == b[0] for a, b in itertools.pairwise(bands))
    # whole rows; several rows per band only while they fit under the cap
    assert all(r1 > r0 for r0, r1 in bands)
    assert all((r1 - r0) * nx <= cap for r0, r1 in bands) or cap < nx


def test_row_bands_alignment():
    bands = row_bands(300, 10, rows=100, align=128)
    assert bands == [(0, 128), (128, 256), (256, 300)]
    assert row_bands(300, 10, rows=300, align=128) == [(0, 256), (256, 300)]


def test_force_band_pixels_restores_and_validates():
    before = band_pixel_limit()
    assert before <= WARP_MAX_DIM
    with pytest.raises(RuntimeError), force_band_pixels(10):
        assert band_pixel_limit() == 10
        raise RuntimeError
    assert band_pixel_limit() == before
    with pytest.raises(ValueError, match="max_pixels"), force_band_pixels(0):
        pass
    with pytest.raises(ValueError, match="max_pixels"), force_band_pixels(2**31):
        pass


def _maps():
    rng = np.random.default_rng(1)
    yield "normal-64x64", rng.normal(size=(64, 64))
    yield "ties-100x96", np.round(rng.normal(size=(100, 96)) * 8) / 8
    yield "uniform-37x91", rng.uniform(-1, 1, size=(37, 91))


@pytest.mark.parametrize("name,z", list(_maps()), ids=[m[0] for m in _maps()])
@pytest.mark.parametrize("cap", [1, 7 * 64 + 3, 1000])
def test_banded_truncation_equals_numpy_and_one_band(device, name, z, cap):
    z = np.asarray(z, dtype=np.float32)
    s = from_heights(z, 1e-6)
    ref = truncate(s, 80, max_depth_fraction=0.6, device=device)
    with force_band_pixels(cap):
        assert len(row_bands(*z.shape)) > 1
        c = truncate(s, 80, max_depth_fraction=0.6, device=device)
        index = contact_index_map(s, c.depth, device=device)
        lo, hi = height_range(wp.array(z, device=device), device)
    np.testing.assert_array_equal(c.n_contact_pixels, numpy_counts(z, c.threshold))
    np.testing.assert_array_equal(c.n_contact_pixels, ref.n_contact_pixels)
    assert (c.z_top, c.Rt) == (ref.z_top, ref.Rt)
    assert (lo, hi) == (float(z.min()), float(z.max()))
    # the contact index: the first k with z ≥ threshold[k], as NumPy finds it
    expect = np.argmax(z[..., None] >= c.threshold[None, None, :], axis=-1)
    expect[~np.any(z[..., None] >= c.threshold, axis=-1)] = c.threshold.size
    np.testing.assert_array_equal(index, expect)


def test_banded_wm_generation_is_unchanged(device):
    kw = dict(D=2.5, Wr=100e-6, n=(96, 100), seed=9, device=device)
    ref = wm_surface(**kw)
    with force_band_pixels(5 * 96 + 1):  # extremes by 20 bands of 5 rows
        s = wm_surface(**kw)
    np.testing.assert_array_equal(s.heights, ref.heights)
    assert s.Rt == ref.Rt and s.params["scale"] == ref.params["scale"]


def test_side_limit_is_refused_before_allocating(capsys):
    with pytest.raises(ValueError, match=r"n must be an integer in \[2, 1048576\]"):
        wm_spec(n=2**20 + 1)
    with pytest.raises(SystemExit) as exit_:  # refused while parsing, by --n's declared range
        main(["generate", "--n", str(2**21), "-o", "unused.npz"])
    assert exit_.value.code == 2
    assert "--n: must be an integer in [2, 1048576], got '2097152'" in capsys.readouterr().err


@pytest.mark.parametrize("shape", [(32768, 32768), (46400, 46400)], ids=["2^30", "46400^2"])
def test_island_labelling_limit_is_refused_before_touching_memory(shape):
    """A (ny, nx) int32 view over a 16-element buffer: the size check must come first."""
    from warptrunc.islands import island_counts_device
    from warptrunc.islands.unionfind import label_device

    buf = wp.zeros(16, dtype=wp.int32, device="cpu")
    index = wp.array(ptr=buf.ptr, shape=shape, dtype=wp.int32, device="cpu")
    n = shape[0] * shape[1]
    with pytest.raises(ValueError, match=rf"grid of {n} pixels is too large .*limit 2\*\*30"):
        island_counts_device(index, 10)
    mask = wp.array(ptr=buf.ptr, shape=shape, dtype=wp.uint8, device="cpu")
    with pytest.raises(ValueError, match=rf"grid of {n} pixels is too large"):
        label_device(mask)


@pytest.mark.gpu
@pytest.mark.slow
def test_gpu_past_2_31_pixels_in_memory_equals_streamed_and_numpy():
    """46400² = 2.15·10⁹ pixels (> 2³¹ − 1), in memory on the GPU, against the streamed path
    and NumPy at a few thresholds. ~9 GB of device memory and ~20 GB of host memory."""
    import os

    want = os.environ.get("WARPTRUNC_TEST_DEVICES")
    if wp.get_cuda_device_count() == 0 or (want and "cuda:0" not in want):
        pytest.skip("needs a CUDA device")
    if os.environ.get("WARPTRUNC_SLOW") != "1":
        pytest.skip("large case: set WARPTRUNC_SLOW=1")
    n = 46400
    s = wm_surface(n=n, seed=1, device="cuda:0")
    assert s.heights.size > 2**31 - 1
    c = truncate(s, 50, max_depth_fraction=0.3, device="cuda:0")
    st = truncate(s.params, 50, max_depth_fraction=0.3, stream=True, device="cuda:0")
    np.testing.assert_array_equal(st.n_contact_pixels, c.n_contact_pixels)
    assert (st.z_top, st.Rt) == (c.z_top, c.Rt)
    assert c.z_top == float(s.heights.max())
    for k in (0, 10, 50):
        assert c.n_contact_pixels[k] == np.count_nonzero(s.heights >= c.threshold[k])
