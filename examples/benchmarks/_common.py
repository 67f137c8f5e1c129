# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Helpers shared by the scripts in ``examples/benchmarks/``: timing and provenance.

The scripts import it as ``from _common import ...``: run as
``python examples/benchmarks/benchmark_x.py``, their own folder is first on ``sys.path``.
"""

from __future__ import annotations

import argparse
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


def bench_parser(description: str | None) -> argparse.ArgumentParser:
    """The options every timing benchmark takes: ``--device``, ``--n``, ``--repeats``, ``--out``."""
    ap = argparse.ArgumentParser(
        description=description, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ... (default: CUDA if present)")
    ap.add_argument("--n", type=int, nargs="+", default=[1024, 4096], help="pixels per side")
    ap.add_argument("--repeats", type=int, default=5, help="timed repeats per measurement")
    ap.add_argument("--out", type=Path, default=Path("bench"), help="folder for the JSON")
    return ap
