# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: WM generation and truncation analysis, against a reference in the same process.

What it shows
    Median times of warptrunc's generation (tables + product, then R_t scaling) and truncation
    (min/max + atomic histogram over 200 increments) next to a reference on the same surface:
    NumPy float64 and float32/BLAS on the CPU, CuPy (cuBLAS, ``cupy.histogram``) on a GPU.
    Reports the accuracy of the float32 heights against a float64 evaluation.

    End to end (``--e2e``, on by default): one surface as a sweep runs it, ``wm_surface`` →
    ``truncate`` (200 increments) → ``stiffness_curve`` → ``fit_power_law``, median ms per surface
    over ``--repeats`` surfaces (different seeds), with the time of each stage;
    ``island_curve`` at 200 depths with and without statistics; ``describe`` and the four D
    methods (``fractal_dimensions``) on the device-resident surface. On CUDA, CuPy references in
    the same process where they exist (moments, 2-D float64 FFT).

Run
    python examples/benchmarks/benchmark_pipeline.py --device cpu --n 1024 4096
    python examples/benchmarks/benchmark_pipeline.py --device cuda:0 --n 10240 --json $OUT/bench.json
"""

from __future__ import annotations

import json
import platform
import statistics
import time
from pathlib import Path

import numpy as np
import warp as wp
from _common import bench_parser, git_commit, timeit

import warptrunc
from warptrunc.descriptors import describe
from warptrunc.fractal import fractal_dimensions
from warptrunc.islands import IslandSettings, island_curve
from warptrunc.stiffness import fit_power_law, stiffness_curve
from warptrunc.truncation import truncate
from warptrunc.wm import generate_on_device, wm_heights, wm_product, wm_spec, wm_surface, wm_tables


def tables(xp, spec, dtype):
    """Row and column tables of the separable WM sum, built with NumPy or CuPy."""
    x = xp.arange(spec.nx, dtype=xp.float64) * spec.dx
    y = xp.arange(spec.ny, dtype=xp.float64) * spec.dy
    kx, ky, al, w = (xp.asarray(v) for v in (spec.kx, spec.ky, spec.alpha, spec.w))
    a = kx[:, None] * x[None, :] + al[:, None]
    q = xp.concatenate([xp.cos(a), xp.sin(a)]).astype(dtype)
    b = y[:, None] * ky[None, :]
    p = xp.concatenate([w * xp.cos(b), -w * xp.sin(b)], axis=1).astype(dtype)
    return p, q


def run_case(n: int, device, repeats: int) -> dict:
    spec = wm_spec(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6)
    sync = lambda: wp.synchronize_device(device)  # noqa: E731
    res = {"n": n, "terms": spec.n_terms, "device": str(device), "device_name": device.name}
    res["warp_tables_and_product_s"] = timeit(lambda: wm_heights(spec, device), repeats, sync)
    p, q, c0 = wm_tables(spec, device)
    zbuf = wp.empty((spec.ny, spec.nx), dtype=wp.float32, device=device)
    res["warp_tables_s"] = timeit(lambda: wm_tables(spec, device), repeats, sync)
    res["warp_product_s"] = timeit(lambda: wm_product(p, q, zbuf), repeats, sync)
    p = q = zbuf = None  # free the buffers before the next measurement
    res["warp_generate_on_device_s"] = timeit(
        lambda: generate_on_device(spec, device), repeats, sync
    )
    res["warp_generate_s"] = timeit(
        lambda: wm_surface(2.5, 100e-6, L=1e-3, n=n, device=device), repeats, sync
    )
    s = wm_surface(2.5, 100e-6, L=1e-3, n=n, device=device)
    res["warp_truncate_s"] = timeit(lambda: truncate(s, 200, device=device), repeats, sync)
    c = truncate(s, 200, device=device)
    z = s.heights
    if device.is_cuda:
        try:
            import cupy as cp
        except ImportError:
            return res
        csync = cp.cuda.Device().synchronize
        p32, q32 = tables(cp, spec, cp.float32)
        res["cupy_sgemm_s"] = timeit(lambda: p32 @ q32, repeats, csync)
        res["cupy_tables_and_sgemm_s"] = timeit(
            lambda: (lambda pq: pq[0] @ pq[1])(tables(cp, spec, cp.float32)), repeats, csync
        )
        p64, q64 = tables(cp, spec, cp.float64)
        ref = p64 @ q64
        raw = wm_heights(spec, device)
        c0 = float(np.sum(spec.w * np.cos(spec.alpha)))
        err = cp.abs(cp.asarray(raw.numpy()) - (c0 - ref)).max() / (ref.max() - ref.min())
        res["max_rel_err_vs_float64"] = float(err)
        zc = cp.asarray(z)
        top = zc.max()
        thr = cp.asarray(c.threshold)

        def cupy_trunc():
            depth_bins = cp.concatenate([thr[::-1], top[None] + 1])
            h, _ = cp.histogram(zc, bins=depth_bins)
            return cp.cumsum(h[::-1])

        res["cupy_histogram_truncate_s"] = timeit(cupy_trunc, repeats, csync)
        res["product_ratio_warp_over_cublas"] = res["warp_product_s"] / res["cupy_sgemm_s"]
        return res
    # CPU references: float64 NumPy evaluation (tables + BLAS dgemm) and float32 BLAS sgemm
    p64, q64 = tables(np, spec, np.float64)
    res["numpy_float64_generate_s"] = timeit(
        lambda: (lambda pq: pq[0] @ pq[1])(tables(np, spec, np.float64)),
        max(1, repeats // 2),
        lambda: None,
    )
    p32, q32 = tables(np, spec, np.float32)
    res["numpy_sgemm_s"] = timeit(lambda: p32 @ q32, repeats, lambda: None)
    res["numpy_tables_s"] = timeit(lambda: tables(np, spec, np.float32), repeats, lambda: None)
    c0 = float(np.sum(spec.w * np.cos(spec.alpha)))
    raw = wm_heights(spec, device).numpy()
    ref = c0 - p64 @ q64
    res["max_rel_err_vs_float64"] = float(np.abs(raw - ref).max() / np.ptp(ref))
    thr = c.threshold
    res["numpy_searchsorted_truncate_s"] = timeit(
        lambda: np.searchsorted(np.sort(z, axis=None), thr[::-1], side="left"), 1, lambda: None
    )
    res["numpy_histogram_truncate_s"] = timeit(
        lambda: np.histogram(z, bins=np.concatenate([thr[::-1], [z.max() + 1]])), 1, lambda: None
    )
    res["product_ratio_warp_over_numpy_sgemm"] = res["warp_product_s"] / res["numpy_sgemm_s"]
    return res


def run_end_to_end(n: int, device, repeats: int) -> dict:
    """One surface end to end, island curve with statistics, descriptors and four D methods."""
    sync = lambda: wp.synchronize_device(device)  # noqa: E731
    res: dict = {"n": n, "device": str(device), "device_name": device.name}
    gen = lambda seed: wm_surface(2.5, 100e-6, L=1e-3, n=n, seed=seed, device=device)  # noqa: E731
    one = lambda seed: fit_power_law(stiffness_curve(truncate(gen(seed), 200, device=device)))  # noqa: E731
    one(0)  # warm-up: kernels loaded, memory pool filled
    sync()
    stages: dict[str, list[float]] = {"total": [], "generate": [], "truncate": [], "fit": []}
    for seed in range(1, repeats + 1):
        t0 = time.perf_counter()
        s = gen(seed)
        t1 = time.perf_counter()
        c = truncate(s, 200, device=device)
        t2 = time.perf_counter()
        fit_power_law(stiffness_curve(c))
        sync()
        t3 = time.perf_counter()
        for k, v in zip(stages, (t3 - t0, t1 - t0, t2 - t1, t3 - t2), strict=True):
            stages[k].append(v)
        del s, c
    for k, v in stages.items():
        res[f"e2e_{k}_s"] = statistics.median(v)
    s = gen(0)
    rep = max(1, repeats // 2)
    res["island_curve_stats_200_s"] = timeit(
        lambda: island_curve(s, settings=IslandSettings(snapshots=None), device=device), rep, sync
    )
    res["island_curve_counts_200_s"] = timeit(
        lambda: island_curve(s, settings=IslandSettings(statistics=False), device=device),
        rep,
        sync,
    )
    res["describe_s"] = timeit(lambda: describe(s), rep, sync)
    res["fractal_dimensions_s"] = timeit(lambda: fractal_dimensions(s, device=device), rep, sync)
    res["describe_and_four_D_s"] = res["describe_s"] + res["fractal_dimensions_s"]
    # False when everything ran on the device (None: a warptrunc without device surfaces)
    res["surface_host_copy_made"] = getattr(s, "has_host_copy", None)
    if device.is_cuda:
        try:
            import cupy as cp
        except ImportError:
            res["cupy"] = None
            return res
        res["cupy"] = cp.__version__
        csync = cp.cuda.Device().synchronize
        zc = cp.asarray(s.device_heights() if hasattr(s, "device_heights") else s.heights)

        def moments():
            z = zc.astype(cp.float64)
            d = z - z.mean()
            return [
                float(v) for v in (cp.abs(d).mean(), (d**2).mean(), (d**3).mean(), (d**4).mean())
            ]

        res["cupy_moments_s"] = timeit(moments, rep, csync)
        res["cupy_fft2_float64_s"] = timeit(lambda: cp.fft.fft2(zc.astype(cp.float64)), rep, csync)
    return res


def main(argv=None) -> int:
    ap = bench_parser(__doc__)
    ap.add_argument("--quick", action="store_true", help="one 256² case, 2 repeats")
    ap.add_argument("--json", type=Path, default=None, help="also write the JSON to this file")
    ap.add_argument(
        "--no-e2e", action="store_true", help="skip the end-to-end, island and descriptor timings"
    )
    ap.add_argument(
        "--no-kernels", action="store_true", help="skip the per-kernel timings and references"
    )
    ap.add_argument("--no-show", action="store_true", help="(no figures; accepted for symmetry)")
    args = ap.parse_args(argv)
    device = warptrunc.resolve_device(args.device)
    sizes, repeats = ([256], 2) if args.quick else (args.n, args.repeats)
    meta = {
        "warp": wp.config.version,
        "numpy": np.__version__,
        "host": platform.processor() or platform.machine(),
        "commit": git_commit(),
    }
    results, e2e = [], []
    for n in sizes:
        if not args.no_kernels:
            r = run_case(n, device, repeats)
            results.append(r)
            print(json.dumps(r), flush=True)
        if not args.no_e2e:
            r = run_end_to_end(n, device, repeats)
            e2e.append(r)
            print(json.dumps(r), flush=True)
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / f"benchmark_pipeline_{str(device).replace(':', '')}.json"
    doc = json.dumps({"meta": meta, "results": results, "end_to_end": e2e}, indent=2) + "\n"
    path.write_text(doc)
    if args.json is not None:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(doc)
    print(f"\n{'n':>6} {'terms':>5} {'product':>10} {'generate':>10} {'truncate':>10}  reference")
    for r in results:
        ref = (
            f"cuBLAS {r.get('cupy_sgemm_s', float('nan')) * 1e3:.2f} ms, cupy.histogram "
            f"{r.get('cupy_histogram_truncate_s', float('nan')) * 1e3:.2f} ms"
            if device.is_cuda
            else f"numpy sgemm {r['numpy_sgemm_s'] * 1e3:.1f} ms, float64 {r['numpy_float64_generate_s'] * 1e3:.0f} ms, "
            f"np.histogram {r['numpy_histogram_truncate_s'] * 1e3:.0f} ms"
        )
        print(
            f"{r['n']:>6} {r['terms']:>5} {r['warp_product_s'] * 1e3:>8.2f}ms {r['warp_generate_s'] * 1e3:>8.2f}ms "
            f"{r['warp_truncate_s'] * 1e3:>8.2f}ms  {ref}; err {r.get('max_rel_err_vs_float64', float('nan')):.1e}"
        )
    if e2e:
        print(
            f"\n{'n':>6} {'e2e/surface':>12} {'generate':>10} {'truncate':>10} {'fit':>8} "
            f"{'islands+stats':>14} {'counts':>9} {'describe+4D':>12}"
        )
    for r in e2e:
        ms = lambda k, r=r: r[k] * 1e3  # noqa: E731
        print(
            f"{r['n']:>6} {ms('e2e_total_s'):>10.2f}ms {ms('e2e_generate_s'):>8.2f}ms "
            f"{ms('e2e_truncate_s'):>8.2f}ms {ms('e2e_fit_s'):>6.2f}ms "
            f"{ms('island_curve_stats_200_s'):>12.2f}ms {ms('island_curve_counts_200_s'):>7.2f}ms "
            f"{ms('describe_and_four_D_s'):>10.1f}ms"
        )
    print(f"wrote {path}" + (f" and {args.json}" if args.json else ""))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
