# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Running the cases: one case (:func:`compute_case`) and the in-process engine.

The Dask engine is in :mod:`warptrunc.sweep.cluster` (imported only when used).

Cases are pure: a case returns its rows and curve and writes nothing, so a case that runs
twice (a worker lost mid-case, its task rescheduled) cannot write twice; the client, the
store's single writer, drops the second result.
"""

from __future__ import annotations

import functools
import socket
import time
from collections.abc import Callable
from datetime import datetime, timezone
from typing import Any

import numpy as np

from .grid import Case, SweepOptions

__all__ = ["compute_case", "failed_case", "pinned_device", "run_inprocess"]

Sink = Callable[[list[dict[str, Any]], "dict[str, np.ndarray] | None"], bool]


@functools.cache
def _provenance() -> tuple[str, str | None, str]:
    from .. import __version__
    from .._bench import git_commit

    return __version__, git_commit(), socket.gethostname()


def _base_row(case: Case, o: SweepOptions) -> dict[str, Any]:
    Lx, Ly = (o.L, o.L) if isinstance(o.L, float) else o.L
    nx, ny = (o.n, o.n) if isinstance(o.n, int) else o.n
    lo, hi = o.depth_window if o.depth_window is not None else (np.nan, np.nan)
    version, commit, host = _provenance()
    return {
        "case_id": case.case_id, "case_index": case.index, "D_in": case.D, "delta": case.delta,
        "seed": case.seed, "Rt_m": case.delta * o.Wr, "Wr_m": o.Wr, "Lx_m": Lx, "Ly_m": Ly,
        "nx": nx, "ny": ny, "M": o.M, "gamma": o.gamma,
        "Wc_m": np.nan if o.Wc is None else o.Wc, "cutoff": o.cutoff,
        "increments": o.increments, "max_depth_fraction": o.max_depth_fraction,
        "max_depth_m": np.nan if o.max_depth is None else o.max_depth, "E_Pa": o.E, "nu": o.nu,
        "E_flat_Pa": o.E_flat, "nu_flat": o.nu_flat, "beta_prime": o.beta_prime,
        "depth_window_lo_m": lo, "depth_window_hi_m": hi, "alpha": np.nan, "beta": np.nan,
        "r2": np.nan, "n_points": None, "fit_depth_min_m": np.nan, "fit_depth_max_m": np.nan,
        "final_contact_pixels": None, "final_area_fraction": np.nan, "rt_measured_m": np.nan,
        "fit_error": None, "error": None, "host": host, "warptrunc_version": version,
        "git_commit": commit,
    }  # fmt: skip


def compute_case(
    case: Case, options: SweepOptions, device: str | None = None
) -> tuple[list[dict[str, Any]], dict[str, np.ndarray] | None]:
    """Generate, truncate and fit one case; never raises for a failing case.

    Returns the case's rows (one per fit range) and its curve columns, or (rows with the
    ``error`` column set, None) when generation or truncation raised.
    """
    from .._device import resolve_device
    from ..stiffness import fit_power_law, stiffness_curve
    from ..truncation import truncate
    from ..wm import wm_surface

    o = options
    base = _base_row(case, o)
    t0 = time.perf_counter()
    curve = None
    try:
        dev = resolve_device(device)
        base.update(device=str(dev), device_name=str(dev.name))
        s = wm_surface(
            case.D, o.Wr, L=o.L, n=o.n, Rt=case.delta * o.Wr, M=o.M, gamma=o.gamma, Wc=o.Wc,
            cutoff=o.cutoff, seed=case.seed, device=dev,
        )  # fmt: skip
        tc = truncate(s, o.increments, max_depth=o.max_depth,
                      max_depth_fraction=o.max_depth_fraction, device=dev)  # fmt: skip
        sc = stiffness_curve(tc, o.material(), beta_prime=o.beta_prime)
        curve = sc.to_dict()
        base.update(
            final_contact_pixels=int(sc.n_contact_pixels[-1]),
            final_area_fraction=float(sc.contact_area[-1] / sc.apparent_area),
            rt_measured_m=float(sc.rt),
        )
    except Exception as exc:  # recorded, the sweep goes on
        base.update(error=f"{type(exc).__name__}: {exc}")
    rows = []
    for mp in o.min_pixels:
        row = {**base, "min_pixels": mp}
        if curve is not None:
            try:
                f = fit_power_law(sc, min_pixels=mp, depth_window=o.depth_window)
                row.update(alpha=f.alpha, beta=f.beta, r2=f.r2, n_points=f.n_points,
                           fit_depth_min_m=f.depth_min, fit_depth_max_m=f.depth_max)  # fmt: skip
            except ValueError as exc:  # too few increments in this range: recorded, not dropped
                row.update(n_points=0, fit_error=str(exc))
        rows.append(row)
    seconds = time.perf_counter() - t0
    stamp = datetime.now(timezone.utc).isoformat(timespec="milliseconds")
    for r in rows:
        r.update(seconds=seconds, finished_utc=stamp)
        r.setdefault("device", str(device))
        r.setdefault("device_name", None)
    return rows, curve


def _bar(total: int, initial: int, progress: bool, desc: str):
    from tqdm.auto import tqdm

    return tqdm(total=total, initial=initial, disable=not progress, desc=desc, unit="case")


def run_inprocess(
    cases: list[Case], options: SweepOptions, sink: Sink, *, device=None, total: int,
    progress: bool = True,
) -> None:  # fmt: skip
    """Run ``cases`` one after another in this process, handing each result to ``sink``.

    ``sink`` (the store's write) runs in one background thread, so that writing a case
    overlaps computing the next; at most one write is pending, and it completes before
    this function returns or an interrupt propagates.
    """
    from concurrent.futures import ThreadPoolExecutor

    from .._device import resolve_device

    dev = str(resolve_device(device))
    with _bar(total, total - len(cases), progress, f"sweep [{dev}]") as bar, \
            ThreadPoolExecutor(1, thread_name_prefix="warptrunc-store") as pool:  # fmt: skip
        pending = None
        for case in cases:
            result = compute_case(case, options, dev)
            if pending is not None:
                pending.result()
                bar.update()
            pending = pool.submit(sink, *result)
        if pending is not None:
            pending.result()
            bar.update()


def pinned_device(worker_name: Any, n_devices: int) -> str | None:
    """The CUDA device of a LocalCluster worker: ``cuda:{name mod n_devices}``, or None."""
    if n_devices <= 0:
        return None
    try:
        i = int(worker_name)
    except (TypeError, ValueError):
        i = abs(hash(str(worker_name)))
    return f"cuda:{i % n_devices}"


def failed_case(case: Case, options: SweepOptions, why: str):
    base = _base_row(case, options)
    stamp = datetime.now(timezone.utc).isoformat(timespec="milliseconds")
    base.update(error=why, seconds=np.nan, finished_utc=stamp, device=None, device_name=None)
    return [{**base, "min_pixels": mp} for mp in options.min_pixels], None
