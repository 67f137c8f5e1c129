# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The Dask engine: cases on a LocalCluster (one worker per GPU) or on an existing cluster.

Imported only when ``workers`` or ``scheduler`` is given (needs ``warptrunc[sweep]``). The
client, the store's only writer, receives each case's rows and curve as the case finishes
(``as_completed``); workers write nothing.
"""

from __future__ import annotations

import logging
import os
import sys
from typing import Any

from distributed import Client, LocalCluster, WorkerPlugin, as_completed

from .engines import Sink, _bar, compute_case, failed_case, pinned_device
from .grid import Case, SweepOptions

__all__ = ["PinDevice", "run_dask"]


def _cuda_device_count() -> int:
    import warp as wp

    from .._device import _init

    _init()
    return wp.get_cuda_device_count()


class PinDevice(WorkerPlugin):
    """Dask worker plugin: sets WARPTRUNC_DEVICE in each worker process before any task.

    Worker ``i`` of a LocalCluster (named 0..N-1, and a restarted worker keeps its name)
    gets ``cuda:{i mod n_devices}``; ``n_devices=None`` asks Warp in the worker. With no
    CUDA device nothing is set and the workers run on the CPU.
    """

    name = "warptrunc-pin-device"
    idempotent = True

    def __init__(self, n_devices: int | None = None) -> None:
        self.n_devices = n_devices

    def setup(self, worker) -> None:
        n = self.n_devices if self.n_devices is not None else _cuda_device_count()
        dev = pinned_device(worker.name, n)
        if dev is not None:
            os.environ["WARPTRUNC_DEVICE"] = dev


def run_dask(
    cases: list[Case], options: SweepOptions, sink: Sink, *, workers: int | None = None,
    scheduler: Any = None, device=None, total: int, progress: bool = True,
    max_retries: int = 3,
) -> None:  # fmt: skip
    """Run ``cases`` on a Dask cluster; results reach ``sink`` in this process as they finish.

    ``scheduler`` (an address or a ``distributed.Client``) uses an existing cluster; else a
    LocalCluster of ``workers`` processes with one thread each, one per CUDA device when
    ``device`` is None and CUDA devices exist (:class:`PinDevice`). A case whose worker died
    or whose future was cancelled (``client.restart()``) is submitted again, up to
    ``max_retries`` times, then recorded as failed.
    """
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
    try:
        futures = {}

        def submit(cid: str):
            attempts[cid] += 1
            f = client.submit(compute_case, by_id[cid], options, device,
                              key=f"warptrunc-case-{cid}-{attempts[cid]}", pure=False)  # fmt: skip
            futures[f] = cid
            return f

        pending = as_completed([submit(c.case_id) for c in cases])
        with _bar(total, total - len(cases), progress, "sweep [dask]") as bar:
            for fut in pending:
                cid = futures.pop(fut)
                if fut.status == "finished":
                    sink(*fut.result())
                    bar.update()
                elif attempts[cid] <= max_retries:
                    pending.add(submit(cid))
                else:
                    try:
                        exc = fut.exception()
                        why = f"{type(exc).__name__}: {exc}"
                    except Exception as e:  # cancelled futures raise here
                        why = f"{type(e).__name__}: {e}"
                    rows, _ = failed_case(by_id[cid], options, f"lost {attempts[cid]} times: {why}")
                    sink(rows, None)
                    bar.update()
                fut.release()
    finally:
        if own_client:
            client.close()
        if cluster is not None:
            cluster.close()
