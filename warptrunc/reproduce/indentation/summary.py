# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The ``indentation`` stage's result from its stored pieces (:mod:`.pieces`): one
table of rows over every surface × design × model × realisation × punch × placement × load,
the timings of each piece, the windows and the settings."""

from __future__ import annotations

import math
from typing import Any

from ..._support.docs import fill_doc
from .analysis import _STAGE_DOCS
from .design import DESIGNS, IndentationStage, design_of, material, model_name, spec
from .pieces import SUBDIR

__all__ = ["summary_from_pieces"]

KEEP = (
    "realisation",
    "punch_diameter_m",
    "placement",
    "peak_load_N",
    "F_over_EA",
    "displacement_m",
    "contact_area_m2",
    "plastic_area_m2",
    "n_contact",
    "E_c_over_E",
    "E_c_partial_over_E",
    "converged",
    "overlap_fraction",
    "n_punch_pixels",
    "in_fit",
    "resolved",
    "saturated",
    "pixel_size_m",
    "truncation_E_c_over_E",
    "truncation_depth_m",
    "resolution_change",
    "area_change",
    "area_resolved",
    "bulk_yield",
    "sub_window",
    "mean_pressure_Pa",
    "stiffness_error_N_per_m",
    "contact_area_error_m2",
    "threshold_depth_m",
    "resolution_note",
)
"""Columns of the pieces kept in the stage's rows (with ``surface``, ``design``, ``model``,
``hardness_Pa``)."""


def _append(
    rows: dict[str, list],
    s: str,
    design: str,
    model: str,
    h: float | None,
    r: dict[str, list],
    over: dict[str, list] | None = None,
) -> None:
    m = len(r["peak_load_N"])
    rows["surface"] += [s] * m
    rows["design"] += [design] * m
    rows["model"] += [model] * m
    rows["hardness_Pa"] += [h] * m
    for c in KEEP:  # a piece stored before a column existed: NaN there
        rows[c].extend((over or {}).get(c, r.get(c, [math.nan] * m)))


FACE_KEEP = (
    "realisation",
    "punch_diameter_m",
    "placement",
    "peak_load_N",
    "F_over_EA",
    "displacement_m",
    "unloading_stiffness_N_per_m",
    "E_c_over_E",
    "converged",
    "in_fit",
    "n_contact",
    "pixel_size_m",
    "truncation_E_c_over_E",
    "truncation_depth_m",
    "threshold_depth_m",
)


def _timing(
    st: IndentationStage,
    s: str,
    design: str,
    name: str,
    rec: dict[str, Any],
    face: str | None = None,
) -> dict[str, Any]:
    """One piece's entry of the cost table: seconds, cells per final pixel (per punch too)."""
    r = rec["rows"]
    dx = st.pixel_size

    def factors(sel) -> dict[str, int]:
        out: dict[int, int] = {}
        for d, px in zip(r["punch_diameter_m"], r["pixel_size_m"], strict=True):
            if sel(d):
                k = round(dx / px) if px else 1
                out[k] = out.get(k, 0) + 1
        return {str(k): v for k, v in sorted(out.items())}

    per_punch = [
        {
            **pp,
            "cells_per_factor": factors(
                lambda d, pp=pp: math.isclose(d, pp["punch_diameter_m"], rel_tol=1e-9)
            ),
        }
        for pp in rec.get("per_punch", [])
    ]
    seeds, placements = design_of(st, design)
    return {
        "surface": s,
        "design": design,
        "model": name,
        "face": face,
        "seeds": list(seeds),
        "placements": placements,
        **rec["seconds"],
        "largest_window_px": max(
            (w["window_px"] for w in rec["windows"]), key=lambda v: v[0] * v[1]
        ),
        "n_not_converged": rec["n_not_converged"],
        "reused_elastic_cycles": rec.get("reused_elastic_cycles", 0),
        "device": rec["device"],
        "per_punch": per_punch,
        "cells_per_factor": factors(lambda d: True),
        "n_cells": len(r["peak_load_N"]),
    }


def _face(s: str, label: str, h: float, rec: dict[str, Any]) -> dict[str, Any]:
    """A face piece: its face, its rows (the columns the comparison needs) and its seconds."""
    r = rec["rows"]
    return {
        "surface": s,
        "label": label,
        "model": model_name(h),
        "hardness_Pa": None if math.isinf(h) else h,
        "face": rec["params"]["face"],
        "rows": {c: r.get(c, [None] * len(r["peak_load_N"])) for c in FACE_KEEP},
        "local_plane_tilt_deg": [w.get("local_plane_tilt_deg") for w in rec["windows"]],
        "seconds": rec["seconds"],
        "n_not_converged": rec["n_not_converged"],
        "device": rec["device"],
    }


@fill_doc(_STAGE_DOCS)
def summary_from_pieces(
    st: IndentationStage,
    pieces: list[tuple[tuple[str, str, float], dict[str, Any]]],
    resolution: dict[str, Any] | None,
) -> dict[str, Any]:
    """The stage result from its stored pieces.

    {indentation_stage}
    pieces : list of ((str, str, float), dict)
        ((surface, design, H), piece record) in the order computed; H in Pa, inf = elastic;
        design ``"sweep"``, ``"stats"`` or ``"face:<label>"``.
    resolution : dict or None
        The resolution-check record.

    Returns
    -------
    dict
        ``rows`` (columns over every surface × design × model × realisation × punch ×
        placement × load, with ``surface``, ``design``, ``model``, ``hardness_Pa``; Eq. 2
        truncation as ``model = "truncation"`` once per surface and design, taken from the
        design's elastic piece, else its first; every model row also carries the truncation
        of its own cell, ``truncation_E_c_over_E`` and ``truncation_depth_m``), ``timings``
        (one entry per piece), ``windows``, ``designs``, ``models`` (per design), ``faces``
        (the ``face`` pieces: surface, label, model, face, rows, seconds), the settings and
        the ``resolution`` record (JSON-able).
    """
    from ...indent import ALUMINIUM_HARDNESS

    rows: dict[str, list] = {c: [] for c in ("surface", "design", "model", "hardness_Pa", *KEEP)}
    timings, windows = [], []
    models: dict[str, list[str]] = {d: [] for d in DESIGNS}
    hardness: dict[str, float | None] = {}
    by_sd: dict[tuple[str, str], list[tuple[float, dict[str, Any]]]] = {}
    faces, face_t = [], []
    for (s, design, h), rec in pieces:
        if design.startswith("face:"):
            faces.append(_face(s, design[len("face:") :], h, rec))
            face_t.append(_timing(st, s, "face", model_name(h), rec, design[len("face:") :]))
            continue
        by_sd.setdefault((s, design), []).append((h, rec))
    for (s, design), group in by_sd.items():
        trunc = next((rec for h, rec in group if math.isinf(h)), group[0][1])
        for h, rec in group:
            name = model_name(h)
            hardness[name] = None if math.isinf(h) else h
            if name not in models[design]:
                models[design].append(name)
            r = rec["rows"]
            _append(rows, s, design, name, hardness[name], r)
            if rec is trunc:
                m = len(r["peak_load_N"])
                _append(
                    rows,
                    s,
                    design,
                    "truncation",
                    None,
                    r,
                    {
                        "E_c_over_E": r["truncation_E_c_over_E"],
                        "E_c_partial_over_E": [None] * m,
                        "contact_area_m2": r["truncation_contact_area_m2"],
                        "displacement_m": r["truncation_depth_m"],
                        "plastic_area_m2": [None] * m,
                        "n_contact": [None] * m,
                        "threshold_depth_m": [None] * m,
                        "converged": [not b for b in r.get("bulk_yield", [False] * m)],
                    },
                )
            timings.append(_timing(st, s, design, name, rec))
            windows += [
                {"surface": s, "design": design, "model": name, **w} for w in rec["windows"]
            ]
    m = material(st, math.inf)
    pr = st.protocol
    return {
        "store": SUBDIR,
        "surfaces": list(st.surfaces),
        "Rt_m": {s: spec(st, s).Rt for s in st.surfaces},
        "designs": {
            d: {"seeds": list(design_of(st, d)[0]), "placements": design_of(st, d)[1]}
            for d in (*DESIGNS, "face")
        },
        "models": models,
        "hardness_Pa": hardness,
        "punches_m": list(pr.punch_diameters),
        "loads_N": list(pr.peak_loads),
        "n": st.n,
        "L_m": st.L,
        "dx_m": st.pixel_size,
        "dtype": st.solver.dtype,
        "refine_max": pr.refine_max,
        "refine_punches_m": (
            list(pr.punch_diameters) if st.refine_punches is None else list(st.refine_punches)
        ),
        "resolution_tol": pr.resolution_tol,
        "min_contact_pixels": pr.min_contact_pixels,
        "depth_target_m": st.depth_target,
        "depth_band_m": list(st.depth_band),
        "stats_requested": list(st.stats),
        "material": {
            "E_Pa": m.E,
            "nu": m.nu,
            "E_i_Pa": m.E_i,
            "nu_i": m.nu_i,
            "E_star_Pa": m.contact_modulus,
            "H_default_Pa": ALUMINIUM_HARDNESS,
        },
        "rows": rows,
        "windows": windows,
        "timings": timings + face_t,
        "faces": faces,
        "resolution": resolution,
    }
