# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""``run_sweep``: the grid, the store and an engine put together."""

from __future__ import annotations

import sys
from contextlib import ExitStack
from dataclasses import replace
from pathlib import Path
from typing import Any

from .._support.docs import fill_doc
from .._support.outputs import store_rollback
from .grid import GRID_DOCS, SweepGrid
from .options import SweepExecution, SweepOptions
from .store import Store, store_lock

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
    store: str | Path | None = None,
    *,
    options: SweepOptions | None = None,
    execution: SweepExecution | None = None,
    overwrite: bool = False,
    retry_failed: bool = False,
    progress: bool = True,
    device: Any = None,
):
    """Run every case of ``grid`` (or those the store at ``store`` still lacks).

    Parameters
    ----------
    grid : SweepGrid, dict or path
        D_in × δ × seeds (and optional extra axes: sweepable fields of WMSpec or Material that
        are options of the sweep, e.g. ``M``, ``gamma``, ``Wr``, ``E``); a dict {"D": [...],
        "delta": [...], "seeds": "0-4", "axes": {"M": [8, 10]}} or a TOML file with those
        keys.
    store : path, optional
        Store folder (``sweep.json``, ``curves/part-*.parquet``, ``cases.parquet``; see
        :mod:`warptrunc.sweep.store`). An existing store made by the same grid and options is
        resumed; another one is refused (ValueError) unless ``overwrite``. ``None`` keeps the
        results in memory only.
    options : SweepOptions, optional
        What every case computes (as ``warptrunc analyze``: generation, truncation, material,
        fit ranges; the sweep's own relative fit ranges, fractal dimensions and elastic
        solves). Default ``SweepOptions()``.
    execution : SweepExecution, optional
        Where and how the cases run: in this process (the default, ``SweepExecution()``), on a
        local Dask cluster (``workers``) or an existing one (``scheduler``), the shard sizes and
        the devices of each elastic solve (``devices``). With a cluster, the workers write
        their parts into ``store`` themselves: it must be on a filesystem that every worker
        shares with this process.
    overwrite : bool
        Replace an existing store's results.
    retry_failed : bool
        Run again the cases that the store records as failed.
    progress : bool
        Report the cases on stderr (every engine): a bar on a terminal, else a line every
        few seconds.
    device : str, optional
        Warp device for every case; default ``$WARPTRUNC_DEVICE``, else CUDA when present
        (per-worker pinning with ``workers``).

    Returns
    -------
    pandas.DataFrame
        One row per case × fit range, in grid order; columns ``store.CASE_COLUMNS``.
        A case that raised has its message in ``error`` and NaN results.

    Raises
    ------
    ValueError
        A store made by another grid or options (without ``overwrite``), a grid axis that the
        sweep cannot vary, or ``execution.devices`` without ``options.bem_fractions`` (nothing
        to spread).

    Examples
    --------
    >>> from warptrunc.sweep import SweepExecution, SweepGrid, SweepOptions, run_sweep
    >>> df = run_sweep(SweepGrid([2.1, 2.5], [0.01], "0-4"), "runs/g2",
    ...                options=SweepOptions(n=1024, min_pixels=(1, 100)),
    ...                execution=SweepExecution(workers="auto"))  # doctest: +SKIP
    """
    grid = as_grid(grid)
    opts = SweepOptions() if options is None else options
    ex = SweepExecution() if execution is None else execution
    out = store
    if ex.spread and not opts.bem_fractions:
        raise ValueError(
            f"devices={ex.devices!r} spreads the elastic solves of bem_fractions, "
            "and none are asked for"
        )
    group = 1
    if ex.spread and ex.distributed:
        from .groups import group_size

        group = group_size(ex.devices)  # each worker takes this many devices
    cases = grid.cases(opts)  # checks that the sweep can vary the grid's extra axes
    guard = ExitStack()  # a failed run on a new store that finished nothing leaves nothing
    st: Store | None = None
    if out is not None:

        def keep() -> bool:  # finished cases (or parts a worker wrote) are kept for a rerun
            return (st is not None and bool(st.done)) or any(
                Path(out).glob("curves/part-*.parquet")
            )

        guard.enter_context(store_rollback(out, keep=keep))
    with guard:
        held = ExitStack()  # one writer per store: a second sweep on ``out`` is refused at once
        if out is not None:
            held.enter_context(store_lock(out, notify=lambda m: print(m, file=sys.stderr)))
        try:
            st = Store(
                out, grid, opts, overwrite=overwrite, retry_failed=retry_failed, device=device
            )
        except BaseException:
            held.close()
            raise
        todo = [c for c in cases if c.case_id not in st.done]
        groups: dict[tuple, list] = {}  # the cases of each value of the extra axes share options
        for c in todo:
            groups.setdefault(c.params, []).append(c)
        try:
            run = ex
            if todo and ex.distributed:
                # one cluster for every group: its start (and the workers' kernel loads) once
                client = held.enter_context(
                    _open_client(ex, device, progress, bool(opts.bem_fractions), group)
                )[0]
                run = replace(ex, workers=None, scheduler=client)
            left = len(todo)
            for params, part in groups.items():
                left -= len(part)
                _run_group(
                    part,
                    opts.with_axes(dict(params)),
                    st,
                    run,
                    total=len(grid) - left,
                    progress=progress,
                    device=device,
                )
            st.remove_temporaries()  # of workers killed mid-write; their cases ran again
        finally:
            try:
                st.flush()
            finally:
                held.close()
    return st.frame()


def _open_client(ex: SweepExecution, device, progress, warm_contact, group):
    """:func:`warptrunc.sweep.cluster.open_client` of ``ex``, with a clear message without Dask."""
    try:
        from .cluster import open_client
    except ImportError as exc:
        raise ImportError(
            f"workers/scheduler need dask.distributed, a dependency of warptrunc that this "
            f'environment lacks ({exc.name} is missing): pip install "dask[distributed]"'
        ) from None
    return open_client(ex.workers, ex.scheduler, device, progress, warm_contact, group)


def _run_group(todo, opts, store, ex: SweepExecution, *, total, progress, device) -> None:
    """Run cases that share ``opts`` on the engine of ``ex``."""
    if todo and ex.distributed:
        from .cluster import run_dask

        run_dask(todo, opts, store, execution=ex, total=total, progress=progress, device=device)
    elif todo:
        from .engines import run_inprocess

        run_inprocess(
            todo, opts, store.add_many, execution=ex, total=total, progress=progress, device=device
        )
