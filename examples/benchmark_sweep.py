# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: sweep throughput (surfaces per second) in-process and on a local Dask cluster.

What it shows
    For each grid size n, K cases (D = 2.5, δ = 0.01, seeds 0..K-1, 200 increments, fit range
    min_pixels = 10) run through :func:`warptrunc.sweep.run_sweep` into a fresh result store,
    in this process and with ``--workers N`` (a LocalCluster, one worker per GPU). Everything
    a user pays is inside: generation, truncation, fits, the Parquet writes, the transfer of
    results to the client. Two rates per run:

    - wall: K / (wall time of run_sweep), including cluster start-up and warm-up;
    - steady: (K − w) / (t_K − t_w), from the finish stamps of the cases, leaving out the first
      w cases (w = number of workers: one per worker, which pays kernel loading) — the rate
      a long sweep approaches.

    In-process runs get one untimed warm-up case first (kernels compiled and loaded).

Run
    python examples/benchmark_sweep.py --device cpu --n 512 --cases 16 --workers 0 2
    python examples/benchmark_sweep.py --n 2048 10240 --cases 40 --workers 0 2   # on 2 GPUs
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


def one(n: int, cases: int, workers: int, device, increments: int, chunk_size=None,
        worker_writes=None) -> dict:
    from warptrunc.sweep import SweepGrid, run_sweep

    opts = dict(n=n, increments=increments, min_pixels=(10,))
    if workers == 0:  # warm-up outside the timing
        run_sweep(SweepGrid([2.5], [0.01], [10**6]), None, progress=False, device=device, **opts)
    tmp = Path(tempfile.mkdtemp(prefix="warptrunc-bench-sweep-"))
    try:
        t0 = time.perf_counter()
        df = run_sweep(
            SweepGrid([2.5], [0.01], list(range(cases))), tmp / "store", progress=False,
            workers=workers or None, device=device, **opts,
            **(dict(chunk_size=chunk_size, worker_writes=worker_writes) if workers else {}),
        )  # fmt: skip
        wall = time.perf_counter() - t0
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if df["error"].notna().any():
        raise RuntimeError(f"failed cases: {df['error'].dropna().unique()[:3]}")
    import pandas as pd

    per_case = df.drop_duplicates("case_id")
    stamps = pd.to_datetime(per_case["finished_utc"]).sort_values().reset_index(drop=True)
    w = max(workers, 1)
    span = (stamps.iloc[-1] - stamps.iloc[w - 1]).total_seconds()
    return {
        "n": n, "cases": cases, "workers": workers, "devices": sorted(df["device"].unique()),
        "device_name": str(df["device_name"].iloc[0]), "wall_s": wall,
        "wall_surfaces_per_s": cases / wall,
        "steady_surfaces_per_s": (cases - w) / span if span > 0 else float("nan"),
        "median_case_s": float(per_case["seconds"].median()),
    }  # fmt: skip


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--n", type=int, nargs="+", default=[512], help="pixels per side")
    ap.add_argument("--cases", type=int, default=16, help="surfaces per run")
    ap.add_argument("--workers", type=int, nargs="+", default=[0, 2],
                    help="0 = in-process; N = LocalCluster of N workers")  # fmt: skip
    ap.add_argument("--increments", type=int, default=200, help="depth increments")
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ... (default: resolved)")
    ap.add_argument("--chunk-size", type=int, default=None,
                    help="cases per Dask task (default: adaptive)")
    ap.add_argument("--worker-writes", action=argparse.BooleanOptionalAction, default=None,
                    help="workers write the curve files (default: on for a LocalCluster on GPUs)")
    ap.add_argument("--json", type=Path, default=None, help="append the results here")
    args = ap.parse_args(argv)
    from warptrunc import __version__
    from warptrunc._bench import git_commit

    results = []
    for n in args.n:
        for w in args.workers:
            r = one(n, args.cases, w, args.device, args.increments, args.chunk_size,
                    args.worker_writes)
            r.update(host=platform.node(), cpus=os.cpu_count(), warptrunc=__version__,
                     commit=git_commit())  # fmt: skip
            results.append(r)
            mode = "in-process" if w == 0 else f"{w} workers"
            print(f"n={n:6d} {mode:>11s} on {','.join(r['devices'])} ({r['device_name']}): "
                  f"{r['steady_surfaces_per_s']:8.3f} surfaces/s steady, "
                  f"{r['wall_surfaces_per_s']:8.3f} wall ({args.cases} cases in {r['wall_s']:.1f} s; "
                  f"median case {r['median_case_s'] * 1e3:.1f} ms)", flush=True)  # fmt: skip
        base = [r for r in results if r["n"] == n and r["workers"] == 0]
        for r in results:
            if base and r["n"] == n and r["workers"] > 0:
                print(f"n={n:6d} speed-up with {r['workers']} workers: "
                      f"{r['steady_surfaces_per_s'] / base[0]['steady_surfaces_per_s']:.2f}× steady, "
                      f"{r['wall_surfaces_per_s'] / base[0]['wall_surfaces_per_s']:.2f}× wall")  # fmt: skip
    if args.json:
        with args.json.open("a") as fh:
            for r in results:
                fh.write(json.dumps(r) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
