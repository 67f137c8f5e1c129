# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Helpers shared by the scripts in ``examples/benchmarks/``: timing and provenance.

The scripts import it as ``from _common import ...``: run as
``python examples/benchmarks/benchmark_x.py``, their own folder is first on ``sys.path``.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import time
from collections.abc import Callable
from pathlib import Path

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


def git_commit(root: str | Path | None = None) -> str | None:
    """The commit of the checkout at ``root`` (default: this repository's), or None.

    ``$WARPTRUNC_GIT_COMMIT``, when set, is returned as it is.
    """
    env = os.environ.get("WARPTRUNC_GIT_COMMIT")
    if env:  # a copy without .git (e.g. a tree shipped to a GPU machine) can say its commit
        return env.strip()
    try:
        out = subprocess.run(
            ["git", "-C", str(root or ROOT), "rev-parse", "HEAD"], capture_output=True, text=True
        )
        return out.stdout.strip() or None
    except OSError:
        return None
