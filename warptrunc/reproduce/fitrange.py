# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The fit-range map of Table 3: α(D) and β(δ) re-fitted from the stored curves of groups 1–2
for a grid of fit ranges (no surface is recomputed).

A fit range is either absolute, ``min_pixels`` = m (increments with ≥ m contact pixels), or
relative, ``fraction`` = f (increments with ≥ max(1, ⌈f·N_final⌉) contact pixels, N_final the
surface's final contact pixels). Each stored curve is fitted with
:func:`warptrunc.stiffness.fit_power_law`; the per-surface α then give the α(D) lines and the
per-surface β the β(δ) power law, exactly as the report's two stored ranges do.
"""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..stiffness import fit_power_law
from .analysis import D_KEYS, _line, _power
from .paper import TABLE3

__all__ = ["FRACTIONS", "MIN_PIXELS", "TOLERANCE", "fit_range_map", "refit_store"]

MIN_PIXELS = (1, 2, 3, 5, 7, 10, 20, 50, 100)
"""Absolute fit ranges of the map (contact pixels)."""
FRACTIONS = (0.001, 0.003, 0.01, 0.03, 0.1)
"""Relative fit ranges of the map (fraction of the final contact pixels, dimensionless)."""
TOLERANCE = 0.10
"""Relative distance from Table 3 (slope and α(2.5) each) that counts as reproducing it."""


def _ranges(min_pixels, fractions) -> list[tuple[str, str, float]]:
    return [(f"min_pixels={m}", "min_pixels", m) for m in min_pixels] + [
        (f"fraction={f:g}", "fraction", f) for f in fractions
    ]


def _threshold(kind: str, value: float, final: int) -> int:
    if kind == "min_pixels":
        return int(value)
    return max(1, math.ceil(round(value * final, 9)))


def refit_store(
    path: str | Path,
    *,
    min_pixels: tuple[int, ...] = MIN_PIXELS,
    fractions: tuple[float, ...] = FRACTIONS,
) -> list[dict[str, Any]]:
    """α and β of every stored curve of a sweep store for every fit range.

    Parameters
    ----------
    path : str or Path
        Sweep store folder (read with :func:`warptrunc.sweep.load` and
        :func:`warptrunc.sweep.load_curves`).
    min_pixels : tuple of int
        Absolute fit ranges (contact pixels).
    fractions : tuple of float
        Relative fit ranges (fraction of the final contact pixels, dimensionless).

    Returns
    -------
    list of dict
        One row per surface × range: ``case_id``, ``D_in``, ``delta``, ``seed``, ``D`` (the
        stored D per method, when there are any), ``range``, ``kind``, ``value``,
        ``threshold`` (contact pixels), ``alpha``, ``beta``, ``r2``, ``n_points`` (None where
        fewer than 3 increments remain).
    """
    from ..sweep.read import load, load_curves

    cases = load(path)
    curves = load_curves(path)
    by_case = dict(tuple(curves.groupby("case_id", sort=False)))
    out = []
    for cid, part in cases.groupby("case_id", sort=False):
        first = part.iloc[0]
        if cid not in by_case:  # a failed case: no curve
            continue
        c = by_case[cid]
        sc = SimpleNamespace(
            depth=c["depth_m"].to_numpy(),
            n_contact_pixels=c["n_contact_pixels"].to_numpy(),
            load=c["load_N"].to_numpy(),
            Ec_over_E=c["Ec_over_E"].to_numpy(),
            F_over_EA=c["F_over_EA"].to_numpy(),
        )
        final = int(sc.n_contact_pixels[-1])
        D = {
            m: float(first[f"D_{m}"])
            for m in D_KEYS[1:]
            if f"D_{m}" in part and np.isfinite(first[f"D_{m}"])
        }
        for name, kind, value in _ranges(min_pixels, fractions):
            mp = _threshold(kind, value, final)
            row = {
                "case_id": cid,
                "D_in": float(first["D_in"]),
                "delta": float(first["delta"]),
                "seed": int(first["seed"]),
                "D": D,
                "range": name,
                "kind": kind,
                "value": value,
                "threshold": mp,
            }
            try:
                f = fit_power_law(sc, min_pixels=max(1, mp))
                row.update(alpha=f.alpha, beta=f.beta, r2=f.r2, n_points=f.n_points)
            except ValueError:
                row.update(alpha=None, beta=None, r2=None, n_points=None)
            out.append(row)
    return out


def _rel(ours, paper):
    return None if ours is None else (ours - paper) / abs(paper)


def fit_range_map(
    group1: str | Path,
    group2: str | Path,
    *,
    min_pixels: tuple[int, ...] = MIN_PIXELS,
    fractions: tuple[float, ...] = FRACTIONS,
    tolerance: float = TOLERANCE,
) -> dict[str, Any]:
    """α(D) lines per D method and β(δ) per fit range, re-fitted from the two group stores.

    Parameters
    ----------
    group1, group2 : str or Path
        Sweep stores of Table 3 group 1 (δ sweep) and group 2 (D_in sweep).
    min_pixels, fractions : tuple
        Fit ranges, as in :func:`refit_store`.
    tolerance : float
        Relative distance from Table 3 (dimensionless) within which a range reproduces it.

    Returns
    -------
    dict of str to Any
        ``ranges`` (name, kind, value), ``alpha`` {range: {D key: line fit with ``alpha_2_5``
        = α at D = 2.5 and the relative deviations ``slope_dev`` and ``alpha_2_5_dev`` from
        Table 3, or None}}, ``beta`` {range: power fit of β against δ with ``minus_alpha``
        (−mean α of group 1) and ``p_dev``}, ``reproduces`` {D key: ranges whose slope and
        α(2.5) are both within ``tolerance`` of Table 3}, ``paper`` (Table 3 slopes,
        intercepts, α(2.5)) and ``tolerance``.
    """
    ranges = _ranges(min_pixels, fractions)
    r2 = refit_store(group2, min_pixels=min_pixels, fractions=fractions)
    r1 = refit_store(group1, min_pixels=min_pixels, fractions=fractions)
    alpha: dict[str, Any] = {}
    beta: dict[str, Any] = {}
    paper = {
        k: {"slope": s, "intercept": i, "r": r, "alpha_2_5": s * 2.5 + i}
        for k, (s, i, r) in TABLE3["alpha"].items()
    }
    for name, _kind, _v in ranges:
        alpha[name] = {}
        rows = [r for r in r2 if r["range"] == name and r["alpha"] is not None]
        for k in D_KEYS:
            xs = [r["D_in"] if k == "in" else r["D"].get(k) for r in rows]
            pts = [(x, r["alpha"]) for x, r in zip(xs, rows, strict=True) if x is not None]
            f = _line(*zip(*pts, strict=True)) if pts else None
            if f is not None:
                f["alpha_2_5"] = f["slope"] * 2.5 + f["intercept"]
                f["slope_dev"] = _rel(f["slope"], paper[k]["slope"])
                f["alpha_2_5_dev"] = _rel(f["alpha_2_5"], paper[k]["alpha_2_5"])
            alpha[name][k] = f
        rows = [r for r in r1 if r["range"] == name and r["beta"] is not None]
        pf = _power([r["delta"] for r in rows], [r["beta"] for r in rows]) if rows else None
        if pf is not None:
            pf["minus_alpha"] = -float(np.mean([r["alpha"] for r in rows]))
            pf["p_dev"] = _rel(pf["p"], TABLE3["beta"][1])
        beta[name] = pf
    reproduces = {
        k: [
            n
            for n, _, _ in ranges
            if (f := alpha[n][k]) is not None
            and abs(f["slope_dev"]) <= tolerance
            and abs(f["alpha_2_5_dev"]) <= tolerance
        ]
        for k in D_KEYS
    }
    return {
        "ranges": [{"name": n, "kind": k, "value": v} for n, k, v in ranges],
        "alpha": alpha,
        "beta": beta,
        "reproduces": reproduces,
        "paper": paper,
        "paper_beta": dict(zip(("b", "p", "r"), TABLE3["beta"], strict=True)),
        "tolerance": tolerance,
    }
