# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Power-law fits of indentation cells with 95 % confidence intervals.

A fit E_c/E = β·[F/(E·A)]^α of one contact model uses only the cells that may enter it
(``in_fit``: resolved in the pixel size, not saturated, converged) and is made from at least
:data:`MIN_FIT_POINTS` of them. Its intervals come from a bootstrap over **indents** — one
punch placement on one surface realisation, with all its peak loads — not over the loads of
one indent, whose points are not independent: each replicate draws, per punch diameter, as
many indents as there are, with replacement, and fits the cells of the drawn indents by the
same least squares in log–log (:func:`warptrunc.stiffness.fit_power_law`). The 95 % interval
is the 2.5th to 97.5th percentile of α and of β over the replicates with at least
:data:`MIN_FIT_POINTS` cells and two distinct loads.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..stiffness import PowerLawFit, fit_power_law

__all__ = ["MIN_FIT_POINTS", "N_BOOTSTRAP", "IndentFit", "bootstrap_power_law", "fit_cells"]

MIN_FIT_POINTS = 6
"""Fewest cells of a fit; with fewer, the fit is not made."""
N_BOOTSTRAP = 2000
"""Bootstrap replicates of the intervals."""
CI_METHOD = (
    "percentile bootstrap over indents (punch placement × surface realisation), "
    "resampled within each punch diameter"
)


@dataclass(frozen=True, eq=False)
class IndentFit:
    """A power-law fit of one contact model over its cells, with 95 % intervals.

    The fit's own fields (``alpha``, ``beta``, ``r2``, ``F_over_EA_min``, …) read through:
    ``fit.alpha`` is ``fit.fit.alpha``.
    """

    fit: PowerLawFit
    """The least-squares fit over every cell used."""
    alpha_ci95: tuple[float, float]
    """95 % interval of α (dimensionless); NaN with fewer than two indents."""
    beta_ci95: tuple[float, float]
    """95 % interval of β (dimensionless); NaN with fewer than two indents."""
    n_points: int
    """Cells fitted (count)."""
    n_indents: int
    """Indents the cells come from (count)."""
    n_bootstrap: int
    """Bootstrap replicates that gave a fit (count)."""

    def __getattr__(self, name: str) -> Any:
        if name == "fit":  # not yet set (copy, unpickling)
            raise AttributeError(name)
        return getattr(self.fit, name)

    def to_dict(self) -> dict[str, Any]:
        """The fit's fields with the intervals and counts (SI, JSON-able).

        Returns
        -------
        dict
            :meth:`PowerLawFit.to_dict` and ``made`` (True), ``alpha_ci95``, ``beta_ci95``
            ([low, high]), ``n_points``, ``n_indents``, ``n_bootstrap``, ``ci_method``.
        """
        return {
            **self.fit.to_dict(),
            "made": True,
            "alpha_ci95": list(self.alpha_ci95),
            "beta_ci95": list(self.beta_ci95),
            "n_points": self.n_points,
            "n_indents": self.n_indents,
            "n_bootstrap": self.n_bootstrap,
            "ci_method": CI_METHOD,
        }


def bootstrap_power_law(
    x: Any,
    y: Any,
    indent: Any,
    stratum: Any,
    *,
    n_boot: int = N_BOOTSTRAP,
    seed: int = 0,
    min_points: int = MIN_FIT_POINTS,
) -> dict[str, Any]:
    """95 % percentile intervals of α and β of y = β·x^α, resampling whole indents.

    Parameters
    ----------
    x, y : (m,) array_like
        Abscissae and ordinates (> 0, finite), one per cell.
    indent : (m,) array_like
        Indent label of each cell (any hashable values): the unit resampled.
    stratum : (m,) array_like
        Stratum of each cell (the punch diameter): indents are drawn within it, as many as
        it has. An indent lies in one stratum.
    n_boot : int
        Replicates.
    seed : int
        Seed of the draws (``numpy.random.default_rng``).
    min_points : int
        Fewest cells of a replicate's fit.

    Returns
    -------
    dict
        ``alpha_ci95``, ``beta_ci95`` ((low, high); NaN with fewer than two indents or no
        replicate that fits), ``n_bootstrap`` (replicates that fitted), ``n_indents``.
    """
    lx, ly = np.log(np.asarray(x, np.float64)), np.log(np.asarray(y, np.float64))
    ids, inv = np.unique(np.asarray(indent), return_inverse=True, axis=0)
    inv = inv.reshape(-1)
    n_ind = len(ids)
    nan2 = (math.nan, math.nan)
    if n_ind < 2 or lx.size == 0:
        return {"alpha_ci95": nan2, "beta_ci95": nan2, "n_bootstrap": 0, "n_indents": n_ind}
    # sufficient statistics per indent: n, Σx, Σy, Σx², Σxy
    stats = np.zeros((n_ind, 5))
    for col, v in enumerate((np.ones_like(lx), lx, ly, lx * lx, lx * ly)):
        stats[:, col] = np.bincount(inv, weights=v, minlength=n_ind)
    strata = np.asarray(stratum)
    first = np.zeros(n_ind, dtype=int)
    first[inv[::-1]] = np.arange(inv.size)[::-1]  # a cell of each indent
    ind_stratum = strata[first]
    rng = np.random.default_rng(seed)
    counts = np.zeros((n_boot, n_ind))
    for s in np.unique(ind_stratum):
        members = np.flatnonzero(ind_stratum == s)
        draws = rng.integers(0, members.size, size=(n_boot, members.size))
        for k in range(members.size):
            counts[:, members[k]] = (draws == k).sum(axis=1)
    tot = counts @ stats
    n, sx, sy, sxx, sxy = tot.T
    with np.errstate(divide="ignore", invalid="ignore"):
        var = sxx - sx * sx / n
        alpha = (sxy - sx * sy / n) / var
        beta = np.exp((sy - alpha * sx) / n)
    ok = (
        (n >= min_points)
        & (var > 1e-12 * np.maximum(n, 1))
        & np.isfinite(alpha)
        & np.isfinite(beta)
    )
    if not ok.any():
        return {"alpha_ci95": nan2, "beta_ci95": nan2, "n_bootstrap": 0, "n_indents": n_ind}
    q = lambda v: tuple(float(t) for t in np.percentile(v[ok], [2.5, 97.5]))  # noqa: E731
    return {
        "alpha_ci95": q(alpha),
        "beta_ci95": q(beta),
        "n_bootstrap": int(ok.sum()),
        "n_indents": n_ind,
    }


def fit_cells(
    x: Any,
    y: Any,
    depth: Any,
    indent: Any,
    stratum: Any,
    material: Any,
    *,
    n_boot: int = N_BOOTSTRAP,
    seed: int = 0,
) -> IndentFit | None:
    """The fit E_c/E = β·[F/(E·A)]^α of given cells with its bootstrap intervals.

    Parameters
    ----------
    x : (m,) array_like
        F/(E·A) of the cells (dimensionless, > 0).
    y : (m,) array_like
        E_c/E of the cells (dimensionless, > 0).
    depth : (m,) array_like
        The approach (or truncation depth) of each cell (m), for the fit's depth range.
    indent, stratum : (m,) array_like
        Indent and punch diameter of each cell (:func:`bootstrap_power_law`).
    material : Material
        For ``beta_contact_modulus``.
    n_boot : int
        Bootstrap replicates.
    seed : int
        Seed of the replicates.

    Returns
    -------
    IndentFit or None
        None (the fit is not made) with fewer than :data:`MIN_FIT_POINTS` cells or one load.
    """
    x, y = np.asarray(x, np.float64), np.asarray(y, np.float64)
    if x.size < MIN_FIT_POINTS:
        return None
    curve = SimpleNamespace(
        load=x,
        n_contact_pixels=np.ones(x.size, np.int64),
        depth=np.asarray(depth, np.float64),
        F_over_EA=x,
        Ec_over_E=y,
        material=material,
    )
    try:
        fit = fit_power_law(curve, min_pixels=1)  # type: ignore[arg-type]
    except ValueError:
        return None
    b = bootstrap_power_law(x, y, indent, stratum, n_boot=n_boot, seed=seed)
    return IndentFit(
        fit,
        b["alpha_ci95"],
        b["beta_ci95"],
        int(x.size),
        int(b["n_indents"]),
        int(b["n_bootstrap"]),
    )
