# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Where one convolution of the free half-space spends its time, on a CUDA device.

Per map size N (float32 by default): the half-space's forward transform, spectral product and
inverse transform, each phase timed alone (median of repeats, device synchronised around it):
the pad rows zeroed, the map copied into the spectrum's rows, the row transforms (pruned to the
map's rows), the column transforms (in slabs), the spectral product, and the inverse column and
row transforms; then ``apply`` as a whole; then the same with the transforms in one slab; then
one 2-D in-place cuFFT plan over the whole padded grid (no pruning) with its work size; and the
floor of the scaling benchmark (CuPy rfft2 + irfft2, out of place). Prints a table and writes
JSON.

Run (GPU machine):
    python examples/gpu_checks/convolution_breakdown.py --n 10240 16384 --out $OUT/conv.json
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import warp as wp

import warptrunc.contact.transforms as hsmod
from warptrunc.contact.halfspace import ElasticHalfSpace, cupy_stream

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from benchmark_solver_scaling import fft_floor  # noqa: E402 - the floor of the scaling benchmark


def timed(fn, dev, repeats):
    fn()
    wp.synchronize_device(dev)
    ts = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        wp.synchronize_device(dev)
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def phases(hs, buf, dev, repeats):
    import cupy
    from warptrunc.kernels.contact import spectral as _kr

    spec = hs.work
    ny = hs.shape[0]
    nk = hs.spectrum_shape[1]
    item = np.dtype(hs.np_dtype).itemsize
    plans, rows, cols = hs._cupy_plans()
    fwd, inv = hs._directions
    stream = cupy_stream(cupy, wp.get_stream(dev), dev.ordinal)

    def zero():
        spec[ny:].zero_()

    def pad():
        rv = hs._real_rows(spec)
        wp.launch(_kr.pad_rows_kernel, dim=rv.shape, inputs=[buf], outputs=[rv], device=dev)

    def run(kind, which, direction):
        def f():
            with cupy.cuda.Device(dev.ordinal), stream:
                for a0, c in which:
                    off = a0 * nk * 2 * item if kind.startswith("rows") else a0 * 2 * item
                    v = hs._cupy_view(spec, off)
                    plans[kind, c].fft(v, v, direction)

        return f

    out = {
        "zero_pad_rows": timed(zero, dev, repeats),
        "copy_map_in": timed(pad, dev, repeats),
        "rows_r2c": timed(run("rows", rows, fwd), dev, repeats),
        "cols_fwd": timed(run("cols", cols, fwd), dev, repeats),
        "spectral": timed(lambda: hs.spectral(_kr.SPECTRUM_APPLY, spec), dev, repeats),
        "cols_inv": timed(run("cols", cols, inv), dev, repeats),
        "rows_c2r": timed(run("rows_inv", rows, inv), dev, repeats),
        "apply": timed(lambda: hs.apply(buf), dev, repeats),
        "slabs_rows": len(rows),
        "slabs_cols": len(cols),
        "cufft_work_bytes": int(hs.fft_work.capacity),
    }
    return out


def plan_2d(hs, dev, repeats):
    """One in-place 2-D R2C and C2R plan over the whole (Ny, Nx) grid in the work spectrum."""
    import cupy
    from cupy.cuda import cufft

    big_y, big_x = hs.grid
    nk = hs.spectrum_shape[1]
    r2c, c2r = (
        (cufft.CUFFT_R2C, cufft.CUFFT_C2R)
        if hs.dtype == "float32"
        else (cufft.CUFFT_D2Z, cufft.CUFFT_Z2D)
    )
    sizes = []
    scratch = hs.work  # only for learning the work sizes; never executed

    def record(size):
        sizes.append(int(size))
        mem = cupy.cuda.UnownedMemory(scratch.ptr, int(size), scratch, dev.ordinal)
        return cupy.cuda.MemoryPointer(mem, 0)

    def make():
        pf = cufft.PlanNd(
            (big_y, big_x),
            (big_y, 2 * nk),
            1,
            big_y * 2 * nk,
            (big_y, nk),
            1,
            big_y * nk,
            r2c,
            1,
            "C",
            1,
            nk,
        )
        pi = cufft.PlanNd(
            (big_y, big_x),
            (big_y, nk),
            1,
            big_y * nk,
            (big_y, 2 * nk),
            1,
            big_y * 2 * nk,
            c2r,
            1,
            "C",
            1,
            big_x,
        )
        return pf, pi

    with cupy.cuda.Device(dev.ordinal):
        with cupy.cuda.using_allocator(record):
            tmp = make()
        del tmp
        need = max(sizes, default=1)
        area = cupy.empty(max(1, need), dtype=cupy.uint8)
        with cupy.cuda.using_allocator(lambda size: area.data):
            pf, pi = make()
    v = hs._cupy_view(hs.work, 0)
    stream = cupy_stream(cupy, wp.get_stream(dev), dev.ordinal)

    def f():
        with cupy.cuda.Device(dev.ordinal), stream:
            pf.fft(v, v, cufft.CUFFT_FORWARD)
            pi.fft(v, v, cufft.CUFFT_INVERSE)

    t = timed(f, dev, repeats)
    del pf, pi, area
    cupy.get_default_memory_pool().free_all_blocks()
    return {"fwd_inv_2d_inplace": t, "work_bytes_2d": sizes}


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--n", type=int, nargs="+", default=[10240, 16384])
    p.add_argument("--dtype", default="float32", choices=["float32", "float64"])
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--out", default=None)
    a = p.parse_args()
    dev = wp.get_device("cuda:0")
    res = []
    for n in a.n:
        row = {"n": n, "dtype": a.dtype}
        t0 = time.perf_counter()
        hs = ElasticHalfSpace(
            (n, n), (1e-3 / n, 1e-3 / n), 78e9, substrate="free", dtype=a.dtype, device=dev
        )
        row["setup_s"] = time.perf_counter() - t0
        buf, _ = hs.map_buffer()
        buf.fill_(1.0)
        row.update(phases(hs, buf, dev, a.repeats))
        del hs
        saved = hsmod.FFT_SLABS
        hsmod.FFT_SLABS = 1
        try:
            hs1 = ElasticHalfSpace(
                (n, n), (1e-3 / n, 1e-3 / n), 78e9, substrate="free", dtype=a.dtype, device=dev
            )
            b1, _ = hs1.map_buffer()
            b1.fill_(1.0)
            row["apply_one_slab"] = timed(lambda: hs1.apply(b1), dev, a.repeats)
            row["cufft_work_bytes_one_slab"] = int(hs1.fft_work.capacity)
            try:
                row.update(plan_2d(hs1, dev, a.repeats))
            except Exception as exc:  # noqa: BLE001 - report, go on
                row["plan_2d_error"] = repr(exc)[:300]
            del hs1, b1
        finally:
            hsmod.FFT_SLABS = saved
        wp.synchronize_device(dev)
        row["floor"] = fft_floor(n, a.dtype, dev, a.repeats)
        res.append(row)
        ms = {
            k: round(v * 1e3, 2) for k, v in row.items() if isinstance(v, float) and k != "setup_s"
        }
        print(
            f"N={n} {a.dtype}: "
            + ", ".join(f"{k} {v} ms" for k, v in ms.items())
            + f"; slabs rows/cols {row['slabs_rows']}/{row['slabs_cols']}, cufft work "
            f"{row['cufft_work_bytes'] / 2**30:.2f} GiB (one slab "
            f"{row['cufft_work_bytes_one_slab'] / 2**30:.2f}), 2-D work {row.get('work_bytes_2d')}",
            flush=True,
        )
    if a.out:
        with open(a.out, "w") as fh:
            json.dump(res, fh, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
