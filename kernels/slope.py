# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Sums of the finite-difference slope and curvature of a height map, row by row.

Launched by ``warptrunc.slope``. One thread per row iy of the (ny, nx) float32 map z (m),
accumulating in float64 in a fixed order along the row, so the sums do not depend on the device's
scheduling: ``sums[iy] = (Σ (h − r), Σ (h − r)², Σ (Δx h/dx)², Σ (Δy h/dy)², Σ (∇²h)²)``, r the
map's first height (a reference that keeps the squares' cancellation small), with forward
differences over the row's nx − 1 pairs and the pairs to the next row (none on the last), and the
five-point Laplacian on the interior pixels (rows and columns 1..n − 2) only. The host adds the rows
in order.
"""

import warp as wp

wp.set_module_options({"enable_backward": False})


@wp.kernel
def slope_sums_kernel(
    z: wp.array2d[wp.float32],
    dx: wp.float64,
    dy: wp.float64,
    sums: wp.array2d[wp.float64],
):
    """One thread per row; ``sums[iy, 0..4]`` as the module docstring says (m, m², 1, 1, 1/m²)."""
    iy = wp.tid()
    ny = z.shape[0]
    nx = z.shape[1]
    ref = wp.float64(z[0, 0])
    h1 = wp.float64(0.0)
    h2 = wp.float64(0.0)
    gx = wp.float64(0.0)
    gy = wp.float64(0.0)
    lap = wp.float64(0.0)
    for ix in range(nx):
        c = wp.float64(z[iy, ix])
        h1 += c - ref
        h2 += (c - ref) * (c - ref)
        if ix + 1 < nx:
            d = (wp.float64(z[iy, ix + 1]) - c) / dx
            gx += d * d
        if iy + 1 < ny:
            d = (wp.float64(z[iy + 1, ix]) - c) / dy
            gy += d * d
        if iy > 0 and iy + 1 < ny and ix > 0 and ix + 1 < nx:
            lx = (wp.float64(z[iy, ix + 1]) - wp.float64(2.0) * c + wp.float64(z[iy, ix - 1])) / (
                dx * dx
            )
            ly = (wp.float64(z[iy + 1, ix]) - wp.float64(2.0) * c + wp.float64(z[iy - 1, ix])) / (
                dy * dy
            )
            lap += (lx + ly) * (lx + ly)
    sums[iy, 0] = h1
    sums[iy, 1] = h2
    sums[iy, 2] = gx
    sums[iy, 3] = gy
    sums[iy, 4] = lap
