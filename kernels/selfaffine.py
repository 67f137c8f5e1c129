# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Self-affine surfaces by Fourier synthesis: the half spectrum of a real, periodic map.

Launched by ``warptrunc.selfaffine``. A mode of integer wavenumbers (mx, my) has the wavevector
q = 2π(mx/Lx, my/Ly) (rad/m) and the amplitude s·f(|q|), f the shape of the power spectrum
(:func:`shape`: flat below the roll-off, a power law |q|^(−1−H) above it, zero outside the
cut-offs and at the grid's Nyquist rows and columns), s the normalisation set on the host. Its
phase φ(mx, my) is drawn by Warp's counter-based generator from the surface's key and the mode's
wavenumbers alone, so the same key gives the same phases on every device and on every grid that
holds the mode; the conjugate mode (−mx, −my) takes −φ, so the map is real.

Kernels
-------
``mode_sums_kernel``: one thread per row of the half spectrum (ny, nx//2 + 1); Σ f², Σ |q|²f² and
Σ |q|⁴f² over the row's modes and their conjugates, in a fixed order (float64).
``fill_spectrum_kernel``: one thread per mode of the half spectrum; writes nx·ny·s·f·e^{iφ}
(float64 complex as ``vec2d``), the coefficients of an unnormalised inverse real FFT.
``to_float32_kernel``: one thread per pixel; float64 heights to the float32 map.
"""

import warp as wp

wp.set_module_options({"enable_backward": False})


@wp.func
def wavenumber(i: int, n: int) -> int:
    """Signed wavenumber of FFT index i on n points (0..n/2 − 1, then −n/2..−1)."""
    if i < (n + 1) // 2:
        return i
    return i - n


@wp.func
def shape(
    q: wp.float64, hurst: wp.float64, q_roll: wp.float64, q_long: wp.float64, q_short: wp.float64
) -> wp.float64:
    """√C(q)/√C(q_roll), the spectrum's shape (dimensionless): 1 for q_long ≤ q < q_roll,
    (q/q_roll)^(−1−H) for q_roll ≤ q ≤ q_short, 0 otherwise; a mode on a cut-off to 10⁻⁹
    (relative) is inside, whatever the rounding of its |q|."""
    tol = wp.float64(1.0e-9)
    if q < q_long * (wp.float64(1.0) - tol) or q > q_short * (wp.float64(1.0) + tol):
        return wp.float64(0.0)
    if q <= wp.float64(0.0):
        return wp.float64(0.0)
    if q < q_roll:
        return wp.float64(1.0)
    return wp.pow(q / q_roll, -(wp.float64(1.0) + hurst))


@wp.func
def nyquist(mx: int, my: int, nx: int, ny: int) -> bool:
    """The mode is on a Nyquist row or column of an even grid (its own conjugate: left empty)."""
    return (nx % 2 == 0 and (mx == nx // 2 or mx == -nx // 2)) or (
        ny % 2 == 0 and (my == ny // 2 or my == -ny // 2)
    )


@wp.func
def phase(key: int, mx: int, my: int) -> wp.float64:
    """Phase (rad) of the mode (mx, my) of a representative half plane (my > 0, or my = 0 and
    mx > 0): the row's seed from (key, my), then the column's draw from it."""
    row = wp.rand_init(key, my + 1073741824)
    u = wp.randf(wp.rand_init(int(wp.randi(row)), mx + 1073741824))
    return wp.float64(6.283185307179586) * wp.float64(u)


@wp.kernel
def mode_sums_kernel(
    nx: int,
    ny: int,
    lx: wp.float64,
    ly: wp.float64,
    hurst: wp.float64,
    q_roll: wp.float64,
    q_long: wp.float64,
    q_short: wp.float64,
    sums: wp.array2d[wp.float64],
):
    """One thread per row iy of the half spectrum: sums[iy] = (Σ f², Σ |q|² f², Σ |q|⁴ f²) over
    the row's columns, each column that stands for its conjugate too counted twice."""
    iy = wp.tid()
    my = wavenumber(iy, ny)
    qy = wp.float64(6.283185307179586) * wp.float64(my) / ly
    s0 = wp.float64(0.0)
    s2 = wp.float64(0.0)
    s4 = wp.float64(0.0)
    for ix in range(nx // 2 + 1):
        mx = ix
        if nyquist(mx, my, nx, ny):
            continue
        qx = wp.float64(6.283185307179586) * wp.float64(mx) / lx
        q2 = qx * qx + qy * qy
        f = shape(wp.sqrt(q2), hurst, q_roll, q_long, q_short)
        w = wp.float64(2.0)
        if ix == 0:
            w = wp.float64(1.0)  # column 0 holds both (0, my) and (0, −my)
        s0 += w * f * f
        s2 += w * q2 * f * f
        s4 += w * q2 * q2 * f * f
    sums[iy, 0] = s0
    sums[iy, 1] = s2
    sums[iy, 2] = s4


@wp.kernel
def fill_spectrum_kernel(
    nx: int,
    ny: int,
    lx: wp.float64,
    ly: wp.float64,
    hurst: wp.float64,
    q_roll: wp.float64,
    q_long: wp.float64,
    q_short: wp.float64,
    amplitude: wp.float64,
    key: int,
    spectrum: wp.array2d[wp.vec2d],
):
    """One thread per mode (iy, ix) of the (ny, nx//2 + 1) half spectrum: the coefficient
    amplitude·f(|q|)·e^{iφ} with φ(mx, my) on the representative half plane, −φ(−mx, −my) off it."""
    iy, ix = wp.tid()
    mx = ix
    my = wavenumber(iy, ny)
    if nyquist(mx, my, nx, ny):
        spectrum[iy, ix] = wp.vec2d(wp.float64(0.0), wp.float64(0.0))
        return
    qx = wp.float64(6.283185307179586) * wp.float64(mx) / lx
    qy = wp.float64(6.283185307179586) * wp.float64(my) / ly
    f = shape(wp.sqrt(qx * qx + qy * qy), hurst, q_roll, q_long, q_short)
    phi = wp.float64(0.0)
    if my > 0 or (my == 0 and mx > 0):
        phi = phase(key, mx, my)
    else:
        phi = -phase(key, -mx, -my)
    a = amplitude * f
    spectrum[iy, ix] = wp.vec2d(a * wp.cos(phi), a * wp.sin(phi))


@wp.kernel
def to_float32_kernel(h: wp.array2d[wp.float64], z: wp.array2d[wp.float32]):
    """One thread per pixel: z = float32(h)."""
    iy, ix = wp.tid()
    z[iy, ix] = wp.float32(h[iy, ix])
