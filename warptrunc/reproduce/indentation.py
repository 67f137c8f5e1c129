# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stage ``indentation`` of ``warptrunc reproduce``: the paper's experiment (§ 4.1, Fig. 6) in silico.

The four Table 1 surfaces (:data:`warptrunc.presets.TABLE1`) at ``Profile.indentation_n``
pixels over 1 mm, the three flat punches, ``Profile.indentation_placements`` random placements
per punch and the paper's load / partial-unload cycles (:func:`warptrunc.indent`), for each
hardness H ∈ ``Profile.indentation_hardness_factors`` × the alloy's
(:data:`~warptrunc.indent.ALUMINIUM_HARDNESS`; ``inf`` = elastic). Eq. 2 truncation runs on the
same punch disks and placements. Every E_c/E is normalised by the Young's modulus E (Fig. 6).

The work is stored in pieces, one JSON file per surface × H under ``OUT/indentation/``
(written atomically), so an interrupted stage (a GPU call that hit its time limit, or
``time_budget``) continues where it stopped when ``warptrunc reproduce`` is run again; the stage
file ``stages/indentation.json`` holds the summary, recomputed from the pieces. One more piece,
``resolution``, solves the smallest punch at the map centre on the same surface sampled at the
profile's pixel size and at half of it (same phases and cut-off W_c), since H caps the pressure
of each pixel.

The section of ``report.md`` and its figure are in :mod:`.indentation_report`; the numbers it
states (fits, the tracking rule, the resolution check) come from
:func:`~warptrunc.reproduce.indentation_analysis.analyse_indentation`.
"""

from __future__ import annotations

import json
import math
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from .._support.docs import fill_doc
from .._support.results import jsonable, write_atomic
from .indentation_analysis import (  # noqa: F401 - the analysis's names stay importable here
    _STAGE_DOCS,
    GOOD,
    analyse_indentation,
    cells,
    tracking,
)
from .profiles import Profile
from .store import StageConflict

__all__ = [
    "StageIncomplete",
    "piece_names",
    "stage_indentation",
    "stage_params",
    "summary_from_pieces",
]

SUBDIR = "indentation"
"""Piece store of the stage, inside the reproduction folder."""
RESOLUTION_SURFACE = "GB300s"
"""Surface of the resolution check (the paper's Fig. 7 surface); the first one if absent."""
COLUMNS = (
    "punch_diameter_m", "placement", "peak_load_N", "F_over_EA", "displacement_m",
    "contact_area_m2", "plastic_area_m2", "n_contact", "unloading_stiffness_N_per_m",
    "partial_unloading_stiffness_N_per_m", "E_c_over_E", "E_c_partial_over_E", "converged",
    "overlap_fraction", "n_punch_pixels", "truncation_depth_m", "truncation_contact_area_m2",
    "truncation_stiffness_N_per_m", "truncation_E_c_over_E", "centre_x_m", "centre_y_m",
    "max_pressure_Pa", "pixel_size_m", "resolution_change", "resolved", "saturated", "in_fit",
)  # fmt: skip
"""Columns of :meth:`warptrunc.indent.IndentationResult.to_dict` kept in each piece."""


class StageIncomplete(RuntimeError):
    """The stage stopped before its last piece (time budget); a rerun continues it."""


def _material(factor: float):
    from ..indent import ALUMINIUM_HARDNESS, default_material

    return default_material(hardness=math.inf if math.isinf(factor) else factor * ALUMINIUM_HARDNESS)


def model_name(factor: float) -> str:
    """Model key of a hardness factor: ``elastic`` (inf) or ``elastic_plastic_<f>H``.

    Parameters
    ----------
    factor : float
        H / the alloy's hardness (dimensionless); inf = elastic.

    Returns
    -------
    str
        ``"elastic"``, ``"elastic_plastic_1H"``, ``"elastic_plastic_2H"``, …
    """
    return "elastic" if math.isinf(factor) else f"elastic_plastic_{factor:g}H"


def _spec(p: Profile, name: str):
    from ..presets import TABLE1

    return TABLE1[name].replace(n=p.indentation_n, L=p.indentation_L)


@fill_doc(_STAGE_DOCS)
def stage_params(p: Profile) -> dict[str, Any]:
    """The parameters that identify a stored ``indentation`` stage.

    {indentation_profile}

    {stage_params_returns}
    """
    m = _material(1.0)
    return jsonable({
        "surfaces": {s: _spec(p, s).to_dict() for s in p.indentation_surfaces},
        "punches_m": list(p.indentation_punches), "loads_N": list(p.indentation_loads),
        "placements": p.indentation_placements, "seed": p.indentation_seed,
        "hardness_factors": [("inf" if math.isinf(f) else f) for f in p.indentation_hardness_factors],
        "unload_fraction": p.indentation_unload_fraction, "dtype": p.indentation_dtype,
        "maxiter": p.indentation_maxiter, "truncation_increments": p.indentation_increments, "refine": p.indentation_refine,
        "material": m.to_dict(), **_refinement(p),
    })  # fmt: skip


def _refinement(p: Profile) -> dict[str, Any]:
    """The cells' refinement rule (issue 38) when it is on; {} when off, so that pieces stored
    before it keep their parameters."""
    if p.indentation_refine_max <= 1:
        return {}
    return {"refine_max": p.indentation_refine_max,
            "resolution_tol": p.indentation_resolution_tol,
            "min_contact_pixels": p.indentation_min_contact_pixels}  # fmt: skip


@fill_doc(_STAGE_DOCS)
def piece_names(p: Profile) -> list[tuple[str, float]]:
    """(surface, hardness factor) of every piece, in the order they are computed.

    {profile}

    Returns
    -------
    list of (str, float)
        Surface name and H factor (inf = elastic).
    """
    return [(s, f) for s in p.indentation_surfaces for f in p.indentation_hardness_factors]


def _piece_file(store: Path, surface: str, factor: float) -> Path:
    return store / f"{surface}__{model_name(factor)}.json"


def _piece_params(p: Profile, surface: str, factor: float) -> dict[str, Any]:
    par = stage_params(p)
    return jsonable({
        "surface": surface, "spec": par["surfaces"][surface], "hardness_factor": factor,
        "material": _material(factor).to_dict(),
        **{k: par[k] for k in ("punches_m", "loads_N", "placements", "seed", "unload_fraction",
                               "dtype", "maxiter", "truncation_increments")},
        **_refinement(p),
    })  # fmt: skip


def _load_piece(path: Path, params: dict[str, Any], overwrite: bool) -> dict[str, Any] | None:
    if not path.exists():
        return None
    rec = json.loads(path.read_text())
    if rec.get("params") == params:
        return rec
    if overwrite:
        return None
    raise StageConflict(
        f"piece {path.name} of stage 'indentation' in {path.parent} was computed with other "
        "parameters; use another --out, or --overwrite to replace it"
    )


def _run_indent(surface, p: Profile, factor: float, *, placements, device, reuse=None) -> Any:
    from ..contact.settings import SolverSettings
    from ..indent import PlacementOverlapWarning, indent

    with warnings.catch_warnings():  # the overlap is recorded per row (overlap_fraction)
        warnings.simplefilter("ignore", PlacementOverlapWarning)
        return indent(
            surface, punch_diameter=tuple(p.indentation_punches),
            peak_loads=tuple(p.indentation_loads), unload_fraction=p.indentation_unload_fraction,
            material=_material(factor), placements=placements, seed=p.indentation_seed,
            settings=SolverSettings(dtype=p.indentation_dtype, maxiter=p.indentation_maxiter),
            truncation_increments=p.indentation_increments, elastic=math.isinf(factor),
            reuse=reuse, device=device, refine_max=p.indentation_refine_max,
            resolution_tol=p.indentation_resolution_tol,
            min_contact_pixels=p.indentation_min_contact_pixels,
        )  # fmt: skip


def _piece_record(res, params: dict[str, Any], gen_s: float, wall_s: float) -> dict[str, Any]:
    cols = {**res.to_dict()}
    cols["n_contact"] = cols["n_contact_pixels"]  # the pieces' name, kept
    sec = res.settings["seconds"]
    windows = [{"punch_diameter_m": w["punch_diameter_m"], "placement": w["placement"],
                "window_px": w["window"][2:], "n_punch_pixels": w["n_punch_pixels"],
                "disk_Rt_m": w["disk_Rt_m"]} for w in res.settings["punches"]]  # fmt: skip
    return jsonable({
        "params": params,
        "rows": {c: cols[c] for c in COLUMNS},
        "windows": windows,
        "seconds": {**sec, "surface_s": gen_s, "piece_s": wall_s},
        "device": res.settings["device"],
        "n_not_converged": int((~np.asarray(res.converged, bool)).sum()),
        "reused_elastic_cycles": int(res.settings.get("reused_elastic_cycles", 0)),
    })  # fmt: skip


@fill_doc(_STAGE_DOCS)
def stage_indentation(p: Profile, out: str | Path, device, *, overwrite: bool = False,
                      deadline: float | None = None, progress: bool = True) -> dict[str, Any]:  # fmt: skip
    """Run (or continue) the pieces under ``out/indentation`` and summarise them.

    {indentation_profile}
    out : str or Path
        Reproduction folder; the pieces go to ``out/indentation``.
    device : str, optional
        Warp device.
    overwrite : bool
        Recompute pieces stored with other parameters (else :class:`StageConflict`).
    deadline : float, optional
        ``time.perf_counter()`` value after which no new piece is started; the stage then
        raises :class:`StageIncomplete` (the pieces done are stored).
    progress : bool
        Progress bar over the pieces (stderr).

    Returns
    -------
    dict
        :func:`summary_from_pieces` of the stored pieces.

    Raises
    ------
    StageIncomplete
        The deadline passed before the last piece.
    StageConflict
        A piece stored with other parameters and ``overwrite`` off.
    """
    from .._support.progress import progress_bar

    store = Path(out) / SUBDIR
    store.mkdir(parents=True, exist_ok=True)
    pieces = piece_names(p)
    done: dict[tuple[str, float], dict[str, Any]] = {}
    cache: dict[str, tuple[Any, float]] = {}  # one surface at a time, shared by its H values
    todo = []
    for s, f in pieces:
        rec = _load_piece(_piece_file(store, s, f), _piece_params(p, s, f), overwrite)
        if rec is None:
            todo.append((s, f))
        else:
            done[(s, f)] = rec
    ref = _resolution_params(p)
    rpath = store / "resolution.json"
    res_rec = _load_piece(rpath, ref, overwrite) if ref is not None else None
    n_todo = len(todo) + (ref is not None and res_rec is None)
    bar = progress_bar(total=n_todo, desc="indentation pieces", unit="piece", enabled=progress)
    with bar:
        for s, f in todo:
            if deadline is not None and time.perf_counter() > deadline:
                raise StageIncomplete(
                    f"stage 'indentation' stopped at its time budget: {len(done)} of "
                    f"{len(pieces)} pieces stored in {store} (resolution check "
                    f"{'stored' if res_rec is not None else 'not run'}); run the same "
                    "command again to continue"
                )
            t0 = time.perf_counter()
            if s not in cache:
                cache.clear()
                from ..wm import wm_surface

                surface = wm_surface(_spec(p, s), device=device)
                surface.heights  # noqa: B018 - one host copy, shared by the pieces
                cache[s] = (surface, time.perf_counter() - t0)
            surface, gen_s = cache[s]
            t1 = time.perf_counter()
            # the elastic piece's unyielded cycles are this piece's too (warptrunc.indent's reuse)
            el = done.get((s, math.inf))
            reuse = (el["rows"] if el is not None and not math.isinf(f)
                     and "max_pressure_Pa" in el["rows"] and p.indentation_refine_max <= 1
                     else None)  # fmt: skip
            res = _run_indent(surface, p, f, placements=p.indentation_placements, device=device,
                              reuse=reuse)  # fmt: skip
            rec = _piece_record(res, _piece_params(p, s, f), gen_s, time.perf_counter() - t1)
            write_atomic(_piece_file(store, s, f), json.dumps(rec, indent=None, allow_nan=False) + "\n")
            done[(s, f)] = rec
            bar.update()
        cache.clear()
        if ref is not None and res_rec is None:
            if deadline is not None and time.perf_counter() > deadline:
                raise StageIncomplete(
                    f"stage 'indentation' stopped at its time budget before the resolution "
                    f"check ({len(done)} of {len(pieces)} pieces stored in {store}); run the "
                    "same command again to continue"
                )
            res_rec = _run_resolution(p, ref, device)
            write_atomic(rpath, json.dumps(res_rec, indent=None, allow_nan=False) + "\n")
            bar.update()
    return summary_from_pieces(p, [done[k] for k in pieces], res_rec)


# --- resolution check -------------------------------------------------------------------------


def _resolution_params(p: Profile) -> dict[str, Any] | None:
    if not p.indentation_refine:
        return None
    s = RESOLUTION_SURFACE if RESOLUTION_SURFACE in p.indentation_surfaces else p.indentation_surfaces[0]
    finite = [f for f in p.indentation_hardness_factors if math.isfinite(f)]
    return jsonable({
        "surface": s, "spec": _spec(p, s).to_dict(), "n_coarse": p.indentation_n,
        "n_fine": 2 * p.indentation_n, "punch_m": min(p.indentation_punches),
        "hardness_factors": ["inf", *finite[:1]], "placement": "map centre",
        **{k: stage_params(p)[k] for k in ("loads_N", "unload_fraction", "dtype", "maxiter",
                                            "truncation_increments")},
    })  # fmt: skip


def _run_resolution(p: Profile, ref: dict[str, Any], device) -> dict[str, Any]:
    """The smallest punch at the map centre on the same surface at dx and dx/2."""
    from ..contact.settings import SolverSettings
    from ..indent import indent
    from ..wm import wm_surface

    spec = _spec(p, ref["surface"])
    coarse = wm_surface(spec, device=device)
    # the same surface twice as finely: the coarse map's height scale (as a topothesy) and
    # cut-off, so that no term is added and none aliases
    fine_spec = spec.replace(n=ref["n_fine"], Rt=None, G=coarse.params["G_equivalent"],
                             Wc=coarse.params["Wc"])  # fmt: skip
    t0 = time.perf_counter()
    fine = wm_surface(fine_spec, device=device)
    out: dict[str, Any] = {"params": ref, "grids": {}, "fine_spec": fine_spec.to_dict()}
    for tag, surf in (("coarse", coarse), ("fine", fine)):
        g: dict[str, Any] = {"n": int(surf.heights.shape[0]), "dx_m": surf.dx, "Rt_m": surf.Rt}
        for fac in (math.inf, *[f for f in ref["hardness_factors"] if f != "inf"]):
            t1 = time.perf_counter()
            r = indent(surf, punch_diameter=(ref["punch_m"],), peak_loads=tuple(ref["loads_N"]),
                       unload_fraction=ref["unload_fraction"], material=_material(fac),
                       placements=None,
                       settings=SolverSettings(dtype=ref["dtype"], maxiter=ref["maxiter"]),
                       truncation_increments=ref["truncation_increments"],
                       elastic=math.isinf(fac), device=device, refine_max=1)  # fmt: skip
            cols = {**r.to_dict()}
            cols["n_contact"] = cols["n_contact_pixels"]
            g[model_name(fac)] = {c: cols[c] for c in (
                "peak_load_N", "unloading_stiffness_N_per_m", "partial_unloading_stiffness_N_per_m",
                "contact_area_m2", "plastic_area_m2", "n_contact", "E_c_over_E", "converged",
                "truncation_E_c_over_E", "n_punch_pixels")}  # fmt: skip
            g[model_name(fac)]["seconds"] = time.perf_counter() - t1
        out["grids"][tag] = g
    out["seconds"] = time.perf_counter() - t0
    return jsonable(out)


# --- summary --------------------------------------------------------------------------------------


@fill_doc(_STAGE_DOCS)
def summary_from_pieces(p: Profile, pieces: list[dict[str, Any]],
                        resolution: dict[str, Any] | None) -> dict[str, Any]:  # fmt: skip
    """The stage result from its stored pieces.

    {profile}
    pieces : list of dict
        The piece records, in :func:`piece_names` order.
    resolution : dict or None
        The resolution-check record.

    Returns
    -------
    dict
        ``rows`` (columns over every surface × model × punch × placement × load, with
        ``surface`` and ``model``; the truncation rows under ``model = "truncation"``, taken
        from the first piece of each surface), ``timings`` (one entry per piece), ``windows``,
        the settings and the ``resolution`` record (JSON-able).
    """
    from ..indent import ALUMINIUM_HARDNESS

    rows: dict[str, list] = {"surface": [], "model": []}
    keep = ("punch_diameter_m", "placement", "peak_load_N", "F_over_EA", "displacement_m",
            "contact_area_m2", "plastic_area_m2", "n_contact", "E_c_over_E", "E_c_partial_over_E",
            "converged", "overlap_fraction", "n_punch_pixels", "in_fit")  # fmt: skip
    timings, seen, trunc_same = [], set(), True
    first_trunc: dict[str, list] = {}
    for (s, f), rec in zip(piece_names(p), pieces, strict=True):
        r = rec["rows"]
        m = len(r["peak_load_N"])
        rows["surface"] += [s] * m
        rows["model"] += [model_name(f)] * m
        r = {**r, "in_fit": r["in_fit"] if "in_fit" in r else r["converged"]}  # older pieces
        for c in keep:
            rows.setdefault(c, []).extend(r[c])
        if s not in seen:  # truncation does not depend on H: once per surface
            seen.add(s)
            first_trunc[s] = r["truncation_E_c_over_E"]
            rows["surface"] += [s] * m
            rows["model"] += ["truncation"] * m
            for c in keep:
                v = {"E_c_over_E": r["truncation_E_c_over_E"], "E_c_partial_over_E": [None] * m,
                     "contact_area_m2": r["truncation_contact_area_m2"],
                     "displacement_m": r["truncation_depth_m"], "plastic_area_m2": [None] * m,
                     "n_contact": [None] * m, "converged": [True] * m}.get(c, r[c])  # fmt: skip
                rows[c].extend(v)
        else:
            trunc_same &= r["truncation_E_c_over_E"] == first_trunc[s]
        win = max((w["window_px"] for w in rec["windows"]), key=lambda v: v[0] * v[1])
        timings.append({"surface": s, "model": model_name(f), **rec["seconds"],
                        "largest_window_px": win, "n_not_converged": rec["n_not_converged"],
                        "reused_elastic_cycles": rec.get("reused_elastic_cycles", 0),
                        "device": rec["device"]})  # fmt: skip
    m = _material(1.0)
    return {
        "store": SUBDIR,
        "surfaces": list(p.indentation_surfaces),
        "models": [model_name(f) for f in p.indentation_hardness_factors],
        "hardness_Pa": {model_name(f): (None if math.isinf(f) else f * ALUMINIUM_HARDNESS)
                        for f in p.indentation_hardness_factors},  # fmt: skip
        "punches_m": list(p.indentation_punches),
        "loads_N": list(p.indentation_loads),
        "placements": p.indentation_placements,
        "n": p.indentation_n, "L_m": p.indentation_L, "dx_m": p.indentation_L / p.indentation_n,
        "dtype": p.indentation_dtype,
        # the cells the fits use: every converged one without refinement (as before issue 38)
        "fit_cells": "in_fit" if p.indentation_refine_max > 1 else "converged",
        "refine_max": p.indentation_refine_max,
        "material": {"E_Pa": m.E, "nu": m.nu, "E_i_Pa": m.E_i, "nu_i": m.nu_i,
                     "E_star_Pa": m.contact_modulus, "H_alloy_Pa": ALUMINIUM_HARDNESS},
        "truncation_same_over_H": bool(trunc_same),
        "rows": rows,
        "windows": pieces[0]["windows"] if pieces else [],
        "timings": timings,
        "resolution": resolution,
    }  # fmt: skip


# --- analysis -------------------------------------------------------------------------------------
