# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: generation + truncation of large maps, in memory (past 2³¹ pixels) and streamed.

What it shows
    For one n × n WM surface (defaults of ``wm_surface``: D = 2.5, W_r = 100 µm, L = 1 mm,
    R_t = 10 µm, 200 increments to 0.1·R_t), the wall time of
    - ``device``: generation on the device + truncation on the device array (no host copy);
    - ``surface``: ``truncate(wm_surface(...))``, the user path (includes the host copy);
    - ``stream``: ``truncate(spec, stream=True)`` (two passes over row bands, never the whole map);
    each after one warm-up run (kernels compiled and loaded), with the peak memory of the
    Warp memory pool (CUDA) and the peak resident host memory of the process. When more than
    one path runs, it checks that their counts are equal.
    ``--path auto`` runs ``device`` when the map fits in free memory, else ``stream``.

Run
    python examples/benchmarks/benchmark_large.py --n 32768 --path device surface stream --json out.json
    python examples/benchmarks/benchmark_large.py --n 131072 --path auto
"""

from __future__ import annotations

import argparse
import json
import platform
import resource
import time

import numpy as np
import warp as wp
from _common import git_commit

import warptrunc
from warptrunc.truncation import truncate
from warptrunc.truncation.curve import depth_grid, depth_thresholds, height_range, histogram_bands
from warptrunc.truncation.stream import fits_in_memory
from warptrunc.wm import generate_on_device, wm_spec, wm_surface

N_INCREMENTS = 200


def run_device(spec, device):
    """Generate on the device and truncate the device array; returns the counts."""
    z, _scale = generate_on_device(spec, device)
    lo, hi = height_range(z, device)
    depth = depth_grid(float(np.float64(hi) - np.float64(lo)), N_INCREMENTS)
    t, _, _, _, inv_step = depth_thresholds(None, depth, device, (lo, hi))
    return np.cumsum(histogram_bands(z, t, hi, inv_step, device, deep=False))  # sync point


def run_surface(spec, device):
    s = wm_surface(
        spec.D, spec.Wr, L=(spec.Lx, spec.Ly), n=(spec.nx, spec.ny), seed=spec.seed, device=device
    )
    return truncate(s, N_INCREMENTS, device=device).n_contact_pixels


def run_stream(spec, device):
    return truncate(spec, N_INCREMENTS, stream=True, device=device).n_contact_pixels


RUNS = {"device": run_device, "surface": run_surface, "stream": run_stream}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--n", type=int, default=4096, help="pixels per side")
    ap.add_argument("--path", nargs="+", default=["auto"], choices=[*RUNS, "auto"])
    ap.add_argument("--device", default=None)
    ap.add_argument("--repeat", type=int, default=1, help="timed runs after the warm-up")
    ap.add_argument("--no-warmup", action="store_true", help="time the first run only")
    ap.add_argument("--json", default=None, help="write the results here")
    args = ap.parse_args()
    device = warptrunc.resolve_device(args.device)
    spec = wm_spec(n=args.n)
    fits = fits_in_memory(spec, device)
    paths = [("device" if fits else "stream") if p == "auto" else p for p in args.path]
    rows, counts = [], {}
    for path in paths:
        fn = RUNS[path]
        times = []
        for i in range((0 if args.no_warmup else 1) + args.repeat):
            if device.is_cuda:
                wp.synchronize_device(device)
            t0 = time.perf_counter()
            c = fn(spec, device)
            if device.is_cuda:
                wp.synchronize_device(device)
            if i > 0 or args.no_warmup:
                times.append(time.perf_counter() - t0)
        counts[path] = np.asarray(c)
        row = {
            "n": args.n,
            "pixels": args.n**2,
            "path": path,
            "fits_in_memory": fits,
            "seconds": min(times),
            "seconds_all": times,
            "final_contact_pixels": int(c[-1]),
        }
        if device.is_cuda:
            row["mempool_high_GiB"] = wp.get_mempool_used_mem_high(device) / 2**30
            row["free_GiB_after"] = device.free_memory / 2**30
        row["host_maxrss_GiB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20
        print(json.dumps(row))
        rows.append(row)
    first = next(iter(counts.values()))
    equal = all(np.array_equal(first, c) for c in counts.values())
    out = {
        "device": str(device),
        "device_name": getattr(device, "name", ""),
        "host": platform.node(),
        "commit": git_commit(),
        "n_terms": spec.n_terms,
        "counts_equal_across_paths": equal,
        "rows": rows,
    }
    print(f"counts equal across {list(counts)}: {equal}")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=2)
    if not equal:
        raise SystemExit("counts differ between paths")


if __name__ == "__main__":
    main()
