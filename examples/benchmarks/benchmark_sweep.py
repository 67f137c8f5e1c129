# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: sweep throughput (surfaces/s) against the kernel loop, and scaling with workers.

What it shows
    For each grid size n, K cases (D = 2.5, δ = 0.01, seeds 0..K-1, 200 increments, fit range
    min_pixels = 10; with ``--bem-fractions`` an elastic solve per case) are run by up to three
    kinds of run, all in one process and printed as one table that names the device:

    - ``kernel``: the reference, the bare loop generate → truncate → fit (→ elastic solve) of
      the same cases with no store, no rows, no thread (``wp.synchronize_device`` at the end);
    - ``inproc``: :func:`warptrunc.sweep.run_sweep` in this process into a fresh store (the
      writer thread writes the parts while the device computes); ratio = inproc / kernel;
    - ``N`` (from ``--workers``): a LocalCluster of N worker processes, one thread each, started
      and warmed up (one case per worker: kernels loaded) before the clock starts, then
      ``run_sweep(..., scheduler=client)`` into a fresh store; ratio = rate / (N × rate of 1
      worker), the parallel efficiency (1.0 = linear). With ``--device cuda:0`` every worker
      uses that GPU (two workers sharing one GPU); with ``--device cpu`` the workers use
      CPU cores only, worker i pinned to core i and single-threaded (``--pin-cores``, on by
      default for the CPU: the CPU paths size their thread pools by ``os.cpu_count()``, so
      without it one worker would already use every core).

    Rates are K / wall time of the timed part; every timed run is preceded by an untimed
    warm-up case on the same device (kernels compiled and loaded).

Run
    # the H100: light cases, in-process against the kernel loop
    python examples/benchmarks/benchmark_sweep.py --n 2048 10240 --cases 200
    # 16 CPU cores: elastic 512² cases on 1, 2, 4, 8 CPU workers
    python examples/benchmarks/benchmark_sweep.py --device cpu --n 512 --cases 64 \\
        --bem-fractions 0.05 0.1 0.2 --runs workers --workers 1 2 4 8
    # one GPU shared by 2 workers against 1 worker
    python examples/benchmarks/benchmark_sweep.py --device cuda:0 --n 512 --cases 128 \\
        --bem-fractions 0.05 0.1 0.2 --runs workers --workers 1 2
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import tempfile
import time
from pathlib import Path

D, DELTA = 2.5, 0.01


def _opts(n: int, increments: int, bem: list[float]) -> dict:
    return dict(n=n, increments=increments, min_pixels=(10,), bem_fractions=tuple(bem))


def kernel_loop(n: int, cases: int, device, increments: int, bem: list[float]) -> float:
    """Wall time (s) of the bare loop over ``cases`` surfaces (after one warm-up surface)."""
    import warp as wp

    from warptrunc.stiffness import fit_power_law, stiffness_curve
    from warptrunc.sweep import SweepOptions
    from warptrunc.sweep.engines import elastic_record
    from warptrunc.truncation import truncate
    from warptrunc.wm import wm_surface

    o = SweepOptions(**_opts(n, increments, bem))
    mat = o.material()

    def one(seed):
        s = wm_surface(D, o.Wr, L=o.L, n=n, Rt=DELTA * o.Wr, seed=seed, device=device)
        sc = stiffness_curve(truncate(s, increments, max_depth_fraction=o.max_depth_fraction,
                                      device=device), mat)  # fmt: skip
        try:
            fit_power_law(sc, min_pixels=10)
        except ValueError:  # too few increments in the range: the sweep records it too
            pass
        if bem and (why := elastic_record(s, sc, o, device)["bem_error"]) is not None:
            raise RuntimeError(f"elastic solve failed: {why}")

    one(10**6)
    wp.synchronize_device(device)
    t0 = time.perf_counter()
    for seed in range(cases):
        one(seed)
    wp.synchronize_device(device)
    return time.perf_counter() - t0


def _check(df) -> None:
    if df["error"].notna().any():
        raise RuntimeError(f"failed cases: {df['error'].dropna().unique()[:3]}")
    if "bem_error" in df and df["bem_error"].notna().any():  # e.g. CuPy missing on a GPU
        raise RuntimeError(f"failed elastic solves: {df['bem_error'].dropna().unique()[:3]}")


def inprocess(n: int, cases: int, device, increments: int, bem: list[float]) -> float:
    """Wall time (s) of run_sweep in this process into a fresh store (after a warm-up case)."""
    from warptrunc.sweep import SweepGrid, run_sweep

    opts = _opts(n, increments, bem)
    run_sweep(SweepGrid([D], [DELTA], [10**6]), None, progress=False, device=device, **opts)
    tmp = Path(tempfile.mkdtemp(prefix="warptrunc-bench-sweep-"))
    try:
        t0 = time.perf_counter()
        df = run_sweep(SweepGrid([D], [DELTA], list(range(cases))), tmp / "store",
                       progress=False, device=device, **opts)  # fmt: skip
        wall = time.perf_counter() - t0
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    _check(df)
    return wall


def _pin_plugin():
    """A worker plugin: worker i runs on CPU core i (mod the cores) and reports one CPU.

    ``os.cpu_count`` is what the CPU paths size their thread pools by (scipy.fft's
    ``workers``, the threaded WM product); reporting 1 makes each worker single-threaded, so
    N workers use N cores and one worker is the one-core baseline.
    """
    from distributed import WorkerPlugin

    class PinCores(WorkerPlugin):
        name = "benchmark-pin-cores"
        idempotent = True

        def setup(self, worker):
            cores = sorted(os.sched_getaffinity(0))
            os.sched_setaffinity(0, {cores[int(worker.name) % len(cores)]})
            os.cpu_count = lambda: 1

    return PinCores()


def workers_run(n: int, cases: int, workers: int, device, increments: int, bem: list[float],
                pin: bool):  # fmt: skip
    """Wall time (s) of run_sweep on a warmed-up LocalCluster of ``workers`` processes."""
    import logging

    from distributed import Client, LocalCluster

    from warptrunc.sweep import SweepGrid, SweepOptions, run_sweep
    from warptrunc.sweep.cluster import PinDevice
    from warptrunc.sweep.engines import compute_case

    opts = _opts(n, increments, bem)
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=":0", silence_logs=logging.ERROR)  # fmt: skip
    client = Client(cluster)
    tmp = Path(tempfile.mkdtemp(prefix="warptrunc-bench-sweep-"))
    try:
        if device is None:
            client.register_plugin(PinDevice())
        if pin:
            client.register_plugin(_pin_plugin())
        o = SweepOptions(**opts)
        warm = SweepGrid([D], [DELTA], list(range(10**6, 10**6 + workers))).cases(o)
        names = list(client.scheduler_info()["workers"])
        futs = [client.submit(compute_case, c, o, device, workers=[w], pure=False)
                for c, w in zip(warm, names, strict=True)]  # fmt: skip
        client.gather(futs)  # every worker has loaded its kernels
        t0 = time.perf_counter()
        df = run_sweep(SweepGrid([D], [DELTA], list(range(cases))), tmp / "store",
                       scheduler=client, progress=False, device=device, **opts)  # fmt: skip
        wall = time.perf_counter() - t0
        devices = sorted(df["device"].unique())
    finally:
        client.close()
        cluster.close()
        shutil.rmtree(tmp, ignore_errors=True)
    _check(df)
    return wall, devices


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--n", type=int, nargs="+", default=[512], help="pixels per side")
    ap.add_argument("--cases", type=int, default=16, help="surfaces per run")
    ap.add_argument("--runs", nargs="+", default=["kernel", "inproc"],
                    choices=("kernel", "inproc", "workers"),
                    help="which runs: the kernel loop, run_sweep in process, --workers")  # fmt: skip
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2],
                    help="LocalCluster sizes for --runs workers")  # fmt: skip
    ap.add_argument("--increments", type=int, default=200, help="depth increments")
    ap.add_argument("--bem-fractions", type=float, nargs="+", default=[],
                    help="elastic solves per case at δ = f·R_t (as warptrunc sweep)")  # fmt: skip
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ... (default: resolved)")
    ap.add_argument("--pin-cores", action=argparse.BooleanOptionalAction, default=None,
                    help="worker i on CPU core i, single-threaded (default: on with --device cpu)")
    ap.add_argument("--json", type=Path, default=None, help="append the results here")
    args = ap.parse_args(argv)
    import warp as wp
    from _common import git_commit

    from warptrunc import __version__
    from warptrunc._device import resolve_device

    dev = resolve_device(args.device)
    device = args.device if args.device is not None else None
    if "workers" not in args.runs:
        device = str(dev)
    results = []
    for n in args.n:
        if "kernel" in args.runs:
            results.append(dict(n=n, run="kernel", workers=0,
                                wall_s=kernel_loop(n, args.cases, str(dev), args.increments,
                                                   args.bem_fractions)))  # fmt: skip
        if "inproc" in args.runs:
            results.append(dict(n=n, run="inproc", workers=0,
                                wall_s=inprocess(n, args.cases, str(dev), args.increments,
                                                 args.bem_fractions)))  # fmt: skip
        if "workers" in args.runs:
            for w in args.workers:
                pin = args.pin_cores if args.pin_cores is not None else str(dev) == "cpu"
                wall, devs = workers_run(n, args.cases, w, device, args.increments,
                                         args.bem_fractions, pin)  # fmt: skip
                results.append(dict(n=n, run=f"{w} workers", workers=w, wall_s=wall,
                                    devices=devs))  # fmt: skip
    for r in results:
        r["surfaces_per_s"] = args.cases / r["wall_s"]
        ref = [q for q in results if q["n"] == r["n"] and q["run"] == ("kernel" if r["run"] == "inproc" else "1 workers")]
        if r["run"] == "inproc" and ref:
            r["ratio"] = r["surfaces_per_s"] / ref[0]["surfaces_per_s"]
        elif r["workers"] and ref:
            r["ratio"] = r["surfaces_per_s"] / (r["workers"] * ref[0]["surfaces_per_s"])
        r.update(cases=args.cases, bem_fractions=args.bem_fractions, device=str(dev),
                 device_name=str(dev.name), host=platform.node(), cpus=os.cpu_count(),
                 warp=wp.config.version, warptrunc=__version__, commit=git_commit())  # fmt: skip
    bem = f", elastic solves at {args.bem_fractions} R_t" if args.bem_fractions else ""
    print(f"\ndevice {dev} ({dev.name}); host {platform.node()}, {os.cpu_count()} CPUs; "
          f"warp {wp.config.version}; {args.cases} cases per run, {args.increments} increments{bem}")  # fmt: skip
    print("ratio: inproc / kernel loop; N workers: rate / (N × rate of 1 worker)\n")
    print(f"| {'n':>6} | {'run':<10} | {'devices':<16} | {'wall s':>8} | {'surfaces/s':>10} | {'ratio':>6} |")
    print(f"|{'-' * 8}|{'-' * 12}|{'-' * 18}|{'-' * 10}|{'-' * 12}|{'-' * 8}|")
    for r in results:
        devs = ",".join(r.get("devices", [str(dev)]))
        ratio = f"{r['ratio']:.2f}" if "ratio" in r else ""
        print(f"| {r['n']:>6} | {r['run']:<10} | {devs:<16} | {r['wall_s']:>8.2f} | "
              f"{r['surfaces_per_s']:>10.1f} | {ratio:>6} |")  # fmt: skip
    if args.json:
        with args.json.open("a") as fh:
            for r in results:
                fh.write(json.dumps(r) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
