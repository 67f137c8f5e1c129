# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The stored units of work of the ``indentation`` stage: pieces and their parts.

A **piece** is a surface × design × hardness H (:mod:`warptrunc.reproduce.indentation.design`): its parameters
(:func:`piece_params`), its file ``<surface>__<design>__<model>.json`` under ``OUT/indentation``
(written atomically), and its rows. A **part** is one punch × one realisation of a piece, the
unit of work that runs in this process or on a Dask worker: punch k of
``protocol.punch_diameters`` on realisation r of the design's phase seeds, one
:func:`warptrunc.indent` call on one surface with the piece's punch, placements (seed
``protocol.placement_seed + k``, the same centres on every realisation) and settings. The rows
of a piece merged from its parts (:func:`merge_parts`: punch-major, then realisation,
placement, load) are the rows of the undivided piece: each punch window is solved on its own.
A part is written to ``<piece>__p<k>r<r>.json`` as soon as it is done (by the worker that ran
it); the piece file is written when its last part is, and the part files are then removed. A
store of whole pieces is read as it is.

Parts of finite H in the hardness sweep take their unyielded cycles from the elastic part of
the same punch (``reuse``) when that punch is not refined: that is the only dependency between
parts, besides the ``depth-match`` statistics, whose H is known once every surface's sweep is.
"""

from __future__ import annotations

import json
import math
import os
import time
import warnings
from collections import OrderedDict
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..._support.outputs import jsonable, write_atomic
from ..store import StageConflict
from .design import (
    IndentationStage,
    design_of,
    face_fields,
    face_spec,
    face_variants,
    material,
    model_name,
    refine_of,
    spec,
)

__all__ = [
    "COLUMNS",
    "SUBDIR",
    "Part",
    "compute_part",
    "load_piece",
    "merge_parts",
    "part_file",
    "part_params",
    "parts_of",
    "piece_file",
    "piece_params",
    "run_part",
]

SUBDIR = "indentation"
"""Piece store of the stage, inside the reproduction folder."""
COLUMNS = (
    "punch_diameter_m",
    "placement",
    "realisation",
    "peak_load_N",
    "F_over_EA",
    "displacement_m",
    "contact_area_m2",
    "plastic_area_m2",
    "n_contact",
    "unloading_stiffness_N_per_m",
    "partial_unloading_stiffness_N_per_m",
    "E_c_over_E",
    "E_c_partial_over_E",
    "converged",
    "overlap_fraction",
    "n_punch_pixels",
    "truncation_depth_m",
    "truncation_contact_area_m2",
    "truncation_stiffness_N_per_m",
    "truncation_E_c_over_E",
    "centre_x_m",
    "centre_y_m",
    "max_pressure_Pa",
    "pixel_size_m",
    "resolution_change",
    "area_change",
    "resolved",
    "saturated",
    "in_fit",
    "area_resolved",
    "sub_window",
    "bulk_yield",
    "mean_pressure_Pa",
    "stiffness_extrapolated_N_per_m",
    "stiffness_error_N_per_m",
    "contact_area_error_m2",
    "detection_displacement_m",
    "threshold_depth_m",
    "truncation_pixel_size_m",
    "resolution_note",
)
"""Columns of :meth:`warptrunc.indent.IndentationResult.to_dict` kept in each piece."""

CAP_MARGIN = 0.99
"""A part solves only the peak loads below this fraction of what its punch's pressure cap can
carry, H·A (dimensionless); the heavier ones (at soft H under the smallest punch) cannot be
solved by the cap model and are stored as rows flagged ``bulk_yield``, not solved
(:func:`bulk_yield_rows`)."""

PLACEMENT_SEEDS = "indentation_seed + punch index"
"""How a piece's parameters say punch k's placement seed is drawn (protocol.placement_seed + k):
the wording of the stored pieces' parameters, which identify them."""


# --- pieces -------------------------------------------------------------------------------------


def piece_params(
    st: IndentationStage,
    surface: str,
    design: str,
    hardness: float,
    face: tuple[str, dict[str, float]] | None = None,
) -> dict[str, Any]:
    """The parameters that identify one stored piece.

    Parameters
    ----------
    st : IndentationStage
        The stage.
    surface : str
        Table 1 name.
    design : str
        ``"sweep"``, ``"stats"`` or ``"face"``.
    hardness : float
        H (Pa); inf = elastic.
    face : (str, dict), optional
        A punch face of :func:`~.design.face_variants` (``face`` pieces).

    Returns
    -------
    dict
        JSON-able: surface and its preset, the design's seeds and placements, H and the
        material, punches, loads, placement seed, solver settings, the refinement per punch
        and the face (each punch's :class:`~warptrunc.indent.PunchFaceSpec` fields).
    """
    seeds, placements = design_of(st, design)
    pr = st.protocol
    refine = {
        "refine_max": {f"{d:g}": refine_of(st, d) for d in pr.punch_diameters},
        "resolution_tol": pr.resolution_tol,
        "min_contact_pixels": pr.min_contact_pixels,
    }
    return jsonable(
        {
            "surface": surface,
            "design": design,
            "spec": spec(st, surface).to_dict(),
            "seeds": list(seeds),
            "placements": placements,
            "hardness_Pa": hardness,
            "material": material(st, hardness).to_dict(),
            "punches_m": list(pr.punch_diameters),
            "loads_N": list(pr.peak_loads),
            "placement_seed": pr.placement_seed,
            "placement_seeds": PLACEMENT_SEEDS,
            "unload_fraction": pr.unload_fraction,
            "dtype": st.solver.dtype,
            "maxiter": st.solver.maxiter,
            "truncation_increments": pr.truncation_increments,
            "refinement": refine,
            **(
                {}
                if face is None
                else {
                    "face": {
                        "label": face[0],
                        "per_punch": [
                            face_fields(st, face[1], k, d) for k, d in enumerate(pr.punch_diameters)
                        ],
                    }
                }
            ),
        }
    )


def _slug(label: str) -> str:
    return label.replace(" µm rms", "um").replace("°", "deg").replace(" ", "")


def piece_file(
    store: Path, surface: str, design: str, hardness: float, face: str | None = None
) -> Path:
    """The piece's file.

    Parameters
    ----------
    store : Path
        The piece folder.
    surface, design : str
        Table 1 name and design.
    hardness : float
        H (Pa); inf = elastic.
    face : str, optional
        Face label of a ``face`` piece.

    Returns
    -------
    Path
        ``<store>/<surface>__<design>__<model>.json`` (a face piece: ``__face__<face>__``).
    """
    tag = design if face is None else f"{design}__{_slug(face)}"
    return store / f"{surface}__{tag}__{model_name(hardness)}.json"


def load_piece(path: Path, params: dict[str, Any], overwrite: bool) -> dict[str, Any] | None:
    """The stored piece when its parameters are ``params``; None when absent (or replaced).

    Parameters
    ----------
    path : Path
        The piece's file.
    params : dict
        Its parameters (:func:`piece_params`).
    overwrite : bool
        A piece stored with other parameters is replaced (else refused).

    Returns
    -------
    dict or None
        The piece record.

    Raises
    ------
    StageConflict
        A piece stored with other parameters, without ``overwrite``.
    """
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


def reuse_rows(rows: dict[str, list] | None, d: float) -> dict[str, list] | None:
    """The elastic piece's rows of punch ``d`` (for :func:`warptrunc.indent`'s ``reuse``).

    Parameters
    ----------
    rows : dict or None
        The rows of the elastic sweep piece.
    d : float
        Punch diameter (m).

    Returns
    -------
    dict or None
        Its rows of punch ``d``; None without rows (or rows without ``max_pressure_Pa``).
    """
    if rows is None or "max_pressure_Pa" not in rows:
        return None
    idx = [i for i, x in enumerate(rows["punch_diameter_m"]) if math.isclose(x, d, rel_tol=1e-9)]
    return {c: [v[i] for i in idx] for c, v in rows.items()}


# --- parts --------------------------------------------------------------------------------------

CACHE_SIZE = int(os.environ.get("WARPTRUNC_INDENT_SURFACES", "4"))
"""Surfaces (realisations) kept per process between parts (count; ``$WARPTRUNC_INDENT_SURFACES``)."""
_SURFACES: OrderedDict[tuple, tuple[Any, float]] = OrderedDict()


@dataclass(frozen=True)
class Part:
    """One punch × one realisation of a piece.

    Parameters
    ----------
    surface : str
        Table 1 name.
    design : str
        ``"sweep"``, ``"stats"`` or ``"face"``.
    hardness : float
        H (Pa); inf = elastic.
    face : str or None
        Label of the punch face (:func:`~.design.face_variants`; ``face`` pieces).
    punch : int
        Index k of the punch in ``protocol.punch_diameters``.
    realisation : int
        Index r of the phase seed in the design's seeds.
    """

    surface: str
    """Table 1 name."""
    design: str
    """``"sweep"``, ``"stats"`` or ``"face"``."""
    hardness: float
    """H (Pa); inf = elastic."""
    face: str | None
    """Label of the punch face, or None."""
    punch: int
    """Index k of the punch in ``protocol.punch_diameters``."""
    realisation: int
    """Index r of the phase seed in the design's seeds."""

    @property
    def piece(self) -> tuple[str, str, float, str | None]:
        """(surface, design, H, face label): the piece this part belongs to."""
        return (self.surface, self.design, self.hardness, self.face)

    def label(self) -> str:
        """Short text for messages.

        Returns
        -------
        str
            E.g. ``Ps sweep H=1e+09 Pa punch 2 realisation 0``.
        """
        face = "" if self.face is None else f" face {self.face!r}"
        return (
            f"{self.surface} {self.design} H={self.hardness:g} Pa{face} punch {self.punch} "
            f"realisation {self.realisation}"
        )


def face_of(st: IndentationStage, label: str | None) -> tuple[str, dict[str, float]] | None:
    """The face variant (label, keywords) named ``label``; None for the aligned smooth punch."""
    if label is None:
        return None
    for f in face_variants(st):
        if f[0] == label:
            return f
    raise ValueError(f"face must be one of {[f[0] for f in face_variants(st)]}, got {label!r}")


def parts_of(
    st: IndentationStage, surface: str, design: str, hardness: float, face: str | None = None
) -> list[Part]:
    """The parts of one piece, punch-major (the order of its rows).

    Parameters
    ----------
    st : IndentationStage
        The stage.
    surface, design : str
        Table 1 name and design.
    hardness : float
        H (Pa); inf = elastic.
    face : str, optional
        Face label of a ``face`` piece.

    Returns
    -------
    list of Part
        ``len(protocol.punch_diameters) × len(seeds of the design)`` parts.
    """
    seeds, _ = design_of(st, design)
    return [
        Part(surface, design, float(hardness), face, k, r)
        for k in range(len(st.protocol.punch_diameters))
        for r in range(len(seeds))
    ]


def part_params(st: IndentationStage, part: Part) -> dict[str, Any]:
    """The parameters that identify a stored part: its piece's, the punch and the seed.

    Parameters
    ----------
    st : IndentationStage
        The stage.
    part : Part
        The part.

    Returns
    -------
    dict
        JSON-able: ``piece`` (:func:`piece_params`), ``punch_m``,
        ``seed``, ``realisation``.
    """
    seeds, _ = design_of(st, part.design)
    return jsonable(
        {
            "piece": piece_params(
                st, part.surface, part.design, part.hardness, face_of(st, part.face)
            ),
            "punch_m": st.protocol.punch_diameters[part.punch],
            "seed": seeds[part.realisation],
            "realisation": part.realisation,
        }
    )


def part_file(store: Path, part: Part) -> Path:
    """The part's file, next to its piece's.

    Parameters
    ----------
    store : Path
        The piece folder.
    part : Part
        The part.

    Returns
    -------
    Path
        ``<piece file stem>__p<k>r<r>.json``.
    """
    f = piece_file(store, part.surface, part.design, part.hardness, part.face)
    return f.with_name(f"{f.stem}__p{part.punch}r{part.realisation}.json")


def reuses(st: IndentationStage, part: Part) -> bool:
    """Whether ``part`` takes its unyielded cycles from the elastic part of its punch.

    Parameters
    ----------
    st : IndentationStage
        The stage.
    part : Part
        The part.

    Returns
    -------
    bool
        A finite-H sweep part of a punch that is not refined.
    """
    return (
        part.design == "sweep"
        and math.isfinite(part.hardness)
        and part.face is None
        and refine_of(st, st.protocol.punch_diameters[part.punch]) <= 1
    )


def elastic_of(part: Part) -> Part:
    """The elastic sweep part whose rows ``part`` reuses.

    Parameters
    ----------
    part : Part
        A finite-H sweep part.

    Returns
    -------
    Part
    """
    return Part(part.surface, "sweep", math.inf, None, part.punch, part.realisation)


def surface_for(st: IndentationStage, name: str, seed: int, device) -> tuple[Any, float]:
    """The realisation (generated once per process, :data:`CACHE_SIZE` kept) and its seconds.

    Parameters
    ----------
    st : IndentationStage
        The stage (its maps).
    name : str
        Table 1 name.
    seed : int
        Phase seed.
    device : str, optional
        Warp device.

    Returns
    -------
    tuple
        (Surface, seconds of its generation in this call; the first call's when cached).
    """
    from ...wm import wm_surface

    sp = spec(st, name, seed)
    key = (name, int(seed), json.dumps(jsonable(sp.to_dict()), sort_keys=True), str(device))
    if key in _SURFACES:
        _SURFACES.move_to_end(key)
        return _SURFACES[key]
    t0 = time.perf_counter()
    surf = wm_surface(sp, device=device)
    surf.heights  # noqa: B018 - one host copy, shared by the parts
    while len(_SURFACES) >= max(CACHE_SIZE, 1):
        _SURFACES.popitem(last=False)
    _SURFACES[key] = (surf, time.perf_counter() - t0)
    return _SURFACES[key]


def run_part(
    st: IndentationStage, part: Part, *, device, reuse: dict[str, list] | None = None
) -> dict[str, Any]:
    """Run one part: :func:`warptrunc.indent` with one punch on one realisation.

    Parameters
    ----------
    st : IndentationStage
        The stage.
    part : Part
        The part.
    device : str, optional
        Warp device (None: ``$WARPTRUNC_DEVICE``, else the default).
    reuse : dict, optional
        Rows of ``elastic_of``'s part (when ``reuses``): the unyielded cycles.

    Returns
    -------
    dict
        ``params`` (:func:`part_params`), ``rows`` (:data:`COLUMNS`,
        ``realisation`` = r), ``windows``, ``per_punch`` (one entry), ``seconds`` (with
        ``surface_s``, the realisation's generation, 0 when it was cached), ``device``,
        ``reused_elastic_cycles``.
    """
    from ...indent import PlacementOverlapWarning, indent

    seeds, placements = design_of(st, part.design)
    surf, gen = surface_for(st, part.surface, seeds[part.realisation], device)
    t0 = time.perf_counter()
    k, d, h = part.punch, st.protocol.punch_diameters[part.punch], part.hardness
    loads = tuple(st.protocol.peak_loads)
    carried = tuple(f for f in loads if f < CAP_MARGIN * h * math.pi * d * d / 4)
    protocol = st.protocol.replace(
        punch_diameters=(d,),
        peak_loads=carried or loads[:1],
        placements=placements,
        placement_seed=st.protocol.placement_seed + k,
        refine_max=refine_of(st, d),
        elastic=math.isinf(h),
        face=face_spec(st, face_of(st, part.face), k, d),
    )
    use = reuse if reuses(st, part) else None
    if use is not None and len(carried) < len(loads):  # the elastic rows of the loads solved
        keep = [i for i, f in enumerate(use["peak_load_N"]) if f in carried]
        use = {c: [v[i] for i in keep] for c, v in use.items()}
    with warnings.catch_warnings():  # the overlap is recorded per row (overlap_fraction)
        warnings.simplefilter("ignore", PlacementOverlapWarning)
        res = indent(
            surf,
            protocol=protocol,
            material=material(st, h),
            solver=st.solver,
            reuse=use,
            device=device,
        )
    cols = res.to_dict()
    cols["n_contact"] = cols["n_contact_pixels"]  # the pieces' name, kept
    cols["realisation"] = [part.realisation] * len(cols["peak_load_N"])
    rows = {c: np.asarray(cols[c]).tolist() for c in COLUMNS}
    if len(carried) < len(loads):
        rows = bulk_yield_rows(rows, loads, carried)
    windows, refined = [], {}
    for w in res.settings["punches"]:
        windows.append(
            {
                "realisation": part.realisation,
                "punch_diameter_m": d,
                "placement": w["placement"],
                "window_px": w["window"][2:],
                "n_punch_pixels": w["n_punch_pixels"],
                "disk_Rt_m": w["disk_Rt_m"],
                "local_plane_tilt_deg": w.get("local_plane_tilt_deg"),
                "face_tilt_azimuth_deg": w.get("face_tilt_azimuth_deg"),
            }
        )
        for f, shape in w["refined_windows"].items():
            old = refined.get(str(int(f)), [0, 0])
            refined[str(int(f))] = shape if shape[0] * shape[1] > old[0] * old[1] else old
    s = dict(res.settings["seconds"])
    return jsonable(
        {
            "params": part_params(st, part),
            "rows": rows,
            "windows": windows,
            "per_punch": {
                "punch_diameter_m": d,
                "refine_max": refine_of(st, d),
                "seconds": s,
                "refined_windows": refined,
            },
            "seconds": {**s, "surface_s": gen, "part_s": time.perf_counter() - t0},
            "device": res.settings["device"],
            "reused_elastic_cycles": int(res.settings.get("reused_elastic_cycles", 0)),
        }
    )


def bulk_yield_rows(
    rows: dict[str, list], loads: tuple[float, ...], carried: tuple[float, ...]
) -> dict[str, list]:
    """A part's rows with a row per load its punch's cap cannot carry, flagged, not solved.

    Parameters
    ----------
    rows : dict of str to list
        The rows of the loads solved (:data:`COLUMNS`), placement-major, load fastest; when no
        load was carried, the rows of the lightest load solved only for the placements.
    loads : tuple of float
        Every peak load of the stage (N).
    carried : tuple of float
        The loads solved (N).

    Returns
    -------
    dict of str to list
        Per placement, a row per load of ``loads`` in order: the solved ones as they were,
        the others with the punch, placement and load, ``bulk_yield`` True, ``converged``,
        ``resolved``, ``in_fit`` False and None (NaN) for every measured quantity.
    """
    keys = ("punch_diameter_m", "placement", "realisation", "centre_x_m", "centre_y_m",
            "overlap_fraction", "n_punch_pixels", "pixel_size_m", "truncation_pixel_size_m")  # fmt: skip
    flags = {"bulk_yield": True, "converged": False, "resolved": False, "area_resolved": False,
             "saturated": False, "in_fit": False, "sub_window": False,
             "resolution_note": "bulk-yield"}  # fmt: skip
    out: dict[str, list] = {c: [] for c in rows}
    n = len(rows["peak_load_N"])
    for j in dict.fromkeys(rows["placement"]):
        mine = [i for i in range(n) if rows["placement"][i] == j]
        by_load = {rows["peak_load_N"][i]: i for i in mine}
        for f in loads:
            if f in carried and f in by_load:
                for c in rows:
                    out[c].append(rows[c][by_load[f]])
                continue
            i0 = mine[0]
            for c in rows:
                if c in keys:
                    out[c].append(rows[c][i0])
                elif c in flags:
                    out[c].append(flags[c])
                elif c == "peak_load_N":
                    out[c].append(f)
                elif c == "F_over_EA":
                    out[c].append(rows[c][i0] * f / rows["peak_load_N"][i0])
                elif c == "mean_pressure_Pa":
                    out[c].append(rows[c][i0] * f / rows["peak_load_N"][i0])
                else:
                    out[c].append(None)
    return out


def load_part(path: Path, params: dict[str, Any]) -> dict[str, Any] | None:
    """The stored part when its parameters are ``params``; None when absent or other (a part
    of other parameters is recomputed: the piece it belongs to is what the store checks).

    Parameters
    ----------
    path : Path
        The part's file.
    params : dict
        Its parameters (:func:`part_params`).

    Returns
    -------
    dict or None
    """
    if not path.exists():
        return None
    try:
        rec = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError):
        return None
    return rec if rec.get("params") == params else None


def compute_part(
    st: IndentationStage, part: Part, store: str, device=None, reuse: dict[str, list] | None = None
) -> dict[str, Any]:
    """Run ``part`` unless its file is stored, write it atomically, return its record.

    The task of a Dask worker (and of the in-process run): a part whose file exists with the
    same parameters (written by a worker that died before its result arrived) is read, not
    solved again.

    Parameters
    ----------
    st : IndentationStage
        The stage.
    part : Part
        The part.
    store : str
        The stage's piece folder (``OUT/indentation``; a filesystem the workers share).
    device : str, optional
        Warp device (None: the worker's ``$WARPTRUNC_DEVICE``).
    reuse : dict, optional
        Rows of the elastic part (``reuses``).

    Returns
    -------
    dict
        The part record (:func:`run_part`).
    """
    path = part_file(Path(store), part)
    params = part_params(st, part)
    rec = load_part(path, params)
    if rec is None:
        rec = run_part(st, part, device=device, reuse=reuse)
        write_atomic(path, json.dumps(rec, indent=None, allow_nan=False) + "\n")
    return rec


def merge_parts(
    st: IndentationStage, piece: tuple[str, str, float, str | None], recs: dict[Part, dict]
) -> dict[str, Any]:
    """The piece record of a piece's parts (the layout of an undivided piece).

    Parameters
    ----------
    st : IndentationStage
        The stage.
    piece : tuple
        (surface, design, H, face label).
    recs : dict
        Part → its record, for every part of the piece.

    Returns
    -------
    dict
        ``params`` (the piece's), ``rows`` (punch-major, then realisation), ``windows``,
        ``seconds`` (summed over parts; ``surface_s`` the realisations' generation once each;
        ``piece_s`` the parts' solve seconds summed — device time, not wall time, when the
        parts ran in parallel), ``per_punch`` (one entry per punch, seconds summed over its
        realisations), ``device`` (one, or the sorted list of the parts' devices),
        ``n_not_converged``, ``reused_elastic_cycles``, ``n_parts``.
    """
    s, design, h, face = piece
    order = parts_of(st, s, design, h, face)
    rows: dict[str, list] = {c: [] for c in COLUMNS}
    windows, per_punch, sec, gen = [], [], {}, {}
    devices, n_reused = set(), 0
    for k in range(len(st.protocol.punch_diameters)):
        pp: dict[str, Any] = {"seconds": {}, "refined_windows": {}}
        for part in (q for q in order if q.punch == k):
            rec = recs[part]
            for c in COLUMNS:
                rows[c].extend(rec["rows"][c])
            windows += rec["windows"]
            one = rec["per_punch"]
            pp.update(punch_diameter_m=one["punch_diameter_m"], refine_max=one["refine_max"])
            for key, v in one["seconds"].items():
                pp["seconds"][key] = pp["seconds"].get(key, 0.0) + v
            for f, shape in one["refined_windows"].items():
                old = pp["refined_windows"].get(f, [0, 0])
                pp["refined_windows"][f] = shape if shape[0] * shape[1] > old[0] * old[1] else old
            for key, v in rec["seconds"].items():
                if key not in ("surface_s", "part_s"):
                    sec[key] = sec.get(key, 0.0) + v
            gen[part.realisation] = max(gen.get(part.realisation, 0.0), rec["seconds"]["surface_s"])
            sec["piece_s"] = sec.get("piece_s", 0.0) + rec["seconds"]["part_s"]
            devices.add(rec["device"])
            n_reused += int(rec.get("reused_elastic_cycles", 0))
        per_punch.append(pp)
    return jsonable(
        {
            "params": piece_params(st, s, design, h, face_of(st, face)),
            "rows": rows,
            "windows": windows,
            "seconds": {**sec, "surface_s": sum(gen.values())},
            "per_punch": per_punch,
            "device": next(iter(devices)) if len(devices) == 1 else sorted(devices),
            "n_not_converged": int(
                sum(
                    not c and not b
                    for c, b in zip(rows["converged"], rows["bulk_yield"], strict=True)
                )
            ),
            "n_bulk_yield": int(sum(bool(b) for b in rows["bulk_yield"])),
            "reused_elastic_cycles": n_reused,
            "n_parts": len(order),
        }
    )
