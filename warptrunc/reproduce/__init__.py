# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Reproduce the paper in one call: :func:`reproduce` (CLI: ``warptrunc reproduce``).

Stages (Fig. 2 single asperity, Fig. 5 convergence, Table 1 calibration, Figs. 7–8/Table 2
islands, Table 3 groups 1 and 2 with Figs. 9–10, the elastic BEM cross-check, the indentation
experiment of Fig. 6 in silico, :mod:`.indentation`) are computed by :mod:`.study` at the sizes
of a :mod:`.profiles` profile, stored and reused by :mod:`.store`, summarised by
:mod:`.analysis` and written as ``report.md`` (:mod:`.report`), ``results.json`` and PNG
figures (:mod:`.figures`).
"""

from __future__ import annotations

import contextlib
import json
import time
from pathlib import Path
from typing import Any

from .._support.device import resolve_device
from .._support.outputs import jsonable, staged_outputs, store_rollback
from .._support.provenance import provenance
from .profiles import PROFILES, Profile, get_profile
from .store import StageConflict, StageStore

__all__ = ["PROFILES", "Profile", "StageConflict", "get_profile", "reproduce"]


def reproduce(
    profile: str | Profile = "quick",
    out: str | Path = "reproduction",
    *,
    stages: str | tuple[str, ...] | None = None,
    overwrite: bool = False,
    time_budget: float | None = None,
    commit: str | None = None,
    device=None,
    workers: int | str | None = None,
    scheduler: Any = None,
) -> dict[str, Any]:
    """Run the study at ``profile`` into ``out``; returns the content of ``results.json``.

    Finished stages in ``out/stages`` are reused when their parameters match; a stage stored
    with other parameters raises :class:`StageConflict` unless ``overwrite``.

    Parameters
    ----------
    profile : str or Profile
        Sizes of the run: ``"tiny"``, ``"quick"``, ``"paper"`` or a :class:`Profile`.
    out : str or Path
        Output folder (created): ``stages/``, the figures, ``results.json`` and ``report.md``.
    stages : str or sequence of str, optional
        Compute only these stages (names of :data:`~warptrunc.reproduce.study.STAGES`, or one
        comma-separated string; a stage's inputs are added). The others are read from
        ``out/stages`` when stored with the same parameters and left out of the report
        otherwise. Default: every stage.
    overwrite : bool
        Recompute stages stored with other parameters instead of raising.
    time_budget : float, optional
        Seconds from the start after which the ``indentation`` stage starts no new piece
        (its pieces are stored as they finish; a rerun continues). The report then says the
        stage is incomplete. Default: no limit.
    commit : str, optional
        Commit recorded in the report; default ``$WARPTRUNC_GIT_COMMIT``, else ``git rev-parse
        HEAD`` of the package's checkout, else "unknown".
    device : str, optional
        Warp device.
    workers : int or "auto", optional
        Run the ``indentation`` stage's parts (one punch × one realisation of a piece each) and
        the ``elastic`` stage's maps on a local Dask cluster of this many worker processes, one per GPU (``"auto"``: one per
        visible GPU; :func:`warptrunc.sweep.cluster.open_client`). The other stages run in
        this process. The stored result is the one an in-process run stores. Default: every
        stage in this process.
    scheduler : str or distributed.Client, optional
        An existing Dask scheduler (address) or client for the same tasks; its workers must
        see ``out`` (a shared filesystem) and be pinned one per GPU.

    Returns
    -------
    dict of str to Any
        ``{"meta": ..., "analysis": ..., "stages": ...}``, as written to ``results.json``;
        ``meta`` holds the equivalent ``warptrunc reproduce`` command (``command``) and the
        :func:`~warptrunc._support.provenance.provenance` of the run (its command line among
        it).

    Raises
    ------
    StageConflict
        If a stored stage has other parameters and ``overwrite`` is False.
    ValueError
        If ``profile`` names no profile, ``stages`` names no stage or ``time_budget`` ≤ 0.
    """
    # the study stack (sweeps, calibration, figures) loads when a study runs, not with the
    # package: `warptrunc --help` reads the profiles only
    from .analysis import analyse
    from .study import run_study, select_stages

    p = get_profile(profile) if isinstance(profile, str) else profile
    selected = select_stages(stages)
    if time_budget is not None and not time_budget > 0:
        raise ValueError(f"time_budget must be > 0 s, got {time_budget!r}")
    out = Path(out)
    store: StageStore | None = None

    # a run that stored nothing leaves nothing behind; finished stages and sweep parts are kept
    # for a rerun
    def keep() -> bool:
        return (store is not None and bool(store.computed)) or any(out.rglob("*.parquet"))

    with store_rollback(out, keep=keep):
        out.mkdir(parents=True, exist_ok=True)
        dev = resolve_device(device)
        store = StageStore(out, overwrite=overwrite)
        t0 = time.perf_counter()
        deadline = None if time_budget is None else t0 + float(time_budget)
        with _cluster(workers, scheduler, dev) as (client, task_device):
            study = run_study(
                p,
                store,
                device=dev,
                stages=stages,
                deadline=deadline,
                client=client,
                task_device=task_device,
            )
        res = study["results"]
        ana = analyse(res)
        if all(g in res and res[g].get("store") for g in ("group1", "group2")):  # re-fit
            from .fitrange import fit_range_map

            try:
                ana["fit_range_map"] = fit_range_map(
                    out / res["group1"]["store"], out / res["group2"]["store"]
                )
            except FileNotFoundError as exc:  # stages reused from a folder without the stores
                ana["fit_range_map_missing"] = str(exc)
        with staged_outputs() as st:  # the figures, results.json and report.md, or none of them
            stage = st.folder(out)
            doc = _final_outputs(
                stage,
                p,
                res,
                ana,
                study,
                store,
                dev,
                t0,
                out,
                commit,
                None if stages is None else selected,
            )
    return jsonable(doc)


@contextlib.contextmanager
def _cluster(workers, scheduler, dev):
    """(client, the tasks' device): none without workers or scheduler; on a local cluster of a
    CUDA machine each worker's pinned GPU (the tasks' device None), on the CPU ``"cpu"``."""
    if workers is None and scheduler is None:
        yield None, None
        return
    from ..sweep.cluster import open_client

    task_device = "cpu" if dev.is_cpu else None
    with open_client(workers, scheduler, task_device, warm_contact=True) as (
        client,
        _cluster,
        _own,
    ):
        yield client, task_device


def _final_outputs(stage, p, res, ana, study, store, dev, t0, out, commit, selected):
    """Write the figures, results.json and report.md into ``stage``; returns the document."""
    from .figures import figures
    from .report import markdown

    names = figures(res, ana, stage, device=dev)
    meta = {
        "profile": p.to_dict(),
        "wall_s": time.perf_counter() - t0,
        "stage_wall_s": study["wall_s"],
        "stage_seconds": {k: store.seconds(k) for k in res},
        "reused": store.reused,
        "computed": store.computed,
        "command": f"warptrunc reproduce --profile {p.name} --out {out}"
        + ("" if selected is None else f" --stages {','.join(selected)}"),
        "figures": names,
        "provenance": provenance(dev, commit=commit),
    }
    if selected is not None:
        meta["stages_selected"] = list(selected)
    if study["skipped"]:
        meta["stages_skipped"] = study["skipped"]
    if study["incomplete"]:
        meta["incomplete"] = study["incomplete"]
    doc = {"meta": meta, "analysis": ana, "stages": res}
    (stage / "results.json").write_text(json.dumps(jsonable(doc), indent=1, allow_nan=False) + "\n")
    (stage / "report.md").write_text(markdown(meta, res, ana, names))
    return doc
