# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""WM synthesis (Eq. 4) against a float64 NumPy evaluation written independently."""

import math

import numpy as np
import pytest
from reference import wm_numpy

import warptrunc
from warptrunc import read_height_map
from warptrunc.wm import wm_spec, wm_surface

# (D, Lx, Ly, nx, ny): squares up to 128² and rectangles (non-square pixels too)
CASES = [
    (2.5, 1e-3, 1e-3, 32, 32),
    (2.2, 1e-3, 1e-3, 128, 128),
    (2.8, 1.5e-3, 1e-3, 96, 64),
    (2.4, 1e-3, 1e-3, 80, 48),
]


@pytest.mark.parametrize("method", ["tile", "direct"])
@pytest.mark.parametrize("case", CASES, ids=lambda c: f"D{c[0]}-{c[3]}x{c[4]}")
def test_matches_float64_numpy(device, case, method):
    D, Lx, Ly, nx, ny = case
    Wr, G, seed = 100e-6, 1e-9, 7
    Wc = 2 * max(Lx / nx, Ly / ny)
    ref, n_max = wm_numpy(D, Wr, Lx, Ly, nx, ny, G=G, Wc=Wc, seed=seed)
    s = wm_surface(
        D, Wr, L=(Lx, Ly), n=(nx, ny), Rt=None, G=G, seed=seed, method=method, device=device
    )
    assert s.heights.shape == (ny, nx) and s.heights.dtype == np.float32
    assert s.params["n_max"] == n_max
    err = np.abs(s.heights.astype(np.float64) - ref).max() / np.ptp(ref)
    assert err <= 1e-5, err


def test_phases_far_from_origin_stay_accurate(device):
    # phases up to ~5e5 rad: a float32 phase would be off by ~0.03 rad, i.e. ~1e-2 of the range
    D, Wr, L, n, Wc, G = 2.5, 100e-6, 0.1, 64, 1e-6, 1e-9
    ref, _ = wm_numpy(D, Wr, L, L, n, n, G=G, Wc=Wc, seed=3)
    s = wm_surface(D, Wr, L=L, n=n, Rt=None, G=G, Wc=Wc, seed=3, device=device)
    assert np.abs(s.heights - ref).max() / np.ptp(ref) <= 1e-5


def test_rt_scaling(device):
    s = wm_surface(2.5, 100e-6, L=1e-3, n=(64, 48), Rt=3e-6, seed=1, device=device)
    z = s.heights.astype(np.float64)
    # float32 rounding of the extremes: relative 2^-24 each
    assert z.max() - z.min() == pytest.approx(3e-6, rel=1e-6)
    # scaling does not change the shape: compare with the unscaled (G) surface
    g = wm_surface(2.5, 100e-6, L=1e-3, n=(64, 48), Rt=None, G=1e-9, seed=1, device=device)
    zg = g.heights.astype(np.float64)
    np.testing.assert_allclose(z / np.ptp(z), zg / np.ptp(zg), atol=2e-6)
    assert s.params["scale"] > 0 and s.params["Rt"] == 3e-6


def test_same_seed_same_surface_other_seed_differs(device):
    a = wm_surface(2.5, 100e-6, n=64, seed=5, device=device).heights
    b = wm_surface(2.5, 100e-6, n=64, seed=5, device=device).heights
    c = wm_surface(2.5, 100e-6, n=64, seed=6, device=device).heights
    np.testing.assert_array_equal(a, b)
    assert np.abs(a - c).max() > 0.1 * np.ptp(a)


def test_cutoff_choices_give_paper_term_counts():
    # 10240² over 1 mm, Wr = 100 µm: Nyquist W_c = 2dx keeps n ≤ 15 (160 terms with M = 10);
    # the literal one-pixel cut-off keeps n ≤ 17 (180 terms)
    nyq = wm_spec(2.5, 100e-6, L=1e-3, n=10240)
    pix = wm_spec(2.5, 100e-6, L=1e-3, n=10240, cutoff="pixel")
    assert (nyq.n_max, nyq.n_terms) == (15, 160)
    assert (pix.n_max, pix.n_terms) == (17, 180)
    # every kept wavelength is at least W_c
    assert 100e-6 / 1.5**nyq.n_max >= nyq.Wc > 100e-6 / 1.5 ** (nyq.n_max + 1)


@pytest.mark.parametrize(
    "kw, match",
    [
        ({"D": 2.0}, "D must be in \\(2, 3\\)"),
        ({"D": 3.2}, "D must be in"),
        ({"D": float("nan")}, "D must be in"),
        ({"gamma": 1.0}, "gamma must be in"),
        ({"M": 0}, "M must be an integer in"),
        ({"L": -1e-3}, "L must be in"),
        ({"L": (1e-3, 0.0)}, "L \\(y\\) must be in"),
        ({"n": 0}, "n must be an integer"),
        ({"n": (64, 1)}, "n \\(y\\) must be an integer"),
        ({"Wr": 0.0}, "Wr must be in"),
        ({"Wc": 200e-6}, "Wc must be in"),
        ({"Wc": 100e-6}, "Wc must be in"),
        ({"Rt": -1.0}, "Rt must be in"),
        ({"Rt": 1e-6, "G": 1e-9}, "either Rt"),
        ({"Rt": None}, "give Rt"),
        ({"cutoff": "half"}, "cutoff must be"),
        ({"n": 16, "Wr": 1e-4, "L": 1e-3}, "cut-off W_c"),
    ],
)
def test_bad_input_raises(kw, match):
    args = {"D": 2.5, "Wr": 100e-6, "n": 64} | kw
    with pytest.raises(ValueError, match=match):
        wm_surface(args.pop("D"), args.pop("Wr"), device="cpu", **args)


def test_too_large_for_memory_raises_before_allocating():
    with pytest.raises(MemoryError, match=r"needs .* GiB .* only .* GiB is free"):
        wm_surface(2.5, 100e-6, L=1.0, n=1 << 20, device="cpu")


@pytest.mark.parametrize("suffix", [".npz", ".npy"])
def test_save_load_round_trip(tmp_path, suffix):
    s = wm_surface(2.3, 80e-6, L=(1e-3, 0.5e-3), n=(64, 32), seed=2, device="cpu")
    path = warptrunc.write_height_map(s, tmp_path / f"s{suffix}")
    t = read_height_map(path)
    np.testing.assert_array_equal(t.heights, s.heights)
    assert (t.dx, t.dy) == (s.dx, s.dy)
    assert {k: t.params[k] for k in s.params} == s.params  # kept; the reader adds its source
    assert math.isclose(t.lx, 1e-3) and math.isclose(t.ly, 0.5e-3)


def test_cpu_and_cuda_surfaces_agree():
    import warp as wp

    if wp.get_cuda_device_count() == 0:
        pytest.skip("no CUDA device")
    kw = {"L": (1e-3, 0.7e-3), "n": (512, 384), "seed": 11}
    a = wm_surface(2.5, 100e-6, device="cpu", **kw).heights
    b = wm_surface(2.5, 100e-6, device="cuda:0", **kw).heights
    assert np.abs(a - b).max() / np.ptp(a) <= 1e-5


@pytest.mark.parametrize("n", [64, (96, 80), 200])
@pytest.mark.parametrize("seed", [0, 3])
def test_recorded_extremes_equal_the_map(device, n, seed):
    """The generator's (min, max), derived from the raw sum's extremes without a pass over the
    scaled map, equal NumPy's min and max of the heights bit for bit (they set the truncation
    thresholds, so an ulp off would change counts)."""
    for kw in ({"Rt": 10e-6}, {"Rt": None, "G": 1e-9}):
        s = wm_surface(2.4, 50e-6, L=1e-3, n=n, seed=seed, device=device, **kw)
        lo, hi = s.extremes()  # recorded by the generator, no pass over the map
        assert np.float32(lo) == s.heights.min() and np.float32(hi) == s.heights.max()


def test_content_fixed_by_the_surface_a_finer_grid_samples_the_same_map():
    """With W_c given as a length and R_t measured on the grid of ``Rt_pixel``, the height scale
    is that grid's: 2N² and 4N² maps over the same L equal the N² map where their pixels
    coincide, bit for bit (the same terms, phases and scale; the sums in the same order)."""
    from warptrunc.wm_params import WMSpec

    spec = WMSpec(D=2.4, Wr=1e-4, L=1e-3, n=128, Rt=10e-6, Wc=2e-3 / 128, Rt_pixel=1e-3 / 128,
                  seed=1)  # fmt: skip
    ref = wm_surface(spec, device="cpu")
    assert np.ptp(ref.heights) == pytest.approx(10e-6, rel=1e-6)  # R_t at the reference pixel
    for f in (2, 4):
        fine = wm_surface(spec.replace(n=128 * f), device="cpu")
        assert fine.params["scale"] == ref.params["scale"]
        np.testing.assert_array_equal(fine.heights[::f, ::f], ref.heights)
        assert np.ptp(fine.heights) >= np.ptp(ref.heights)  # finer samples, same surface
    # without Rt_pixel each grid is scaled to its own R_t (the paper's procedure)
    own = wm_surface(spec.replace(n=256, Rt_pixel=None), device="cpu")
    assert np.ptp(own.heights) == pytest.approx(10e-6, rel=1e-6)


def test_rt_pixel_streamed_equals_in_memory():
    from warptrunc.wm_params import WMSpec

    spec = WMSpec(D=2.3, Wr=1e-4, L=1e-3, n=192, Rt=5e-6, Wc=2e-3 / 96, Rt_pixel=1e-3 / 96)
    mem = wm_surface(spec, device="cpu")
    from warptrunc import truncate

    a = truncate(mem, 40, max_depth_fraction=0.3, device="cpu")
    b = truncate(spec.terms(), 40, max_depth_fraction=0.3, stream=True, band_rows=16, device="cpu")
    np.testing.assert_array_equal(a.n_contact_pixels, b.n_contact_pixels)
