# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Spectral products and float64 lane reductions of the constrained conjugate gradients of
``kernels/contact/cg.py`` (array layouts, ``mask`` bits and the lane grids are described there).

Launched by ``warptrunc.contact.halfspace`` (``spectral_kernel``; ``expand_spectrum_kernel`` and
``pad_rows_kernel``, which fill a spectrum from the kernel's half rows and the real rows of an
in-place transform from a map), ``warptrunc.contact.influence``
(``sum_lanes_kernel``, through ``LaneReduction``) and ``warptrunc.contact.solver``
(``contact_sums_kernel``; the ``SPECTRUM_*`` modes). State arrays are float32 or float64 (one
overload each); spectra are (Ny, Nx//2 + 1) arrays of vec2 (re, im), the kernel spectrum ``w`` is
real and even in y and stored for rows 0 … Ny//2 only.
"""

from typing import Any

import warp as wp

from ..lanes import declare_overloads, lane_more, lane_next, lane_next_rc, lane_start, lane_start_rc

wp.set_module_options({"enable_backward": False})


SPECTRUM_ENERGY = wp.constant(0)
SPECTRUM_APPLY = wp.constant(1)
SPECTRUM_INVERSE = wp.constant(2)


@wp.kernel
def spectral_kernel(
    b: wp.array2d(dtype=Any),
    w: wp.array2d(dtype=Any),
    mode: int,
    inv_n: wp.float64,
    nx_full: int,
    col: int,
    stride: int,
    chunk: int,
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the half spectrum (Ny, Nx//2 + 1) of a real-to-complex FFT, by ``mode``:

    * ``SPECTRUM_ENERGY``: nothing written; part[i, col] = Σ m·w·|b|², m = 2 for the columns that
      stand for two conjugate modes, else 1, i.e. N·Σ t·(K t) by Parseval (N = Ny·Nx);
    * ``SPECTRUM_APPLY``: the same sum, then b ← w·b/N (K, with the inverse FFT's 1/N);
    * ``SPECTRUM_INVERSE``: b ← b/(w·N) (K⁻¹).

    ``w`` holds rows 0 … Ny//2."""
    lane = wp.tid()
    nk = b.shape[1]
    ny_full = b.shape[0]
    # (row, column) walk: Ny·(Nx//2 + 1) passes 2³¹ − 1 at 32768² (free boundary)
    iy, ix, sy, sx, ey, ex = lane_start_rc(lane, stride, chunk, ny_full, nk)
    acc = wp.float64(0.0)
    while lane_more(iy, ix, ey, ex):
        wv = w[wp.min(iy, ny_full - iy), ix]
        v = b[iy, ix]
        if mode <= SPECTRUM_APPLY:
            mult = wp.float64(2.0)
            if ix == 0 or 2 * ix == nx_full:
                mult = wp.float64(1.0)
            acc += (
                mult
                * wp.float64(wv)
                * (wp.float64(v[0]) * wp.float64(v[0]) + wp.float64(v[1]) * wp.float64(v[1]))
            )
            if mode == SPECTRUM_APPLY:
                b[iy, ix] = v * (wv * w.dtype(inv_n))
        else:
            b[iy, ix] = v * (w.dtype(inv_n) / wv)
        iy, ix = lane_next_rc(iy, ix, sy, sx, nk)
    if mode <= SPECTRUM_APPLY:
        part[lane, col] = acc


@wp.kernel
def contact_sums_kernel(
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    stride: int,
    chunk: int,
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: part[i] = [n(q > 0), Σ c·g, Σ c·g², Σ q] (start of a solve)."""
    lane = wp.tid()
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    n_c = wp.float64(0.0)
    s_g = wp.float64(0.0)
    s_gg = wp.float64(0.0)
    s_q = wp.float64(0.0)
    while i < n:
        if q[iy, ix] > q.dtype(0.0):
            g = wp.float64(u[iy, ix]) - wp.float64(h[iy, ix]) - offset
            n_c += wp.float64(1.0)
            s_g += g
            s_gg += g * g
            s_q += wp.float64(q[iy, ix])
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = n_c
    part[lane, 1] = s_g
    part[lane, 2] = s_gg
    part[lane, 3] = s_q


@wp.kernel
def sum_lanes_kernel(
    part: wp.array2d(dtype=wp.float64),
    is_max: wp.array[wp.int32],
    out: wp.array2d(dtype=wp.float64),
):
    """One thread per (output row, column): out[k, j] = Σ (or max) of part[k::rows, j], in order."""
    k, j = wp.tid()
    rows = out.shape[0]
    acc = wp.float64(0.0)
    i = k
    while i < part.shape[0]:
        v = part[i, j]
        if is_max[j] != 0:
            acc = wp.max(acc, v)
        else:
            acc += v
        i += rows
    out[k, j] = acc


@wp.kernel
def expand_spectrum_kernel(w: wp.array2d(dtype=Any), scale: wp.float64, b: wp.array2d(dtype=Any)):
    """One thread per element of the (Ny, Nx//2 + 1) half spectrum ``b``: b = (scale·w, 0), with
    ``w`` the kernel spectrum's rows 0 … Ny//2 mirrored to the full Ny rows."""
    iy, ix = wp.tid()
    wv = w[wp.min(iy, b.shape[0] - iy), ix] * w.dtype(scale)
    b[iy, ix] = b.dtype(wv, w.dtype(0.0))


@wp.kernel
def pad_rows_kernel(x: wp.array2d(dtype=Any), rows: wp.array2d(dtype=Any)):
    """One thread per element of ``rows`` (ny, 2·(Nx//2 + 1)), the real rows of an in-place
    real-to-complex transform: rows = x on the map's columns, 0 in the pad."""
    iy, ix = wp.tid()
    if ix < x.shape[1]:
        rows[iy, ix] = x[iy, ix]
    else:
        rows[iy, ix] = rows.dtype(0.0)


declare_overloads(
    (spectral_kernel, contact_sums_kernel, expand_spectrum_kernel, pad_rows_kernel),
    vec_args={(spectral_kernel, "b"), (expand_spectrum_kernel, "b")},
)
