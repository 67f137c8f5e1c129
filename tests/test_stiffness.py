# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stiffness, load and the power-law fit against closed forms."""

import math

import numpy as np
import pytest

from warptrunc.stiffness import (
    Material,
    StiffnessCurve,
    fit_power_law,
    flat_punch_stiffness,
    stiffness_curve,
)
from warptrunc.truncation import TruncationCurve


def curve_from_area(depth, area, A=1e-6, pixel_area=1e-12):
    n = np.round(np.asarray(area) / pixel_area).astype(np.int64)
    return TruncationCurve(
        depth=np.asarray(depth, float),
        threshold=np.zeros(len(depth), np.float32),
        n_contact_pixels=n,
        contact_area=np.asarray(area, float),
        apparent_area=A,
        pixel_area=pixel_area,
        n_pixels=int(A / pixel_area),
        z_top=0.0,
        Rt=float(depth[-1]) * 10,
    )


def test_contact_modulus():
    assert Material(E=200e9, nu=0.3).contact_modulus == pytest.approx(200e9 / (1 - 0.09))
    m = Material(E=70e9, nu=0.33, E_i=1141e9, nu_i=0.07)  # aluminium on diamond
    assert m.contact_modulus == pytest.approx(1 / ((1 - 0.33**2) / 70e9 + (1 - 0.07**2) / 1141e9))


def test_eq2_eq3_and_trapezoid_load():
    # A_c = c·ω² → k = β'(2/√π)E_r'·√c·ω is linear in ω, so the trapezoidal rule is exact:
    # F = β'(2/√π)E_r'·√c·ω²/2
    depth = np.linspace(0, 1e-6, 11)
    c = 4.0
    mat = Material(E=100e9, nu=0.25)
    sc = stiffness_curve(curve_from_area(depth, c * depth**2), mat, beta_prime=1.2)
    k_expected = 1.2 * 2 / math.sqrt(math.pi) * mat.contact_modulus * math.sqrt(c) * depth
    np.testing.assert_allclose(sc.stiffness, k_expected, rtol=1e-12, atol=1e-30)
    np.testing.assert_allclose(sc.load, k_expected * depth / 2, rtol=1e-12, atol=1e-30)
    Estar_over_E = 1 / (1 - 0.25**2)  # rigid flat
    np.testing.assert_allclose(sc.Ec_over_Estar, 1.2 * np.sqrt(c * depth**2 / 1e-6), rtol=1e-12)
    np.testing.assert_allclose(sc.Ec_over_E, Estar_over_E * sc.Ec_over_Estar, rtol=1e-14)
    np.testing.assert_allclose(sc.F_over_EA, sc.load / (100e9 * 1e-6), rtol=1e-12)


@pytest.mark.parametrize("alpha,beta", [(0.5, 2.0), (0.62, 35.0), (0.9, 0.1)])
def test_fit_recovers_exact_power_law(alpha, beta):
    f = np.geomspace(1e-8, 1e-3, 60)
    n = np.arange(60, dtype=np.int64) + 1
    z = np.zeros(60)
    sc = StiffnessCurve(
        depth=np.linspace(1e-9, 1e-6, 60),
        n_contact_pixels=n * 1000,
        contact_area=z,
        stiffness=z,
        load=f,
        Ec_over_E=beta * f**alpha,
        F_over_EA=f,
        Ec_over_Estar=z,
        material=Material(),
        beta_prime=1.0,
        apparent_area=1.0,
        Rt=1e-5,
    )
    fit = fit_power_law(sc, min_pixels=1)
    assert fit.alpha == pytest.approx(alpha, rel=1e-10)
    assert fit.beta == pytest.approx(beta, rel=1e-10)  # the fitted column is E_c/E
    assert fit.beta == pytest.approx(beta, rel=1e-9)
    assert fit.r2 == pytest.approx(1.0)
    assert fit.n_points == 60


def test_fit_range_selection():
    depth = np.linspace(0, 1e-6, 101)
    area = 1e-12 * np.round(1 + 1e4 * (depth / 1e-6) ** 2)  # 1 … 10001 pixels
    sc = stiffness_curve(curve_from_area(depth, area))
    all_ = fit_power_law(sc, min_pixels=1)
    assert all_.n_points == 100  # every increment with non-zero load
    big = fit_power_law(sc, min_pixels=1000)
    assert big.n_points == int(np.count_nonzero(sc.n_contact_pixels[1:] >= 1000))
    assert big.depth_min >= 0.3e-6
    win = fit_power_law(sc, min_pixels=1, depth_window=(0.5e-6, 0.8e-6))
    sel = (depth >= 0.5e-6) & (depth <= 0.8e-6)
    assert win.n_points == int(sel.sum())
    assert (win.depth_min, win.depth_max) == (depth[sel].min(), depth[sel].max())
    with pytest.raises(ValueError, match="only 0 increments"):
        fit_power_law(sc, min_pixels=10**9)
    with pytest.raises(ValueError, match="depth_window"):
        fit_power_law(sc, depth_window=(1e-6, 0.5e-6))


@pytest.mark.parametrize(
    "kw, match",
    [({"E": 0.0}, "E must be in"), ({"nu": 0.6}, "nu must be in"), ({"E_i": -1.0}, "E_i must be")],
)
def test_bad_material_raises(kw, match):
    with pytest.raises(ValueError, match=match):
        Material(**kw)


def test_csv_and_json_export(tmp_path):
    depth = np.linspace(0, 1e-6, 21)
    sc = stiffness_curve(curve_from_area(depth, 1e-12 * (1 + np.round(1e3 * depth / 1e-6))))
    p = sc.to_csv(tmp_path / "c.csv")
    data = np.genfromtxt(p, delimiter=",", names=True)
    assert data.dtype.names == (
        "depth_m",
        "n_contact_pixels",
        "contact_area_m2",
        "stiffness_N_per_m",
        "load_N",
        "Ec_over_E",
        "F_over_EA",
        "Ec_over_Estar",
    )
    np.testing.assert_allclose(data["Ec_over_E"], data["Ec_over_Estar"] / (1 - 0.33**2), rtol=1e-14)
    np.testing.assert_array_equal(data["load_N"], sc.load)
    fit = fit_power_law(sc, min_pixels=1)
    import json

    d = json.loads(fit.to_json(tmp_path / "f.json").read_text())
    assert d["alpha"] == fit.alpha and d["min_pixels"] == 1


def test_curve_json_export(tmp_path):
    import json

    depth = np.linspace(0, 1e-6, 5)
    sc = stiffness_curve(curve_from_area(depth, 1e-12 * np.arange(1, 6)))
    d = json.loads(sc.to_json(tmp_path / "c.json").read_text())
    assert d["load_N"] == sc.load.tolist() and d["material"]["E"] == 70e9


def _paraboloid_tile(n=40, R=1e-3, dx=1e-6):
    """One paraboloid cap z = h − r²/(2R) on an n² tile, floored at 0, centred in the tile
    (float32, m)."""
    x = (np.arange(n) - (n - 1) / 2) * dx
    r2 = x[None, :] ** 2 + x[:, None] ** 2
    h = ((n / 2 - 2) * dx) ** 2 / (2 * R)  # the cap ends 2 pixels inside the tile
    return np.maximum(h - r2 / (2 * R), 0.0).astype(np.float32), dx


@pytest.mark.parametrize("tiles", [(1, 1), (2, 3), (4, 4)])
def test_separate_paraboloids_islands_vs_eq2(device, tiles):
    """N identical, separate paraboloids: island-resolved k is N × that of one, Eq. 2's is √N ×
    (Σ√A_i = N√a, √ΣA_i = √N·√a); loads scale alike. Exact up to float64 rounding."""
    from warptrunc.islands import island_curve
    from warptrunc.stiffness import island_stiffness_curve
    from warptrunc.surface import from_heights
    from warptrunc.truncation import TruncationSettings, truncate

    tile, dx = _paraboloid_tile()
    N = tiles[0] * tiles[1]
    one = from_heights(tile, dx)
    many = from_heights(np.tile(tile, tiles), dx)
    # islands stay apart below R_t
    kw = dict(truncation=TruncationSettings(increments=30, max_depth_fraction=0.9), device=device)
    ic1, icN = island_curve(one, **kw), island_curve(many, **kw)
    assert np.all(icN.n_islands[1:] == N)
    k1 = island_stiffness_curve(ic1)
    kN = island_stiffness_curve(icN)
    eN = stiffness_curve(truncate(many, 30, max_depth_fraction=0.9, device=device))
    np.testing.assert_allclose(kN.stiffness, N * k1.stiffness, rtol=1e-9)
    np.testing.assert_allclose(kN.load, N * k1.load, rtol=1e-9)
    np.testing.assert_allclose(eN.stiffness, math.sqrt(N) * k1.stiffness, rtol=1e-9)
    np.testing.assert_allclose(eN.load, math.sqrt(N) * k1.load, rtol=1e-9)
    # one island: both models agree; E_c/E* of the islands model is k/((2/√π)E*√A), and
    # E_c/E = E_c·(√π/2)/(E·√A) = k/((2/√π)E√A) with E the Young's modulus
    e1 = stiffness_curve(truncate(one, 30, max_depth_fraction=0.9, device=device))
    np.testing.assert_allclose(k1.stiffness, e1.stiffness, rtol=1e-9)
    c = 2 / math.sqrt(math.pi) * kN.material.contact_modulus * math.sqrt(kN.apparent_area)
    np.testing.assert_allclose(kN.Ec_over_Estar, kN.stiffness / c, rtol=1e-12)
    c_young = 2 / math.sqrt(math.pi) * kN.material.E * math.sqrt(kN.apparent_area)
    np.testing.assert_allclose(kN.Ec_over_E, kN.stiffness / c_young, rtol=1e-12)
    assert kN.model == "islands" and eN.model == "area"


# --- one Eq. 2, two normalisations, one fit -----------------------------------------------------


@pytest.mark.parametrize("beta_prime", [1.0, 1.034])
def test_flat_punch_stiffness_is_eq2(beta_prime):
    """k = β'(2/√π)E*√A, and for a circular punch of radius a Sneddon's k = 2E*a."""
    Estar = Material.against_diamond().contact_modulus
    a = np.array([1e-6, 3e-5, 2e-4])
    area = math.pi * a**2
    k = flat_punch_stiffness(np.sqrt(area), Estar, beta_prime=beta_prime)
    np.testing.assert_allclose(k, beta_prime * 2.0 * Estar * a, rtol=1e-15)
    assert flat_punch_stiffness(1e-3, 1e9) == pytest.approx(2e6 / math.sqrt(math.pi), rel=1e-15)
    with pytest.raises(ValueError, match="contact_modulus"):
        flat_punch_stiffness(1e-3, -1.0)
    with pytest.raises(ValueError, match="beta_prime"):
        flat_punch_stiffness(1e-3, 1e9, beta_prime=0.0)


@pytest.mark.parametrize(
    "mat, ratio",
    [
        (Material(), 1 / (1 - 0.33**2)),  # rigid flat: E*/E = 1/(1 − ν²) = 1.12
        (Material.against_diamond(), 1 / (1 - 0.33**2 + (1 - 0.07**2) * 70 / 1141)),
    ],  # 1.05
)
def test_two_normalisations_differ_by_Estar_over_E(mat, ratio):
    """For a known A_c/A: E_c/E* = β'·√(A_c/A) and E_c/E = (E*/E)·β'·√(A_c/A), closed forms."""
    depth = np.linspace(0, 1e-6, 11)
    frac = np.linspace(0, 0.3, 11)  # A_c/A
    sc = stiffness_curve(curve_from_area(depth, frac * 1e-6), mat, beta_prime=1.1)
    np.testing.assert_allclose(sc.Ec_over_Estar, 1.1 * np.sqrt(frac), rtol=1e-14)
    np.testing.assert_allclose(sc.Ec_over_E, ratio * 1.1 * np.sqrt(frac), rtol=1e-14)
    np.testing.assert_allclose(sc.Ec_over_E[1:] / sc.Ec_over_Estar[1:], ratio, rtol=1e-15)
    assert round(ratio, 2) == (1.12 if math.isinf(mat.E_i) else 1.05)


def test_fit_reports_both_betas():
    """α is the same on E_c/E and E_c/E*; ``beta`` is that of E_c/E (E the Young's modulus, as
    the paper's Fig. 6 and 9), β* = β·E/E*; the fit says which β it is."""
    depth = np.linspace(0, 1e-6, 41)
    mat = Material(E=200e9, nu=0.3)
    sc = stiffness_curve(curve_from_area(depth, 1e-12 * np.round(1e6 * (depth / 1e-6) ** 1.7)), mat)
    fit = fit_power_law(sc, min_pixels=1)
    assert fit.normalisation == "E_c/E"
    assert fit.beta_contact_modulus == pytest.approx(fit.beta * (1 - 0.3**2), rel=1e-14)
    sel = sc.load > 0
    # independent: numpy's least squares on E_c/E = β′√(A_c/A)/(1 − ν²) built here from the areas
    y_young = np.sqrt(sc.contact_area[sel] / sc.apparent_area) / (1 - 0.3**2)
    slope, icpt = np.polyfit(np.log(sc.F_over_EA[sel]), np.log(y_young), 1)
    assert fit.alpha == pytest.approx(slope, rel=1e-10)
    assert fit.beta == pytest.approx(math.exp(icpt), rel=1e-10)
    slope_s, icpt_s = np.polyfit(np.log(sc.F_over_EA[sel]), np.log(sc.Ec_over_Estar[sel]), 1)
    assert fit.alpha == pytest.approx(slope_s, rel=1e-10)
    assert fit.beta_contact_modulus == pytest.approx(math.exp(icpt_s), rel=1e-10)
    d = fit.to_dict()
    assert d["normalisation"] == "E_c/E" and "beta_contact_modulus" in d and "r" not in d
    assert "beta_young" not in d


def test_old_fit_json_is_read_with_its_meaning():
    """A fit.json written before the one normalisation held β of E_c/E* in ``beta`` (and that
    of E_c/E in ``beta_young``, ``normalisation`` "E_c/E*"): read back, ``beta`` is E_c/E's."""
    from warptrunc.stiffness import NORMALISATION_E, NORMALISATION_ESTAR, PowerLawFit

    old = {
        "alpha": 0.53,
        "beta": 6.5,
        "r2": 0.97,
        "n_points": 142,
        "depth_min": 2.9e-7,
        "depth_max": 1e-6,
        "F_over_EA_min": 1.4e-6,
        "F_over_EA_max": 1e-5,
        "min_pixels": 10,
        "depth_window": None,
        "beta_young": 7.3,
        "normalisation": NORMALISATION_ESTAR,
        "surface": {"nx": 512},
        "provenance": {},
    }
    f = PowerLawFit.from_dict(old)
    assert (f.beta, f.beta_contact_modulus, f.normalisation) == (7.3, 6.5, NORMALISATION_E)
    new = PowerLawFit.from_dict(
        {
            **old,
            "depth_window": [1e-7, 1e-6],
            "beta": 7.3,
            "beta_contact_modulus": 6.5,
            "normalisation": NORMALISATION_E,
        }
    )
    assert (new.beta, new.beta_contact_modulus, new.depth_window) == (7.3, 6.5, (1e-7, 1e-6))
    assert PowerLawFit.from_dict(new.to_dict()) == new


def test_fit_power_law_of_two_arrays():
    x = np.geomspace(1e-3, 1e2, 30)
    rng = np.random.default_rng(0)
    y = 3.0 * x**0.62 * np.exp(0.01 * rng.standard_normal(30))
    fit = fit_power_law(np.r_[x, 0.0, -1.0], np.r_[y, 1.0, 1.0])  # non-positive pairs dropped
    slope, icpt = np.polyfit(np.log(x), np.log(y), 1)
    assert fit.n_points == 30 and fit.normalisation == "y = beta*x^alpha"
    assert fit.alpha == pytest.approx(slope, rel=1e-12)
    assert fit.beta == pytest.approx(math.exp(icpt), rel=1e-12)
    r = np.corrcoef(np.log(x), np.log(y))[0, 1]
    assert fit.r == pytest.approx(r, rel=1e-12) and fit.r2 == pytest.approx(r * r, rel=1e-9)
    with pytest.raises(ValueError, match="at least 3"):
        fit_power_law([1.0, 2.0], [1.0, 2.0])
    assert fit_power_law([1.0, 2.0], [1.0, 2.0], min_points=2).alpha == pytest.approx(1.0)


def test_models_have_one_name():
    import warptrunc.stiffness as st

    assert st.STIFFNESS_MODELS == ("area", "islands")
    assert not hasattr(st, "MODELS")
