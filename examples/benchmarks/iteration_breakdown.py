# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: where one BCCG iteration's time goes, and the loop with one read-back against the
loop with one per reduction.

What it shows
    Per map size N (D = 2.5 WM map, L = 1 mm, W_r = 100 µm, R_t = 10 µm, free boundary, as the
    scaling benchmark): the warm solve (δ = 0.21·R_t after a cold one at 0.20·R_t) with
    ``SolverSettings(loop="host")`` (four to five read-backs per iteration) and ``loop="device"``
    (one) and ``loop="graph"`` (one, the steady iterations replayed from a CUDA graph), each in
    a solver of its own: time, iterations, convolutions, time per iteration and
    per convolution against the FFT floor of the scaling benchmark (CuPy rfft2 + irfft2 of the
    padded grid) measured in the same run; then the parts of an iteration timed alone on the
    device (CUDA events, median of repeats): one convolution K·t and one K⁻¹·r (transforms and
    spectral product), each lane kernel of the iteration, a fold with its one-thread kernel,
    the read-back of the scalars (round trip, queue empty) and the host's time to launch a
    kernel. Their sum per iteration (with the solve's convolutions per iteration) is the
    device's busy time; the warm solve's time per iteration minus it is what launches and
    read-backs leave idle.

Run
    python examples/benchmarks/iteration_breakdown.py --device cuda:0 --n 2048 4096 8192 16384 \
        --out $OUT/breakdown
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

import numpy as np
import warp as wp
from _common import git_commit
from benchmark_solver_scaling import COLD, E_STAR, WARM, fft_floor
from warptrunc.kernels.contact import bccg as _kb
from warptrunc.kernels.contact import bccg_device as _kl
from warptrunc.kernels.contact import cg as _k

import warptrunc
from warptrunc.contact import ContactSolver, SolverSettings
from warptrunc.wm import wm_surface


def gpu_time(fn, dev, repeats: int) -> float:
    """Median device time (s) of ``fn`` (CUDA events; on the CPU the wall time)."""
    fn()
    wp.synchronize_device(dev)
    ts = []
    for _ in range(repeats):
        if dev.is_cuda:
            a, b = wp.Event(dev, enable_timing=True), wp.Event(dev, enable_timing=True)
            wp.record_event(a)
            fn()
            wp.record_event(b)
            wp.synchronize_event(b)
            ts.append(wp.get_event_elapsed_time(a, b) * 1e-3)
        else:
            t0 = time.perf_counter()
            fn()
            ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def parts(solver, dev, repeats: int) -> dict:
    """The parts of an iteration, each timed alone on the solver's present state (s)."""
    red, hs, n_map = solver.hs.reduction, solver.hs, solver.shape[0] * solver.shape[1]
    s = solver._loop_scalars()
    r_buf, z_old = solver._bccg_maps()
    hf = wp.float64(1e300)
    solver.tau.zero_()  # the update kernel then moves nothing
    out = {
        "convolution": gpu_time(lambda: hs.apply(solver.t_buf), dev, repeats),
        "preconditioner": gpu_time(lambda: hs.apply(r_buf, inverse=True), dev, repeats),
        "residual": gpu_time(
            lambda: red.launch(
                _kl.residual_loop_kernel,
                n_map,
                [solver.q, solver.u, solver.h, s, hf],
                [r_buf, solver.mask],
            ),
            dev,
            repeats,
        ),
        "dot": gpu_time(
            lambda: red.launch(_kb.bccg_dot_kernel, n_map, [r_buf, r_buf, z_old, solver.mask], []),
            dev,
            repeats,
        ),
        "direction": gpu_time(
            lambda: red.launch(
                _kl.direction_loop_kernel, n_map, [r_buf, s, solver.mask, r_buf], [solver.t, z_old]
            ),
            dev,
            repeats,
        ),
        "update": gpu_time(
            lambda: red.launch(
                _kb.bccg_update_kernel,
                n_map,
                [solver.t, solver.tau, hf, solver.t],
                [solver.q, solver.u, r_buf, solver.mask, solver.lane_count],
            ),
            dev,
            repeats,
        ),
        "fold + scalar kernel": gpu_time(
            lambda: wp.launch(
                _kl.loop_residual_kernel,
                dim=1,
                inputs=[red.fold((False,) * 9)],
                outputs=[s],
                device=dev,
            ),
            dev,
            repeats,
        ),
        "read-back (round trip)": statistics.median(
            _wall(lambda: s.numpy(), dev) for _ in range(repeats)
        ),
    }
    wp.synchronize_device(dev)
    t0 = time.perf_counter()
    k = 200
    for _ in range(k):
        wp.launch(
            _k.step_length_kernel,
            dim=1,
            inputs=[red.fold((False, False)), wp.float64(0.0), wp.float64(1.0)],
            outputs=[solver.tau],
            device=dev,
        )
    out["launch (host, per kernel)"] = (time.perf_counter() - t0) / (2 * k)
    wp.synchronize_device(dev)
    return out


def _wall(fn, dev) -> float:
    wp.synchronize_device(dev)
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def warm_solve(s, dtype: str, dev, loop: str) -> tuple[dict, ContactSolver]:
    solver = ContactSolver(
        s.heights, (s.dx, s.dy), E_STAR, device=dev, settings=SolverSettings(dtype=dtype, loop=loop)
    )
    cold = solver.solve(COLD * s.Rt)
    wp.synchronize_device(dev)
    t0 = time.perf_counter()
    warm = solver.solve(WARM * s.Rt)
    wp.synchronize_device(dev)
    t = time.perf_counter() - t0
    row = {
        "loop": loop,
        "cold_iterations": cold.n_iterations,
        "warm_s": t,
        "warm_iterations": warm.n_iterations,
        "warm_convolutions": warm.n_convolutions,
        "load_N": warm.load,
        "n_contact": warm.n_contact,
        "converged": bool(cold.converged and warm.converged),
        "graph_error": solver.graph_error(),
    }
    return row, solver


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--n", type=int, nargs="+", default=None, help="map sizes (pixels a side)")
    p.add_argument("--dtype", nargs="+", default=["float32"], choices=["float32", "float64"])
    p.add_argument("--device", default=None, help="Warp device (cpu, cuda:0)")
    p.add_argument("--repeats", type=int, default=5, help="repeats of each timing (median)")
    p.add_argument("--out", type=Path, default=None, help="folder for breakdown.json")
    a = p.parse_args(argv)
    dev = warptrunc.resolve_device(a.device)
    sizes = a.n or ([2048, 4096, 8192, 16384] if dev.is_cuda else [256, 512])
    name = wp.get_device(dev).name
    print(f"device {dev} ({name}), warp {wp.config.version}, commit {git_commit()}", flush=True)
    rows = []
    for n in sizes:
        s = wm_surface(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6, seed=0, device=dev)
        for dtype in a.dtype:
            floor = fft_floor(n, dtype, dev, a.repeats)
            row = {"n": n, "dtype": dtype, "fft_floor_s": floor, "loops": {}}
            for loop in ("host", "device", "graph"):
                r, solver = warm_solve(s, dtype, dev, loop)
                it, conv = r["warm_iterations"], r["warm_convolutions"]
                r["per_iteration_s"] = r["warm_s"] / it
                r["per_convolution_s"] = r["warm_s"] / conv if conv else None
                r["per_convolution_over_floor"] = (
                    r["warm_s"] / conv / floor if conv and floor else None
                )
                if loop == "device":
                    row["parts_s"] = parts(solver, dev, a.repeats)
                row["loops"][loop] = r
                del solver
            d = row["loops"]["device"]
            ps = row["parts_s"]
            conv_it = d["warm_convolutions"] / d["warm_iterations"]
            busy = (
                ps["convolution"] * conv_it
                + ps["residual"]
                + ps["dot"]
                + ps["direction"]
                + ps["update"]
                + 4 * ps["fold + scalar kernel"]
            )
            row["device_busy_per_iteration_s"] = busy
            for loop, r in row["loops"].items():
                r["idle_per_iteration_s"] = r["per_iteration_s"] - busy
            rows.append(row)
            h, g = row["loops"]["host"], row["loops"]["graph"]
            print(
                f"N={n} {dtype}: warm host {h['warm_s'] * 1e3:.1f} ms ({h['warm_iterations']} it,"
                f" {h['warm_convolutions']} conv), graph {g['warm_s'] * 1e3:.1f} ms "
                f"({g['warm_iterations']} it, loads equal to "
                f"{abs(h['load_N'] - g['load_N']) / h['load_N']:.1e}, capture error "
                f"{g['graph_error']}), device {d['warm_s'] * 1e3:.1f} ms "
                f"({d['warm_iterations']} it, {d['warm_convolutions']} conv); per conv "
                f"{(d['per_convolution_over_floor'] or float('nan')):.2f}× floor "
                f"({(floor or float('nan')) * 1e3:.2f} ms); busy/it {busy * 1e3:.2f} ms, "
                f"idle/it host {h['idle_per_iteration_s'] * 1e3:.2f} ms, device "
                f"{d['idle_per_iteration_s'] * 1e3:.2f} ms; loads equal to "
                f"{abs(h['load_N'] - d['load_N']) / h['load_N']:.1e}",
                flush=True,
            )
            print(
                "   parts (ms): " + ", ".join(f"{k} {v * 1e3:.3f}" for k, v in ps.items()),
                flush=True,
            )
        del s
    if a.out is not None:
        a.out.mkdir(parents=True, exist_ok=True)
        doc = {
            "device": str(dev),
            "device_name": name,
            "warp": wp.config.version,
            "commit": git_commit(),
            "rows": rows,
            "surface": "wm_surface(D=2.5, Wr=100 µm, L=1 mm, Rt=10 µm, seed 0), free",
        }
        (a.out / "breakdown.json").write_text(json.dumps(doc, indent=1) + "\n")
        print(f"wrote {a.out / 'breakdown.json'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
