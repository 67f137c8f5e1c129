# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Helpers shared by the scripts in ``examples/benchmarks/``: timing, provenance, record names.

A run record kept in ``benchmarks/records/`` is named by what was measured, on which machine,
at which commit: ``<what>_<machine>_<commit>.json`` (``record_name``), e.g.
``table1_presets_cpu_79581b0.json``.

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


RECORDS = ROOT / "benchmarks" / "records"
"""The folder of the run records (``benchmarks/records/``; its README lists every record)."""


def machine_token(device: str | None) -> str:
    """Short name of the machine a run used: ``cpu``, ``h100``, ``h200x4`` (GPU model and count).

    A CUDA device is named by its model (the first word such as ``H100`` in its name) and, on a
    host with several GPUs, ``x`` and their count.
    """
    import re

    import warp as wp

    dev = wp.get_device(device)
    if not dev.is_cuda:
        return "cpu"
    m = re.search(r"\b([A-Z]{1,2}\d{2,4})\b", dev.name)
    model = (m.group(1) if m else dev.name.split()[-1]).lower()
    count = wp.get_cuda_device_count()
    return f"{model}x{count}" if count > 1 else model


def record_name(what: str, device: str | None, suffix: str = ".json") -> str:
    """File name of a run record: ``<what>_<machine>_<commit>`` and ``suffix``.

    ``machine`` is :func:`machine_token`; ``commit`` the checkout's short commit (or
    ``$WARPTRUNC_GIT_COMMIT``), ``nocommit`` where neither is known.
    """
    commit = (git_commit() or "nocommit")[:7]
    return f"{what}_{machine_token(device)}_{commit}{suffix}"


def cpu_name() -> str:
    """The CPU model (/proc/cpuinfo), else platform.processor()."""
    import platform

    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def machine_fields(device) -> dict:
    """The head of a run record: the device, its name, Warp's version, the commit and the
    platform (``device``, ``device_name``, ``warp``, ``commit``, ``platform``)."""
    import platform

    import warp as wp

    return {
        "device": str(device),
        "device_name": wp.get_device(device).name,
        "warp": wp.config.version,
        "commit": git_commit(),
        "platform": platform.platform(),
    }


__all__ = [
    "RECORDS",
    "ROOT",
    "cpu_name",
    "git_commit",
    "machine_fields",
    "machine_token",
    "record_name",
    "timeit",
]


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
