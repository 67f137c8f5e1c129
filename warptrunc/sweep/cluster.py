# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The Dask engine: cases on a LocalCluster (one worker per GPU) or on an existing cluster.

Imported only when ``workers`` or ``scheduler`` is given (dask.distributed loads then).
:func:`open_client` opens the cluster once per command (``run_sweep`` and ``reproduce`` use
it): ``workers="auto"`` is one worker per visible CUDA device (1 on a machine without one);
dask-cuda's ``LocalCUDACluster`` is used when it is installed and every worker gets a GPU of
its own, else a ``LocalCluster`` whose workers :class:`PinDevice` pins; either way every worker
uses the kernel cache directory of this process, so a kernel compiled once is loaded by all,
and a local cluster's workers are warmed as it starts (:func:`warm_worker`: Warp started, the
pinned device made the default, the light cases' kernels loaded). Cases go out in shards
(one task per shard of about 1 s of work, at most about four per worker:
:class:`~warptrunc.sweep.sharding.ShardPlanner`), so the task overhead is amortised when a
case takes milliseconds. Each worker writes its shard as one part of the store
(:func:`~warptrunc.sweep.engines.compute_shard`) and sends back only the part's name and rows;
the client records which parts exist and is the only writer of ``cases.parquet``.

What the worker processes of a local cluster inherit (:func:`worker_environment`): Warp's
kernel cache folder, the process environment Dask sets before it spawns them less glibc's
trim threshold, and a configuration without Dask's statistical profiler
(:data:`PROFILE_ENV`).

Dask's nanny sets ``MALLOC_TRIM_THRESHOLD_=65536`` in every worker it spawns
(``distributed.nanny.pre-spawn-environ``), so that workers give freed memory back to the
operating system. Setting that variable turns glibc's dynamic mmap threshold off: every
allocation above 128 KiB (a 2048² map, a solver's temporaries) is then mapped and unmapped
afresh, and its pages are faulted in each time. Measured on the CPU (2-core VM): a 256² contact
solve with its host work took 0.29–0.32 s in a worker against 0.16–0.18 s in process, and
0.17–0.19 s in a worker without the variable; the indentation stage's pieces (tiny profile at
256²) cost 17.7 s with the variable and 13.8 s without, in process and in a worker alike
(``benchmarks/records/worker_trim_cpu_fcb7142.json``; ``tests/test_sweep_spawn.py`` checks the setting, the
timing is not asserted). On the 4 × H200 host the indentation pieces cost 1.24× as much on
workers as in process (``benchmarks/records/indentation_workers_h200x4_34cbf1b.json``), the same
ratio; but with the variable left out, on 4 × H100, they still cost 1.31× (2 workers) and 1.44×
(4 workers) (``benchmarks/records/indentation_workers_h100x4_cc1dcf5.json``): on GPUs it is not the
whole cause. With the profiler off as well (:data:`PROFILE_ENV`), on 4 × H100 at ``1b64d9c``, they cost
1.04× (4 workers) and 1.10× (2), and 4 workers run the stage 3.44× faster than one process
(``benchmarks/records/indentation_workers_h100x4_1b64d9c.json``).

A user who sets ``MALLOC_TRIM_THRESHOLD_`` in their own environment keeps it: the workers
inherit it. Workers of an existing cluster (``--scheduler``) are started by the user: give them
``distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_: null`` in their Dask configuration
file (Dask's ``DASK_*`` variables lowercase the key, so they cannot name it), or start them
with ``--no-nanny``.
"""

from __future__ import annotations

import logging
import os
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from distributed import WorkerPlugin

from .._support.device import cuda_device_count
from .._support.interrupt import check_interrupt
from .._support.progress import progress_bar
from .._support.validate import check_int
from .curves import part_name, part_rows
from .engines import MAX_SHARD, compute_shard, failed_case, pinned_device
from .grid import Case
from .options import SweepExecution, SweepOptions
from .sharding import ShardPlanner

__all__ = [
    "PROFILE_ENV",
    "TRIM_VARIABLE",
    "PinDevice",
    "kernel_cache_base",
    "open_client",
    "resolve_workers",
    "run_dask",
    "warm_worker",
    "worker_environment",
]

#: Set to ``0`` to use a LocalCluster with :class:`PinDevice` even where dask-cuda is installed.
DASK_CUDA_ENV = "WARPTRUNC_DASK_CUDA"

TRIM_VARIABLE = "MALLOC_TRIM_THRESHOLD_"
"""glibc's trim threshold variable, which Dask's nanny sets in its workers unless told not to."""

PROFILE_ENV = "WARPTRUNC_DASK_PROFILE"
"""Set to ``1`` to keep Dask's statistical profiler in a local cluster's workers (off by default:
it samples every worker thread's stack every 10 ms, holding the GIL meanwhile, and the solver's
loop on a GPU waits on its host thread between launches)."""


def kernel_cache_base() -> str | None:
    """The folder to give every worker as ``WARP_CACHE_PATH``: that of this process, if set.

    Warp appends its version to ``WARP_CACHE_PATH`` (or to ``wp.config.kernel_cache_dir`` set
    before it initialises) and resolves ``wp.config.kernel_cache_dir`` to the result when it
    initialises; the folder returned is that directory without the version, so a worker given
    it resolves the same directory and loads the kernels any process compiled there instead
    of compiling them again. Warp is not initialised here.

    Returns
    -------
    str or None
        Absolute path of the cache's base folder: from ``wp.config.kernel_cache_dir`` (set by
        the user, or resolved by Warp's start), else ``$WARP_CACHE_PATH``; None when neither
        is set (every process of the user then resolves the same default folder).
    """
    import warp as wp

    where = wp.config.kernel_cache_dir
    if where is None:
        env = os.environ.get("WARP_CACHE_PATH")
        return os.path.realpath(env) if env else None
    resolved = os.path.realpath(str(where))
    head, tail = os.path.split(resolved)
    return head if tail == wp.config.version else resolved


def worker_environment() -> dict[str, Any]:
    """The Dask configuration a local cluster's workers are spawned under.

    Returns
    -------
    dict of str to Any
        For ``dask.config.set`` (the nanny hands its configuration to the worker it spawns):
        ``"distributed.nanny.environ"``, the configured one plus ``WARP_CACHE_PATH`` (from
        :func:`kernel_cache_base`, where it gives a folder); ``"distributed.nanny.pre-spawn-environ"``,
        the configured one with :data:`TRIM_VARIABLE` set to None (Dask then leaves it unset)
        unless this process's environment sets it; and ``"distributed.worker.profile.enabled"``
        False (Dask's statistical profiler off; the dashboard's Profile page stays empty) unless
        ``$WARPTRUNC_DASK_PROFILE`` is ``1``.

    Notes
    -----
    The profiler, measured on one H100 (``examples/benchmarks/benchmark_worker_overhead.py``, an
    elastic and an elastic–plastic indentation part at 1024²,
    ``benchmarks/records/worker_overhead_h100x4_12e7a94.json``): the parts took 1.23× their time in the main
    thread on a worker as Dask configures it, 0.88× and 0.80× (two calls) with the profiler and
    the system monitor off, 1.15× with only the profiler off; runs of one setting spread by up to
    30 %, so the profiler's share is not pinned down. It is turned off because it costs the GIL
    and gives nothing a command needs. With it off (``1b64d9c``, 4 × H100 of one NUMA node, so
    the CPU binding changed nothing there), a worker took 1.03–1.08× the main thread
    (``benchmarks/records/worker_overhead_h100x4_1b64d9c.json``) and the indentation stage's pieces
    1.04× on 4 workers.
    """
    import dask

    environ = dict(dask.config.get("distributed.nanny.environ", {}) or {})
    cache = kernel_cache_base()
    if cache is not None:
        environ["WARP_CACHE_PATH"] = cache
    pre = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}) or {})
    if TRIM_VARIABLE not in os.environ:
        pre[TRIM_VARIABLE] = None
    profile = os.environ.get(PROFILE_ENV, "").strip().lower() in ("1", "true", "yes", "on")
    return {
        "distributed.nanny.environ": environ,
        "distributed.nanny.pre-spawn-environ": pre,
        "distributed.worker.profile.enabled": profile,
    }


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
    group : int, optional
        Devices per worker (count, default 1). Above 1, worker ``i`` takes devices
        ``i·group …`` (:func:`~warptrunc.sweep.groups.worker_group`), written to
        ``WARPTRUNC_DEVICE_GROUP``, and its Warp device is the group's first.
    platform : {"cuda", "cpu"}, optional
        Platform of the group's device names (``"cpu"``: JAX's host devices; no Warp pinning).
    pin : bool, optional
        Set ``WARPTRUNC_DEVICE`` (False: the caller passes a Warp device; only the group).

    Notes
    -----
    A worker given a CUDA device (or group) is also bound to the CPUs near it, those it may
    use (``bind_near`` of ``warptrunc.sweep._affinity``: the GPU's socket on a host of several;
    nothing where Linux or the driver does not say; ``WARPTRUNC_CPU_AFFINITY=0`` turns it off),
    as dask-cuda's ``LocalCUDACluster`` binds its workers.
    """

    name = "warptrunc-pin-device"
    idempotent = True

    def __init__(
        self, n_devices: int | None = None, group: int = 1, platform: str = "cuda", pin: bool = True
    ) -> None:
        self.n_devices = n_devices
        self.group, self.platform, self.pin = int(group), platform, pin

    def setup(self, worker) -> None:
        """Set ``WARPTRUNC_DEVICE`` in this worker process (called by Dask at worker start).

        Parameters
        ----------
        worker : distributed.Worker
            The worker; its ``name`` picks the device (:func:`pinned_device`).
        """
        n = self.n_devices if self.n_devices is not None else cuda_device_count()
        if self.group > 1 and n > 0:  # a group of devices (warptrunc.sweep.groups)
            from .groups import GROUP_ENV, worker_group

            names = worker_group(worker.name, n, self.group, self.platform)
            os.environ[GROUP_ENV] = ",".join(names)
            if self.platform == "cuda":
                if self.pin:
                    os.environ["WARPTRUNC_DEVICE"] = names[0]
                _bind_near(names)
            return
        dev = pinned_device(worker.name, n) if self.pin else None
        if dev is not None:
            os.environ["WARPTRUNC_DEVICE"] = dev
            _bind_near([dev])


def _bind_near(names: list[str]) -> None:
    """Bind this worker to the CPUs near its CUDA devices (``"cuda:i"`` names;
    ``bind_near`` of ``warptrunc.sweep._affinity``), as dask-cuda binds its workers."""
    from ._affinity import bind_near

    ordinals = [int(d.split(":", 1)[1]) for d in names if d.startswith("cuda:")]
    if ordinals:
        bind_near(ordinals)


def warm_worker(device: Any = None, contact: bool = False) -> str:
    """Start Warp in this process and load the kernels every sweep case uses on its device.

    Run in each worker of a local cluster as it starts (:func:`open_client`), so that a
    worker's first task does not pay for Warp's start, the CUDA context and the kernel loads
    (compiled kernels come from the shared cache, :func:`kernel_cache_base`).

    Parameters
    ----------
    device : str, optional
        The device the tasks will be given; None: ``$WARPTRUNC_DEVICE`` (set by
        :class:`PinDevice`), else CUDA when present, else the CPU.
    contact : bool, optional
        Also warm the contact solver (elastic cases, ``reproduce``): on a CUDA device one
        solve of a 64² map, which loads its kernel modules, CuPy and cuFFT (about a second
        the first task would otherwise pay).

    Returns
    -------
    str
        The device, or ``"<device>: <error>"`` when it cannot be used here (never raises: the
        tasks then record the error themselves).

    Notes
    -----
    On a CUDA device it becomes Warp's default device in this process (``wp.set_device``), so
    that nothing left on the default device or stream lands on another worker's GPU, and the
    modules of generation, truncation and the reductions are loaded
    (``wp.load_module``). On the CPU only Warp is started: its kernels load (and compile) on
    first use, in the first task, as in process.
    """
    try:
        import warp as wp

        from .._support.device import resolve_device

        dev = resolve_device(device)
        if dev.is_cuda:
            wp.set_device(dev)
            from ..kernels import reduce, truncation, wm

            for module in (wm, truncation, reduce):
                wp.load_module(module, device=dev)
            if contact:
                import numpy as np

                from ..contact import ContactSolver, SolverSettings

                x = np.linspace(0.0, 2.0 * np.pi, 64)
                h = 1e-6 * np.outer(np.cos(x), np.cos(x))  # m
                f32 = SolverSettings(dtype="float32")
                ContactSolver(h, 1e-6, 1e11, settings=f32, device=dev).solve(5e-7)
                wp.synchronize_device(dev)
        return str(dev)
    except Exception as exc:  # reported by the tasks
        return f"{device}: {type(exc).__name__}: {exc}"


def resolve_workers(workers: int | str | None) -> int | None:
    """The worker count of a local cluster: ``"auto"`` is one per visible CUDA device.

    Parameters
    ----------
    workers : int, str or None
        A count ≥ 1 (an int or its decimal text), ``"auto"``, or None (Dask chooses).

    Returns
    -------
    int or None
        The count; ``"auto"`` gives the number of visible CUDA devices (those that
        ``CUDA_VISIBLE_DEVICES`` leaves, as Warp counts them; Warp is not started for it),
        or 1 on a machine without one.

    Raises
    ------
    ValueError
        ``workers`` is neither a count ≥ 1, ``"auto"`` nor None.
    """
    if workers is None:
        return None
    if isinstance(workers, str):
        text = workers.strip().lower()
        if text == "auto":
            return max(1, _gpu_count())
        if not text.isdigit():
            raise ValueError(f"workers must be an integer ≥ 1 or 'auto', got {workers!r}")
        workers = int(text)
    return check_int("workers", workers, 1)


def _gpu_count() -> int:
    """CUDA devices visible to this process (count), without starting Warp when the CUDA
    driver answers directly (``cuInit`` + ``cuDeviceGetCount``, no context is created);
    else, or once Warp has started here, the count Warp reports."""
    from .._support import device as _device

    if not _device._initialised and sys.platform.startswith("linux"):
        import ctypes

        try:
            lib = ctypes.CDLL("libcuda.so.1")
            count = ctypes.c_int(0)
            if lib.cuInit(0) == 0 and lib.cuDeviceGetCount(ctypes.byref(count)) == 0:
                return int(count.value)
            return 0  # a driver without a usable device
        except (OSError, AttributeError):  # no CUDA driver: Warp says the same, quickly
            pass
    return cuda_device_count()


def _dask_cuda_cluster():
    """dask-cuda's LocalCUDACluster class, or None (not installed, or turned off)."""
    if os.environ.get(DASK_CUDA_ENV, "").strip().lower() in ("0", "false", "no", "off"):
        return None
    try:
        from dask_cuda import LocalCUDACluster
    except Exception:  # not installed, or broken (no matching CUDA libraries)
        return None
    return LocalCUDACluster


@contextmanager
def open_client(
    workers: int | str | None = None,
    scheduler: Any = None,
    device: Any = None,
    progress: bool = True,
    warm_contact: bool = False,
    group: int = 1,
) -> Iterator[tuple[Any, Any, bool]]:
    """A Dask client for a command: a local cluster started once, or an existing cluster.

    Parameters
    ----------
    workers : int or "auto", optional
        Worker processes of a local cluster (one thread each); ``"auto"``: one per visible
        CUDA device, 1 on a machine without one (:func:`resolve_workers`); None lets Dask
        choose. Ignored with ``scheduler``.
    scheduler : str or distributed.Client, optional
        Address of an existing scheduler (``"tcp://host:8786"``, a dask-jobqueue cluster's
        ``scheduler_address``), or a client, used as it is; None starts a local cluster.
    device : str, optional
        Warp device the caller passes to every task. None (and ``$WARPTRUNC_DEVICE`` unset):
        the workers of a local cluster are pinned one per CUDA device.
    progress : bool
        Print the dashboard's address (stderr) when a local cluster starts.
    warm_contact : bool, optional
        Warm the contact solver in every worker as it starts (``warm_worker(contact=True)``:
        elastic sweeps, ``reproduce``).
    group : int, optional
        Devices per worker of a local cluster (count, default 1; :mod:`warptrunc.sweep.groups`:
        worker ``i`` takes devices ``i·group …``, ``workers="auto"`` is the devices present
        divided by ``group``). Ignored with ``scheduler`` (give each worker its group there).

    Yields
    ------
    client : distributed.Client
        The client to submit to.
    cluster : distributed.LocalCluster or None
        The local cluster started here (a ``dask_cuda.LocalCUDACluster`` where used), or None
        with ``scheduler``.
    own : bool
        True when the client was opened here; it (and the cluster) is closed on exit. A
        client passed as ``scheduler`` is left open (False).

    Notes
    -----
    With CUDA devices, no ``device`` and dask-cuda installed, at most one worker per device
    runs on a ``LocalCUDACluster`` (``CUDA_VISIBLE_DEVICES`` per worker, its device is its
    ``cuda:0``); set ``WARPTRUNC_DASK_CUDA=0`` to use the LocalCluster instead. Otherwise a
    ``LocalCluster`` whose worker i runs on ``cuda:{i mod n_gpus}`` (:class:`PinDevice`).
    The workers of a local cluster get this process's kernel cache folder as
    ``WARP_CACHE_PATH`` (:func:`kernel_cache_base`; with none set, all resolve the user's
    default), so they share one kernel cache on disk, and are warmed before the first task
    (:func:`warm_worker`, on every worker at once). Warp is not started here: devices are
    counted through the CUDA driver (only for ``"auto"`` and dask-cuda). Workers of an
    existing cluster are not pinned: start one per GPU with its ``CUDA_VISIBLE_DEVICES``
    (``dask cuda worker`` does) or ``WARPTRUNC_DEVICE``.
    """
    import dask
    from distributed import Client, LocalCluster

    if workers is not None and scheduler is not None:
        raise ValueError("give workers (a local cluster) or scheduler (an existing one), not both")
    if isinstance(scheduler, Client):
        yield scheduler, None, False
        return
    cluster = None
    if scheduler is not None:
        client = Client(scheduler)
    else:
        n = resolve_workers(workers)
        pin = device is None and not os.environ.get("WARPTRUNC_DEVICE")
        if group > 1:
            from .groups import group_layout

            n, have, platform = group_layout(workers, n, group, _gpu_count())
            plugin = PinDevice(n_devices=have, group=group, platform=platform, pin=pin)
            pin = False
        cuda_cls = _dask_cuda_cluster() if pin else None  # counted only where installed
        n_gpus = _gpu_count() if cuda_cls is not None else 0
        if not (n_gpus > 0 and (n or n_gpus) <= n_gpus):
            cuda_cls = None
        common = dict(threads_per_worker=1, dashboard_address=":0", silence_logs=logging.ERROR)
        with dask.config.set(worker_environment()):
            if cuda_cls is not None:
                cluster = cuda_cls(n_workers=n or n_gpus, **common)
            else:
                cluster = LocalCluster(n_workers=n, processes=True, **common)
        try:
            client = Client(cluster)
            if pin:  # a LocalCUDACluster's worker sees its own device first: cuda:0
                client.register_plugin(PinDevice(n_devices=1 if cuda_cls else None))
            elif group > 1:
                client.register_plugin(plugin)
            t0 = time.perf_counter()
            # all workers at once; never raises in a worker
            client.run(warm_worker, device, warm_contact)
            warm = time.perf_counter() - t0
        except BaseException:
            cluster.close()
            raise
        if progress:
            kind = type(cluster).__name__
            print(
                f"Dask {kind} of {len(cluster.workers)} workers (warmed in {warm:.1f} s), "
                f"dashboard: {client.dashboard_link}",
                file=sys.stderr,
            )
    try:
        yield client, cluster, True
    finally:
        try:
            client.close()
        finally:
            if cluster is not None:
                cluster.close()


def run_dask(
    cases: list[Case],
    options: SweepOptions,
    store,
    *,
    execution: SweepExecution | None = None,
    total: int | None = None,
    progress: bool = True,
    device: Any = None,
) -> None:
    """Run ``cases`` on a Dask cluster; each task writes one part of ``store``.

    Parameters
    ----------
    cases : list of Case
        Cases to compute (those not yet in ``store``), in grid order.
    options : SweepOptions
        Options shared by all cases.
    store : warptrunc.sweep.store.Store
        Records the parts (:meth:`~warptrunc.sweep.store.Store.record_part`).
    execution : SweepExecution, optional
        The cluster (``workers`` of a local one, or ``scheduler``: an address or a client of an
        existing one; neither: a local cluster of Dask's choosing), the shard sizes
        (``shard_size``, ``shard_seconds``), ``max_retries`` and the devices of each elastic
        solve (``devices``: a count, the worker's own group, :mod:`warptrunc.sweep.groups`).
        Default ``SweepExecution()``.
    total : int, optional
        Cases of the whole grid (count), for the progress bar; ``total − len(cases)`` count
        as done. Default ``len(cases)``.
    progress : bool
        Show a progress bar and print the dashboard link (stderr).
    device : str, optional
        Warp device passed to every task; None lets each worker choose (pinned by
        :class:`PinDevice` on a LocalCluster unless ``WARPTRUNC_DEVICE`` is set).

    Notes
    -----
    The client comes from :func:`open_client`: ``scheduler`` (an address or a
    ``distributed.Client``) uses an existing cluster; else a local cluster of ``workers``
    processes with one thread each, one per CUDA device when ``device`` is None and CUDA
    devices exist (with more workers than devices they share them). A client this function
    opens, and its cluster, are closed at the end; a client passed in is left open.

    Cases go to the workers in shards (one task each, :func:`compute_shard`): ``shard_size``
    cases, or an adaptive size (:class:`~warptrunc.sweep.sharding.ShardPlanner`: about
    ``shard_seconds`` of work per task from the cases per second of the finished tasks, each
    worker's first task left out; 1, 2, 4 … cases while none is known; at most about four
    tasks per worker), with about two tasks in flight per worker. The workers write the parts
    into ``store.curves`` (a filesystem shared with this process) and send back only the part's
    name and rows. A task whose worker died or whose future was cancelled
    (``client.restart()``): if its part exists (written before the worker died) it is
    recorded; else the shard is submitted again whole (same part name, so two attempts never
    both land), and after a second loss one case per task, up to ``max_retries`` times per
    case, then recorded as failed. A task that raised (a bug: a case records its own errors)
    is handled the same way, and its error printed once (stderr).
    """

    from .groups import group_size

    ex = SweepExecution() if execution is None else execution
    total = len(cases) if total is None else total
    group = group_size(ex.devices) if ex.scheduler is None else 1
    with open_client(ex.workers, ex.scheduler, device, progress, group=group) as (client, _, _):
        _run_on(client, cases, options, store, ex, device=device, total=total, progress=progress)


def _run_on(client, cases, options, store, ex: SweepExecution, *, device, total, progress) -> None:
    """:func:`run_dask` on an open ``client``."""
    from distributed import as_completed

    curves = str(store.curves.resolve()) if store.path is not None else None
    by_id = {c.case_id: c for c in cases}
    attempts = dict.fromkeys(by_id, 0)
    queue = [c.case_id for c in cases]  # not yet submitted, in grid order
    retry: list[list[str]] = []  # lost shards, submitted again first
    plan = ShardPlanner(len(cases), target_s=ex.shard_seconds, max_size=MAX_SHARD)
    n_workers = [1, 0.0]
    told: set[str] = set()  # errors of tasks already reported

    def workers_now() -> int:
        if time.monotonic() - n_workers[1] > 5:
            n_workers[:] = [
                max(1, len(client.scheduler_info().get("workers", {}))),
                time.monotonic(),
            ]
        return n_workers[0]

    def record(part, held) -> int:
        if part is None:
            new = store.add_many([(rows, None) for rows in held])
        else:
            new = store.record_part(part, held)
        return sum(new)

    futures: dict = {}
    pending = as_completed()

    def submit(ids: list[str]) -> None:
        for cid in ids:
            attempts[cid] += 1
        key = f"warptrunc-shard-{ids[0]}-{len(ids)}-{attempts[ids[0]]}"
        f = client.submit(
            compute_shard,
            [by_id[c] for c in ids],
            options,
            device,
            curves,
            ex.devices,
            key=key,
            pure=False,
        )
        futures[f] = ids
        pending.add(f)

    def top_up() -> None:
        w = workers_now()
        while (retry or queue) and len(futures) < 2 * w:
            if retry:
                submit(retry.pop(0))
                continue
            size = ex.shard_size or plan.size(len(queue), w)
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
                plan.finished(len(ids), plan.task_seconds(out), out.get("worker"))
                bar.update(record(out["part"], out["rows"]))
            else:
                if fut.status == "error":  # a bug, not a lost worker: say so once per message
                    why = _task_error(fut)
                    if why not in told:
                        told.add(why)
                        print(
                            f"warning: a task of {len(ids)} cases raised {why}; its cases "
                            "are submitted again",
                            file=sys.stderr,
                        )
                if curves is not None:  # the worker may have written the part and died
                    name = part_name(ids, min(by_id[c].index for c in ids))
                    held = part_rows(os.path.join(curves, name))
                    if held is not None:
                        bar.update(record(name, held))
                lost = [c for c in ids if c not in store.rows]
                again = [c for c in lost if attempts[c] <= ex.max_retries]
                if again and len(again) == len(ids) and attempts[again[0]] == 1:
                    retry.append(again)  # the same shard once more: the same part name
                else:
                    retry += [[c] for c in again]
                if len(again) < len(lost):
                    why = _task_error(fut)
                    for cid in set(lost) - set(again):
                        rows, _ = failed_case(
                            by_id[cid], options, f"lost {attempts[cid]} times: {why}"
                        )
                        store.add(rows, None)
                        bar.update()
            fut.release()
            check_interrupt()  # a stop signal swallowed in a destructor
            top_up()


def _task_error(fut) -> str:
    """``"<type>: <message>"`` of the exception of a failed or cancelled future."""
    try:
        exc = fut.exception()
        return f"{type(exc).__name__}: {exc}"
    except Exception as e:  # cancelled futures raise here
        return f"{type(e).__name__}: {e}"
