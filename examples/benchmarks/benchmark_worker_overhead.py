#!/usr/bin/env python3
# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Where a Dask worker's extra cost on an indentation part comes from.

On Dask workers the indentation stage's parts can cost more than in process, with the same
iterations and bit-identical results (on 4 × H100 1.31× on 2 workers and 1.44× on 4:
``benchmarks/records/indentation_workers_h100x4_cc1dcf5.json``). This benchmark runs the same parts
(one surface's elastic part and one elastic–plastic part of the paper profile's stage at
``--n``) one after another, each timed, in these settings, on one device:

``main``
    in this process, in its main thread (as ``reproduce`` in process);
``thread``
    in this process, in a second thread (as a Dask worker runs its tasks);
``worker``
    on a one-worker local cluster opened as ``reproduce --workers`` opens it
    (:func:`warptrunc.sweep.cluster.open_client`);
``worker-bare``
    the same with Dask's worker profiler and system monitor off and the nanny's other
    pre-spawn variables (``OMP_NUM_THREADS``, ``MKL_NUM_THREADS``, ``OPENBLAS_NUM_THREADS``) unset;
``process``
    in a plain child process (``multiprocessing``, spawn), no Dask.

The workers bind themselves to the CPUs near their GPU (``PinDevice``; ``WARPTRUNC_CPU_AFFINITY=0``
turns that off) and ``--bind near`` binds this process the same way, so the settings compare
bound with bound or, with both off, unbound with unbound; each run records its CPUs.

Each setting runs ``--repeat`` times (the first is a warm-up, not counted); ``--profile-top K``
also records the K most expensive functions (cProfile, cumulative and own time) of one more
run, not counted, in ``main`` and in ``worker``. Prints a table and writes
``worker_overhead.json`` in ``--out``. Records: ``benchmarks/records/worker_overhead_h100x4_12e7a94.json``
(workers unbound, with Dask's profiler) and ``worker_overhead_h100x4_1b64d9c.json`` (unbound, then
bound; ``examples/gpu_checks/indent_workers.sh probe`` runs it so).

    python examples/benchmarks/benchmark_worker_overhead.py --n 1536 --device cuda:0
    python examples/benchmarks/benchmark_worker_overhead.py --n 128 --device cpu   # a dry run
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import threading
import time
from pathlib import Path

SETTINGS = ("main", "thread", "worker", "worker-bare", "process")


def _stage(n: int):
    from warptrunc.reproduce import PROFILES

    return PROFILES["paper"].indentation.replace(n=int(n))


def run_parts(n: int, device: str | None, surface: str, hardness: float, top: int = 0) -> dict:
    """Run the elastic part then the elastic–plastic part (punch 0, realisation 0, sweep
    design) of ``surface``; their seconds, and cProfile's ``top`` rows when ``top`` > 0."""
    import cProfile
    import io
    import pstats

    from warptrunc.reproduce.indentation.pieces import Part, run_part

    p = _stage(n)
    parts = [
        Part(surface, "sweep", float("inf"), None, 0, 0),
        Part(surface, "sweep", float(hardness), None, 0, 0),
    ]
    prof = cProfile.Profile() if top else None
    out: dict = {
        "thread": threading.current_thread().name,
        "pid": os.getpid(),
        "env": {
            k: os.environ.get(k)
            for k in (
                "MALLOC_TRIM_THRESHOLD_",
                "OMP_NUM_THREADS",
                "MKL_NUM_THREADS",
                "OPENBLAS_NUM_THREADS",
            )
        },
    }
    t0 = time.perf_counter()
    if prof:
        prof.enable()
    recs = [run_part(p, part, device=device) for part in parts]
    if prof:
        prof.disable()
    out["wall_s"] = time.perf_counter() - t0
    out["parts"] = [
        {
            k: r["seconds"][k]
            for k in ("part_s", "elastic_plastic_s", "refinement_s")
            if k in r["seconds"]
        }
        for r in recs
    ]
    out["device"] = recs[0]["device"]
    if hasattr(os, "sched_getaffinity"):  # where this thread may run (bound or not)
        from warptrunc.sweep._affinity import format_cpulist

        out["cpus"] = format_cpulist(os.sched_getaffinity(0))
    if prof:
        s = io.StringIO()
        pstats.Stats(prof, stream=s).sort_stats("cumulative").print_stats(top)
        out["profile"] = s.getvalue()
        s = io.StringIO()
        pstats.Stats(prof, stream=s).sort_stats("tottime").print_stats(top)
        out["profile_tottime"] = s.getvalue()
    return out


def _in_thread(*args) -> dict:
    box: dict = {}
    t = threading.Thread(target=lambda: box.update(run_parts(*args)), name="task-thread")
    t.start()
    t.join()
    return box


def _worker(args, bare: bool):
    import dask

    from warptrunc.sweep.cluster import open_client

    cfg = {}
    if bare:
        pre = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}) or {})
        for k in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
            if k not in os.environ:
                pre[k] = None
        cfg = {
            "distributed.worker.profile.enabled": False,
            "distributed.admin.system-monitor.interval": "3600s",
            "distributed.nanny.pre-spawn-environ": pre,
        }
    results = []
    with (
        dask.config.set(cfg),
        open_client(workers=1, progress=False, warm_contact=True) as (c, _, _),
    ):
        for _ in range(args.repeat):
            fut = c.submit(
                run_parts, args.n, args.device, args.surface, args.hardness, 0, pure=False
            )
            results.append(fut.result())
        if args.profile_top and not bare:  # one more run, profiled, not counted
            results.append(
                c.submit(
                    run_parts,
                    args.n,
                    args.device,
                    args.surface,
                    args.hardness,
                    args.profile_top,
                    pure=False,
                ).result()
            )
    return results


def _process(args):
    import multiprocessing as mp

    ctx = mp.get_context("spawn")
    with ctx.Pool(1) as pool:
        return [
            pool.apply(run_parts, (args.n, args.device, args.surface, args.hardness))
            for _ in range(args.repeat)
        ]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument(
        "--n",
        type=int,
        default=1536,
        help="pixels per side of the paper profile's indentation maps (indentation.n)",
    )
    ap.add_argument("--device", default=None, help="Warp device (default: cuda:0, else cpu)")
    ap.add_argument("--surface", default="SMATs", help="Table 1 surface (default SMATs)")
    ap.add_argument(
        "--hardness", type=float, default=1e9, help="H of the elastic–plastic part (Pa)"
    )
    ap.add_argument("--repeat", type=int, default=3, help="runs per setting, the first a warm-up")
    ap.add_argument("--settings", nargs="+", default=list(SETTINGS), choices=SETTINGS)
    ap.add_argument("--profile-top", type=int, default=25, help="cProfile rows (0: none)")
    ap.add_argument("--out", default="worker_overhead_out", help="results folder")
    ap.add_argument(
        "--bind",
        choices=("none", "near"),
        default="none",
        help="near: bind this process to the CPUs near --device first (the workers "
        "bind themselves unless WARPTRUNC_CPU_AFFINITY=0)",
    )
    args = ap.parse_args(argv)
    if args.device is None:
        from warptrunc._support.device import cuda_device_count

        args.device = "cuda:0" if cuda_device_count() > 0 else "cpu"
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    bound = None
    if args.bind == "near" and str(args.device).startswith("cuda"):
        from warptrunc.sweep._affinity import bind_near, format_cpulist

        ordinal = int(str(args.device).partition(":")[2] or 0)
        bound = bind_near([ordinal])
        print(f"bound to CPUs {format_cpulist(bound) if bound else '(unchanged)'}", flush=True)
    rec = {
        "benchmark": "worker_overhead",
        "commit": os.environ.get("WARPTRUNC_GIT_COMMIT"),
        "host": platform.node(),
        "started_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        "args": vars(args),
        "settings": {},
        "bound": None if not bound else sorted(bound),
        "cpu_affinity_env": os.environ.get("WARPTRUNC_CPU_AFFINITY"),
    }
    for s in args.settings:
        t0 = time.perf_counter()
        if s == "main":
            runs = [
                run_parts(args.n, args.device, args.surface, args.hardness, 0)
                for _ in range(args.repeat)
            ]
            if args.profile_top:  # one more run, profiled, not counted
                runs.append(
                    run_parts(args.n, args.device, args.surface, args.hardness, args.profile_top)
                )
        elif s == "thread":
            runs = [
                _in_thread(args.n, args.device, args.surface, args.hardness, 0)
                for _ in range(args.repeat)
            ]
        elif s == "worker":
            runs = _worker(args, bare=False)
        elif s == "worker-bare":
            runs = _worker(args, bare=True)
        else:
            runs = _process(args)
        counted = [r for r in runs if "profile" not in r]
        counted = counted[1:] if len(counted) > 1 else counted
        walls = [r["wall_s"] for r in counted]
        rec["settings"][s] = {
            "runs": runs,
            "wall_s": walls,
            "best_s": min(walls),
            "setting_s": time.perf_counter() - t0,
        }
        print(
            f"{s:12s} best {min(walls):7.2f} s  runs " + " ".join(f"{w:.2f}" for w in walls),
            flush=True,
        )
        (out / "worker_overhead.json").write_text(json.dumps(rec, indent=1, default=str))
    base = rec["settings"].get("main", {}).get("best_s")
    if base:
        for s, v in rec["settings"].items():
            print(f"{s:12s} {v['best_s'] / base:5.2f}× main")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
