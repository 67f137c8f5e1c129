# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Two distributed FFT engines for the padded transform pair of the elastic half-space (both
engines' floors for the pair on 2 GPUs): JAX/XLA in one process, and cuFFTMp
(nvmath-python's ``nvmath.distributed.fft``) in MPI ranks.

The pair: a real N × N map zero-padded to 2N × 2N, the forward real 2-D FFT, times a real kernel
spectrum W = 1 / (1 + 8|f|) (f in cycles per sample; even in f, so the product stays Hermitian),
the inverse real 2-D FFT, the N × N top-left block kept. Both engines hold the padded grid in row
slabs (2N rows split evenly; x's rows in the first slabs, the pad's rows zeros) and transform all
of it: rows (local), the transpose to column slabs (all-to-all), columns, W, the inverse columns,
the transpose back, the inverse rows, the N columns kept. Floor: the median of ``--repeats``
calls after 2 warm-up calls, each ended by a device synchronisation (MPI: the slowest rank).

``jax``: ``--ndev`` devices of one process, a Mesh with axis "x", ``shard_map`` for the local
FFTs, ``jax.lax.with_sharding_constraint`` between row and column slabs (XLA's all-to-alls);
FFT calls of at most 2**30 elements (blocks of rows or columns where needed): XLA's GPU FFT
leaves an inverse transform of 2**31 elements or more unscaled (openxla/xla#45009).
``jax-pruned``: the solver's convolution (``ShardedHalfSpace.apply``, Love's kernel; the floor
of benchmark_sharded.py), which never transforms the zero rows; error column: its unit-force
check. ``cufftmp``: one MPI rank per GPU (rank % local GPUs), ``nvmath.distributed.initialize(
device, MPIProcessGroup(comm), backends=["nvshmem"])``, ``nvmath.distributed.fft.
allocate_operand(..., distribution=Slab.X, fft_type="R2C")`` (symmetric heap, in place), two
``nvmath.distributed.fft.FFT`` planned once (R2C on Slab.X, C2R on Slab.Y; ``redistribute``
(``reshape`` before 1.0) False), W on the Y slabs with 1/(2N)² (cuFFT does not scale); C2C
where R2C fails (``transform``).

Correctness: the pair at ``--check-n`` (256) against numpy float64 (rfft2/irfft2 of the padded
map): ``max_rel_error`` = max|y − y_ref| / max|y_ref|. One JSON line per (engine, n, ndev, dtype)
is appended to ``--jsonl`` (MPI: rank 0): devices, versions, padded shape, ``floor_ms``,
``repeats_ms``, ``max_rel_error``, ``elements_per_fft_call``, ``commit``; a failure is a line
with ``error`` and ``traceback``. Subcommands: ``jax`` and ``cufftmp`` (``--n``, ``--ndev``,
``--dtype``, ``--repeats``, ``--jsonl``; cufftmp under ``mpiexec -n 2``), ``report --jsonl``
(the table, with the cuFFTMp/JAX ratio), ``diag`` (versions, ``nvidia-smi -L``). Driver:
``examples/gpu_checks/fft_engines.sh``. CPU dry run: ``JAX_PLATFORMS=cpu
XLA_FLAGS=--xla_force_host_platform_device_count=2 python
examples/benchmarks/benchmark_fft_engines.py jax --n 64 128 --ndev 2 --dtype float64``.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import os
import subprocess
import sys
import time
import traceback
from pathlib import Path

os.environ.setdefault("XLA_PYTHON_CLIENT_PREALLOCATE", "false")

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
FFT_ELEMENTS_MAX = 1 << 30  # per XLA FFT call, as warptrunc.contact.sharded.grid (bug: 2**31)
WARMUP = 2
PACKAGES = (
    "nvmath-python mpi4py cupy cupy-cuda12x cupy-cuda13x cuda-bindings cuda-python "
    "cuda-core cuda-pathfinder nvidia-nvshmem-cu12 nvidia-nvshmem-cu13 nvidia-cufftmp-cu12 "
    "nvidia-cufftmp-cu13 jax jaxlib jax-cuda12-plugin jax-cuda12-pjrt jax-cuda13-plugin "
    "jax-cuda13-pjrt numpy"
).split()


# --- shared: environment, records, the kernel and the reference ---------------------------------


def versions() -> dict:
    """Installed versions of the packages that matter here (absent ones left out)."""
    from importlib import metadata

    out = {}
    for name in PACKAGES:
        with contextlib.suppress(metadata.PackageNotFoundError):
            out[name] = metadata.version(name)
    return out


def nvidia_smi() -> list[str]:
    """``nvidia-smi -L`` lines (or the reason there are none)."""
    try:
        r = subprocess.run(["nvidia-smi", "-L"], capture_output=True, text=True, timeout=30)
        return r.stdout.strip().splitlines() or [f"nvidia-smi: rc {r.returncode} {r.stderr[:200]}"]
    except (OSError, subprocess.SubprocessError) as exc:
        return [f"nvidia-smi: {type(exc).__name__}: {exc}"]


def commit() -> str | None:
    """$WARPTRUNC_GIT_COMMIT, else git's HEAD, else None."""
    if os.environ.get("WARPTRUNC_GIT_COMMIT"):
        return os.environ["WARPTRUNC_GIT_COMMIT"].strip()
    with contextlib.suppress(OSError, subprocess.SubprocessError):
        r = subprocess.run(
            ["git", "-C", str(ROOT), "rev-parse", "HEAD"],
            capture_output=True,
            text=True,
            timeout=10,
        )
        return r.stdout.strip() or None
    return None


def diagnostics() -> dict:
    return {
        "record": "diagnostics",
        "python": sys.version.split()[0],
        "versions": versions(),
        "nvidia_smi": nvidia_smi(),
        "cuda_visible_devices": os.environ.get("CUDA_VISIBLE_DEVICES"),
        "commit": commit(),
    }


def emit(path: Path | None, record: dict) -> None:
    """Print one JSON line and append it to ``path``."""
    line = json.dumps({"time": time.strftime("%Y-%m-%dT%H:%M:%S"), **record}, default=str)
    print(line, flush=True)
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(path, "a", encoding="utf-8") as f:
            f.write(line + "\n")


def fail(rec: dict, exc: BaseException) -> dict:
    rec["error"] = f"{type(exc).__name__}: {exc}"[:2000]
    rec["traceback"] = traceback.format_exc()[-6000:]
    print(rec["traceback"], file=sys.stderr, flush=True)
    return rec


def kernel(xp, big: int, col0: int, ncols: int, half: bool = True, dtype=np.float64):
    """W = 1 / (1 + 8|f|), columns col0 … of the half (or full) spectrum; xp: numpy, cupy, jnp."""
    fy = xp.fft.fftfreq(big)[:, None]
    fx = (xp.fft.rfftfreq(big) if half else xp.fft.fftfreq(big))[col0 : col0 + ncols][None, :]
    return (1.0 / (1.0 + 8.0 * xp.sqrt(fy * fy + fx * fx))).astype(dtype)


def check_input(n: int) -> np.ndarray:
    return np.random.default_rng(42).standard_normal((n, n))


def reference(x: np.ndarray) -> np.ndarray:
    """The pair in numpy float64: pad, rfft2, W, irfft2, the N × N block."""
    n = x.shape[0]
    xp = np.zeros((2 * n, 2 * n))
    xp[:n, :n] = x
    s = np.fft.rfft2(xp) * kernel(np, 2 * n, 0, n + 1)
    return np.fft.irfft2(s, s=(2 * n, 2 * n))[:n, :n]


def rel_error(y: np.ndarray, ref: np.ndarray) -> float:
    return float(np.max(np.abs(y.astype(np.float64) - ref)) / np.max(np.abs(ref)))


def stats(ts: list[float]) -> dict:
    return {"floor_ms": 1e3 * float(np.median(ts)), "repeats_ms": [1e3 * t for t in ts]}


def blocks(count: int, per: int) -> int:
    """The fewest blocks dividing ``count`` with FFT calls (count/blocks × per) in the limit."""
    need = -(-count * per // FFT_ELEMENTS_MAX)
    return 1 if need <= 1 else next(k for k in range(need, count + 1) if count % k == 0)


# --- engine 1: JAX/XLA, one process -------------------------------------------------------------


def shard_map_fn(jax):
    if hasattr(jax, "shard_map"):  # JAX >= 0.7
        return jax.shard_map
    from jax.experimental.shard_map import shard_map

    return lambda f, *, mesh, in_specs, out_specs: shard_map(
        f, mesh, in_specs=in_specs, out_specs=out_specs, check_rep=False
    )


class JaxPair:
    """The plain padded pair of one (n, dtype) on a Mesh("x"): input and output (2n, n) in row
    slabs (the rows below n are the pad's: zeros in, ignored out)."""

    def __init__(self, jax, mesh, n: int, dtype: str) -> None:
        import jax.numpy as jnp
        from jax.sharding import NamedSharding
        from jax.sharding import PartitionSpec as P

        self.jax, self.n, self.dtype = jax, n, np.dtype(dtype)
        ndev, big, nk = mesh.devices.size, 2 * n, n + 1
        if big % ndev:
            raise ValueError(f"2n = {big} is not a multiple of ndev = {ndev}")
        nkp = -(-nk // ndev) * ndev  # the half spectrum's columns, padded to a multiple of ndev
        rows, cols = big // ndev, nkp // ndev
        kr, kc = blocks(rows, big), blocks(cols, big)
        self.elements = max(rows // kr * big, big * -(-cols // kc))
        if self.elements >= 1 << 31:
            raise ValueError(f"an FFT call of {self.elements} elements (openxla/xla#45009)")
        self.blocks = {"rows": kr, "cols": kc}
        R, C = P("x", None), P(None, "x")
        self.rows, self.cols = NamedSharding(mesh, R), NamedSharding(mesh, C)
        smap, rdt = shard_map_fn(jax), self.dtype

        def in_rows(fn, a):  # row blocks through lax.map (a reshape, no copy)
            if kr == 1:
                return fn(a)
            out = jax.lax.map(fn, a.reshape(kr, rows // kr, a.shape[1]))
            return out.reshape(rows, out.shape[2])

        def in_cols(fn, *arrays):  # column blocks: static slices
            if kc == 1:
                return fn(*arrays)
            b = -(-cols // kc)
            parts = [fn(*(a[:, j : j + b] for a in arrays)) for j in range(0, cols, b)]
            return jnp.concatenate(parts, axis=1)

        def forward_x(a):
            s = in_rows(lambda r: jnp.fft.rfft(r, n=big, axis=1), a)
            return jnp.pad(s, ((0, 0), (0, nkp - nk)))

        def columns(s, w):
            return in_cols(lambda c, v: jnp.fft.ifft(jnp.fft.fft(c, axis=0) * v, axis=0), s, w)

        def inverse_x(s):
            return in_rows(lambda r: jnp.fft.irfft(r[:, :nk], n=big, axis=1)[:, :n].astype(rdt), s)

        def pair(x, w):
            s = smap(forward_x, mesh=mesh, in_specs=R, out_specs=R)(x)
            s = jax.lax.with_sharding_constraint(s, self.cols)  # all-to-all
            s = smap(columns, mesh=mesh, in_specs=(C, C), out_specs=C)(s, w)
            s = jax.lax.with_sharding_constraint(s, self.rows)  # all-to-all
            return smap(inverse_x, mesh=mesh, in_specs=R, out_specs=R)(s)

        self.fn = jax.jit(pair, out_shardings=self.rows)

        def make_w():
            w = kernel(jnp, big, 0, nk, dtype=rdt)
            return jnp.pad(w, ((0, 0), (0, nkp - nk)), constant_values=1)

        self.w = jax.jit(make_w, out_shardings=self.cols)()

        def make_x(key):
            u = jax.random.uniform(key, (big, n), rdt)
            return jnp.where(jnp.arange(big)[:, None] < n, u, 0)

        self.make_x = jax.jit(make_x, out_shardings=self.rows)

    def put(self, x: np.ndarray):
        a = np.concatenate([x, np.zeros_like(x)]).astype(self.dtype)  # x's rows, the pad's
        return self.jax.make_array_from_callback(a.shape, self.rows, lambda i: a[i])

    def __call__(self, x):
        return self.fn(x, self.w)


def jax_time(jax, fn, repeats: int) -> tuple[float, list[float]]:
    """The first call (compile included) and the timed ones after the warm-up calls (s)."""
    ts = []
    for _ in range(WARMUP + repeats):
        t = time.perf_counter()
        jax.block_until_ready(fn())
        ts.append(time.perf_counter() - t)
    return ts[0], ts[WARMUP:]


def run_jax(args) -> None:
    emit(args.jsonl, diagnostics())
    import jax

    jax.config.update("jax_enable_x64", True)
    from jax.sharding import Mesh

    base = {
        "record": "measurement",
        "versions": versions(),
        "commit": commit(),
        "ndev": args.ndev,
        "check_n": args.check_n,
    }
    try:
        devices = jax.devices()[: args.ndev]
        if len(devices) < args.ndev:
            raise RuntimeError(f"{len(devices)} devices, {args.ndev} asked: {jax.devices()}")
        mesh = Mesh(np.array(devices, dtype=object), ("x",))
        base["devices"] = [f"{d.device_kind} ({d.platform}:{d.id})" for d in devices]
    except Exception as exc:  # every measurement fails alike: one line
        emit(args.jsonl, fail({**base, "engine": "jax"}, exc))
        return
    for dtype in args.dtype:
        try:  # the check at check_n, once per dtype
            x = check_input(args.check_n)
            pair = JaxPair(jax, mesh, args.check_n, dtype)
            y = np.asarray(pair(pair.put(x)))[: args.check_n]
            err = rel_error(y, reference(x))
        except Exception as exc:
            err = f"check failed: {type(exc).__name__}: {exc}"
            traceback.print_exc()
        for n in args.n:
            rec = {
                **base,
                "engine": "jax",
                "n": n,
                "padded_shape": [2 * n, 2 * n],
                "dtype": dtype,
                "max_rel_error": err,
            }
            try:
                pair = JaxPair(jax, mesh, n, dtype)
                rec["elements_per_fft_call"], rec["fft_blocks"] = pair.elements, pair.blocks
                x = pair.make_x(jax.random.PRNGKey(0))
                rec["compile_s"], ts = jax_time(jax, lambda p=pair, a=x: p(a), args.repeats)
                rec.update(stats(ts))
                del pair, x
            except Exception as exc:
                fail(rec, exc)
            emit(args.jsonl, rec)
            if args.pruned and args.ndev >= 2:
                emit(args.jsonl, run_pruned(jax, devices, n, dtype, args.repeats, base))


def run_pruned(jax, devices, n: int, dtype: str, repeats: int, base: dict) -> dict:
    """The solver's pruned convolution (benchmark_sharded.py's floor: ``hs.apply(q)``)."""
    rec = {
        **base,
        "engine": "jax-pruned",
        "n": n,
        "padded_shape": [2 * n, 2 * n],
        "dtype": dtype,
        "max_rel_error": None,
    }
    try:
        if str(ROOT) not in sys.path:
            sys.path.insert(1, str(ROOT))
        from warptrunc.contact.sharded.fft import ShardedHalfSpace

        e_star = 70e9 / (1 - 0.33**2)
        hs = ShardedHalfSpace(
            (n, n),
            (1e-3 / n, 1e-3 / n),
            e_star,
            substrate="free",
            dtype=dtype,
            devices=list(devices),
        )
        rec["unit_force_check"] = float(hs.check)
        rec["grid_shape"], rec["column_blocks"] = list(hs.layout.grid_shape), hs.layout.blocks
        q = hs.full(1.0)
        rec["compile_s"], ts = jax_time(jax, lambda: hs.apply(q), repeats)
        rec.update(stats(ts))
    except Exception as exc:
        fail(rec, exc)
    return rec


# --- engine 2: cuFFTMp through nvmath-python, MPI ranks -----------------------------------------


def slab(total: int, rank: int, size: int) -> tuple[int, int]:
    """cuFFTMp's slab of ``total`` on ``rank``: (start, count); the first total % size hold more."""
    sizes = [total // size + (1 if r < total % size else 0) for r in range(size)]
    return sum(sizes[:rank]), sizes[rank]


class CufftmpPair:
    """The padded pair of one (n, dtype) with cuFFTMp: R2C on Slab.X (rows of the padded grid),
    W on the Y slabs, C2R back to Slab.X; or C2C both ways (``transform="C2C"``)."""

    def __init__(self, nvd, Slab, cp, comm, n: int, dtype: str, transform: str) -> None:
        self.cp, self.nvd, self.Slab, self.comm = cp, nvd, Slab, comm
        self.n, self.transform, self.rdt = n, transform, np.dtype(dtype)
        self.a = self.fwd = self.inv = None
        row0, self.nrows = slab(2 * n, comm.Get_rank(), comm.Get_size())
        self.row0, self.k = row0, max(0, min(n - row0, self.nrows))  # x's rows in this slab

    def setup(self) -> None:
        """Allocate (symmetric heap), plan both transforms, W on this rank's Y slab."""
        cp, fft, Slab, n = self.cp, self.nvd.fft, self.Slab, self.n
        big, r2c = 2 * n, self.transform == "R2C"
        cdt = np.dtype(np.complex64 if self.rdt == np.float32 else np.complex128)
        names = {f.name for f in dataclasses.fields(fft.FFTOptions)}  # 1.0 renamed reshape
        opts = {"redistribute" if "redistribute" in names else "reshape": False}
        self.a = fft.allocate_operand(
            (self.nrows, big),
            cp,
            input_dtype=self.rdt if r2c else cdt,
            distribution=Slab.X,
            fft_type=self.transform,
        )
        self.a.fill(0)
        if r2c:
            self.fwd = fft.FFT(self.a, distribution=Slab.X, options={**opts, "fft_type": "R2C"})
            self.kw_fwd, self.kw_inv = {}, {}
        else:
            self.fwd = fft.FFT(self.a, distribution=Slab.X, options=opts)
            self.kw_fwd = {"direction": fft.FFTDirection.FORWARD}
            self.kw_inv = {"direction": fft.FFTDirection.INVERSE}
        self.fwd.plan()
        b = self.fwd.execute(**self.kw_fwd)  # the Y-slab view of the spectrum
        inv_opts = {**opts, "fft_type": "C2R"} if r2c else opts
        self.inv = fft.FFT(b, distribution=Slab.Y, options=inv_opts)
        self.inv.plan()
        cols = b.shape[1]
        col0 = sum(self.comm.allgather(cols)[: self.comm.Get_rank()])
        w = kernel(cp, big, col0, cols, half=r2c) / float(big) ** 2  # cuFFT leaves 1/(2N)² out
        self.w = w.astype(self.rdt)
        self.out = cp.empty((self.k, n), self.rdt)
        self.shapes = {"input": list(self.a.shape), "spectrum": list(b.shape)}
        self.elements = int(self.nrows * big)

    def __call__(self, x):
        """x: this rank's (k, n) rows of the map (cupy); returns its rows of the result."""
        a, n, k = self.a, self.n, self.k
        a.fill(0)
        a[:k, :n] = x
        b = self.fwd.execute(**self.kw_fwd)  # symmetric-memory sync first (the default)
        b *= self.w
        c = self.inv.execute(**self.kw_inv)
        self.out[...] = c[:k, :n] if self.transform == "R2C" else c[:k, :n].real
        return self.out

    def free(self) -> str | None:
        """Free plans and buffer (collective: all ranks, same order); the error as text, or None."""
        try:
            for f in (self.inv, self.fwd):
                if f is not None:
                    f.free()
            if self.a is not None:
                self.nvd.free_symmetric_memory(self.a)
        except Exception as exc:
            traceback.print_exc()
            return f"{type(exc).__name__}: {exc}"
        finally:
            self.inv = self.fwd = self.a = None
        return None


def heap_bytes(ns: list[int], dtypes: list[str], size: int) -> int:
    """NVSHMEM_SYMMETRIC_SIZE (unless set) for the largest case: the in-place buffer (the larger
    complex slab, X or Y), two workspaces of that size at most, 1 GiB."""
    n, item = max(ns), 16 if "float64" in dtypes else 8
    buf = max((2 * n // size + 1) * (n + 1), 2 * n * ((n + 1) // size + 1)) * item
    return int((-(-(3 * buf + (1 << 30)) // (1 << 30))) << 30)


def run_cufftmp(args) -> None:
    from mpi4py import MPI

    comm = MPI.COMM_WORLD
    rank, size = comm.Get_rank(), comm.Get_size()
    out = args.jsonl if rank == 0 else None
    emit(out, diagnostics())  # every rank prints its own; rank 0 writes
    base = {
        "record": "measurement",
        "engine": "cufftmp",
        "versions": versions(),
        "commit": commit(),
        "ndev": size,
        "ndev_asked": args.ndev,
        "check_n": args.check_n,
        "mpi": MPI.Get_library_version().strip()[:200],
    }
    try:
        import cupy as cp

        device_id = rank % cp.cuda.runtime.getDeviceCount()
        cp.cuda.Device(device_id).use()
        name = cp.cuda.runtime.getDeviceProperties(device_id)["name"]
        name = getattr(name, "decode", lambda: name)()  # bytes in CuPy 13 and 14
        base["devices"] = comm.allgather(f"{name} (cuda:{device_id}, rank {rank})")
        if size != args.ndev:  # e.g. an mpiexec of another MPI than mpi4py's: singletons
            raise RuntimeError(f"MPI world size {size}, --ndev {args.ndev}")
        os.environ.setdefault(
            "NVSHMEM_SYMMETRIC_SIZE", str(heap_bytes([*args.n, args.check_n], args.dtype, size))
        )
        base["nvshmem_symmetric_size"] = os.environ["NVSHMEM_SYMMETRIC_SIZE"]
        import nvmath.distributed as nvd

        try:
            from nvmath.distributed.distribution import Slab
        except ImportError:  # before nvmath-python 0.7
            from nvmath.distributed.fft import Slab
        group = nvd.MPIProcessGroup(comm) if hasattr(nvd, "MPIProcessGroup") else comm  # >= 0.9
        nvd.initialize(device_id, group, backends=["nvshmem"])
    except Exception as exc:
        rec = fail(dict(base), exc)
        for dtype, n in ((d, n) for d in args.dtype for n in args.n if rank == 0):
            emit(out, {**rec, "n": n, "dtype": dtype})
        return
    order = ("R2C", "C2C")  # C2C only where R2C fails
    for dtype in args.dtype:
        err, tried = None, []
        for transform in order:
            pair = CufftmpPair(nvd, Slab, cp, comm, args.check_n, dtype, transform)
            try:  # the check at check_n (it picks the transform too)
                x = check_input(args.check_n)
                pair.setup()
                parts = comm.gather(pair(cp.asarray(x[pair.row0 : pair.row0 + pair.k])).get())
                err = rel_error(np.concatenate(parts), reference(x)) if rank == 0 else None
                err = comm.bcast(err, root=0)
                break
            except Exception as exc:
                tried.append(f"{transform}: {type(exc).__name__}: {exc}"[:1000])
                traceback.print_exc()
                err = "check failed: " + tried[-1]
            finally:
                pair.free()
        order = (transform,)
        for n in args.n:
            rec = {
                **base,
                "n": n,
                "padded_shape": [2 * n, 2 * n],
                "dtype": dtype,
                "transform": transform,
                "max_rel_error": err,
                "transforms_failed": tried,
                "api": "nvmath.distributed.fft: allocate_operand, FFT.plan/execute, no redistribution, "
                + ("R2C on Slab.X, C2R on Slab.Y" if transform == "R2C" else "C2C"),
            }
            pair = CufftmpPair(nvd, Slab, cp, comm, n, dtype, transform)
            try:
                pair.setup()
                rec["local_shapes"], rec["elements_per_fft_call"] = pair.shapes, pair.elements
                rng = cp.random.default_rng(rank)  # one row at least: a rank may hold none
                x = rng.random((max(pair.k, 1), n), dtype=pair.rdt)[: pair.k]
                stream, ts = cp.cuda.get_current_stream(), []
                for _ in range(WARMUP + args.repeats):
                    comm.Barrier()
                    t = time.perf_counter()
                    pair(x)
                    stream.synchronize()
                    ts.append(time.perf_counter() - t)
                slowest = np.max(np.array(comm.allgather(ts)), axis=0)  # per call, over ranks
                rec["first_call_ms"] = 1e3 * float(slowest[0])
                rec.update(stats([float(v) for v in slowest[WARMUP:]]))
            except Exception as exc:
                fail(rec, exc)
            finally:
                rec["free_error"] = pair.free()
            errors = comm.gather(rec.get("error"))
            if rank == 0:
                emit(out, {**rec, "error_by_rank": errors} if any(errors) else rec)
    try:
        nvd.finalize()
    except Exception:
        traceback.print_exc()


# --- report --------------------------------------------------------------------------------------


def report(args) -> None:
    """The table of the measurements in ``--jsonl`` (the last line of each key wins)."""
    last = {}
    for line in args.jsonl.read_text().splitlines():
        try:
            r = json.loads(line)
        except ValueError:
            continue
        if r.get("record") == "measurement":
            last[(r.get("engine"), r.get("n"), r.get("ndev"), r.get("dtype"))] = r
    jax_floor = {k[1:]: r["floor_ms"] for k, r in last.items() if k[0] == "jax" and "floor_ms" in r}
    print(
        f"\n{'engine':<11} {'n':>6} {'ndev':>4} {'dtype':>8} {'floor ms':>9} {'min ms':>8} "
        f"{'error':>9} {'/ jax':>6}  transform, device"
    )
    key = lambda kv: (kv[0][1] or 0, kv[0][2] or 0, str(kv[0][3]), str(kv[0][0]))  # noqa: E731
    for (engine, n, ndev, dtype), r in sorted(last.items(), key=key):
        head = f"{engine!s:<11} {n!s:>6} {ndev!s:>4} {dtype!s:>8}"
        if "floor_ms" not in r:
            print(f"{head}  ERROR {str(r.get('error', '?'))[:100]}")
            continue
        e = r.get("unit_force_check" if engine == "jax-pruned" else "max_rel_error")
        e = f"{e:9.1e}" if isinstance(e, float) else f"{str(e)[:9]:>9}"
        base = jax_floor.get((n, ndev, dtype))
        ratio = f"{r['floor_ms'] / base:6.2f}" if base and engine != "jax" else " " * 6
        dev = (r.get("devices") or [""])[0]
        print(
            f"{head} {r['floor_ms']:9.2f} {min(r['repeats_ms']):8.2f} {e} {ratio}  "
            f"{r.get('transform', '')} {dev}".rstrip()
        )
    print(
        "\n/ jax: the floor over the jax (plain pair) floor of the same n, ndev, dtype (cufftmp:"
        " cuFFTMp/JAX). error: max|y - y_ref| / max|y_ref| at check_n against numpy float64; "
        "jax-pruned: the solver's unit-force check (Love's kernel)."
    )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("engine", choices=("jax", "cufftmp", "report", "diag"))
    ap.add_argument("--n", type=int, nargs="+", default=[8192, 16384], help="map sides N")
    ap.add_argument("--ndev", type=int, default=2, help="devices (jax); mpiexec -n (cufftmp)")
    ap.add_argument("--dtype", nargs="+", default=["float32"], choices=("float32", "float64"))
    ap.add_argument("--repeats", type=int, default=10, help="timed calls after 2 warm-up calls")
    ap.add_argument("--check-n", type=int, default=256, help="N of the check against numpy")
    ap.add_argument(
        "--no-pruned",
        dest="pruned",
        action="store_false",
        help="skip the solver's pruned convolution (jax)",
    )
    ap.add_argument("--jsonl", type=Path, default=Path("fft_engines.jsonl"), help="results file")
    args = ap.parse_args(argv)
    diag = lambda _: emit(None, diagnostics())  # noqa: E731
    {"jax": run_jax, "cufftmp": run_cufftmp, "report": report, "diag": diag}[args.engine](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
