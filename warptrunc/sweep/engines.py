# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Running the cases: one case (:func:`compute_case`), one shard (:func:`compute_shard`) and
the in-process engine (:func:`run_inprocess`).

The Dask engine is in :mod:`warptrunc.sweep.cluster` (imported only when used).

A case (:func:`compute_case`) is pure: it returns its rows and curve and writes nothing. A
shard (:func:`compute_shard`, one Dask task) computes its cases and writes them as one part
of the store (:func:`~warptrunc.sweep.curves.write_part`); parts are never replaced (the
first attempt of a shard wins), and the client, the only writer of ``cases.parquet``, records
which parts exist and drops a second part of a case.
"""

from __future__ import annotations

import collections
import json
import os
import queue
import re
import socket
import threading
import time
import zlib
from collections.abc import Callable
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

import numpy as np
import warp as wp

from .._support.device import resolve_device
from .._support.docs import SHARED_DOCS, fill_doc
from .._support.interrupt import check_interrupt
from .._support.progress import progress_bar
from ..plausibility import check_dimensions, check_fit, fit_error_text
from ..slope import slope_record, slope_warnings
from ..stiffness import fit_power_law, stiffness_curve
from ..truncation.api import truncate
from ..wm import wm_surface
from .batch import WMBatch, batch_size
from .curves import part_name, part_rows, write_part
from .grid import Case
from .options import SweepExecution, SweepOptions
from .rows import base_row, elastic_record, fit_ranges, fractal_record, resolve_min_pixels

__all__ = [
    "MAX_SHARD",
    "batched_results",
    "compute_case",
    "compute_many",
    "compute_shard",
    "elastic_record",
    "failed_case",
    "finish_batch",
    "pinned_device",
    "run_inprocess",
    "worker_index",
]

MAX_SHARD = 4096
"""Most cases in one part of the store (count): the in-process engine's queue, the Dask
engine's largest shard."""

Result = tuple[list[dict[str, Any]], "dict[str, np.ndarray] | None"]
Sink = Callable[[list[dict[str, Any]], "dict[str, np.ndarray] | None"], bool]
BatchSink = Callable[[list[Result]], Any]


@fill_doc(SHARED_DOCS)
def compute_case(
    case: Case, options: SweepOptions, device: str | None = None, devices: Any = None
) -> tuple[list[dict[str, Any]], dict[str, np.ndarray] | None]:
    """Generate, truncate and fit one case; never raises for a failing case.

    Parameters
    ----------
    case : Case
        D, δ = R_t/W_r and seed of the WM surface.
    options : SweepOptions
        Grid size, material, increments, fit ranges and fractal methods.
    {warp_device}
    devices : int, "auto" or list, optional
        Spread the elastic solves (``bem_fractions``) over several devices
        (``contact_solver(..., devices=...)``; JAX); default None: ``device`` alone.

    Returns
    -------
    rows : list of dict
        One row per fit range (``min_pixels`` and ``min_pixels_fraction``), with α, β, r²
        (NaN and ``fit_error`` set when the fit has too few increments), provenance, timing.
    curve : dict of str to ndarray or None
        The columns of :meth:`~warptrunc.stiffness.StiffnessCurve.to_dict`, or None when
        generation, the fractal dimensions or truncation raised (then every row has the
        ``error`` column set).
    """

    o = options
    base = base_row(case, o)
    t0 = time.perf_counter()
    sc = None
    try:
        dev = resolve_device(device)
        base.update(device=str(dev), device_name=str(dev.name))
        s = wm_surface(o.wm_spec(case.D, case.delta * o.Wr, case.seed), device=dev)
        slope = slope_record(s)  # h′_rms at the pixel (finite differences) and of the terms
        base.update(
            slope_rms=slope["slope_rms"],
            curvature_rms_per_m=slope["curvature_rms_per_m"],
            slope_rms_spectrum=slope["spectrum"]["slope_rms"],
        )
        if o.bem_fractions:  # the elastic columns hold for small slopes only
            found = slope_warnings(slope)
            if found:
                base["warnings"] = _join_warnings(base["warnings"], found)
        if o.fractal_methods:
            from ..fractal import fractal_dimensions

            t1 = time.perf_counter()
            base.update(fractal_record(fractal_dimensions(s, o.fractal_methods, device=dev)))
            found = check_dimensions({m: base[f"D_{m}"] for m in o.fractal_methods})
            if found:
                base["warnings"] = _join_warnings(None, found)
            base["fractal_seconds"] = time.perf_counter() - t1
        tc = truncate(
            s,
            o.increments,
            max_depth=o.max_depth,
            max_depth_fraction=o.max_depth_fraction,
            device=dev,
        )
        sc = stiffness_curve(tc, o.material(), beta_prime=o.beta_prime)
        if o.bem_fractions:
            base.update(elastic_record(s, sc, o, dev, devices=devices))
    except Exception as exc:  # recorded, the sweep goes on
        base.update(error=f"{type(exc).__name__}: {exc}")
    return _finish(o, base, sc, time.perf_counter() - t0, device)


def _finish(o: SweepOptions, base: dict[str, Any], sc, seconds: float, device) -> Result:
    """Rows (one per fit range, fitted when the curve ``sc`` exists) and the curve of a case
    whose ``base`` row holds its inputs, device and any error; ``seconds``: its wall time (s)."""
    curve = None
    if sc is not None:
        curve = sc.to_dict()
        base.update(
            final_contact_pixels=int(sc.n_contact_pixels[-1]),
            final_area_fraction=float(sc.contact_area[-1] / sc.apparent_area),
            Rt_measured_m=float(sc.Rt),
        )
    rows = []
    for mp, frac in fit_ranges(o):
        if mp is None:
            mp = 0 if curve is None else resolve_min_pixels(frac, base["final_contact_pixels"])
        row = {**base, "min_pixels": mp, "min_pixels_fraction": frac}
        if curve is not None:
            try:
                f = fit_power_law(sc, min_pixels=mp, depth_window=o.depth_window)
                row.update(
                    alpha=f.alpha,
                    beta=f.beta,
                    beta_contact_modulus=f.beta_contact_modulus,
                    r2=f.r2,
                    n_points=f.n_points,
                    fit_depth_min_m=f.depth_min,
                    fit_depth_max_m=f.depth_max,
                )
                found = check_fit(f, sc)  # not worth reading: kept, with fit_error and warnings
                row.update(fit_error=fit_error_text(found))
                if found:
                    row["warnings"] = _join_warnings(row.get("warnings"), found)
            except ValueError as exc:  # too few increments in this range: recorded, not dropped
                row.update(n_points=0, fit_error=str(exc))
        rows.append(row)
    stamp = datetime.now(timezone.utc).isoformat(timespec="milliseconds")
    for r in rows:
        r.update(seconds=seconds, finished_utc=stamp)
        r.setdefault("device", str(device))
        r.setdefault("device_name", None)
    return rows, curve


def _join_warnings(old: str | None, found: list) -> str:
    """The ``warnings`` column: a JSON list of ``{code, message, details}``."""
    return json.dumps(
        [*(json.loads(old) if old else []), *(w.to_dict() for w in found)], allow_nan=True
    )


def finish_batch(
    cases: list[Case], options: SweepOptions, curves, seconds: float, device: wp.context.Device
) -> list[Result]:
    """The results of ``cases`` from their batched truncation curves.

    Parameters
    ----------
    cases : list of Case
        The cases of one batch.
    options : SweepOptions
        Options shared by all cases.
    curves : list of TruncationCurve or None
        Their curves (:meth:`~warptrunc.sweep.batch.WMBatch.collect`); None: every case is
        computed by :func:`compute_case` instead.
    seconds : float
        The batch's wall time (s), shared equally between its cases.
    device : warp.context.Device
        The resolved device.

    Returns
    -------
    list of (rows, curve)
        As :func:`compute_case` on the same device; a case's ``seconds`` is its share of the
        batch plus its own fit time.
    """
    if curves is None:
        return [compute_case(c, options, device) for c in cases]
    o, share = options, seconds / max(1, len(cases))
    out = []
    for c, tc in zip(cases, curves, strict=True):
        t0 = time.perf_counter()
        base = base_row(c, o)
        base.update(device=str(device), device_name=str(device.name))
        sc = None
        try:
            sc = stiffness_curve(tc, o.material(), beta_prime=o.beta_prime)
        except Exception as exc:  # recorded, the sweep goes on
            base.update(error=f"{type(exc).__name__}: {exc}")
        out.append(_finish(o, base, sc, share + time.perf_counter() - t0, device))
    return out


@fill_doc(SHARED_DOCS)
def compute_many(
    cases: list[Case],
    options: SweepOptions,
    device=None,
    *,
    batch: bool | None = None,
    devices: Any = None,
) -> list[Result]:
    """:func:`compute_case` of every case, several surfaces per launch where that applies.

    Parameters
    ----------
    cases : list of Case
        The cases.
    options : SweepOptions
        Options shared by all cases.
    {warp_device}
    batch : bool, optional
        None: batch where :func:`~warptrunc.sweep.batch.batch_size` allows (CUDA, light cases
        of tile-sized grids); True: batch on the CPU too; False: one case at a time.
    devices : int, "auto" or list, optional
        Passed to :func:`compute_case` (elastic solves over several devices; such cases are
        never batched).

    Returns
    -------
    list of (rows, curve)
        As :func:`compute_case`, in the order of ``cases``.
    """
    dev = resolve_device(device)
    size = 1 if batch is False else batch_size(options, dev, force=bool(batch))
    if size <= 1 or len(cases) < 2:
        return [compute_case(c, options, dev, devices) for c in cases]
    return [r for rs in batched_results(cases, options, dev, min(size, len(cases))) for r in rs]


@fill_doc(SHARED_DOCS)
def run_inprocess(
    cases: list[Case],
    options: SweepOptions,
    sink: BatchSink,
    *,
    execution: SweepExecution | None = None,
    total: int | None = None,
    progress: bool = True,
    device: Any = None,
) -> None:
    """Run ``cases`` one after another in this process, handing the results to ``sink``.

    Parameters
    ----------
    cases : list of Case
        Cases to compute, in order.
    options : SweepOptions
        Options shared by all cases.
    sink : callable
        Takes a list of (rows, curve) results (:func:`compute_case`): one part of the store.
    execution : SweepExecution, optional
        ``shard_seconds``: hand results to ``sink`` once they hold about this much computing
        time (s; 0 hands over whatever finished while the previous part was written), at most
        :data:`MAX_SHARD` at once; ``devices``: the elastic solves over several devices
        (:func:`compute_case`). Default ``SweepExecution()``; its cluster fields are not
        used here.
    total : int, optional
        Cases of the whole grid (count), for the progress bar. Default ``len(cases)``.
    progress : bool
        Show a progress bar.
    {warp_device}

    Raises
    ------
    BaseException
        The first exception ``sink`` raised, re-raised here after the writer thread stopped.

    Notes
    -----
    ``sink`` (the store's :meth:`~warptrunc.sweep.store.Store.add_many`, which writes one part)
    runs in one background thread, so encoding and writing never hold up the device: the
    computing thread only queues results. Every computed case is written before this
    function returns or an exception (Ctrl-C included) propagates; a hard kill loses at most
    the last ``shard_seconds`` of work.
    """
    ex = SweepExecution() if execution is None else execution
    total = len(cases) if total is None else total
    shard_seconds, devices, max_shard = ex.shard_seconds, ex.devices, MAX_SHARD
    dev = str(resolve_device(device))
    q: queue.Queue = queue.Queue(maxsize=max_shard)
    failed: list[BaseException] = []
    done = object()

    with progress_bar(
        total=total,
        initial=total - len(cases),
        enabled=progress,
        desc=f"sweep [{dev}]",
        unit="case",
    ) as bar:

        def writer() -> None:
            pending: list = []
            work = 0.0
            while True:
                item = q.get()
                stop = item is done
                if not stop:
                    pending.append(item)
                    s = item[0][0].get("seconds")
                    work += s if isinstance(s, float) and s == s else 0.0
                    if len(pending) < max_shard and (
                        work < shard_seconds if shard_seconds > 0 else not q.empty()
                    ):
                        continue
                if pending and not failed:
                    try:
                        sink(pending)
                        bar.update(len(pending))
                    except BaseException as exc:  # re-raised in the computing thread
                        failed.append(exc)
                pending, work = [], 0.0
                if stop:
                    return

        th = threading.Thread(target=writer, name="warptrunc-store", daemon=True)
        th.start()
        try:
            size = batch_size(options, resolve_device(dev)) if len(cases) > 1 else 1
            if size > 1:
                for rs in batched_results(
                    cases, options, resolve_device(dev), min(size, len(cases))
                ):
                    for r in rs:
                        q.put(r)
                    if failed:
                        break
                    check_interrupt()  # a stop signal swallowed in a destructor
            for case in cases if size <= 1 else ():
                if failed:
                    break
                q.put(compute_case(case, options, dev, devices))
                check_interrupt()
        finally:
            q.put(done)
            th.join()
        if failed:
            raise failed[0]


def batched_results(cases: list[Case], options: SweepOptions, device, size: int):
    """Yield the results (:func:`compute_case`'s) of ``cases``, batch by batch.

    Parameters
    ----------
    cases : list of Case
        The cases, in order.
    options : SweepOptions
        Options shared by all cases (light cases: see
        :func:`~warptrunc.sweep.batch.batch_size`).
    device : warp.context.Device
        The resolved device.
    size : int
        Cases per batch (≥ 1).

    Yields
    ------
    list of (rows, curve)
        The results of one batch, in the order of ``cases``.

    Notes
    -----
    One thread keeps the device busy: batch i + 1 is scaled and batch i + 2 queued
    (:meth:`~warptrunc.sweep.batch.WMBatch.submit`) before the host fits batch i. A batch
    whose submission or scaling raises ValueError is computed case by case (each case records
    its own error); so is every case when the batch buffers do not fit the device's memory. A case's ``seconds`` is its share of its batch's time from submission to
    its curves, plus its own fit time.
    """
    try:
        wb = WMBatch(options, size, device, slots=2)
    except MemoryError:  # a small or busy GPU: one case at a time
        for c in cases:
            yield [compute_case(c, options, device)]
        return
    chunks = iter([cases[i : i + size] for i in range(0, len(cases), size)])
    pending: collections.deque = collections.deque()  # [chunk, slot or None, t0, scaled]

    def submit_next() -> None:
        if (chunk := next(chunks, None)) is not None:
            t0 = time.perf_counter()
            try:
                slot = wb.submit(chunk)
            except ValueError:  # a case out of range: compute_case records it
                slot = None
            pending.append([chunk, slot, t0, False])

    def scale_first() -> None:
        e = pending[0] if pending else None
        if e is not None and e[1] is not None and not e[3]:
            try:
                wb.scale(e[1])
                e[3] = True
            except ValueError:  # a flat surface
                wb.release(e[1])
                e[1] = None

    submit_next()
    scale_first()
    submit_next()
    while pending:
        chunk, slot, t0, _ = pending.popleft()
        curves = None if slot is None else wb.collect(slot)
        seconds = time.perf_counter() - t0
        scale_first()
        submit_next()
        yield finish_batch(chunk, options, curves, seconds, device)


@fill_doc(SHARED_DOCS)
def compute_shard(
    cases: list[Case],
    options: SweepOptions,
    device: str | None = None,
    curves: str | None = None,
    devices: Any = None,
) -> dict[str, Any]:
    """Run a shard of cases (one Dask task) and write it as one part of the store.

    Parameters
    ----------
    cases : list of Case
        Cases of this task.
    options : SweepOptions
        Options shared by all cases.
    {warp_device}
    curves : str, optional
        The store's ``curves/`` folder, on a filesystem this worker shares with the client;
        None (a sweep kept in memory) returns the rows without writing anything.
    devices : int, optional
        Devices of each elastic solve (:func:`compute_case`; in a worker of a device group,
        its group: :mod:`warptrunc.sweep.groups`).

    Returns
    -------
    dict
        ``part``: the part's file name (None without ``curves``); ``rows``: per case, its
        fit-range rows as stored in that part; ``seconds``: the task's time on this worker
        (s; None when an existing part was read instead); ``worker``: ``host:pid`` of this
        process (the client leaves each worker's first task out of its shard sizing).

    Notes
    -----
    The part's name is a function of the shard's cases
    (:func:`~warptrunc.sweep.curves.part_name`): a shard whose part exists already (an
    earlier attempt wrote it, and the client did not hear of it) is not computed again, and
    two attempts running at once write one part (the first rename wins, the other returns
    that part's rows).
    """
    t0, me = time.perf_counter(), f"{socket.gethostname()}:{os.getpid()}"
    if curves is None:
        rows = [r[0] for r in compute_many(cases, options, device, devices=devices)]
        return {"part": None, "rows": rows, "seconds": time.perf_counter() - t0, "worker": me}
    folder = Path(curves)
    name = part_name([c.case_id for c in cases], min(c.index for c in cases))
    if (folder / name).exists():
        held = part_rows(folder / name)
        if held is not None:
            return {"part": name, "rows": held, "seconds": None, "worker": me}
    results = compute_many(cases, options, device, devices=devices)
    name, held = write_part(folder, results)
    return {"part": name, "rows": held, "seconds": time.perf_counter() - t0, "worker": me}


def pinned_device(worker_name: Any, n_devices: int) -> str | None:
    """The CUDA device of a Dask worker: ``cuda:{index mod n_devices}``, or None.

    The index is a stable function of the worker's name, the same in every process and run
    (unlike :func:`hash`, which Python randomises per process): an integer name (a
    LocalCluster's workers are named 0..N-1) is the index; a name ending in digits
    (``"gpu-worker-3"``) uses that trailing number; any other name, the CRC-32 of its UTF-8
    text (:func:`zlib.crc32`).

    Parameters
    ----------
    worker_name : Any
        Dask worker name.
    n_devices : int
        CUDA devices (count).

    Returns
    -------
    str or None
        ``"cuda:<i>"``, or None when ``n_devices`` ≤ 0.
    """
    if n_devices <= 0:
        return None
    return f"cuda:{worker_index(worker_name) % n_devices}"


def worker_index(worker_name: Any) -> int:
    """A stable non-negative index for a Dask worker name (see :func:`pinned_device`).

    Parameters
    ----------
    worker_name : Any
        Dask worker name: an integer, a string ending in digits, or any other object.

    Returns
    -------
    int
        The integer name (its absolute value), the trailing number of the name, or the
        CRC-32 of ``str(worker_name)`` encoded as UTF-8.
    """
    try:
        return abs(int(worker_name))
    except (TypeError, ValueError):
        pass
    text = str(worker_name)
    digits = re.search(r"(\d+)$", text)
    if digits is not None:
        return int(digits.group(1))
    return zlib.crc32(text.encode("utf-8"))


def failed_case(case: Case, options: SweepOptions, why: str):
    """Rows of a case that could not be computed (its task was lost too often).

    Parameters
    ----------
    case : Case
        The case.
    options : SweepOptions
        Options of the sweep (they give the fit ranges and the input columns).
    why : str
        Reason, stored in the ``error`` column.

    Returns
    -------
    rows : list of dict
        One row per fit range, ``seconds`` NaN, no device; ``min_pixels`` 0 for a relative
        fit range.
    curve : None
        No curve.
    """
    base = base_row(case, options)
    stamp = datetime.now(timezone.utc).isoformat(timespec="milliseconds")
    base.update(error=why, seconds=np.nan, finished_utc=stamp, device=None, device_name=None)
    return [
        {**base, "min_pixels": mp or 0, "min_pixels_fraction": f} for mp, f in fit_ranges(options)
    ], None
