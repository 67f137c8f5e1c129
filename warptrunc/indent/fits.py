# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Power-law fits of indentation cells over loads, one punch at a time, with 95 % intervals.

**Over loads, per punch.** E_c/E = β·[F/(E·A)]^α is a law in the load: it is fitted per
punch diameter over the cells ``in_fit`` of that punch (:func:`fit_model`), and made only when
they hold at least :data:`MIN_LOADS` distinct peak loads. A slope between punch sizes at one
load measures how K scales with the punch, not with the load (in the many-contact regime K
does not depend on the punch area at fixed F, so that slope is 0.5 by construction): a fit
over one load and several punches, or over two loads, is refused (``made`` False) with the
reason. A **pooled** fit over every punch whose own fit is made is given beside the per-punch
fits, and only where they agree: where the per-punch 95 % intervals of α have a value in
common (max of the lower ends ≤ min of the upper ends), tested on every punch fitted; else it is
refused with the intervals that disagree.

**Intervals over independent surfaces.** The unit resampled is the **indent** — one punch
placement on one surface realisation, all its loads together (the loads of one indent are not
independent points) — and indents on one realisation share its long waves, so the bootstrap is
hierarchical (:func:`bootstrap_power_law` with ``group``): each replicate draws as many
realisations as there are, with replacement, then within each drawn realisation and punch as
many placements as it holds, with replacement, and fits the drawn cells by the least squares
in log–log of :func:`warptrunc.stiffness.fit_power_law`. Drawn at both levels as they are,
such a bootstrap counts the placements' scatter twice (once in the realisation means, once
within); the realisation level is therefore shrunk to its own variance component (Davison &
Hinkley [1]_, § 3.8): indent u of realisation g enters as s̄ + c·(s̄_g − s̄) + (s_u − s̄_g) of
its sufficient statistics s, with c² = n/(n − 1)·max(0, 1 − MS_within/MS_between) from the
one-way analysis of variance of the indents' influence on α over the n realisations. Without a
realisation effect c ≈ 0 and the interval is that of the flat bootstrap over indents; with one,
it is wider; with one realisation it is the flat one. The 95 % interval is the 2.5th to 97.5th
percentile over the replicates that fit.

**The cell rule is a systematic.** Which cells are resolved depends on the rule: the one rule
of the fits is the unloading stiffness K converged in the pixel size (``stiffness``); the
same fit over the cells whose contact area also converged (``stiffness_and_area``) moves α. Each
fit is made under both rules and its reported ``alpha_ci95`` / ``beta_ci95`` span both rules'
intervals (their union's hull, at least as wide as the wider), so that they include the rule's
systematic; the rules' own fits are kept (``rules``).

References
----------
.. [1] A.C. Davison, D.V. Hinkley, *Bootstrap Methods and their Application*, Cambridge
   University Press (1997), § 3.8 (hierarchical data).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..stiffness import PowerLawFit, fit_power_law

__all__ = [
    "CI_METHOD",
    "MIN_FIT_POINTS",
    "MIN_LOADS",
    "N_BOOTSTRAP",
    "RULES",
    "IndentFit",
    "ModelFits",
    "agree_within_intervals",
    "bootstrap_power_law",
    "fit_model",
]

MIN_LOADS = 3
"""Fewest distinct peak loads of one punch with cells ``in_fit`` for a fit over loads."""
MIN_FIT_POINTS = MIN_LOADS
"""Fewest cells of a fit (one per load at least)."""
N_BOOTSTRAP = 2000
"""Bootstrap replicates of the intervals."""
RULES = ("stiffness", "stiffness_and_area")
"""The cell rules every fit is made under: ``stiffness``, the one rule (K converged in the
pixel size), and ``stiffness_and_area`` (the contact area converged too), whose difference is
the rule's systematic."""
CI_METHOD = (
    "hierarchical percentile bootstrap over indents: surface realisations with replacement, "
    "then the placements of each drawn realisation and punch with replacement, the realisation "
    "level shrunk to its variance component (Davison & Hinkley 1997, 3.8); the interval spans "
    "the fits under both cell rules (stiffness; stiffness and area)"
)


# --- the bootstrap ----------------------------------------------------------------------------


def _sufficient(lx: np.ndarray, ly: np.ndarray, inv: np.ndarray, n_ind: int) -> np.ndarray:
    """Per indent: n, Σx, Σy, Σx², Σxy of its cells (logs)."""
    stats = np.zeros((n_ind, 5))
    for col, v in enumerate((np.ones_like(lx), lx, ly, lx * lx, lx * ly)):
        stats[:, col] = np.bincount(inv, weights=v, minlength=n_ind)
    return stats


def _line(tot: np.ndarray, min_points: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """α, β and which rows fit, from totals of sufficient statistics (rows: replicates)."""
    n, sx, sy, sxx, sxy = tot.T
    with np.errstate(divide="ignore", invalid="ignore"):
        var = sxx - sx * sx / n
        alpha = (sxy - sx * sy / n) / var
        beta = np.exp((sy - alpha * sx) / n)
    ok = (
        (n >= min_points - 1e-9)
        & (var > 1e-12 * np.maximum(np.abs(n), 1))
        & np.isfinite(alpha)
        & np.isfinite(beta)
    )
    return alpha, beta, ok


def _labels(v: Any) -> tuple[np.ndarray, np.ndarray]:
    """Unique labels (rows of a 2-D array, or values) and each item's index among them."""
    a = np.asarray(v)
    ids, inv = np.unique(a, return_inverse=True, axis=0)
    return ids, inv.reshape(-1)


def _influence(lx: np.ndarray, ly: np.ndarray, inv: np.ndarray, n_ind: int) -> np.ndarray:
    """Each indent's empirical influence on the least-squares slope over every cell:
    Σ_cells (x − x̄)·(residual) / Σ(x − x̄)²."""
    xc = lx - lx.mean()
    sxx = float(xc @ xc)
    if not sxx > 0:
        return np.zeros(n_ind)
    a = float(xc @ (ly - ly.mean())) / sxx
    resid = ly - ly.mean() - a * xc
    return np.bincount(inv, weights=xc * resid, minlength=n_ind) / sxx


def _shrink(values: np.ndarray, groups: np.ndarray) -> float:
    """c of the realisation level: c² = n/(n − 1)·max(0, 1 − MS_w/MS_b) of a one-way
    analysis of variance of ``values`` over ``groups`` (n groups); c² = n/(n − 1) with one
    value per group (no within-group spread to take out), 0 with one group."""
    ids, inv = np.unique(groups, return_inverse=True)
    n = ids.size
    if n < 2:
        return 0.0
    sizes = np.bincount(inv, minlength=n).astype(np.float64)
    means = np.bincount(inv, weights=values, minlength=n) / sizes
    grand = float(values.mean())
    ms_b = float(np.sum(sizes * (means - grand) ** 2)) / (n - 1)
    dfw = values.size - n
    if dfw <= 0:
        return math.sqrt(n / (n - 1))
    ms_w = float(np.sum((values - means[inv]) ** 2)) / dfw
    if not ms_b > 0:
        return 0.0
    return math.sqrt(n / (n - 1) * max(0.0, 1.0 - ms_w / ms_b))


def bootstrap_power_law(
    x: Any,
    y: Any,
    indent: Any,
    stratum: Any,
    group: Any = None,
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
    indent : (m,) or (m, k) array_like
        Indent label of each cell (values or rows): the unit resampled.
    stratum : (m,) array_like
        Stratum of each cell (the punch diameter): indents are drawn within it, as many as it
        has. An indent lies in one stratum.
    group : (m,) array_like, optional
        Surface realisation of each cell: the bootstrap is hierarchical (realisations drawn
        with replacement, then the placements of each drawn realisation and stratum, the
        realisation level shrunk to its variance component: :mod:`warptrunc.indent.fits`).
        None (or one realisation): the flat bootstrap over the indents of each stratum.
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
        replicate that fits), ``n_bootstrap`` (replicates that fitted), ``n_indents``,
        ``n_realisations``, ``shrink`` (per stratum, c of the realisation level; empty for the
        flat bootstrap) and ``hierarchical`` (bool).
    """
    lx, ly = np.log(np.asarray(x, np.float64)), np.log(np.asarray(y, np.float64))
    ids, inv = _labels(indent)
    n_ind = len(ids)
    nan2 = (math.nan, math.nan)
    strata = np.asarray(stratum)
    first = np.zeros(n_ind, dtype=int)
    first[inv[::-1]] = np.arange(inv.size)[::-1]  # a cell of each indent
    ind_stratum = strata[first] if n_ind else strata[:0]
    groups = None
    if group is not None and n_ind:
        g_all = np.asarray(group)
        ind_group = g_all[first]
        if np.unique(ind_group).size > 1:
            groups = ind_group
    out = {
        "alpha_ci95": nan2,
        "beta_ci95": nan2,
        "n_bootstrap": 0,
        "n_indents": n_ind,
        "n_realisations": 1 if groups is None else int(np.unique(groups).size),
        "shrink": {},
        "hierarchical": groups is not None,
    }
    if n_ind < 2 or lx.size == 0:
        return out
    stats = _sufficient(lx, ly, inv, n_ind)
    rng = np.random.default_rng(seed)
    if groups is None:
        counts = np.zeros((n_boot, n_ind))
        for s in np.unique(ind_stratum):
            members = np.flatnonzero(ind_stratum == s)
            draws = rng.integers(0, members.size, size=(n_boot, members.size))
            for k in range(members.size):
                counts[:, members[k]] = (draws == k).sum(axis=1)
        tot = counts @ stats
    else:
        tot = _hierarchical_totals(stats, ind_stratum, groups, lx, ly, inv, n_boot, rng, out)
    alpha, beta, ok = _line(tot, min_points)
    if not ok.any():
        return out
    q = lambda v: tuple(float(t) for t in np.percentile(v[ok], [2.5, 97.5]))  # noqa: E731
    out.update(alpha_ci95=q(alpha), beta_ci95=q(beta), n_bootstrap=int(ok.sum()))
    return out


def _hierarchical_totals(
    stats: np.ndarray,
    ind_stratum: np.ndarray,
    groups: np.ndarray,
    lx: np.ndarray,
    ly: np.ndarray,
    inv: np.ndarray,
    n_boot: int,
    rng: np.random.Generator,
    out: dict[str, Any],
) -> np.ndarray:
    """Totals of the replicates' sufficient statistics: realisations drawn with replacement
    (shared by every stratum), then within each drawn realisation and stratum its placements,
    the realisation level shrunk to its variance component (c)."""
    gids, ginv = np.unique(groups, return_inverse=True)
    n_g = gids.size
    k = rng.multinomial(n_g, np.full(n_g, 1.0 / n_g), size=n_boot)  # (n_boot, n_g)
    influence = _influence(lx, ly, inv, stats.shape[0])
    tot = np.zeros((n_boot, 5))
    for s in np.unique(ind_stratum):
        members = np.flatnonzero(ind_stratum == s)
        c = _shrink(influence[members], ginv[members])
        out["shrink"][float(s) if np.ndim(s) == 0 else str(s)] = c
        mean_s = stats[members].mean(axis=0)
        for g in np.unique(ginv[members]):
            mem = members[ginv[members] == g]
            m = mem.size
            mean_g = stats[mem].mean(axis=0)
            kg = k[:, g]
            tot += (kg * m)[:, None] * (mean_s + c * (mean_g - mean_s))[None, :]
            within = rng.multinomial(kg * m, np.full(m, 1.0 / m))  # (n_boot, m)
            tot += within @ (stats[mem] - mean_g)
    return tot


# --- one fit ----------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class IndentFit:
    """A power-law fit E_c/E = β·[F/(E·A)]^α over loads, with 95 % intervals.

    The fit's own fields (``alpha``, ``beta``, ``r2``, ``F_over_EA_min``, …) read through:
    ``fit.alpha`` is ``fit.fit.alpha``.
    """

    fit: PowerLawFit
    """The least-squares fit over the cells of the one rule (``stiffness``)."""
    alpha_ci95: tuple[float, float]
    """95 % interval of α spanning both cell rules' intervals (dimensionless); NaN with fewer
    than two indents."""
    beta_ci95: tuple[float, float]
    """95 % interval of β, likewise (dimensionless)."""
    n_points: int
    """Cells fitted (count)."""
    n_indents: int
    """Indents the cells come from (count)."""
    n_bootstrap: int
    """Bootstrap replicates of the one rule that gave a fit (count)."""
    n_loads: int = 0
    """Distinct peak loads of the cells fitted (count)."""
    n_realisations: int = 1
    """Surface realisations the cells come from (count)."""
    punch_diameter: float | None = None
    """The punch diameter d of a per-punch fit (m); None for a fit over several punches."""
    punch_diameters: tuple[float, ...] = ()
    """The punch diameters whose cells are fitted (m)."""
    flat_alpha_ci95: tuple[float, float] = (math.nan, math.nan)
    """95 % interval of α of the one rule by the flat bootstrap over indents (dimensionless):
    beside the hierarchical one, to show what the realisation level adds."""
    rules: dict[str, dict[str, Any]] = field(default_factory=dict)
    """Rule name (:data:`RULES`) → its own fit: ``made``, ``alpha``, ``beta``, ``alpha_ci95``,
    ``beta_ci95``, ``n_points``, ``n_loads``, or ``reason`` when not made."""

    def __getattr__(self, name: str) -> Any:
        if name == "fit":  # not yet set (copy, unpickling)
            raise AttributeError(name)
        return getattr(self.fit, name)

    @property
    def rule_shift(self) -> float:
        """abs(α_stiffness − α_stiffness_and_area) (dimensionless); NaN when the second rule's
        fit is not made."""
        r = self.rules.get("stiffness_and_area", {})
        return abs(self.fit.alpha - r["alpha"]) if r.get("made") else math.nan

    def to_dict(self) -> dict[str, Any]:
        """The fit's fields with the intervals and counts (SI, JSON-able).

        Returns
        -------
        dict
            :meth:`PowerLawFit.to_dict` and ``made`` (True), ``alpha_ci95``, ``beta_ci95``
            ([low, high], both rules), ``alpha_ci95_flat``, ``n_points``, ``n_loads``,
            ``n_indents``, ``n_realisations``, ``n_bootstrap``, ``punch_diameter_m`` (None
            when pooled), ``punch_diameters_m``, ``rules``, ``rule_shift_alpha``, ``ci_method``.
        """
        return {
            **self.fit.to_dict(),
            "made": True,
            "punch_diameter_m": self.punch_diameter,
            "punch_diameters_m": list(self.punch_diameters),
            "alpha_ci95": list(self.alpha_ci95),
            "beta_ci95": list(self.beta_ci95),
            "alpha_ci95_flat": list(self.flat_alpha_ci95),
            "n_points": self.n_points,
            "n_loads": self.n_loads,
            "n_indents": self.n_indents,
            "n_realisations": self.n_realisations,
            "n_bootstrap": self.n_bootstrap,
            "rules": self.rules,
            "rule_shift_alpha": self.rule_shift,
            "ci_method": CI_METHOD,
        }


def _least_squares(x: np.ndarray, y: np.ndarray, depth: np.ndarray, material: Any):
    curve = SimpleNamespace(
        load=x,
        n_contact_pixels=np.ones(x.size, np.int64),
        depth=depth,
        F_over_EA=x,
        Ec_over_E=y,
        material=material,
    )
    try:
        return fit_power_law(curve, min_pixels=1)  # type: ignore[arg-type]
    except ValueError:
        return None


def _loads_text(loads: np.ndarray) -> str:
    v = sorted({float(f) for f in loads})
    return ", ".join(f"{f * 1e3:.4g}" for f in v) + " mN" if v else "none"


def _one(
    c: dict[str, np.ndarray],
    sel: np.ndarray,
    material: Any,
    n_boot: int,
    seed: int,
) -> tuple[PowerLawFit | None, dict[str, Any], dict[str, Any]]:
    """The least-squares fit of the cells ``sel`` and its bootstrap intervals (hierarchical
    and flat); None where fewer than :data:`MIN_LOADS` loads."""
    loads = c["load"][sel]
    n_loads = int(np.unique(loads).size)
    if n_loads < MIN_LOADS:
        return None, {"n_loads": n_loads, "loads": loads}, {}
    fit = _least_squares(c["x"][sel], c["y"][sel], c["depth"][sel], material)
    if fit is None:
        return None, {"n_loads": n_loads, "loads": loads}, {}
    ind = c["indent"][sel]
    hb = bootstrap_power_law(
        c["x"][sel], c["y"][sel], ind, c["punch"][sel], c["realisation"][sel],
        n_boot=n_boot, seed=seed,
    )  # fmt: skip
    fb = bootstrap_power_law(
        c["x"][sel], c["y"][sel], ind, c["punch"][sel], n_boot=n_boot, seed=seed
    )
    return fit, {"n_loads": n_loads, "loads": loads, **hb}, fb


def _hull(a: tuple[float, float], b: tuple[float, float] | None) -> tuple[float, float]:
    if b is None or not all(math.isfinite(v) for v in b):
        return a
    if not all(math.isfinite(v) for v in a):
        return a
    return (min(a[0], b[0]), max(a[1], b[1]))


def _fit_with_rules(
    c: dict[str, np.ndarray],
    sel: dict[str, np.ndarray],
    material: Any,
    n_boot: int,
    seed: int,
    punch: float | None,
) -> tuple[IndentFit | None, str | None]:
    """One fit under every rule of ``sel`` (rule → cell mask), the first the one rule; the
    reported intervals span them all. (fit, None) or (None, reason)."""
    names = list(sel)
    main = names[0]
    fit, info, flat = _one(c, sel[main], material, n_boot, seed)
    if fit is None:
        what = "" if punch is None else f" of the {punch * 1e6:.4g} µm punch"
        return None, (
            f"{info['n_loads']} distinct peak load(s){what} with cells in_fit "
            f"({_loads_text(info['loads'])}); a power law in the load needs at least "
            f"{MIN_LOADS} loads of one punch"
        )
    rules: dict[str, dict[str, Any]] = {}
    a_ci, b_ci = tuple(info["alpha_ci95"]), tuple(info["beta_ci95"])
    for name in names:
        if name == main:
            f, inf = fit, info
        else:
            f, inf, _ = _one(c, sel[name], material, n_boot, seed)
        if f is None:
            rules[name] = {
                "made": False,
                "n_points": int(sel[name].sum()),
                "n_loads": inf["n_loads"],
                "reason": f"{inf['n_loads']} distinct peak load(s) with cells resolved by this "
                f"rule, at least {MIN_LOADS} needed: its systematic is not assessed",
            }
            continue
        rules[name] = {
            "made": True,
            "alpha": f.alpha,
            "beta": f.beta,
            "alpha_ci95": list(inf["alpha_ci95"]),
            "beta_ci95": list(inf["beta_ci95"]),
            "n_points": f.n_points,
            "n_loads": inf["n_loads"],
        }
        if name != main:
            a_ci = _hull(a_ci, tuple(inf["alpha_ci95"]))
            b_ci = _hull(b_ci, tuple(inf["beta_ci95"]))
            # the interval includes the other rule's estimate too
            if all(math.isfinite(v) for v in a_ci):
                a_ci = (min(a_ci[0], f.alpha, fit.alpha), max(a_ci[1], f.alpha, fit.alpha))
                b_ci = (min(b_ci[0], f.beta, fit.beta), max(b_ci[1], f.beta, fit.beta))
    m = sel[main]
    return (
        IndentFit(
            fit,
            a_ci,
            b_ci,
            int(m.sum()),
            int(info["n_indents"]),
            int(info["n_bootstrap"]),
            n_loads=int(info["n_loads"]),
            n_realisations=int(np.unique(c["realisation"][m]).size),
            punch_diameter=punch,
            punch_diameters=tuple(sorted({float(d) for d in c["diameter"][m]})),
            flat_alpha_ci95=tuple(flat.get("alpha_ci95", (math.nan, math.nan))),
            rules=rules,
        ),
        None,
    )


def agree_within_intervals(intervals: list[tuple[float, float]]) -> bool:
    """Whether intervals have a value in common: max of the lower ends ≤ min of the upper ends.

    Parameters
    ----------
    intervals : list of (float, float)
        (low, high) each; a NaN end makes the answer False.

    Returns
    -------
    bool
    """
    if not intervals or any(not (math.isfinite(a) and math.isfinite(b)) for a, b in intervals):
        return False
    return max(a for a, _ in intervals) <= min(b for _, b in intervals)


# --- the fits of one model --------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ModelFits:
    """The fits of one contact model: one per punch diameter, and the pooled one beside them."""

    per_punch: dict[float, IndentFit | None]
    """Punch diameter d (m; NaN for a flat larger than the map) → its fit over loads, None
    where not made (:attr:`reasons`)."""
    pooled: IndentFit | None
    """The fit over every punch fitted, made only where the per-punch α intervals agree."""
    reasons: dict[str, str]
    """Why a fit is not made: punch diameter (as ``"%.6g"`` in m) or ``"pooled"`` → reason."""
    n_loads: dict[float, int]
    """Punch diameter (m) → distinct peak loads with cells in_fit (the one rule)."""
    agreement: dict[str, Any]
    """How the pooled fit's condition was tested: ``test``, ``intervals`` (per punch, α's),
    ``agree`` (bool or None when fewer than two punches are fitted)."""

    def to_dict(self) -> dict[str, Any]:
        """What ``indent.json`` holds of the model's fits (JSON-able).

        Returns
        -------
        dict
            ``per_punch``: a list, per punch diameter, of ``punch_diameter_m``, ``n_loads``
            and :meth:`IndentFit.to_dict` or ``made`` False with ``reason``; ``pooled``: the
            same for the fit over the punches; ``agreement``.
        """
        rows = []
        for d, f in self.per_punch.items():
            key = _key(d)
            dd = None if not math.isfinite(d) else d
            if f is not None:
                rows.append({**f.to_dict(), "punch_diameter_m": dd, "n_loads": self.n_loads[d]})
            else:
                rows.append(
                    {
                        "made": False,
                        "punch_diameter_m": dd,
                        "n_loads": self.n_loads[d],
                        "reason": self.reasons[key],
                    }
                )
        pooled = (
            self.pooled.to_dict()
            if self.pooled is not None
            else {"made": False, "reason": self.reasons["pooled"]}
        )
        return {"per_punch": rows, "pooled": pooled, "agreement": self.agreement}


def _key(d: float) -> str:
    return "flat" if not math.isfinite(d) else f"{d:.6g}"


AGREEMENT_TEST = (
    "the per-punch 95 % intervals of alpha have a value in common "
    "(max of the lower ends <= min of the upper ends)"
)


def fit_model(
    cells: dict[str, Any],
    material: Any,
    *,
    punches: Any = None,
    n_boot: int = N_BOOTSTRAP,
    seed: int = 0,
) -> ModelFits:
    """The fits of one contact model: per punch over its loads, and pooled where they agree.

    Parameters
    ----------
    cells : dict of str to (m,) array_like
        The model's cells that may enter a fit (E_c/E and F/(E·A) > 0, finite): ``x``
        (F/(E·A), dimensionless), ``y`` (E_c/E, dimensionless), ``depth`` (the approach or
        truncation depth, m), ``load`` (peak load F, N), ``punch`` (diameter d, m; NaN for a
        flat larger than the map), ``realisation`` and ``placement`` (labels), and ``rules``:
        rule name → (m,) bool, the cells each rule resolves (:data:`RULES`; the first is the
        one rule of the fits; absent: every cell under one rule ``stiffness``).
    material : Material
        For ``beta_contact_modulus``.
    punches : sequence of float, optional
        Every punch diameter of the run (m; None or NaN: a flat larger than the map), so that
        a punch without a cell is listed too (``n_loads`` 0).
    n_boot : int
        Bootstrap replicates.
    seed : int
        Seed of the replicates.

    Returns
    -------
    ModelFits
    """
    c = {k: np.asarray(cells[k]) for k in ("x", "y", "depth", "load", "realisation", "placement")}
    c["x"], c["y"] = c["x"].astype(np.float64), c["y"].astype(np.float64)
    c["depth"] = c["depth"].astype(np.float64)
    c["diameter"] = np.asarray(cells["punch"], np.float64)
    c["punch"] = np.nan_to_num(c["diameter"], nan=-1.0)  # a flat larger than the map: -1
    m = c["x"].size
    rules = cells.get("rules") or {"stiffness": np.ones(m, bool)}
    rules = {k: np.asarray(v, bool) for k, v in rules.items()}
    main = next(iter(rules))
    pkey = c["punch"]
    c["indent"] = np.stack(
        [c["realisation"].astype(np.float64), pkey, c["placement"].astype(np.float64)], 1
    ) if m else np.zeros((0, 3))  # fmt: skip
    listed = {float(v) for v in pkey} | {
        -1.0 if d is None or not math.isfinite(d) else float(d) for d in (punches or ())
    }
    diameters = sorted(listed)
    per: dict[float, IndentFit | None] = {}
    reasons: dict[str, str] = {}
    n_loads: dict[float, int] = {}
    for dk in diameters:
        d = math.nan if dk == -1.0 else dk
        on = pkey == dk
        sel = {k: v & on for k, v in rules.items()}
        n_loads[d] = int(np.unique(c["load"][sel[main]]).size)
        f, why = _fit_with_rules(c, sel, material, n_boot, seed, None if math.isnan(d) else d)
        per[d] = f
        if f is None:
            reasons[_key(d)] = str(why)
    made = {d: f for d, f in per.items() if f is not None}
    intervals = {_key(d): list(f.alpha_ci95) for d, f in made.items()}
    agreement: dict[str, Any] = {"test": AGREEMENT_TEST, "intervals": intervals, "agree": None}
    pooled = None
    if len(made) < 2:
        if not made and len(diameters) > 1 and all(n <= 1 for n in n_loads.values()):
            reasons["pooled"] = (
                "every punch has cells in_fit at one peak load at most: a slope across punch "
                "sizes at one load measures how K scales with the punch, not with the load"
            )
        else:
            reasons["pooled"] = (
                f"{len(made)} punch(es) fitted over loads; a pooled fit is given only beside at "
                "least two per-punch fits that agree"
            )
    elif not all(all(math.isfinite(x) for x in v) for v in intervals.values()):
        reasons["pooled"] = (
            "a per-punch fit has no interval (a single indent): whether the punches share one "
            "exponent cannot be tested"
        )
    else:
        ok = agree_within_intervals([tuple(v) for v in intervals.values()])
        agreement["agree"] = ok
        if not ok:
            reasons["pooled"] = (
                "the per-punch alpha intervals have no value in common ("
                + "; ".join(f"{k} m: [{a:.4g}, {b:.4g}]" for k, (a, b) in intervals.items())
                + "): the punches do not share one exponent"
            )
        else:
            on = np.isin(pkey, [(-1.0 if math.isnan(d) else d) for d in made])
            sel = {k: v & on for k, v in rules.items()}
            pooled, why = _fit_with_rules(c, sel, material, n_boot, seed, None)
            if pooled is None:
                reasons["pooled"] = str(why)
    return ModelFits(per, pooled, reasons, n_loads, agreement)
