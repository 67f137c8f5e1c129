# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stage ``indentation`` of ``warptrunc reproduce``: the paper's experiment (§ 4.1, Fig. 6) in silico.

The four Table 1 surfaces (:data:`warptrunc.presets.TABLE1`) at ``n`` pixels over ``L``, the
three flat punches and the paper's load / partial-unload cycles (:func:`warptrunc.indent`), as
the profile's :class:`~.design.IndentationStage` says. The paper states no hardness, so H is a
question: a **sweep** over ``hardness`` (and H = ∞) on one realisation × ``protocol.placements``
placements per punch, then **statistics** (``seeds`` × ``stats_placements`` indents per punch)
for H = ∞ and, per surface, the H of the sweep whose depth at the largest load best matches the
paper's ≈ 5 µm (:func:`~.rules.depth_match`; none when no H of the sweep reaches
``depth_band``). Then the sweep's indents of ``face_surface`` (Ps) again with tilted and rough
punch faces (§ 4.2). Eq. 2 truncation runs on the same punch disks. Every E_c/E is normalised by
the Young's modulus E (Fig. 6).

The work is stored in pieces, one JSON file per surface × design × H under ``OUT/indentation/``
(written atomically, :mod:`.pieces`), so an interrupted stage (a GPU call that hit its time
limit, or ``time_budget``) continues where it stopped when ``warptrunc reproduce`` is run
again; the stage file ``stages/indentation.json`` holds the summary, recomputed from the pieces
(:mod:`.summary`). One more piece, ``resolution``, solves the smallest punch at the map centre on
the same surface sampled at the stage's pixel size and at half of it (same phases and cut-off
W_c).

The section of ``report.md`` and its figures are in :mod:`warptrunc.reproduce.indentation.report`; the numbers come from
:func:`~.analysis.analyse_indentation`.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from typing import Any

from ..._support.docs import fill_doc
from ..._support.outputs import jsonable, write_atomic
from .analysis import _STAGE_DOCS
from .design import IndentationStage, face_variants, material, model_name, spec, sweep_order
from .pieces import SUBDIR, load_piece, parts_of
from .schedule import Plan, run_in_process
from .summary import summary_from_pieces

__all__ = ["RESOLUTION_SURFACE", "StageIncomplete", "stage_indentation", "stage_params"]

RESOLUTION_SURFACE = "GB300s"
"""Surface of the resolution check (the paper's Fig. 7 surface); the first one if absent."""


class StageIncomplete(RuntimeError):
    """The stage stopped before its last piece (time budget); a rerun continues it."""


@fill_doc(_STAGE_DOCS)
def stage_params(st: IndentationStage) -> dict[str, Any]:
    """The parameters that identify a stored ``indentation`` stage.

    {indentation_stage}

    {stage_params_returns}
    """
    m = material(st, math.inf)
    pr = st.protocol
    return jsonable(
        {
            "surfaces": {s: spec(st, s).to_dict() for s in st.surfaces},
            "punches_m": list(pr.punch_diameters),
            "loads_N": list(pr.peak_loads),
            "placements": pr.placements,
            "seed": pr.placement_seed,
            "hardness_Pa": sweep_order(st),
            "seeds": list(st.seeds),
            "stats_placements": st.stats_placements,
            "stats": list(st.stats),
            "depth_target_m": st.depth_target,
            "depth_band_m": list(st.depth_band),
            "unload_fraction": pr.unload_fraction,
            "dtype": st.solver.dtype,
            "maxiter": st.solver.maxiter,
            "truncation_increments": pr.truncation_increments,
            "refine": st.refine,
            "refine_max": pr.refine_max,
            "refine_punches_m": None if st.refine_punches is None else list(st.refine_punches),
            "resolution_tol": pr.resolution_tol,
            "min_contact_pixels": pr.min_contact_pixels,
            "material": m.to_dict(),
        }
    )


@fill_doc(_STAGE_DOCS)
def stage_indentation(
    st: IndentationStage,
    out: str | Path,
    device,
    *,
    overwrite: bool = False,
    deadline: float | None = None,
    progress: bool = True,
    client=None,
) -> dict[str, Any]:
    """Run (or continue) the pieces under ``out/indentation`` and summarise them.

    {indentation_stage}
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
        (:func:`~.schedule.run_on_cluster`); default in this process.

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
    """
    from ..._support.progress import progress_bar

    store = Path(out) / SUBDIR
    store.mkdir(parents=True, exist_ok=True)
    plan = Plan(st, store, overwrite)
    ref = _resolution_params(st)
    rpath = store / "resolution.json"
    res_rec = load_piece(rpath, ref, overwrite) if ref is not None else None
    n_parts = len(parts_of(st, st.surfaces[0], "sweep", math.inf))
    n_plan = len(st.surfaces) * (len(plan.sweep) + len(st.stats)) + len(face_variants(st))
    plan.extra_parts = int(ref is not None and res_rec is None)
    bar = progress_bar(
        total=plan.parts_left(), desc="indentation parts", unit="part", enabled=progress
    )

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
            from .schedule import run_on_cluster

            if ref is not None and res_rec is None:
                res_future = client.submit(
                    _run_resolution, st, ref, device, pure=False, priority=10
                )
            if not run_on_cluster(plan, client, device=device, deadline=deadline, bar=bar):
                if res_future is not None and res_future.done() and res_future.status == "finished":
                    write_atomic(
                        rpath, json.dumps(res_future.result(), indent=None, allow_nan=False) + "\n"
                    )
                raise incomplete("the next part")
        else:
            run_in_process(plan, device=device, stop=stop, bar=bar)
        if ref is not None and res_rec is None:
            if res_future is None:
                stop("the resolution check")
            res_rec = (
                _run_resolution(st, ref, device) if res_future is None else res_future.result()
            )
            write_atomic(rpath, json.dumps(res_rec, indent=None, allow_nan=False) + "\n")
            plan.extra_parts = 0
            bar.update()
    return summary_from_pieces(st, plan.records(), res_rec)


# --- resolution check -------------------------------------------------------------------------


def _resolution_hardness(st: IndentationStage) -> float | None:
    """The finite H of the sweep nearest (in log H) to warptrunc.indent's default, 1 GPa."""
    from ...indent import ALUMINIUM_HARDNESS

    finite = [h for h in st.hardness if math.isfinite(h)]
    return min(finite, key=lambda h: abs(math.log(h / ALUMINIUM_HARDNESS))) if finite else None


def _resolution_params(st: IndentationStage) -> dict[str, Any] | None:
    if not st.refine:
        return None
    s = RESOLUTION_SURFACE if RESOLUTION_SURFACE in st.surfaces else st.surfaces[0]
    h = _resolution_hardness(st)
    pr = st.protocol
    return jsonable(
        {
            "surface": s,
            "spec": spec(st, s).to_dict(),
            "n_coarse": st.n,
            "n_fine": 2 * st.n,
            "punch_m": min(pr.punch_diameters),
            "hardness_Pa": [None] + ([] if h is None else [h]),
            "placement": "map centre",
            "loads_N": list(pr.peak_loads),
            "unload_fraction": pr.unload_fraction,
            "dtype": st.solver.dtype,
            "maxiter": st.solver.maxiter,
            "truncation_increments": pr.truncation_increments,
        }
    )


def _run_resolution(st: IndentationStage, ref: dict[str, Any], device) -> dict[str, Any]:
    """The smallest punch at the map centre on the same surface at dx and dx/2."""
    from ...contact.settings import SolverSettings
    from ...indent import IndentProtocol, indent
    from ...wm import wm_surface

    sp = spec(st, ref["surface"])
    coarse = wm_surface(sp, device=device)
    # the same surface twice as finely: the coarse map's height scale (as a topothesy) and
    # cut-off, so that no term is added and none aliases
    fine_spec = sp.replace(
        n=ref["n_fine"], Rt=None, G=coarse.params["G_equivalent"], Wc=coarse.params["Wc"]
    )
    t0 = time.perf_counter()
    fine = wm_surface(fine_spec, device=device)
    out: dict[str, Any] = {"params": ref, "grids": {}, "fine_spec": fine_spec.to_dict()}
    for tag, surf in (("coarse", coarse), ("fine", fine)):
        g: dict[str, Any] = {"n": int(surf.heights.shape[0]), "dx_m": surf.dx, "Rt_m": surf.Rt}
        for h in ref["hardness_Pa"]:
            h = math.inf if h is None else h
            t1 = time.perf_counter()
            protocol = IndentProtocol(
                punch_diameters=(ref["punch_m"],),
                peak_loads=tuple(ref["loads_N"]),
                unload_fraction=ref["unload_fraction"],
                placements=None,
                truncation_increments=ref["truncation_increments"],
                refine_max=1,
                elastic=math.isinf(h),
            )
            r = indent(
                surf,
                protocol=protocol,
                material=material(st, h),
                device=device,
                solver=SolverSettings(dtype=ref["dtype"], maxiter=ref["maxiter"]),
            )
            cols = {**r.to_dict()}
            cols["n_contact"] = cols["n_contact_pixels"]
            g[model_name(h)] = {
                c: cols[c]
                for c in (
                    "peak_load_N",
                    "unloading_stiffness_N_per_m",
                    "partial_unloading_stiffness_N_per_m",
                    "contact_area_m2",
                    "plastic_area_m2",
                    "n_contact",
                    "E_c_over_E",
                    "converged",
                    "truncation_E_c_over_E",
                    "n_punch_pixels",
                )
            }
            g[model_name(h)]["seconds"] = time.perf_counter() - t1
        out["grids"][tag] = g
    out["seconds"] = time.perf_counter() - t0
    return jsonable(out)
