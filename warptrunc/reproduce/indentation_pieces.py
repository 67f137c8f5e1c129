# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One piece of the ``indentation`` stage: a surface × design × hardness H, its parameters, its
file (its run: one :func:`warptrunc.indent` call per punch and realisation, the parts of
:mod:`.indentation_parts`).

Two designs (issue 38, item 7): ``sweep`` — one realisation (the first of
``Profile.indentation_seeds``) × ``indentation_placements`` placements per punch, for every H of
``indentation_hardness``; ``stats`` — every realisation of ``indentation_seeds`` ×
``indentation_stats_placements`` placements per punch, for the models of
``indentation_stats``. A third, ``face``, repeats the sweep's indents of
``indentation_face_surface`` at ``indentation_face_hardness`` with a tilted or a rough punch
face (:func:`face_variants`). Punch k draws its placements with seed ``indentation_seed + k``
(one :func:`~warptrunc.indent.indent` call per punch, so that each punch has its own
refinement: ``indentation_refine_punches``).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from .._support.results import jsonable
from .profiles import Profile
from .store import StageConflict

__all__ = ["COLUMNS", "DESIGNS", "SUBDIR", "face_variants", "model_name", "piece_params"]

SUBDIR = "indentation"
"""Piece store of the stage, inside the reproduction folder."""
DESIGNS = ("sweep", "stats")
"""The two designs of the stage's main pieces: the hardness sweep and the statistics (the
``face`` pieces are summarised apart)."""
COLUMNS = (
    "punch_diameter_m", "placement", "realisation", "peak_load_N", "F_over_EA", "displacement_m",
    "contact_area_m2", "plastic_area_m2", "n_contact", "unloading_stiffness_N_per_m",
    "partial_unloading_stiffness_N_per_m", "E_c_over_E", "E_c_partial_over_E", "converged",
    "overlap_fraction", "n_punch_pixels", "truncation_depth_m", "truncation_contact_area_m2",
    "truncation_stiffness_N_per_m", "truncation_E_c_over_E", "centre_x_m", "centre_y_m",
    "max_pressure_Pa", "pixel_size_m", "resolution_change", "area_change", "resolved", "saturated",
    "in_fit",
)  # fmt: skip
"""Columns of :meth:`warptrunc.indent.IndentationResult.to_dict` kept in each piece."""


def model_name(hardness: float | None) -> str:
    """Model key of a hardness: ``elastic`` (inf or None) or ``elastic_plastic_<H in GPa>GPa``.

    Parameters
    ----------
    hardness : float or None
        H (Pa); inf or None = elastic.

    Returns
    -------
    str
        ``"elastic"``, ``"elastic_plastic_0.5GPa"``, ``"elastic_plastic_2GPa"``, …
    """
    if hardness is None or math.isinf(hardness):
        return "elastic"
    return f"elastic_plastic_{hardness / 1e9:g}GPa"


def material(hardness: float):
    """The stage's material at hardness H: :func:`warptrunc.indent.default_material`'s elastic
    constants (assumptions, ``docs/guide/indentation.md``) against diamond."""
    from ..indent import default_material

    return default_material(hardness=hardness)


def spec(p: Profile, name: str, seed: int | None = None):
    """The Table 1 preset ``name`` on the stage's map (and phase seed)."""
    from ..presets import TABLE1

    s = TABLE1[name].replace(n=p.indentation_n, L=p.indentation_L)
    return s if seed is None else s.replace(seed=int(seed))


def face_variants(p: Profile) -> list[tuple[str, dict[str, float]]]:
    """The punch faces of the ``face`` pieces: (label, :func:`warptrunc.indent` keywords).

    Parameters
    ----------
    p : Profile
        The profile (``indentation_face_tilts_deg``, ``indentation_face_roughness``).

    Returns
    -------
    list of (str, dict)
        ``("tilt 0.1°", {"punch_tilt_deg": 0.1})``, …, then ``("rough 0.05 µm rms",
        {"punch_roughness": 5e-08})``; empty without a face surface.
    """
    if p.indentation_face_surface is None:
        return []
    out = [(f"tilt {t:g}°", {"tilt_deg": float(t)}) for t in p.indentation_face_tilts_deg if t > 0]
    if p.indentation_face_roughness > 0:
        out.append((f"rough {p.indentation_face_roughness * 1e6:g} µm rms",
                    {"roughness": float(p.indentation_face_roughness)}))  # fmt: skip
    return out


def _slug(label: str) -> str:
    return label.replace(" µm rms", "um").replace("°", "deg").replace(" ", "")


def _face_kw(p: Profile, face: dict[str, float], k: int, d: float) -> dict[str, Any]:
    """The face keywords of punch k: its own face seed and, for a rough face, the shortest
    wavelength 2 map pixels or, when the punch's face grid cannot hold that, the shortest it can."""
    from ..indent.face import MAX_FACE_GRID

    kw: dict[str, Any] = {**face, "seed": k}
    if face.get("roughness", 0) > 0:
        dx = p.indentation_L / p.indentation_n
        kw["cutoff_short"] = max(2 * dx, 2 * d / (MAX_FACE_GRID / 2 - 1) * (1 + 1e-6))
    return kw


def design_of(p: Profile, design: str) -> tuple[tuple[int, ...], int]:
    """(phase seeds, placements per punch) of a design (``face``: the sweep's)."""
    if design in ("sweep", "face"):
        return (p.indentation_seeds[0],), p.indentation_placements
    return tuple(p.indentation_seeds), p.indentation_stats_placements


def refine_of(p: Profile, d: float) -> int:
    """The refinement of punch ``d``'s cells (1: none)."""
    sel = p.indentation_refine_punches
    if sel is None or any(math.isclose(d, x, rel_tol=1e-9) for x in sel):
        return p.indentation_refine_max
    return 1


def piece_params(p: Profile, surface: str, design: str, hardness: float,
                 face: tuple[str, dict[str, float]] | None = None) -> dict[str, Any]:  # fmt: skip
    """The parameters that identify one stored piece.

    Parameters
    ----------
    p : Profile
        The profile.
    surface : str
        Table 1 name.
    design : str
        ``"sweep"`` or ``"stats"``.
    hardness : float
        H (Pa); inf = elastic.
    face : (str, dict), optional
        A punch face of :func:`face_variants` (``face`` pieces).

    Returns
    -------
    dict
        JSON-able: surface and its preset, the design's seeds and placements, H and the
        material, punches, loads, placement seed, solver settings, the refinement per punch
        and the face (each punch's keywords).
    """
    seeds, placements = design_of(p, design)
    refine = {"refine_max": {f"{d:g}": refine_of(p, d) for d in p.indentation_punches},
              "resolution_tol": p.indentation_resolution_tol,
              "min_contact_pixels": p.indentation_min_contact_pixels}  # fmt: skip
    return jsonable({
        "surface": surface, "design": design, "spec": spec(p, surface).to_dict(),
        "seeds": list(seeds), "placements": placements, "hardness_Pa": hardness,
        "material": material(hardness).to_dict(), "punches_m": list(p.indentation_punches),
        "loads_N": list(p.indentation_loads), "placement_seed": p.indentation_seed,
        "placement_seeds": "indentation_seed + punch index", "unload_fraction":
        p.indentation_unload_fraction, "dtype": p.indentation_dtype, "maxiter": p.indentation_maxiter,
        "truncation_increments": p.indentation_increments, "refinement": refine,
        **({} if face is None else {"face": {"label": face[0], "per_punch": [
            _face_kw(p, face[1], k, d) for k, d in enumerate(p.indentation_punches)]}}),
    })  # fmt: skip


def piece_file(store: Path, surface: str, design: str, hardness: float, face: str | None = None) -> Path:
    """``<store>/<surface>__<design>__<model>.json`` (a face piece: ``__face__<face>__``)."""
    tag = design if face is None else f"{design}__{_slug(face)}"
    return store / f"{surface}__{tag}__{model_name(hardness)}.json"


def load_piece(path: Path, params: dict[str, Any], overwrite: bool) -> dict[str, Any] | None:
    """The stored piece when its parameters are ``params``; None when absent (or replaced)."""
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


def _reuse_rows(rows: dict[str, list] | None, d: float) -> dict[str, list] | None:
    """The elastic piece's rows of punch ``d`` (for :func:`warptrunc.indent`'s ``reuse``)."""
    if rows is None or "max_pressure_Pa" not in rows:
        return None
    idx = [i for i, x in enumerate(rows["punch_diameter_m"]) if math.isclose(x, d, rel_tol=1e-9)]
    return {c: [v[i] for i in idx] for c, v in rows.items()}
