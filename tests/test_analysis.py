# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The whole analysis of ``warptrunc analyze`` as a library call, against NumPy and SciPy."""

import math

import numpy as np
import pytest
from scipy import ndimage

from warptrunc.analysis import FitRangeError, analyze
from warptrunc.material import Material
from warptrunc.surface import from_heights
from warptrunc.truncation.settings import FitRange, TruncationSettings

DX = 1e-6

T50 = TruncationSettings(increments=50)


def _bumps(n: int = 64) -> np.ndarray:
    """Separated Gaussian bumps of different heights on a tilted floor: several islands."""
    y, x = np.mgrid[0:n, 0:n] * 1.0
    z = 1e-9 * (x + 0.5 * y)  # breaks ties between pixels
    for cx, cy, h in ((12, 14, 3.0), (44, 16, 2.6), (20, 46, 2.8), (48, 48, 2.2)):
        z += h * 1e-6 * np.exp(-((x - cx) ** 2 + (y - cy) ** 2) / 30.0)
    return z


def _trapezoid(k, w):
    return np.concatenate([[0.0], np.cumsum(0.5 * (k[1:] + k[:-1]) * np.diff(w))])


def test_analysis_matches_numpy_and_scipy(device):
    z = _bumps()
    mat = Material(E=100e9, nu=0.3)
    a = analyze(
        from_heights(z, DX),
        material=mat,
        device=device,
        truncation=TruncationSettings(60, max_depth_fraction=0.5, beta_prime=1.1, connectivity=4),
        fit=FitRange(min_pixels=3),
    )
    z32 = z.astype(np.float32)
    A, pa = z.size * DX * DX, DX * DX
    # counts: z ≥ threshold on the same float32 heights and thresholds (exact)
    n = np.count_nonzero(z32[None] >= a.curve.threshold[:, None, None], axis=(1, 2))
    np.testing.assert_array_equal(a.curve.n_contact_pixels, n)
    # Eq. 2, k = β'(2/√π)E*√A_c, and F by the trapezoidal rule
    k = 1.1 * 2 / math.sqrt(math.pi) * (100e9 / (1 - 0.09)) * np.sqrt(n * pa)
    np.testing.assert_allclose(a.stiffness.stiffness, k, rtol=1e-12)
    np.testing.assert_allclose(a.stiffness.load, _trapezoid(k, a.curve.depth), rtol=1e-12)
    # the fit: np.polyfit over the fit range (load > 0, ≥ 3 contact pixels) of E_c/E, E the
    # Young's modulus: E_c/E = (E*/E)·β′·√(A_c/A), E*/E = 1/(1 − ν²) against a rigid flat
    sel = (a.stiffness.load > 0) & (n >= 3)
    slope, icpt = np.polyfit(
        np.log(a.stiffness.load[sel] / (100e9 * A)),
        np.log(1.1 * np.sqrt(n[sel] * pa / A) / (1 - 0.09)),
        1,
    )
    assert a.fit.alpha == pytest.approx(slope, rel=1e-9)
    assert a.fit.beta == pytest.approx(math.exp(icpt), rel=1e-9)
    assert a.fit.beta_contact_modulus == pytest.approx(math.exp(icpt) * (1 - 0.09), rel=1e-9)
    # the island-resolved model: Σ√A_i over scipy's 4-connected labels
    k_isl = np.empty_like(k)
    for i, t in enumerate(a.curve.threshold):
        lab, m = ndimage.label(z32 >= t)
        sizes = np.bincount(lab.ravel(), minlength=m + 1)[1:]
        k_isl[i] = 1.1 * 2 / math.sqrt(math.pi) * (100e9 / 0.91) * np.sqrt(sizes * pa).sum()
    # rtol: Σ√n_i is accumulated on the device in its own order, then scaled by √(pixel area)
    np.testing.assert_allclose(a.islands.stiffness, k_isl, rtol=1e-9)
    assert a.islands_fit is not None and a.connectivity == 4
    cols = a.to_dict()
    np.testing.assert_array_equal(cols["stiffness_islands_N_per_m"], a.islands.stiffness)
    s = a.summary()
    assert s["path"] == "in-memory" and s["islands"]["connectivity"] == 4
    assert s["alpha"] == a.fit.alpha and s["surface"]["nx"] == 64


def test_islands_off_and_empty_fit_range():
    s = from_heights(_bumps(), DX)
    a = analyze(
        s,
        truncation=TruncationSettings(40, max_depth_fraction=0.5, islands=False),
        fit=FitRange(min_pixels=3),
        device="cpu",
    )
    assert a.islands is None and a.summary()["islands"] is None
    assert "stiffness_islands_N_per_m" not in a.to_dict()
    with pytest.raises(FitRangeError, match="increments in the fit range") as e:
        analyze(
            s,
            truncation=TruncationSettings(40, max_depth_fraction=0.5),
            fit=FitRange(min_pixels=10**6),
            device="cpu",
        )
    assert e.value.surface is s  # the surface to advise a fit range on


def test_streamed_wm_surface_equals_in_memory():
    wm = dict(D=2.3, Wr=100e-6, L=1e-3, n=64, Rt=10e-6, seed=3)
    mem = analyze(wm, truncation=T50, stream=False, fit=FitRange(min_pixels=1), device="cpu")
    st = analyze(
        wm,
        truncation=T50,
        stream=True,
        band_rows=16,
        fit=FitRange(min_pixels=1),
        progress=False,
        device="cpu",
    )
    np.testing.assert_array_equal(mem.curve.n_contact_pixels, st.curve.n_contact_pixels)
    assert st.path["path"] == "streamed" and st.islands is None
    assert st.fit == mem.fit
    with pytest.raises(ValueError, match="islands=True needs the map in memory"):
        analyze(wm, truncation=T50.replace(islands=True), stream=True, device="cpu")
    with pytest.raises(ValueError, match="rt_percentile needs the map in memory"):
        analyze(
            wm, truncation=T50, stream=True, fit=FitRange(rt_percentile=(0.1, 99.9)), device="cpu"
        )
    with pytest.raises(ValueError, match="stream=True applies to generated surfaces"):
        analyze(from_heights(_bumps(), DX), truncation=T50, stream=True, device="cpu")
