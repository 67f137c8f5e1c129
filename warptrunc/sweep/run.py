# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""``run_sweep``: the grid, the store and an engine put together."""

from __future__ import annotations

import sys
from contextlib import ExitStack
from pathlib import Path
from typing import Any

from .._support.atomic import store_rollback
from .._support.docs import fill_doc
from .._support.validate import check_int, check_range
from .grid import GRID_DOCS, SweepGrid
from .lock import store_lock
from .options import SweepOptions
from .store import Store

__all__ = ["as_grid", "run_sweep"]


@fill_doc(GRID_DOCS)
def as_grid(grid: Any) -> SweepGrid:
    """A :class:`SweepGrid` from a grid, a dict {"D", "delta", "seeds"} or a TOML path.

    Parameters
    ----------
    grid : SweepGrid, dict or str or Path
        A grid (returned as is), its dict form (:meth:`SweepGrid.from_dict`) or a TOML file
        (:meth:`SweepGrid.from_toml`).

    {returns_grid}
        If ``grid`` is of another type, or the dict or file is invalid.
    """
    if isinstance(grid, SweepGrid):
        return grid
    if isinstance(grid, dict):
        return SweepGrid.from_dict(grid)
    if isinstance(grid, (str, Path)):
        return SweepGrid.from_toml(grid)
    raise ValueError(f"grid must be a SweepGrid, a dict or a TOML path, got {type(grid).__name__}")


def run_sweep(
    grid: Any,
    out: str | Path | None = None,
    *,
    workers: int | None = None,
    scheduler: Any = None,
    overwrite: bool = False,
    retry_failed: bool = False,
    shard_size: int | None = None,
    shard_seconds: float = 1.0,
    progress: bool = True,
    device: Any = None,
    devices: Any = None,
    **options: Any,
):
    """Run every case of ``grid`` (or those a store at ``out`` still lacks).

    Parameters
    ----------
    grid : SweepGrid, dict or path
        D_in × δ × seeds (and optional extra axes: sweepable fields of WMSpec or Material that
        are options of the sweep, e.g. ``M``, ``gamma``, ``Wr``, ``E``); a dict {"D": [...],
        "delta": [...], "seeds": "0-4", "axes": {"M": [8, 10]}} or a TOML file with those
        keys.
    out : path, optional
        Store folder (``sweep.json``, ``curves/part-*.parquet``, ``cases.parquet``; see
        :mod:`warptrunc.sweep.store`). An existing store made by the same grid and options is
        resumed (one of the previous layout is converted first); another one is refused
        (ValueError) unless ``overwrite``. ``None`` keeps the results in memory only.
    workers : int or "auto", optional
        Run on a local Dask cluster of this many worker processes (one thread each; ``"auto"``:
        one per visible CUDA device, 1 on a machine without one), started once for the whole
        run (:func:`warptrunc.sweep.cluster.open_client`); with CUDA devices and
        ``device=None``, worker i is pinned to ``cuda:{i mod n_gpus}`` (dask-cuda's
        LocalCUDACluster where installed). Default: in this process. The workers are spawned processes, so a script
        that passes ``workers`` needs the ``if __name__ == "__main__":`` guard.
    scheduler : str or distributed.Client, optional
        Use an existing Dask cluster (e.g. ``"tcp://host:8786"``, or a dask-jobqueue
        cluster's ``scheduler_address``) instead.
    overwrite : bool
        Replace an existing store's results.
    retry_failed : bool
        Run again the cases that the store records as failed.
    shard_size : int, optional
        With ``workers``/``scheduler``: cases per Dask task (one part of the store each).
        Default: adaptive, about ``shard_seconds`` of work per task (from the median case time
        so far, at most 4096 cases, and at least two tasks per worker for what remains).
        Workers write their parts into ``out`` themselves: it must be on a filesystem that
        every worker shares with this process.
    shard_seconds : float
        Work per part (s): the adaptive shard size with workers, and how much the in-process
        engine gathers before writing a part (0: whatever finished while the previous part was
        written). A hard kill loses at most about this much work per worker.
    progress : bool
        tqdm progress bar (every engine).
    device : str, optional
        Warp device for every case; default ``$WARPTRUNC_DEVICE``, else CUDA when present
        (per-worker pinning with ``workers``).
    devices : int, "auto" or list, optional
        Spread each elastic solve (``bem_fractions``) over several devices
        (``ContactSolver(..., devices=...)``; JAX); default None: ``device`` alone. With
        ``workers`` or ``scheduler``, a count G: each worker takes G devices of its own and
        spreads its solves over them (:mod:`warptrunc.sweep.groups`; ``workers="auto"`` is
        then the devices present divided by G). Without ``bem_fractions`` (nothing to spread):
        ValueError.
    **options
        Fields of :class:`SweepOptions` (as ``warptrunc analyze``): Wr (m), L (m), n, M,
        gamma, Wc (m), cutoff, increments, max_depth_fraction, max_depth (m), E (Pa), nu,
        E_flat (Pa), nu_flat, beta_prime, min_pixels (one or several fit ranges),
        depth_window (m), min_pixels_fraction, fractal_methods, bem_fractions (elastic
        solves at δ = f·R_t, wide columns ``F_bem_N_<f>``, ...: see
        :data:`warptrunc.sweep.read.BEM_QUANTITIES`).

    Returns
    -------
    pandas.DataFrame
        One row per case × fit range, in grid order; columns ``store.CASE_COLUMNS``.
        A case that raised has its message in ``error`` and NaN results.
    """
    grid = as_grid(grid)
    try:
        opts = SweepOptions(**options)
    except TypeError:
        from dataclasses import fields

        allowed = sorted(f.name for f in fields(SweepOptions))
        bad = sorted(set(options) - set(allowed))
        raise ValueError(f"unknown sweep options {bad}; allowed: {allowed}") from None
    if workers is not None and not (isinstance(workers, str) and workers.strip() == "auto"):
        workers = check_int("workers", workers, 1)
    if shard_size is not None:
        shard_size = check_int("shard_size", shard_size, 1)
    shard_seconds = check_range("shard_seconds", shard_seconds, 0, None, lo_open=False, unit="s")
    if workers is not None and scheduler is not None:
        raise ValueError("give workers (a local cluster) or scheduler (an existing one), not both")
    group = 1
    if devices not in (None, 1):
        if workers is not None or scheduler is not None:
            from .groups import group_size

            group = group_size(devices)  # each worker takes this many devices
        if not opts.bem_fractions:
            raise ValueError(f"devices={devices!r} spreads the elastic solves of bem_fractions, "
                             "and none are asked for")  # fmt: skip
    cases = grid.cases(opts)  # checks that the sweep can vary the grid's extra axes
    guard = ExitStack()  # a failed run on a new store that finished nothing leaves nothing
    store: Store | None = None
    if out is not None:

        def keep() -> bool:  # finished cases (or parts a worker wrote) are kept for a rerun
            return (store is not None and bool(store.done)) or any(
                Path(out).glob("curves/part-*.parquet")
            )

        guard.enter_context(store_rollback(out, keep=keep))
    with guard:
        held = ExitStack()  # one writer per store: a second sweep on ``out`` is refused at once
        notify = lambda m: print(m, file=sys.stderr)  # noqa: E731
        if out is not None:
            held.enter_context(store_lock(out, notify=notify))
        try:
            store = Store(out, grid, opts, overwrite=overwrite, retry_failed=retry_failed,
                          notify=notify)  # fmt: skip
        except BaseException:
            held.close()
            raise
        todo = [c for c in cases if c.case_id not in store.done]
        groups: dict[tuple, list] = {}  # the cases of each value of the extra axes share options
        for c in todo:
            groups.setdefault(c.params, []).append(c)
        try:
            if todo and (workers is not None or scheduler is not None):
                # one cluster for every group: its start (and the workers' kernel loads) once
                scheduler = held.enter_context(_open_client(
                    workers, scheduler, device, progress, bool(opts.bem_fractions), group))[0]
                workers = None
            left = len(todo)
            for params, group in groups.items():
                left -= len(group)
                _run_group(group, opts.with_axes(dict(params)), store, workers=workers,
                           scheduler=scheduler, device=device, total=len(grid) - left,
                           progress=progress, shard_size=shard_size,
                           shard_seconds=shard_seconds, devices=devices)  # fmt: skip
            store.remove_temporaries()  # of workers killed mid-write; their cases ran again
        finally:
            try:
                store.flush()
            finally:
                held.close()
    return store.frame()


def _open_client(workers, scheduler, device, progress, warm_contact=False, group=1):
    """:func:`warptrunc.sweep.cluster.open_client`, with a clear message without Dask."""
    try:
        from .cluster import open_client
    except ImportError as exc:
        raise ImportError(
            f"workers/scheduler need dask.distributed, a dependency of warptrunc that this "
            f'environment lacks ({exc.name} is missing): pip install "dask[distributed]"'
        ) from None
    return open_client(workers, scheduler, device, progress, warm_contact, group)


def _run_group(todo, opts, store, *, workers, scheduler, device, total, progress, shard_size,
               shard_seconds, devices=None) -> None:  # fmt: skip
    """Run cases that share ``opts`` on the chosen engine."""
    if todo and (workers is not None or scheduler is not None):
        from .cluster import run_dask

        run_dask(todo, opts, store, workers=workers, scheduler=scheduler, device=device,
                 total=total, progress=progress, shard_size=shard_size,
                 shard_seconds=shard_seconds, devices=devices)  # fmt: skip
    elif todo:
        from .engines import run_inprocess

        run_inprocess(todo, opts, store.add_many, device=device, total=total,
                      progress=progress, shard_seconds=shard_seconds, devices=devices)  # fmt: skip
