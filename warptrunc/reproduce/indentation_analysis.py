# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The numbers of the ``indentation`` stage's report: E_c/E per (surface, model, punch, load)
cell, the power-law fits per surface and model, which model truncation tracks (the ±20 % rule,
:data:`GOOD`) and the resolution check, all from the stage result
(:func:`~warptrunc.reproduce.indentation.summary_from_pieces`)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._support.docs import fill_doc
from .store import STAGE_DOCS

__all__ = ["GOOD", "analyse_indentation", "cells", "tracking"]

_STAGE_DOCS = {
    **STAGE_DOCS,
    "{stage}": (
        "Parameters\n----------\nstage : dict\n    The stage result "
        "(:func:`~warptrunc.reproduce.indentation.summary_from_pieces`)."
    ),
}
"""The indentation stage functions' parameter text, written once (:func:`fill_doc`; shared with
:mod:`.indentation`)."""

GOOD = 0.2
"""Truncation *tracks* a model at a (surface, punch, load) cell when
abs(E_c,trunc/E_c,model − 1) ≤ GOOD (geometric means over the placements)."""


def _gmean(v: list[float]) -> float | None:
    v = [x for x in v if x is not None and math.isfinite(x) and x > 0]
    return float(np.exp(np.mean(np.log(v)))) if v else None


@fill_doc(_STAGE_DOCS)
def cells(stage: dict[str, Any]) -> dict[tuple[str, str, float, float], dict[str, Any]]:
    """Per (surface, model, punch, peak load): E_c/E and F/(E·A), geometric means over the
    converged placements.

    {stage}

    Returns
    -------
    dict
        (surface, model, punch diameter (m), peak load (N)) → ``E_c_over_E``,
        ``E_c_partial_over_E`` (None where no placement converged), ``F_over_EA``,
        ``contact_area_m2``, ``plastic_area_m2`` (means), ``n`` (placements used).
    """
    r = stage["rows"]
    groups: dict[tuple, list[int]] = {}
    for i in range(len(r["surface"])):
        groups.setdefault((r["surface"][i], r["model"][i], r["punch_diameter_m"][i],
                           r["peak_load_N"][i]), []).append(i)  # fmt: skip
    out = {}
    for k, idx in groups.items():
        ok = [i for i in idx if r["converged"][i]]

        def mean(c, ok=ok):
            v = [r[c][i] for i in ok if r[c][i] is not None]
            return float(np.mean(v)) if v else None

        out[k] = {"E_c_over_E": _gmean([r["E_c_over_E"][i] for i in ok]),
                  "E_c_partial_over_E": _gmean([r["E_c_partial_over_E"][i] for i in ok]),
                  "F_over_EA": r["F_over_EA"][idx[0]], "contact_area_m2": mean("contact_area_m2"),
                  "plastic_area_m2": mean("plastic_area_m2"), "n": len(ok)}  # fmt: skip
    return out


def tracking(ratios: dict[str, dict[tuple[float, float], float | None]],
             good: float = GOOD) -> dict[str, Any]:  # fmt: skip
    """Which model truncation tracks, by the rule abs(ratio − 1) ≤ ``good``, per model.

    Parameters
    ----------
    ratios : dict
        model → {(punch diameter (m), peak load (N)): E_c,trunc/E_c,model or None}.
    good : float
        Half-width of the band (dimensionless).

    Returns
    -------
    dict
        ``per_model``: model → ``n_cells`` (cells with a ratio), ``n_good`` (within the band),
        ``runs`` (per punch, the loads within the band as contiguous runs of the loads that
        have a ratio:
        ``[punch_m, first_load_N, last_load_N, n_loads]``), ``median_ratio``, ``range``;
        ``closest``: model → cells where it is the model nearest to truncation (smallest
        abs(ln ratio)); ``tracked``: the model with most cells in the band (ties: more
        ``closest`` cells, then the order given), None when no cell is in the band.

    Notes
    -----
    The model tracked is the one with the largest *fraction* n_good/n_cells (cells where a
    solve did not converge have no ratio); ties go to more ``n_good``, then more ``closest``.
    """
    per: dict[str, Any] = {}
    closest: dict[str, int] = {m: 0 for m in ratios}
    keys = sorted({k for v in ratios.values() for k in v})
    for k in keys:
        best = min(((abs(math.log(v[k])), m) for m, v in ratios.items()
                    if v.get(k) is not None and v[k] > 0), default=None)  # fmt: skip
        if best is not None:
            closest[best[1]] += 1
    for m, v in ratios.items():
        have = {k: x for k, x in v.items() if x is not None and x > 0}
        goodk = {k for k, x in have.items() if abs(x - 1) <= good}
        runs = []
        for d in sorted({k[0] for k in have}):
            loads = sorted(k[1] for k in have if k[0] == d)
            run: list[float] = []
            for f in loads + [None]:
                if f is not None and (d, f) in goodk:
                    run.append(f)
                    continue
                if run:
                    runs.append([d, run[0], run[-1], len(run)])
                run = []
        xs = list(have.values())
        per[m] = {"n_cells": len(have), "n_good": len(goodk), "runs": runs,
                  "median_ratio": float(np.median(xs)) if xs else None,
                  "range": [min(xs), max(xs)] if xs else None}  # fmt: skip
    order = list(ratios)
    cand = [m for m in order if per[m]["n_good"] > 0]
    tracked = (max(cand, key=lambda m: (per[m]["n_good"] / per[m]["n_cells"], per[m]["n_good"],
                                        closest[m], -order.index(m)))
               if cand else None)  # fmt: skip
    return {"per_model": per, "closest": closest, "tracked": tracked, "band": good}


@fill_doc(_STAGE_DOCS)
def analyse_indentation(stage: dict[str, Any]) -> dict[str, Any]:
    """The numbers the section states: fits (surface × model), tracking per surface, the
    resolution check and the mean pressure of the largest load on the smallest punch.

    {stage}

    Returns
    -------
    dict
        ``fits``: surface → model → {alpha, beta, r2, n_points} or None (E_c/E = β·[F/(E·A)]^α
        over every converged placement, punch and load; ``<model>_partial`` for the
        partial-unloading secant); ``tracking``: surface → :func:`tracking` of truncation
        against each contact model; ``mean_pressure``; ``resolution``; ``not_converged``.
    """
    from ..stiffness import fit_power_law

    r = stage["rows"]
    n = len(r["surface"])
    use = r.get(stage.get("fit_cells", "converged"), r["converged"])  # in_fit when refined
    fits: dict[str, dict[str, Any]] = {}
    for s in stage["surfaces"]:
        fits[s] = {}
        for m in ("truncation", *stage["models"]):
            for kind, col in (("", "E_c_over_E"), ("_partial", "E_c_partial_over_E")):
                if m == "truncation" and kind:
                    continue
                sel = [i for i in range(n) if r["surface"][i] == s and r["model"][i] == m
                       and r["converged"][i] and use[i] and r[col][i] is not None]  # fmt: skip
                try:
                    f = fit_power_law([r["F_over_EA"][i] for i in sel], [r[col][i] for i in sel])
                    fits[s][m + kind] = {"alpha": f.alpha, "beta": f.beta, "r2": f.r2,
                                         "n_points": f.n_points}  # fmt: skip
                except ValueError:
                    fits[s][m + kind] = None
    c = cells(stage)
    track = {}
    for s in stage["surfaces"]:
        ratios: dict[str, dict] = {}
        for m in stage["models"]:
            ratios[m] = {}
            for (ss, mm, d, f), v in c.items():
                if ss != s or mm != "truncation":
                    continue
                w = c.get((s, m, d, f))
                t = v["E_c_over_E"]
                ratios[m][(d, f)] = (t / w["E_c_over_E"] if t and w and w["E_c_over_E"] else None)
        track[s] = tracking(ratios)
    loads, punches = stage["loads_N"], stage["punches_m"]
    pmean = max(loads) / (math.pi * min(punches) ** 2 / 4)
    finite = [v for v in stage["hardness_Pa"].values() if v is not None]
    conv = [i for i in range(n) if r["model"][i] != "truncation"]
    return {
        "good_band": GOOD,
        "fits": fits,
        "tracking": track,
        "mean_pressure": {"load_N": max(loads), "punch_m": min(punches), "p_mean_Pa": pmean,
                          "H_min_Pa": min(finite) if finite else None,
                          "below_H": bool(finite) and pmean < min(finite)},  # fmt: skip
        "smooth_Ec_over_E": stage["material"]["E_star_Pa"] / stage["material"]["E_Pa"],
        "not_converged": sum(not r["converged"][i] for i in conv),
        "n_solved_rows": len(conv),
        "max_overlap": max((r["overlap_fraction"][i] for i in range(n)
                            if r["punch_diameter_m"][i] == max(punches)), default=0.0),  # fmt: skip
        "resolution": _resolution_summary(stage.get("resolution")),
    }


def _resolution_summary(rec: dict[str, Any] | None) -> dict[str, Any] | None:
    if not rec:
        return None
    g = rec["grids"]
    out: dict[str, Any] = {"surface": rec["params"]["surface"], "punch_m": rec["params"]["punch_m"],
                           "n_coarse": g["coarse"]["n"], "n_fine": g["fine"]["n"],
                           "dx_coarse_m": g["coarse"]["dx_m"], "dx_fine_m": g["fine"]["dx_m"],
                           "models": {}}  # fmt: skip
    for m in g["coarse"]:
        if not isinstance(g["coarse"][m], dict):
            continue
        a, b = g["coarse"][m], g["fine"][m]
        rec_m = {"load_N": a["peak_load_N"][-1]}
        for q in ("unloading_stiffness_N_per_m", "partial_unloading_stiffness_N_per_m",
                  "contact_area_m2", "plastic_area_m2", "truncation_E_c_over_E"):  # fmt: skip
            x, y = a[q][-1], b[q][-1]
            rec_m[q] = [x, y, (y / x if x else None) if x is not None and y is not None else None]
        rec_m["converged"] = bool(a["converged"][-1] and b["converged"][-1])
        out["models"][m] = rec_m
    return out
