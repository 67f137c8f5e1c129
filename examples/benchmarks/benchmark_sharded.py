# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One contact problem over several GPUs: correctness against one GPU, the sharded
FFT floor, per-iteration time and peak memory per device against ``memory_bytes``.

Each step runs in its own process (``examples/gpu_checks/sharded.sh`` runs them under
``timeout``) and appends one JSON line per result to ``--jsonl``; a failing measurement writes
its error and the next one goes on. Steps:

``check``   2 devices against the one-device solver (Warp, ``--device``, ``direct_max=0``: the same
            iteration) at ``--n`` (4096²): free and periodic, float64 and float32; a solve at
            0.2·R_t (loads compared) and one at its load ×1.05 (approaches compared), the
            contact pixels that differ, Barber's stiffness. Tolerances 1e-9 (float64), 1e-5
            (float32).
``solve``   ``--ndev`` devices at ``--n``: the floor (one K·x, median of ``--repeats``; on one
            device the Warp solver's own convolution, on several JAX's sharded one), the solver's
            set-up, a cold solve at 0.20·R_t and a warm one at 0.21·R_t (at most ``--maxiter``
            iterations each), time per iteration and per convolution against the floor, and the
            peak memory of each device (JAX's ``peak_bytes_in_use``, Warp's pool high-water)
            against ``ContactSolver.memory_bytes(..., devices=ndev)``.
``maps``    make the map of ``--n`` (cached for the next steps).
``report``  the table of the JSON lines (``--jsonl``), printed, and ``sharded_summary.json``.

The map is a self-affine Gaussian surface (H = 0.8, 1 mm, rms 1 µm), made on the host and kept
as ``.npy`` under ``--maps`` for the next process. ``XLA_PYTHON_CLIENT_PREALLOCATE=false`` and
``XLA_PYTHON_CLIENT_MEM_FRACTION=0.95`` are set here before JAX is imported (unless given): JAX
would otherwise take 75 % of every GPU at start, and no more.

Run (GPU machine): ``OUT=out bash examples/gpu_checks/sharded.sh``, or one step,
``python examples/benchmarks/benchmark_sharded.py solve --n 16384 --ndev 2 --jsonl out/s.jsonl``.
A CPU dry run: ``XLA_FLAGS=--xla_force_host_platform_device_count=2 python
examples/benchmarks/benchmark_sharded.py check --n 128 --device cpu``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
import traceback
from pathlib import Path

os.environ.setdefault("XLA_PYTHON_CLIENT_PREALLOCATE", "false")
os.environ.setdefault("XLA_PYTHON_CLIENT_MEM_FRACTION", "0.95")

import numpy as np

L = 1e-3  # map side (m)
E = 70e9 / (1 - 0.33**2)  # contact modulus (Pa)
TOL = {"float64": 1e-9, "float32": 1e-5}


MAP = {"kind": "selfaffine"}
"""The map of every step (``--map``): ``selfaffine`` (below) or ``wm``."""


def surface(n: int, maps: Path) -> np.ndarray:
    """The map (m), n × n, seed 0, cached as .npy for the next process (float64 up to 16384²,
    float32 above to keep the host copy small): ``--map selfaffine``, a self-affine Gaussian
    surface; ``--map wm``, the paper's kind of map, the D = 2.5 WM surface of
    ``benchmark_solver_scaling.py`` (W_r = 100 µm, R_t = 10 µm over 1 mm, made on Warp's
    default device)."""
    if MAP["kind"] == "wm":
        path = maps / f"wm_{n}.npy"
        if path.exists():
            return np.load(path)
        from warptrunc.wm import wm_surface

        h = wm_surface(2.5, 100e-6, L=L, n=n, Rt=10e-6, seed=0).heights  # default device
        maps.mkdir(parents=True, exist_ok=True)
        np.save(path, h)
        return h
    dtype = np.float64 if n <= 16384 else np.float32
    path = maps / f"selfaffine_{n}_{np.dtype(dtype).name}.npy"
    if path.exists():
        return np.load(path)
    import scipy.fft

    rng = np.random.default_rng(0)
    white = rng.standard_normal((n, n), dtype=np.float32)
    spec = scipy.fft.rfft2(white, workers=os.cpu_count())
    del white
    fy = np.fft.fftfreq(n).astype(np.float32)[:, None]
    fx = np.fft.rfftfreq(n).astype(np.float32)[None, :]
    k = np.hypot(fx, fy)
    k[0, 0] = 1.0
    spec *= k ** np.float32(-1.8)  # PSD ∝ k^-(2 + 2H), H = 0.8
    spec[0, 0] = 0
    del k
    h = scipy.fft.irfft2(spec, s=(n, n), workers=os.cpu_count())
    del spec
    h *= np.float32(1e-6 / h.std())
    h = h.astype(dtype)
    maps.mkdir(parents=True, exist_ok=True)
    np.save(path, h)
    return h


def maps(args) -> None:
    """Make the map of ``--n`` (and keep it for the next steps)."""
    t = time.perf_counter()
    h = surface(args.n, args.maps)
    print(f"map {args.n}² {h.dtype}: {time.perf_counter() - t:.1f} s", flush=True)


def emit(path: Path, record: dict) -> None:
    """Append one JSON line (and print it)."""
    from _common import git_commit

    record = {"commit": git_commit(), "time": time.strftime("%Y-%m-%dT%H:%M:%S"), **record}
    line = json.dumps(record, default=float)
    print(line, flush=True)
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a", encoding="utf-8") as f:
        f.write(line + "\n")


def device_names() -> list[str]:
    import jax

    return [f"{d.device_kind} ({d.platform}:{d.id})" for d in jax.devices()]


def check(args) -> None:
    """2 devices against 1 (module docstring)."""
    import jax

    from warptrunc.contact import ContactSolver, SolverSettings, contact_solver

    h = surface(args.n, args.maps).astype(np.float64)
    dx = L / args.n
    depth = 0.2 * float(np.ptp(h))
    for dtype in ("float64", "float32"):
        for substrate in ("free", "periodic"):
            rec = {
                "step": "check",
                "n": args.n,
                "substrate": substrate,
                "dtype": dtype,
                "ndev": 2,
                "devices": device_names()[:2],
            }
            try:
                st = SolverSettings(substrate=substrate, dtype=dtype)
                t = time.perf_counter()
                one = ContactSolver(h, dx, E, device=args.device, settings=st.replace(direct_max=0))
                two = contact_solver(h, dx, E, devices=jax.devices()[:2], settings=st)
                rec["setup_s"] = time.perf_counter() - t
                out = {}
                for name, solver in (("one", one), ("two", two)):
                    t = time.perf_counter()
                    a = solver.solve(depth)
                    b = solver.solve(load=1.05 * a.load)
                    k = solver.punch_stiffness()
                    out[name] = (a, b, k, solver.maps()[0] > 0, time.perf_counter() - t)
                (a1, b1, k1, c1, t1), (a2, b2, k2, c2, t2) = out["one"], out["two"]
                ok = all(x.converged for x in (a1, b1, a2, b2))
                rec["load_rel"] = abs(a1.load - a2.load) / a1.load
                rec["depth_rel"] = abs(b1.depth - b2.depth) / b1.depth
                rec["stiffness_rel"] = abs(k1[0] - k2[0]) / k1[0]
                rec["iterations"] = [x.n_iterations for x in (a1, b1, a2, b2)]
                rec["contact_fraction"] = float(c1.mean())
                rec["pixels_differ"] = int((c1 != c2).sum())
                rec["converged"] = ok
                rec["one_device_s"], rec["two_devices_s"] = t1, t2
                tol = TOL[dtype]
                rec["pass"] = bool(
                    rec["converged"]
                    and max(rec["load_rel"], rec["depth_rel"], rec["stiffness_rel"]) < tol
                )
                del one, two
            except Exception as exc:  # recorded; the next case goes on
                rec["error"] = f"{type(exc).__name__}: {exc}"
                traceback.print_exc()
            emit(args.jsonl, rec)


def _timed(fn, repeats: int) -> float:
    fn()
    ts = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return float(np.median(ts))


def programme_memory(solver) -> dict:
    """XLA's memory of the sharded solver's programmes as compiled for these devices (bytes per
    device: arguments, outputs, temporaries; ``memory_analysis()``), to set the model's XLA
    terms on the devices' own compile: the spectrum's build, the CG step, the preconditioner,
    one convolution."""
    from warptrunc.contact.sharded.spectrum import spectrum_programme
    from warptrunc.contact.sharded.steps import make_step

    lay, w = solver.hs.layout, solver.hs.spectrum
    x, mask = solver.q, solver.mask
    calls = {
        "build": (lambda: spectrum_programme(lay, solver.pixel_size, solver.contact_modulus), ()),
        "step": (lambda: make_step(lay, "step"), (x, 0.0, 0.0, mask, x, x, x, x, 1.0, 1e300, w)),
        "precondition": (lambda: make_step(lay, "precondition"), (x, x, mask, w)),
        "apply": (lambda: lay.jax.jit(lambda a, b: lay.conv(a, b), out_shardings=lay.rows), (x, w)),
    }
    out = {}
    for name, (make, fn_args) in calls.items():
        try:
            m = make().lower(*fn_args).compile().memory_analysis()
            out[name] = {
                "argument": int(m.argument_size_in_bytes),
                "output": int(m.output_size_in_bytes),
                "alias": int(getattr(m, "alias_size_in_bytes", -1)),
                "temp": int(m.temp_size_in_bytes),
            }
        except Exception as exc:  # recorded; the others go on
            out[name] = {"error": f"{type(exc).__name__}: {exc}"[:300]}
    return out


def solve(args) -> None:
    """Floor, set-up, cold and warm solves, peak memory (module docstring)."""
    rec = {
        "step": "solve",
        "map": args.map,
        "n": args.n,
        "ndev": args.ndev,
        "dtype": args.dtype,
        "substrate": args.substrate,
        "maxiter": args.maxiter,
    }
    try:
        from warptrunc.contact import ContactSolver, SolverSettings, contact_solver

        t = time.perf_counter()
        h = surface(args.n, args.maps)
        rec["surface_s"] = time.perf_counter() - t
        dx = L / args.n
        rt = float(np.ptp(h))
        kw = {
            "settings": SolverSettings(
                substrate=args.substrate, dtype=args.dtype, maxiter=args.maxiter
            )
        }
        shape = (args.n, args.n)
        rec["model_bytes_per_device"] = ContactSolver.memory_bytes(
            shape, args.substrate, args.dtype, devices=args.ndev
        )
        t = time.perf_counter()
        if args.ndev == 1:
            import warp as wp

            dev = wp.get_device(args.device)
            solver = ContactSolver(h, dx, E, device=dev, **kw)
            wp.synchronize_device(dev)
            rec["devices"] = [dev.name]

            def sync():
                wp.synchronize_device(dev)

            def floor():
                solver.hs.apply(solver.q_buf)
                sync()
        else:
            import jax

            devices = jax.devices()[: args.ndev]
            solver = contact_solver(h, dx, E, devices=devices, **kw)
            rec["devices"] = device_names()[: args.ndev]

            def sync():
                jax.block_until_ready(solver.q)

            def floor():
                jax.block_until_ready(solver.hs.apply(solver.q))

        del h
        rec["setup_s"] = time.perf_counter() - t
        rec["floor_ms"] = 1e3 * _timed(floor, args.repeats)  # one K·x: forward and inverse
        for name, frac in (("cold", 0.20), ("warm", 0.21)):
            t = time.perf_counter()
            r = solver.solve(frac * rt)
            sync()
            dt = time.perf_counter() - t
            rec[name] = {
                "s": dt,
                "iterations": r.n_iterations,
                "convolutions": r.n_convolutions,
                "converged": r.converged,
                "load": r.load,
                "contact_fraction": r.n_contact / args.n**2,
                "ms_per_iteration": 1e3 * dt / max(1, r.n_iterations),
                "ms_per_convolution": 1e3 * dt / max(1.0, r.n_convolutions),
            }
        rec["warm_over_floor"] = rec["warm"]["ms_per_convolution"] / rec["floor_ms"]
        if args.ndev == 1:
            import warp as wp

            rec["peak_bytes"] = [int(wp.get_mempool_used_mem_high(dev)) if dev.is_cuda else -1]
            rec["model_bytes_per_device"] = ContactSolver.memory_bytes(
                shape, args.substrate, args.dtype, fft_plan=solver.fft_plan, device=dev
            )
        else:
            stats = [d.memory_stats() or {} for d in devices]
            rec["peak_bytes"] = [int(s.get("peak_bytes_in_use", -1)) for s in stats]
            rec["programmes"] = programme_memory(solver)
            rec["model_terms"] = type(solver).memory_terms_per_device(
                shape, args.substrate, args.dtype, args.ndev
            )
        rec["peak_over_model"] = max(rec["peak_bytes"]) / rec["model_bytes_per_device"]
    except Exception as exc:  # recorded; the script goes on
        rec["error"] = f"{type(exc).__name__}: {exc}"
        traceback.print_exc()
    emit(args.jsonl, rec)


def step_rows(rows: list[dict], step: str, ident: tuple, width: int):
    """The rows of ``step`` in order; a row with an error is printed as one line instead (its
    ``ident`` fields, (key, width) pairs, and the error's first ``width`` characters)."""
    for r in rows:
        if r.get("step") != step:
            continue
        if "error" in r:
            head = " ".join(f"{r.get(k, '?'):>{w}}" for k, w in ident)
            print(f"{head}  ERROR {r['error'][:width]} {r.get('args', '')}")
            continue
        yield r


def report(args) -> None:
    """The table of the JSON lines, and sharded_summary.json beside them."""
    rows = [json.loads(x) for x in args.jsonl.read_text().splitlines() if x.strip()]
    print("\ncheck: 2 devices against 1 (relative differences; tolerance 1e-9 f64, 1e-5 f32)")
    print(
        f"{'n':>6} {'substrate':>9} {'dtype':>8} {'load':>9} {'depth':>9} {'k':>9} "
        f"{'px':>4} {'pass':>5}"
    )
    for r in step_rows(rows, "check", (("n", 6), ("substrate", 9), ("dtype", 8)), 60):
        print(
            f"{r['n']:>6} {r['substrate']:>9} {r['dtype']:>8} {r['load_rel']:9.1e} "
            f"{r['depth_rel']:9.1e} {r['stiffness_rel']:9.1e} {r['pixels_differ']:>4} "
            f"{r['pass']!s:>5}"
        )
    print("\nsolve: floor = one K·x; per convolution (warm) against it; peak memory per device")
    print(
        f"{'n':>6} {'dev':>3} {'dtype':>8} {'floor ms':>9} {'setup s':>8} {'cold s':>7} "
        f"{'warm s':>7} {'it':>4} {'ms/it':>7} {'ms/conv':>8} {'/floor':>6} {'peak GB':>8} "
        f"{'model GB':>8}"
    )
    for r in step_rows(rows, "solve", (("n", 6), ("ndev", 3), ("dtype", 8)), 70):
        w = r["warm"]
        print(
            f"{r['n']:>6} {r['ndev']:>3} {r['dtype']:>8} {r['floor_ms']:9.1f} "
            f"{r['setup_s']:8.1f} {r['cold']['s']:7.2f} {w['s']:7.2f} {w['iterations']:>4} "
            f"{w['ms_per_iteration']:7.1f} {w['ms_per_convolution']:8.1f} "
            f"{r['warm_over_floor']:6.2f} {max(r['peak_bytes']) / 1e9:8.2f} "
            f"{r['model_bytes_per_device'] / 1e9:8.2f}"
        )
    out = args.jsonl.with_name("sharded_summary.json")
    out.write_text(json.dumps(rows, indent=1, default=float))
    print(f"\nwritten: {out}")


def main(argv: list[str] | None = None) -> int:
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("step", choices=("check", "maps", "solve", "report"))
    ap.add_argument("--n", type=int, default=4096, help="pixels per side")
    ap.add_argument("--ndev", type=int, default=2, help="devices (solve)")
    ap.add_argument("--device", default="cuda:0", help="Warp device of the one-device solver")
    ap.add_argument("--dtype", default="float32", choices=("float32", "float64"))
    ap.add_argument("--substrate", default="free", choices=("free", "periodic"))
    ap.add_argument("--maxiter", type=int, default=100, help="iteration cap per solve (solve)")
    ap.add_argument("--repeats", type=int, default=10, help="timed repeats of the floor")
    ap.add_argument("--maps", type=Path, default=Path("sharded_maps"), help="map cache folder")
    ap.add_argument("--jsonl", type=Path, default=Path("sharded.jsonl"), help="results file")
    ap.add_argument(
        "--map",
        default="selfaffine",
        choices=("selfaffine", "wm"),
        help="the map: a self-affine Gaussian surface (H = 0.8, rms 1 µm), or the "
        "D = 2.5 WM surface of benchmark_solver_scaling.py (R_t = 10 µm)",
    )
    args = ap.parse_args(argv)
    MAP["kind"] = args.map
    steps = {"check": check, "maps": maps, "solve": solve, "report": report}
    steps[args.step](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
