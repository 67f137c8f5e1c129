# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: the elastic contact solver (warptrunc.contact) against its floors and references.

What it shows
    For each ``--n``: a D = 2.5 WM map (``wm_surface``, L = 1 mm, R_t = 10 µm), solved at
    δ = 0.15·R_t (cold) and then δ = 0.2·R_t warm-started from it, in float64 and float32, free
    half-space. Reports the median time of the warm solve over ``--repeats`` (after a warm-up
    that compiles the kernels), its iterations and convolutions, time per iteration, F and A,
    the memory estimate of :meth:`ContactSolver.memory_bytes` and the measured memory (CUDA: the
    device memory in use with the solver alive after its warm solve, above what was in use before
    it was made, pools emptied first; also the high-water mark of Warp's pool; CPU: the growth of
    the process's peak RSS). Between sizes and dtypes CuPy's and Warp's pools and CuPy's FFT plan
    cache are emptied, so that sizes do not starve each other.

    Floors in the same run: one zero-padded (2N)² convolution (rfft2 → multiply → irfft2) plus
    three elementwise passes over the padded grid, with CuPy on CUDA and ``scipy.fft`` on the CPU.
    The target on a GPU is a time per iteration ≤ 1.3× that floor.

    On the CPU, ContactMechanics (the ``bem`` extra) solves the same two approaches with the same
    tolerances; its time, iterations, F and A and the ratio warptrunc/ContactMechanics are printed
    (``--no-reference`` skips it; it is slow above 512²).

Run
    python examples/benchmarks/benchmark_contact.py --device cpu --n 256 512
    python examples/benchmarks/benchmark_contact.py --device cuda:0 --n 2048 4096 8192 10240 \\
        --json $OUT/contact.json
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import resource
import statistics
import time
import warnings
from pathlib import Path

import numpy as np
import scipy.fft
import warp as wp
from _common import git_commit, machine_fields

import warptrunc
from warptrunc.contact import ContactSolver, SolverSettings, default_pentol, influence_spectrum
from warptrunc.wm import wm_surface

E_STAR = 70e9 / (1 - 0.33**2)
FRACTIONS = (0.15, 0.2)


def _sync(dev) -> None:
    wp.synchronize_device(dev)


def _rss_bytes() -> int:
    """Peak resident set size of this process so far (bytes)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def free_pools(dev) -> None:
    """Return cached device memory: Python garbage, CuPy's pools and FFT plans, Warp's pool."""
    gc.collect()
    if dev.is_cuda:
        import cupy as cp

        wp.synchronize_device(dev)
        cp.fft.config.get_plan_cache().clear()
        cp.get_default_memory_pool().free_all_blocks()
        cp.get_default_pinned_memory_pool().free_all_blocks()
        wp.synchronize_device(dev)  # Warp's pool (release threshold 0) gives back at a sync


def device_used_bytes(dev) -> int:
    """Bytes in use on a CUDA device (cudaMemGetInfo: total − free, all processes)."""
    import cupy as cp

    with cp.cuda.Device(dev.ordinal):
        free, total = cp.cuda.runtime.memGetInfo()
    return int(total - free)


DIRECT_MAX: int | str = "auto"


def run_solver(s, dtype: str, dev) -> dict:
    """One cold solve at 0.15·R_t and the warm-started one at 0.2·R_t, timed; on CUDA also the
    device memory the solver holds after them."""
    free_pools(dev)
    base = device_used_bytes(dev) if dev.is_cuda else 0
    settings = SolverSettings(dtype=dtype, direct_max=DIRECT_MAX)
    solver = ContactSolver(s.heights, (s.dx, s.dy), E_STAR, settings=settings, device=dev)
    _sync(dev)
    t0 = time.perf_counter()
    solver.solve(FRACTIONS[0] * s.Rt)
    _sync(dev)
    t1 = time.perf_counter()
    info = solver.solve(FRACTIONS[1] * s.Rt)
    _sync(dev)
    t2 = time.perf_counter()
    used = device_used_bytes(dev) - base if dev.is_cuda else 0
    del solver
    free_pools(dev)
    return {"cold": t1 - t0, "warm": t2 - t1, "info": info, "device_bytes": used}


def summarise_solver(s, dtype: str, dev, runs: list[dict], rss0: int) -> dict:
    """Medians of the timed runs, iterations and memory."""
    info = runs[-1]["info"]
    out = {
        "dtype": dtype,
        "time_warm_solve_s": statistics.median(r["warm"] for r in runs),
        "time_cold_solve_s": statistics.median(r["cold"] for r in runs),
        "n_iterations": info.n_iterations,
        "n_convolutions": info.n_convolutions,
        "converged": bool(info.converged),
        "load_N": info.load,
        "area_m2": info.n_contact * s.pixel_area,
        "memory_estimate_bytes": ContactSolver.memory_bytes(s.shape, "free", dtype),
    }
    out["time_per_iteration_s"] = out["time_warm_solve_s"] / info.n_iterations
    if dev.is_cuda:
        import cupy as cp

        out["device_bytes"] = max(r["device_bytes"] for r in runs)
        out["warp_pool_high_water_bytes"] = int(wp.get_mempool_used_mem_high(dev))  # process
        out["cupy_pool_bytes"] = int(cp.get_default_memory_pool().total_bytes())
    else:
        out["peak_rss_growth_bytes"] = max(0, _rss_bytes() - rss0)
    return out


def conv_floor(n: int, dtype: str, dev, repeats: int) -> float:
    """Median time (s) of one zero-padded (2n)² convolution plus three elementwise passes."""
    w = influence_spectrum((n, n), (1e-3 / n, 1e-3 / n), E_STAR, "free").astype(dtype)
    rng = np.random.default_rng(0)
    if dev.is_cuda:
        import cupy as cp
        import cupyx.scipy.fft as cfft

        with cp.cuda.Device(dev.ordinal):
            x = cp.zeros((2 * n, 2 * n), dtype=dtype)
            x[:n, :n] = cp.asarray(rng.random((n, n)), dtype=dtype)
            wd = cp.asarray(w)
            u = cp.zeros_like(x)

            def step():
                y = cfft.irfft2(cfft.rfft2(x) * wd, s=x.shape)
                u[...] = u - 0.5 * y  # pass 1 (read u, y; write u)
                float(cp.abs(y).max())  # pass 2 (reduction, sync)
                x[:n, :n] = x[:n, :n] * 1.0  # pass 3 (map quarter, read+write)

            step()
            cp.cuda.Device().synchronize()
            ts = []
            for _ in range(repeats):
                t0 = time.perf_counter()
                step()
                cp.cuda.Device().synchronize()
                ts.append(time.perf_counter() - t0)
            del x, wd, u
        free_pools(dev)
        return statistics.median(ts)
    x = np.zeros((2 * n, 2 * n), dtype=dtype)
    x[:n, :n] = rng.random((n, n))
    u = np.zeros_like(x)
    workers = os.cpu_count()
    ts = []
    for _ in range(repeats + 1):
        t0 = time.perf_counter()
        y = scipy.fft.irfft2(scipy.fft.rfft2(x, workers=workers) * w, s=x.shape, workers=workers)
        u -= 0.5 * y
        float(np.abs(y).max())
        x[:n, :n] *= 1.0
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts[1:])


def contactmechanics_system(s):
    """ContactMechanics' system for the map, or None without the ``bem`` extra."""
    try:
        from warptrunc.contact.check import require_bem

        Free, _, System, Topography = require_bem()
    except ImportError:
        return None
    h = np.ascontiguousarray(s.heights.T, dtype=np.float64)
    return System(Free(h.shape, E_STAR, (s.lx, s.ly)), Topography(h, physical_sizes=(s.lx, s.ly)))


def run_contactmechanics(s, system) -> dict:
    """ContactMechanics on the same map and approaches (CPU, float64), same tolerances."""
    h = np.ascontiguousarray(s.heights.T, dtype=np.float64)
    kw = {"pentol": default_pentol(h), "forcetol": 1e-5 * E_STAR * s.pixel_area, "maxiter": 10000}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        r0 = system.minimize_proxy(offset=FRACTIONS[0] * s.Rt - h.max(), **kw)
        t1 = time.perf_counter()
        r = system.minimize_proxy(
            offset=FRACTIONS[1] * s.Rt - h.max(), initial_displacements=r0.x, **kw
        )
        t2 = time.perf_counter()
    return {
        "time_cold_solve_s": t1 - t0,
        "time_warm_solve_s": t2 - t1,
        "n_iterations": int(r.nit),
        "converged": bool(r.success),
        "load_N": float(r.jac.sum()),
        "area_m2": int(np.count_nonzero(r.jac > 0)) * s.pixel_area,
    }


def main(argv: list[str] | None = None) -> int:
    """Run the benchmark; print a table and optionally write JSON."""
    p = argparse.ArgumentParser(
        description=__doc__.split("\n")[0], formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    p.add_argument("--n", type=int, nargs="+", default=[256, 512], help="map sizes N (N × N)")
    p.add_argument("--device", default=None, help="Warp device (cpu, cuda:0)")
    p.add_argument("--repeats", type=int, default=3, help="timed repeats (median)")
    p.add_argument(
        "--dtype", nargs="+", default=["float64", "float32"], choices=["float64", "float32"]
    )
    p.add_argument("--no-reference", action="store_true", help="skip ContactMechanics on the CPU")
    p.add_argument(
        "--direct-max",
        default="auto",
        help="ContactSolver(direct_max=...): changed forces summed directly (int or auto)",
    )
    p.add_argument("--json", type=Path, default=None, help="write all figures to this JSON file")
    a = p.parse_args(argv)
    global DIRECT_MAX
    DIRECT_MAX = a.direct_max if a.direct_max == "auto" else int(a.direct_max)
    dev = warptrunc.resolve_device(a.device)
    name = wp.get_device(dev).name
    print(f"device {dev} ({name}), warp {wp.config.version}, commit {git_commit()}")
    if dev.is_cuda and wp.is_mempool_enabled(dev):
        wp.set_mempool_release_threshold(dev, 0)  # freed blocks go back to the driver at syncs
    rows = []
    for n in a.n:
        s = wm_surface(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6, seed=0, device="cpu")
        system = None if (dev.is_cuda or a.no_reference) else contactmechanics_system(s)
        rss0 = _rss_bytes()
        free_pools(dev)
        for dtype in a.dtype:
            run_solver(s, dtype, dev)  # warm-up: compiles the kernels, makes the FFT plans
        runs: dict[str, list] = {dtype: [] for dtype in a.dtype}
        refs = []
        for _ in range(a.repeats):  # interleaved, so that load from other processes hits both
            for dtype in a.dtype:
                runs[dtype].append(run_solver(s, dtype, dev))
            if system is not None:
                refs.append(run_contactmechanics(s, system))
        ref = None
        if refs:
            ref = dict(refs[-1])
            for key in ("time_cold_solve_s", "time_warm_solve_s"):
                ref[key] = statistics.median(x[key] for x in refs)
            ref["time_per_iteration_s"] = ref["time_warm_solve_s"] / max(1, ref["n_iterations"])
        for dtype in a.dtype:
            r = summarise_solver(s, dtype, dev, runs[dtype], rss0)
            r["n"] = n
            r["conv_floor_s"] = conv_floor(n, dtype, dev, a.repeats)
            r["iteration_over_floor"] = r["time_per_iteration_s"] / r["conv_floor_s"]
            if ref is not None:
                r["contactmechanics"] = ref
                r["time_ratio_to_contactmechanics"] = (
                    r["time_warm_solve_s"] / ref["time_warm_solve_s"]
                )
                r["total_ratio_to_contactmechanics"] = (
                    r["time_warm_solve_s"] + r["time_cold_solve_s"]
                ) / (ref["time_warm_solve_s"] + ref["time_cold_solve_s"])
                r["load_rel_diff"] = r["load_N"] / ref["load_N"] - 1
                r["area_rel_diff"] = r["area_m2"] / ref["area_m2"] - 1
            rows.append(r)
            line = (
                f"n={n:6d} {dtype}: warm solve {r['time_warm_solve_s'] * 1e3:9.1f} ms "
                f"(cold {r['time_cold_solve_s'] * 1e3:8.1f} ms), {r['n_iterations']} it, "
                f"{r['n_convolutions']} conv, {r['time_per_iteration_s'] * 1e3:7.2f} ms/it = "
                f"{r['iteration_over_floor']:.2f}× floor ({r['conv_floor_s'] * 1e3:.2f} ms), "
                f"mem est {r['memory_estimate_bytes'] / 2**20:.0f} MiB"
            )
            if dev.is_cuda:
                line += f", used {r['device_bytes'] / 2**20:.0f} MiB"
            if ref is not None:
                line += (
                    f"; ContactMechanics warm {ref['time_warm_solve_s'] * 1e3:.1f} ms "
                    f"(cold {ref['time_cold_solve_s'] * 1e3:.1f} ms), {ref['n_iterations']} it, "
                    f"ratio {r['time_ratio_to_contactmechanics']:.2f} (both solves "
                    f"{r['total_ratio_to_contactmechanics']:.2f}), ΔF/F {r['load_rel_diff']:.1e}, "
                    f"ΔA/A {r['area_rel_diff']:.1e}"
                )
            print(line, flush=True)
        del runs, refs, system, s
        free_pools(dev)
    if a.json:
        doc = {
            **machine_fields(dev),
            "cpu_count": os.cpu_count(),
            "surface": "wm_surface(D=2.5, Wr=100 µm, L=1 mm, Rt=10 µm, seed=0)",
            "fractions_of_Rt": FRACTIONS,
            "rows": rows,
        }
        a.json.parent.mkdir(parents=True, exist_ok=True)
        a.json.write_text(json.dumps(doc, indent=1) + "\n")
        print(f"wrote {a.json}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
