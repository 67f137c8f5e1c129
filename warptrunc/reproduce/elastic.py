# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stage ``elastic`` of ``warptrunc reproduce``: how far is truncation from elastic contact?

Eq. 2 (one flat punch of the whole truncated area), island-resolved truncation (one punch per
island) and warptrunc's elastic BEM solver (free half-space, Barber stiffness) on the same WM
maps (:mod:`warptrunc.compare`): D ∈ ``Profile.elastic_D``, approaches δ/R_t ∈
``Profile.elastic_fractions``, map sizes L/W_r ∈ ``Profile.elastic_size_ratios`` at a fixed
pixel size, the pixel size halved once at L/W_r = ``Profile.elastic_refine_ratio``,
``Profile.elastic_seeds`` seeds. The cases are stored one Parquet file each under
``OUT/elastic/`` (resumed case by case by a rerun, also after an interrupted stage); the stage
file holds the summary tables, recomputed from those rows.

This stage replaces the former ``bem`` stage (ContactMechanics on the CPU at one map size):
its cases are the L/W_r = 10 column here, solved by warptrunc's own solver on the run's device.
A ``stages/bem.json`` of an earlier run is left in place and no longer read.

Also runnable alone (``python -m warptrunc.reproduce.elastic_report --profile paper --out DIR``):
then it writes ``DIR/elastic.md`` (the report section) and its figures. The section's text and
figures are made by :mod:`.elastic_report`.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from .._support.docs import fill_doc
from .profiles import Profile
from .store import STAGE_DOCS

__all__ = [
    "GOOD",
    "analyse_elastic",
    "profile_design",
    "stage_elastic",
    "stage_params",
    "summary_from_rows",
]

GOOD = 0.2
"""abs(model/BEM − 1) ≤ GOOD counts as "within ±20 %" in the section's sentences."""
SUBDIR = "elastic"
"""Case store of the stage, inside the reproduction folder."""
POHRT_POPOV = ((2.0, 0.51), (3.0, 0.77))
"""α at D = 2 and 3 from Pohrt & Popov (2012), BEM; the section interpolates linearly."""
PAPER_ALPHA = (0.209, 0.090)
"""The paper's Table 3: α = 0.209·D_in + 0.090."""


def default_material():
    from ..stiffness import Material

    return Material()


def profile_design(p: Profile):
    """The comparison study of a profile's ``elastic`` stage: its WM surfaces, one per (D, grid,
    seed), and its approaches.

    Parameters
    ----------
    p : Profile
        Its ``elastic_*`` fields and ``Wr`` (m) set the study.

    Returns
    -------
    StudyDesign
        The :class:`~warptrunc.compare.StudyDesign` (seeds 0 … ``elastic_seeds`` − 1).
    """
    from ..compare.design import StudyDesign

    return StudyDesign(
        D=p.elastic_D,
        size_ratios=p.elastic_size_ratios,
        pixels_per_Wr=p.elastic_pixels_per_Wr,
        refine_ratio=p.elastic_refine_ratio,
        seeds=tuple(range(p.elastic_seeds)),
        Wr=p.Wr,
        fractions=p.elastic_fractions,
    )


@fill_doc(STAGE_DOCS)
def stage_params(p: Profile) -> dict[str, Any]:
    """The parameters that identify a stored ``elastic`` stage.

    {profile}

    {stage_params_returns}
    """
    m = default_material()
    return {
        "elastic_D": list(p.elastic_D),
        "elastic_size_ratios": list(p.elastic_size_ratios),
        "elastic_pixels_per_Wr": p.elastic_pixels_per_Wr,
        "elastic_refine_ratio": p.elastic_refine_ratio,
        "elastic_seeds": p.elastic_seeds,
        "elastic_fractions": list(p.elastic_fractions),
        "elastic_dtype": p.elastic_dtype,
        "Wr": p.Wr,
        "material": {"E_Pa": m.E, "nu": m.nu, "E_star_Pa": m.contact_modulus},
        "solver": "warptrunc",
    }


@fill_doc(STAGE_DOCS)
def stage_elastic(p: Profile, out: str | Path, device, client=None) -> dict[str, Any]:
    """Run (or resume) the comparison study under ``out/elastic`` and summarise it.

    {elastic_profile}
    out : str or Path
        Reproduction folder; the case store is ``out/elastic``.
    device : str, optional
        Warp device of every route (with ``client``: the tasks' device, None for each worker's
        pinned GPU).
    client : distributed.Client, optional
        Run the maps as tasks of this Dask cluster (:func:`warptrunc.compare.compare_study`);
        default in this process.

    Returns
    -------
    dict
        :func:`summary_from_rows` of the study's rows.
    """
    from ..compare.study import compare_study
    from ..contact.settings import SolverSettings

    store = Path(out) / SUBDIR
    rows = compare_study(
        store,
        profile_design(p),
        material=default_material(),
        settings=SolverSettings(dtype=p.elastic_dtype),
        overwrite=True,
        progress=True,
        device=device,
        client=client,
    )
    return summary_from_rows(rows, store=SUBDIR)


def summary_from_rows(rows, store: str = SUBDIR) -> dict[str, Any]:
    """The stage result from the study's rows.

    Parameters
    ----------
    rows : pandas.DataFrame
        Rows of :func:`warptrunc.compare.load_comparison`.
    store : str
        Folder of the case store, as the report names it.

    Returns
    -------
    dict
        Counts, grids, the two summary tables of :func:`warptrunc.compare.summarize` as
        records, the grid-convergence pairs and mean times per map size (JSON-able).
    """
    from ..compare.study import summarize

    s = summarize(rows)
    conv = rows["converged"].astype(bool)
    per_n = (
        rows.groupby("n")[["solve_time_s", "case_seconds"]].mean().reset_index().to_dict("records")
    )
    return {
        "store": store,
        "n_cases": int(rows["case_id"].nunique()),
        "n_rows": len(rows),
        "not_converged_rows": int((~conv).sum()),
        "device": sorted(set(rows["device"].astype(str))),
        "fractions": sorted(float(f) for f in rows["depth_fraction_of_Rt"].unique()),
        "grids": sorted(
            {(float(r), int(n)) for r, n in zip(rows["size_ratio"], rows["n"], strict=True)}
        ),
        "Wr_m": float(rows["Wr_m"].iloc[0]),
        "Rt_m": sorted({float(v) for v in rows["Rt_m"]}),
        "ratios": s["ratios"].to_dict("records"),
        "alpha": s["alpha"].to_dict("records"),
        "grid": _grid_pairs(rows),
        "times": per_n,
    }


def _grid_pairs(rows) -> list[dict[str, Any]]:
    """Per (D, δ/R_t) at the refined L/W_r: fine/coarse of each route's k and F and of the
    areas, same seed paired (the same surface sampled twice as finely)."""
    out = []
    for r in sorted(rows["size_ratio"].unique()):
        ns = sorted(rows.loc[rows["size_ratio"] == r, "n"].unique())
        if len(ns) < 2:
            continue
        lo, hi = ns[0], ns[-1]
        a = rows[(rows["size_ratio"] == r) & (rows["n"] == lo)]
        b = rows[(rows["size_ratio"] == r) & (rows["n"] == hi)]
        m = a.merge(b, on=["D_in", "seed", "depth_fraction_of_Rt"], suffixes=("_c", "_f"))
        for (Dv, f), g in m.groupby(["D_in", "depth_fraction_of_Rt"], sort=True):
            rec: dict[str, Any] = {
                "D_in": float(Dv),
                "size_ratio": float(r),
                "n_coarse": int(lo),
                "n_fine": int(hi),
                "depth_fraction_of_Rt": float(f),
            }
            for q in (
                "eq2_stiffness_N_per_m",
                "islands_stiffness_N_per_m",
                "bem_stiffness_N_per_m",
                "eq2_load_N",
                "islands_load_N",
                "bem_load_N",
                "trunc_area_m2",
                "bem_area_m2",
                "eq2_k_ratio",
                "islands_k_ratio",
            ):
                v = (g[f"{q}_f"] / g[f"{q}_c"]).to_numpy(dtype=float)
                v = v[np.isfinite(v)]
                rec[f"{q}_fine_over_coarse"] = float(v.mean()) if v.size else None
            out.append(rec)
    return out


# --- analysis -------------------------------------------------------------------------------------


def base_records(records: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Records at the base pixel size (largest dx = L/n over the stored sizes)."""
    if not records:
        return []
    dx = max(r["size_ratio"] / r["n"] for r in records)
    return [r for r in records if math.isclose(r["size_ratio"] / r["n"], dx, rel_tol=1e-9)]


def is_finite(v: Any) -> bool:
    return v is not None and isinstance(v, (int, float)) and math.isfinite(v)


def analyse_elastic(stage: dict[str, Any]) -> dict[str, Any]:
    """The numbers the section states.

    Parameters
    ----------
    stage : dict
        The stage result (:func:`summary_from_rows`).

    Returns
    -------
    dict
        Per model and quantity the cells within ±GOOD of BEM, the range elsewhere and in the
        paper's range, the trend with L/W_r; the grid change; α with the two references.
    """
    ratios = base_records(stage["ratios"])
    res: dict[str, Any] = {"good_band": GOOD, "models": {}}
    for m in ("eq2", "islands"):
        for q in ("k", "F"):
            key = f"{m}_{q}_ratio"
            cells = [r for r in ratios if is_finite(r[f"{key}_mean"])]
            good = [r for r in cells if abs(r[f"{key}_mean"] - 1) <= GOOD]
            all_good = [
                r for r in good if r[f"{key}_min"] >= 1 - GOOD and r[f"{key}_max"] <= 1 + GOOD
            ]
            bad = [r[f"{key}_mean"] for r in cells if abs(r[f"{key}_mean"] - 1) > GOOD]
            low = [r for r in cells if r["depth_fraction_of_Rt"] <= 0.1 + 1e-9]
            res["models"][key] = {
                "cells": len(cells),
                "good": [[r["D_in"], r["size_ratio"], r["depth_fraction_of_Rt"]] for r in good],
                "good_all_seeds": len(all_good),
                "below_one": sum(r[f"{key}_mean"] < 1 for r in cells),
                "range": [
                    min(r[f"{key}_mean"] for r in cells),
                    max(r[f"{key}_mean"] for r in cells),
                ]
                if cells
                else None,
                "outside_range": [min(bad), max(bad)] if bad else None,
                "low_range": [
                    min(r[f"{key}_mean"] for r in low),
                    max(r[f"{key}_mean"] for r in low),
                ]
                if low
                else None,
                "size_trend": _size_trend(cells, key),
            }
    res["alpha"] = _alpha_vs_refs(stage["alpha"])
    res["grid"] = _grid_summary(stage["grid"])
    return res


def _size_trend(cells: list[dict[str, Any]], key: str) -> dict[str, Any] | None:
    """Ratio at the largest L/W_r over that at the smallest, per (D, δ/R_t)."""
    sizes = sorted({r["size_ratio"] for r in cells})
    if len(sizes) < 2:
        return None
    by = {(r["D_in"], r["depth_fraction_of_Rt"], r["size_ratio"]): r[f"{key}_mean"] for r in cells}
    f = []
    for Dv, fr in sorted({(r["D_in"], r["depth_fraction_of_Rt"]) for r in cells}):
        a, b = by.get((Dv, fr, sizes[0])), by.get((Dv, fr, sizes[-1]))
        if is_finite(a) and is_finite(b) and a > 0:
            f.append(b / a)
    if not f:
        return None
    return {
        "smallest": sizes[0],
        "largest": sizes[-1],
        "factor_min": min(f),
        "factor_median": float(np.median(f)),
        "factor_max": max(f),
        "decreasing": sum(v < 1 for v in f),
        "n": len(f),
    }


def _alpha_vs_refs(alpha: list[dict[str, Any]]) -> list[dict[str, Any]]:
    out = []
    (d0, a0), (d1, a1) = POHRT_POPOV
    for r in base_records(alpha):
        D = r["D_in"]
        out.append(
            {
                **r,
                "pohrt_popov": a0 + (a1 - a0) * (D - d0) / (d1 - d0),
                "paper_table3": PAPER_ALPHA[0] * D + PAPER_ALPHA[1],
            }
        )
    return out


def _grid_summary(grid: list[dict[str, Any]]) -> dict[str, Any] | None:
    if not grid:
        return None
    out: dict[str, Any] = {
        "size_ratio": grid[0]["size_ratio"],
        "n_coarse": grid[0]["n_coarse"],
        "n_fine": grid[0]["n_fine"],
    }
    for q in (
        "eq2_stiffness_N_per_m",
        "islands_stiffness_N_per_m",
        "bem_stiffness_N_per_m",
        "bem_load_N",
        "trunc_area_m2",
        "bem_area_m2",
        "eq2_k_ratio",
        "islands_k_ratio",
    ):
        v = [g[f"{q}_fine_over_coarse"] for g in grid if is_finite(g[f"{q}_fine_over_coarse"])]
        out[q] = [min(v), max(v)] if v else None
    return out


# --- standalone ---------------------------------------------------------------------------------
