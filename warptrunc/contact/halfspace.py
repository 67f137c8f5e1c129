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

The transforms (pruned or one 2-D cuFFT plan each way, SciPy on the CPU) are
:mod:`warptrunc.contact.transforms`, which :class:`ElasticHalfSpace` inherits.
"""

from __future__ import annotations

import contextlib
from typing import Any

import numpy as np
import warp as wp

from .._support.device import resolve_device
from .._support.docs import fill_doc
from ..kernels.contact import spectral as _kr
from .influence import (
    GRID_DOCS,
    SUBSTRATES,
    LaneReduction,
    build_free_spectrum,
    build_periodic_spectrum,
)
from .transforms import FFT_PLANS, FFT_SLABS, PaddedTransforms, cupy_stream

_REEXPORTED = (FFT_PLANS, FFT_SLABS)  # kept importable from here

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


@fill_doc(GRID_DOCS)
class ElasticHalfSpace(PaddedTransforms):
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
        self.fft_plan = fft_plan if substrate == "free" and self.device.is_cuda else "pruned"
        self._views: dict[int, Any] = {}
        self.fft_work = None  # the cuFFT plans' one shared work area (CUDA)
        self.spectrum = wp.empty(
            (rows, self.spectrum_shape[1]), dtype=self.scalar, device=self.device
        )
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

            spectrum, table, raw = (
                self._cupy_array(a) for a in (self.spectrum, self.table, self.work)
            )
        ctx = self._cupy_context() if self._cp is not None else contextlib.nullcontext()
        with ctx:
            if self.substrate == "free":
                scratch = raw[: (ny + 1) * (nx + 1) * 8].view(xp.float64).reshape(ny + 1, nx + 1)
                build_free_spectrum(
                    self.shape, pixel, contact_modulus, spectrum, table, scratch, xp=xp, rfft=rfft
                )
                del scratch
            else:
                build_periodic_spectrum(self.shape, pixel, contact_modulus, spectrum, xp=xp)
            del spectrum, table, raw
            if self._cp is not None:
                self._cp[0].fft.config.get_plan_cache().clear()
        if self.substrate == "periodic":  # the table: the inverse transform of the spectrum
            wp.launch(
                _kr.expand_spectrum_kernel,
                dim=self.spectrum_shape,
                inputs=[self.spectrum, wp.float64(1.0 / self.n_total)],
                outputs=[self.work],
                device=self.device,
            )
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
        dt = {
            wp.float32: np.float32,
            wp.float64: np.float64,
            wp.vec2f: np.float32,
            wp.vec2d: np.float64,
        }[arr.dtype]
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
        view = wp.array(
            ptr=spec.ptr,
            dtype=self.scalar,
            shape=(ny, nx),
            strides=(row * item, item),
            device=self.device,
        )
        view._spectrum_owner = spec  # keeps the spectrum alive as long as the view
        return view

    @staticmethod
    @fill_doc(GRID_DOCS)
    def memory_terms(
        shape: tuple[int, int],
        substrate: str,
        dtype: str,
        *,
        cuda: bool = True,
        fft_plan: str = "pruned",
        device: wp.DeviceLike = None,
    ) -> dict[str, int]:
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
            (``cufft_work_bytes``) instead of the estimate.

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
        exact = (
            ElasticHalfSpace.cufft_work_bytes(shape, substrate, dtype, fft_plan, device)
            if cuda and device is not None
            else None
        )
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
    def memory_bytes(
        shape: tuple[int, int], substrate: str, dtype: str, fft_plan: str = "pruned"
    ) -> tuple[int, int]:
        """Device bytes of a half-space on a CUDA device: (held, while made).

        Parameters
        ----------
        {shape}
        {substrate}
        {dtype}
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

    def spectral(self, mode: int, spec: wp.array, *, col: int = LaneReduction.COLUMNS - 1) -> None:
        """Launch the spectral kernel on a half spectrum, over the lanes of ``reduction``.

        The kernel is ``spectral_kernel`` of ``warptrunc.kernels.contact.spectral``; it multiplies by
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
            _kr.spectral_kernel,
            dim=red.lanes,
            inputs=[
                spec,
                self.spectrum,
                int(mode),
                wp.float64(1.0 / self.n_total),
                self.grid[1],
                int(col),
                stride,
                chunk,
            ],
            outputs=[red.part],
            device=self.device,
        )

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
