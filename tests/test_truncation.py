# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation counts against NumPy, closed forms, and invariants."""

import math

import numpy as np
import pytest

from warptrunc import contact_index_map, from_heights, truncate
from warptrunc.wm import wm_surface


def numpy_counts(z, thresholds):
    return np.array([np.count_nonzero(z >= t) for t in thresholds])


def _maps():
    rng = np.random.default_rng(0)
    yield "normal-64x64", rng.normal(size=(64, 64))
    yield "uniform-37x91", rng.uniform(-1, 1, size=(37, 91))
    yield "ties-128x96", np.round(rng.normal(size=(128, 96)) * 8) / 8  # many equal heights
    yield "wm-256", wm_surface(2.6, 100e-6, n=256, seed=4, device="cpu").heights


@pytest.mark.parametrize("name,z", list(_maps()), ids=[m[0] for m in _maps()])
@pytest.mark.parametrize("frac", [0.1, 0.5, 1.0])
def test_counts_equal_numpy_at_every_depth(device, name, z, frac):
    z = np.asarray(z, dtype=np.float32)
    c = truncate(from_heights(z, 1e-6), 200, max_depth_fraction=frac, device=device)
    assert c.threshold.dtype == np.float32
    # the thresholds are z_top − ω_k rounded to float32, from the float64 depths
    np.testing.assert_array_equal(c.threshold, (np.float64(z.max()) - c.depth).astype(np.float32))
    np.testing.assert_array_equal(c.n_contact_pixels, numpy_counts(z, c.threshold))
    np.testing.assert_allclose(c.contact_area, c.n_contact_pixels * 1e-12)
    assert np.all(np.diff(c.n_contact_pixels) >= 0)  # monotone in depth
    if frac == 1.0:
        assert c.n_contact_pixels[-1] == z.size  # ω = R_t reaches every pixel


def test_contact_index_map_matches_numpy(device):
    z = np.random.default_rng(1).normal(size=(50, 70)).astype(np.float32)
    s = from_heights(z, 1e-6)
    c = truncate(s, 40, max_depth_fraction=0.6, device=device)
    idx = contact_index_map(s, c.depth, device=device)
    for k in (0, 1, 17, 40):
        np.testing.assert_array_equal(idx <= k, z >= c.threshold[k])
    assert idx.max() == 41  # never-touching pixels get len(depth)


def test_paraboloid_area_is_2_pi_R_omega(device):
    # z = −r²/(2R) with the apex on a sample: truncated area is π·(2Rω) = 2πRω (§2.1, a' = 2a_E).
    # Bound: a sample is inside the circle of radius ρ = √(2Rω) iff its dx-cell centre is, so the
    # cells lie between the discs of radius ρ − dx/√2 and ρ + dx/√2.
    n, dx, R = 257, 1e-6, 1e-3
    x = (np.arange(n) - n // 2) * dx
    X, Y = np.meshgrid(x, x)
    z = (-(X**2 + Y**2) / (2 * R)).astype(np.float32)
    c = truncate(from_heights(z, dx), 100, max_depth=6e-6, device=device)  # ρ ≤ 110 px
    rho = np.sqrt(2 * R * c.depth)
    lo = np.pi * np.maximum(rho - dx / math.sqrt(2), 0) ** 2
    hi = np.pi * (rho + dx / math.sqrt(2)) ** 2
    assert np.all(c.contact_area >= lo - 1e-18) and np.all(c.contact_area <= hi + 1e-18)
    deep = c.depth > 1.5e-6  # ρ > 54 px: the band above is within ±2.6 % of the area
    np.testing.assert_allclose(c.contact_area[deep], 2 * np.pi * R * c.depth[deep], rtol=0.03)


def test_tilted_plane_area_linear_in_depth(device):
    # z = −a·x: columns touch one after another; A_c(ω) = (⌊ω/(a·dx)⌋ + 1)·Ly·dx
    nx, ny, dx, a = 200, 30, 1e-6, 0.01
    z = np.broadcast_to(-a * np.arange(nx) * dx, (ny, nx)).astype(np.float32)
    c = truncate(from_heights(z, dx), 50, max_depth_fraction=0.5, device=device)
    exact_cols = c.depth / (a * dx) + 1
    cols = c.n_contact_pixels / ny
    assert np.all(c.n_contact_pixels % ny == 0)  # whole columns
    assert np.all(np.abs(cols - exact_cols) <= 1.0 + 1e-9)  # one column of discretisation
    slope = np.polyfit(c.depth, c.contact_area, 1)[0]
    assert slope == pytest.approx(ny * dx * dx / (a * dx), rel=0.02)


def test_plane_is_all_or_nothing(device):
    z = np.full((20, 30), 3.0, dtype=np.float32)
    z[0, 0] = 3.5  # a single peak so that R_t > 0
    c = truncate(from_heights(z, 1e-6), 10, max_depth_fraction=1.0, device=device)
    assert list(c.n_contact_pixels[:-1]) == [1] * 10
    assert c.n_contact_pixels[-1] == 600


def test_invariants(device):
    rng = np.random.default_rng(2)
    z = (np.round(rng.normal(size=(48, 64)) * 64) / 64).astype(np.float32)  # exact binary fractions
    base = truncate(from_heights(z, 1e-6), 60, max_depth_fraction=0.7, device=device)
    shifted = truncate(
        from_heights(z + np.float32(8.0), 1e-6), 60, max_depth_fraction=0.7, device=device
    )
    transposed = truncate(from_heights(z.T.copy(), 1e-6), 60, max_depth_fraction=0.7, device=device)
    scaled = truncate(from_heights(z, 3e-6), 60, max_depth_fraction=0.7, device=device)
    np.testing.assert_array_equal(shifted.n_contact_pixels, base.n_contact_pixels)
    np.testing.assert_array_equal(transposed.n_contact_pixels, base.n_contact_pixels)
    np.testing.assert_allclose(scaled.contact_area, 9 * base.contact_area, rtol=1e-12)


def test_depth_options(device):
    z = np.random.default_rng(3).normal(size=(32, 32)).astype(np.float32)
    s = from_heights(z, 1e-6)
    c = truncate(s, 20, max_depth=0.5, device=device)
    assert c.depth[-1] == pytest.approx(0.5) and c.depth.size == 21
    c = truncate(s, 8, max_depth_fraction=0.25, device=device)
    assert c.depth[-1] == pytest.approx(0.25 * s.Rt)


@pytest.mark.parametrize(
    "z, match",
    [
        (np.zeros(10), "must be 2-D"),
        (np.zeros((2, 3, 4)), "must be 2-D"),
        (np.array([[1.0, np.nan], [0.0, 1.0]]), "NaN/inf"),
        (np.array([[1.0, np.inf], [0.0, 1.0]]), "NaN/inf"),
        (np.zeros((0, 5)), "must not be empty"),
        (np.array([["a", "b"]]), "real numbers"),
    ],
)
def test_bad_height_maps_raise(z, match):
    with pytest.raises(ValueError, match=match):
        from_heights(z, 1e-6)


@pytest.mark.parametrize(
    "kw, match",
    [
        ({"n_increments": 0}, "n_increments must be an integer"),
        ({"max_depth_fraction": 0.0}, "max_depth_fraction must be in"),
        ({"max_depth_fraction": 1.5}, "max_depth_fraction must be in"),
        ({"max_depth": -1.0}, "max_depth must be in"),
    ],
)
def test_bad_truncation_options_raise(kw, match):
    s = from_heights(np.random.default_rng(0).normal(size=(8, 8)), 1e-6)
    with pytest.raises(ValueError, match=match):
        truncate(s, device="cpu", **kw)


def test_flat_map_raises():
    with pytest.raises(ValueError, match="flat"):
        truncate(from_heights(np.ones((8, 8)), 1e-6), device="cpu")


def test_bad_spacing_and_device_raise():
    with pytest.raises(ValueError, match="dx must be in"):
        from_heights(np.ones((4, 4)), 0.0)
    with pytest.raises(ValueError, match="device must be one of"):
        truncate(from_heights(np.eye(4), 1e-6), device="tpu:3")


@pytest.mark.parametrize("mode", ["auto", "block", "vec4", "pixel"])
@pytest.mark.parametrize("n_inc", [200, 255, 300])
def test_histogram_kernels_equal_numpy(device, monkeypatch, mode, n_inc):
    """Every histogram kernel (block-private, 4 pixels per thread, one per pixel), with bins
    beyond the shared histogram's size and a remainder of n mod 4 pixels, counts as NumPy."""
    import warptrunc.truncation.curve as tr

    monkeypatch.setattr(tr, "GPU_HISTOGRAM", mode)
    z = np.random.default_rng(5).normal(size=(61, 67)).astype(np.float32)  # 4087 pixels
    for frac in (0.05, 1.0):
        c = truncate(from_heights(z, 1e-6), n_inc, max_depth_fraction=frac, device=device)
        np.testing.assert_array_equal(c.n_contact_pixels, numpy_counts(z, c.threshold))


def test_histogram_of_unaligned_view_equals_numpy(device):
    """A flat view that starts off a 16-byte boundary takes the one-pixel-per-thread path."""
    import warp as wp

    from warptrunc import resolve_device
    from warptrunc.truncation import contact_histogram

    dev = resolve_device(device)
    z = np.random.default_rng(6).normal(size=1001).astype(np.float32)
    zw = wp.array(z, device=dev)[1:]
    thr = (np.float64(z[1:].max()) - np.linspace(0.0, 2.0, 101)).astype(np.float32)
    hist = contact_histogram(zw, wp.array(thr, device=dev), float(z[1:].max()), 50.0, dev)
    np.testing.assert_array_equal(np.cumsum(hist.numpy()[:101]), numpy_counts(z[1:], thr))


@pytest.mark.parametrize("stream", [False, True])
def test_device_is_resolved_once_per_call(monkeypatch, stream):
    """The public call resolves the device; the helpers below it take the resolved device."""
    import sys

    import warptrunc
    import warptrunc._support.device as dev

    real, calls = dev.resolve_device, []

    def counting(device=None):
        calls.append(device)
        return real(device)

    for m in list(sys.modules.values()):
        if (
            getattr(m, "__name__", "").startswith("warptrunc")
            and getattr(m, "resolve_device", None) is real
        ):
            monkeypatch.setattr(m, "resolve_device", counting)
    spec = {"D": 2.5, "Wr": 100e-6, "n": 64, "seed": 1}
    warptrunc.truncate(spec, 20, stream=stream, device="cpu")
    warptrunc.truncate(warptrunc.from_heights(np.eye(8), 1e-6), 4, device="cpu")
    assert calls == ["cpu", "cpu"]
