# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Device-resident surfaces: same results as host surfaces, lazy host copy, device validation."""

import math

import numpy as np
import pytest
import scipy.ndimage as ndi
import warp as wp

import warptrunc
from warptrunc import Surface, from_heights, island_curve, label_islands, truncate
from warptrunc.islands import ISLANDS_TRUNCATION, MIN_ISLANDS
from warptrunc.wm import wm_surface


def _wm(device, n=128, seed=3):
    return wm_surface(2.4, 100e-6, L=1e-3, n=n, seed=seed, device=device)


def test_wm_surface_stays_on_its_device(device):
    s = _wm(device)
    assert s.device == str(wp.get_device(device))
    assert not s.has_host_copy
    z = s.device_heights()
    assert isinstance(z, wp.array) and z.shape == (128, 128) and z.device == wp.get_device(device)
    assert s.device_heights(device) is z  # no second copy on the same device
    # R_t from the device reduction equals the float64 difference of the host extremes
    h = z.numpy()
    assert s.Rt == float(np.float64(h.max()) - np.float64(h.min()))
    assert not s.has_host_copy


def test_lazy_host_copy_equals_device_array(device):
    s = _wm(device)
    ref = s.device_heights().numpy().copy()
    h = s.heights
    assert s.has_host_copy
    assert h.dtype == np.float32 and h.shape == (s.ny, s.nx)
    np.testing.assert_array_equal(h, ref)
    assert s.heights is h  # made once
    assert not h.flags.writeable
    with pytest.raises(ValueError):
        h[0, 0] = 1.0


def test_release_device_copies_keeps_the_heights(device):
    """``release_device_copies``: the heights move to the host (the same values), the device
    copies are dropped, and a later device use uploads them again (same truncation)."""
    s = _wm(device)
    ref = s.device_heights().numpy().copy()
    before = truncate(s, 20, device=device).n_contact_pixels
    assert s.release_device_copies() is s
    assert s.device is None and s.has_host_copy and not s._dev
    np.testing.assert_array_equal(s.heights, ref)
    np.testing.assert_array_equal(truncate(s, 20, device=device).n_contact_pixels, before)


def test_truncate_and_islands_make_no_host_copy(device):
    s = _wm(device)
    truncate(s, 50, device=device)
    warptrunc.truncation.contact_index_device(
        s, np.linspace(0, 0.3 * s.Rt, 11), warptrunc.resolve_device(device)
    )
    island_curve(s, truncation=ISLANDS_TRUNCATION.replace(increments=20), device=device)
    warptrunc.islands.islands_at_depths(s, [0.1 * s.Rt, 0.2 * s.Rt], device=device)
    assert not s.has_host_copy
    warptrunc.fractal_dimensions(s, ("tri", "box"), device=device)
    assert not s.has_host_copy
    warptrunc.fractal_dimensions(s, ("vs", "sp"), device=device)  # spectra: W_r, D_sp
    warptrunc.describe(s)
    if s.device == "cpu" or _has_cupy():  # CUDA without CuPy: NumPy FFT on the host copy
        assert not s.has_host_copy


def _has_cupy():
    try:
        import cupy  # noqa: F401
    except ImportError:
        return False
    return True


def test_device_surface_counts_equal_host_surface(device):
    s = _wm(device)
    h = from_heights(np.array(s.device_heights().numpy()), s.dx)  # a user's NumPy map
    assert h.device is None and h.has_host_copy
    a = truncate(s, 100, max_depth_fraction=0.6, device=device)
    b = truncate(h, 100, max_depth_fraction=0.6, device=device)
    np.testing.assert_array_equal(a.n_contact_pixels, b.n_contact_pixels)
    np.testing.assert_array_equal(a.threshold, b.threshold)
    assert (a.z_top, a.Rt) == (b.z_top, b.Rt)
    # and against NumPy directly
    z = h.heights
    np.testing.assert_array_equal(
        a.n_contact_pixels, [np.count_nonzero(z >= t) for t in a.threshold]
    )
    t = ISLANDS_TRUNCATION.replace(increments=30)
    ca = island_curve(s, truncation=t, device=device)
    cb = island_curve(h, truncation=t, device=device)
    for f in ("n_islands", "n_contact_pixels", "euler_characteristic", "slit_n_islands"):
        np.testing.assert_array_equal(getattr(ca, f), getattr(cb, f))
    np.testing.assert_array_equal(ca.area_histogram, cb.area_histogram)
    np.testing.assert_allclose(ca.slit_exponent, cb.slit_exponent, rtol=1e-10, equal_nan=True)


def test_numpy_surface_uploaded_once_per_device(device):
    z = np.random.default_rng(0).normal(size=(40, 50)).astype(np.float32)
    s = from_heights(z, 1e-6)
    a = s.device_heights(device)
    assert s.device_heights(device) is a
    np.testing.assert_array_equal(a.numpy(), z)
    truncate(s, 10, device=device)
    assert s.device_heights(device) is a


def test_copy_to_another_device():
    if wp.get_cuda_device_count() == 0:
        pytest.skip("needs CUDA")
    s = _wm("cuda:0")
    c = s.device_heights("cpu")
    np.testing.assert_array_equal(c.numpy(), s.device_heights().numpy())
    assert not s.has_host_copy
    a = truncate(s, 40, device="cpu")
    b = truncate(s, 40, device="cuda:0")
    np.testing.assert_array_equal(a.n_contact_pixels, b.n_contact_pixels)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_device_validation_names_bad_values(device, bad):
    z = np.zeros((30, 40), np.float32)
    z[7, 11] = bad
    z[20, 3] = bad
    zd = wp.array(z, dtype=wp.float32, device=device)
    with pytest.raises(
        ValueError, match=r"heights contains 2 NaN/inf values \(first at iy=7, ix=11\)"
    ):
        Surface(zd, 1e-6, 1e-6)


def test_device_validation_refuses_bad_arrays(device):
    with pytest.raises(ValueError, match="float32"):
        Surface(wp.zeros((4, 4), dtype=wp.float64, device=device), 1.0, 1.0)
    with pytest.raises(ValueError, match="2-D"):
        Surface(wp.zeros(16, dtype=wp.float32, device=device), 1.0, 1.0)
    with pytest.raises(ValueError, match="dx"):
        Surface(wp.zeros((4, 4), dtype=wp.float32, device=device), -1.0, 1.0)


def test_device_extremes_equal_numpy(device):
    rng = np.random.default_rng(5)
    z = rng.normal(size=(257, 129)).astype(np.float32)  # not a multiple of any lane count
    s = Surface(wp.array(z, dtype=wp.float32, device=device), 1e-6, 2e-6)
    assert s.extremes() == (float(z.min()), float(z.max()))
    assert s.Rt == float(np.float64(z.max()) - np.float64(z.min()))
    assert (s.nx, s.ny, s.lx, s.ly) == (129, 257, 129e-6, 257 * 2e-6)


def test_immutable():
    s = from_heights(np.zeros((3, 3)), 1.0)
    with pytest.raises(AttributeError):
        s.dx = 2.0


def test_save_uses_the_lazy_copy(tmp_path, device):
    s = _wm(device, n=64)
    p = warptrunc.write_height_map(s, tmp_path / "s.npz")
    t = warptrunc.read_height_map(p)
    np.testing.assert_array_equal(t.heights, s.heights)
    assert t.params["seed"] == 3


# --- island statistics on the device against a per-depth SciPy/NumPy reference ---------------


def _edges(labels, n):
    fg = labels > 0
    p = np.pad(fg, 1)
    ex = (fg & ~p[1:-1, :-2]).astype(int) + (fg & ~p[1:-1, 2:])
    ey = (fg & ~p[:-2, 1:-1]).astype(int) + (fg & ~p[2:, 1:-1])
    idx = labels.ravel()
    area = np.bincount(idx, minlength=n + 1)[1:]
    return (
        area,
        np.bincount(idx, weights=ex.ravel(), minlength=n + 1)[1:].astype(np.int64),
        np.bincount(idx, weights=ey.ravel(), minlength=n + 1)[1:].astype(np.int64),
    )


@pytest.mark.parametrize("connectivity", [4, 8])
def test_island_statistics_on_device_equal_scipy_per_depth(device, connectivity):
    s = _wm(device, n=192, seed=8)
    t = ISLANDS_TRUNCATION.replace(increments=40, max_depth_fraction=0.6, connectivity=connectivity)
    c = island_curve(s, truncation=t, device=device)
    assert not s.has_host_copy
    z = s.device_heights().numpy()
    thr = (np.float64(z.max()) - c.depth).astype(np.float32)
    st = ndi.generate_binary_structure(2, 1 if connectivity == 4 else 2)
    nbins = c.area_histogram.shape[1]
    fitted = 0
    for k, t in enumerate(thr):
        lab, n = ndi.label(z >= t, st)
        assert c.n_islands[k] == n
        area, ex, ey = _edges(lab, n)
        hist = np.bincount(np.floor(np.log2(area)).astype(int), minlength=nbins) if n else 0
        np.testing.assert_array_equal(c.area_histogram[k], hist)
        big = area >= c.min_pixels
        assert c.slit_n_islands[k] == big.sum()
        if big.sum() >= MIN_ISLANDS:
            x = np.log10(area[big] * s.pixel_area)
            y = np.log10(ex[big] * s.dy + ey[big] * s.dx)
            slope = np.polyfit(x, y, 1)[0]
            r2 = np.corrcoef(x, y)[0, 1] ** 2
            assert c.slit_exponent[k] == pytest.approx(slope, rel=1e-9, abs=1e-12)
            assert c.slit_r2[k] == pytest.approx(r2, rel=1e-9, abs=1e-12)
            fitted += 1
        else:
            assert math.isnan(c.slit_exponent[k])
    assert fitted >= 5  # the comparison covered real fits


def test_label_islands_device_mask_lazy_labels(device):
    s = _wm(device, n=128)
    z = s.device_heights().numpy()
    m = z >= np.float32(z.max() - 0.3 * s.Rt)
    a = label_islands(m, s.dx, device=device)
    mw = wp.array(m.astype(np.uint8), dtype=wp.uint8, device=device)
    b = label_islands(mw, s.dx)
    assert not b.has_host_labels and b.device_labels is not None
    ref, n = ndi.label(m)
    assert a.n_islands == b.n_islands == n
    np.testing.assert_array_equal(b.area_pixels, a.area_pixels)
    np.testing.assert_array_equal(b.perimeter, a.perimeter)
    np.testing.assert_array_equal(b.labels, ref)
    assert b.has_host_labels
    np.testing.assert_array_equal(a.labels, ref)


# --- descriptors and the four D methods on a device surface -----------------------------------


def test_descriptors_of_device_surface_equal_host(device):
    s = _wm(device, n=160, seed=2)
    h = from_heights(np.array(s.device_heights().numpy()), s.dx)
    a = warptrunc.describe(s)
    # independent float64 NumPy moments of the same map
    z = h.heights.astype(np.float64)
    d = z - z.mean()
    assert a.mean == pytest.approx(z.mean(), rel=1e-12, abs=1e-18)
    assert a.Rrms == pytest.approx(np.sqrt(np.mean(d**2)), rel=1e-10)
    assert a.Ra == pytest.approx(np.mean(np.abs(d)), rel=1e-10)
    assert a.skewness == pytest.approx(np.mean(d**3) / np.mean(d**2) ** 1.5, rel=1e-8, abs=1e-12)
    assert a.kurtosis == pytest.approx(np.mean(d**4) / np.mean(d**2) ** 2, rel=1e-10)
    assert a.Rt == np.float64(z.max()) - np.float64(z.min())
    b = warptrunc.describe(h)
    assert (a.Wr, a.Wr_resolved) == (b.Wr, b.Wr_resolved)
    fa = warptrunc.fractal_dimensions(s, device=device)
    fb = warptrunc.fractal_dimensions(h, device=device)
    for m in fa:
        assert fa[m].D == pytest.approx(fb[m].D, rel=1e-9, abs=1e-12), m
        np.testing.assert_allclose(fa[m].measure, fb[m].measure, rtol=1e-9)
    if s.device == "cpu":  # CUDA without CuPy falls back to the lazy host copy for spectra
        assert not s.has_host_copy


def test_device_statistics_of_a_constant_map(device):
    s = Surface(wp.full((8, 9), 2.5e-6, dtype=wp.float32, device=device), 1e-6, 1e-6)
    st = warptrunc.descriptors.surface_statistics(s)
    assert st["Rt"] == 0.0 and st["Rrms"] == 0.0
    assert (st["skewness"], st["kurtosis"]) == (0.0, 3.0)
