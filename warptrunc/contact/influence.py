# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Host side of the elastic half-space (:mod:`warptrunc.contact.halfspace`): the influence
coefficients of a pixel grid (Love's closed form, their spectrum and real-space table) and the
deterministic float64 lane reductions that the half-space and the solver share.

The spectral kernels these serve are in ``warptrunc.kernels.contact.spectral``.
"""

from __future__ import annotations

import functools
import math
import os
from typing import Any

import numpy as np
import scipy.fft
import warp as wp

from .._support.docs import fill_doc
from ..kernels.contact import spectral as _kr

__all__ = [
    "SUBSTRATES",
    "LaneReduction",
    "build_free_spectrum",
    "build_periodic_spectrum",
    "influence_spectrum",
    "influence_table",
]

SUBSTRATES = ("free", "periodic")

GRID_DOCS = {
    "{grid}": (
        "Parameters\n----------\nshape : (int, int)\n    Map size (ny, nx).\n"
        "pixel_size : (float, float)\n    Pixel sides (dx, dy) (m).\n"
        "contact_modulus : float\n    Contact modulus E* (Pa)."
    ),
    "{shape}": "shape : (int, int)\n    Map size (ny, nx).",
    "{substrate}": 'substrate : {"free", "periodic"}\n    Half-space.',
    "{dtype}": 'dtype : {"float64", "float32"}\n    Precision.',
    "{xp}": "xp : module, optional\n    Array module: NumPy (``None``, the default) or CuPy.",
    "{slab_elements}": "slab_elements : int, optional\n    Float64 elements per slab (dimensionless count).",
}
"""The parameters every half-space builder shares, written once (:func:`fill_doc`)."""


def _love(x, y, a: float, b: float, contact_modulus: float, xp=np):
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
    return v / (math.pi * contact_modulus)


SLAB_ELEMENTS = 1 << 18
"""Elements (float64) of one slab of the spectrum's construction (:func:`build_free_spectrum`):
rows of Love's coefficients or columns of their row transforms are processed this many at a
time, so that the construction's temporaries stay a few MiB whatever the map."""


def slab_rows(n_rows: int, row_length: int, slab_elements: int = SLAB_ELEMENTS) -> int:
    """Rows per slab: as many rows of ``row_length`` elements as fit ``slab_elements`` (≥ 1).

    Parameters
    ----------
    n_rows : int
        Rows to process (dimensionless count).
    row_length : int
        Elements per row (dimensionless count).
    slab_elements : int, optional
        Elements per slab (dimensionless count).

    Returns
    -------
    int
        Rows per slab, between 1 and ``n_rows``.
    """
    return int(max(1, min(n_rows, slab_elements // max(1, row_length))))


@fill_doc(GRID_DOCS)
def build_free_spectrum(
    shape: tuple[int, int],
    pixel_size: tuple[float, float],
    contact_modulus: float,
    spectrum: Any,
    table: Any,
    scratch: Any,
    *,
    xp: Any = None,
    rfft: Any = None,
    slab_elements: int = SLAB_ELEMENTS,
) -> None:
    """Fill the free half-space's half spectrum and influence table in place, in slabs.

    The (2ny, 2nx) mirrored grid of Love's coefficients is never formed. W = FFT(G)/(dx·dy)
    with G even in x and y is separable: the x transform of the mirrored rows of the quadrant
    (rows 0 … ny, which are all that the mirror needs), then the y transform of the mirrored
    columns of that. Rows of the quadrant are evaluated (float64) and transformed a slab at a
    time into ``scratch`` (float64), then its columns a slab at a time into ``spectrum`` (in its
    own dtype). Both transforms are real (the mirrored sequences are even), and the arithmetic is
    float64 whatever the dtype of the outputs, so the spectrum equals :func:`influence_spectrum`
    rounded to that dtype. Temporaries: a few slabs of ``slab_elements`` float64.

    {grid}
    spectrum : (ny + 1, nx + 1) array
        Output: rows 0 … ny of W (m/N), float32 or float64 (NumPy, or CuPy with ``xp=cupy``;
        may be a view of a Warp array).
    table : (ny, nx) array
        Output: the influence table G (m/N) at separations (iy, ix) pixels (:func:`influence_table`).
    scratch : (ny + 1, nx + 1) array of float64
        Work memory (e.g. the half-space's work spectrum, viewed as float64), overwritten.
    {xp}
    rfft : callable, optional
        ``rfft(x, axis)`` of ``xp`` (default ``scipy.fft.rfft`` with all cores).
    {slab_elements}
    """
    xp = np if xp is None else xp  # (a module default would print its path in the docs)
    ny, nx = shape
    dx, dy = pixel_size
    area = dx * dy
    if rfft is None:
        workers = os.cpu_count()

        def rfft(x, axis):
            return scipy.fft.rfft(x, axis=axis, workers=workers)

    xs = xp.arange(nx + 1, dtype=xp.float64) * dx
    step = slab_rows(ny + 1, 2 * nx, slab_elements)
    for j0 in range(0, ny + 1, step):
        j1 = min(ny + 1, j0 + step)
        ys = xp.arange(j0, j1, dtype=xp.float64)[:, None] * dy
        quad = _love(xs[None, :], ys, dx / 2, dy / 2, contact_modulus, xp=xp)  # (rows, nx + 1)
        if j0 < ny:
            k = min(j1, ny) - j0
            table[j0 : j0 + k] = (quad[:k, :nx] / area).astype(table.dtype)
        row = xp.concatenate([quad, quad[:, nx - 1 : 0 : -1]], axis=1)  # x mirrored: 2nx
        del quad
        scratch[j0:j1] = rfft(row, 1).real
        del row
    step = slab_rows(nx + 1, 2 * ny, slab_elements)
    for i0 in range(0, nx + 1, step):
        i1 = min(nx + 1, i0 + step)
        col = scratch[:, i0:i1]
        col = xp.concatenate([col, col[ny - 1 : 0 : -1]], axis=0)  # y mirrored: 2ny
        spectrum[:, i0:i1] = (rfft(col, 0).real / area).astype(spectrum.dtype)
        del col


@fill_doc(GRID_DOCS)
def build_periodic_spectrum(
    shape: tuple[int, int],
    pixel_size: tuple[float, float],
    contact_modulus: float,
    spectrum: Any,
    *,
    xp: Any = None,
    slab_elements: int = SLAB_ELEMENTS,
) -> None:
    """Fill rows 0 … ny//2 of the periodic half-space's spectrum in place, in slabs of rows.

    W = 1/(q·E*/2·dx·dy) (m/N) with the mean displacement's convention of
    :func:`influence_spectrum`, evaluated in float64 and stored in the dtype of ``spectrum``.

    {grid}
    spectrum : (ny//2 + 1, nx//2 + 1) array
        Output, float32 or float64 (NumPy, or CuPy with ``xp=cupy``).
    {xp}
    {slab_elements}
    """
    xp = np if xp is None else xp  # (a module default would print its path in the docs)
    ny, nx = shape
    dx, dy = pixel_size
    area = dx * dy
    rows, nk = ny // 2 + 1, nx // 2 + 1
    fx = xp.arange(nk, dtype=xp.float64)[None, :] / (nx * dx)  # cycles per metre; q = 2πf
    step = slab_rows(rows, nk, slab_elements)
    for j0 in range(0, rows, step):
        j1 = min(rows, j0 + step)
        fy = xp.arange(j0, j1, dtype=xp.float64)[:, None] / (ny * dy)
        stiff = math.pi * contact_modulus * xp.hypot(fx, fy)  # = q·E*/2 (Pa/m)
        if j0 == 0:
            stiff[0, 0] = math.pi * contact_modulus * (1 / (nx * dx) + 1 / (ny * dy)) / 2
        spectrum[j0:j1] = (1.0 / (stiff * area)).astype(spectrum.dtype)


@functools.lru_cache(maxsize=8)
@fill_doc(GRID_DOCS)
def influence_spectrum(
    shape: tuple[int, int], pixel_size: tuple[float, float], contact_modulus: float, substrate: str
) -> np.ndarray:
    """Half spectrum W (m/N) of the half-space's pixel-force → displacement convolution.

    {grid}
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
        quad = _love(
            np.arange(nx + 1)[None, :] * dx,
            np.arange(ny + 1)[:, None] * dy,
            dx / 2,
            dy / 2,
            contact_modulus,
        )
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


@fill_doc(GRID_DOCS)
def influence_table(
    shape: tuple[int, int], pixel_size: tuple[float, float], contact_modulus: float, substrate: str
) -> np.ndarray:
    """Real-space influence coefficients G (m/N): displacement at a pixel per unit force on
    another, by separation, for the direct summation of a few forces.

    {grid}
    {substrate}

    Returns
    -------
    (ny, nx) ndarray of float64
        ``"free"``: G at separations (abs(Δy), abs(Δx)) pixels (Love's form divided by the pixel
        area; the values the spectrum transforms). ``"periodic"``: G at separations
        (Δy mod ny, Δx mod nx), the inverse transform of the spectrum.
    """
    ny, nx = shape
    dx, dy = pixel_size
    if substrate == "free":
        quad = _love(
            np.arange(nx)[None, :] * dx,
            np.arange(ny)[:, None] * dy,
            dx / 2,
            dy / 2,
            contact_modulus,
        )
        return quad / (dx * dy)
    w = influence_spectrum(shape, pixel_size, contact_modulus, substrate)
    return scipy.fft.irfft2(w, s=shape)


class LaneReduction:
    """Deterministic float64 partial sums/maxima of the lane kernels of ``kernels/contact/cg.py``.

    Parameters
    ----------
    device : warp Device
        Where the kernels run.
    n_max : int
        Largest number of elements a lane kernel walks (sets the CPU chunk).
    """

    COLUMNS = 9

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
        """Stride and chunk arguments of a lane kernel that walks ``n`` elements.

        Parameters
        ----------
        n : int
            Number of elements the kernel walks (dimensionless count).

        Returns
        -------
        stride : int
            Step between the elements one lane visits: the number of lanes, ``lanes``.
        chunk : int
            On the CPU, the length of the contiguous run of elements each lane walks instead
            (ceil(n / lanes), at least 1); 0 on a CUDA device, where the lanes stride.
        """
        if self.device.is_cuda:
            return self.lanes, 0
        return self.lanes, max(1, -(-n // self.lanes))

    def launch(self, kernel, n: int, inputs: list, outputs: list) -> None:
        """Launch a lane kernel on ``lanes`` threads, its partials going to ``part``.

        Parameters
        ----------
        kernel : warp Kernel
            Lane kernel whose last two inputs are (stride, chunk) and whose last output is the
            (lanes, COLUMNS) float64 partials array.
        n : int
            Number of elements the kernel walks (dimensionless count; sets the chunk, see
            :meth:`geometry`).
        inputs : list
            The kernel's inputs before (stride, chunk), which are appended.
        outputs : list
            The kernel's outputs before the partials ``part``, which is appended.
        """
        stride, chunk = self.geometry(n)
        wp.launch(
            kernel,
            dim=self.lanes,
            inputs=[*inputs, stride, chunk],
            outputs=[*outputs, self.part],
            device=self.device,
        )

    def fold(self, is_max: tuple[bool, ...]) -> wp.array:
        """Fold the lane partials of the first ``len(is_max)`` columns into a few rows.

        On a CUDA device ``sum_lanes_kernel`` folds the (lanes, COLUMNS) partials into
        (rows, COLUMNS), on the device; on the CPU the lanes are few and are the rows (the
        partials are returned as they are). Nothing is read back.

        Parameters
        ----------
        is_max : tuple of bool
            One flag per column from column 0: True takes the maximum of the column's partials
            (non-negative quantities; the fold starts from 0), False their sum.

        Returns
        -------
        (rows, COLUMNS) warp array of float64
            Rows to sum (or take the maximum of) per column.
        """
        if not self.device.is_cuda:
            return self.part
        ncol = len(is_max)
        flags = self._flags.get(is_max)
        if flags is None:
            f = [int(v) for v in is_max] + [0] * (self.COLUMNS - ncol)
            flags = self._flags[is_max] = wp.array(f, dtype=wp.int32, device=self.device)
        wp.launch(
            _kr.sum_lanes_kernel,
            dim=(self.rows, ncol),
            inputs=[self.part, flags],
            outputs=[self.out],
            device=self.device,
        )
        return self.out

    def read(self, is_max: tuple[bool, ...]) -> np.ndarray:
        """Reduce the lane partials of the first ``len(is_max)`` columns to one value each.

        Folds on the device (:meth:`fold`), then reads the rows back to the host (a
        synchronisation point) and finishes there in float64.

        Parameters
        ----------
        is_max : tuple of bool
            One flag per column from column 0: True takes the maximum of the column's partials,
            False their sum.

        Returns
        -------
        (len(is_max),) ndarray of float64
            Per column, the sum or the maximum of the partials, in the units of what the lane
            kernel accumulated in that column.
        """
        ncol = len(is_max)
        p = self.fold(is_max).numpy()[:, :ncol]  # sync point
        return np.array([p[:, j].max() if is_max[j] else p[:, j].sum() for j in range(ncol)])
