# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The elastic half-space's FFTs of the zero-padded grid: forward, inverse and their cuFFT plans.

Pruned transforms. Forces live on the (ny, nx) map and only the map's displacements are needed,
so the free half-space never forms the (2ny, 2nx) grid: the forward transform is a real-to-complex
FFT along x of the ny map rows (on a CUDA device each row is first written with its zero pad,
length 2nx, into the work spectrum's memory and transformed there in place; the maps themselves
hold no pad) into the first ny
rows of a (2ny, nx + 1) spectrum whose other rows are zeroed, then a complex FFT along y of every
column; the inverse is the complex inverse FFT along y, then the complex-to-real FFT along x of the
first ny rows only. Both equal the full zero-padded transforms to round-off
(``tests/test_contact.py::test_pruned_transform_equals_full``) at about three quarters of their
work (the x transforms of the pad rows are skipped both ways). The periodic half-space is the
same with no pad (Nx = nx, Ny = ny). Transforms are unnormalised both ways; the 1/N of the
inverse is folded into the spectral kernel (``warptrunc.kernels.contact.spectral.spectral_kernel``),
which also forms t·K·t by Parseval in the same pass. A few forces are also applied by direct
summation over the real-space influence table (:func:`influence_table`, held by the half-space).

FFT backends, one algorithm: on a CUDA device (``fft_plan="pruned"``) three cuFFT plans (``cupy.cuda.cufft.PlanNd``
with the advanced data layout: the batched row R2C, the strided in-place column C2C, the row
C2R in place, so no transposes; each executed in at most ``FFT_SLABS`` slabs of rows or columns,
with one work area shared by all plans and allocated, like every CuPy allocation the half-space
makes, from Warp's memory pool) executed on Warp's own stream (CuPy's view of it:
``cupy.cuda.Stream.from_external`` on CuPy ≥ 14, ``ExternalStream`` before), so kernels and
transforms stay ordered with no device-wide synchronisation; the buffers are Warp arrays, handed to cuFFT by pointer
(``cupy.cuda.UnownedMemory``; no copies, no ``__cuda_array_interface__``). On the CPU ``scipy.fft``
(``workers=os.cpu_count()``) performs the same three steps on the same buffers.

With ``fft_plan="full"`` (CUDA, free half-space; ``SolverSettings.fft_plan``) the forward and
inverse transforms are each one in-place 2-D cuFFT plan over the whole (2ny, 2nx) grid (the pad
rows zeroed and the map written with its pad into the work spectrum first): no pruning, but on an
H100 about twice as fast as the strided column transforms at 16384², for a cuFFT work area as
large as the work spectrum. :class:`PaddedTransforms` is the half of
:class:`~warptrunc.contact.halfspace.ElasticHalfSpace` that does this.
"""

from __future__ import annotations

import contextlib
import os
from typing import Any

import numpy as np
import scipy.fft
import warp as wp

from .._support.device import resolve_device
from .._support.docs import fill_doc
from ..kernels.contact import spectral as _kr
from .influence import GRID_DOCS

__all__ = ["FFT_PLANS", "FFT_SLABS", "PaddedTransforms", "cupy_stream"]

_CUPY_STREAMS: dict[tuple[int, int], Any] = {}

FFT_PLANS = ("pruned", "full")
"""cuFFT plans of the free half-space on a CUDA device: ``"pruned"`` row transforms of the map's
rows only and column transforms in slabs (least memory: cuFFT needs next to no work area),
``"full"`` one in-place 2-D plan each way over the whole padded grid (faster, measured 2.3× at
16384² on an H100; cuFFT's work area is then as large as the work spectrum)."""

FFT_SLABS = 8
"""Largest number of slabs a cuFFT transform is cut into (batches of rows or columns, one plan
execution each), so that cuFFT's work area, which may be as large as the data a plan transforms,
stays a fraction of the work spectrum; slabs are never below 256 MiB of data."""

_SLAB_MIN_BYTES = 1 << 28


def cupy_stream(cupy, stream: wp.Stream, ordinal: int):
    """CuPy's view of a Warp stream, so that cuFFT runs on it.

    CuPy ≥ 14 deprecates ``cupy.cuda.ExternalStream`` for ``Stream.from_external`` (the CUDA
    stream protocol, ``__cuda_stream__``, which Warp's streams implement); older CuPy has only
    the former. A ``Stream`` made by ``from_external`` destroys its handle when collected, so the
    views are kept for the life of the process (one per Warp stream), never collected.

    Parameters
    ----------
    cupy : module
        The ``cupy`` module.
    stream : warp Stream
        The Warp stream to run on.
    ordinal : int
        CUDA device ordinal of the stream.

    Returns
    -------
    cupy.cuda.Stream
        CuPy's view of the stream (a context manager: CuPy work inside runs on it).
    """
    key = (ordinal, int(stream.cuda_stream))
    view = _CUPY_STREAMS.get(key)
    if view is None:
        with cupy.cuda.Device(ordinal):
            from_external = getattr(cupy.cuda.Stream, "from_external", None)
            if from_external is not None:
                view = from_external(stream)
            else:
                view = cupy.cuda.ExternalStream(key[1], ordinal)
        _CUPY_STREAMS[key] = view
    return view


class PaddedTransforms:
    """The FFTs of :class:`~warptrunc.contact.halfspace.ElasticHalfSpace` (a mixin: it reads the
    half-space's ``shape``, ``grid``, ``spectrum_shape``, ``substrate``, ``dtype``, ``np_dtype``,
    ``scalar``, ``device``, ``fft_plan``, ``work``, ``_cp``, ``_plans``, ``_views`` and
    ``result_map``)."""

    @staticmethod
    def fft_slabs(n_batch: int, slab_bytes: int) -> list[tuple[int, int]]:
        """Cut a batched transform of ``n_batch`` rows or columns into slabs (module docstring).

        Parameters
        ----------
        n_batch : int
            Rows or columns the plan transforms (dimensionless count).
        slab_bytes : int
            Bytes of one row or column of data (complex) (B).

        Returns
        -------
        list of (int, int)
            (first, count) per slab: at most ``FFT_SLABS`` slabs of at least 256 MiB each (one
            slab for small grids), of at most two distinct counts.
        """
        total = n_batch * slab_bytes
        k = int(min(FFT_SLABS, max(1, total // _SLAB_MIN_BYTES), n_batch))
        size = -(-n_batch // k)
        return [(i, min(size, n_batch - i)) for i in range(0, n_batch, size)]

    def _complex_view(self, spec: wp.array) -> np.ndarray:
        """CPU: the spectrum's memory as a complex NumPy array (no copy)."""
        return spec.numpy().view(np.result_type(self.np_dtype, np.complex64))[..., 0]

    @staticmethod
    def _plan_layout(shape: tuple[int, int], substrate: str, dtype: str, fft_plan: str):
        """What the cuFFT plans transform: a function ``make(cufft)`` that builds the plans dict,
        and the row and column slabs (the pruned plans run one execution per slab)."""
        ny, nx = shape
        big_y, big_x = (2 * ny, 2 * nx) if substrate == "free" else (ny, nx)
        nk = big_x // 2 + 1
        item = 2 * np.dtype(dtype).itemsize  # bytes of one complex element
        free = substrate == "free"
        in_row = 2 * nk if free else big_x  # reals per input row: in place, or the map's
        rows = PaddedTransforms.fft_slabs(ny, nk * item)
        cols = PaddedTransforms.fft_slabs(nk, big_y * item)

        def make(cufft):
            if dtype == "float64":
                r2c, c2c, c2r = cufft.CUFFT_D2Z, cufft.CUFFT_Z2Z, cufft.CUFFT_Z2D
            else:
                r2c, c2c, c2r = cufft.CUFFT_R2C, cufft.CUFFT_C2C, cufft.CUFFT_C2R
            # PlanNd(n, inembed, istride, idist, onembed, ostride, odist, type, batch,
            #        order, last_axis, last_size): element (b, x) at b·dist + x·stride
            plans = {}
            if fft_plan == "full" and free:  # in place over the whole padded grid, one batch
                # (the distances between batches are unused: 1, since past 2³¹ they overflow)
                plans["full"] = cufft.PlanNd(
                    (big_y, big_x), (big_y, 2 * nk), 1, 1, (big_y, nk), 1, 1, r2c, 1, "C", 1, nk
                )
                plans["full_inv"] = cufft.PlanNd(
                    (big_y, big_x), (big_y, nk), 1, 1, (big_y, 2 * nk), 1, 1, c2r, 1, "C", 1, big_x
                )
                return plans
            for _, c in rows:
                plans["rows", c] = cufft.PlanNd(
                    (big_x,), (in_row,), 1, in_row, (nk,), 1, nk, r2c, c, "C", 1, nk
                )
                plans["rows_inv", c] = cufft.PlanNd(
                    (big_x,), (nk,), 1, nk, (2 * nk,), 1, 2 * nk, c2r, c, "C", 1, big_x
                )
            for _, c in cols:
                plans["cols", c] = cufft.PlanNd(
                    (big_y,), (big_y,), nk, 1, (big_y,), nk, 1, c2c, c, "C", 0, None
                )
            return plans

        return make, rows, cols

    @staticmethod
    @fill_doc(GRID_DOCS)
    def cufft_work_bytes(
        shape: tuple[int, int], substrate: str, dtype: str, fft_plan: str, device: wp.DeviceLike
    ) -> int | None:
        """The work area cuFFT asks for the half-space's plans, learnt by making them (no
        transform runs and nothing of that size is allocated).

        Parameters
        ----------
        {shape}
        {substrate}
        {dtype}
        fft_plan : {"pruned", "full"}
            The plans (``warptrunc.contact.halfspace.FFT_PLANS``).
        device : str or warp Device
            A CUDA device.

        Returns
        -------
        int or None
            The largest work area of the plans (B), or None without CuPy or off CUDA.

        Raises
        ------
        ValueError
            cuFFT cannot make these plans (the message says which and why).
        """
        dev = resolve_device(device)
        if not dev.is_cuda:
            return None
        try:
            import cupy
            import cupyx.scipy.fft  # noqa: F401 - loads cupy.cuda.cufft
        except ImportError:
            return None
        make, _, _ = PaddedTransforms._plan_layout(shape, substrate, dtype, fft_plan)
        sizes: list[int] = []
        with cupy.cuda.Device(dev.ordinal):
            dummy = cupy.empty(1, dtype=cupy.uint8)

            def record(size):  # a pointer for the plan to keep; never written
                sizes.append(int(size))
                mem = cupy.cuda.UnownedMemory(dummy.data.ptr, int(size), dummy, dev.ordinal)
                return cupy.cuda.MemoryPointer(mem, 0)

            try:
                with cupy.cuda.using_allocator(record):
                    plans = make(cupy.cuda.cufft)
                del plans
            except Exception as exc:  # cuFFT's errors, named in the message
                raise ValueError(
                    f"cuFFT cannot make the {fft_plan!r} plans of a {shape[0]}×{shape[1]} map "
                    f"({substrate}, {dtype}): {exc}"
                ) from None
        return max(sizes, default=0)

    def _make_plans(self):
        """The cuFFT plans (:meth:`_plan_layout`): made twice, first to learn their work sizes,
        then with one shared work area (they run one after another on one stream)."""
        cupy = self._cp[0]
        cufft = cupy.cuda.cufft  # loaded by cupyx.scipy.fft (imported in __init__)
        make, rows, cols = self._plan_layout(self.shape, self.substrate, self.dtype, self.fft_plan)
        sizes = []

        def record(size):
            sizes.append(int(size))
            mem = cupy.cuda.UnownedMemory(self.work.ptr, int(size), self.work, self.device.ordinal)
            return cupy.cuda.MemoryPointer(mem, 0)

        with cupy.cuda.Device(self.device.ordinal):
            with cupy.cuda.using_allocator(record):
                del_plans = make(cufft)  # never executed: only their work sizes are kept
            del del_plans
            # rows of 2²⁰ 8-byte words: one dimension past 2³¹ − 1 elements (the full plan's
            # work area at 32768²: 2³¹ + 2¹⁶ words) is beyond Warp's int32 shapes
            words = -(-max(1, max(sizes, default=1)) // 8)
            width = min(words, 1 << 20)
            self.fft_work = wp.empty(
                (-(-words // width), width), dtype=wp.float64, device=self.device
            )
            shared = cupy.cuda.UnownedMemory(
                self.fft_work.ptr, self.fft_work.capacity, self.fft_work, self.device.ordinal
            )
            with cupy.cuda.using_allocator(lambda size: cupy.cuda.MemoryPointer(shared, 0)):
                plans = make(cufft)
        self._plans = (plans, rows, cols)
        self._directions = (cufft.CUFFT_FORWARD, cufft.CUFFT_INVERSE)
        return self._plans

    def _cupy_plans(self):
        """The plans and their slabs (made once)."""
        return self._plans if self._plans is not None else self._make_plans()

    def _cupy_view(self, arr: wp.array, offset: int = 0):
        """A CuPy array starting ``offset`` bytes into a contiguous Warp buffer (no copy;
        cached), all that ``PlanNd.fft`` reads (``.data.ptr``). Made from the pointer
        (``cupy.cuda.UnownedMemory``, which keeps the Warp array alive), not through
        ``__cuda_array_interface__``."""
        key = (arr.ptr, offset)
        view = self._views.get(key)
        if view is None or view[0] is not arr:
            cupy = self._cp[0]
            mem = cupy.cuda.UnownedMemory(arr.ptr, arr.capacity, arr, self.device.ordinal)
            data = cupy.ndarray(
                (arr.capacity - offset,),
                dtype=cupy.uint8,
                memptr=cupy.cuda.MemoryPointer(mem, offset),
            )
            view = self._views[key] = (arr, data)
        return view[1]

    @contextlib.contextmanager
    def _cufft(self):
        """CuPy on this device and on Warp's stream, for running the plans: yields the plans,
        their row and column slabs, the half spectrum's row length and the bytes of one real."""
        cupy = self._cp[0]
        plans, rows, cols = self._cupy_plans()
        with (
            cupy.cuda.Device(self.device.ordinal),
            cupy_stream(cupy, wp.get_stream(self.device), self.device.ordinal),
        ):
            yield plans, rows, cols, self.spectrum_shape[1], np.dtype(self.np_dtype).itemsize

    def _real_rows(self, spec: wp.array) -> wp.array:
        """The first ny real rows of a spectrum's memory in the in-place layout, 2·(Nx//2 + 1)
        reals each (a view, no copy)."""
        nk2 = 2 * self.spectrum_shape[1]
        view = wp.array(
            ptr=spec.ptr, dtype=self.scalar, shape=(self.shape[0], nk2), device=self.device
        )
        view._spectrum_owner = spec
        return view

    def forward(self, buf: wp.array, spec: wp.array) -> None:
        """Transform a map, zero-padded, into its half spectrum (unnormalised, real to complex).

        ``spec`` ← the 2-D FFT of the (Ny, Nx) grid whose first ny rows and nx columns are
        ``buf`` and whose other elements are zero, computed pruned (module docstring). On a
        CUDA device the map is copied into the spectrum's first rows with its pad (the real
        layout of an in-place transform; the free half-space) and the cuFFT plans run on Warp's
        stream; nothing is synchronised.

        Parameters
        ----------
        buf : (ny, nx) warp array
            Input map (:meth:`map_buffer`): pixel forces in N, or displacements in m.
        spec : (Ny, Nx//2 + 1) warp array of vec2
            Output spectrum (:meth:`new_spectrum`), overwritten with the unnormalised
            transform (same units as ``buf``).
        """
        ny = self.shape[0]
        big_x = self.grid[1]
        if self._cp is None:
            s = self._complex_view(spec)
            workers = os.cpu_count()
            s[:ny] = scipy.fft.rfft(buf.numpy(), n=big_x, axis=1, workers=workers)
            s[ny:] = 0
            s[...] = scipy.fft.fft(s, axis=0, workers=workers, overwrite_x=True)
            return
        if ny < self.grid[0]:
            spec[ny:].zero_()  # the pad rows: zero before the column transform
        free = self.substrate == "free"
        if free:
            rows_view = self._real_rows(spec)
            wp.launch(
                _kr.pad_rows_kernel,
                dim=rows_view.shape,
                inputs=[buf],
                outputs=[rows_view],
                device=self.device,
            )
        with self._cufft() as (plans, rows, cols, nk, item):
            fwd = self._directions[0]
            if self.fft_plan == "full":
                v = self._cupy_view(spec, 0)
                plans["full"].fft(v, v, fwd)
                return
            for r0, c in rows:
                out = self._cupy_view(spec, r0 * nk * 2 * item)
                src = out if free else self._cupy_view(buf, r0 * big_x * item)
                plans["rows", c].fft(src, out, fwd)
            for c0, c in cols:
                v = self._cupy_view(spec, c0 * 2 * item)
                plans["cols", c].fft(v, v, fwd)

    def inverse(self, spec: wp.array) -> wp.array:
        """Inverse-transform a half spectrum in place and return its real map.

        The unnormalised inverse 2-D FFT (no 1/N; :meth:`spectral` folds it into the kernel) of
        ``spec``, of which only the first ny rows and nx columns are formed; it is written
        into ``spec``'s memory, which it destroys.

        Parameters
        ----------
        spec : (Ny, Nx//2 + 1) warp array of vec2
            Spectrum to transform (:meth:`forward`, then :meth:`spectral`); overwritten.

        Returns
        -------
        (ny, nx) warp array
            The map, a view into ``spec``'s memory (:meth:`result_map`), valid until ``spec`` is
            next written; units those of the spectrum (m for K·x, N for K⁻¹·x).
        """
        ny = self.shape[0]
        big_x = self.grid[1]
        if self._cp is None:
            s = self._complex_view(spec)
            workers = os.cpu_count()
            c = scipy.fft.ifft(s, axis=0, norm="forward", workers=workers, overwrite_x=True)
            r = scipy.fft.irfft(c[:ny], n=big_x, axis=1, norm="forward", workers=workers)
            real = spec.numpy().reshape(spec.shape[0], -1)
            real[:ny, :big_x] = r
            return self.result_map(spec)
        with self._cufft() as (plans, rows, cols, nk, item):
            inv = self._directions[1]
            if self.fft_plan == "full":
                v = self._cupy_view(spec, 0)
                plans["full_inv"].fft(v, v, inv)
                return self.result_map(spec)
            for c0, c in cols:
                v = self._cupy_view(spec, c0 * 2 * item)
                plans["cols", c].fft(v, v, inv)
            for r0, c in rows:
                v = self._cupy_view(spec, r0 * nk * 2 * item)
                plans["rows_inv", c].fft(v, v, inv)
        return self.result_map(spec)
