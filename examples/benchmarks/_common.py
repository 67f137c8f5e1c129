# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Helpers shared by the scripts in ``examples/benchmarks/``: timing and provenance.

The scripts import it as ``from _common import ...``: run as
``python examples/benchmarks/benchmark_x.py``, their own folder is first on ``sys.path``.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from pathlib import Path

from warptrunc._support.provenance import git_commit

ROOT = Path(__file__).resolve().parents[2]
"""The repository root (this file is ``examples/benchmarks/_common.py``)."""


def timeit(fn: Callable[[], object], repeats: int, sync: Callable[[], object]) -> float:
    """Median wall time (s) of ``fn`` over ``repeats`` runs after one warm-up run.

    ``sync`` is called after each run (e.g. ``wp.synchronize_device``) so that asynchronous
    device work is inside the measurement.
    """
    fn()
    sync()
    ts = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        sync()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)

__all__ = ["ROOT", "git_commit", "timeit"]
