# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Synthetic self-affine (random-phase, power-law spectrum) surfaces of known Hurst exponent."""

from __future__ import annotations

import numpy as np

from .._support.validate import check_int, check_range, pair
from ..surface import Surface


def self_affine_surface(
    H: float,
    n: int | tuple[int, int] = 256,
    L: float | tuple[float, float] = 1e-3,
    *,
    Rrms: float = 1e-6,
    rolloff: float | None = None,
    seed: int = 0,
) -> Surface:
    """A periodic random-phase surface with an isotropic power-law spectrum of Hurst exponent H.

    Parameters
    ----------
    H : float
        Hurst exponent, 0 < H < 1 (dimensionless); the fractal dimension is D = 3 − H.
    n : int or (int, int)
        Pixels per side, or (nx, ny) (pixels, ≥ 4).
    L : float or (float, float)
        Side length, or (Lx, Ly) (m).
    Rrms : float
        RMS height after scaling (m).
    rolloff : float, optional
        Roll-off wavelength W_r (m): the PSD is flat below 1/W_r. Default: no roll-off (pure
        power law down to the lowest frequency).
    seed : int
        Seed of the phases and amplitudes (NumPy default generator).

    Returns
    -------
    Surface
        ``params`` records H, D, Rrms, rolloff and seed.

    Raises
    ------
    ValueError
        If H is not in (0, 1), a side has fewer than 4 pixels, or L, Rrms or ``rolloff`` is
        not positive and finite.

    Notes
    -----
    Fourier amplitudes are Gaussian with variance C(f) ∝ f^−2(1+H) (flat below 1/W_r), the
    DC term is zero, and the real part of the inverse FFT is taken, so the map is periodic.

    Examples
    --------
    >>> s = self_affine_surface(0.5, 256, 1e-3, Rrms=1e-6, seed=1)  # D = 2.5
    >>> fractal_dimension(s, "vs").D
    """

    H = check_range("H", H, 0.0, 1.0)
    nx, ny = pair("n", n, int)
    check_int("n", nx, 4)
    check_int("n", ny, 4)
    lx, ly = pair("L", L)
    check_range("L", lx, 0.0, unit="m")
    check_range("L", ly, 0.0, unit="m")
    Rrms = check_range("Rrms", Rrms, 0.0, unit="m")
    rng = np.random.default_rng(seed)
    fy, fx = np.meshgrid(np.fft.fftfreq(ny, ly / ny), np.fft.fftfreq(nx, lx / nx), indexing="ij")
    f = np.hypot(fx, fy)
    f[0, 0] = np.inf
    if rolloff is not None:
        fr = 1.0 / check_range("rolloff", rolloff, 0.0, unit="m")
        f = np.maximum(f, fr)
    amp = f ** (-(1.0 + H))
    amp[0, 0] = 0.0
    spec = amp * (rng.standard_normal((ny, nx)) + 1j * rng.standard_normal((ny, nx)))
    z = np.fft.ifft2(spec).real
    z *= Rrms / z.std()
    return Surface(
        z, lx / nx, ly / ny, {"H": H, "D": 3.0 - H, "Rrms": Rrms, "rolloff": rolloff, "seed": seed}
    )
