# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Persson's theory of elastic contact of a randomly rough surface with a flat, from its PSD.

- :func:`persson_contact`: relative contact area A/A₀(p), its small-load limit, the mean
  interfacial separation ū(p) and the normal stiffness per unit area K = −dp/dū, over an array
  of nominal pressures p;
- :func:`persson_pressure_distribution`: the distribution of contact pressure P(σ) at the
  largest magnification;
- :func:`persson_gap_distribution`: the distribution of interfacial separations P(u).

The rough surface's spectrum is an :class:`~warptrunc.theory.IsotropicPSD` (Persson's
normalisation, ⟨h²⟩ = 2π ∫ q C dq) and the elastic body a :class:`~warptrunc.Material`
(E* = ``contact_modulus``, E/(1 − ν²) against a rigid flat; its hardness is not used). The
integrals run over the spectrum's samples (vectorised over pressures), never over pixels.

Notation
--------
q₀ is the smallest wavevector of the spectrum, q₁ = ζ q₀ the largest used (ζ the
magnification) and

    S(q) = π ∫_{q₀}^{q} q′³ C(q′) dq′ = ⟨‖∇h‖²⟩_q / 2,

half the mean square slope of the roughness up to q; t(q) = √S(q) = 1/w(q) with Persson's
w(q) = (π ∫ q′³ C dq′)^(−1/2).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.integrate import cumulative_simpson
from scipy.special import erf, erfcx, exp1, ndtr

from ._common import check_pressure, columns, modulus_of
from .psd import IsotropicPSD

__all__ = [
    "KAPPA_PERSSON",
    "GapDistribution",
    "PerssonCurve",
    "PressureDistribution",
    "persson_contact",
    "persson_gap_distribution",
    "persson_pressure_distribution",
]

KAPPA_PERSSON = math.sqrt(8.0 / math.pi)
"""κ = √(8/π) ≈ 1.596 of Persson's small-load limit A/A₀ = κ p/(E* h′_rms) (dimensionless)."""

_GAMMA_DOC = """gamma : float
        Yang & Persson's correction factor γ in (0, 1] of the separation integral
        (dimensionless): they found γ ≈ 0.4–0.5 to match simulations; γ = 1 is Persson's
        original form (2007)."""


@dataclass(frozen=True, eq=False)
class PerssonCurve:
    """Persson's contact area, mean separation and stiffness over nominal pressures (SI)."""

    pressure: np.ndarray
    """(n,) nominal pressure p (Pa)."""
    area_fraction: np.ndarray
    """(n,) relative contact area A/A₀ = erf(p/(E* √S(q₁))) (dimensionless)."""
    area_fraction_small_load: np.ndarray
    """(n,) its small-load limit κ p/(E* h′_rms), κ = √(8/π) (dimensionless)."""
    mean_separation: np.ndarray
    """(n,) mean interfacial separation ū (m)."""
    stiffness: np.ndarray
    """(n,) normal contact stiffness per unit nominal area K = −dp/dū (Pa/m)."""
    contact_modulus: float
    """E* (Pa)."""
    slope_rms: float
    """h′_rms = √⟨‖∇h‖²⟩ of the spectrum up to q₁ (dimensionless): the theory is a small-slope
    theory, so well below 1."""
    h_rms: float
    """Rms height of the spectrum up to q₁ (m)."""
    magnification: float
    """ζ = q₁/q₀ used (dimensionless)."""
    gamma: float
    """Yang & Persson's correction factor γ (dimensionless)."""
    separation_scale: float
    """u₀ = √π γ ∫ q² C w dq (m): at small loads ū ≈ −u₀ ln p + const and K → p/u₀."""

    @property
    def kappa(self) -> np.ndarray:
        """(n,) κ = (A/A₀) E* h′_rms / p, the area–load coefficient (dimensionless)."""
        return self.area_fraction * self.contact_modulus * self.slope_rms / self.pressure

    def to_dict(self) -> dict[str, Any]:
        """1-D columns: the curves and, repeated, the scalars.

        Returns
        -------
        dict
            ``pressure_Pa``, ``area_fraction``, ``area_fraction_small_load``,
            ``mean_separation_m``, ``stiffness_Pa_per_m``, ``contact_modulus_Pa``,
            ``slope_rms``, ``h_rms_m``, ``magnification``, ``gamma``, ``separation_scale_m``.
        """
        return columns(
            self,
            {
                "pressure": "pressure_Pa",
                "mean_separation": "mean_separation_m",
                "stiffness": "stiffness_Pa_per_m",
                "contact_modulus": "contact_modulus_Pa",
                "h_rms": "h_rms_m",
                "separation_scale": "separation_scale_m",
            },
        )


@dataclass(frozen=True, eq=False)
class PressureDistribution:
    """Persson's distribution of contact pressure at the largest magnification (SI)."""

    stress: np.ndarray
    """(m,) contact pressure σ ≥ 0 (Pa)."""
    density: np.ndarray
    """(m,) P(σ) (1/Pa): ∫₀^∞ P dσ = A/A₀, ∫₀^∞ σ P dσ = p (the rest of the area carries σ = 0)."""
    pressure: float
    """Nominal pressure p (Pa)."""
    area_fraction: float
    """A/A₀ (dimensionless)."""
    stress_variance: float
    """⟨σ²⟩ of full contact, E*² ⟨‖∇h‖²⟩/4 = 2G (Pa²)."""
    slope_rms: float
    """h′_rms up to q₁ (dimensionless)."""
    magnification: float
    """ζ = q₁/q₀ (dimensionless)."""

    def to_dict(self) -> dict[str, Any]:
        """1-D columns ``stress_Pa``, ``density_per_Pa`` and, repeated, the scalars.

        Returns
        -------
        dict
            Also ``pressure_Pa``, ``area_fraction``, ``stress_variance_Pa2``, ``slope_rms``,
            ``magnification``.
        """
        return columns(
            self,
            {
                "stress": "stress_Pa",
                "density": "density_per_Pa",
                "pressure": "pressure_Pa",
                "stress_variance": "stress_variance_Pa2",
            },
        )


@dataclass(frozen=True, eq=False)
class GapDistribution:
    """The distribution of interfacial separations u between the surfaces (SI)."""

    gap: np.ndarray
    """(m,) separation u ≥ 0 (m)."""
    density: np.ndarray
    """(m,) P(u) (1/m) of the non-contact area; ∫₀^∞ P du = 1 − A/A₀."""
    cumulative: np.ndarray
    """(m,) ∫₀^u P du′ (dimensionless), exact (not a sum over the grid)."""
    pressure: float
    """Nominal pressure p (Pa)."""
    contact_fraction: float
    """A/A₀: the weight of the delta function at u = 0 (dimensionless)."""
    mean_separation: float
    """ū(p), the separation integral of :func:`persson_contact` on this function's samples (m)."""
    slope_rms: float
    """h′_rms up to q₁ (dimensionless)."""
    magnification: float
    """ζ = q₁/q₀ (dimensionless)."""
    gamma: float
    """Yang & Persson's γ used for ū(ζ) (dimensionless)."""

    def to_dict(self) -> dict[str, Any]:
        """1-D columns ``gap_m``, ``density_per_m``, ``cumulative`` and, repeated, the scalars.

        Returns
        -------
        dict
            Also ``pressure_Pa``, ``contact_fraction``, ``mean_separation_m``, ``slope_rms``,
            ``magnification``, ``gamma``.
        """
        return columns(
            self,
            {
                "gap": "gap_m",
                "density": "density_per_m",
                "pressure": "pressure_Pa",
                "mean_separation": "mean_separation_m",
            },
        )


# --- the functions of the separation integral ------------------------------------------------

_Y_MAX = 6.5  # beyond it erf(y)² = 1 to 1e-19: the tails are closed forms
_H = 2e-4  # step of the tables (interpolation error ≈ 1e-9)


@functools.cache
def _tables() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """y, J(y) = ∫_y^∞ erf² e^(−x²)/x dx and L(y) = ∫_y^∞ erf² e^(−x²)/x² dx on [0, 6.5]."""
    y = np.linspace(0.0, _Y_MAX, round(_Y_MAX / _H) + 1)
    e2 = np.exp(-(y**2))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(y > 0, erf(y) / y, 2 / math.sqrt(math.pi))  # erf(y)/y → 2/√π
    fj = erf(y) * ratio * e2  # erf² e^(−y²)/y, → 0 at 0
    fl = ratio**2 * e2  # erf² e^(−y²)/y², → 4/π at 0
    top = y[-1]
    tail_j = 0.5 * exp1(top**2)
    tail_l = math.exp(-(top**2)) * (1 / top - math.sqrt(math.pi) * erfcx(top))
    j = tail_j + cumulative_simpson(fj[::-1], dx=_H, initial=0.0)[::-1]
    lt = tail_l + cumulative_simpson(fl[::-1], dx=_H, initial=0.0)[::-1]
    return y, j, lt


def _i_k(x: np.ndarray, gamma: float) -> tuple[np.ndarray, np.ndarray]:
    """I(x) = ∫_x^∞ g(y)/y dy and K(x) = ∫_x^∞ g(y)/y² dy, g = [γ + 3(1 − γ) erf²] e^(−y²),
    for x > 0 (inf gives 0)."""
    y, jt, lt = _tables()
    x = np.asarray(x, dtype=np.float64)
    xs = np.where(np.isfinite(x), x, 1e3)
    with np.errstate(over="ignore", under="ignore"):
        e1 = exp1(xs**2)
        k_gauss = np.exp(-(xs**2)) * (1 / xs - math.sqrt(math.pi) * erfcx(xs))
    inside = xs < _Y_MAX
    j = np.where(inside, np.interp(xs, y, jt), 0.5 * e1)
    lv = np.where(inside, np.interp(xs, y, lt), k_gauss)
    i = 0.5 * gamma * e1 + 3 * (1 - gamma) * j
    k = gamma * k_gauss + 3 * (1 - gamma) * lv
    far = ~np.isfinite(x)
    return np.where(far, 0.0, i), np.where(far, 0.0, k)


def _antiderivative(t: np.ndarray, c: np.ndarray, gamma: float) -> tuple[np.ndarray, ...]:
    """At x = c/t: F = t I(x) − c K(x) (dF/dt = I(c/t), ∂F/∂c = −K(c/t)), T = t³ I(x)/3
    (dT/dt = t² I(c/t) + t² g(c/t)/3, ∂T/∂c = −t³ g(x)/(3c)) and K(x); all 0 at t = 0.

    ``t`` and ``c`` broadcast; returns (F, T, K, g).
    """
    with np.errstate(divide="ignore"):
        x = np.where(t > 0, c / np.where(t > 0, t, 1.0), np.inf)
    i, k = _i_k(x, gamma)
    pos = t > 0
    return (
        np.where(pos, t * i - c * k, 0.0),
        np.where(pos, t**3 * i / 3, 0.0),
        np.where(pos, k, 0.0),
        np.where(pos, _g(x, gamma), 0.0),
    )


def _g(x: np.ndarray, gamma: float) -> np.ndarray:
    """g(x) = [γ + 3(1 − γ) erf² x] e^(−x²) (0 at x = inf)."""
    with np.errstate(under="ignore", invalid="ignore"):
        xs = np.where(np.isfinite(x), x, 0.0)
        out = (gamma + 3 * (1 - gamma) * erf(xs) ** 2) * np.exp(-(xs**2))
    return np.where(np.isfinite(x), out, 0.0)


def _dg(x: np.ndarray, gamma: float) -> np.ndarray:
    """g′(x) = 12(1 − γ) erf(x) e^(−2x²)/√π − 2x g(x)."""
    with np.errstate(under="ignore"):
        return 12 * (1 - gamma) * erf(x) * np.exp(-2 * x**2) / math.sqrt(math.pi) - 2 * x * _g(
            x, gamma
        )


_GL = np.polynomial.legendre.leggauss(6)
_GL_U, _GL_W = 0.5 * (_GL[0] + 1.0), 0.5 * _GL[1]  # on [0, 1]


# --- checks shared by the three functions ----------------------------------------------------


def _band(psd: IsotropicPSD, magnification: float | None, points_per_decade: int) -> IsotropicPSD:
    if not isinstance(psd, IsotropicPSD):
        raise TypeError(f"psd must be an IsotropicPSD, got {type(psd).__name__}")
    if magnification is not None:
        z = float(magnification)
        if not 1.0 < z <= psd.magnification * (1 + 1e-12):
            raise ValueError(
                f"magnification must be in (1, {psd.magnification:.6g}] (the spectrum's "
                f"q_max/q₀), got {magnification!r}"
            )
        psd = psd.band(q_max=min(psd.wavevector[0] * z, psd.wavevector[-1]))
    return psd.refined(points_per_decade)


def _gamma(gamma: float) -> float:
    g = float(gamma)
    if not 0.0 < g <= 1.0:
        raise ValueError(f"gamma must be in (0, 1], got {gamma!r}")
    return g


def _slope_half(psd: IsotropicPSD) -> np.ndarray:
    """S(q) = π ∫ q³ C dq at every sample (dimensionless)."""
    return psd.cumulative_moment(2) / 2.0


def _q_of_s(psd: IsotropicPSD, s: np.ndarray, seg: np.ndarray, target: np.ndarray) -> np.ndarray:
    """q with S(q) = ``target`` inside interval ``seg`` of ``psd`` (S its samples' values), by
    Newton's method from the linear guess; S(q) − S_i = π ∫_{q_i}^{q} q′³ C dq′ by 8-point
    Gauss–Legendre (exact to rounding on one interval of the interpolant)."""
    q = psd.wavevector
    qa, qb = q[seg], q[seg + 1]
    sa, sb = s[seg], s[seg + 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(sb > sa, (target - sa) / np.where(sb > sa, sb - sa, 1.0), 0.0)
    x = qa + np.clip(frac, 0.0, 1.0) * (qb - qa)
    u, w = np.polynomial.legendre.leggauss(8)
    u, w = 0.5 * (u + 1.0), 0.5 * w
    for _ in range(4):
        qq = qa[..., None] + (x - qa)[..., None] * u
        part = math.pi * (qq**3 * psd.at(qq) * w).sum(axis=-1) * (x - qa)
        slope = math.pi * x**3 * psd.at(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(slope > 0, (sa + part - target) / np.where(slope > 0, slope, 1.0), 0.0)
        x = np.clip(x - step, qa, qb)
    return x


def _separation(
    psd: IsotropicPSD, s: np.ndarray, start: np.ndarray, c: np.ndarray, gamma: float
) -> tuple[np.ndarray, np.ndarray]:
    """ū and dū/dc for reduced pressures ``c`` = p/E* ((r,) array) with the roughness of each
    row starting at S = ``start`` ((r,) array: S(ζq₀) of that row's magnification).

    ū = (2/√π) ∫ I(c/t)/q(t) dt over t² = S(q) − start ≥ 0. On each interval of the samples
    1/q = α + βt² + ρ(t): the part linear in t² is integrated exactly in I (antiderivatives
    F and T of :func:`_antiderivative`, and ∫ t² g by 6-point Gauss–Legendre, a smooth bounded
    term), the small remainder ρ (1/q(t) from S inverted on the interval) by the same Gauss
    rule. dū/dc differentiates the same sum, so that −dp/dū is exact for the ū returned.
    """
    q = psd.wavevector
    inv = 1 / q
    t2 = np.clip(s[None, :] - start[:, None], 0.0, None)
    ds = np.diff(t2, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        beta = np.where(ds > 0, np.diff(inv)[None, :] / np.where(ds > 0, ds, 1.0), 0.0)
    alpha = inv[None, :-1] - beta * t2[:, :-1]
    t = np.sqrt(t2)
    cc = c[:, None]
    f, tt, k, g_end = _antiderivative(t, cc, gamma)
    ta, tb = t[:, :-1], t[:, 1:]
    tg = ta[..., None] + (tb - ta)[..., None] * _GL_U  # Gauss nodes in t, (r, k − 1, 6)
    seg = np.broadcast_to(np.arange(q.size - 1)[None, :, None], tg.shape)
    qg = _q_of_s(psd, s, seg, tg**2 + start[:, None, None])
    rho = 1 / qg - (alpha[..., None] + beta[..., None] * tg**2)
    with np.errstate(divide="ignore"):
        xg = np.where(tg > 0, cc[..., None] / np.where(tg > 0, tg, 1.0), np.inf)
    ig, _kg = _i_k(xg, gamma)
    gg = _g(xg, gamma)
    with np.errstate(invalid="ignore"):
        dgg = np.where(np.isfinite(xg), _dg(np.where(np.isfinite(xg), xg, 0.0), gamma), 0.0)
    wgt = (tb - ta)[..., None] * _GL_W
    int_t2g = (tg**2 * gg * wgt).sum(axis=-1)
    dint_t2g = (tg * dgg * wgt).sum(axis=-1)  # ∂/∂c ∫ t² g(c/t) dt = ∫ t g′(c/t) dt
    rem = (ig * rho * wgt).sum(axis=-1)
    drem = (-gg / cc[..., None] * rho * wgt).sum(axis=-1)  # ∂I(c/t)/∂c = −g(c/t)/c
    with np.errstate(divide="ignore", invalid="ignore"):
        dtt_dc = np.where(t > 0, -(t**3) * g_end / (3 * cc), 0.0)  # ∂T/∂c
    u = (alpha * np.diff(f, axis=1) + beta * (np.diff(tt, axis=1) - int_t2g / 3) + rem).sum(axis=1)
    du = (-alpha * np.diff(k, axis=1) + beta * (np.diff(dtt_dc, axis=1) - dint_t2g / 3) + drem).sum(
        axis=1
    )
    return 2 / math.sqrt(math.pi) * u, 2 / math.sqrt(math.pi) * du


# --- the theory ------------------------------------------------------------------------------


def persson_contact(
    psd: IsotropicPSD,
    pressure: Any,
    *,
    material: Any,
    magnification: float | None = None,
    gamma: float = 0.45,
    points_per_decade: int = 64,
) -> PerssonCurve:
    """Persson's A/A₀, mean separation ū and stiffness K = −dp/dū at nominal pressures p.

    Parameters
    ----------
    psd : IsotropicPSD
        The rough surface's spectrum.
    pressure : float or (n,) array_like
        Nominal pressures p > 0 (Pa).
    material : Material
        The elastic constants; E* = ``material.contact_modulus`` (Pa).
    magnification : float, optional
        ζ = q₁/q₀: use the spectrum up to q₁ (dimensionless). Default: all of it.
    {gamma}
    points_per_decade : int
        Samples per decade the spectrum is refined to before the integrals (count).

    Returns
    -------
    PerssonCurve
        The curves over p and the regime quantities (h′_rms, ζ, u₀).

    Notes
    -----
    Contact area (Persson 2001; the "erf" form with the factor of Persson 2006). The
    probability distribution of contact pressure obeys a diffusion equation in magnification
    with the absorbing boundary P(0, ζ) = 0; its solution gives

        A/A₀ = erf(p / (2√G)),  G(ζ) = (π/4) E*² ∫_{q₀}^{ζq₀} q³ C(q) dq = E*² S/4,

    i.e. A/A₀ = erf(p/√(2V)) with V = 2G = E*² ⟨‖∇h‖²⟩/4 the variance of the pressure in full
    contact (V = ¼ E*² ∫ d²q q² C). As p → 0, A/A₀ → κ p/(E* h′_rms) with κ = √(8/π)
    (``area_fraction_small_load``); numerical contact mechanics finds κ ≈ 2 (Hyun et al.
    2004), so this form underestimates the area at small loads by about 20 %.

    Mean separation (Persson 2007; Yang & Persson 2008, with their factor γ):

        ū = √π ∫_{q₀}^{q₁} dq q² C(q) w(q) ∫_p^∞ (dp′/p′) [γ + 3(1 − γ) P²(q, p′)]
            exp(−[w(q) p′/E*]²),  P(q, p′) = erf(w(q) p′/E*),

    evaluated as ū = (2/√π) ∫₀^{t₁} I(p/(E* t)) dt/q(t) with t = 1/w and
    I(x) = ∫_x^∞ (dy/y)[γ + 3(1 − γ) erf² y] e^(−y²) = (γ/2) E₁(x²) + 3(1 − γ) J(x), J from a
    table; the change of variable removes the integrable singularity of w at q₀. On each
    interval of the refined samples, the part of 1/q linear in t² (S is locally linear in q)
    is integrated exactly in I (antiderivatives t I(c/t) − c K(c/t) and t³ I(c/t)/3), the
    rest by 6-point Gauss–Legendre with q(t) from S inverted on the interval. The stiffness is
    the same sum differentiated analytically:

        K = −dp/dū = √π p / (2 ∫₀^{t₁} g(p/(E* t)) dt/q),  g(y) = [γ + 3(1 − γ) erf² y] e^(−y²),

    so K → p/u₀ at small p with u₀ = (2γ/√π) ∫ dt/q = √π γ ∫ q² C w dq.

    Regime: elastic, frictionless, non-adhesive, small slopes (h′_rms ≪ 1), a Gaussian
    surface; ū is the separation between the mean planes, and the theory holds for
    separations well above the smallest roughness scale.

    References
    ----------
    Persson (2001), J. Chem. Phys. 115, 3840, doi:10.1063/1.1388626.
    Persson (2006), Surf. Sci. Rep. 61, 201, doi:10.1016/j.surfrep.2006.04.001.
    Persson (2007), Phys. Rev. Lett. 99, 125502, doi:10.1103/PhysRevLett.99.125502.
    Yang & Persson (2008), J. Phys.: Condens. Matter 20, 215214,
    doi:10.1088/0953-8984/20/21/215214.
    Hyun, Pei, Molinari & Robbins (2004), Phys. Rev. E 70, 026117,
    doi:10.1103/PhysRevE.70.026117.
    """
    p = check_pressure(pressure)
    modulus = modulus_of(material)
    g = _gamma(gamma)
    band = _band(psd, magnification, points_per_decade)
    q = band.wavevector
    s = _slope_half(band)
    t = np.sqrt(s)
    c = p / modulus
    area = erf(c / t[-1])
    u, du_dc = _separation(band, s, np.zeros_like(c), c, g)
    # u₀ = (2γ/√π) ∫ dt/q, with 1/q linear in t² as in the integral
    beta = np.diff(1 / q) / np.diff(s)
    alpha = 1 / q[:-1] - beta * s[:-1]
    u0 = 2 * g / math.sqrt(math.pi) * float((alpha * np.diff(t) + beta * np.diff(t**3) / 3).sum())
    return PerssonCurve(
        pressure=p,
        area_fraction=area,
        area_fraction_small_load=KAPPA_PERSSON * p / (modulus * band.slope_rms),
        mean_separation=u,
        stiffness=-modulus / du_dc,
        contact_modulus=modulus,
        slope_rms=band.slope_rms,
        h_rms=band.h_rms,
        magnification=band.magnification,
        gamma=g,
        separation_scale=u0,
    )


def persson_pressure_distribution(
    psd: IsotropicPSD,
    pressure: float,
    stress: Any = None,
    *,
    material: Any,
    magnification: float | None = None,
) -> PressureDistribution:
    """Persson's distribution of contact pressure P(σ) at magnification ζ.

    Parameters
    ----------
    psd : IsotropicPSD
        The rough surface's spectrum.
    pressure : float
        Nominal pressure p > 0 (Pa).
    stress : (m,) array_like, optional
        Pressures σ ≥ 0 to evaluate P at (Pa). Default: 401 points on [0, p + 6√V].
    material : Material
        The elastic constants; E* = ``material.contact_modulus`` (Pa).
    magnification : float, optional
        ζ = q₁/q₀ (dimensionless). Default: the whole spectrum.

    Returns
    -------
    PressureDistribution

    Notes
    -----
    The solution of Persson's diffusion equation ∂P/∂ζ = G′(ζ) ∂²P/∂σ² with P(σ, 1) = δ(σ − p)
    and the absorbing boundary P(0, ζ) = 0 (Persson 2001, 2006):

        P(σ, ζ) = [exp(−(σ − p)²/(4G)) − exp(−(σ + p)²/(4G))] / (2√(πG)),  σ ≥ 0,

    with G(ζ) = E*² S(ζq₀)/4 (Pa²). Its integral over σ > 0 is A/A₀ = erf(p/(2√G)) and its
    first moment is p: the load is carried by the contact area alone.

    References
    ----------
    Persson (2001), J. Chem. Phys. 115, 3840, doi:10.1063/1.1388626.
    Persson (2006), Surf. Sci. Rep. 61, 201, doi:10.1016/j.surfrep.2006.04.001.
    """
    p = float(check_pressure(pressure)[0])
    modulus = modulus_of(material)
    band = _band(psd, magnification, 8)
    G = modulus**2 * float(_slope_half(band)[-1]) / 4
    if stress is None:
        sigma = np.linspace(0.0, p + 6 * math.sqrt(2 * G), 401)
    else:
        sigma = np.asarray(stress, dtype=np.float64).reshape(-1)
        if not np.all(np.isfinite(sigma) & (sigma >= 0)):
            raise ValueError("stress must be finite and ≥ 0 (Pa)")
    dens = (np.exp(-((sigma - p) ** 2) / (4 * G)) - np.exp(-((sigma + p) ** 2) / (4 * G))) / (
        2 * math.sqrt(math.pi * G)
    )
    return PressureDistribution(
        stress=sigma,
        density=dens,
        pressure=p,
        area_fraction=float(erf(p / (2 * math.sqrt(G)))),
        stress_variance=2 * G,
        slope_rms=band.slope_rms,
        magnification=band.magnification,
    )


def persson_gap_distribution(
    psd: IsotropicPSD,
    pressure: float,
    gap: Any = None,
    *,
    material: Any,
    magnification: float | None = None,
    gamma: float = 0.45,
    points_per_decade: int = 32,
) -> GapDistribution:
    """The distribution of interfacial separations P(u) from Persson's theory.

    Parameters
    ----------
    psd : IsotropicPSD
        The rough surface's spectrum.
    pressure : float
        Nominal pressure p > 0 (Pa).
    gap : (m,) array_like, optional
        Separations u ≥ 0 to evaluate P at (m). Default: 801 points on [0, ū + 6 h_rms].
    material : Material
        The elastic constants; E* = ``material.contact_modulus`` (Pa).
    magnification : float, optional
        ζ₁ = q₁/q₀ (dimensionless). Default: the whole spectrum.
    {gamma}
    points_per_decade : int
        Samples per decade of the magnifications ζ (count); the work grows as its square.

    Returns
    -------
    GapDistribution

    Notes
    -----
    The construction of Almqvist, Campañá, Prodanov & Persson (2011). Observed at
    magnification ζ, the apparent contact covers A(ζ)/A₀ = erf(p/(E* √S(ζq₀))) and carries the
    mean pressure p(ζ) = p A₀/A(ζ); the mean separation inside it, ū(ζ), is the separation
    integral of :func:`persson_contact` with the roughness above ζq₀ only (t² = S(q) − S(ζq₀),
    q > ζq₀) at the pressure p(ζ), and ū(1) = ū. Going from ζ to ζ + dζ, the area −dA leaves
    the apparent contact; the gap volume A ū then changes by d(Aū) = u₁ dA, so the separation
    there averages u₁(ζ) = d(Aū)/dA, and it is spread as a Gaussian of the rms height
    h_rms(ζ)² = 2π ∫_{ζq₀}^{q₁} q C dq of the roughness not yet resolved, mirrored at u = 0:

        P(u) = Σ_ζ (−ΔA/A₀) [N(u; u₁, h_rms²) + N(u; −u₁, h_rms²)],  u > 0,

    with A(ζ₁)/A₀ in contact (u = 0). Between magnification samples ζ_j, ζ_(j+1):
    u₁ = (A_j ū_j − A_(j+1) ū_(j+1))/(A_j − A_(j+1)) exactly, and h_rms² the mean of its
    ends. The mirror makes the mean of P slightly larger than ū where u₁ ≲ h_rms.

    References
    ----------
    Almqvist, Campañá, Prodanov & Persson (2011), J. Mech. Phys. Solids 59, 2355,
    doi:10.1016/j.jmps.2011.08.004.
    Yang & Persson (2008), J. Phys.: Condens. Matter 20, 215214,
    doi:10.1088/0953-8984/20/21/215214.
    """
    p = float(check_pressure(pressure)[0])
    modulus = modulus_of(material)
    g = _gamma(gamma)
    band = _band(psd, magnification, points_per_decade)
    s = _slope_half(band)
    with np.errstate(divide="ignore"):
        area = erf(np.where(s > 0, p / (modulus * np.sqrt(np.where(s > 0, s, 1.0))), np.inf))
    c = p / (modulus * area)  # p(ζ)/E* at each ζ_j
    # t²_(j, i) = S_i − S_j for i ≥ j: the roughness above ζ_j q₀ (0 below)
    ubar, _du = _separation(band, s, s, c, g)
    vol = area * ubar
    d_area = area[:-1] - area[1:]
    keep = d_area > 0
    u1 = np.where(keep, (vol[:-1] - vol[1:]) / np.where(keep, d_area, 1.0), 0.0)
    m0 = band.cumulative_moment(0)
    h2 = np.clip(m0[-1] - m0, 0.0, None)
    hs = np.sqrt(0.5 * (h2[:-1] + h2[1:]))
    if gap is None:
        u = np.linspace(0.0, ubar[0] + 6 * band.h_rms, 801)
    else:
        u = np.asarray(gap, dtype=np.float64).reshape(-1)
        if not np.all(np.isfinite(u) & (u >= 0)):
            raise ValueError("gap must be finite and ≥ 0 (m)")
    wgt, u1, hs = d_area[keep], u1[keep], hs[keep]
    z1 = (u[:, None] - u1[None, :]) / hs
    z2 = (u[:, None] + u1[None, :]) / hs
    norm = 1 / (math.sqrt(2 * math.pi) * hs)
    dens = ((np.exp(-0.5 * z1**2) + np.exp(-0.5 * z2**2)) * norm * wgt).sum(axis=1)
    cum = ((ndtr(z1) - ndtr(-u1 / hs) + ndtr(z2) - ndtr(u1 / hs)) * wgt).sum(axis=1)
    return GapDistribution(
        gap=u,
        density=dens,
        cumulative=cum,
        pressure=p,
        contact_fraction=float(area[-1]),
        mean_separation=float(ubar[0]),
        slope_rms=band.slope_rms,
        magnification=band.magnification,
        gamma=g,
    )


for _f in (persson_contact, persson_gap_distribution):
    _f.__doc__ = _f.__doc__.replace("{gamma}", _GAMMA_DOC)
