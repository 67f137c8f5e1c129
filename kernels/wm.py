# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Weierstrass–Mandelbrot synthesis, Eq. (4) of the paper.

Launched by ``warptrunc.wm``. With r·cos(θ − πm/M) = x·cos(πm/M) + y·sin(πm/M), every term
separates: cos(a_t(x) + b_t(y)) = cos a·cos b − sin a·sin b, where a_t = kx_t·x + α_t and
b_t = ky_t·y. The sum over T = M·(n_max + 1) terms is then a matrix product

    S[iy, ix] = c0 + Σ_j P[iy, j]·Q[j, ix],   j < 2T,

with row tables P = [−w·cos b, w·sin b] (ny × 2T) and column tables Q = [cos a; sin a]
(2T × nx), w_t = γ^{(D−3)n}, c0 = Σ_t w_t·cos α_t. The product kernels compute P·Q; the
constant c0 and the height scale are applied afterwards by ``affine_kernel``. The tables are
built in float64 (phases up
to ~10⁵ rad stay accurate to ~1e-11 rad) and stored as float32; the product accumulates in
float32 over at most a few hundred terms. Heights are dimensionless here; the driver scales.

Kernels
-------
``column_table_kernel`` / ``row_table_kernel``: one thread per (term, pixel).
``wm_tile_gemm_kernel``: one tile block per TILE_M × TILE_N output tile (``wp.launch_tiled``).
``wm_rowblock_kernel``: CPU path, one thread per 8 rows × 16 columns (register blocking; no
tiles, whose CPU shared memory is a process-wide static buffer, so row bands can be launched
from several host threads at once).
``wm_direct_kernel``: one thread per pixel, float64 phases, loop over terms (reference path).
``affine_kernel``: one thread per pixel, z = (z + offset)·scale.

Batches (``warptrunc.sweep.batch``): B surfaces of one grid stacked along the rows, the grid's
sides multiples of the GEMM tiles (no padding). ``column_table_batch_kernel`` /
``row_table_batch_kernel`` write surface s's tables at rows s·K (Q) and s·ny (P) with its own
phases α and weights w, by the same float64 expressions as the single-surface kernels;
``wm_tile_gemm_batch_kernel`` multiplies each surface's P by its own Q tile by tile, as
``wm_tile_gemm_kernel`` does (the same sums in the same order); ``affine_batch_kernel`` applies
each surface's offset and scale.
"""

import warp as wp

wp.set_module_options({"enable_backward": False})

TILE_M = wp.constant(128)
TILE_N = wp.constant(128)
TILE_K = wp.constant(32)
ROWS = wp.constant(8)  # rows per thread in the CPU register-blocked product
COLS = 16  # columns per thread (one vec16)
vec16 = wp.types.vector(length=COLS, dtype=wp.float32)


@wp.kernel
def column_table_kernel(
    kx: wp.array[wp.float64],
    alpha: wp.array[wp.float64],
    dx: wp.float64,
    n_terms: int,
    nx: int,
    q: wp.array2d[wp.float32],
):
    """One thread per (term t, padded column ix): Q[t, ix] = cos(kx_t·x + α_t), Q[T+t, ix] =
    sin(...). Padding columns ix ≥ nx repeat column nx − 1 (finite values; their products are
    never stored)."""
    t, ix = wp.tid()
    a = kx[t] * (wp.float64(wp.min(ix, nx - 1)) * dx) + alpha[t]
    q[t, ix] = wp.float32(wp.cos(a))
    q[n_terms + t, ix] = wp.float32(wp.sin(a))


@wp.kernel
def row_table_kernel(
    ky: wp.array[wp.float64],
    w: wp.array[wp.float64],
    dy: wp.float64,
    n_terms: int,
    ny: int,
    p: wp.array2d[wp.float32],
):
    """One thread per (padded row iy, term t): P[iy, t] = −w_t·cos(ky_t·y), P[iy, T+t] =
    w_t·sin(...). Padding rows iy ≥ ny repeat row ny − 1."""
    iy, t = wp.tid()
    b = ky[t] * (wp.float64(wp.min(iy, ny - 1)) * dy)
    p[iy, t] = wp.float32(-w[t] * wp.cos(b))
    p[iy, n_terms + t] = wp.float32(w[t] * wp.sin(b))


@wp.kernel
def wm_tile_gemm_kernel(
    p: wp.array2d[wp.float32],
    q: wp.array2d[wp.float32],
    z: wp.array2d[wp.float32],
):
    """One tile block per TILE_M × TILE_N output tile: z = P·Q (stores outside z are masked).

    Writing each tile's min and max here as well (``wp.tile_min``/``tile_max``) cost 0.55 ms
    at 10240² on an H200, more than a separate tile reduction (0.29 ms)."""
    i, j = wp.tid()
    acc = wp.tile_zeros(shape=(TILE_M, TILE_N), dtype=wp.float32)
    for k in range(p.shape[1] // TILE_K):
        a = wp.tile_load(p, shape=(TILE_M, TILE_K), offset=(i * TILE_M, k * TILE_K))
        b = wp.tile_load(q, shape=(TILE_K, TILE_N), offset=(k * TILE_K, j * TILE_N))
        wp.tile_matmul(a, b, acc)
    wp.tile_store(z, acc, offset=(i * TILE_M, j * TILE_N))


@wp.func
def store_row(z: wp.array2d[vec16], iy: int, jb: int, acc: vec16):
    """z[iy, jb] = acc for rows inside z (z is the output viewed as 16-wide vectors)."""
    if iy < z.shape[0]:
        z[iy, jb] = acc


@wp.kernel
def wm_rowblock_kernel(
    p: wp.array2d[wp.float32],
    q: wp.array2d[vec16],
    row0: int,
    z: wp.array2d[vec16],
):
    """One thread per 8 × 16 block: z = P·Q (P rows padded to 8, Q and z columns to 16).

    z is a vec16 view of the output: with a float32 output array the compiler cannot prove that
    the stores do not alias P, and the kernel ran three times slower."""
    i, jb = wp.tid()
    iy = row0 + i * ROWS
    a0 = vec16()
    a1 = vec16()
    a2 = vec16()
    a3 = vec16()
    a4 = vec16()
    a5 = vec16()
    a6 = vec16()
    a7 = vec16()
    for k in range(p.shape[1]):
        v = q[k, jb]
        a0 += p[iy, k] * v
        a1 += p[iy + 1, k] * v
        a2 += p[iy + 2, k] * v
        a3 += p[iy + 3, k] * v
        a4 += p[iy + 4, k] * v
        a5 += p[iy + 5, k] * v
        a6 += p[iy + 6, k] * v
        a7 += p[iy + 7, k] * v
    store_row(z, iy, jb, a0)
    store_row(z, iy + 1, jb, a1)
    store_row(z, iy + 2, jb, a2)
    store_row(z, iy + 3, jb, a3)
    store_row(z, iy + 4, jb, a4)
    store_row(z, iy + 5, jb, a5)
    store_row(z, iy + 6, jb, a6)
    store_row(z, iy + 7, jb, a7)


@wp.kernel
def crop_kernel(src: wp.array2d[wp.float32], dst: wp.array2d[wp.float32]):
    """One thread per output pixel: dst = src[:ny, :nx] (drops the padded columns)."""
    iy, ix = wp.tid()
    dst[iy, ix] = src[iy, ix]


@wp.kernel
def wm_direct_kernel(
    kx: wp.array[wp.float64],
    ky: wp.array[wp.float64],
    alpha: wp.array[wp.float64],
    w: wp.array[wp.float64],
    dx: wp.float64,
    dy: wp.float64,
    z: wp.array2d[wp.float32],
):
    """One thread per pixel: z = −Σ_t w_t·cos(kx_t·x + ky_t·y + α_t), phases in float64."""
    iy, ix = wp.tid()
    x = wp.float64(ix) * dx
    y = wp.float64(iy) * dy
    s = wp.float64(0.0)
    for t in range(kx.shape[0]):
        s -= w[t] * wp.cos(kx[t] * x + ky[t] * y + alpha[t])  # Eq. (4) without cos α
    z[iy, ix] = wp.float32(s)


@wp.kernel
def affine_kernel(z: wp.array2d[wp.float32], offset: wp.float64, scale: wp.float64):
    """One thread per pixel: z = (z + offset)·scale, evaluated in float64."""
    iy, ix = wp.tid()
    z[iy, ix] = wp.float32((wp.float64(z[iy, ix]) + offset) * scale)


@wp.kernel
def column_table_batch_kernel(
    kx: wp.array[wp.float64],
    alpha: wp.array2d[wp.float64],
    dx: wp.float64,
    k_rows: int,
    q: wp.array2d[wp.float32],
):
    """One thread per (surface s, term t, column ix): Q[s·K + t, ix] = cos(kx_t·x + α_st),
    Q[s·K + T + t, ix] = sin(...), T = alpha.shape[1], K = ``k_rows`` (rows ≥ 2T stay 0)."""
    s, t, ix = wp.tid()
    n_terms = alpha.shape[1]
    a = kx[t] * (wp.float64(ix) * dx) + alpha[s, t]
    q[s * k_rows + t, ix] = wp.float32(wp.cos(a))
    q[s * k_rows + n_terms + t, ix] = wp.float32(wp.sin(a))


@wp.kernel
def row_table_batch_kernel(
    ky: wp.array[wp.float64],
    w: wp.array2d[wp.float64],
    dy: wp.float64,
    ny: int,
    p: wp.array2d[wp.float32],
):
    """One thread per (surface s, row iy, term t): P[s·ny + iy, t] = −w_st·cos(ky_t·y),
    P[s·ny + iy, T + t] = w_st·sin(...)."""
    s, iy, t = wp.tid()
    n_terms = w.shape[1]
    b = ky[t] * (wp.float64(iy) * dy)
    p[s * ny + iy, t] = wp.float32(-w[s, t] * wp.cos(b))
    p[s * ny + iy, n_terms + t] = wp.float32(w[s, t] * wp.sin(b))


@wp.kernel
def wm_tile_gemm_batch_kernel(
    p: wp.array2d[wp.float32],
    q: wp.array2d[wp.float32],
    tiles_per_surface: int,
    z: wp.array2d[wp.float32],
):
    """One tile block per output tile of the stacked maps: row tile i belongs to surface
    s = i // ``tiles_per_surface``, whose Q starts at row s·K (K = p.shape[1])."""
    i, j = wp.tid()
    k_rows = p.shape[1]
    q0 = (i // tiles_per_surface) * k_rows
    acc = wp.tile_zeros(shape=(TILE_M, TILE_N), dtype=wp.float32)
    for k in range(k_rows // TILE_K):
        a = wp.tile_load(p, shape=(TILE_M, TILE_K), offset=(i * TILE_M, k * TILE_K))
        b = wp.tile_load(q, shape=(TILE_K, TILE_N), offset=(q0 + k * TILE_K, j * TILE_N))
        wp.tile_matmul(a, b, acc)
    wp.tile_store(z, acc, offset=(i * TILE_M, j * TILE_N))


@wp.kernel
def affine_batch_kernel(
    z: wp.array2d[wp.float32],
    ny: int,
    offset: wp.array[wp.float64],
    scale: wp.array[wp.float64],
):
    """One thread per pixel of the stacked maps: z = (z + offset_s)·scale_s, s = iy // ny."""
    iy, ix = wp.tid()
    s = iy // ny
    z[iy, ix] = wp.float32((wp.float64(z[iy, ix]) + offset[s]) * scale[s])
