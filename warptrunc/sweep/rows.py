# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The columns of a sweep case beside its truncation fit: its blank row, its fit ranges, the
fractal-dimension columns and the elastic columns (the half-space solver against Eq. 2 at
δ = f·R_t, when ``bem_fractions`` is set).

Used by :mod:`warptrunc.sweep.engines`, which fills the rows.
"""

from __future__ import annotations

import functools
import json
import math
import socket
import time
from typing import Any

import numpy as np

from .._support.docs import SHARED_DOCS, fill_doc
from .._support.provenance import __version__, git_commit
from ..stiffness import DEFAULT_MIN_PIXELS, flat_punch_stiffness, stiffness_curve
from ..truncation.api import truncate
from .grid import Case
from .options import FRACTAL_METHODS, SweepOptions

__all__ = [
    "base_row",
    "bem_blank",
    "elastic_record",
    "fit_ranges",
    "fractal_record",
    "resolve_min_pixels",
]


@functools.cache
def _provenance() -> tuple[str, str | None, str]:
    return __version__, git_commit(), socket.gethostname()


def base_row(case: Case, o: SweepOptions) -> dict[str, Any]:
    """The columns of a case before it runs.

    Parameters
    ----------
    case : Case
        The case.
    o : SweepOptions
        The sweep's options.

    Returns
    -------
    dict of str to Any
        Inputs, options and provenance, the results missing (NaN or None), SI units.
    """
    Lx, Ly = (o.L, o.L) if isinstance(o.L, float) else o.L
    nx, ny = (o.n, o.n) if isinstance(o.n, int) else o.n
    lo, hi = o.depth_window if o.depth_window is not None else (np.nan, np.nan)
    version, commit, host = _provenance()
    return {
        "case_id": case.case_id,
        "case_index": case.index,
        "D_in": case.D,
        "delta": case.delta,
        "seed": case.seed,
        "Rt_m": case.delta * o.Wr,
        "Wr_m": o.Wr,
        "Lx_m": Lx,
        "Ly_m": Ly,
        "nx": nx,
        "ny": ny,
        "M": o.M,
        "gamma": o.gamma,
        "Wc_m": np.nan if o.Wc is None else o.Wc,
        "cutoff": o.cutoff,
        "increments": o.increments,
        "max_depth_fraction": o.max_depth_fraction,
        "max_depth_m": np.nan if o.max_depth is None else o.max_depth,
        "E_Pa": o.E,
        "nu": o.nu,
        "E_flat_Pa": o.E_i,
        "nu_flat": o.nu_i,
        "beta_prime": o.beta_prime,
        "depth_window_lo_m": lo,
        "depth_window_hi_m": hi,
        "alpha": np.nan,
        "beta": np.nan,
        "beta_contact_modulus": np.nan,
        "r2": np.nan,
        "n_points": None,
        "fit_depth_min_m": np.nan,
        "fit_depth_max_m": np.nan,
        "final_contact_pixels": None,
        "final_area_fraction": np.nan,
        "Rt_measured_m": np.nan,
        "slope_rms": np.nan,
        "curvature_rms_per_m": np.nan,
        "slope_rms_spectrum": np.nan,
        **{f"D_{m}{s}": np.nan for m in FRACTAL_METHODS for s in ("", "_r2")},
        "fractal_options": None,
        "fractal_seconds": np.nan,
        "fit_error": None,
        "warnings": None,
        "error": None,
        "host": host,
        "warptrunc_version": version,
        "git_commit": commit,
        **bem_blank(o),
    }


def fit_ranges(o: SweepOptions) -> list[tuple[int | None, float]]:
    """The fit ranges of the sweep, absolute ones first.

    Parameters
    ----------
    o : SweepOptions
        The sweep's options (``min_pixels``, ``min_pixels_fraction``).

    Returns
    -------
    list of (int or None, float)
        ``(min_pixels, NaN)`` per absolute range (pixels), ``(None, fraction)`` per relative
        one (dimensionless).
    """
    return [(mp, math.nan) for mp in o.min_pixels] + [
        (None, f) for f in o.min_pixels_fraction or ()
    ]


def resolve_min_pixels(fraction: float, final_contact_pixels: int) -> int:
    """max(DEFAULT_MIN_PIXELS, ⌈fraction·final_contact_pixels⌉): a relative fit range's count.

    Parameters
    ----------
    fraction : float
        Fraction of the contact pixels at the deepest truncation (dimensionless).
    final_contact_pixels : int
        Contact pixels at the deepest truncation (count).

    Returns
    -------
    int
        The ``min_pixels`` of the fit range (pixels).

    Notes
    -----
    The product is rounded to 9 decimals before the ceiling, so that float noise
    (0.05·280 = 14.000000000000002) does not add a pixel.
    """

    return max(DEFAULT_MIN_PIXELS, math.ceil(round(fraction * final_contact_pixels, 9)))


def fractal_record(fits: dict[str, Any]) -> dict[str, Any]:
    """Columns ``D_<m>``, ``D_<m>_r2`` and ``fractal_options`` (JSON) of ``{m: FractalFit}``.

    Parameters
    ----------
    fits : dict of str to FractalFit
        Fits by method key.

    Returns
    -------
    dict of str to Any
        ``D_<m>`` and ``D_<m>_r2`` (float, dimensionless) per method, and ``fractal_options``
        (a JSON string).

    Notes
    -----
    ``fractal_options`` holds, per method, the scalars of :meth:`FractalFit.to_dict` (slope,
    intercept, fit range in m), the number of fitted scales and the fit's ``options`` (the
    convention it ran with); the per-scale arrays are left out to keep rows small.
    """
    out: dict[str, Any] = {}
    info = {}
    for m, f in fits.items():
        out[f"D_{m}"], out[f"D_{m}_r2"] = float(f.D), float(f.r2)
        d = {k: v for k, v in f.to_dict().items() if np.ndim(v) == 0 and k not in ("D", "r2")}
        info[m] = {**d, "n_fitted": f.n_fitted, "options": f.options}
    out["fractal_options"] = json.dumps(info, default=_json_default, allow_nan=True)
    return out


def _json_default(v: Any) -> Any:
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, np.generic):
        return v.item()
    raise TypeError(f"{type(v).__name__} is not JSON-serialisable")


def bem_blank(o: SweepOptions) -> dict[str, Any]:
    """The elastic columns of a case before its solve.

    Parameters
    ----------
    o : SweepOptions
        The sweep's options (``bem_fractions``).

    Returns
    -------
    dict of str to Any
        Every elastic column missing (NaN, or None for flags and counts); empty without
        ``bem_fractions``.
    """
    from .read import BEM_QUANTITIES

    if o.bem_fractions is None:
        return {}
    out: dict[str, Any] = {}
    for f in o.bem_fractions:
        for q in BEM_QUANTITIES:
            out[f"{q}_{f:g}"] = None if q in ("bem_converged", "bem_iterations") else np.nan
    return {**out, "bem_seconds": np.nan, "bem_error": None}


@fill_doc(SHARED_DOCS)
def elastic_record(
    surface, sc, options: SweepOptions, device=None, *, devices: Any = None
) -> dict[str, Any]:
    """Elastic columns of one case: the free half-space solver against Eq. 2 at δ = f·R_t.

    Parameters
    ----------
    surface : Surface
        The generated surface.
    sc : StiffnessCurve
        Its truncation curve (:func:`~warptrunc.stiffness.stiffness_curve`); a deeper one is
        computed when the largest approach lies beyond it.
    options : SweepOptions
        ``bem_fractions`` (f, dimensionless), material, β', increments.
    {warp_device}
    devices : int, "auto" or list, optional
        Spread the elastic solver over several devices (``contact_solver(..., devices=...)``;
        JAX); default None: ``device`` alone.

    Returns
    -------
    dict of str to Any
        The columns of ``warptrunc.sweep.read.bem_columns`` (SI units).

    Notes
    -----
    Truncation at δ: A' = (pixels with z ≥ z_max − δ)·pixel area (exact count, float32 as the
    kernels), k' = β'·(2/√π)·E*·√A' (Eq. 2), F'(δ) by linear interpolation of the curve's
    trapezoidal load; the same formulas as ``warptrunc.bem_check``. The elastic
    solve is :func:`warptrunc.contact.solve_contact` on its defaults (free substrate, Barber's
    stiffness; :class:`~warptrunc.contact.SolverSettings`, :class:`~warptrunc.contact.CurveSettings`),
    warm-started over increasing δ; a solve that stops at its iteration limit is kept with
    ``bem_converged_<f>`` False. A solver error leaves the columns NaN and sets ``bem_error``.
    """
    from ..contact.curve import solve_contact

    o = options
    out = bem_blank(o)
    t0 = time.perf_counter()
    Rt = float(sc.Rt)
    fr = np.asarray(o.bem_fractions, dtype=np.float64)
    d = fr * Rt
    contact_modulus = o.material().contact_modulus
    z = surface.heights
    z_top = np.float32(z.max())
    n_trunc = np.array([np.count_nonzero(z >= np.float32(z_top - v)) for v in d], dtype=np.int64)
    a_trunc = n_trunc * surface.pixel_area
    k_trunc = flat_punch_stiffness(np.sqrt(a_trunc), contact_modulus, beta_prime=o.beta_prime)
    deep = sc
    if d[-1] > sc.depth[-1]:
        tc = truncate(surface, o.increments, max_depth=float(d[-1]), device=device)
        deep = stiffness_curve(tc, o.material(), beta_prime=o.beta_prime)
    f_trunc = np.interp(d, deep.depth, deep.load)
    try:
        # the solver's defaults: free substrate, float64, Barber's stiffness
        cc = solve_contact(surface, depths=d, material=o.material(), device=device, devices=devices)
    except Exception as exc:  # recorded; the truncation results stand
        out["bem_error"] = f"{type(exc).__name__}: {exc}"
        out["bem_seconds"] = time.perf_counter() - t0
        return out
    with np.errstate(divide="ignore", invalid="ignore"):
        for i, f in enumerate(o.bem_fractions):
            s = f"_{f:g}"
            out.update(
                {
                    "bem_depth_m" + s: float(d[i]),
                    "F_bem_N" + s: float(cc.load[i]),
                    "A_bem_m2" + s: float(cc.area[i]),
                    "k_bem_N_per_m" + s: float(cc.stiffness[i]),
                    "F_trunc_N" + s: float(f_trunc[i]),
                    "A_trunc_m2" + s: float(a_trunc[i]),
                    "k_trunc_N_per_m" + s: float(k_trunc[i]),
                    "F_ratio" + s: float(np.float64(cc.load[i]) / f_trunc[i]),
                    "A_ratio" + s: float(np.float64(cc.area[i]) / a_trunc[i]),
                    "k_ratio" + s: float(np.float64(cc.stiffness[i]) / k_trunc[i]),
                    "bem_converged" + s: bool(cc.converged[i]),
                    "bem_iterations" + s: int(cc.n_iterations[i]),
                }
            )
    out["bem_seconds"] = time.perf_counter() - t0
    return out
