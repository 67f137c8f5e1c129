# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Parts of the ``indentation`` stage's pieces: one punch × one realisation of a piece, the unit
of work that runs in this process or on a Dask worker (issue 39, item 2).

A piece (surface × design × H, :mod:`.indentation_pieces`) is the union of its parts: punch k
of ``Profile.indentation_punches`` on realisation r of the design's phase seeds. A part is one
:func:`warptrunc.indent` call on one surface with the piece's punch, placements (seed
``indentation_seed + k``, the same centres on every realisation) and settings, so the rows of
a piece merged from its parts (:func:`merge_parts`: punch-major, then realisation, placement,
load) are the rows of the undivided piece: each punch window is solved on its own. A part is
written to ``<piece>__p<k>r<r>.json`` as soon as it is done (by the worker that ran it); the
piece file is written when its last part is, and the part files are then removed. A store of
whole pieces (written before the parts existed) is read as it is.

Parts of finite H in the hardness sweep take their unyielded cycles from the elastic part of
the same punch (``reuse``) when that punch is not refined: that is the only dependency between
parts, besides the ``depth-match`` statistics, whose H is known once the surface's sweep is.
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

from .._support.results import jsonable, write_atomic
from .indentation_pieces import (
    COLUMNS,
    _face_kw,
    design_of,
    face_variants,
    material,
    piece_file,
    piece_params,
    refine_of,
    spec,
)
from .profiles import Profile

__all__ = ["Part", "compute_part", "merge_parts", "part_file", "part_params", "parts_of", "run_part"]

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
        Label of the punch face (:func:`~.indentation_pieces.face_variants`; ``face`` pieces).
    punch : int
        Index k of the punch in ``Profile.indentation_punches``.
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
    """Index k of the punch in ``Profile.indentation_punches``."""
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
        return (f"{self.surface} {self.design} H={self.hardness:g} Pa{face} punch {self.punch} "
                f"realisation {self.realisation}")  # fmt: skip


def face_of(p: Profile, label: str | None) -> tuple[str, dict[str, float]] | None:
    """The face variant (label, keywords) named ``label``; None for the aligned smooth punch."""
    if label is None:
        return None
    for f in face_variants(p):
        if f[0] == label:
            return f
    raise ValueError(f"face must be one of {[f[0] for f in face_variants(p)]}, got {label!r}")


def parts_of(p: Profile, surface: str, design: str, hardness: float, face: str | None = None) -> list[Part]:
    """The parts of one piece, punch-major (the order of its rows).

    Parameters
    ----------
    p : Profile
        The profile.
    surface, design : str
        Table 1 name and design.
    hardness : float
        H (Pa); inf = elastic.
    face : str, optional
        Face label of a ``face`` piece.

    Returns
    -------
    list of Part
        ``len(indentation_punches) × len(seeds of the design)`` parts.
    """
    seeds, _ = design_of(p, design)
    return [Part(surface, design, float(hardness), face, k, r)
            for k in range(len(p.indentation_punches)) for r in range(len(seeds))]  # fmt: skip


def part_params(p: Profile, part: Part) -> dict[str, Any]:
    """The parameters that identify a stored part: its piece's, the punch and the seed.

    Parameters
    ----------
    p : Profile
        The profile.
    part : Part
        The part.

    Returns
    -------
    dict
        JSON-able: ``piece`` (:func:`~.indentation_pieces.piece_params`), ``punch_m``,
        ``seed``, ``realisation``.
    """
    seeds, _ = design_of(p, part.design)
    return jsonable({
        "piece": piece_params(p, part.surface, part.design, part.hardness, face_of(p, part.face)),
        "punch_m": p.indentation_punches[part.punch], "seed": seeds[part.realisation],
        "realisation": part.realisation,
    })  # fmt: skip


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


def reuses(p: Profile, part: Part) -> bool:
    """Whether ``part`` takes its unyielded cycles from the elastic part of its punch."""
    return (part.design == "sweep" and math.isfinite(part.hardness) and part.face is None
            and refine_of(p, p.indentation_punches[part.punch]) <= 1)  # fmt: skip


def elastic_of(part: Part) -> Part:
    """The elastic sweep part whose rows ``part`` reuses."""
    return Part(part.surface, "sweep", math.inf, None, part.punch, part.realisation)


def surface_for(p: Profile, name: str, seed: int, device) -> tuple[Any, float]:
    """The realisation (generated once per process, :data:`CACHE_SIZE` kept) and its seconds."""
    from ..wm import wm_surface

    sp = spec(p, name, seed)
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


def run_part(p: Profile, part: Part, *, device, reuse: dict[str, list] | None = None) -> dict[str, Any]:
    """Run one part: :func:`warptrunc.indent` with one punch on one realisation.

    Parameters
    ----------
    p : Profile
        The profile.
    part : Part
        The part.
    device : str, optional
        Warp device (None: ``$WARPTRUNC_DEVICE``, else the default).
    reuse : dict, optional
        Rows of ``elastic_of``'s part (when ``reuses``): the unyielded cycles.

    Returns
    -------
    dict
        ``params`` (:func:`part_params`), ``rows`` (:data:`~.indentation_pieces.COLUMNS`,
        ``realisation`` = r), ``windows``, ``per_punch`` (one entry), ``seconds`` (with
        ``surface_s``, the realisation's generation, 0 when it was cached), ``device``,
        ``reused_elastic_cycles``.
    """
    from ..contact.settings import SolverSettings
    from ..indent import IndentProtocol, PlacementOverlapWarning, PunchFaceSpec, indent

    seeds, placements = design_of(p, part.design)
    surf, gen = surface_for(p, part.surface, seeds[part.realisation], device)
    t0 = time.perf_counter()
    k, d, h = part.punch, p.indentation_punches[part.punch], part.hardness
    face = face_of(p, part.face)
    with warnings.catch_warnings():  # the overlap is recorded per row (overlap_fraction)
        warnings.simplefilter("ignore", PlacementOverlapWarning)
        protocol = IndentProtocol(
            punch_diameters=(d,), peak_loads=tuple(p.indentation_loads),
            unload_fraction=p.indentation_unload_fraction, placements=placements,
            placement_seed=p.indentation_seed + k, truncation_increments=p.indentation_increments,
            refine_max=refine_of(p, d), resolution_tol=p.indentation_resolution_tol,
            min_contact_pixels=p.indentation_min_contact_pixels, elastic=math.isinf(h),
            face=PunchFaceSpec() if face is None else PunchFaceSpec(**_face_kw(p, face[1], k, d)),
        )  # fmt: skip
        res = indent(
            surf, protocol=protocol, material=material(h),
            solver=SolverSettings(dtype=p.indentation_dtype, maxiter=p.indentation_maxiter),
            reuse=reuse if reuses(p, part) else None, device=device,
        )  # fmt: skip
    cols = res.to_dict()
    cols["n_contact"] = cols["n_contact_pixels"]  # the pieces' name, kept
    cols["realisation"] = [part.realisation] * len(cols["peak_load_N"])
    rows = {c: np.asarray(cols[c]).tolist() for c in COLUMNS}
    windows, refined = [], {}
    for w in res.settings["punches"]:
        windows.append({"realisation": part.realisation, "punch_diameter_m": d,
                        "placement": w["placement"], "window_px": w["window"][2:],
                        "n_punch_pixels": w["n_punch_pixels"], "disk_Rt_m": w["disk_Rt_m"]})  # fmt: skip
        for f, shape in w["refined_windows"].items():
            old = refined.get(str(int(f)), [0, 0])
            refined[str(int(f))] = shape if shape[0] * shape[1] > old[0] * old[1] else old
    s = dict(res.settings["seconds"])
    return jsonable({
        "params": part_params(p, part), "rows": rows, "windows": windows,
        "per_punch": {"punch_diameter_m": d, "refine_max": refine_of(p, d), "seconds": s,
                      "refined_windows": refined},
        "seconds": {**s, "surface_s": gen, "part_s": time.perf_counter() - t0},
        "device": res.settings["device"],
        "reused_elastic_cycles": int(res.settings.get("reused_elastic_cycles", 0)),
    })  # fmt: skip


def load_part(path: Path, params: dict[str, Any]) -> dict[str, Any] | None:
    """The stored part when its parameters are ``params``; None when absent or other (a part
    of other parameters is recomputed: the piece it belongs to is what the store checks)."""
    if not path.exists():
        return None
    try:
        rec = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError):
        return None
    return rec if rec.get("params") == params else None


def compute_part(p: Profile, part: Part, store: str, device=None,
                 reuse: dict[str, list] | None = None) -> dict[str, Any]:  # fmt: skip
    """Run ``part`` unless its file is stored, write it atomically, return its record.

    The task of a Dask worker (and of the in-process run): a part whose file exists with the
    same parameters (written by a worker that died before its result arrived) is read, not
    solved again.

    Parameters
    ----------
    p : Profile
        The profile.
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
    params = part_params(p, part)
    rec = load_part(path, params)
    if rec is None:
        rec = run_part(p, part, device=device, reuse=reuse)
        write_atomic(path, json.dumps(rec, indent=None, allow_nan=False) + "\n")
    return rec


def merge_parts(p: Profile, piece: tuple[str, str, float, str | None], recs: dict[Part, dict]) -> dict[str, Any]:
    """The piece record of a piece's parts (the layout of an undivided piece).

    Parameters
    ----------
    p : Profile
        The profile.
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
    order = parts_of(p, s, design, h, face)
    rows: dict[str, list] = {c: [] for c in COLUMNS}
    windows, per_punch, sec, gen = [], [], {}, {}
    devices, n_reused = set(), 0
    for k in range(len(p.indentation_punches)):
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
    return jsonable({
        "params": piece_params(p, s, design, h, face_of(p, face)),
        "rows": rows, "windows": windows,
        "seconds": {**sec, "surface_s": sum(gen.values())},
        "per_punch": per_punch,
        "device": next(iter(devices)) if len(devices) == 1 else sorted(devices),
        "n_not_converged": int(sum(not c for c in rows["converged"])),
        "reused_elastic_cycles": n_reused, "n_parts": len(order),
    })  # fmt: skip
