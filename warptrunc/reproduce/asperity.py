# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Single spherical asperity against a rigid flat (paper §2.1, Fig. 2).

The truncation curve is computed through the *same* path as a rough surface: a pixelated
sphere cap is wrapped as a :class:`~warptrunc.Surface`, truncated by :func:`warptrunc.truncate`
and turned into stiffness and load by :func:`warptrunc.stiffness_curve` (Eq. 2). It is drawn
next to closed forms:

- truncation, closed form: a' = π(2Rd − d²), F' = ∫ (2/√π)·E_r·√a' dd;
- Hertz: a_E = πRd, F = (4/3)·E_r·R^½·d^{3/2};
- fully plastic (Abbott–Firestone): a_P = 2πRd, F = H·a_P;
- the self-consistent inelastic flattening model of Storåkers, Biwa & Larsson (1997) for the
  power-law material σ = σ₀·ε^{m_B} (n_B = 0, no creep): see :func:`storakers`.

Material constants are explicit (:class:`AsperityMaterial`); the default is an aluminium alloy
(E = 70 GPa, ν = 0.33, H = 1.0 GPa, the order of the paper's Al samples, Zhai et al. 2016).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from .._support.docs import fill_doc
from .._support.validate import check_int, check_range
from ..stiffness import Material, stiffness_curve
from ..surface import from_heights
from ..truncation.api import truncate

__all__ = [
    "M_B_VALUES",
    "AsperityMaterial",
    "AsperityResult",
    "bounds_summary",
    "closed_form_truncation",
    "critical_interference",
    "fully_plastic",
    "hertz",
    "pixel_area_bounds",
    "run_asperity",
    "sphere_surface",
    "storakers",
    "storakers_constants",
]

#: Hardening exponents m_B of the paper's Fig. 2.
M_B_VALUES = (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 1.0)


@dataclass(frozen=True)
class AsperityMaterial:
    """Material of the asperity (rigid flat)."""

    E: float = 70e9
    """Young's modulus (Pa)."""
    nu: float = 0.33
    """Poisson's ratio (dimensionless)."""
    H: float = 1.0e9
    """Hardness H (Pa)."""
    sigma_y_over_H: float = 1.0 / 3.0
    """Yield stress σ_y as a fraction of H (Tabor, H ≈ 3σ_y); sets σ₀ of the inelastic model."""

    def __post_init__(self) -> None:
        check_range("E", self.E, 0.0, unit="Pa")
        check_range("nu", self.nu, -1.0, 0.5, hi_open=False)
        check_range("H", self.H, 0.0, unit="Pa")
        check_range("sigma_y_over_H", self.sigma_y_over_H, 0.0, 1.0, hi_open=False)

    @property
    def contact_modulus(self) -> float:
        """Contact modulus E* (the paper's E_r) against a rigid flat, E/(1 − ν²) (Pa)."""
        return self.E / (1.0 - self.nu**2)

    @property
    def sigma_y(self) -> float:
        """Yield stress σ_y (Pa)."""
        return self.sigma_y_over_H * self.H

    def sigma0(self, m: float) -> float:
        """σ₀ of σ = σ₀·ε^m continuous with linear elasticity at yield: σ_y^{1−m}·E^m (Pa).

        Parameters
        ----------
        m : float
            Hardening exponent (dimensionless).

        Returns
        -------
        float
            σ₀ (Pa).
        """
        return self.sigma_y ** (1.0 - m) * self.E**m


_D_R = "Parameters\n----------\nd : ndarray\n    (k,) {} (m).\nR : float\n    Sphere radius (m)."
_CURVE_DOCS = {
    "{d_R}": _D_R.format("interferences"),
    "{depth_R}": _D_R.format("truncation depths"),
    "{area_load}": (
        "Returns\n-------\narea : ndarray\n    (k,) contact area (m²).\n"
        "load : ndarray\n    (k,) load (N)."
    ),
}
"""Parameter and return text of the closed-form curves, written once (:func:`fill_doc`)."""


def critical_interference(R: float, mat: AsperityMaterial) -> float:
    """ω_c = (π·k·H/(2·E_r))²·R with k = 0.454 + 0.41·ν (m) (paper §2.1).

    Parameters
    ----------
    R : float
        Sphere radius (m).
    mat : AsperityMaterial
        E, ν and hardness H of the asperity.

    Returns
    -------
    float
        Critical interference ω_c (m).
    """
    k = 0.454 + 0.41 * mat.nu
    return (math.pi * k * mat.H / (2.0 * mat.contact_modulus)) ** 2 * R


@fill_doc(_CURVE_DOCS)
def hertz(d: np.ndarray, R: float, mat: AsperityMaterial) -> tuple[np.ndarray, np.ndarray]:
    """Hertz: contact area a_E = πRd (m²) and load F = (4/3)·E_r·√R·d^{3/2} (N).

    {d_R}
    mat : AsperityMaterial
        Elastic constants (E* = ``contact_modulus``).

    {area_load}
    """
    d = np.asarray(d, dtype=np.float64)
    return math.pi * R * d, 4.0 / 3.0 * mat.contact_modulus * math.sqrt(R) * d**1.5


@fill_doc(_CURVE_DOCS)
def fully_plastic(d: np.ndarray, R: float, mat: AsperityMaterial) -> tuple[np.ndarray, np.ndarray]:
    """Fully plastic: a_P = 2πRd (m²), F = H·a_P (N).

    {d_R}
    mat : AsperityMaterial
        Hardness H.

    {area_load}
    """
    a = 2.0 * math.pi * R * np.asarray(d, dtype=np.float64)
    return a, mat.H * a


@fill_doc(_CURVE_DOCS)
def closed_form_truncation(
    d: np.ndarray, R: float, mat: AsperityMaterial
) -> tuple[np.ndarray, np.ndarray]:
    """Exact truncated area a' = π(2Rd − d²) (m²) and its Eq. (2) load (N).

    F'(d) = (2/√π)·E_r·√π·∫₀^d √(2Rs − s²) ds, integrated in closed form
    (the area under a circle's arc): ∫√(2Rs − s²) ds = ½[(s−R)√(2Rs − s²) + R² asin((s−R)/R)].

    {depth_R}
    mat : AsperityMaterial
        Elastic constants (E* = ``contact_modulus``).

    Returns
    -------
    area : ndarray
        (k,) truncated area a' (m²).
    load : ndarray
        (k,) load F' (N), with β' = 1.
    """
    d = np.asarray(d, dtype=np.float64)
    a = math.pi * (2.0 * R * d - d**2)

    def prim(s):
        return 0.5 * (
            (s - R) * np.sqrt(np.maximum(2 * R * s - s**2, 0.0))
            + R**2 * np.arcsin(np.clip((s - R) / R, -1.0, 1.0))
        )

    return a, 2.0 * mat.contact_modulus * (prim(d) - prim(0.0))


def storakers_constants(m: float) -> tuple[float, float]:
    """(c², α) of the self-similar inelastic contact model for hardening exponent m.

    c² = a²/(2Rd) is the ratio of the true contact area to the truncated area (c² > 1: pile-up,
    c² < 1: sink-in) and α the mean-pressure factor, p_m = α·σ₀·(a/R)^m. We use the curve fits
    c² = 1.43·exp(−0.97·m), α = 3·6^{−m} quoted by Storåkers, Fleck & McMeeking (1999) from the
    finite-element solutions of the self-similar problem (Biwa & Storåkers 1995; Storåkers,
    Biwa & Larsson 1997). They are not re-derived here. Checks: m = 0 gives α = 3, the
    rigid-perfectly-plastic mean pressure p = 3σ_y (≈ H, Tabor), and c² = 1.43 (pile-up);
    m = 1 gives c² = 0.54 and α = 0.5, against the incompressible Hertz values c² = 0.5 and
    α = 16/(9π) = 0.566 (σ₀ = E, ν = ½).

    Parameters
    ----------
    m : float
        Hardening exponent, 0 ≤ m ≤ 1 (dimensionless).

    Returns
    -------
    c2 : float
        Area ratio c² (dimensionless).
    alpha : float
        Mean-pressure factor α (dimensionless).
    """
    m = check_range("m", m, 0.0, 1.0, lo_open=False, hi_open=False)
    return 1.43 * math.exp(-0.97 * m), 3.0 * 6.0 ** (-m)


@fill_doc(_CURVE_DOCS)
def storakers(
    d: np.ndarray, R: float, mat: AsperityMaterial, m: float
) -> tuple[np.ndarray, np.ndarray]:
    """Contact area (m²) and load (N) of a sphere flattened by d, Storåkers et al. (1997).

    For σ = σ₀·ε^m (n_B = 0), self-similarity gives a² = 2c²·R·d and F = π·a²·α·σ₀·(a/R)^m, so
    F ∝ d^{1 + m/2}: m = 1 is Hertz-like (F ∝ d^{3/2}), m = 0 perfectly plastic (F ∝ a ∝ d,
    constant mean pressure 3σ₀). σ₀ = σ_y^{1−m}·E^m (:meth:`AsperityMaterial.sigma0`).

    {d_R}
    mat : AsperityMaterial
        E and σ_y of the asperity.
    m : float
        Hardening exponent (dimensionless).

    Returns
    -------
    area : ndarray
        (k,) contact area π·a² (m²).
    load : ndarray
        (k,) load (N).

    References
    ----------
    Storåkers, Biwa & Larsson (1997), Similarity analysis of inelastic contact, Int. J. Solids
    Struct. 34, 3061–3083, doi:10.1016/S0020-7683(96)00175-2. Biwa & Storåkers (1995), An
    analysis of fully plastic Brinell indentation, J. Mech. Phys. Solids 43, 1303–1333,
    doi:10.1016/0022-5096(95)00031-D. Storåkers, Fleck & McMeeking (1999), The viscoplastic
    compaction of composite powders, J. Mech. Phys. Solids 47, 785–815 (curve fits of c², α).
    """
    c2, alpha = storakers_constants(m)
    d = np.asarray(d, dtype=np.float64)
    a2 = 2.0 * c2 * R * d
    area = math.pi * a2
    return area, area * alpha * mat.sigma0(m) * (np.sqrt(a2) / R) ** m


def sphere_surface(R: float, half_width: float, n: int):
    """A pixelated spherical cap of radius R (m) on an n×n grid of side 2·half_width (m).

    Heights z = −r²/(R + √(R² − r²)) (= √(R² − r²) − R, stable in float32 near the top) with
    the apex on the pixel (n//2, n//2), so the top is exactly 0.

    Parameters
    ----------
    R : float
        Sphere radius (m).
    half_width : float
        Half the side of the map (m).
    n : int
        Pixels per side.

    Returns
    -------
    Surface
        (n, n) float32 heights (m) with ``params`` generator="sphere" and R.
    """

    R = check_range("R", R, 0.0, unit="m")
    n = check_int("n", n, 8, 1 << 16)
    half_width = check_range("half_width", half_width, 0.0, R, unit="m")
    dx = 2.0 * half_width / n
    c = np.arange(n, dtype=np.float64) - n // 2
    r2 = (c[None, :] ** 2 + c[:, None] ** 2) * dx * dx
    z = -r2 / (R + np.sqrt(np.maximum(R * R - r2, 0.0)))
    return from_heights(z.astype(np.float32), dx, generator="sphere", R=R)


@fill_doc(_CURVE_DOCS)
def pixel_area_bounds(d: np.ndarray, R: float, dx: float) -> tuple[np.ndarray, np.ndarray]:
    """Bounds (m²) on the pixel-counted truncated area of :func:`sphere_surface` at depth d.

    The pixels counted are those whose centre lies in the disc of radius ρ = √(2Rd − d²); their
    squares lie inside the disc of radius ρ + dx/√2 and cover the disc of radius ρ − dx/√2, so
    π·max(ρ − h, 0)² ≤ A ≤ π(ρ + h)², h = dx/√2.

    {depth_R}
    dx : float
        Pixel spacing (m).

    Returns
    -------
    lower, upper : ndarray
        (k,) bounds on the counted area (m²).
    """
    rho = np.sqrt(np.maximum(2 * R * np.asarray(d, dtype=np.float64) - np.asarray(d) ** 2, 0.0))
    h = dx / math.sqrt(2.0)
    return math.pi * np.maximum(rho - h, 0.0) ** 2, math.pi * (rho + h) ** 2


@dataclass(frozen=True, eq=False)
class AsperityResult:
    """Fig. 2 curves: areas (m²) and loads (N) against the interference d (m)."""

    R: float
    """Sphere radius (m)."""
    omega_c: float
    """Critical interference ω_c (m)."""
    material: AsperityMaterial
    """Material constants."""
    n: int
    """Pixels per side of the sphere map."""
    dx: float
    """Pixel size (m)."""
    d: np.ndarray
    """(k,) interference d (m)."""
    curves: dict[str, tuple[np.ndarray, np.ndarray]]
    """Name → ((k,) area (m²), (k,) load (N)): ``truncation`` (pixel map), ``truncation_exact``,
    ``hertz``, ``plastic``, ``storakers_m<m>``."""

    def to_dict(self) -> dict[str, Any]:
        """Scalars and normalised columns A/(πR²), F/(E·πR²) (JSON-serialisable lists).

        Returns
        -------
        dict of str to Any
            ``R_m``, ``omega_c_m``, ``n``, ``dx_m``, ``material``, ``d_m`` and, per curve,
            ``<name>_area_norm`` and ``<name>_load_norm`` (dimensionless lists).
        """
        s = math.pi * self.R**2
        out: dict[str, Any] = {
            "R_m": self.R,
            "omega_c_m": self.omega_c,
            "n": self.n,
            "dx_m": self.dx,
            "material": asdict(self.material),
            "d_m": self.d.tolist(),
        }
        for k, (a, f) in self.curves.items():
            out[f"{k}_area_norm"] = (a / s).tolist()
            out[f"{k}_load_norm"] = (f / (self.material.E * s)).tolist()
        return out


def run_asperity(
    *,
    R: float = 1e-3,
    n: int = 1024,
    n_increments: int = 1000,
    max_omega_c: float = 100.0,
    material: AsperityMaterial | None = None,
    m_values: tuple[float, ...] = M_B_VALUES,
    device=None,
) -> AsperityResult:
    """Fig. 2: truncate a pixelated sphere to d = max_omega_c·ω_c through the rough-surface path.

    Parameters
    ----------
    R : float
        Sphere radius (m).
    n : int
        Pixels per side; the map spans 1.2× the final truncation radius √(2R·d_max).
    n_increments : int
        Truncation increments (the paper: 1000).
    max_omega_c : float
        Largest interference in units of ω_c (the paper: 100).
    material : AsperityMaterial, optional
        Material of the asperity; default :class:`AsperityMaterial`.
    m_values : tuple of float
        Hardening exponents of the inelastic (Storåkers) curves (dimensionless).
    device : str, optional
        Warp device.

    Returns
    -------
    AsperityResult
        The truncation curve of the pixel map and the closed-form curves against d (m).
    """

    mat = AsperityMaterial() if material is None else material
    wc = critical_interference(R, mat)
    dmax = check_range("max_omega_c", max_omega_c, 0.0) * wc
    s = sphere_surface(R, 1.2 * math.sqrt(2 * R * dmax), n)
    sc = stiffness_curve(
        truncate(s, n_increments, max_depth=dmax, device=device), Material(E=mat.E, nu=mat.nu)
    )
    d = sc.depth
    curves = {
        "truncation": (sc.contact_area, sc.load),
        "truncation_exact": closed_form_truncation(d, R, mat),
        "hertz": hertz(d, R, mat),
        "plastic": fully_plastic(d, R, mat),
    }
    for m in m_values:
        curves[f"storakers_m{m:g}"] = storakers(d, R, mat, m)
    return AsperityResult(R, wc, mat, n, s.dx, d, curves)


def bounds_summary(res: AsperityResult) -> dict[str, Any]:
    """Where the truncation curve lies against Hertz and fully plastic, at equal load.

    At equal load the closed forms give A_trunc = 2^{2/3}·A_Hertz (always above Hertz) and
    A_trunc < A_plastic once the truncation mean pressure (2√2/(3π))·E_r·√(d/R) exceeds H, i.e.
    for d > d* = R·(3πH/(2√2·E_r))². The pixel curve is compared with both by interpolating
    each bound's area at the truncation loads.

    Parameters
    ----------
    res : AsperityResult
        Output of :func:`run_asperity`.

    Returns
    -------
    dict of str to Any
        Area ratios of the truncation curve to each bound at equal load
        (``area_ratio_to_hertz``, ``area_ratio_to_plastic``, ...) and their summaries.
    """
    a_t, f_t = res.curves["truncation"]
    out: dict[str, Any] = {}
    sel = f_t > 0
    for name in ("hertz", "plastic"):
        a, f = res.curves[name]
        out[f"area_ratio_to_{name}"] = (a_t[sel] / np.interp(f_t[sel], f, a)).tolist()
    mat = res.material
    d_star = res.R * (3 * math.pi * mat.H / (2 * math.sqrt(2) * mat.contact_modulus)) ** 2
    rh = np.asarray(out["area_ratio_to_hertz"])
    rp = np.asarray(out["area_ratio_to_plastic"])
    d = res.d[sel]
    between = (rh > 1) & (rp <= 1)
    out.update(
        d_star_m=d_star,
        d_star_over_omega_c=d_star / res.omega_c,
        fraction_between=float(between.mean()),
        first_between_d_over_omega_c=float(d[between][0] / res.omega_c) if between.any() else None,
        above_hertz_everywhere=bool((rh > 1).all()),
        hertz_ratio_closed_form=2 ** (2 / 3),
        hertz_ratio_median=float(np.median(rh)),
    )
    return out
