# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The numbers of the ``indentation`` stage's report, from the stage result
(:func:`~warptrunc.reproduce.indentation.summary_from_pieces`): per surface × design × model
the fits E_c/E = β·[F/(E·A)]^α with 95 % intervals over indents, the punch depth at the
largest load, the H range consistent with the paper's ≈ 5 µm, how deep truncation stays within
±20 % of each model (:data:`GOOD`), which model it tracks, the resolution of the cells per
load and the cost per piece and refinement level.

Every comparison uses the **resolved cells** only: ``in_fit`` (resolved in the pixel size or
by the contact-pixel rule, not saturated, converged; :mod:`warptrunc.indent.refine`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..._support.docs import fill_doc
from ..store import STAGE_DOCS
from .rules import agreement_depth, depth_at_load, depth_match, hardness_range

__all__ = ["GOOD", "analyse_indentation", "cells", "ratio_cells", "tracking"]

_STAGE_DOCS = {
    **STAGE_DOCS,
    "{stage}": (
        "Parameters\n----------\nstage : dict\n    The stage result "
        "(:func:`~warptrunc.reproduce.indentation.summary_from_pieces`)."
    ),
}
"""The indentation stage functions' parameter text, written once (:func:`fill_doc`; shared with
:mod:`.stage` and :mod:`.summary`)."""

GOOD = 0.2
"""Truncation *tracks* a model at a (surface, punch, load) cell when
abs(E_c,trunc/E_c,model − 1) ≤ GOOD (geometric mean over the indents)."""


def _gmean(v: list[float]) -> float | None:
    v = [x for x in v if x is not None and math.isfinite(x) and x > 0]
    return float(np.exp(np.mean(np.log(v)))) if v else None


def _groups(r: dict[str, list]) -> dict[tuple[str, str, str], list[int]]:
    out: dict[tuple[str, str, str], list[int]] = {}
    for i in range(len(r["surface"])):
        out.setdefault((r["surface"][i], r["design"][i], r["model"][i]), []).append(i)
    return out


def _ok(r: dict[str, list], i: int) -> bool:
    """A resolved cell: in_fit (resolved, not saturated, converged)."""
    return bool(r["in_fit"][i]) and bool(r["converged"][i])


@fill_doc(_STAGE_DOCS)
def cells(stage: dict[str, Any]) -> dict[tuple[str, str, str, float, float], dict[str, Any]]:
    """Per (surface, design, model, punch, peak load): E_c/E and F/(E·A), geometric means over
    the resolved indents.

    {stage}

    Returns
    -------
    dict
        (surface, design, model, punch diameter (m), peak load (N)) → ``E_c_over_E`` (None
        where no indent is resolved), ``F_over_EA``, ``n`` (indents used).
    """
    r = stage["rows"]
    out: dict[tuple, dict[str, Any]] = {}
    for (s, design, m), idx in _groups(r).items():
        by: dict[tuple[float, float], list[int]] = {}
        for i in idx:
            by.setdefault((r["punch_diameter_m"][i], r["peak_load_N"][i]), []).append(i)
        for (d, f), ii in by.items():
            ok = [i for i in ii if _ok(r, i)]
            out[(s, design, m, d, f)] = {
                "E_c_over_E": _gmean([r["E_c_over_E"][i] for i in ok]),
                "F_over_EA": r["F_over_EA"][ii[0]],
                "n": len(ok),
            }
    return out


@fill_doc(_STAGE_DOCS)
def ratio_cells(
    stage: dict[str, Any], surface: str, design: str, model: str
) -> dict[tuple[float, float], dict[str, Any]]:
    """E_c,trunc/E_c,model per (punch, load) of one model, from the same indents' cells.

    {stage}
    surface, design, model : str
        The group of rows.

    Returns
    -------
    dict
        (punch diameter (m), peak load (N)) → ``ratio`` (geometric mean over the resolved
        indents of each indent's truncation E_c/E over the model's), ``omega_m`` (median
        truncation depth ω of those indents, m) and ``n`` (indents); cells without a resolved
        indent are left out.
    """
    return _ratios(stage["rows"], _groups(stage["rows"]).get((surface, design, model), []))


def _ratios(r: dict[str, list], idx: list[int]) -> dict[tuple[float, float], dict[str, Any]]:
    """:func:`ratio_cells` of the rows ``idx`` of the columns ``r``."""
    by: dict[tuple[float, float], list[int]] = {}
    for i in idx:
        t, e = r["truncation_E_c_over_E"][i], r["E_c_over_E"][i]
        if _ok(r, i) and t and e and t > 0 and e > 0:
            by.setdefault((r["punch_diameter_m"][i], r["peak_load_N"][i]), []).append(i)
    return {
        k: {
            "ratio": _gmean([r["truncation_E_c_over_E"][i] / r["E_c_over_E"][i] for i in ii]),
            "omega_m": float(np.median([r["truncation_depth_m"][i] for i in ii])),
            "n": len(ii),
        }
        for k, ii in sorted(by.items())
    }


def tracking(
    ratios: dict[str, dict[tuple[float, float], float | None]], good: float = GOOD
) -> dict[str, Any]:
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
        have a ratio: ``[punch_m, first_load_N, last_load_N, n_loads]``), ``median_ratio``,
        ``range``; ``closest``: model → cells where it is the model nearest to truncation
        (smallest abs(ln ratio)); ``tracked``: the model with the largest fraction of its cells
        in the band (ties: more such cells, then more ``closest`` cells, then the order given),
        None when no cell is in the band.
    """
    per: dict[str, Any] = {}
    closest: dict[str, int] = {m: 0 for m in ratios}
    keys = sorted({k for v in ratios.values() for k in v})
    for k in keys:
        best = min(
            (
                (abs(math.log(v[k])), m)
                for m, v in ratios.items()
                if v.get(k) is not None and v[k] > 0
            ),
            default=None,
        )
        if best is not None:
            closest[best[1]] += 1
    for m, v in ratios.items():
        have = {k: x for k, x in v.items() if x is not None and x > 0}
        goodk = {k for k, x in have.items() if abs(x - 1) <= good}
        runs = []
        for d in sorted({k[0] for k in have}):
            loads = sorted(k[1] for k in have if k[0] == d)
            run: list[float] = []
            for f in [*loads, None]:
                if f is not None and (d, f) in goodk:
                    run.append(f)
                    continue
                if run:
                    runs.append([d, run[0], run[-1], len(run)])
                run = []
        xs = list(have.values())
        per[m] = {
            "n_cells": len(have),
            "n_good": len(goodk),
            "runs": runs,
            "median_ratio": float(np.median(xs)) if xs else None,
            "range": [min(xs), max(xs)] if xs else None,
        }
    order = list(ratios)
    cand = [m for m in order if per[m]["n_good"] > 0]
    tracked = (
        max(
            cand,
            key=lambda m: (
                per[m]["n_good"] / per[m]["n_cells"],
                per[m]["n_good"],
                closest[m],
                -order.index(m),
            ),
        )
        if cand
        else None
    )
    return {"per_model": per, "closest": closest, "tracked": tracked, "band": good}


def _ok_area(r: dict[str, list], i: int) -> bool:
    """A cell of the second rule: in_fit and its contact area converged too (``area_resolved``)."""
    a = r.get("area_resolved")
    return _ok(r, i) and a is not None and bool(a[i])


def _fit(r: dict[str, list], idx: list[int], col: str) -> dict[str, Any]:
    """The fits of one group's model column: per punch over its loads, the pooled one where the
    punches agree (:func:`warptrunc.indent.fits.fit_model`), under both cell rules."""
    from ...indent import default_material
    from ...indent.fits import fit_model

    sel = [
        i
        for i in idx
        if _ok(r, i) and r[col][i] is not None and r[col][i] > 0 and r["F_over_EA"][i] > 0
    ]
    punches = sorted({r["punch_diameter_m"][i] for i in idx})
    cells = {
        "x": [r["F_over_EA"][i] for i in sel],
        "y": [r[col][i] for i in sel],
        "depth": [r["displacement_m"][i] for i in sel],
        "load": [r["peak_load_N"][i] for i in sel],
        "punch": [r["punch_diameter_m"][i] for i in sel],
        "realisation": [r["realisation"][i] for i in sel],
        "placement": [r["placement"][i] for i in sel],
        "rules": {
            "stiffness": [True] * len(sel),
            "stiffness_and_area": [_ok_area(r, i) for i in sel],
        },
    }
    out = fit_model(cells, default_material(), punches=punches).to_dict()
    keep = (
        "made", "punch_diameter_m", "n_loads", "reason", "alpha", "beta", "r2", "alpha_ci95",
        "beta_ci95", "alpha_ci95_flat", "n_points", "n_indents", "n_realisations",
        "n_bootstrap", "rules", "rule_shift_alpha", "punch_diameters_m",
    )  # fmt: skip
    trim = lambda f: {k: f[k] for k in keep if k in f}  # noqa: E731
    return {
        "per_punch": [trim(f) for f in out["per_punch"]],
        "pooled": trim(out["pooled"]),
        "agreement": out["agreement"],
        "n_points": len(sel),
    }


def _hardness_question(stage: dict[str, Any], depths: dict) -> dict[str, Any]:
    """Per surface, from the sweep: the threshold depth at the largest load per H on the punch
    that goes deepest, with its spread over the placements (min–max), and the H range where its
    deepest placement lies in the band; and, since the paper's ≈ 5 µm is its maximum over all
    tests, ``all``: per H the largest threshold depth over every surface, punch and placement,
    the H range where it lies in the band and the one H matched (the statistics' H)."""
    out: dict[str, Any] = {}
    band, target = tuple(stage["depth_band_m"]), stage["depth_target_m"]
    top: dict[float, tuple[float, str]] = {}
    for s in stage["surfaces"]:
        per = {
            m: v
            for (ss, design, m), v in depths.items()
            if ss == s and design == "sweep" and m != "truncation"
        }
        hs = sorted((stage["hardness_Pa"][m], m) for m in per if stage["hardness_Pa"].get(m))
        deep = [per[m]["deepest"] for _h, m in hs]
        h = [x for x, _m in hs]
        dmax = [None if d is None else d["max"] for d in deep]
        for x, m in hs:
            v = max((p["max"] for p in per[m]["per_punch"].values()), default=None)
            if v is not None and (x not in top or v > top[x][0]):
                top[x] = (v, s)
        el = (per.get("elastic") or {}).get("deepest") or {}
        out[s] = {
            "hardness_Pa": h,
            "depth_m": [None if d is None else d["median"] for d in deep],
            "depth_min_m": [None if d is None else d["min"] for d in deep],
            "depth_max_m": dmax,
            "punch_m": [None if d is None else d["punch_m"] for d in deep],
            "highest_point_depth_m": [
                ((per[m]["highest_point"] or {}).get("deepest") or {}).get("median") for _h, m in hs
            ],
            "elastic_depth_m": el.get("median"),
            "elastic_depth_range_m": [el.get("min"), el.get("max")] if el else None,
            "range": hardness_range(h, dmax, band),
            "reading": next(iter(per.values()))["reading"] if per else None,
        }
    hh = sorted(top)
    dd = [top[x][0] for x in hh]
    out_all = {
        "hardness_Pa": hh,
        "max_depth_m": dd,
        "surface": [top[x][1] for x in hh],
        "range": hardness_range(hh, dd, band),
        "match": depth_match(hh, dd, target, band),
    }
    return {"surfaces": out, "all": out_all}


def _resolution_table(stage: dict[str, Any]) -> dict[tuple[str, str, str, float], dict[str, Any]]:
    """Per (surface, design, model, load): cells, resolved, in_fit, saturated, median contact
    pixels and the largest refinement (map pixel / cell pixel)."""
    r, dx = stage["rows"], stage["dx_m"]
    out: dict[tuple, dict[str, Any]] = {}
    for (s, design, m), idx in _groups(r).items():
        if m == "truncation":
            continue
        for f in stage["loads_N"]:
            ii = [i for i in idx if r["peak_load_N"][i] == f]
            px = [r["n_contact"][i] for i in ii if r["n_contact"][i] is not None]
            fac = [dx / r["pixel_size_m"][i] for i in ii if r["pixel_size_m"][i]]
            out[(s, design, m, f)] = {
                "n": len(ii),
                "resolved": sum(bool(r["resolved"][i]) for i in ii),
                "in_fit": sum(_ok(r, i) for i in ii),
                "saturated": sum(bool(r["saturated"][i]) for i in ii),
                "median_contact_px": float(np.median(px)) if px else None,
                "max_refinement": round(max(fac)) if fac else 1,
            }
    return out


def _cost(stage: dict[str, Any]) -> dict[str, Any]:
    """Seconds per design and per refinement level. warptrunc.indent records the refinement's
    seconds per punch call, not per level: they are apportioned to the levels by cells solved ×
    window pixels at each level (marked as apportioned)."""
    levels: dict[int, dict[str, float]] = {}
    largest = 1
    per_design: dict[str, float] = {}
    for t in stage["timings"]:
        per_design[t["design"]] = per_design.get(t["design"], 0.0) + t["piece_s"]
        largest = max([largest, *(int(k) for k in t.get("cells_per_factor", {}))])
        for pp in t.get("per_punch", []):
            counts = {int(k): v for k, v in pp.get("cells_per_factor", {}).items()}
            wins = {int(k): v for k, v in pp.get("refined_windows", {}).items() if int(k) > 1}
            if not wins:
                continue
            n_cells = {f: sum(v for k, v in counts.items() if k >= f) for f in wins}
            w = {f: n_cells[f] * wins[f][0] * wins[f][1] for f in wins}
            tot = sum(w.values()) or 1.0
            for f in wins:
                lv = levels.setdefault(f, {"cells": 0, "window_px": 0, "seconds": 0.0})
                lv["cells"] += n_cells[f]
                lv["window_px"] = max(lv["window_px"], wins[f][0] * wins[f][1])
                lv["seconds"] += pp["seconds"].get("refinement_s", 0.0) * w[f] / tot
    total = sum(per_design.values())
    return {
        "per_design": per_design,
        "levels": dict(sorted(levels.items())),
        "largest_refinement": largest,
        "pieces_s": total,
        "apportioned": True,
    }


def _faces(stage: dict[str, Any], agree: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Each punch face against the aligned smooth flat of the sweep (the same indents, H and
    truncation): how deep truncation stays within the band, K over the aligned K, and whether
    the face explains the paper's divergence of Ps beyond its range (Table 2)."""
    from ..paper import TABLE2

    out = []
    r = stage["rows"]
    for f in stage.get("faces", []):
        s, m, fr = f["surface"], f["model"], f["rows"]
        rt = stage["Rt_m"][s]
        rc = _ratios(fr, list(range(len(fr["peak_load_N"]))))
        a = agreement_depth(
            [v["omega_m"] / rt * 100 for v in rc.values()], [v["ratio"] for v in rc.values()], GOOD
        )
        base = _face_reference(stage, f)
        if base is not None:  # a tilt relative to the surface: against its 0° face
            bf = base["rows"]
            rb = _ratios(bf, list(range(len(bf["peak_load_N"]))))
            ref = agreement_depth(
                [v["omega_m"] / rt * 100 for v in rb.values()],
                [v["ratio"] for v in rb.values()],
                GOOD,
            )
        else:
            ref = next(
                (x for x in agree if (x["surface"], x["design"], x["model"]) == (s, "sweep", m)),
                None,
            )
        key = lambda rows, i: (  # noqa: E731
            rows["realisation"][i],
            rows["punch_diameter_m"][i],
            rows["placement"][i],
            rows["peak_load_N"][i],
        )
        if base is not None:
            bf = base["rows"]
            aligned = {
                key(bf, i): bf["E_c_over_E"][i] for i in range(len(bf["peak_load_N"])) if _ok(bf, i)
            }
        else:
            aligned = {
                key(r, i): r["E_c_over_E"][i]
                for i in _groups(r).get((s, "sweep", m), [])
                if _ok(r, i)
            }
        k = [
            fr["E_c_over_E"][i] / aligned[key(fr, i)]
            for i in range(len(fr["peak_load_N"]))
            if _ok(fr, i) and key(fr, i) in aligned and fr["E_c_over_E"][i] and aligned[key(fr, i)]
        ]
        lo, hi = TABLE2.get(s, ((math.nan, math.nan),))[0]
        local = [
            float(x)
            for x in (f.get("local_plane_tilt_deg") or [])
            if x is not None and math.isfinite(x)
        ]
        out.append(
            {
                "surface": s,
                "label": f["label"],
                "reference": "tilt 0° local" if base is not None else "the sweep's aligned flat",
                "local_plane_tilt_deg_rms": (
                    float(np.sqrt(np.mean(np.square(local)))) if local else None
                ),
                "model": m,
                **a,
                "aligned": ref,
                "K_over_aligned_median": float(np.median(k)) if k else None,
                "K_over_aligned_range": [min(k), max(k)] if k else None,
                "paper_range": [lo, hi],
                "verdict": _verdict(a, ref, lo, hi),
            }
        )
    return out


def _face_reference(stage: dict[str, Any], f: dict[str, Any]) -> dict[str, Any] | None:
    """The 0° face relative to the surface of the same surface and model (the reference of a
    local tilt and of the tip), when the stage ran one; None otherwise or for itself."""
    for g in stage.get("faces", []):
        if (
            g["surface"] == f["surface"]
            and g["model"] == f["model"]
            and g["label"] == "tilt 0° local"
            and g is not f
        ):
            return g
    return None


def _verdict(a: dict[str, Any], ref: dict[str, Any] | None, lo: float, hi: float) -> str:
    """Does a face explain a divergence between ``lo`` and ``hi`` % R_t′ (the paper's range)?

    Where truncation leaves the band lies between the ω of the last cell inside and that of
    the first outside; it matches the paper when that bracket meets [lo, hi]."""

    def meets(x: dict[str, Any]) -> bool:
        return x["leaves_at"] is not None and (x["depth"] or 0.0) <= hi and x["leaves_at"] >= lo

    if not a["n_cells"] or ref is None or not ref["n_cells"]:
        return "no-cells"
    if meets(ref) or (ref["leaves_at"] is not None and ref["leaves_at"] < lo):
        return "aligned-leaves"  # the aligned smooth flat already leaves the band by then
    if meets(a):
        return "explains"
    if a["leaves_at"] is not None and a["leaves_at"] < lo:
        return "too-early"
    if a["depth"] is not None and a["depth"] > hi and (ref["depth"] or 0.0) > hi:
        return "does-not-explain"
    return "undecided"  # no resolved cell deep enough on one side


@fill_doc(_STAGE_DOCS)
def analyse_indentation(stage: dict[str, Any]) -> dict[str, Any]:
    """The numbers the section states.

    {stage}

    Returns
    -------
    dict
        ``fits``: (surface, design) → model → fit (``made``, α, β, their ``alpha_ci95`` /
        ``beta_ci95``, ``n_points``, ``n_indents``; ``<model>_partial`` for the
        partial-unloading secant; ``stiffness_rule``: the same fit over the cells resolved by
        the rule on K alone, ``summary.resolved_stiffness``), as a list of
        records; ``depths``: records of the punch depth
        at the largest load per surface × design × model (:func:`depth_at_load`);
        ``hardness``: surface → the depth per H of the sweep, ``range``
        (:func:`hardness_range`) and ``match`` (:func:`depth_match`); ``agreement``: records of
        :func:`agreement_depth` per surface × design × model in % R_t′; ``tracking``: records of
        :func:`tracking` per surface × design; ``resolution_table``; ``cost``; ``faces``: per
        punch face, :func:`agreement_depth` against truncation, K over the aligned flat's K
        and the ``verdict`` on the paper's divergence of Ps;
        ``mean_pressure``; ``resolution`` (the check); ``not_converged``.
    """
    r = stage["rows"]
    groups = _groups(r)
    at = max(stage["loads_N"])
    fits, depths, agree, track = [], {}, [], []
    for (s, design, m), idx in groups.items():
        rec = {"surface": s, "design": design, "model": m, **_fit(r, idx, "E_c_over_E")}
        if m != "truncation":
            rec["partial"] = _fit(r, idx, "E_c_partial_over_E")
            args = (
                [r["punch_diameter_m"][i] for i in idx],
                [r["peak_load_N"][i] for i in idx],
            )
            ok = [bool(r["converged"][i]) for i in idx]
            thr = r.get("threshold_depth_m")
            col = [
                (r["displacement_m"][i] if thr is None else thr[i]) for i in idx
            ]  # a store written before the threshold depth: the highest point's
            depths[(s, design, m)] = {
                **depth_at_load(*args, col, ok, at),
                "reading": "from surface detection"
                if thr is not None
                else "from the highest point",
                "highest_point": depth_at_load(
                    *args, [r["displacement_m"][i] for i in idx], ok, at
                ),
            }
            rc = ratio_cells(stage, s, design, m)
            rt = stage["Rt_m"][s]
            a = agreement_depth(
                [v["omega_m"] / rt * 100 for v in rc.values()],
                [v["ratio"] for v in rc.values()],
                GOOD,
            )
            agree.append({"surface": s, "design": design, "model": m, **a})
        fits.append(rec)
    for s in stage["surfaces"]:
        for design, models in stage["models"].items():
            ratios = {
                m: {k: v["ratio"] for k, v in ratio_cells(stage, s, design, m).items()}
                for m in models
                if (s, design, m) in groups
            }
            if ratios:
                track.append({"surface": s, "design": design, **tracking(ratios)})
    hq = _hardness_question(stage, depths)
    punches = stage["punches_m"]
    pmean = at / (math.pi * min(punches) ** 2 / 4)
    solved = [i for i in range(len(r["surface"])) if r["model"][i] != "truncation"]
    return {
        "good_band": GOOD,
        "fits": fits,
        "depths": [
            {"surface": s, "design": d, "model": m, "load_N": at, **v}
            for (s, d, m), v in depths.items()
        ],
        "hardness": hq["surfaces"],
        "hardness_all": hq["all"],
        "agreement": agree,
        "tracking": track,
        "resolution_table": [
            {"surface": s, "design": d, "model": m, "load_N": f, **v}
            for (s, d, m, f), v in _resolution_table(stage).items()
        ],
        "cost": _cost(stage),
        "faces": _faces(stage, agree),
        "mean_pressure": {"load_N": at, "punch_m": min(punches), "p_mean_Pa": pmean},
        "smooth_Ec_over_E": stage["material"]["E_star_Pa"] / stage["material"]["E_Pa"],
        "not_converged": sum(not r["converged"][i] and not _bulk(r, i) for i in solved),
        "n_solved_rows": len(solved),
        "bulk_yield": _bulk_yield(r, solved),
        "in_fit_fraction": _in_fit_fraction(r, groups),
        "max_overlap": max(
            (
                r["overlap_fraction"][i]
                for i in range(len(r["surface"]))
                if r["punch_diameter_m"][i] == max(punches)
            ),
            default=0.0,
        ),
        "resolution": _resolution_summary(stage.get("resolution")),
    }


def _bulk(r: dict[str, list], i: int) -> bool:
    b = r.get("bulk_yield")
    return b is not None and b[i] is True


def _bulk_yield(r: dict[str, list], solved: list[int]) -> dict[str, Any]:
    """The cells flagged bulk_yield (mean punch pressure at or above (2.84/3)·H), by model."""
    from ...indent.depth import BULK_YIELD_SOURCE

    cells = sorted(
        {
            (r["surface"][i], r["design"][i], r["model"][i], r["punch_diameter_m"][i],
             r["peak_load_N"][i])
            for i in solved
            if _bulk(r, i)
        }
    )  # fmt: skip
    return {
        "criterion": BULK_YIELD_SOURCE,
        "n_rows": sum(_bulk(r, i) for i in solved),
        "cells": [list(c) for c in cells],
    }


def _in_fit_fraction(r: dict[str, list], groups: dict) -> list[dict[str, Any]]:
    """Per surface × design × model, the cells in_fit by the one rule, the cells whose contact
    area converged too, and all cells solved (bulk-yield rows left out)."""
    out = []
    for (s, design, m), idx in groups.items():
        if m == "truncation":
            continue
        ii = [i for i in idx if not _bulk(r, i)]
        out.append(
            {
                "surface": s,
                "design": design,
                "model": m,
                "n_cells": len(ii),
                "in_fit": sum(_ok(r, i) for i in ii),
                "in_fit_with_area": sum(_ok_area(r, i) for i in ii),
            }
        )
    return out


def _resolution_summary(rec: dict[str, Any] | None) -> dict[str, Any] | None:
    if not rec:
        return None
    g = rec["grids"]
    out: dict[str, Any] = {
        "surface": rec["params"]["surface"],
        "punch_m": rec["params"]["punch_m"],
        "n_coarse": g["coarse"]["n"],
        "n_fine": g["fine"]["n"],
        "dx_coarse_m": g["coarse"]["dx_m"],
        "dx_fine_m": g["fine"]["dx_m"],
        "models": {},
    }
    for m in g["coarse"]:
        if not isinstance(g["coarse"][m], dict):
            continue
        a, b = g["coarse"][m], g["fine"][m]
        rec_m = {"load_N": a["peak_load_N"][-1]}
        for q in (
            "unloading_stiffness_N_per_m",
            "partial_unloading_stiffness_N_per_m",
            "contact_area_m2",
            "plastic_area_m2",
            "truncation_E_c_over_E",
        ):
            x, y = a[q][-1], b[q][-1]
            rec_m[q] = [x, y, (y / x if x else None) if x is not None and y is not None else None]
        rec_m["converged"] = bool(a["converged"][-1] and b["converged"][-1])
        out["models"][m] = rec_m
    return out
