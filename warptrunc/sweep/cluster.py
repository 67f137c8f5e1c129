# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The Dask engine: cases on a LocalCluster (one worker per GPU) or on an existing cluster.

Imported only when ``workers`` or ``scheduler`` is given (dask.distributed loads then). Cases
go out in shards (one task per shard, sized adaptively to about 1 s of work), so the task
overhead is amortised when a case takes milliseconds. Each worker writes its shard as one
part of the store (:func:`~warptrunc.sweep.engines.compute_shard`) and sends back only the
part's name and rows; the client records which parts exist and is the only writer of
``cases.parquet``.
"""

from __future__ import annotations

import logging
import math
import os
import statistics
import sys
import time
from typing import Any

from distributed import WorkerPlugin

from .._support.device import cuda_device_count
from .._support.progress import progress_bar
from .curves import part_name, part_rows
from .engines import compute_shard, failed_case, pinned_device
from .grid import Case
from .options import SweepOptions

__all__ = ["PinDevice", "run_dask", "shard_size_for"]


class PinDevice(WorkerPlugin):
    """Dask worker plugin: sets WARPTRUNC_DEVICE in each worker process before any task.

    Worker ``i`` of a LocalCluster (named 0..N-1, and a restarted worker keeps its name)
    gets ``cuda:{i mod n_devices}``; other names map by a stable function of the name
    (:func:`~warptrunc.sweep.engines.pinned_device`), the same in every run.
    ``n_devices=None`` asks Warp in the worker. With no CUDA device nothing is set and the
    workers run on the CPU.

    Parameters
    ----------
    n_devices : int, optional
        Number of CUDA devices to spread the workers over (count). None: the count Warp
        reports in each worker.
    """

    name = "warptrunc-pin-device"
    idempotent = True

    def __init__(self, n_devices: int | None = None) -> None:
        self.n_devices = n_devices

    def setup(self, worker) -> None:
        """Set ``WARPTRUNC_DEVICE`` in this worker process (called by Dask at worker start).

        Parameters
        ----------
        worker : distributed.Worker
            The worker; its ``name`` picks the device (:func:`pinned_device`).
        """
        n = self.n_devices if self.n_devices is not None else cuda_device_count()
        dev = pinned_device(worker.name, n)
        if dev is not None:
            os.environ["WARPTRUNC_DEVICE"] = dev


def shard_size_for(
    case_seconds: float | None,
    remaining: int,
    n_workers: int,
    *,
    target_s: float = 1.0,
    max_size: int = 4096,
) -> int:
    """Cases per task: about ``target_s`` of work, at most ``max_size``, and small enough
    that the remaining cases still make ≥ 2 tasks per worker (so the load balances).

    Parameters
    ----------
    case_seconds : float or None
        Median time of one case so far (s); None, 0 or NaN (none finished yet) gives 1.
    remaining : int
        Cases not yet submitted (count).
    n_workers : int
        Workers of the cluster (count); values below 1 count as 1.
    target_s : float
        Work per task to aim for (s).
    max_size : int
        Largest shard (cases).

    Returns
    -------
    int
        Cases per task, ≥ 1: ⌈target_s/case_seconds⌉ clipped to [1, max_size], then to
        at most ⌈remaining/(2·n_workers)⌉.
    """
    if not case_seconds or case_seconds != case_seconds:  # None, 0 or NaN
        return 1
    size = max(1, min(max_size, math.ceil(target_s / case_seconds)))
    return max(1, min(size, -(-remaining // (2 * max(n_workers, 1)))))


def run_dask(
    cases: list[Case], options: SweepOptions, store, *, workers: int | None = None,
    scheduler: Any = None, device=None, total: int, progress: bool = True,
    max_retries: int = 3, shard_size: int | None = None, shard_seconds: float = 1.0,
) -> None:  # fmt: skip
    """Run ``cases`` on a Dask cluster; each task writes one part of ``store``.

    Parameters
    ----------
    cases : list of Case
        Cases to compute (those not yet in ``store``), in grid order.
    options : SweepOptions
        Options shared by all cases.
    store : warptrunc.sweep.store.Store
        Records the parts (:meth:`~warptrunc.sweep.store.Store.record_part`).
    workers : int, optional
        Worker processes of the LocalCluster (count); None lets Dask choose. Ignored with
        ``scheduler``.
    scheduler : str or distributed.Client, optional
        Address of, or a client of, an existing cluster; None starts a LocalCluster.
    device : str, optional
        Warp device passed to every task; None lets each worker choose (pinned by
        :class:`PinDevice` on a LocalCluster unless ``WARPTRUNC_DEVICE`` is set).
    total : int
        Cases of the whole grid (count), for the progress bar; ``total − len(cases)`` count
        as done.
    progress : bool
        Show a progress bar and print the dashboard link (stderr).
    max_retries : int
        Resubmissions of a case whose task was lost before it is recorded as failed (count).
    shard_size : int, optional
        Cases per task; None: adaptive (:func:`shard_size_for`).
    shard_seconds : float
        Work per task that the adaptive size aims for (s).

    Notes
    -----
    ``scheduler`` (an address or a ``distributed.Client``) uses an existing cluster; else a
    LocalCluster of ``workers`` processes with one thread each, one per CUDA device when
    ``device`` is None and CUDA devices exist (:class:`PinDevice`; with more workers than
    devices they share them). A client this function opens, and its LocalCluster, are closed
    at the end; a client passed in is left open.

    Cases go to the workers in shards (one task each, :func:`compute_shard`): ``shard_size``
    cases, or an adaptive size (:func:`shard_size_for`: about ``shard_seconds`` of work per
    task from the median case time so far, starting at 1 case), with about two tasks in
    flight per worker. The workers write the parts into ``store.curves`` (a filesystem shared
    with this process) and send back only the part's name and rows. A task whose worker died
    or whose future was cancelled (``client.restart()``): if its part exists (written before
    the worker died) it is recorded; else the shard is submitted again whole (same part name,
    so two attempts never both land), and after a second loss one case per task, up to
    ``max_retries`` times per case, then recorded as failed.
    """

    from distributed import Client, LocalCluster, as_completed

    curves = str(store.curves.resolve()) if store.path is not None else None
    cluster = None
    own_client = True
    if isinstance(scheduler, Client):
        client, own_client = scheduler, False
    elif scheduler is not None:
        client = Client(scheduler)
    else:
        cluster = LocalCluster(
            n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
            silence_logs=logging.ERROR,
        )  # fmt: skip
        client = Client(cluster)
        if progress:
            print(f"Dask dashboard: {client.dashboard_link}", file=sys.stderr)
        if device is None and not os.environ.get("WARPTRUNC_DEVICE"):
            client.register_plugin(PinDevice())
    by_id = {c.case_id: c for c in cases}
    attempts = dict.fromkeys(by_id, 0)
    queue = [c.case_id for c in cases]  # not yet submitted, in grid order
    retry: list[list[str]] = []  # lost shards, submitted again first
    times: list[float] = []
    n_workers = [1, 0.0]

    def workers_now() -> int:
        if time.monotonic() - n_workers[1] > 5:
            n_workers[:] = [max(1, len(client.scheduler_info().get("workers", {}))),
                            time.monotonic()]  # fmt: skip
        return n_workers[0]

    def record(part, held) -> int:
        if part is None:
            new = store.add_many([(rows, None) for rows in held])
        else:
            new = store.record_part(part, held)
        times.extend(rs[0]["seconds"] for rs in held
                     if rs and isinstance(rs[0].get("seconds"), float)
                     and rs[0]["seconds"] == rs[0]["seconds"])  # fmt: skip
        return sum(new)

    try:
        futures: dict = {}
        pending = as_completed()

        def submit(ids: list[str]) -> None:
            for cid in ids:
                attempts[cid] += 1
            key = f"warptrunc-shard-{ids[0]}-{len(ids)}-{attempts[ids[0]]}"
            f = client.submit(compute_shard, [by_id[c] for c in ids], options, device, curves,
                              key=key, pure=False)  # fmt: skip
            futures[f] = ids
            pending.add(f)

        def top_up() -> None:
            w = workers_now()
            while (retry or queue) and len(futures) < 2 * w:
                if retry:
                    submit(retry.pop(0))
                    continue
                size = shard_size or shard_size_for(
                    statistics.median(times[-64:]) if times else None, len(queue), w,
                    target_s=shard_seconds,
                )  # fmt: skip
                submit(queue[:size])
                del queue[:size]

        top_up()
        with progress_bar(
            total=total,
            initial=total - len(cases),
            enabled=progress,
            desc="sweep [dask]",
            unit="case",
        ) as bar:
            while futures:
                fut = next(pending)
                ids = futures.pop(fut)
                out = None
                if fut.status == "finished":
                    try:
                        out = fut.result()
                    except Exception:  # cancelled after it finished (client.restart()): lost
                        out = None
                if out is not None:
                    bar.update(record(out["part"], out["rows"]))
                else:
                    if curves is not None:  # the worker may have written the part and died
                        name = part_name(ids, min(by_id[c].index for c in ids))
                        held = part_rows(os.path.join(curves, name))
                        if held is not None:
                            bar.update(record(name, held))
                    lost = [c for c in ids if c not in store.rows]
                    again = [c for c in lost if attempts[c] <= max_retries]
                    if again and len(again) == len(ids) and attempts[again[0]] == 1:
                        retry.append(again)  # the same shard once more: the same part name
                    else:
                        retry += [[c] for c in again]
                    if len(again) < len(lost):
                        try:
                            exc = fut.exception()
                            why = f"{type(exc).__name__}: {exc}"
                        except Exception as e:  # cancelled futures raise here
                            why = f"{type(e).__name__}: {e}"
                        for cid in set(lost) - set(again):
                            rows, _ = failed_case(by_id[cid], options,
                                                  f"lost {attempts[cid]} times: {why}")  # fmt: skip
                            store.add(rows, None)
                            bar.update()
                fut.release()
                top_up()
    finally:
        if own_client:
            client.close()
        if cluster is not None:
            cluster.close()
