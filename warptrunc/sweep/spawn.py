# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""What the worker processes of a local cluster inherit: Warp's kernel cache folder, the
process environment Dask sets before it spawns them less glibc's trim threshold, and a
configuration without Dask's statistical profiler (:data:`PROFILE_ENV`).

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
whole cause. With the profiler off as well (below), on 4 × H100 at ``1b64d9c``, they cost
1.04× (4 workers) and 1.10× (2), and 4 workers run the stage 3.44× faster than one process
(``benchmarks/records/indentation_workers_h100x4_1b64d9c.json``).

A user who sets ``MALLOC_TRIM_THRESHOLD_`` in their own environment keeps it: the workers
inherit it. Workers of an existing cluster (``--scheduler``) are started by the user: give them
``distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_: null`` in their Dask configuration
file (Dask's ``DASK_*`` variables lowercase the key, so they cannot name it), or start them
with ``--no-nanny``.
"""

from __future__ import annotations

import os
from typing import Any

__all__ = ["PROFILE_ENV", "TRIM_VARIABLE", "kernel_cache_base", "worker_environment"]

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
    return {"distributed.nanny.environ": environ, "distributed.nanny.pre-spawn-environ": pre,
            "distributed.worker.profile.enabled": profile}
