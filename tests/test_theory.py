# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""warptrunc.theory: the isotropic PSD and its moments, Persson's theory, GW and BGT, each
against something independent (closed forms, scipy quadrature, numpy maps of known spectrum,
invariants)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy import integrate
from scipy.special import erf

from warptrunc import Material, WMSpec
from warptrunc.selfaffine import SelfAffineSpec
from warptrunc.slope import wm_slope_statistics
from warptrunc.theory import (
    KAPPA_BGT,
    KAPPA_PERSSON,
    IsotropicPSD,
    bgt_summit_weights,
    bush_gibson_thomas,
    greenwood_williamson,
    nayak_summits,
    persson_contact,
    persson_gap_distribution,
    persson_pressure_distribution,
    self_affine_c0,
)

MAT = Material(E=70e9, nu=0.33)
ESTAR = MAT.contact_modulus


def _spec(
    H=0.5, q_L=None, q_r=2 * math.pi / 100e-6, q_s=2 * math.pi / 2e-6, h_rms=None, slope_rms=None
):
    """The self-affine spectrum of wavevectors q_L ≤ q_r < q_s (1/m; q_L None: no roll-off) as
    the surface's spec: the side L = 2π/q_L and enough pixels for λ_s (the grid does not enter
    the continuous spectrum)."""
    q_l = q_r if q_L is None else q_L
    L = 2 * math.pi / q_l
    n = min(1 << 20, 2 * math.ceil(L * q_s / (2 * math.pi)) + 2)
    return SelfAffineSpec(
        hurst=H,
        L=L,
        n=n,
        rolloff=None if q_L is None else 2 * math.pi / q_r,
        short_cutoff=2 * math.pi / q_s,
        rms_height=h_rms,
        rms_slope=slope_rms,
    )


def _c_self_affine(q, c0, H, q_l, q_r, q_s):
    """The self-affine C(q) written out (m⁴)."""
    if q < q_l or q > q_s:
        return 0.0
    return c0 if q < q_r else c0 * (q / q_r) ** (-2 * (1 + H))


def _quad_moment(k, c, q_l, q_r, q_s):
    """2π ∫ q^(k+1) C dq by adaptive quadrature, split at the kink."""
    f = lambda q: 2 * math.pi * q ** (k + 1) * c(q)  # noqa: E731
    return sum(
        integrate.quad(f, a, b, epsabs=0, epsrel=1e-13, limit=200)[0]
        for a, b in ((q_l, q_r), (q_r, q_s))
        if b > a
    )


# --- the PSD ---------------------------------------------------------------------------------


@pytest.mark.parametrize("H", [0.3, 0.8, 1.0])
def test_self_affine_moments_against_closed_form_integrals(H):
    q_l, q_r, q_s = 2e4, 1e5, 3e7
    spec = _spec(H=H, q_L=q_l, q_r=q_r, q_s=q_s, h_rms=2e-6)
    psd = IsotropicPSD.from_self_affine(spec)
    c = lambda q: _c_self_affine(q, self_affine_c0(spec), H, q_l, q_r, q_s)  # noqa: E731
    # the normalisation: ⟨h²⟩ = 2π ∫ q C dq = h_rms² (Persson's convention)
    assert psd.h_rms == pytest.approx(2e-6, rel=1e-12)
    assert _quad_moment(0, c, q_l, q_r, q_s) == pytest.approx(4e-12, rel=1e-9)
    for k, value in ((2, psd.slope_rms**2), (4, psd.curvature_rms**2)):
        assert value == pytest.approx(_quad_moment(k, c, q_l, q_r, q_s), rel=1e-9)
    assert psd.m2 == pytest.approx(psd.slope_rms**2 / 2, rel=1e-14)
    assert psd.m4 == pytest.approx(3 * psd.curvature_rms**2 / 8, rel=1e-14)
    by_slope = IsotropicPSD.from_self_affine(spec.replace(rms_height=None, rms_slope=0.2))
    assert by_slope.slope_rms == pytest.approx(0.2, rel=1e-12)


def test_psd_interpolant_band_and_refinement_keep_the_integrals():
    psd = IsotropicPSD.from_self_affine(_spec(q_L=1e4), points_per_decade=4)
    fine = psd.refined(100)
    assert fine.wavevector.size > 5 * psd.wavevector.size
    for k in (0, 2, 4):
        assert fine.moment(k) == pytest.approx(psd.moment(k), rel=1e-12)
    q = np.geomspace(psd.wavevector[0], psd.wavevector[-1], 50)
    np.testing.assert_allclose(fine.at(q), psd.at(q), rtol=1e-12)
    lo, hi = 3e4, 2e5
    part = psd.band(lo, hi)
    cum = np.interp([lo, hi], fine.wavevector, fine.cumulative_moment(2))
    assert part.moment(2) == pytest.approx(cum[1] - cum[0], rel=1e-3)  # interp of the cumulative
    assert psd.at(psd.wavevector[-1] * 1.01) == 0.0


def _random_map(psd: IsotropicPSD, n: int, dx: float, seed: int) -> np.ndarray:
    """A periodic Gaussian map of spectrum ``psd`` by numpy: |h_q|² = C(q) (2π/L)²."""
    rng = np.random.default_rng(seed)
    qx = 2 * np.pi * np.fft.fftfreq(n, dx)
    amp = np.sqrt(psd.at(np.hypot(qx[:, None], qx[None, :]))) * (2 * np.pi / (n * dx))
    hq = amp * (rng.normal(size=(n, n)) + 1j * rng.normal(size=(n, n)))
    return np.real(np.fft.ifft2(hq)) * n * n


def test_height_map_estimate_and_noise_floor():
    n, dx = 256, 1e-6
    q_nyq = math.pi / dx
    spec = _spec(
        H=0.5, q_L=2 * math.pi / (n * dx), q_r=2 * math.pi / (n * dx / 4), q_s=q_nyq, h_rms=1e-6
    )
    ref = IsotropicPSD.from_self_affine(spec)
    z = _random_map(ref, n, dx, seed=0)
    est = IsotropicPSD.from_height_map(z, dx, window="none")
    assert est.source == "height map" and est.interpolation == "linear"
    # variance: the annuli up to the Nyquist circle hold all of it (the spectrum stops there)
    assert est.h_rms == pytest.approx(float(np.std(z)), rel=0.02)
    # the estimate follows C(q) in log bins of a fifth of a decade (hundreds of modes each)
    edges = np.geomspace(2 * spec.grid()["q_roll"], q_nyq / 2, 8)
    for a, b in itertools.pairwise(edges):
        m = (est.wavevector >= a) & (est.wavevector < b)
        assert np.mean(est.psd[m]) == pytest.approx(np.mean(ref.at(est.wavevector[m])), rel=0.15)
    assert est.noise_wavevector == pytest.approx(q_nyq / 2)  # no noise: the 4-pixel bound
    # white noise of variance σ² has C = σ² dx²/(2π)²; with C(q_c) that level, the variance per
    # half decade has its minimum at q = q_c H^(1/(2 + 2H)) = 0.79 q_c (0.05-decade steps)
    rng = np.random.default_rng(1)
    for q_c in (3e5, 6e5):
        sigma = 2 * math.pi / dx * math.sqrt(float(ref.at(q_c)))
        noisy = IsotropicPSD.from_height_map(z + sigma * rng.normal(size=z.shape), dx)
        assert 0.6 * q_c <= noisy.noise_wavevector <= 1.1 * q_c


def test_wm_spectrum_against_its_line_sums():
    spec = WMSpec(n=256, Rt=None, G=1e-9)
    psd = IsotropicPSD.from_wm(spec)
    H, lg = 3 - spec.D, math.log(spec.gamma)
    scale = psd.params["scale"]
    lines = wm_slope_statistics(spec.terms(), scale)
    factor = lambda k: math.sinh((k - 2 * H) * lg / 2) / ((k - 2 * H) * lg / 2)  # noqa: E731
    assert psd.h_rms**2 == pytest.approx(lines.h_rms**2 * factor(0), rel=1e-10)
    assert psd.slope_rms**2 == pytest.approx(lines.slope_rms**2 * factor(2), rel=1e-10)
    assert psd.curvature_rms**2 == pytest.approx(lines.curvature_rms**2 * factor(4), rel=1e-10)


@pytest.fixture(scope="module")
def wm_map():
    from warptrunc.wm import wm_surface

    return wm_surface(WMSpec(n=256, seed=3), device="cpu")


def test_wm_spectrum_against_the_map_estimate(wm_map):
    spec_psd = IsotropicPSD.from_wm(wm_map)
    est = IsotropicPSD.from_height_map(wm_map)
    # the variance of each ring's share of ln q, [q_n γ^(−1/2), q_n γ^(1/2)]: the map holds ten
    # periods of the longest ring and the Hann window spreads each line over a few annuli
    # (measured 0.96–1.04 on three seeds), so 6 %
    p = wm_map.params
    edges = 2 * math.pi / p["Wr"] * p["gamma"] ** (np.arange(-1, 2 * p["n_max"] + 2, 2) / 2)
    edges = edges[edges <= est.wavevector[-1]]
    ring = lambda s: np.diff(np.interp(edges, s.wavevector, s.cumulative_moment(0)))  # noqa: E731
    np.testing.assert_allclose(ring(est), ring(spec_psd), rtol=0.06)
    assert est.h_rms == pytest.approx(spec_psd.h_rms, rel=0.02)
    assert est.slope_rms == pytest.approx(spec_psd.slope_rms, rel=0.02)
    assert est.noise_wavevector == pytest.approx(math.pi / (2 * wm_map.dx))  # no noise floor


def test_theory_from_the_map_agrees_with_the_theory_from_the_spec(wm_map):
    spec_psd = IsotropicPSD.from_wm(wm_map)
    est = IsotropicPSD.from_height_map(wm_map)
    p = np.geomspace(1e5, 1e8, 5)
    a = persson_contact(spec_psd, p, material=MAT)
    b = persson_contact(est, p, material=MAT)
    # A/A₀ ∝ 1/h′_rms at these loads: h′_rms agrees within 1 % (window, finite map, and the
    # continuum's +0.7 % over the line sums); ū and K weigh the longest rings most, whose
    # share the window moves by up to 4 %: 3 % and 4 %
    np.testing.assert_allclose(b.area_fraction, a.area_fraction, rtol=0.02)
    np.testing.assert_allclose(b.mean_separation, a.mean_separation, rtol=0.03)
    np.testing.assert_allclose(b.stiffness, a.stiffness, rtol=0.04)


# --- Persson ---------------------------------------------------------------------------------


def test_persson_area_single_scale_and_small_load_limit():
    q0, q1, c = 1e5, 1.02e5, 1e-30  # a narrow ring of wavevectors
    psd = IsotropicPSD(np.array([q0, q1]), np.array([c, c]))
    slope2 = 2 * math.pi * c * (q1**4 - q0**4) / 4  # ⟨|∇h|²⟩ of the box spectrum
    p = np.geomspace(1e-6, 2, 9) * ESTAR * math.sqrt(slope2)
    r = persson_contact(psd, p, material=MAT)
    np.testing.assert_allclose(
        r.area_fraction, erf(math.sqrt(2) * p / (ESTAR * math.sqrt(slope2))), rtol=1e-12
    )
    assert r.slope_rms == pytest.approx(math.sqrt(slope2), rel=1e-12)
    # A/A₀ = κ p/(E* h′_rms)(1 − (2/3)(p/(E* h′))² …), κ = √(8/π)
    assert r.kappa[0] == pytest.approx(math.sqrt(8 / math.pi), rel=1e-10)
    assert KAPPA_PERSSON == pytest.approx(1.5957691216, rel=1e-10)
    np.testing.assert_allclose(
        r.area_fraction_small_load, KAPPA_PERSSON * p / (ESTAR * r.slope_rms)
    )


def _published_separation(p, c0, H, q0, q1, gamma):
    """ū of Yang & Persson (2008) by nested scipy quadrature of the published expression, with
    w(q) in closed form for C = c0 (q/q0)^(−2(1+H)) on [q0, q1]."""

    def w(q):
        s = math.pi * c0 * q0 ** (2 + 2 * H) * (q ** (2 - 2 * H) - q0 ** (2 - 2 * H)) / (2 - 2 * H)
        return 1 / math.sqrt(s)

    def inner(q):
        wq = w(q)
        f = lambda pp: (  # noqa: E731
            (gamma + 3 * (1 - gamma) * erf(wq * pp / ESTAR) ** 2)
            * math.exp(-((wq * pp / ESTAR) ** 2))
            / pp
        )
        top = 12 * ESTAR / wq  # e^(−144) beyond
        return integrate.quad(f, p, top, epsabs=0, epsrel=1e-11, limit=400)[0] if top > p else 0.0

    outer = lambda q: q**2 * c0 * (q / q0) ** (-2 - 2 * H) * w(q) * inner(q)  # noqa: E731
    # q = q₀ + v²: w(q) ∝ (q − q₀)^(−1/2) near q₀ becomes smooth in v
    f_v = lambda v: 2 * v * outer(q0 + v * v)  # noqa: E731
    return (
        math.sqrt(math.pi)
        * integrate.quad(f_v, 0, math.sqrt(q1 - q0), epsabs=0, epsrel=1e-10, limit=1000)[0]
    )


@pytest.mark.parametrize("gamma", [1.0, 0.45])
def test_persson_separation_against_quadrature_of_the_published_integral(gamma):
    q0, q1, H = 1e5, 1e6, 0.8
    spec = _spec(H=H, q_r=q0, q_s=q1, h_rms=1e-6)
    psd = IsotropicPSD.from_self_affine(spec)
    p = np.array([1e-4, 1e-2]) * ESTAR * psd.slope_rms
    r = persson_contact(psd, p, material=MAT, gamma=gamma)
    ref = [_published_separation(v, self_affine_c0(spec), H, q0, q1, gamma) for v in p]
    np.testing.assert_allclose(r.mean_separation, ref, rtol=1e-6)


def test_persson_stiffness_is_minus_dp_du_of_its_own_separation():
    psd = IsotropicPSD.from_self_affine(_spec(q_L=2e4, H=0.7))
    p = np.geomspace(1e4, 1e9, 6)
    h = 1e-5
    r = persson_contact(psd, p, material=MAT)
    up = persson_contact(psd, p * (1 + h), material=MAT).mean_separation
    dn = persson_contact(psd, p * (1 - h), material=MAT).mean_separation
    np.testing.assert_allclose(r.stiffness, -2 * h * p / (up - dn), rtol=1e-5)
    assert np.all(np.diff(r.mean_separation) < 0) and np.all(np.diff(r.stiffness) > 0)
    # small loads: K → p/u₀
    assert r.stiffness[0] == pytest.approx(p[0] / r.separation_scale, rel=1e-3)


def test_persson_pressure_distribution_carries_the_load_on_the_contact_area():
    psd = IsotropicPSD.from_self_affine(_spec(H=0.8, slope_rms=0.05, h_rms=None))
    for p in (1e6, 3e8):
        d = persson_pressure_distribution(psd, p, np.linspace(0, 2e10, 400_001), material=MAT)
        assert np.trapezoid(d.density, d.stress) == pytest.approx(d.area_fraction, rel=1e-6)
        assert np.trapezoid(d.stress * d.density, d.stress) == pytest.approx(p, rel=1e-6)
        assert d.area_fraction == pytest.approx(
            float(persson_contact(psd, p, material=MAT).area_fraction[0]), rel=1e-12
        )
        assert d.stress_variance == pytest.approx(ESTAR**2 * psd.slope_rms**2 / 4, rel=1e-12)


def test_persson_gap_distribution_is_normalised():
    psd = IsotropicPSD.from_self_affine(_spec(H=0.8, q_L=2e4, slope_rms=0.1, h_rms=None))
    for p in (1e6, 1e8):
        g = persson_gap_distribution(psd, p, np.linspace(0, 2e-5, 20_001), material=MAT)
        assert g.cumulative[-1] + g.contact_fraction == pytest.approx(1.0, abs=1e-9)
        cum = integrate.cumulative_trapezoid(g.density, g.gap, initial=0)
        np.testing.assert_allclose(cum[-1], g.cumulative[-1], rtol=2e-3)
        mean = np.trapezoid(g.gap * g.density, g.gap)
        # the mirrored Gaussians put the mean a little above ū (Notes)
        assert g.mean_separation * 0.999 <= mean <= 1.2 * g.mean_separation
        r = persson_contact(psd, p, material=MAT)
        assert g.contact_fraction == pytest.approx(float(r.area_fraction[0]), rel=1e-9)
        assert g.mean_separation == pytest.approx(float(r.mean_separation[0]), rel=1e-3)


# --- Greenwood–Williamson and Bush–Gibson–Thomas ---------------------------------------------


@pytest.fixture(scope="module")
def broad():
    return IsotropicPSD.from_self_affine(_spec(H=0.8, q_L=2e4, q_r=6e4, q_s=6e6))


def test_nayak_summits_from_the_random_process_density(broad):
    s = nayak_summits(broad)
    assert s.bandwidth == pytest.approx(broad.m0 * broad.m4 / broad.m2**2)
    # Rice's formula for the maxima of the Gaussian field, integrated numerically over the mean
    # curvature, gives Nayak's summit density and McCool's radius as 1/⟨mean curvature⟩
    sc = np.linspace(0, 30 * math.sqrt(s.m4), 400_001)[1:]
    w = bgt_summit_weights(s.m2, s.m4, sc)[0.0]
    assert np.trapezoid(w, sc) == pytest.approx(
        s.m4 / (6 * math.pi * math.sqrt(3) * s.m2), rel=1e-8
    )
    assert np.trapezoid(w, sc) / np.trapezoid(w * sc, sc) == pytest.approx(s.radius, rel=1e-8)
    assert s.height_std == pytest.approx(math.sqrt((1 - 0.8968 / s.bandwidth) * s.m0))


def test_gw_exponential_against_its_closed_form(broad):
    s = nayak_summits(broad)
    p = np.geomspace(1e2, 1e7, 6)
    r = greenwood_williamson(broad, p, material=MAT, heights="exponential")
    eta, R, sig = s.density, s.radius, s.height_std
    d = r.separation - (s.height_mean - sig)  # from the start of the exponential
    assert np.all(d > 0)
    # GW (1966): p = η E* √(πR) σ^(3/2) e^(−d/σ), A/A₀ = πηRσ e^(−d/σ), K = p/σ
    np.testing.assert_allclose(
        eta * ESTAR * math.sqrt(math.pi * R) * sig**1.5 * np.exp(-d / sig), p, rtol=1e-9
    )
    np.testing.assert_allclose(
        r.area_fraction, math.pi * eta * R * sig * np.exp(-d / sig), rtol=1e-9
    )
    np.testing.assert_allclose(r.stiffness, p / sig, rtol=1e-9)
    np.testing.assert_allclose(r.kappa, r.kappa[0], rtol=1e-9)  # area ∝ load


def test_gw_gaussian_against_quadrature(broad):
    s = nayak_summits(broad)
    p = np.array([1e3, 1e6])
    r = greenwood_williamson(broad, p, material=MAT)
    phi = lambda z: (  # noqa: E731
        math.exp(-0.5 * ((z - s.height_mean) / s.height_std) ** 2)
        / (math.sqrt(2 * math.pi) * s.height_std)
    )
    for i, d in enumerate(r.separation):

        def mom(k, d=d):
            return integrate.quad(
                lambda z: (z - d) ** k * phi(z),
                d,
                d + 40 * s.height_std,
                epsabs=0,
                epsrel=1e-12,
                limit=200,
            )[0]

        root_r = math.sqrt(s.radius)
        assert 4 / 3 * s.density * ESTAR * root_r * mom(1.5) == pytest.approx(p[i], rel=1e-7)
        assert r.area_fraction[i] == pytest.approx(
            math.pi * s.density * s.radius * mom(1), rel=1e-7
        )
        assert r.stiffness[i] == pytest.approx(2 * s.density * ESTAR * root_r * mom(0.5), rel=1e-7)


def test_bgt_small_load_kappa_and_stiffness():
    # a narrow spectrum (α ≈ 1.8): high summits are spheres soon, κ → √(2π) within a few σ
    narrow = IsotropicPSD.from_self_affine(_spec(H=0.8, q_L=7e4, q_r=1e5, q_s=1.6e5))
    p = np.geomspace(1e-9, 1e-3, 25) * ESTAR * narrow.slope_rms
    r = bush_gibson_thomas(narrow, p, material=MAT)
    assert 1.5 < r.bandwidth < 2.5
    assert r.kappa[0] == pytest.approx(KAPPA_BGT, rel=0.01)
    assert np.all(np.diff(r.kappa) < 0)  # approaching the limit from below as p → 0
    # K = −dp/dd of its own load–separation law (central differences in ln p)
    lp = np.log(p)
    dd = np.gradient(r.separation, lp)
    np.testing.assert_allclose(r.stiffness[1:-1], (-p / dd)[1:-1], rtol=5e-3)


def test_results_are_columns_and_bad_input_is_refused(broad):
    p = np.geomspace(1e4, 1e7, 4)
    for res in (
        persson_contact(broad, p, material=MAT),
        greenwood_williamson(broad, p, material=MAT),
        bush_gibson_thomas(broad, p, material=MAT),
        persson_pressure_distribution(broad, 1e6, material=MAT),
        persson_gap_distribution(broad, 1e6, material=MAT),
        broad,
    ):
        cols = res.to_dict()
        n = {np.asarray(v).shape for v in cols.values()}
        assert len(n) == 1 and len(next(iter(n))) == 1
    r = persson_contact(broad, p, material=MAT, magnification=10)
    assert r.magnification == pytest.approx(10)
    assert r.slope_rms == pytest.approx(broad.band(q_max=broad.wavevector[0] * 10).slope_rms)
    with pytest.raises(ValueError, match="magnification"):
        persson_contact(broad, p, material=MAT, magnification=1e9)
    with pytest.raises(ValueError, match="pressure"):
        persson_contact(broad, [-1.0], material=MAT)
    with pytest.raises(ValueError, match="rms_height or rms_slope"):
        _spec(h_rms=1e-6, slope_rms=0.1)
    with pytest.raises(ValueError, match="strictly increasing"):
        IsotropicPSD(np.array([2.0, 1.0]), np.array([1.0, 1.0]))
    with pytest.raises(TypeError, match="Material"):
        persson_contact(broad, p, material=70e9)


def test_spectrum_of_a_generated_map_carries_its_own_c0():
    from warptrunc.selfaffine import self_affine_surface

    spec = SelfAffineSpec(
        hurst=0.8, L=1e-4, n=128, short_cutoff=4e-4 / 128, rolloff=2.5e-5, rms_slope=1.0
    )
    s = self_affine_surface(spec, device="cpu")
    from_map = IsotropicPSD.from_self_affine(s)
    from_spec = IsotropicPSD.from_self_affine(spec)
    assert from_map.params["c0"] == s.params["C0_m4"]
    # the continuous spectrum's C₀ against the discrete sums' on 128² (modes fill the band)
    assert from_spec.params["c0"] == pytest.approx(s.params["C0_m4"], rel=0.1)
    np.testing.assert_array_equal(from_map.wavevector, from_spec.wavevector)
