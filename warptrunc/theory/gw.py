# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Asperity models of elastic rough contact from a PSD: Greenwood–Williamson and Bush–Gibson–Thomas.

- :func:`nayak_summits`: the summit statistics of a Gaussian isotropic surface from the
  spectral moments m₀, m₂, m₄ (Nayak 1971; McCool 1986);
- :func:`greenwood_williamson`: identical spherical summits of that density and radius with
  Gaussian or exponential heights, each a Hertz contact (Greenwood & Williamson 1966);
- :func:`bush_gibson_thomas`: the random-process model, summits with Nayak's joint
  distribution of height and principal curvatures (Bush, Gibson & Thomas 1975).

Both models leave out the elastic interaction between contacts and the bulk deformation of
the surface between them: they hold at small loads (A/A₀ ≲ 0.1), where they bracket the
area–load coefficient κ = (A/A₀) E* h′_rms / p. Heights and separations are measured from the
mean plane of the undeformed surface (m); E* is ``Material.contact_modulus`` (Pa).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.interpolate import CubicSpline, PchipInterpolator
from scipy.special import gamma as gamma_fn
from scipy.special import gammaincc, hyp1f1, ndtr, pbdv

from ._common import check_pressure, columns, modulus_of
from .psd import IsotropicPSD

__all__ = [
    "KAPPA_BGT",
    "AsperityCurve",
    "SummitStatistics",
    "bgt_summit_weights",
    "bush_gibson_thomas",
    "greenwood_williamson",
    "nayak_summits",
]

KAPPA_BGT = math.sqrt(2.0 * math.pi)
"""κ = √(2π) ≈ 2.507 of the Bush–Gibson–Thomas limit A/A₀ = κ p/(E* h′_rms) at large
separations (dimensionless)."""

HEIGHTS = ("gaussian", "exponential")


@dataclass(frozen=True)
class SummitStatistics:
    """Summit statistics of a Gaussian isotropic surface from its spectral moments (SI)."""

    m0: float
    """m₀ = ⟨h²⟩ (m²)."""
    m2: float
    """m₂ = ⟨(∂h/∂x)²⟩ (dimensionless)."""
    m4: float
    """m₄ = ⟨(∂²h/∂x²)²⟩ (1/m²)."""
    bandwidth: float
    """Nayak's bandwidth parameter α = m₀m₄/m₂² (dimensionless; ≥ 1.5 for an isotropic
    surface, 1.5 for a single ring of wavevectors)."""
    density: float
    """η = m₄/(6π√3 m₂), summits per unit area (1/m²)."""
    radius: float
    """R = (3/8)√(π/m₄), the mean summit radius of curvature for large α (m)."""
    height_std: float
    """σ_s = √((1 − 0.8968/α) m₀), the rms of summit heights (m)."""
    height_mean: float
    """y_s = 4 m₂/√(π m₄), the mean summit height above the mean plane (m)."""

    def to_dict(self) -> dict[str, Any]:
        """The fields (SI).

        Returns
        -------
        dict
            ``m0_m2``, ``m2``, ``m4_per_m2``, ``bandwidth``, ``density_per_m2``, ``radius_m``,
            ``height_std_m``, ``height_mean_m``.
        """
        return {
            "m0_m2": self.m0,
            "m2": self.m2,
            "m4_per_m2": self.m4,
            "bandwidth": self.bandwidth,
            "density_per_m2": self.density,
            "radius_m": self.radius,
            "height_std_m": self.height_std,
            "height_mean_m": self.height_mean,
        }


@dataclass(frozen=True, eq=False)
class AsperityCurve:
    """An asperity model's contact area, separation and stiffness over nominal pressures (SI)."""

    model: str
    """``"gw-gaussian"``, ``"gw-exponential"`` or ``"bgt"``."""
    pressure: np.ndarray
    """(n,) nominal pressure p (Pa)."""
    separation: np.ndarray
    """(n,) separation d of the flat from the surface's mean plane (m): the load–separation
    law p(d); NaN where p lies outside the range the model was solved on."""
    area_fraction: np.ndarray
    """(n,) relative contact area A/A₀ (dimensionless); not bounded by 1 (no interaction)."""
    stiffness: np.ndarray
    """(n,) normal stiffness per unit nominal area K = −dp/dd at the same separation (Pa/m)."""
    contact_density: np.ndarray
    """(n,) summits in contact per unit area (1/m²)."""
    contact_modulus: float
    """E* (Pa)."""
    slope_rms: float
    """h′_rms = √(2m₂) of the spectrum used (dimensionless)."""
    magnification: float
    """ζ = q₁/q₀ of the spectrum used (dimensionless): the summit statistics depend on it."""
    summit_density: float
    """η (1/m²), Nayak's."""
    summit_radius: float
    """R (m): the GW radius (McCool); for BGT, the same number for comparison (BGT's summits
    have the curvature distribution of the random process)."""
    summit_height_std: float
    """σ_s (m)."""
    bandwidth: float
    """Nayak's α (dimensionless)."""

    @property
    def kappa(self) -> np.ndarray:
        """(n,) κ = (A/A₀) E* h′_rms / p, the area–load coefficient (dimensionless)."""
        return self.area_fraction * self.contact_modulus * self.slope_rms / self.pressure

    def to_dict(self) -> dict[str, Any]:
        """1-D columns: the curves and, repeated, the scalars.

        Returns
        -------
        dict
            ``model``, ``pressure_Pa``, ``separation_m``, ``area_fraction``,
            ``stiffness_Pa_per_m``, ``contact_density_per_m2``, ``contact_modulus_Pa``,
            ``slope_rms``, ``magnification``, ``summit_density_per_m2``, ``summit_radius_m``,
            ``summit_height_std_m``, ``bandwidth``.
        """
        return columns(
            self,
            {
                "pressure": "pressure_Pa",
                "separation": "separation_m",
                "stiffness": "stiffness_Pa_per_m",
                "contact_density": "contact_density_per_m2",
                "contact_modulus": "contact_modulus_Pa",
                "summit_density": "summit_density_per_m2",
                "summit_radius": "summit_radius_m",
                "summit_height_std": "summit_height_std_m",
            },
        )


def _band(psd: IsotropicPSD, magnification: float | None) -> IsotropicPSD:
    if not isinstance(psd, IsotropicPSD):
        raise TypeError(f"psd must be an IsotropicPSD, got {type(psd).__name__}")
    if magnification is None:
        return psd
    z = float(magnification)
    if not 1.0 < z <= psd.magnification * (1 + 1e-12):
        raise ValueError(
            f"magnification must be in (1, {psd.magnification:.6g}], got {magnification!r}"
        )
    return psd.band(q_max=min(psd.wavevector[0] * z, psd.wavevector[-1]))


def nayak_summits(psd: IsotropicPSD, *, magnification: float | None = None) -> SummitStatistics:
    """Summit density, radius and height distribution of a Gaussian isotropic surface.

    Parameters
    ----------
    psd : IsotropicPSD
        The spectrum; its moments m₀, m₂, m₄ (:attr:`IsotropicPSD.m0` …).
    magnification : float, optional
        ζ = q₁/q₀: use the spectrum up to q₁ (dimensionless). Default: all of it.

    Returns
    -------
    SummitStatistics

    Notes
    -----
    For an isotropic Gaussian surface with profile moments m₀, m₂, m₄ and α = m₀m₄/m₂²
    (Nayak 1971), the summit density is η = m₄/(6π√3 m₂); McCool (1986) gives the GW radius
    R = 0.375 √(π/m₄) (the inverse mean summit curvature at large α), the rms summit height
    σ_s = (1 − 0.8968/α)^(1/2) √m₀ and the mean summit height 4√m₀/√(πα) = 4m₂/√(πm₄). All
    three depend on the shortest wavelength included (m₄ on it most), which is why the
    magnification is a stated input.

    References
    ----------
    Nayak (1971), J. Lubr. Technol. 93, 398, doi:10.1115/1.3451608.
    McCool (1986), Wear 107, 37, doi:10.1016/0043-1648(86)90045-1.
    """
    band = _band(psd, magnification)
    m0, m2, m4 = band.m0, band.m2, band.m4
    alpha = m0 * m4 / m2**2
    return SummitStatistics(
        m0=m0,
        m2=m2,
        m4=m4,
        bandwidth=alpha,
        density=m4 / (6 * math.pi * math.sqrt(3) * m2),
        radius=0.375 * math.sqrt(math.pi / m4),
        height_std=math.sqrt(max(1 - 0.8968 / alpha, 0.0) * m0),
        height_mean=4 * m2 / math.sqrt(math.pi * m4),
    )


_X_TABLE = 40.0  # ∣x∣ range of the tabulated Gaussian tails; beyond it the asymptotes


@functools.cache
def _gauss_table(k: float) -> CubicSpline:
    """Cubic spline of ln F_k on [−40, 40], every 0.005, from the parabolic cylinder function
    (scipy's ``pbdv``, accurate to ~1e-13 but slow near 0; the spline adds < 1e-10)."""
    x = np.linspace(-_X_TABLE, _X_TABLE, 16001)
    d, _ = pbdv(-k - 1.0, x)
    log_f = math.lgamma(k + 1) - x**2 / 4 + np.log(d) - 0.5 * math.log(2 * math.pi)
    return CubicSpline(x, log_f)


def _gauss_tail(k: float, x: np.ndarray) -> np.ndarray:
    """F_k(x) = ∫_x^∞ (z − x)^k φ(z) dz for the standard normal φ:
    Γ(k + 1) e^(−x²/4) D_(−k−1)(x)/√(2π) (parabolic cylinder function); F₀ = Φ(−x). Beyond
    ∣x∣ = 40: 0 above, ∣x∣^k (1 + k(k − 1)/(2x²)) below (the moments of Z − x)."""
    x = np.asarray(x, dtype=np.float64)
    if k == 0:
        return ndtr(-x)
    xc = np.clip(x, -_X_TABLE, _X_TABLE)
    with np.errstate(under="ignore"):
        f = np.exp(_gauss_table(float(k))(xc))
    low = np.abs(x) ** k * (1 + k * (k - 1) / (2 * np.maximum(x * x, 1.0)))
    return np.where(x > _X_TABLE, 0.0, np.where(x < -_X_TABLE, low, f))


def _exp_tail(k: float, x: np.ndarray) -> np.ndarray:
    """F_k(x) = ∫ (z − x)^k e^(−z) dz over z ≥ max(x, 0), the unit exponential from 0:
    Γ(k + 1) e^(−x) Q(k + 1, max(−x, 0)), Q the regularised upper incomplete gamma."""
    x = np.asarray(x, dtype=np.float64)
    with np.errstate(under="ignore"):
        return gamma_fn(k + 1) * np.exp(-x) * gammaincc(k + 1, np.maximum(-x, 0.0))


def _invert(fun, target: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """x with fun(x) = target for a decreasing positive ``fun``, by bisection on log fun
    (vectorised); NaN where the target lies outside [fun(hi), fun(lo)]."""
    a = np.full(target.shape, lo)
    b = np.full(target.shape, hi)
    lt = np.log(target)
    for _ in range(200):
        m = 0.5 * (a + b)
        with np.errstate(divide="ignore"):
            above = np.log(fun(m)) > lt
        a = np.where(above, m, a)
        b = np.where(above, b, m)
        if np.all(b - a <= 1e-13 * max(1.0, abs(lo), abs(hi))):
            break
    x = 0.5 * (a + b)
    with np.errstate(divide="ignore"):
        inside = (np.log(fun(np.array(lo))) >= lt) & (np.log(fun(np.array(hi))) <= lt)
    return np.where(inside, x, np.nan)


def greenwood_williamson(
    psd: IsotropicPSD,
    pressure: Any,
    *,
    material: Any,
    heights: str = "gaussian",
    magnification: float | None = None,
) -> AsperityCurve:
    """The Greenwood–Williamson model with Nayak's summits: A/A₀, d and K at pressures p.

    Parameters
    ----------
    psd : IsotropicPSD
        The rough surface's spectrum.
    pressure : float or (n,) array_like
        Nominal pressures p > 0 (Pa).
    material : Material
        The elastic constants; E* = ``material.contact_modulus`` (Pa).
    heights : {"gaussian", "exponential"}
        Summit heights: Gaussian N(y_s, σ_s²), or exponential with the same mean y_s and rms
        σ_s, φ(z) = e^(−(z − z₀)/σ_s)/σ_s for z ≥ z₀ = y_s − σ_s.
    magnification : float, optional
        ζ = q₁/q₀: use the spectrum up to q₁ (dimensionless). Default: all of it.

    Returns
    -------
    AsperityCurve
        ``model="gw-gaussian"`` or ``"gw-exponential"``.

    Notes
    -----
    Summits of density η and radius R (:func:`nayak_summits`), heights z with density φ(z);
    one at z > d makes a Hertz contact of interference δ = z − d: force (4/3)E*R^(1/2)δ^(3/2),
    area πRδ, stiffness 2E*R^(1/2)δ^(1/2) (Johnson 1985). Per unit nominal area

        p = (4/3) η E* R^(1/2) ∫_d^∞ (z − d)^(3/2) φ dz,   A/A₀ = π η R ∫_d^∞ (z − d) φ dz,
        K = −dp/dd = 2 η E* R^(1/2) ∫_d^∞ (z − d)^(1/2) φ dz,

    with ∫_d^∞ (z − d)^k φ dz = σ_s^k F_k((d − y_s)/σ_s) in closed form (parabolic cylinder
    functions for the Gaussian, incomplete gamma functions for the exponential). For the
    exponential and d ≥ z₀ they reduce to GW's closed forms
    p = η E* √(πR) σ_s^(3/2) e^(−(d − z₀)/σ_s), A/A₀ = πηRσ_s e^(−(d − z₀)/σ_s), K = p/σ_s:
    area and stiffness exactly proportional to load. d(p) is found by bisection on the
    closed form (to 10⁻¹³ σ_s), over d − y_s in [−30, 37] σ_s (Gaussian) or d − z₀ in
    [−30, 700] σ_s (exponential).

    References
    ----------
    Greenwood & Williamson (1966), Proc. R. Soc. Lond. A 295, 300, doi:10.1098/rspa.1966.0242.
    McCool (1986), Wear 107, 37, doi:10.1016/0043-1648(86)90045-1.
    Johnson (1985), Contact Mechanics, Cambridge University Press, doi:10.1017/CBO9781139171731.
    """
    if heights not in HEIGHTS:
        raise ValueError(f"heights must be one of {HEIGHTS}, got {heights!r}")
    p = check_pressure(pressure)
    modulus = modulus_of(material)
    band = _band(psd, magnification)
    s = nayak_summits(band)
    eta, R, sig = s.density, s.radius, s.height_std
    if heights == "gaussian":
        tail, origin, lo, hi = _gauss_tail, s.height_mean, -30.0, 37.0
    else:
        tail, origin, lo, hi = _exp_tail, s.height_mean - sig, -30.0, 700.0
    scale_p = (4 / 3) * eta * modulus * math.sqrt(R) * sig**1.5
    x = _invert(lambda v: tail(1.5, v), p / scale_p, lo, hi)
    return AsperityCurve(
        model=f"gw-{heights}",
        pressure=p,
        separation=origin + sig * x,
        area_fraction=math.pi * eta * R * sig * tail(1.0, x),
        stiffness=2 * eta * modulus * math.sqrt(R) * math.sqrt(sig) * tail(0.5, x),
        contact_density=eta * tail(0.0, x),
        contact_modulus=modulus,
        slope_rms=band.slope_rms,
        magnification=band.magnification,
        summit_density=eta,
        summit_radius=R,
        summit_height_std=sig,
        bandwidth=s.bandwidth,
    )


def bgt_summit_weights(m2: float, m4: float, curvature: np.ndarray) -> dict[float, np.ndarray]:
    """Nayak's summit density per unit mean curvature, weighted by powers of Gaussian curvature.

    Parameters
    ----------
    m2 : float
        m₂ (dimensionless).
    m4 : float
        m₄ (1/m²).
    curvature : (k,) ndarray
        Mean curvatures s = (κ₁ + κ₂)/2 ≥ 0 of the summits (1/m).

    Returns
    -------
    dict of float to (k,) ndarray
        For c = 0, 1/4, 1/2: ∫ n(s, r) (s² − r²)^(−c) dr, summits per unit area per unit s
        weighted by (κ₁κ₂)^(−c) (m^(2c−1)): the weights of the contact count, of the load and
        stiffness (R_e^(1/2)) and of the area (R_e).

    Notes
    -----
    For a Gaussian isotropic surface the gradient (h_x, h_y) is independent of the height and
    the Hessian; (h, s) with s = −(h_xx + h_yy)/2 is bivariate normal with Var s = 2m₄/3,
    Cov(h, s) = m₂, and r = ‖((h_xx − h_yy)/2, h_xy)‖ is Rayleigh with σ_r² = m₄/3,
    independent of (h, s). Rice's formula gives the density of maxima,
    n = p(∇h = 0) p(h, s) p(r) ∣det H∣ over s > r, with p(∇h = 0) = 1/(2πm₂) and
    det H = κ₁κ₂ = s² − r². The r-integral is a Kummer function:
    ∫₀^s (s² − r²)^β (r/σ_r²) e^(−r²/(2σ_r²)) dr = (2σ_r²)^β a^(β+1) ₁F₁(1; β + 2; −a)/(β + 1),
    a = s²/(2σ_r²), β = 1 − c; for c = 0 it is σ_r²(t² − 2 + 2e^(−t²/2)), t = s/σ_r, Nayak's
    factor, and the total over s and h is η = m₄/(6π√3 m₂).
    """
    s = np.asarray(curvature, dtype=np.float64)
    var_r = m4 / 3
    var_s = 2 * m4 / 3
    a = s**2 / (2 * var_r)
    phi = np.exp(-(s**2) / (2 * var_s)) / math.sqrt(2 * math.pi * var_s)
    out = {}
    for c in (0.0, 0.25, 0.5):
        b = 1.0 - c
        w = (2 * var_r) ** b * a ** (b + 1) * hyp1f1(1.0, b + 2.0, -a) / (b + 1)
        out[c] = phi * w / (2 * math.pi * m2)
    return out


def bush_gibson_thomas(
    psd: IsotropicPSD,
    pressure: Any,
    *,
    material: Any,
    magnification: float | None = None,
) -> AsperityCurve:
    """The Bush–Gibson–Thomas random-process model: A/A₀, d and K at pressures p.

    Parameters
    ----------
    psd : IsotropicPSD
        The rough surface's spectrum (a Gaussian isotropic surface, α > 1.5).
    pressure : float or (n,) array_like
        Nominal pressures p > 0 (Pa).
    material : Material
        The elastic constants; E* = ``material.contact_modulus`` (Pa).
    magnification : float, optional
        ζ = q₁/q₀: use the spectrum up to q₁ (dimensionless). Default: all of it.

    Returns
    -------
    AsperityCurve
        ``model="bgt"``.

    Notes
    -----
    Every summit (local maximum) of the Gaussian surface, with its own height h and principal
    curvatures κ₁, κ₂ drawn from the joint density of :func:`bgt_summit_weights` (Nayak's
    random-process statistics, as BGT), touches the flat when h > d and makes the Hertz
    contact of the equivalent sphere R_e = (κ₁κ₂)^(−1/2), Greenwood's (2006) simplification of
    BGT's elliptic contacts. With s the mean curvature, h given s is normal with mean
    3m₂s/(2m₄) and variance v = m₀(1 − 3/(2α)), so the height integrals are closed forms
    v^(k/2) F_k and

        p = (4/3) E* ∫ ds W_(1/4)(s) v^(3/4) F_(3/2),  A/A₀ = π ∫ ds W_(1/2)(s) v^(1/2) F₁,
        K = −dp/dd = 2 E* ∫ ds W_(1/4)(s) v^(1/4) F_(1/2),

    the s-integral by the trapezoid rule on a uniform grid resolving the conditional spread
    of s, at separations d every 0.02 √m₀ over [−4, 12] √m₀, and d(p) by monotone cubic
    interpolation of ln p (NaN outside that range). For high summits the curvature
    concentrates at s = (m₂/m₀)h and κ₁ = κ₂, which gives A/A₀ → √(2π) p/(E* h′_rms) as
    d → ∞ (``KAPPA_BGT``); the approach is slow for broad spectra (large α).

    References
    ----------
    Bush, Gibson & Thomas (1975), Wear 35, 87, doi:10.1016/0043-1648(75)90145-3.
    Nayak (1971), J. Lubr. Technol. 93, 398, doi:10.1115/1.3451608.
    Greenwood (2006), Wear 261, 191, doi:10.1016/j.wear.2005.09.031.
    Carbone & Bottiglione (2008), J. Mech. Phys. Solids 56, 2555,
    doi:10.1016/j.jmps.2008.03.011.
    """
    p = check_pressure(pressure)
    modulus = modulus_of(material)
    band = _band(psd, magnification)
    st = nayak_summits(band)
    m0, m2, m4, alpha = st.m0, st.m2, st.m4, st.bandwidth
    if not alpha > 1.5 * (1 + 1e-9):
        raise ValueError(
            f"BGT needs Nayak's α > 1.5 (a spectrum wider than one ring), got α = {alpha:.6g}"
        )
    var_s = 2 * m4 / 3
    v = m0 * (1 - 3 / (2 * alpha))
    sd_cond = math.sqrt(max(var_s - m2**2 / m0, 0.0))  # spread of s at a given height
    s_max = 12 * m2 / math.sqrt(m0) + 12 * math.sqrt(var_s)
    ds = min(math.sqrt(var_s), sd_cond) / 15
    n_s = int(min(max(s_max / ds, 400), 20000))
    s = np.linspace(0.0, s_max, n_s + 1)[1:]
    wts = bgt_summit_weights(m2, m4, s)
    d = np.arange(-4.0, 12.0 + 1e-9, 0.02) * math.sqrt(m0)
    x = (d[:, None] - 1.5 * m2 * s[None, :] / m4) / math.sqrt(v)

    def integral(c: float, k: float) -> np.ndarray:
        return np.trapezoid(wts[c][None, :] * v ** (k / 2) * _gauss_tail(k, x), s, axis=1)

    p_d = (4 / 3) * modulus * integral(0.25, 1.5)
    a_d = math.pi * integral(0.5, 1.0)
    k_d = 2 * modulus * integral(0.25, 0.5)
    n_d = integral(0.0, 0.0)
    ok = p_d > 0
    lp = np.log(p_d[ok])[::-1]  # increasing
    dd = d[ok][::-1]
    sep = PchipInterpolator(lp, dd, extrapolate=False)(np.log(p))
    col = lambda y: PchipInterpolator(dd[::-1], np.log(y[ok]), extrapolate=False)  # noqa: E731
    with np.errstate(invalid="ignore"):
        area = np.exp(col(a_d)(sep))
        stiff = np.exp(col(k_d)(sep))
        count = np.exp(col(n_d)(sep))
    return AsperityCurve(
        model="bgt",
        pressure=p,
        separation=sep,
        area_fraction=area,
        stiffness=stiff,
        contact_density=count,
        contact_modulus=modulus,
        slope_rms=band.slope_rms,
        magnification=band.magnification,
        summit_density=st.density,
        summit_radius=st.radius,
        summit_height_std=st.height_std,
        bandwidth=alpha,
    )
