# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: the four fractal-dimension methods, against NumPy (and CuPy) in the same process.

What it shows
    Median times of D_tri (triangular prism), D_box (cube counting) and D_vs (structure
    function) — the Warp-kernel passes alone on a map already on the device ("kernel"), and
    the public call with its defaults, including the upload and the W_r estimate ("full") —
    and of D_sp (NumPy FFTs on the host, the same code on every device), next to vectorised
    NumPy implementations of the same passes (and CuPy ones on a GPU when CuPy is present).
    The references also check the results: the largest relative difference of the measures
    is reported.

Run
    python examples/benchmarks/benchmark_fractal.py --device cpu --n 1024 4096
    python examples/benchmarks/benchmark_fractal.py --device cuda:0 --n 1024 4096 8192 --out bench
"""

from __future__ import annotations

import json
import math
import platform
import subprocess

import numpy as np
import warp as wp
from _common import bench_parser, timeit

import warptrunc
from warptrunc import fractal
from warptrunc.fractal import box_counting, power_spectrum, triangular_prism, vertical_sections

L = 1e-3


# --- references: the same passes with array operations (xp = numpy or cupy) ---------------------


def ref_prism(xp, z, sizes, dx):
    out = []
    for s in sizes:
        ncy, ncx = (z.shape[0] - 1) // s, (z.shape[1] - 1) // s
        za = z[0 : ncy * s : s, 0 : ncx * s : s]
        zb = z[0 : ncy * s : s, s : ncx * s + 1 : s]
        zc = z[s : ncy * s + 1 : s, s : ncx * s + 1 : s]
        zd = z[s : ncy * s + 1 : s, 0 : ncx * s : s]
        ze = 0.25 * (za + zb + zc + zd)
        h = s * dx
        # triangle (P, Q, E) with P, Q neighbouring corners and E the apex: |PQ × PE| / 2
        total = 0.0
        for (p, px, py), (q, qx, qy) in (
            ((za, 0, 0), (zb, h, 0)),
            ((zb, h, 0), (zc, h, h)),
            ((zc, h, h), (zd, 0, h)),
            ((zd, 0, h), (za, 0, 0)),
        ):
            ux, uy, uz = qx - px, qy - py, q - p
            vx, vy, vz = h / 2 - px, h / 2 - py, ze - p
            cx = uy * vz - uz * vy
            cy = uz * vx - ux * vz
            cz = ux * vy - uy * vx
            total += float(0.5 * xp.sqrt(cx * cx + cy * cy + cz * cz).sum())
        out.append(total / (ncx * h * ncy * h))
    return np.array(out)


def ref_box(xp, z, sizes, dx):
    swv = xp.lib.stride_tricks.sliding_window_view
    z0 = z.min()
    out = []
    for s in sizes:
        ncy, ncx = (z.shape[0] - 1) // s, (z.shape[1] - 1) // s
        w = swv(z[: ncy * s + 1, : ncx * s + 1], (s + 1, s + 1))[::s, ::s]
        eps = s * dx
        n = (
            xp.floor((w.max(axis=(2, 3)) - z0) / eps)
            - xp.floor((w.min(axis=(2, 3)) - z0) / eps)
            + 1
        )
        cov = (ncx * s) * (ncy * s)
        out.append(float(n.sum()) * (z.shape[1] - 1) * (z.shape[0] - 1) / cov)
    return np.array(out)


def ref_structure(xp, z, lags):
    out = []
    for t in lags:
        a = z[:, t:] - z[:, :-t]
        b = z[t:, :] - z[:-t, :]
        out.append(float(((a * a).sum() + (b * b).sum()) / (a.size + b.size)))
    return np.array(out)


def rel_diff(a, b) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b)) / np.abs(np.asarray(b))))


def run_case(n: int, device, repeats: int, max_ref_n: int = 4096) -> dict:
    s = fractal.self_affine_surface(0.5, n, L, Rrms=100 * L / n, seed=0)
    sync = lambda: wp.synchronize_device(device)  # noqa: E731
    res = {"n": n, "device": str(device), "device_name": device.name, "dtype": "float32"}
    sizes = fractal._default_box_sizes(s)
    lags = fractal._default_lags(s)
    res["box_sizes"] = sizes.tolist()
    res["lags"] = lags.tolist()
    zd = wp.array(s.heights, dtype=wp.float32, device=device)
    fr = (0.0, 1.0)  # fixed fit range: times the kernel passes only
    res["tri_kernel_s"] = timeit(lambda: fractal._tri(zd, s, sizes, fr), repeats, sync)
    res["box_kernel_s"] = timeit(lambda: fractal._box(zd, s, sizes, fr), repeats, sync)
    res["vs_kernel_s"] = timeit(lambda: fractal._vs(zd, s, lags, fr, "both"), repeats, sync)
    host_reps = max(1, repeats // 2) if n >= 4096 else repeats  # host FFTs dominate "full"
    res["tri_full_s"] = timeit(lambda: triangular_prism(s, device=device), host_reps, sync)
    res["box_full_s"] = timeit(lambda: box_counting(s, device=device), host_reps, sync)
    res["vs_full_s"] = timeit(lambda: vertical_sections(s, device=device), host_reps, sync)
    res["sp_host_s"] = timeit(lambda: power_spectrum(s), host_reps, lambda: None)
    fits = {
        "tri": fractal._tri(zd, s, sizes, fr),
        "box": fractal._box(zd, s, sizes, fr),
        "vs": fractal._vs(zd, s, lags, fr, "both"),
    }
    res.update({f"D_{k}": f.D for k, f in fits.items()})
    res["D_sp"] = power_spectrum(s).D
    z64 = s.heights.astype(np.float64)
    if device.is_cuda:
        try:
            import cupy as xp
        except ImportError:
            xp = None
        if xp is None:
            return res
        ref_sync = xp.cuda.Device().synchronize
        zr = xp.asarray(z64)
        name, reps = "cupy", repeats
    else:
        if n > max_ref_n:
            return res
        xp, zr, ref_sync, name = np, z64, (lambda: None), "numpy"
        reps = max(1, repeats // 2) if n >= 4096 else repeats
    refs = {
        "tri": lambda: ref_prism(xp, zr, sizes, s.dx),
        "box": lambda: ref_box(xp, zr, sizes, s.dx),
        "vs": lambda: ref_structure(xp, zr, lags),
    }
    for m, fn in refs.items():
        try:
            res[f"{name}_{m}_s"] = timeit(fn, reps, ref_sync)
            res[f"max_rel_diff_{m}"] = rel_diff(fits[m].measure, fn())
        except (AttributeError, NotImplementedError) as exc:  # e.g. an old CuPy
            res[f"{name}_{m}_s"] = f"n/a ({type(exc).__name__})"
    if device.is_cuda:

        def cupy_sp():
            zz = zr - zr.mean()
            w = 0.5 - 0.5 * xp.cos(2 * math.pi * xp.arange(n) / n)
            f = xp.fft.rfft(zz * w, axis=1)
            return (xp.abs(f) ** 2).mean(axis=0)

        res["cupy_sp_fft_s"] = timeit(cupy_sp, repeats, ref_sync)
    return res


def main(argv=None) -> int:
    ap = bench_parser(__doc__)
    ap.add_argument(
        "--max-ref-n", type=int, default=4096, help="largest n timed with the NumPy reference"
    )
    ap.add_argument("--quick", action="store_true", help="one 128² case, 1 repeat")
    ap.add_argument("--no-show", action="store_true", help="(no figures; accepted for symmetry)")
    ap.add_argument("--seed", type=int, default=0, help="(unused; accepted for symmetry)")
    args = ap.parse_args(argv)
    device = warptrunc.resolve_device(args.device)
    sizes, repeats = ([128], 1) if args.quick else (args.n, args.repeats)
    try:
        commit = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, check=False
        ).stdout.strip()
    except OSError:
        commit = ""
    meta = {
        "warp": wp.config.version,
        "numpy": np.__version__,
        "host": platform.processor() or platform.machine(),
        "device": str(device),
        "device_name": device.name,
        "commit": commit,
    }
    results = []
    for n in sizes:
        r = run_case(n, device, repeats, args.max_ref_n)
        results.append(r)
        print(json.dumps(r))
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / f"benchmark_fractal_{str(device).replace(':', '')}.json"
    path.write_text(json.dumps({"meta": meta, "results": results}, indent=2) + "\n")
    ref = "cupy" if device.is_cuda else "numpy"
    print(f"\n{device.name} ({device}), warp {wp.config.version}; times in ms (median)")
    print(f"{'n':>6} {'method':>6} {'kernel':>10} {'full':>10} {ref + ' ref':>12}  max rel diff")
    for r in results:
        for m in ("tri", "box", "vs"):
            rv = r.get(f"{ref}_{m}_s", float("nan"))
            rv = rv * 1e3 if isinstance(rv, float) else float("nan")
            k, f = r[f"{m}_kernel_s"] * 1e3, r[f"{m}_full_s"] * 1e3
            print(
                f"{r['n']:>6} {m:>6} {k:>10.2f} {f:>10.2f} {rv:>12.2f}  "
                f"{r.get(f'max_rel_diff_{m}', float('nan')):.1e}"
            )
        print(f"{r['n']:>6} {'sp':>6} {'(host)':>10} {r['sp_host_s'] * 1e3:>10.2f}")
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
