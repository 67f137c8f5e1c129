# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic half-space on a pixel grid: influence-coefficient spectra and the FFT convolution.

Discretisation (identical to ContactMechanics' ``FreeFFTElasticHalfSpace`` and
``PeriodicFFTElasticHalfSpace``, so that both solve the same discrete problem):

* **free** (default): the (ny, nx) map is an isolated patch, zero-padded to (2ny, 2nx)
  (Hockney 1970); the displacement at a pixel centre due to a uniform pressure on a rectangular
  pixel of sides dx × dy is Love's (1929) closed form divided by π·E*, sampled at the
  separations ``x = i·dx`` for ``i ≤ nx`` and ``(i − 2nx)·dx`` above, and transformed once.
  The convolution of a force map with it is then exact (aperiodic) for sources on the map.
* **periodic**: the map repeats; a displacement mode of wavevector q (rad/m) has stiffness
  q·E*/2 per unit area. q = 0 has no finite stiffness; as in ContactMechanics the mean
  displacement gets the mean of the stiffnesses of the two lowest modes,
  π·E*·(1/Lx + 1/Ly)/2, so F(δ) depends on that convention, the pressure at a given mean
  pressure does not.

The spectrum ``W = FFT(G)/(dx·dy)`` (m/N) is real and even; it is computed in float64 once per
:class:`ElasticHalfSpace` (one per solver, reused by every solve): on a CUDA device with CuPy and
cuFFT on the device (the free half-space; no host memory at the paper's sizes), otherwise on the
host, cached by (grid, pixel size, E*, substrate) (:func:`influence_spectrum`). W is even in y
too, so the half-space keeps its rows 0 … Ny//2 only.

Pruned transforms. Forces live on the (ny, nx) map and only the map's displacements are needed,
so the free half-space never forms the (2ny, 2nx) grid: the forward transform is a real-to-complex
FFT along x of the ny map rows (each row stored with its zero pad, length 2nx) into the first ny
rows of a (2ny, nx + 1) spectrum whose other rows are zeroed, then a complex FFT along y of every
column; the inverse is the complex inverse FFT along y, then the complex-to-real FFT along x of the
first ny rows only. Both equal the full zero-padded transforms to round-off
(``tests/test_contact.py::test_pruned_transform_equals_full``) at about three quarters of their
work (the x transforms of the pad rows are skipped both ways). The periodic half-space is the
same with no pad (Nx = nx, Ny = ny). Transforms are unnormalised both ways; the 1/N of the
inverse is folded into the spectral kernel (``warptrunc.kernels.contact_reduce.spectral_kernel``),
which also forms t·K·t by Parseval in the same pass. A few forces are also applied by direct
summation over the real-space influence table (:func:`influence_table`, held by the half-space).

FFT backends, one algorithm: on a CUDA device three cuFFT plans (``cupy.cuda.cufft.PlanNd``
with the advanced data layout: the batched row R2C, the strided in-place column C2C, the row
C2R in place, so no transposes and no copies) executed on Warp's own stream (CuPy's view of it:
``cupy.cuda.Stream.from_external`` on CuPy ≥ 14, ``ExternalStream`` before), so kernels and
transforms stay ordered with no device-wide synchronisation; the buffers are Warp arrays, handed to cuFFT by pointer
(``cupy.cuda.UnownedMemory``; no copies, no ``__cuda_array_interface__``). On the CPU ``scipy.fft``
(``workers=os.cpu_count()``) performs the same three steps on the same buffers.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np
import scipy.fft
import warp as wp

from .._support.device import resolve_device
from ..kernels import contact_reduce as _kr
from .influence import (
    SUBSTRATES,
    LaneReduction,
    free_spectrum_cupy,
    influence_spectrum,
    influence_table,
)

__all__ = [
    "SUBSTRATES",
    "ElasticHalfSpace",
]

DTYPES = {
    "float64": (wp.float64, wp.vec2d, np.float64),
    "float32": (wp.float32, wp.vec2f, np.float32),
}


_CUPY_STREAMS: dict[tuple[int, int], Any] = {}


def cupy_stream(cupy, stream: wp.Stream, ordinal: int):
    """CuPy's view of a Warp stream, so that cuFFT runs on it.

    CuPy ≥ 14 deprecates ``cupy.cuda.ExternalStream`` for ``Stream.from_external`` (the CUDA
    stream protocol, ``__cuda_stream__``, which Warp's streams implement); older CuPy has only
    the former. A ``Stream`` made by ``from_external`` destroys its handle when collected, so the
    views are kept for the life of the process (one per Warp stream), never collected.
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


class ElasticHalfSpace:
    """Pixel-force → displacement operator K of an elastic half-space, on a Warp device.

    Parameters
    ----------
    shape : (int, int)
        Map size (ny, nx).
    pixel_size : (float, float)
        Pixel sides (dx, dy) (m).
    contact_modulus : float
        Contact modulus E* (Pa).
    substrate : {"free", "periodic"}
        Zero-padded isolated patch (default) or periodic map.
    dtype : {"float64", "float32"}
        Precision of the arrays and transforms (reductions are float64 either way).
    device : str or warp Device, optional
        Warp device (default: see :func:`warptrunc.resolve_device`).

    Notes
    -----
    Inputs are (ny, Nx) buffers (:meth:`map_buffer`) whose columns nx … Nx−1 stay zero; the map
    is the view ``buffer[:, :nx]``. The half-space owns one work spectrum and returns results as a
    view into it, valid until its next transform.

    Raises
    ------
    ValueError
        Unknown substrate or dtype.
    ImportError
        On a CUDA device without CuPy (``pip install "warptrunc[gpu]"``).
    """

    def __init__(
        self,
        shape: tuple[int, int],
        pixel_size: tuple[float, float],
        contact_modulus: float,
        *,
        substrate: str = "free",
        dtype: str = "float64",
        device: wp.DeviceLike = None,
    ) -> None:
        if substrate not in SUBSTRATES:
            raise ValueError(f"substrate must be one of {SUBSTRATES}, got {substrate!r}")
        if dtype not in DTYPES:
            raise ValueError(f"dtype must be one of {tuple(DTYPES)}, got {dtype!r}")
        self.device = resolve_device(device)
        self.shape = (int(shape[0]), int(shape[1]))
        self.substrate = substrate
        self.dtype = dtype
        self.scalar, self.vec2, self.np_dtype = DTYPES[dtype]
        ny, nx = self.shape
        self.grid = (2 * ny, 2 * nx) if substrate == "free" else (ny, nx)
        self.n_total = self.grid[0] * self.grid[1]
        self.spectrum_shape = (self.grid[0], self.grid[1] // 2 + 1)
        self.reduction = LaneReduction(self.device, max(self.n_total // 2, ny * nx))
        self._cp = None
        pixel = (float(pixel_size[0]), float(pixel_size[1]))
        rows = self.grid[0] // 2 + 1
        if self.device.is_cuda:
            try:
                import cupy
                import cupyx.scipy.fft
            except ImportError as exc:
                raise ImportError(
                    f"the contact solver on {self.device} needs CuPy for cuFFT ({exc}); "
                    'install it with: pip install "warptrunc[gpu]"'
                ) from exc
            self._cp = (cupy, cupyx.scipy.fft)
        if self._cp is not None and substrate == "free":
            # the free spectrum on the device: no host memory or host FFT at the paper's sizes
            cupy, cfft = self._cp
            with cupy.cuda.Device(self.device.ordinal):
                w, table = free_spectrum_cupy(
                    self.shape, pixel, float(contact_modulus), cupy, cfft
                )
                w = w.astype(self.np_dtype, copy=False)
                table = table.astype(self.np_dtype, copy=False)
                cupy.cuda.get_current_stream().synchronize()
                views = [wp.array(ptr=a.data.ptr, dtype=self.scalar, shape=a.shape,
                                  device=self.device) for a in (w, table)]  # fmt: skip
                # Warp-owned copies, so that CuPy's pool can let go of the work arrays
                self.spectrum, self.table = (wp.clone(v) for v in views)
                wp.synchronize_stream(wp.get_stream(self.device))
                del views, w, table
                cupy.get_default_memory_pool().free_all_blocks()
        else:
            w = influence_spectrum(self.shape, pixel, float(contact_modulus), substrate)
            table = influence_table(self.shape, pixel, float(contact_modulus), substrate)
            self.spectrum = wp.array(w[:rows].astype(self.np_dtype), dtype=self.scalar,
                                     device=self.device)  # fmt: skip
            self.table = wp.array(table.astype(self.np_dtype), dtype=self.scalar,
                                  device=self.device)  # fmt: skip
        self.work = wp.zeros(self.spectrum_shape, dtype=self.vec2, device=self.device)
        self._plans = None
        self._views: dict[int, Any] = {}

    # --- buffers ---------------------------------------------------------------------------

    def map_buffer(self) -> tuple[wp.array, wp.array]:
        """Allocate a zeroed input buffer and its map view.

        Returns
        -------
        buf : (ny, Nx) warp array
            Zeroed buffer of the half-space's dtype, the input of :meth:`forward` and
            :meth:`apply`; columns nx … Nx−1 are the zero pad (Nx = 2nx for the free
            half-space, nx for the periodic one) and must stay zero.
        view : (ny, nx) warp array
            The view ``buf[:, :nx]``: the map, where the pixel forces (N) or displacements (m)
            are written.
        """
        buf = wp.zeros((self.shape[0], self.grid[1]), dtype=self.scalar, device=self.device)
        return buf, buf[:, : self.shape[1]]

    def new_spectrum(self) -> wp.array:
        """Allocate a zeroed half spectrum of the half-space's transform.

        Returns
        -------
        (Ny, Nx//2 + 1) warp array of vec2
            Zeroed complex spectrum, (re, im) per element in the half-space's dtype: the layout
            :meth:`forward` writes and :meth:`inverse` reads. (Ny, Nx) = (2ny, 2nx) for the free
            half-space, (ny, nx) for the periodic one.
        """
        return wp.zeros(self.spectrum_shape, dtype=self.vec2, device=self.device)

    def result_map(self, spec: wp.array) -> wp.array:
        """View the real map that :meth:`inverse` wrote into a spectrum's memory.

        Parameters
        ----------
        spec : (Ny, Nx//2 + 1) warp array of vec2
            Spectrum after :meth:`inverse`: its memory holds real rows in the in-place
            complex-to-real layout, 2·(Nx//2 + 1) reals per row.

        Returns
        -------
        (ny, nx) warp array
            Strided view (no copy) of the first ny rows and nx columns, in the half-space's
            dtype and the units of the transformed quantity (m after :meth:`apply`, N after
            ``apply(..., inverse=True)``). It keeps ``spec`` alive and is valid until ``spec``
            is next written.
        """
        ny, nx = self.shape
        row = 2 * self.spectrum_shape[1]  # reals per complex row: the in-place C2R layout
        item = np.dtype(self.np_dtype).itemsize
        view = wp.array(ptr=spec.ptr, dtype=self.scalar, shape=(ny, nx),
                        strides=(row * item, item), device=self.device)  # fmt: skip
        view._spectrum_owner = spec  # keeps the spectrum alive as long as the view
        return view

    @staticmethod
    def bytes_per_grid(shape: tuple[int, int], substrate: str, dtype: str) -> int:
        """Bytes of one real (Ny, Nx) array of the FFT grid (the unit of the memory estimate).

        Parameters
        ----------
        shape : (int, int)
            Map size (ny, nx).
        substrate : {"free", "periodic"}
            Half-space ((Ny, Nx) = (2ny, 2nx) for the free one).
        dtype : {"float64", "float32"}
            Precision.

        Returns
        -------
        int
            Bytes.
        """
        ny, nx = shape
        n = 4 * ny * nx if substrate == "free" else ny * nx
        return n * np.dtype(dtype).itemsize

    @staticmethod
    def memory_bytes(shape: tuple[int, int], substrate: str, dtype: str) -> tuple[int, int]:
        """Device bytes of a half-space: (held, while made).

        Parameters
        ----------
        shape : (int, int)
            Map size (ny, nx).
        substrate : {"free", "periodic"}
            Half-space.
        dtype : {"float64", "float32"}
            Precision.

        Returns
        -------
        (int, int)
            Bytes held for its life: the half kernel spectrum, the influence table, the work
            spectrum, the lane
            partials and cuFFT's work areas (estimated at the size of the data each plan
            transforms; their true size is cuFFT's choice). Bytes in use at the peak of making
            the free spectrum on a CUDA device (float64 whatever the dtype: Love's quadrant, the
            mirrored (2ny, 2nx) grid, its half spectrum and cuFFT's work area, its real part),
            before anything else is allocated.
        """
        ny, nx = shape
        big_y, big_x = (2 * ny, 2 * nx) if substrate == "free" else (ny, nx)
        nk = big_x // 2 + 1
        item = np.dtype(dtype).itemsize
        spectrum = big_y * nk * 2 * item
        kernel = (big_y // 2 + 1) * nk * item
        cufft_work = spectrum + 2 * ny * nk * 2 * item  # columns; rows forward and inverse
        lanes = (65536 + 256) * LaneReduction.COLUMNS * 8
        table = ny * nx * item
        held = kernel + table + spectrum + cufft_work + lanes
        making = 0
        if substrate == "free":
            making = 8 * (3 * (ny + 1) * (nx + 1) + big_y * big_x + 2 * 2 * big_y * nk)
        return int(held), int(making)

    # --- transforms ------------------------------------------------------------------------

    def _complex_view(self, spec: wp.array) -> np.ndarray:
        """CPU: the spectrum's memory as a complex NumPy array (no copy)."""
        return spec.numpy().view(np.result_type(self.np_dtype, np.complex64))[..., 0]

    def _cupy_plans(self):
        """The three cuFFT plans (made once): rows R2C, columns C2C in place, rows C2R in place."""
        if self._plans is None:
            cupy = self._cp[0]
            cufft = cupy.cuda.cufft  # loaded by cupyx.scipy.fft (imported in __init__)
            ny = self.shape[0]
            big_y, big_x = self.grid
            nk = self.spectrum_shape[1]
            if self.dtype == "float64":
                r2c, c2c, c2r = cufft.CUFFT_D2Z, cufft.CUFFT_Z2Z, cufft.CUFFT_Z2D
            else:
                r2c, c2c, c2r = cufft.CUFFT_R2C, cufft.CUFFT_C2C, cufft.CUFFT_C2R
            with cupy.cuda.Device(self.device.ordinal):
                # PlanNd(n, inembed, istride, idist, onembed, ostride, odist, type, batch,
                #        order, last_axis, last_size): element (b, x) at b·dist + x·stride
                rows = cufft.PlanNd((big_x,), (big_x,), 1, big_x, (nk,), 1, nk, r2c, ny,
                                    "C", 1, nk)  # fmt: skip
                cols = cufft.PlanNd((big_y,), (big_y,), nk, 1, (big_y,), nk, 1, c2c, nk,
                                    "C", 0, None)  # fmt: skip
                rows_inv = cufft.PlanNd((big_x,), (nk,), 1, nk, (2 * nk,), 1, 2 * nk, c2r, ny,
                                        "C", 1, big_x)  # fmt: skip
            self._plans = (rows, cols, rows_inv)
            self._directions = (cufft.CUFFT_FORWARD, cufft.CUFFT_INVERSE)
        return self._plans

    def _cupy_view(self, arr: wp.array):
        """A CuPy array over a contiguous Warp buffer's bytes (no copy; cached by address), all
        that ``PlanNd.fft`` reads (``.data.ptr``). Made from the pointer
        (``cupy.cuda.UnownedMemory``, which keeps the Warp array alive), not through
        ``__cuda_array_interface__``."""
        view = self._views.get(arr.ptr)
        if view is None or view[0] is not arr:
            cupy = self._cp[0]
            mem = cupy.cuda.UnownedMemory(arr.ptr, arr.capacity, arr, self.device.ordinal)
            data = cupy.ndarray((arr.capacity,), dtype=cupy.uint8,
                                memptr=cupy.cuda.MemoryPointer(mem, 0))  # fmt: skip
            view = self._views[arr.ptr] = (arr, data)
        return view[1]

    def forward(self, buf: wp.array, spec: wp.array) -> None:
        """Transform a zero-padded map into its half spectrum (unnormalised, real to complex).

        ``spec`` ← the 2-D FFT of the (Ny, Nx) grid whose first ny rows are ``buf`` and whose
        other rows are zero, computed pruned (module docstring). On a CUDA device the cuFFT
        plans run on Warp's stream; nothing is synchronised.

        Parameters
        ----------
        buf : (ny, Nx) warp array
            Input buffer (:meth:`map_buffer`): the map in columns 0 … nx−1 (pixel forces in N,
            or displacements in m), zeros in the pad.
        spec : (Ny, Nx//2 + 1) warp array of vec2
            Output spectrum (:meth:`new_spectrum`), overwritten with the unnormalised
            transform (same units as ``buf``).
        """
        ny = self.shape[0]
        if self._cp is None:
            s = self._complex_view(spec)
            workers = os.cpu_count()
            s[:ny] = scipy.fft.rfft(buf.numpy(), axis=1, workers=workers)
            s[ny:] = 0
            s[...] = scipy.fft.fft(s, axis=0, workers=workers, overwrite_x=True)
            return
        if ny < self.grid[0]:
            spec[ny:].zero_()  # the pad rows: zero before the column transform
        cupy = self._cp[0]
        rows, cols, _ = self._cupy_plans()
        s = self._cupy_view(spec)
        with (
            cupy.cuda.Device(self.device.ordinal),
            cupy_stream(cupy, wp.get_stream(self.device), self.device.ordinal),
        ):
            rows.fft(self._cupy_view(buf), s, self._directions[0])
            cols.fft(s, s, self._directions[0])

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
        cupy = self._cp[0]
        _, cols, rows_inv = self._cupy_plans()
        s = self._cupy_view(spec)
        with (
            cupy.cuda.Device(self.device.ordinal),
            cupy_stream(cupy, wp.get_stream(self.device), self.device.ordinal),
        ):
            cols.fft(s, s, self._directions[1])
            rows_inv.fft(s, s, self._directions[1])
        return self.result_map(spec)

    def spectral(self, mode: int, spec: wp.array, *, col: int = LaneReduction.COLUMNS - 1) -> None:
        """Launch the spectral kernel on a half spectrum, over the lanes of ``reduction``.

        The kernel is ``spectral_kernel`` of ``warptrunc.kernels.contact_reduce``; it multiplies by
        the half-space's spectrum W (m/N) and, for the sums, counts each column that stands for
        two conjugate modes twice. Nothing is read back.

        Parameters
        ----------
        mode : int
            ``SPECTRUM_ENERGY`` (0): ``spec`` is left as is; the lanes' partial sums of
            Σ W·abs(spec)², which is N·Σ x·(K·x) by Parseval (N = Ny·Nx; N·m for pixel forces
            x in newtons), go to column ``col`` of ``reduction.part``. ``SPECTRUM_APPLY`` (1):
            the same sums, then ``spec`` ← W·spec/N (K, with the inverse transform's 1/N).
            ``SPECTRUM_INVERSE`` (2): ``spec`` ← spec/(W·N) (K⁻¹); no sums.
        spec : (Ny, Nx//2 + 1) warp array of vec2
            Spectrum of a map (:meth:`forward`); modified in place by modes 1 and 2.
        col : int, optional
            Column of ``reduction.part`` that gets the partial sums (default the last,
            COLUMNS − 1).
        """
        red = self.reduction
        stride, chunk = red.geometry(spec.shape[0] * spec.shape[1])
        wp.launch(
            _kr.spectral_kernel, dim=red.lanes,
            inputs=[spec, self.spectrum, int(mode), wp.float64(1.0 / self.n_total), self.grid[1],
                    int(col), stride, chunk],
            outputs=[red.part], device=self.device,
        )  # fmt: skip

    def apply(self, buf: wp.array, *, inverse: bool = False, energy_column: int = -1) -> wp.array:
        """Apply the operator K, or its inverse, to a map by FFT convolution.

        K·x gives the displacements (m) of pixel forces x (N) on the map; K⁻¹·x the pixel forces
        (N) of displacements x (m) (the map of K⁻¹ applied to the zero-padded map). One forward
        transform, the spectral kernel and one inverse transform, in the work spectrum; nothing
        is read back.

        Parameters
        ----------
        buf : (ny, Nx) warp array
            Input buffer (:meth:`map_buffer`) holding x on its map, columns 0 … nx−1: pixel
            forces (N), or displacements (m) with ``inverse=True``; the pad stays zero.
        inverse : bool, optional
            False (default): K·x. True: K⁻¹·x.
        energy_column : int, optional
            Forward only. With a value ≥ 0 the lanes of ``reduction`` get the partial sums of
            N·Σ x·(K·x) (N·m times N = Ny·Nx; Parseval) in that column: read them with
            ``reduction.read`` and divide by N. Default −1: the sums go to the last column,
            COLUMNS − 1, as scratch.

        Returns
        -------
        (ny, nx) warp array
            K·x (m) or K⁻¹·x (N), a view into the work spectrum, valid until the half-space's
            next transform.
        """
        self.forward(buf, self.work)
        if inverse:
            self.spectral(_kr.SPECTRUM_INVERSE, self.work)
        else:
            col = energy_column if energy_column >= 0 else LaneReduction.COLUMNS - 1
            self.spectral(_kr.SPECTRUM_APPLY, self.work, col=col)
        return self.inverse(self.work)
