# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Per-box and per-pixel passes of the fractal-dimension estimators.

Launched by ``warptrunc.fractal`` (imported there as ``_k``). Heights ``z[iy, ix]`` are float32
metres; every sum is accumulated in float64 by one thread over a fixed range and written to its
own output slot (no atomics), so results do not depend on the thread order and agree between
the CPU and the GPU to float64 round-off. The host adds the partial sums.

Cells of side ``s`` pixels use the ``(s + 1) × (s + 1)`` grid points ``[j·s, (j+1)·s] ×
[i·s, (i+1)·s]`` (neighbouring cells share their edges), so a map of ``ny × nx`` points holds
``((ny − 1) // s) × ((nx − 1) // s)`` cells.

* :func:`prism_area_kernel` — triangular prism (Clarke 1986): grid ``(cells_y, chunks)``, one
  thread per chunk of ``chunk`` cells along a row of cells; writes the summed top area (m²).
* :func:`box_count_kernel` — cube counting: same grid; writes the number of cubes of height
  ``eps`` (m) that the surface crosses in each chunk (int64).
* :func:`structure_function_kernel` — vertical sections: grid ``(n_lags, nx)``, one thread per
  (lag, column); writes Σ (z(p + τ) − z(p))² (m²) over the pairs in that column, along x or y.
  Neighbouring threads read neighbouring columns, so GPU reads are coalesced.
* :func:`structure_function_rows_kernel` — the same sums with one thread per (lag, row),
  walking along the row: contiguous reads for the CPU, where a launch runs its threads one
  after the other.
"""

import warp as wp

wp.set_module_options({"enable_backward": False})


@wp.func
def triangle_area(a: wp.vec3d, b: wp.vec3d, c: wp.vec3d) -> wp.float64:
    """Area of the triangle abc (m²)."""
    return wp.float64(0.5) * wp.length(wp.cross(b - a, c - a))


@wp.kernel
def prism_area_kernel(
    z: wp.array2d[wp.float32],
    s: int,
    hx: wp.float64,
    hy: wp.float64,
    chunk: int,
    area: wp.array2d[wp.float64],
):
    """One thread per chunk of cells in a row of cells; ``hx = s·dx``, ``hy = s·dy`` (m)."""
    j, c = wp.tid()
    ncx = (z.shape[1] - 1) // s
    i0 = c * chunk
    i1 = wp.min(i0 + chunk, ncx)
    y0 = j * s
    y1 = y0 + s
    half = wp.float64(0.5)
    acc = wp.float64(0.0)
    for i in range(i0, i1):
        x0 = i * s
        x1 = x0 + s
        za = wp.float64(z[y0, x0])
        zb = wp.float64(z[y0, x1])
        zc = wp.float64(z[y1, x1])
        zd = wp.float64(z[y1, x0])
        # prism apex: the mean of the four corners (Clarke 1986)
        ze = wp.float64(0.25) * (za + zb + zc + zd)
        pa = wp.vec3d(wp.float64(0.0), wp.float64(0.0), za)
        pb = wp.vec3d(hx, wp.float64(0.0), zb)
        pc = wp.vec3d(hx, hy, zc)
        pd = wp.vec3d(wp.float64(0.0), hy, zd)
        pe = wp.vec3d(half * hx, half * hy, ze)
        acc += (
            triangle_area(pa, pb, pe)
            + triangle_area(pb, pc, pe)
            + triangle_area(pc, pd, pe)
            + triangle_area(pd, pa, pe)
        )
    area[j, c] = acc


@wp.kernel
def box_count_kernel(
    z: wp.array2d[wp.float32],
    s: int,
    eps: wp.float64,
    z0: wp.float64,
    chunk: int,
    count: wp.array2d[wp.int64],
):
    """One thread per chunk of cells in a row of cells; cubes of height ``eps`` (m) stacked
    from ``z0`` (m)."""
    j, c = wp.tid()
    ncx = (z.shape[1] - 1) // s
    i0 = c * chunk
    i1 = wp.min(i0 + chunk, ncx)
    y0 = j * s
    n = wp.int64(0)
    for i in range(i0, i1):
        x0 = i * s
        lo = wp.float64(z[y0, x0])
        hi = lo
        for yy in range(y0, y0 + s + 1):
            for xx in range(x0, x0 + s + 1):
                v = wp.float64(z[yy, xx])
                lo = wp.min(lo, v)
                hi = wp.max(hi, v)
        # cubes k·eps ≤ z − z0 < (k+1)·eps crossed between the lowest and highest point
        klo = wp.int64(wp.floor((lo - z0) / eps))
        khi = wp.int64(wp.floor((hi - z0) / eps))
        n += khi - klo + wp.int64(1)
    count[j, c] = n


@wp.func
def squared_differences(
    z: wp.array2d[wp.float32],
    iy: int,
    ix: int,
    sy: int,
    sx: int,
    n: int,
    dy: int,
    dx: int,
) -> wp.float64:
    """Σ over the n pixels p_j = (iy + j·sy, ix + j·sx) of (z(p_j + (dy, dx)) − z(p_j))² (m²),
    in the order of j."""
    acc = wp.float64(0.0)
    for j in range(n):
        y = iy + j * sy
        x = ix + j * sx
        d = wp.float64(z[y + dy, x + dx]) - wp.float64(z[y, x])
        acc += d * d
    return acc


@wp.kernel
def structure_function_kernel(
    z: wp.array2d[wp.float32],
    lags: wp.array[wp.int32],
    along_x: int,
    out: wp.array2d[wp.float64],
):
    """One thread per (lag, column): Σ over the column's pairs of (z(p + τ) − z(p))² (m²)."""
    k, ix = wp.tid()
    tau = int(lags[k])
    ny = z.shape[0]
    nx = z.shape[1]
    acc = wp.float64(0.0)
    if along_x != 0:
        if ix + tau < nx:
            acc = squared_differences(z, 0, ix, 1, 0, ny, 0, tau)
    else:
        acc = squared_differences(z, 0, ix, 1, 0, ny - tau, tau, 0)
    out[k, ix] = acc


@wp.kernel
def structure_function_rows_kernel(
    z: wp.array2d[wp.float32],
    lags: wp.array[wp.int32],
    along_x: int,
    out: wp.array2d[wp.float64],
):
    """One thread per (lag, row): Σ over the row's pairs of (z(p + τ) − z(p))² (m²)."""
    k, iy = wp.tid()
    tau = int(lags[k])
    ny = z.shape[0]
    nx = z.shape[1]
    acc = wp.float64(0.0)
    if along_x != 0:
        acc = squared_differences(z, iy, 0, 0, 1, nx - tau, 0, tau)
    elif iy + tau < ny:
        acc = squared_differences(z, iy, 0, 0, 1, nx, tau, 0)
    out[k, iy] = acc


@wp.kernel
def cube_scale_kernel(
    z: wp.array2d(dtype=wp.float32),
    z0: wp.float64,
    factor: wp.float64,
    out: wp.array2d(dtype=wp.float32),
):
    """Heights mapped into the cube of the ``"cube"`` convention: (z − z0)·factor, in float64
    (driver: ``warptrunc.fractal._scaled_upload``)."""
    iy, ix = wp.tid()
    out[iy, ix] = wp.float32((wp.float64(z[iy, ix]) - z0) * factor)
