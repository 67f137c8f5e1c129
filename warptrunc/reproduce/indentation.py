# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stage ``indentation`` of ``warptrunc reproduce``: the paper's experiment (§ 4.1, Fig. 6) in silico.

The four Table 1 surfaces (:data:`warptrunc.presets.TABLE1`) at ``Profile.indentation_n``
pixels over ``indentation_L``, the three flat punches and the paper's load / partial-unload
cycles (:func:`warptrunc.indent`). The paper states no hardness, so H is a question
(issue 38, item 4): a **sweep** over ``Profile.indentation_hardness`` (and H = ∞) on one
realisation × ``indentation_placements`` placements per punch, then **statistics**
(``indentation_seeds`` × ``indentation_stats_placements`` indents per punch) for H = ∞ and, per
surface, the H of the sweep whose depth at the largest load best matches the paper's ≈ 5 µm
(:func:`~warptrunc.reproduce.indentation_rules.depth_match`; none when no H of the sweep
reaches ``indentation_depth_band``). Then the sweep's indents of ``indentation_face_surface``
(Ps) again with tilted and rough punch faces (§ 4.2). Eq. 2 truncation runs on the same punch
disks. Every E_c/E is normalised by the Young's modulus E (Fig. 6).

The work is stored in pieces, one JSON file per surface × design × H under
``OUT/indentation/`` (written atomically, :mod:`.indentation_pieces`), so an interrupted stage
(a GPU call that hit its time limit, or ``time_budget``) continues where it stopped when
``warptrunc reproduce`` is run again; the stage file ``stages/indentation.json`` holds the
summary, recomputed from the pieces (:mod:`.indentation_summary`). One more piece,
``resolution``, solves the smallest punch at the map centre on the same surface sampled at the
profile's pixel size and at half of it (same phases and cut-off W_c).

The section of ``report.md`` and its figures are in :mod:`.indentation_report`; the numbers
come from :func:`~warptrunc.reproduce.indentation_analysis.analyse_indentation`.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from typing import Any

from .._support.docs import fill_doc
from .._support.results import jsonable, write_atomic
from .indentation_analysis import (  # noqa: F401 - the analysis's names stay importable here
    _STAGE_DOCS,
    GOOD,
    analyse_indentation,
    cells,
    tracking,
)
from .indentation_parts import parts_of
from .indentation_pieces import SUBDIR, face_variants, load_piece, material, model_name, spec
from .indentation_schedule import Plan, run_in_process, stats_hardness
from .indentation_schedule import sweep_order as _sweep_order
from .indentation_summary import summary_from_pieces
from .profiles import Profile

__all__ = [
    "StageIncomplete",
    "model_name",
    "stage_indentation",
    "stage_params",
    "stats_hardness",
    "summary_from_pieces",
]

RESOLUTION_SURFACE = "GB300s"
"""Surface of the resolution check (the paper's Fig. 7 surface); the first one if absent."""
STATS_MODELS = ("elastic", "depth-match")
"""What ``Profile.indentation_stats`` may name."""


class StageIncomplete(RuntimeError):
    """The stage stopped before its last piece (time budget); a rerun continues it."""


def _check(p: Profile) -> None:
    """One-line errors naming the profile field, its value and what is allowed."""
    bad = [m for m in p.indentation_stats if m not in STATS_MODELS]
    if bad:
        raise ValueError(f"indentation_stats must name models among {STATS_MODELS}, got {bad!r}")
    if not p.indentation_seeds:
        raise ValueError("indentation_seeds must hold at least one phase seed, got ()")
    if not p.indentation_hardness or not all(h > 0 for h in p.indentation_hardness):
        raise ValueError(
            f"indentation_hardness must be H values > 0 Pa (inf = elastic), got {p.indentation_hardness!r}"
        )
    lo, hi = p.indentation_depth_band
    if not 0 < lo <= p.indentation_depth_target <= hi:
        raise ValueError(
            f"indentation_depth_band must bracket indentation_depth_target, 0 < low ≤ target ≤ high "
            f"(m), got {p.indentation_depth_band!r} around {p.indentation_depth_target!r}"
        )
    if p.indentation_face_surface is not None and face_variants(p):
        if p.indentation_face_surface not in p.indentation_surfaces:
            raise ValueError(
                f"indentation_face_surface must be one of indentation_surfaces "
                f"{p.indentation_surfaces!r} or None, got {p.indentation_face_surface!r}"
            )
        if p.indentation_face_hardness not in p.indentation_hardness:
            raise ValueError(
                f"indentation_face_hardness must be one of indentation_hardness "
                f"{p.indentation_hardness!r} (Pa), got {p.indentation_face_hardness!r}"
            )
    for name in ("indentation_placements", "indentation_stats_placements"):
        if getattr(p, name) < 1:
            raise ValueError(f"{name} must be ≥ 1 placement, got {getattr(p, name)!r}")


@fill_doc(_STAGE_DOCS)
def stage_params(p: Profile) -> dict[str, Any]:
    """The parameters that identify a stored ``indentation`` stage.

    {indentation_profile}

    {stage_params_returns}
    """
    m = material(math.inf)
    return jsonable({
        "surfaces": {s: spec(p, s).to_dict() for s in p.indentation_surfaces},
        "punches_m": list(p.indentation_punches), "loads_N": list(p.indentation_loads),
        "placements": p.indentation_placements, "seed": p.indentation_seed,
        "hardness_Pa": _sweep_order(p), "seeds": list(p.indentation_seeds),
        "stats_placements": p.indentation_stats_placements, "stats": list(p.indentation_stats),
        "depth_target_m": p.indentation_depth_target, "depth_band_m": list(p.indentation_depth_band),
        "unload_fraction": p.indentation_unload_fraction, "dtype": p.indentation_dtype,
        "maxiter": p.indentation_maxiter, "truncation_increments": p.indentation_increments,
        "refine": p.indentation_refine, "refine_max": p.indentation_refine_max,
        "refine_punches_m": p.indentation_refine_punches,
        "resolution_tol": p.indentation_resolution_tol,
        "min_contact_pixels": p.indentation_min_contact_pixels, "material": m.to_dict(),
    })  # fmt: skip


@fill_doc(_STAGE_DOCS)
def stage_indentation(p: Profile, out: str | Path, device, *, overwrite: bool = False,
                      deadline: float | None = None, progress: bool = True,
                      client=None) -> dict[str, Any]:  # fmt: skip
    """Run (or continue) the pieces under ``out/indentation`` and summarise them.

    {indentation_profile}
    out : str or Path
        Reproduction folder; the pieces go to ``out/indentation``.
    device : str, optional
        Warp device (with ``client``: the tasks' device, None for each worker's pinned one).
    overwrite : bool
        Recompute pieces stored with other parameters (else :class:`StageConflict`).
    deadline : float, optional
        ``time.perf_counter()`` value after which no new part is started; the stage then
        raises :class:`StageIncomplete` (the parts and pieces done are stored).
    progress : bool
        Progress bar over the parts (stderr).
    client : distributed.Client, optional
        Run the parts as tasks of this Dask cluster, one in flight per worker
        (:func:`~.indentation_schedule.run_on_cluster`); default in this process.

    Returns
    -------
    dict
        :func:`summary_from_pieces` of the stored pieces.

    Raises
    ------
    StageIncomplete
        The deadline passed before the last part.
    StageConflict
        A piece stored with other parameters and ``overwrite`` off.
    ValueError
        A profile field out of range (the message names it).
    """
    from .._support.progress import progress_bar

    _check(p)
    store = Path(out) / SUBDIR
    store.mkdir(parents=True, exist_ok=True)
    plan = Plan(p, store, overwrite)
    ref = _resolution_params(p)
    rpath = store / "resolution.json"
    res_rec = load_piece(rpath, ref, overwrite) if ref is not None else None
    n_parts = len(parts_of(p, p.indentation_surfaces[0], "sweep", math.inf))
    n_plan = (len(p.indentation_surfaces) * (len(plan.sweep) + len(p.indentation_stats))
              + len(face_variants(p)))  # fmt: skip
    bar = progress_bar(total=None, desc="indentation parts", unit="part", enabled=progress)

    def incomplete(what: str) -> StageIncomplete:
        have, _ = plan.n_pieces()
        return StageIncomplete(
            f"stage 'indentation' stopped at its time budget before {what}: {have} of "
            f"{n_plan} planned pieces ({n_parts} parts each for the sweep) stored in {store} "
            f"(resolution check {'stored' if res_rec is not None else 'not run'}); run the same "
            "command again to continue"
        )

    def stop(what: str) -> None:
        if deadline is not None and time.perf_counter() > deadline:
            raise incomplete(what)

    with bar:
        res_future = None
        if client is not None:
            from .indentation_schedule import run_on_cluster

            if ref is not None and res_rec is None:
                res_future = client.submit(_run_resolution, p, ref, device, pure=False, priority=10)
            if not run_on_cluster(plan, client, device=device, deadline=deadline, bar=bar):
                if res_future is not None and res_future.done() and res_future.status == "finished":
                    write_atomic(rpath, json.dumps(res_future.result(), indent=None,
                                                   allow_nan=False) + "\n")  # fmt: skip
                raise incomplete("the next part")
        else:
            run_in_process(plan, device=device, stop=stop, bar=bar)
        if ref is not None and res_rec is None:
            if res_future is None:
                stop("the resolution check")
            res_rec = _run_resolution(p, ref, device) if res_future is None else res_future.result()
            write_atomic(rpath, json.dumps(res_rec, indent=None, allow_nan=False) + "\n")
            bar.update()
    return summary_from_pieces(p, plan.records(), res_rec)


# --- resolution check -------------------------------------------------------------------------


def _resolution_hardness(p: Profile) -> float | None:
    """The finite H of the sweep nearest (in log H) to warptrunc.indent's default, 1 GPa."""
    from ..indent import ALUMINIUM_HARDNESS

    finite = [h for h in p.indentation_hardness if math.isfinite(h)]
    return min(finite, key=lambda h: abs(math.log(h / ALUMINIUM_HARDNESS))) if finite else None


def _resolution_params(p: Profile) -> dict[str, Any] | None:
    if not p.indentation_refine:
        return None
    s = RESOLUTION_SURFACE if RESOLUTION_SURFACE in p.indentation_surfaces else p.indentation_surfaces[0]
    h = _resolution_hardness(p)
    return jsonable({
        "surface": s, "spec": spec(p, s).to_dict(), "n_coarse": p.indentation_n,
        "n_fine": 2 * p.indentation_n, "punch_m": min(p.indentation_punches),
        "hardness_Pa": [None] + ([] if h is None else [h]), "placement": "map centre",
        "loads_N": list(p.indentation_loads), "unload_fraction": p.indentation_unload_fraction,
        "dtype": p.indentation_dtype, "maxiter": p.indentation_maxiter,
        "truncation_increments": p.indentation_increments,
    })  # fmt: skip


def _run_resolution(p: Profile, ref: dict[str, Any], device) -> dict[str, Any]:
    """The smallest punch at the map centre on the same surface at dx and dx/2."""
    from ..contact.settings import SolverSettings
    from ..indent import IndentProtocol, indent
    from ..wm import wm_surface

    sp = spec(p, ref["surface"])
    coarse = wm_surface(sp, device=device)
    # the same surface twice as finely: the coarse map's height scale (as a topothesy) and
    # cut-off, so that no term is added and none aliases
    fine_spec = sp.replace(n=ref["n_fine"], Rt=None, G=coarse.params["G_equivalent"],
                           Wc=coarse.params["Wc"])  # fmt: skip
    t0 = time.perf_counter()
    fine = wm_surface(fine_spec, device=device)
    out: dict[str, Any] = {"params": ref, "grids": {}, "fine_spec": fine_spec.to_dict()}
    for tag, surf in (("coarse", coarse), ("fine", fine)):
        g: dict[str, Any] = {"n": int(surf.heights.shape[0]), "dx_m": surf.dx, "Rt_m": surf.Rt}
        for h in ref["hardness_Pa"]:
            h = math.inf if h is None else h
            t1 = time.perf_counter()
            protocol = IndentProtocol(
                punch_diameters=(ref["punch_m"],), peak_loads=tuple(ref["loads_N"]),
                unload_fraction=ref["unload_fraction"], placements=None,
                truncation_increments=ref["truncation_increments"], refine_max=1,
                elastic=math.isinf(h),
            )  # fmt: skip
            r = indent(surf, protocol=protocol, material=material(h), device=device,
                       solver=SolverSettings(dtype=ref["dtype"], maxiter=ref["maxiter"]))
            cols = {**r.to_dict()}
            cols["n_contact"] = cols["n_contact_pixels"]
            g[model_name(h)] = {c: cols[c] for c in (
                "peak_load_N", "unloading_stiffness_N_per_m", "partial_unloading_stiffness_N_per_m",
                "contact_area_m2", "plastic_area_m2", "n_contact", "E_c_over_E", "converged",
                "truncation_E_c_over_E", "n_punch_pixels")}  # fmt: skip
            g[model_name(h)]["seconds"] = time.perf_counter() - t1
        out["grids"][tag] = g
    out["seconds"] = time.perf_counter() - t0
    return jsonable(out)
