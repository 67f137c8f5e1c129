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
host, cached by (grid, pixel size, E*, substrate) (:func:`influence_spectrum`). ``u = irfft2(W·rfft2(q))`` maps pixel forces q (N) to
displacements u (m): one real-to-complex transform, one multiply, one inverse.

FFT backends: on a CUDA device cuFFT through CuPy (the ``gpu`` extra, ``cupy-cuda12x``), which
the package already uses for the spectra of :mod:`warptrunc.descriptors`; CuPy reads and writes
the Warp arrays zero-copy through ``__cuda_array_interface__`` (Warp exports it without a
stream, so nothing synchronises), runs on Warp's own stream (``cupy.cuda.ExternalStream``), so
kernels and transforms stay ordered with no device-wide synchronisation, and keeps a cuFFT plan
cache, so a plan is made once per grid. On the CPU ``scipy.fft`` with
``workers=os.cpu_count()`` (skipping the zero pad in the forward transform, row transforms of
the map's rows then column transforms, was measured slower with scipy at 256² and 512²).
The multiply is a Warp kernel that also returns Σ t·(K t) by Parseval.
"""

from __future__ import annotations

import functools
import math
import os

import numpy as np
import scipy.fft
import warp as wp

from .._device import resolve_device
from ..kernels import contact as _k

__all__ = ["SUBSTRATES", "ElasticHalfSpace", "LaneReduction", "influence_spectrum"]

SUBSTRATES = ("free", "periodic")
DTYPES = {
    "float64": (wp.float64, wp.vec2d, np.float64),
    "float32": (wp.float32, wp.vec2f, np.float32),
}


def _love(x, y, a: float, b: float, e_star: float, xp=np):
    """Displacement (m) at (x, y) under a unit pressure on [−a, a]×[−b, b] (Love 1929).

    ``xp`` is the array module (NumPy on the host, CuPy on a CUDA device).
    """

    xa, xm, yb, ym = x + a, x - a, y + b, y - b
    with np.errstate(divide="ignore", invalid="ignore"):
        v = (
            xa * xp.log((yb + xp.hypot(yb, xa)) / (ym + xp.hypot(ym, xa)))
            + yb * xp.log((xa + xp.hypot(yb, xa)) / (xm + xp.hypot(yb, xm)))
            + xm * xp.log((ym + xp.hypot(ym, xm)) / (yb + xp.hypot(yb, xm)))
            + ym * xp.log((xm + xp.hypot(ym, xm)) / (xa + xp.hypot(ym, xa)))
        )
    return v / (math.pi * e_star)


def _free_spectrum_cupy(shape, pixel_size, contact_modulus, cupy, cfft):
    """The ``"free"`` spectrum of :func:`influence_spectrum`, computed on the current CUDA device.

    Same float64 formula and mirroring as the host path, evaluated with CuPy and transformed with
    cuFFT, so that a 10240² map needs no host memory or host FFT (≈ 3 GB of device memory
    briefly, freed on return except the (2ny, nx + 1) result).
    """
    ny, nx = shape
    dx, dy = pixel_size
    quad = _love(cupy.arange(nx + 1, dtype=cupy.float64)[None, :] * dx,
                 cupy.arange(ny + 1, dtype=cupy.float64)[:, None] * dy,
                 dx / 2, dy / 2, contact_modulus, xp=cupy)  # fmt: skip
    jx = cupy.arange(2 * nx)
    jy = cupy.arange(2 * ny)
    g = quad[cupy.minimum(jy, 2 * ny - jy)[:, None], cupy.minimum(jx, 2 * nx - jx)[None, :]]
    del quad
    w = cfft.rfft2(g).real / (dx * dy)
    del g
    return cupy.ascontiguousarray(w)


@functools.lru_cache(maxsize=8)
def influence_spectrum(
    shape: tuple[int, int], pixel_size: tuple[float, float], contact_modulus: float, substrate: str
) -> np.ndarray:
    """Half spectrum W (m/N) of the half-space's pixel-force → displacement convolution.

    Parameters
    ----------
    shape : (int, int)
        Map size (ny, nx).
    pixel_size : (float, float)
        Pixel sides (dx, dy) (m).
    contact_modulus : float
        Contact modulus E* (Pa).
    substrate : {"free", "periodic"}
        Zero-padded isolated patch, or a periodic map (module docstring).

    Returns
    -------
    (Ny, Nx//2 + 1) ndarray of float64
        W for ``u = irfft2(W·rfft2(q), (Ny, Nx))``; (Ny, Nx) = (2ny, 2nx) for ``"free"``,
        (ny, nx) for ``"periodic"``. Cached; do not modify it.
    """
    ny, nx = shape
    dx, dy = pixel_size
    area = dx * dy
    if substrate == "free":
        # separations i·dx for i ≤ nx and (i − 2nx)·dx above; Love's G is even in x and y, so it
        # is evaluated on one quadrant (|x| ≤ nx·dx, |y| ≤ ny·dy) and mirrored
        quad = _love(np.arange(nx + 1)[None, :] * dx, np.arange(ny + 1)[:, None] * dy,
                     dx / 2, dy / 2, contact_modulus)  # fmt: skip
        jx = np.arange(2 * nx)
        jy = np.arange(2 * ny)
        g = quad[np.minimum(jy, 2 * ny - jy)[:, None], np.minimum(jx, 2 * nx - jx)[None, :]]
        del quad
        w = scipy.fft.rfft2(g, workers=os.cpu_count()).real / area
    elif substrate == "periodic":
        fx = np.fft.rfftfreq(nx, dx)
        fy = np.fft.fftfreq(ny, dy)
        f = np.hypot(fx[None, :], fy[:, None])  # cycles per metre; q = 2πf
        stiff = math.pi * contact_modulus * f  # = q·E*/2 (Pa/m)
        stiff[0, 0] = math.pi * contact_modulus * (1 / (nx * dx) + 1 / (ny * dy)) / 2
        w = 1.0 / (stiff * area)
    else:
        raise ValueError(f"substrate must be one of {SUBSTRATES}, got {substrate!r}")
    w.setflags(write=False)
    return w


class LaneReduction:
    """Deterministic float64 partial sums/maxima of the lane kernels of ``kernels/contact.py``.

    Parameters
    ----------
    device : warp Device
        Where the kernels run.
    n_max : int
        Largest number of elements a lane kernel walks (sets the CPU chunk).
    """

    COLUMNS = 8

    def __init__(self, device: wp.context.Device, n_max: int) -> None:
        self.device = device
        if device.is_cuda:
            self.lanes = int(min(65536, max(1, n_max)))
            self.rows = 256
            self.out = wp.zeros((self.rows, self.COLUMNS), dtype=wp.float64, device=device)
        else:
            self.lanes = int(min(64, max(1, n_max)))
            self.rows = 0
            self.out = None
        self.part = wp.zeros((self.lanes, self.COLUMNS), dtype=wp.float64, device=device)
        self._flags: dict[tuple[bool, ...], wp.array] = {}

    def geometry(self, n: int) -> tuple[int, int]:
        """(stride, chunk) arguments of a lane kernel that walks ``n`` elements."""
        if self.device.is_cuda:
            return self.lanes, 0
        return self.lanes, max(1, -(-n // self.lanes))

    def launch(self, kernel, n: int, inputs: list, outputs: list) -> None:
        """Launch ``kernel`` on the lanes; ``inputs`` end before (stride, chunk)."""
        stride, chunk = self.geometry(n)
        wp.launch(
            kernel, dim=self.lanes, inputs=[*inputs, stride, chunk], outputs=[*outputs, self.part],
            device=self.device,
        )  # fmt: skip

    def read(self, is_max: tuple[bool, ...]) -> np.ndarray:
        """The reduced columns (host float64), summing or taking the maximum per column."""
        ncol = len(is_max)
        if self.device.is_cuda:
            flags = self._flags.get(is_max)
            if flags is None:
                f = [int(v) for v in is_max] + [0] * (self.COLUMNS - ncol)
                flags = self._flags[is_max] = wp.array(f, dtype=wp.int32, device=self.device)
            wp.launch(
                _k.sum_lanes_kernel, dim=(self.rows, ncol), inputs=[self.part, flags],
                outputs=[self.out], device=self.device,
            )  # fmt: skip
            p = self.out.numpy()[:, :ncol]  # sync point
        else:
            p = self.part.numpy()[:, :ncol]
        return np.array([p[:, j].max() if is_max[j] else p[:, j].sum() for j in range(ncol)])


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
        self.reduction = LaneReduction(self.device, self.grid[0] * self.grid[1])
        self._cp = None
        pixel = (float(pixel_size[0]), float(pixel_size[1]))
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
                w = _free_spectrum_cupy(self.shape, pixel, float(contact_modulus), cupy, cfft)
                w = w.astype(self.np_dtype, copy=False)
                wp.synchronize_device(self.device)  # CuPy's stream → Warp's stream
            self.spectrum = wp.array(ptr=w.data.ptr, dtype=self.scalar, shape=w.shape,
                                     capacity=w.nbytes, device=self.device, copy=False)  # fmt: skip
            self.spectrum._cupy_owner = w  # keeps CuPy's buffer alive
        else:
            w = influence_spectrum(self.shape, pixel, float(contact_modulus), substrate)
            self.spectrum = wp.array(w.astype(self.np_dtype), dtype=self.scalar,
                                     device=self.device)  # fmt: skip

    @staticmethod
    def bytes_per_grid(shape: tuple[int, int], substrate: str, dtype: str) -> int:
        """Bytes of one real (Ny, Nx) array of the FFT grid.

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

    def apply(self, x: wp.array, *, inverse: bool = False, energy_column: int = -1) -> wp.array:
        """K·x: displacements (m) of pixel forces ``x`` (N) on the (Ny, Nx) grid; with
        ``inverse=True`` K⁻¹·x: pixel forces (N) of displacements x (m).

        With ``energy_column ≥ 0`` (forward only) the lanes of ``self.reduction`` get the partial
        sums of N·Σ x·(K·x) in that column (Parseval; read them with ``reduction.read``, divide
        by N = Ny·Nx); nothing is read back here. The result is a new (Ny, Nx) array (CPU:
        NumPy-owned memory; CUDA: CuPy's pool, kept alive by the Warp view).
        """
        red = self.reduction
        nyk, nxk = self.spectrum.shape
        stride, chunk = red.geometry(nyk * nxk)
        col = energy_column if (energy_column >= 0 and not inverse) else LaneReduction.COLUMNS - 1
        args = [self.spectrum, int(inverse), self.grid[1], col, stride, chunk]
        if self._cp is None:
            xh = x.numpy()
            workers = os.cpu_count()
            spec = scipy.fft.rfft2(xh, workers=workers)
            spec_w = wp.array(spec.view(self.np_dtype).reshape(nyk, nxk, 2), dtype=self.vec2,
                              device=self.device, copy=False)  # fmt: skip
            wp.launch(_k.spectral_multiply_kernel, dim=red.lanes, inputs=[spec_w, *args],
                      outputs=[red.part], device=self.device)  # fmt: skip
            out = scipy.fft.irfft2(spec, s=self.grid, workers=workers)
            if out.dtype != self.np_dtype:
                out = out.astype(self.np_dtype)
            return wp.array(out, dtype=self.scalar, device=self.device, copy=False)
        cp, cfft = self._cp
        stream = wp.get_stream(self.device)
        with cp.cuda.Device(self.device.ordinal), cp.cuda.ExternalStream(stream.cuda_stream):
            spec = cfft.rfft2(cp.asarray(x))
            spec_w = wp.array(ptr=spec.data.ptr, dtype=self.vec2, shape=(nyk, nxk),
                              capacity=spec.nbytes, device=self.device, copy=False)  # fmt: skip
            wp.launch(_k.spectral_multiply_kernel, dim=red.lanes, inputs=[spec_w, *args],
                      outputs=[red.part], device=self.device)  # fmt: skip
            out = cfft.irfft2(spec, s=self.grid)
        res = wp.array(ptr=out.data.ptr, dtype=self.scalar, shape=self.grid, capacity=out.nbytes,
                       device=self.device, copy=False)  # fmt: skip
        res._cupy_owner = out  # keeps CuPy's buffer alive as long as the Warp view
        return res
