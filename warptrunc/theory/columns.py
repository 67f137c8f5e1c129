# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The theories beside elastic solves: Persson's and Greenwood–Williamson's predictions at the
nominal pressure of each solve, as columns of the tables of ``compare`` and ``bem-check``.

- :func:`surface_spectrum`: the spectrum the theories read for a map: its known spectrum (a WM
  or a self-affine map made by warptrunc) or, for any other map, its radially averaged
  periodogram cut at its noise floor (:meth:`~warptrunc.theory.IsotropicPSD.from_height_map`);
- :func:`theory_columns`: at the nominal pressure p = F/A₀ of every solve (F the solve's load,
  A₀ the map's area), Persson's contact area, mean gap and stiffness and GW's contact area and
  stiffness, in the units of the solver's own columns (m², m, N/m), and the area–load
  coefficient κ of the solve beside them;
- :func:`kappa_record`: the small-load κ of the solves beside Persson's √(8/π) and BGT's √(2π).

The stiffness columns are per map, K·A₀ with K = −dp/dū the stiffness per unit nominal area of
the theory (Pa/m): −dF/dū, the change of load with the mean gap. On a periodic half-space the
solver's k = dF/dδ equals it; on the free one (a map that is an isolated patch) δ and ū differ
by the bulk displacement under the patch, and the two are different quantities.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .gw import KAPPA_BGT, greenwood_williamson
from .persson import KAPPA_PERSSON, persson_contact
from .psd import IsotropicPSD

__all__ = ["THEORY_COLUMNS", "kappa_record", "surface_spectrum", "theory_columns"]

THEORY_COLUMNS = (
    "nominal_pressure_Pa",
    "bem_kappa",
    "persson_area_m2",
    "persson_mean_gap_m",
    "persson_stiffness_N_per_m",
    "gw_area_m2",
    "gw_stiffness_N_per_m",
    "spectrum_source",
    "spectrum_slope_rms",
    "spectrum_q_max_per_m",
)
"""The columns of :func:`theory_columns`, in order: the nominal pressure F/A₀ (Pa); the solve's
κ = (A/A₀)·E*·h′_rms/p (dimensionless, h′_rms of the spectrum); Persson's contact area A/A₀·A₀
(m²), mean gap ū (m) and stiffness K·A₀ (N/m); GW's (Gaussian summit heights) contact area (m²)
and stiffness (N/m); what the spectrum is (``"weierstrass-mandelbrot"``, ``"self-affine"`` or
``"height map"``), its h′_rms (dimensionless) and the largest wavevector it holds (1/m: for a
map's estimate, the noise floor)."""

KAPPA_MAX_AREA_FRACTION = 0.05
"""The small-load κ of :func:`kappa_record` reads the solves with A/A₀ up to this
(dimensionless)."""

KAPPA_MIN_PIXELS = 100
"""... and with at least this many contact pixels (count)."""


def surface_spectrum(surface: Any, *, window: str = "hann") -> IsotropicPSD:
    """The isotropic spectrum C(q) the theories read for a map.

    Parameters
    ----------
    surface : Surface
        The height map (m).
    window : {"hann", "none"}
        Window of the periodogram of a map without a known spectrum: ``"hann"`` for a scan (not
        periodic), ``"none"`` for a periodic map.

    Returns
    -------
    IsotropicPSD
        A WM map of :func:`warptrunc.wm_surface`: :meth:`~warptrunc.theory.IsotropicPSD.from_wm`;
        a self-affine map of :func:`~warptrunc.selfaffine.self_affine_surface`: its own spectrum
        (:meth:`~warptrunc.theory.IsotropicPSD.from_self_affine`); any other map: its radially
        averaged periodogram up to its noise floor ``noise_wavevector`` (1/m), which is then the
        largest wavevector the theories see.
    """
    params = getattr(surface, "params", None) or {}
    gen = params.get("generator")
    if gen == "weierstrass-mandelbrot":
        return IsotropicPSD.from_wm(surface)
    if gen == "self-affine":
        return IsotropicPSD.from_self_affine(surface)
    est = IsotropicPSD.from_height_map(surface, window=window)
    top = min(est.noise_wavevector, float(est.wavevector[-1]))
    return est.band(q_max=top) if top < est.wavevector[-1] else est


def theory_columns(
    psd: IsotropicPSD,
    load: Any,
    apparent_area: float,
    *,
    material: Any,
    area: Any = None,
) -> dict[str, np.ndarray]:
    """Persson's and GW's predictions at the nominal pressure of each solve.

    Parameters
    ----------
    psd : IsotropicPSD
        The spectrum of the map (:func:`surface_spectrum`).
    load : (m,) array_like
        The solves' loads F (N); a row with F ≤ 0 or not finite gets NaN.
    apparent_area : float
        The map's area A₀ (m²); p = F/A₀.
    material : Material
        E* = ``material.contact_modulus`` (Pa).
    area : (m,) array_like, optional
        The solves' contact areas A (m²), for ``bem_kappa``; NaN without it.

    Returns
    -------
    dict of str to ndarray
        The (m,) columns :data:`THEORY_COLUMNS`.

    Notes
    -----
    Persson (:func:`~warptrunc.theory.persson_contact`, Yang & Persson's γ = 0.45): A/A₀, ū and
    K = −dp/dū; GW (:func:`~warptrunc.theory.greenwood_williamson`, Gaussian summit heights,
    Nayak's summits of the whole spectrum): A/A₀ and K. Both over the whole spectrum given
    (its magnification). GW holds for A/A₀ ≲ 0.1 only (no interaction between contacts; its
    A/A₀ is not bounded by 1).
    """
    f = np.atleast_1d(np.asarray(load, dtype=np.float64))
    a0 = float(apparent_area)
    if not a0 > 0:
        raise ValueError(f"apparent_area must be > 0 m², got {apparent_area!r}")
    m = f.size
    p = f / a0
    ok = np.isfinite(p) & (p > 0)
    nan = np.full(m, np.nan)
    out: dict[str, Any] = {k: nan.copy() for k in THEORY_COLUMNS}
    out["nominal_pressure_Pa"] = np.where(np.isfinite(p), p, np.nan)
    if ok.any():
        # a map's periodogram can hold empty annuli (a line spectrum: a sinusoid), where the
        # theories divide by zero-width steps of the slope integral: those values become NaN
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            pc = persson_contact(psd, p[ok], material=material)
            gw = greenwood_williamson(psd, p[ok], material=material)
            vals = {
                "persson_area_m2": pc.area_fraction * a0,
                "persson_mean_gap_m": pc.mean_separation,
                "persson_stiffness_N_per_m": pc.stiffness * a0,
                "gw_area_m2": gw.area_fraction * a0,
                "gw_stiffness_N_per_m": gw.stiffness * a0,
            }
        for k, v in vals.items():
            out[k][ok] = np.where(np.isfinite(v), v, np.nan)
    modulus = float(material.contact_modulus)
    slope = psd.slope_rms
    if area is not None:
        a = np.atleast_1d(np.asarray(area, dtype=np.float64))
        with np.errstate(divide="ignore", invalid="ignore"):
            out["bem_kappa"] = np.where(
                ok, (a / a0) * modulus * slope / np.where(ok, p, 1.0), np.nan
            )
    out["spectrum_source"] = np.full(m, psd.source, dtype=object)
    out["spectrum_slope_rms"] = np.full(m, slope)
    out["spectrum_q_max_per_m"] = np.full(m, float(psd.wavevector[-1]))
    return out


def kappa_record(
    columns: Any, area: Any, apparent_area: float, *, pixel_area: float | None = None
) -> dict[str, Any]:
    """The small-load κ of elastic solves (A/A₀ = κ p/(E* h′_rms)) beside the theories'.

    Parameters
    ----------
    columns : mapping
        The :func:`theory_columns` of the solves (a dict or a DataFrame's columns):
        ``bem_kappa``, ``persson_area_m2``, ``gw_area_m2``, ``spectrum_slope_rms``.
    area : (m,) array_like
        The solves' contact areas A (m²).
    apparent_area : float
        A₀ (m²).
    pixel_area : float, optional
        The map's pixel area (m²): solves with fewer than ``KAPPA_MIN_PIXELS`` contact
        pixels are left out (a contact of a few pixels does not resolve its area).

    Returns
    -------
    dict
        ``bem``: the mean κ of the solves with 0 < A/A₀ ≤ ``KAPPA_MAX_AREA_FRACTION``
        (and at least ``KAPPA_MIN_PIXELS`` contact pixels, given ``pixel_area``; None
        when there is none), ``bem_range`` (min, max), ``n_solves``, ``min_pixels``; ``persson`` and
        ``gw``: the theories' κ at the same pressures (mean); ``persson_limit`` √(8/π) and
        ``bgt_limit`` √(2π), the small-load limits (all dimensionless); ``max_area_fraction``;
        ``slope_rms`` (h′_rms of the spectrum, the one κ is measured with).

    Notes
    -----
    κ of a theory at the same p is κ_BEM·A_theory/A_BEM (both are A/A₀ · E* h′_rms/p).
    """
    k = np.asarray(columns["bem_kappa"], dtype=np.float64)
    a = np.atleast_1d(np.asarray(area, dtype=np.float64))
    ar = a / float(apparent_area)
    slope = np.asarray(columns["spectrum_slope_rms"], dtype=np.float64)
    sel = np.isfinite(k) & (ar > 0) & (ar <= KAPPA_MAX_AREA_FRACTION)
    if pixel_area is not None:
        sel &= a >= KAPPA_MIN_PIXELS * float(pixel_area) * (1 - 1e-9)
    out: dict[str, Any] = {
        "bem": None,
        "bem_range": None,
        "n_solves": int(sel.sum()),
        "min_pixels": KAPPA_MIN_PIXELS if pixel_area is not None else None,
        "persson": None,
        "gw": None,
        "persson_limit": KAPPA_PERSSON,
        "bgt_limit": KAPPA_BGT,
        "max_area_fraction": KAPPA_MAX_AREA_FRACTION,
        "slope_rms": float(slope[0]) if slope.size else None,
    }
    if sel.any():
        kb = k[sel]
        kp = kb * np.asarray(columns["persson_area_m2"], dtype=np.float64)[sel] / a[sel]
        kg = kb * np.asarray(columns["gw_area_m2"], dtype=np.float64)[sel] / a[sel]
        out.update(
            bem=float(kb.mean()),
            bem_range=[float(kb.min()), float(kb.max())],
            persson=float(kp.mean()),
            gw=float(kg.mean()),
        )
    return out
