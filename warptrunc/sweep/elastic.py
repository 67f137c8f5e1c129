# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic columns of a sweep case: the half-space BEM solver against Eq. 2 at δ = f·R_t.

Used by :func:`warptrunc.sweep.engines.compute_case` when ``bem_fractions`` is set.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from .._support.docs import SHARED_DOCS, fill_doc
from ..stiffness import flat_punch_stiffness, stiffness_curve
from ..truncation.api import truncate
from .options import SweepOptions

__all__ = ["bem_blank", "elastic_record"]


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

    if not o.bem_fractions:
        return {}
    out: dict[str, Any] = {}
    for f in o.bem_fractions:
        for q in BEM_QUANTITIES:
            out[f"{q}_{f:g}"] = None if q in ("bem_converged", "bem_iterations") else np.nan
    return {**out, "bem_seconds": np.nan, "bem_error": None}


@fill_doc(SHARED_DOCS)
def elastic_record(surface, sc, options: SweepOptions, device=None, *,
                   devices: Any = None) -> dict[str, Any]:  # fmt: skip
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
        Spread the elastic solver over several devices (``ContactSolver(..., devices=...)``;
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
    solve is :func:`warptrunc.contact.solve_contact` (``substrate="free"``, Barber stiffness),
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
        cc = solve_contact(surface, depths=d, contact_modulus=contact_modulus, substrate="free",
                           stiffness="barber", device=device, devices=devices)  # fmt: skip
    except Exception as exc:  # recorded; the truncation results stand
        out["bem_error"] = f"{type(exc).__name__}: {exc}"
        out["bem_seconds"] = time.perf_counter() - t0
        return out
    with np.errstate(divide="ignore", invalid="ignore"):
        for i, f in enumerate(o.bem_fractions):
            s = f"_{f:g}"
            out.update({
                "bem_depth_m" + s: float(d[i]), "F_bem_N" + s: float(cc.load[i]),
                "A_bem_m2" + s: float(cc.area[i]), "k_bem_N_per_m" + s: float(cc.stiffness[i]),
                "F_trunc_N" + s: float(f_trunc[i]), "A_trunc_m2" + s: float(a_trunc[i]),
                "k_trunc_N_per_m" + s: float(k_trunc[i]),
                "F_ratio" + s: float(np.float64(cc.load[i]) / f_trunc[i]),
                "A_ratio" + s: float(np.float64(cc.area[i]) / a_trunc[i]),
                "k_ratio" + s: float(np.float64(cc.stiffness[i]) / k_trunc[i]),
                "bem_converged" + s: bool(cc.converged[i]),
                "bem_iterations" + s: int(cc.n_iterations[i]),
            })  # fmt: skip
    out["bem_seconds"] = time.perf_counter() - t0
    return out
