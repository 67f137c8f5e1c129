# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The Dask engine: cases on a LocalCluster (one worker per GPU) or on an existing cluster.

Imported only when ``workers`` or ``scheduler`` is given (needs ``warptrunc[sweep]``). Cases
go out in chunks (one task per chunk, sized adaptively to about 0.1 s of work), so the task
overhead is amortised when a case takes milliseconds; results stream back as chunks finish
(``as_completed``). The workers send the curves to the client, or write the curve files
themselves (``worker_writes``, off by default: measured slower on 2 × H200 and on the CPU); the
client records the rows and is the only writer of ``cases.parquet``.
"""

from __future__ import annotations

import logging
import os
import statistics
import sys
import time
from typing import Any

from distributed import WorkerPlugin

from .._device import cuda_device_count
from .._progress import progress_bar
from .engines import compute_chunk, failed_case, pinned_device
from .grid import Case, SweepOptions

__all__ = ["PinDevice", "chunk_size_for", "run_dask"]


class PinDevice(WorkerPlugin):
    """Dask worker plugin: sets WARPTRUNC_DEVICE in each worker process before any task.

    Worker ``i`` of a LocalCluster (named 0..N-1, and a restarted worker keeps its name)
    gets ``cuda:{i mod n_devices}``; ``n_devices=None`` asks Warp in the worker. With no
    CUDA device nothing is set and the workers run on the CPU.

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


def chunk_size_for(
    case_seconds: float | None,
    remaining: int,
    n_workers: int,
    *,
    target_s: float = 0.1,
    max_size: int = 64,
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
        Largest chunk (cases).

    Returns
    -------
    int
        Cases per task, ≥ 1: round(target_s/case_seconds) clipped to [1, max_size], then to
        at most ⌈remaining/(2·n_workers)⌉.
    """
    if not case_seconds or case_seconds != case_seconds:  # None, 0 or NaN
        return 1
    size = max(1, min(max_size, round(target_s / case_seconds)))
    return max(1, min(size, -(-remaining // (2 * max(n_workers, 1)))))


def run_dask(
    cases: list[Case], options: SweepOptions, store, *, workers: int | None = None,
    scheduler: Any = None, device=None, total: int, progress: bool = True,
    max_retries: int = 3, chunk_size: int | None = None, worker_writes: bool | None = None,
) -> None:  # fmt: skip
    """Run ``cases`` on a Dask cluster; results reach ``store`` in this process as they finish.

    Parameters
    ----------
    cases : list of Case
        Cases to compute (those not yet in ``store``), in grid order.
    options : SweepOptions
        Options shared by all cases.
    store : warptrunc.sweep.store.Store
        Receives the rows and curves (:meth:`~warptrunc.sweep.store.Store.add_many`,
        ``record`` and ``add``).
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
    chunk_size : int, optional
        Cases per task; None: adaptive (:func:`chunk_size_for`).
    worker_writes : bool, optional
        Workers write the curve files themselves; None means False.

    Notes
    -----
    ``scheduler`` (an address or a ``distributed.Client``) uses an existing cluster; else a
    LocalCluster of ``workers`` processes with one thread each, one per CUDA device when
    ``device`` is None and CUDA devices exist (:class:`PinDevice`). A client this function
    opens, and its LocalCluster, are closed at the end; a client passed in is left open.

    Cases go to the workers in chunks (one task each, :func:`compute_chunk`):
    ``chunk_size`` cases, or with ``None`` an adaptive size (:func:`chunk_size_for`: about
    0.1 s of work per task, from the median case time so far, starting at 1), with about two
    tasks in flight per worker, so results keep streaming. With ``worker_writes`` the workers
    write the curve files into ``store.curves`` themselves (needs a filesystem shared with
    this process; off by default: Parquet encoding slowed the workers down) and only rows
    travel back. A chunk whose worker died or whose future was cancelled
    (``client.restart()``) has its unfinished cases submitted again one per task, up to
    ``max_retries`` times each, then recorded as failed.
    """

    from distributed import Client, LocalCluster, as_completed

    if worker_writes is None:
        # off by default: Parquet encoding on the workers slowed them on the CPU (2 cores, 512²:
        # median case 14 → 26 ms) and on 2 × H200 (2048², 40 cases: 90 against 247 surfaces/s)
        worker_writes = False
    curves = str(store.curves.resolve()) if worker_writes and store.path is not None else None
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
    retry: list[str] = []  # lost once: one case per task
    times: list[float] = []
    n_workers = [1, 0.0]

    def workers_now() -> int:
        if time.monotonic() - n_workers[1] > 5:
            n_workers[:] = [max(1, len(client.scheduler_info().get("workers", {}))),
                            time.monotonic()]  # fmt: skip
        return n_workers[0]

    try:
        futures: dict = {}
        pending = as_completed()

        def submit(ids: list[str]) -> None:
            for cid in ids:
                attempts[cid] += 1
            key = f"warptrunc-chunk-{ids[0]}-{len(ids)}-{attempts[ids[0]]}"
            f = client.submit(compute_chunk, [by_id[c] for c in ids], options, device, curves,
                              key=key, pure=False)  # fmt: skip
            futures[f] = ids
            pending.add(f)

        def top_up() -> None:
            w = workers_now()
            while (retry or queue) and len(futures) < 2 * w:
                if retry:
                    submit([retry.pop(0)])
                    continue
                size = chunk_size or chunk_size_for(
                    statistics.median(times[-64:]) if times else None, len(queue), w
                )
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
                if fut.status == "finished":
                    results = fut.result()
                    if curves is None:
                        new = store.add_many(results)
                    else:
                        new = [store.record(rows) for rows, _ in results]
                    times += [r[0]["seconds"] for r, _ in results
                              if r and r[0].get("seconds") == r[0].get("seconds")]  # fmt: skip
                    bar.update(sum(new))
                else:
                    lost = [c for c in ids if c not in store.rows]
                    again = [c for c in lost if attempts[c] <= max_retries]
                    retry += again
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
