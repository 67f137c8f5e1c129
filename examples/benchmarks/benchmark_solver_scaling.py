# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: the contact solver's scaling with the map size (time, iterations, memory).

What it shows
    Per map size N and dtype, on a D = 2.5 WM map (L = 1 mm, W_r = 100 µm, R_t = 10 µm, free
    boundary): the cold solve at δ = 0.20·R_t (from zero pressure) and the warm one at
    δ = 0.21·R_t from that solution — time, iterations, convolutions, time per convolution
    against the cuFFT floor measured in the same run (CuPy: one forward rfft2 and one inverse
    irfft2 of the zero-padded (2N)² grid; skipped without CuPy, and on the CPU scipy.fft) —
    and the peak memory of the solver (Warp's allocation tracker: the peak of the bytes Warp
    allocated from before the solver was made to after the warm solve and Barber's stiffness
    solve, host allocations included: the 1 B/px read-back of the contact mask in Barber's
    solve is one; on CUDA also the pool's
    high-water mark, ``wp.get_mempool_used_mem_high``, which is process-wide and never falls)
    against :meth:`ContactSolver.memory_bytes`.

    A time budget (``--budget``, default 480 s) guards the whole run: before each size the
    script predicts its time from the previous one (×4.5 per doubling of N) and stops, printing
    what was measured, when it would not fit.

Run
    python examples/benchmarks/benchmark_solver_scaling.py --quick --out /tmp/scaling
    python examples/benchmarks/benchmark_solver_scaling.py --device cuda:0 --out $OUT/scaling
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import statistics
import time
from pathlib import Path

import numpy as np
import scipy.fft
import warp as wp
from _common import git_commit, machine_fields

import warptrunc
from warptrunc.contact import ContactSolver, SolverSettings
from warptrunc.wm import wm_surface

E_STAR = 70e9 / (1 - 0.33**2)
COLD, WARM = 0.20, 0.21


def _tracker():
    """Warp's native allocation tracker (peak of the bytes Warp allocated, all devices)."""
    from warp._src.context import runtime

    return runtime.core


def fft_floor(n: int, dtype: str, dev, repeats: int) -> float | None:
    """Median time (s) of one forward + one inverse real FFT of the zero-padded (2n)² grid."""
    if dev.is_cuda:
        try:
            import cupy as cp
            import cupyx.scipy.fft as cfft
        except ImportError:
            return None
        with cp.cuda.Device(dev.ordinal):
            x = cp.zeros((2 * n, 2 * n), dtype=dtype)
            x[:n, :n] = 1.0
            ts = []
            for _ in range(repeats + 1):
                cp.cuda.Device().synchronize()
                t0 = time.perf_counter()
                y = cfft.irfft2(cfft.rfft2(x), s=x.shape)
                cp.cuda.Device().synchronize()
                ts.append(time.perf_counter() - t0)
            del x, y
            cp.fft.config.get_plan_cache().clear()
            cp.get_default_memory_pool().free_all_blocks()
        return statistics.median(ts[1:])
    x = np.zeros((2 * n, 2 * n), dtype=dtype)
    x[:n, :n] = 1.0
    ts = []
    for _ in range(repeats + 1):
        t0 = time.perf_counter()
        scipy.fft.irfft2(
            scipy.fft.rfft2(x, workers=os.cpu_count()), s=x.shape, workers=os.cpu_count()
        )
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts[1:])


def run_one(
    s,
    dtype: str,
    dev,
    algorithm: str = "bccg",
    fft_plan: str = "auto",
    precondition_above: float | None = None,
    pentol: float | None = None,
    direct_max: int | None = None,
    loop: str | None = None,
) -> dict:
    """Make a solver, solve cold at 0.20·R_t and warm at 0.21·R_t; times, counts, memory."""
    h = s.heights  # the host copy of a device map: outside the window (Warp's tracker counts
    # host allocations too)
    gc.collect()
    wp.synchronize_device(dev)
    core = _tracker()
    with wp.ScopedMemoryTracker("scaling", print=False):
        core.wp_alloc_tracker_reset()
        base = core.wp_alloc_tracker_get_current_bytes()
        t0 = time.perf_counter()
        settings = SolverSettings(
            dtype=dtype,
            algorithm=algorithm,
            fft_plan=fft_plan,
            precondition_above=precondition_above,
            pentol=pentol,
            direct_max=direct_max,
            **({} if loop is None else {"loop": loop}),
        )
        solver = ContactSolver(h, (s.dx, s.dy), E_STAR, settings=settings, device=dev)
        wp.synchronize_device(dev)
        t1 = time.perf_counter()
        cold = solver.solve(COLD * s.Rt)
        wp.synchronize_device(dev)
        t2 = time.perf_counter()
        warm = solver.solve(WARM * s.Rt)
        wp.synchronize_device(dev)
        t3 = time.perf_counter()
        k, _, k_ok = solver.punch_stiffness()  # its one more map is part of the modelled peak
        wp.synchronize_device(dev)
        t4 = time.perf_counter()
        peak = int(core.wp_alloc_tracker_get_peak_bytes() - base)
        fft_work = solver.hs.fft_work.capacity if solver.hs.fft_work is not None else 0
        plan = solver.fft_plan
        graph_error = solver.graph_error()
        del solver
    gc.collect()
    return {
        "setup_s": t1 - t0,
        "cold_s": t2 - t1,
        "warm_s": t3 - t2,
        "punch_s": t4 - t3,
        "stiffness_N_per_m": k,
        "punch_converged": bool(k_ok),
        "cold_iterations": cold.n_iterations,
        "cold_convolutions": cold.n_convolutions,
        "warm_iterations": warm.n_iterations,
        "warm_convolutions": warm.n_convolutions,
        "converged": bool(cold.converged and warm.converged),
        "load_N": warm.load,
        "n_contact": warm.n_contact,
        "peak_bytes": peak,
        "cufft_work_bytes": int(fft_work),
        "fft_plan": plan,
        "loop": solver_loop(loop),
        "graph_error": graph_error,
    }


def solver_loop(loop: str | None) -> str:
    """The solver's ``SolverSettings.loop`` (its default when None)."""
    from warptrunc.contact import SolverSettings

    return SolverSettings().loop if loop is None else loop


def _threshold(text: str) -> float | None:
    """A ``--precondition-above`` value: a fraction, or "auto" (None)."""
    return None if text == "auto" else float(text)


def main(argv: list[str] | None = None) -> int:
    """Run the benchmark; print a table, write JSON to ``--out``."""
    p = argparse.ArgumentParser(
        description=__doc__.split("\n")[0], formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    p.add_argument(
        "--n",
        type=int,
        nargs="+",
        default=None,
        help="map sizes N (default 2048 … 32768 on CUDA, 128 256 512 on the CPU)",
    )
    p.add_argument(
        "--dtype", nargs="+", default=["float32", "float64"], choices=["float32", "float64"]
    )
    p.add_argument("--device", default=None, help="Warp device (cpu, cuda:0)")
    p.add_argument(
        "--algorithm",
        nargs="+",
        default=["bccg"],
        choices=["bccg", "pk"],
        help="the solver's iteration(s) (SolverSettings.algorithm)",
    )
    p.add_argument(
        "--fft-plan",
        default="auto",
        choices=["auto", "pruned", "full"],
        help="the free half-space's cuFFT plans (SolverSettings.fft_plan)",
    )
    p.add_argument(
        "--precondition-above",
        type=_threshold,
        nargs="+",
        default=[None],
        help="BCCG's preconditioner threshold(s) (SolverSettings.precondition_above; "
        "0 = always, auto = the default rule)",
    )
    p.add_argument(
        "--pentol-rms",
        type=float,
        default=None,
        help="a fixed relative tolerance: pentol = this × the map's rms height "
        "(default: the solver's, rms/(10·N), which tightens with N)",
    )
    p.add_argument(
        "--direct-max",
        type=int,
        nargs="+",
        default=[None],
        help="largest number of projection corrections summed directly "
        "(SolverSettings.direct_max; default auto)",
    )
    p.add_argument(
        "--wc-pixels",
        type=float,
        default=None,
        help="fixed content: the cut-off W_c as this many pixels of the first N "
        "(default: W_c = 2 pixels at every N, finer pixels add roughness)",
    )
    p.add_argument(
        "--loop",
        default=None,
        choices=["host", "device", "graph"],
        help="SolverSettings.loop (default: the solver's)",
    )
    p.add_argument("--repeats", type=int, default=3, help="repeats of the FFT floor (median)")
    p.add_argument("--budget", type=float, default=480.0, help="time budget of the run (s)")
    p.add_argument("--quick", action="store_true", help="small sizes (128, 256), float32 only")
    p.add_argument("--no-show", action="store_true", help="accepted for the examples' runner")
    p.add_argument("--seed", type=int, default=0, help="WM phase seed")
    p.add_argument("--out", type=Path, default=None, help="folder for scaling.json")
    a = p.parse_args(argv)
    start = time.perf_counter()
    dev = warptrunc.resolve_device(a.device)
    name = wp.get_device(dev).name
    sizes = a.n or (
        [128, 256]
        if a.quick
        else [2048, 4096, 8192, 10240, 16384, 32768]
        if dev.is_cuda
        else [128, 256, 512]
    )
    dtypes = ["float32"] if a.quick else a.dtype
    print(f"device {dev} ({name}), warp {wp.config.version}, commit {git_commit()}", flush=True)
    # fixed content: W_c the same length at every N; else None (2 pixels, wm_surface's default)
    wc = {"Wc": a.wc_pixels * 1e-3 / sizes[0]} if a.wc_pixels else {}
    rows: list[dict] = []
    last: tuple[int, float] | None = None
    stopped = None
    for n in sizes:
        for dtype, algorithm, pa, dm in [
            (d, al, pa, dm)
            for d in dtypes
            for al in a.algorithm
            for pa in a.precondition_above
            for dm in a.direct_max
        ]:
            if last is not None:
                predicted = last[1] * 4.5 ** np.log2(n / last[0])
                left = a.budget - (time.perf_counter() - start)
                if predicted > left:
                    stopped = f"stopped before N={n} {dtype}: predicted {predicted:.0f} s, {left:.0f} s left"
                    break
            need = ContactSolver.memory_bytes(
                (n, n), "free", dtype, cuda=dev.is_cuda, algorithm=algorithm
            )
            t0 = time.perf_counter()
            try:
                s = wm_surface(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6, seed=a.seed, device=dev, **wc)
                pentol = None
                if a.pentol_rms is not None:
                    pentol = a.pentol_rms * float(np.std(s.heights))
                r = run_one(s, dtype, dev, algorithm, a.fft_plan, pa, pentol, dm, a.loop)
            except MemoryError as exc:
                print(f"N={n} {dtype}: {exc}", flush=True)
                rows.append(
                    {
                        "n": n,
                        "dtype": dtype,
                        "algorithm": algorithm,
                        "memory_model_bytes": need,
                        "error": str(exc),
                    }
                )
                continue
            floor = fft_floor(n, dtype, dev, a.repeats)
            del s
            need = ContactSolver.memory_bytes(
                (n, n),
                "free",
                dtype,
                cuda=dev.is_cuda,
                algorithm=algorithm,
                fft_plan=r["fft_plan"],
                device=dev if dev.is_cuda else None,
            )
            r.update(
                n=n,
                dtype=dtype,
                algorithm=algorithm,
                memory_model_bytes=need,
                fft_floor_s=floor,
                precondition_above=pa,
                pentol_m=pentol,
                direct_max=dm,
                Wc_m=wc.get("Wc"),
            )
            conv = r["warm_convolutions"]
            r["warm_per_convolution_s"] = r["warm_s"] / conv if conv else None
            r["per_convolution_over_floor"] = (
                r["warm_per_convolution_s"] / floor if floor and conv else None
            )
            if dev.is_cuda:
                r["mempool_high_water_bytes"] = int(wp.get_mempool_used_mem_high(dev))
            rows.append(r)
            last = (n, time.perf_counter() - t0)
            ratio = r["per_convolution_over_floor"]
            print(
                f"N={n:6d} {dtype} {algorithm} pc>{'auto' if pa is None else pa}{'' if dm is None else f' direct_max {dm}'}: cold {r['cold_s']:8.3f} s ({r['cold_iterations']} it, "
                f"{r['cold_convolutions']} conv), warm {r['warm_s']:8.3f} s "
                f"({r['warm_iterations']} it, {conv} conv), "
                f"{(r['warm_per_convolution_s'] or 0) * 1e3:8.2f} ms/conv"
                + (f" = {ratio:.2f}× FFT floor ({floor * 1e3:.2f} ms)" if ratio else ", no floor")
                + f"; peak {r['peak_bytes'] / n**2:.1f} B/px against the model "
                f"{need / n**2:.1f} B/px ({r['peak_bytes'] / need:.3f}; fft_plan {r['fft_plan']}); "
                f"setup {r['setup_s']:.2f} s; converged {r['converged']}",
                flush=True,
            )
        if stopped:
            break
    if stopped:
        print(stopped, flush=True)
    if a.out is not None:
        doc = {
            **machine_fields(dev),
            "surface": "wm_surface(D=2.5, Wr=100 µm, L=1 mm, Rt=10 µm), free boundary",
            "Wc_m": wc.get("Wc"),
            "cold_fraction_of_Rt": COLD,
            "warm_fraction_of_Rt": WARM,
            "stopped": stopped,
            "rows": rows,
        }
        a.out.mkdir(parents=True, exist_ok=True)
        (a.out / "scaling.json").write_text(json.dumps(doc, indent=1) + "\n")
        print(f"wrote {a.out / 'scaling.json'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
