# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Slit-island fits (Eq. 5) and the applicable-depth indicators (Table 2) against NumPy least
squares and synthetic island curves of known exponent."""

import math

import numpy as np
import pytest

from warptrunc.islands import (
    IndicatorSettings,
    IslandCurve,
    applicable_depth,
    label_islands,
    slit_island_fit,
)

# --- slit-island fit and indicators -------------------------------------------------------------


def test_slit_island_fit_recovers_a_power_law():
    class Sizes:
        area_pixels = np.array([3, 12, 40, 100, 400, 900, 2500])
        area = area_pixels * 1e-12
        perimeter = 7e-3 * area**0.75

    f = slit_island_fit(Sizes, min_pixels=10)
    assert f.n_islands == 6
    assert f.exponent == pytest.approx(0.75, rel=1e-12)
    assert f.dimension == pytest.approx(2.5, rel=1e-12)
    assert f.r2 == pytest.approx(1.0, rel=1e-12)
    assert f.intercept == pytest.approx(math.log10(7e-3), rel=1e-12)
    assert math.isnan(slit_island_fit(Sizes, min_pixels=1000).exponent)
    # compact squares: L = 4·sqrt(A) gives exactly 1/2
    mask = np.zeros((12, 80), bool)
    x = 0
    for side in range(4, 10):
        mask[1 : 1 + side, x : x + side] = True
        x += side + 2
    sq = slit_island_fit(label_islands(mask, 1e-6, device="cpu"))
    assert sq.n_islands == 6
    assert sq.exponent == pytest.approx(0.5, rel=1e-12)
    assert sq.r2 == pytest.approx(1.0, rel=1e-12)


def _synthetic_curve(n_islands, exponent, Rt=1.0):
    depth = np.linspace(0, 0.5, n_islands.size) * Rt
    z = np.zeros(depth.size)
    return IslandCurve(
        depth=depth,
        n_islands=np.asarray(n_islands, np.int64),
        n_contact_pixels=z.astype(np.int64),
        contact_area=z,
        total_perimeter=z,
        euler_characteristic=z.astype(np.int64),
        slit_exponent=np.asarray(exponent, float),
        slit_r2=z + 1,
        slit_n_islands=z.astype(np.int64) + 100,
        area_histogram=np.zeros((depth.size, 4), np.int64),
        sizes=(),
        Rt=Rt,
        dx=1.0,
        dy=1.0,
        connectivity=4,
        periodic=False,
        min_pixels=10,
    )


def test_indicators_on_a_synthetic_curve():
    frac = np.linspace(0, 0.5, 101)  # steps of 0.5 % R_t
    n = np.round(1000 * np.exp(-(((frac - 0.4) / 0.1) ** 2))).astype(int)  # peak at 40 %
    beta = np.where(frac <= 0.3, 0.75, 0.75 - 2.0 * (frac - 0.3))  # drops after 30 %
    beta[:3] = np.nan  # too few islands at the top
    ind = applicable_depth(_synthetic_curve(n, beta, Rt=2e-6), IndicatorSettings(smooth=1))
    # the Gaussian's steepest rise is one standard deviation... /sqrt(2) before the peak
    assert ind.max_growth_depth / ind.Rt == pytest.approx(0.4 - 0.1 / math.sqrt(2), abs=0.006)
    assert ind.peak_depth / ind.Rt == pytest.approx(0.4)
    assert ind.plateau_exponent == pytest.approx(0.75)
    # 5 % below 0.75 is 0.7125, crossed at 30 % + 0.01875 → last depth above: 31.5 %
    assert ind.fractal_depth / ind.Rt == pytest.approx(0.315)
    assert not ind.fractal_depth_censored
    d = ind.to_dict()
    assert d["island_peak_depth_percent_Rt"] == pytest.approx(40.0)
    assert ind.plateau_range == pytest.approx((0.015, 0.115))
    flat = applicable_depth(_synthetic_curve(n, np.full(101, 0.7)))
    assert flat.fractal_depth_censored and flat.fractal_depth == pytest.approx(0.5)
    few = _synthetic_curve(n, beta)
    few.slit_n_islands[:] = 10  # too few islands everywhere: no exponent counts
    assert math.isnan(applicable_depth(few).fractal_depth)


def test_indicators_ignore_a_short_dip():
    frac = np.linspace(0, 0.5, 101)
    n = np.arange(101)
    beta = np.full(101, 0.7)
    beta[40:42] = 0.6  # 1 % R_t dip: shorter than persist = 2 %
    beta[80:] = 0.6  # a lasting drop from 40 % R_t
    ind = applicable_depth(_synthetic_curve(n, beta), IndicatorSettings(smooth=1))
    assert ind.fractal_depth == pytest.approx(frac[79])
    ind = applicable_depth(_synthetic_curve(n, beta), IndicatorSettings(smooth=1, persist=0.0))
    assert ind.fractal_depth == pytest.approx(frac[39])


def test_indicators_bad_options_raise_clear_errors():
    with pytest.raises(ValueError, match="smooth must be odd, got 4"):
        IndicatorSettings(smooth=4)
    with pytest.raises(ValueError, match=r"exponent_tolerance must be in \(0, 1\), got 1.5"):
        IndicatorSettings(exponent_tolerance=1.5)
