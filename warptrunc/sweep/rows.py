# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The columns of a sweep case: its blank row, fit ranges and fractal-dimension columns.

Used by :mod:`warptrunc.sweep.engines`, which fills the rows.
"""

from __future__ import annotations

import functools
import json
import math
import socket
from typing import Any

import numpy as np

from .._support.provenance import git_commit
from .._support.version import __version__
from ..stiffness import DEFAULT_MIN_PIXELS
from .elastic import bem_blank
from .grid import Case
from .options import FRACTAL_METHODS, SweepOptions

__all__ = ["base_row", "fit_ranges", "fractal_record", "resolve_min_pixels"]


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
        "case_id": case.case_id, "case_index": case.index, "D_in": case.D, "delta": case.delta,
        "seed": case.seed, "Rt_m": case.delta * o.Wr, "Wr_m": o.Wr, "Lx_m": Lx, "Ly_m": Ly,
        "nx": nx, "ny": ny, "M": o.M, "gamma": o.gamma,
        "Wc_m": np.nan if o.Wc is None else o.Wc, "cutoff": o.cutoff,
        "increments": o.increments, "max_depth_fraction": o.max_depth_fraction,
        "max_depth_m": np.nan if o.max_depth is None else o.max_depth, "E_Pa": o.E, "nu": o.nu,
        "E_flat_Pa": o.E_flat, "nu_flat": o.nu_flat, "beta_prime": o.beta_prime,
        "depth_window_lo_m": lo, "depth_window_hi_m": hi, "alpha": np.nan, "beta": np.nan,
        "beta_contact_modulus": np.nan,
        "r2": np.nan, "n_points": None, "fit_depth_min_m": np.nan, "fit_depth_max_m": np.nan,
        "final_contact_pixels": None, "final_area_fraction": np.nan, "Rt_measured_m": np.nan,
        **{f"D_{m}{s}": np.nan for m in FRACTAL_METHODS for s in ("", "_r2")},
        "fractal_options": None, "fractal_seconds": np.nan, "fit_error": None, "warnings": None, "error": None, "host": host, "warptrunc_version": version,
        "git_commit": commit, **bem_blank(o),
    }  # fmt: skip


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
    return [(mp, math.nan) for mp in o.min_pixels] + [(None, f) for f in o.min_pixels_fraction]


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
