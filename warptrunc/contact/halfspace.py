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

The spectrum ``W = FFT(G)/(dx·dy)`` (m/N) is real and even; the half-space keeps its rows
0 … Ny//2 only, in its dtype, and the (ny, nx) influence table. Both are built in place once per
:class:`ElasticHalfSpace` (one per solver), in float64 arithmetic whatever the dtype, a slab of
rows or columns at a time (:func:`~warptrunc.contact.influence.build_free_spectrum`: the x
transform of the mirrored rows of Love's quadrant into the work spectrum, used as float64
scratch, then the y transform of its mirrored columns), with CuPy on a CUDA device and NumPy on
the CPU: no (2ny, 2nx) grid, no host copy, temporaries of a few MiB. The periodic table is the
inverse transform of the spectrum.

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
inverse is folded into the spectral kernel (``warptrunc.kernels.contact_reduce.spectral_kernel``),
which also forms t·K·t by Parseval in the same pass. A few forces are also applied by direct
summation over the real-space influence table (:func:`influence_table`, held by the half-space).

FFT backends, one algorithm: on a CUDA device three cuFFT plans (``cupy.cuda.cufft.PlanNd``
with the advanced data layout: the batched row R2C, the strided in-place column C2C, the row
C2R in place, so no transposes; each executed in at most ``FFT_SLABS`` slabs of rows or columns,
with one work area shared by all plans and allocated, like every CuPy allocation the half-space
makes, from Warp's memory pool) executed on Warp's own stream (CuPy's view of it:
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
from .._support.docs import fill_doc
from ..kernels import contact_reduce as _kr
from .influence import (
    GRID_DOCS,
    SUBSTRATES,
    LaneReduction,
    build_free_spectrum,
    build_periodic_spectrum,
)

__all__ = [
    "SUBSTRATES",
    "ElasticHalfSpace",
    "fft_size",
]


def fft_size(n: int) -> int:
    """The smallest 7-smooth integer ≥ n (prime factors 2, 3, 5, 7 only).

    FFT libraries (cuFFT, pocketfft) transform such lengths at full speed; a length with a
    large prime factor falls back to Bluestein's algorithm, several times slower. A free
    half-space transforms 2n, so a map of 5147 pixels (a prime) costs about 5× the time per
    iteration of one of 5160 (measured on an H100: 21 ms against the ~4 ms floor).

    Parameters
    ----------
    n : int
        A length (pixels), ≥ 1.

    Returns
    -------
    int

    Examples
    --------
    >>> fft_size(5147), fft_size(1024), fft_size(11)
    (5184, 1024, 12)
    """
    m = max(1, int(n))
    while True:
        k = m
        for p in (2, 3, 5, 7):
            while k % p == 0:
                k //= p
        if k == 1:
            return m
        m += 1

DTYPES = {
    "float64": (wp.float64, wp.vec2d, np.float64),
    "float32": (wp.float32, wp.vec2f, np.float32),
}


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


def _null():
    import contextlib

    return contextlib.nullcontext()


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


@fill_doc(GRID_DOCS)
class ElasticHalfSpace:
    """Pixel-force → displacement operator K of an elastic half-space, on a Warp device.

    {grid}
    substrate : {"free", "periodic"}
        Zero-padded isolated patch (default) or periodic map.
    dtype : {"float64", "float32"}
        Precision of the arrays and transforms (reductions are float64 either way).
    device : str or warp Device, optional
        Warp device (default: see :func:`warptrunc.resolve_device`).
    fft_plan : {"pruned", "full"}, optional
        cuFFT plans (``warptrunc.contact.halfspace.FFT_PLANS``), for the free substrate on a
        CUDA device; elsewhere the transforms are those of ``"pruned"`` (SciPy's on the CPU).

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
        fft_plan: str = "pruned",
    ) -> None:
        if fft_plan not in FFT_PLANS:
            raise ValueError(f"fft_plan must be one of {FFT_PLANS}, got {fft_plan!r}")
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
        self._plans = None
        # one 2-D plan over the padded grid: the free half-space on a CUDA device only
        self.fft_plan = (fft_plan if substrate == "free" and self.device.is_cuda
                         else "pruned")  # fmt: skip
        self._views: dict[int, Any] = {}
        self.fft_work = None  # the cuFFT plans' one shared work area (CUDA)
        self.spectrum = wp.empty((rows, self.spectrum_shape[1]), dtype=self.scalar,
                                 device=self.device)  # fmt: skip
        self.table = wp.empty(self.shape, dtype=self.scalar, device=self.device)
        self.work = wp.zeros(self.spectrum_shape, dtype=self.vec2, device=self.device)
        self._build(pixel, float(contact_modulus))

    def _build(self, pixel: tuple[float, float], contact_modulus: float) -> None:
        """Fill the kernel spectrum and the influence table in place, in slabs, with the work
        spectrum as the float64 scratch (module docstring): nothing of the map's size is
        allocated besides what the half-space holds, on the device or the host."""
        ny, nx = self.shape
        if self._cp is None:
            xp, rfft = np, None
            spectrum, table = self.spectrum.numpy(), self.table.numpy()
            raw = self.work.numpy().reshape(-1).view(np.uint8)
        else:
            cupy, cfft = self._cp
            xp = cupy

            def rfft(x, axis):
                return cfft.rfft(x, axis=axis)

            spectrum, table, raw = (self._cupy_array(a) for a in (self.spectrum, self.table,
                                                                   self.work))  # fmt: skip
        ctx = self._cupy_context() if self._cp is not None else _null()
        with ctx:
            if self.substrate == "free":
                scratch = raw[: (ny + 1) * (nx + 1) * 8].view(xp.float64).reshape(ny + 1, nx + 1)
                build_free_spectrum(self.shape, pixel, contact_modulus, spectrum, table, scratch,
                                    xp=xp, rfft=rfft)  # fmt: skip
                del scratch
            else:
                build_periodic_spectrum(self.shape, pixel, contact_modulus, spectrum, xp=xp)
            del spectrum, table, raw
            if self._cp is not None:
                self._cp[0].fft.config.get_plan_cache().clear()
        if self.substrate == "periodic":  # the table: the inverse transform of the spectrum
            wp.launch(_kr.expand_spectrum_kernel, dim=self.spectrum_shape,
                      inputs=[self.spectrum, wp.float64(1.0 / self.n_total)], outputs=[self.work],
                      device=self.device)  # fmt: skip
            wp.copy(self.table, self.inverse(self.work))
        self.work.zero_()

    def _cupy_context(self):
        """CuPy on this device, its allocations (FFT work areas, temporaries) served from Warp's
        pool, so that one allocator's high-water mark and tracker see all of the solver's memory."""
        import contextlib

        cupy = self._cp[0]
        device = self.device

        def allocate(size):
            arr = wp.empty(max(1, int(size)), dtype=wp.uint8, device=device)
            mem = cupy.cuda.UnownedMemory(arr.ptr, arr.capacity, arr, device.ordinal)
            return cupy.cuda.MemoryPointer(mem, 0)

        stack = contextlib.ExitStack()
        stack.enter_context(cupy.cuda.Device(device.ordinal))
        # on Warp's stream, so that Warp's stream-ordered frees of these blocks follow their use
        stack.enter_context(cupy_stream(cupy, wp.get_stream(device), device.ordinal))
        stack.enter_context(cupy.cuda.using_allocator(allocate))
        return stack

    def _cupy_array(self, arr: wp.array):
        """A CuPy array of the same shape and dtype over a contiguous Warp array (no copy)."""
        cupy = self._cp[0]
        dt = {wp.float32: np.float32, wp.float64: np.float64, wp.vec2f: np.float32,
              wp.vec2d: np.float64}[arr.dtype]  # fmt: skip
        shape = arr.shape + ((2,) if arr.dtype in (wp.vec2f, wp.vec2d) else ())
        mem = cupy.cuda.UnownedMemory(arr.ptr, arr.capacity, arr, self.device.ordinal)
        out = cupy.ndarray(shape, dtype=dt, memptr=cupy.cuda.MemoryPointer(mem, 0))
        return out if arr.dtype not in (wp.vec2f, wp.vec2d) else out.reshape(-1).view(cupy.uint8)

    # --- buffers ---------------------------------------------------------------------------

    def map_buffer(self) -> tuple[wp.array, wp.array]:
        """Allocate a zeroed input map.

        Returns
        -------
        buf : (ny, nx) warp array
            Zeroed map of the half-space's dtype, the input of :meth:`forward` and
            :meth:`apply`: pixel forces (N) or displacements (m). The free half-space's zero pad
            is never stored: :meth:`forward` writes it into the work spectrum's rows.
        view : (ny, nx) warp array
            The same array (kept so that callers written for padded buffers keep working).
        """
        buf = wp.zeros(self.shape, dtype=self.scalar, device=self.device)
        return buf, buf

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

    @staticmethod
    @fill_doc(GRID_DOCS)
    def memory_terms(
        shape: tuple[int, int], substrate: str, dtype: str, *, cuda: bool = True,
        fft_plan: str = "pruned", device: wp.DeviceLike = None,
    ) -> dict[str, int]:  # fmt: skip
        """Bytes a half-space holds for its life, term by term (its peak: the construction
        works inside these arrays, with temporaries of a few MiB).

        Parameters
        ----------
        {shape}
        substrate : {"free", "periodic"}
            Half-space ((Ny, Nx) = (2ny, 2nx) for the free one, (ny, nx) for the periodic one).
        dtype : {"float64", "float32"}
            Precision.
        cuda : bool, optional
            On a CUDA device: the lane partials are 65536 lanes (64 on the CPU) and cuFFT's
            shared work area is counted.
        fft_plan : {"pruned", "full"}, optional
            The plans (``warptrunc.contact.halfspace.FFT_PLANS``); ``"full"`` counts a work
            area as large as the work spectrum (free substrate on CUDA; measured equal to it on
            an H100 at 10240² and 16384², float32).
        device : str or warp Device, optional
            A CUDA device: cuFFT's work area is then the one cuFFT asks for these plans
            (:meth:`cufft_work_bytes`) instead of the estimate.

        Returns
        -------
        dict of str to int
            ``"kernel spectrum"``: rows 0 … Ny//2 of W, (Ny//2 + 1)·(Nx//2 + 1) reals;
            ``"influence table"``: (ny, nx) reals; ``"work spectrum"``: the one FFT work area,
            Ny·(Nx//2 + 1) complex (the transforms run in it in place, and the construction of W
            uses it as float64 scratch); ``"lane partials"``: the float64 reduction partials;
            ``"cufft work area"``: one area shared by all plans, estimated at the data of the
            largest slab one plan execution transforms (cuFFT's choice; the half-space reports
            the true size as ``fft_work.capacity``).
        """
        ny, nx = shape
        big_y, big_x = (2 * ny, 2 * nx) if substrate == "free" else (ny, nx)
        nk = big_x // 2 + 1
        item = np.dtype(dtype).itemsize
        lanes = 65536 if cuda else min(64, max(1, big_y * nk))
        terms = {
            "kernel spectrum": (big_y // 2 + 1) * nk * item,
            "influence table": ny * nx * item,
            "work spectrum": big_y * nk * 2 * item,
            "lane partials": (lanes + (256 if cuda else 0)) * LaneReduction.COLUMNS * 8,
        }
        exact = (ElasticHalfSpace.cufft_work_bytes(shape, substrate, dtype, fft_plan, device)
                 if cuda and device is not None else None)  # fmt: skip
        if exact is not None:
            terms["cufft work area"] = exact
        elif cuda and fft_plan == "full" and substrate == "free":
            terms["cufft work area"] = big_y * nk * 2 * item
        elif cuda:
            row, col = ElasticHalfSpace.fft_slabs, 2 * item
            work = max(
                max(c for _, c in row(ny, nk * col)) * nk * col,  # rows, R2C / C2R
                max(c for _, c in row(nk, big_y * col)) * big_y * col,  # columns, C2C
            )
            terms["cufft work area"] = work
        return terms

    @staticmethod
    @fill_doc(GRID_DOCS)
    def memory_bytes(shape: tuple[int, int], substrate: str, dtype: str,
                     fft_plan: str = "pruned") -> tuple[int, int]:  # fmt: skip
        """Device bytes of a half-space on a CUDA device: (held, while made).

        Parameters
        ----------
        {shape}
        {substrate}
        dtype : {"float64", "float32"}
            Precision.
        fft_plan : {"pruned", "full"}, optional
            The cuFFT plans (``warptrunc.contact.halfspace.FFT_PLANS``).

        Returns
        -------
        (int, int)
            The sum of :meth:`memory_terms`, twice: the construction fills the held arrays in
            place (its slab temporaries, a few MiB, are not counted).
        """
        terms = ElasticHalfSpace.memory_terms(shape, substrate, dtype, fft_plan=fft_plan)
        held = sum(terms.values())
        return int(held), int(held)

    # --- transforms ------------------------------------------------------------------------

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
        rows = ElasticHalfSpace.fft_slabs(ny, nk * item)
        cols = ElasticHalfSpace.fft_slabs(nk, big_y * item)

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
                plans["full"] = cufft.PlanNd((big_y, big_x), (big_y, 2 * nk), 1, 1,
                                             (big_y, nk), 1, 1, r2c, 1, "C", 1, nk)  # fmt: skip
                plans["full_inv"] = cufft.PlanNd((big_y, big_x), (big_y, nk), 1, 1,
                                                 (big_y, 2 * nk), 1, 1, c2r, 1, "C", 1,
                                                 big_x)  # fmt: skip
                return plans
            for _, c in rows:
                plans["rows", c] = cufft.PlanNd((big_x,), (in_row,), 1, in_row, (nk,), 1, nk,
                                                r2c, c, "C", 1, nk)  # fmt: skip
                plans["rows_inv", c] = cufft.PlanNd((big_x,), (nk,), 1, nk, (2 * nk,), 1,
                                                    2 * nk, c2r, c, "C", 1, big_x)  # fmt: skip
            for _, c in cols:
                plans["cols", c] = cufft.PlanNd((big_y,), (big_y,), nk, 1, (big_y,), nk, 1, c2c,
                                                c, "C", 0, None)  # fmt: skip
            return plans

        return make, rows, cols

    @staticmethod
    @fill_doc(GRID_DOCS)
    def cufft_work_bytes(shape: tuple[int, int], substrate: str, dtype: str, fft_plan: str,
                         device: wp.DeviceLike) -> int | None:  # fmt: skip
        """The work area cuFFT asks for the half-space's plans, learnt by making them (no
        transform runs and nothing of that size is allocated).

        Parameters
        ----------
        {shape}
        {substrate}
        dtype : {"float64", "float32"}
            Precision.
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
        make, _, _ = ElasticHalfSpace._plan_layout(shape, substrate, dtype, fft_plan)
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
            except Exception as exc:  # noqa: BLE001 - cuFFT's errors, named in the message
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
        make, rows, cols = self._plan_layout(self.shape, self.substrate, self.dtype,
                                             self.fft_plan)  # fmt: skip
        sizes = []

        def record(size):
            sizes.append(int(size))
            mem = cupy.cuda.UnownedMemory(self.work.ptr, int(size), self.work,
                                          self.device.ordinal)  # fmt: skip
            return cupy.cuda.MemoryPointer(mem, 0)

        with cupy.cuda.Device(self.device.ordinal):
            with cupy.cuda.using_allocator(record):
                del_plans = make(cufft)  # never executed: only their work sizes are kept
            del del_plans
            # rows of 2²⁰ 8-byte words: one dimension past 2³¹ − 1 elements (the full plan's
            # work area at 32768²: 2³¹ + 2¹⁶ words) is beyond Warp's int32 shapes
            words = -(-max(1, max(sizes, default=1)) // 8)
            width = min(words, 1 << 20)
            self.fft_work = wp.empty((-(-words // width), width), dtype=wp.float64,
                                     device=self.device)  # fmt: skip
            shared = cupy.cuda.UnownedMemory(self.fft_work.ptr, self.fft_work.capacity,
                                             self.fft_work, self.device.ordinal)  # fmt: skip
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
            data = cupy.ndarray((arr.capacity - offset,), dtype=cupy.uint8,
                                memptr=cupy.cuda.MemoryPointer(mem, offset))  # fmt: skip
            view = self._views[key] = (arr, data)
        return view[1]

    def _real_rows(self, spec: wp.array) -> wp.array:
        """The first ny real rows of a spectrum's memory in the in-place layout, 2·(Nx//2 + 1)
        reals each (a view, no copy)."""
        nk2 = 2 * self.spectrum_shape[1]
        view = wp.array(ptr=spec.ptr, dtype=self.scalar, shape=(self.shape[0], nk2),
                        device=self.device)  # fmt: skip
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
            wp.launch(_kr.pad_rows_kernel, dim=rows_view.shape, inputs=[buf],
                      outputs=[rows_view], device=self.device)  # fmt: skip
        cupy = self._cp[0]
        plans, rows, cols = self._cupy_plans()
        nk = self.spectrum_shape[1]
        item = np.dtype(self.np_dtype).itemsize
        fwd = self._directions[0]
        with (
            cupy.cuda.Device(self.device.ordinal),
            cupy_stream(cupy, wp.get_stream(self.device), self.device.ordinal),
        ):
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
        cupy = self._cp[0]
        plans, rows, cols = self._cupy_plans()
        nk = self.spectrum_shape[1]
        item = np.dtype(self.np_dtype).itemsize
        inv = self._directions[1]
        with (
            cupy.cuda.Device(self.device.ordinal),
            cupy_stream(cupy, wp.get_stream(self.device), self.device.ordinal),
        ):
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
