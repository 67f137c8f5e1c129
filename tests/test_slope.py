# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Slope and curvature (warptrunc.slope) against closed forms: a sinusoid's and a paraboloid's
finite differences summed by hand, a sinusoid's spectral slope, and a WM surface's finite
differences against the moments of its own terms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from warptrunc.slope import SMALL_SLOPE_LIMIT, check_slope, slope_statistics, wm_slope_statistics
from warptrunc.surface import from_heights

L, N = 1e-3, 256
DX = L / N


def _sinusoid(a=1e-6, periods=4):
    k = 2 * np.pi * periods / L
    x = np.arange(N) * DX
    z = np.broadcast_to(a * np.sin(k * x), (N, N))
    return from_heights(np.ascontiguousarray(z), DX), a, k


def test_sinusoid_finite_differences_equal_their_closed_form():
    s, a, k = _sinusoid()
    st = slope_statistics(s)
    # forward differences 2a·cos(k(x + dx/2))·sin(k·dx/2)/dx over the nx − 1 pairs of a row: the
    # squared cosine sums to nx/2 over all nx pairs of whole periods, less the wrap pair's cos²(k dx/2)
    mean_cos2 = (N / 2 - math.cos(k * DX / 2) ** 2) / (N - 1)
    want = 2 * a * math.sin(k * DX / 2) / DX * math.sqrt(mean_cos2)
    assert st.slope_rms == pytest.approx(want, rel=1e-7)  # float32 heights, float64 sums
    # → a·k/√2 as dx → 0 and nx → ∞ (here 16 pixels per period: 0.24 % below)
    assert st.slope_rms == pytest.approx(a * k / math.sqrt(2), rel=5e-3)
    # five-point Laplacian a·sin(kx)(2cos(k dx) − 2)/dx² on columns 1..nx − 2
    mean_sin2 = (N / 2 - math.sin(k * DX) ** 2) / (N - 2)
    lap = a * (2 - 2 * math.cos(k * DX)) / DX**2 * math.sqrt(mean_sin2)
    assert st.curvature_rms == pytest.approx(lap, rel=1e-7)  # float32 heights, float64 sums
    assert st.h_rms == pytest.approx(a / math.sqrt(2), rel=1e-7)  # float32 heights, float64 sums


def test_sinusoid_spectrum_puts_all_slope_in_its_decade():
    s, a, k = _sinusoid(periods=4)  # λ = 250 µm: the decade [100 µm, 1 mm)
    st = slope_statistics(s)
    i = st.decade_edges.index(1e-3)
    per = np.array(st.slope_rms_per_decade)
    # the Hann window widens the line to its neighbours (q² weights them a few % more)
    assert per[i] == pytest.approx(a * k / math.sqrt(2), rel=0.03)
    assert np.all(np.delete(per, i) < 0.01 * per[i])


def test_paraboloid_equals_its_sums():
    c = 3.0  # 1/m: h = c(x² + y²)
    x = np.arange(N) * DX
    z = c * (x[None, :] ** 2 + x[:, None] ** 2)
    st = slope_statistics(from_heights(z, DX), per_decade=False)
    m = N - 1  # pairs per row: differences c·dx·(2i + 1), i = 0..m − 1
    mean_sq = c**2 * DX**2 * (2 * m - 1) * (2 * m + 1) / 3
    assert st.slope_rms == pytest.approx(math.sqrt(2 * mean_sq), rel=1e-7)  # float32 heights
    # the stencil is exact for a quadratic; second differences of float32 heights amplify their
    # rounding by (h/dx²)/(4c) ≈ 10: 10⁻⁵
    assert st.curvature_rms == pytest.approx(4 * c, rel=1e-5)


def test_wm_terms_and_finite_differences_agree_on_a_resolved_map():
    from warptrunc.wm import wm_spec, wm_surface

    # shortest wavelength 16 pixels: finite differences are within 1 % of the derivative there
    kw = {"D": 2.4, "Wr": L / 4, "L": L, "n": 512, "Rt": 5e-6, "Wc": 16 * L / 512, "seed": 3}
    s = wm_surface(**kw, device="cpu")
    fd = slope_statistics(s)
    sp = wm_slope_statistics(wm_spec(**kw), s.params["scale"])
    # the map holds the longest terms for 4 periods only: its sample of cos² differs from 1/2
    assert fd.slope_rms == pytest.approx(sp.slope_rms, rel=0.01)
    assert fd.h_rms == pytest.approx(sp.h_rms, rel=0.01)
    assert fd.curvature_rms == pytest.approx(sp.curvature_rms, rel=0.02)
    assert sum(v**2 for v in sp.slope_rms_per_decade) == pytest.approx(sp.slope_rms**2, rel=1e-12)
    # the map's windowed periodogram, decade by decade, against the terms (the long waves'
    # decade holds the map's sample of few periods)
    np.testing.assert_allclose(fd.slope_rms_per_decade[:2], sp.slope_rms_per_decade, rtol=0.06)


def test_warning_above_the_limit_only():
    s, _, _ = _sinusoid()
    st = slope_statistics(s, per_decade=False)
    assert check_slope(st) == []  # a·k/√2 ≈ 0.018
    (w,) = check_slope(st, limit=st.slope_rms / 2)
    assert w.code == "slope" and w.details["slope_rms"] == st.slope_rms
    assert SMALL_SLOPE_LIMIT == 0.5


def test_record_of_a_wm_map_has_both_methods_and_the_warning(device):
    from warptrunc.slope import slope_record, slope_warnings
    from warptrunc.wm import wm_surface

    s = wm_surface(D=2.9, Wr=L / 8, L=L, n=256, Rt=20e-6, seed=0, device=device)
    rec = slope_record(s)
    assert rec["method"] == "finite differences"
    assert rec["finite_differences"]["slope_rms"] == rec["slope_rms"]
    assert rec["spectrum"]["method"] == "spectrum"
    # a steep map (D near 3, 2-pixel cut-off) is outside the small-slope range: one warning
    assert rec["slope_rms"] > 0.5 and rec["small_slope"] is False
    (w,) = slope_warnings(rec)
    assert w.code == "slope"
    cpu = slope_record(wm_surface(D=2.9, Wr=L / 8, L=L, n=256, Rt=20e-6, seed=0, device="cpu"))
    # the same map on every device to float32 rounding (the GPU's tile product sums in another order)
    assert rec["slope_rms"] == pytest.approx(cpu["slope_rms"], rel=1e-6)
    # a streamed map has no map: the spectrum alone
    only = slope_record(params=s.to_dict())
    assert only["method"] == "spectrum" and only["finite_differences"] is None
