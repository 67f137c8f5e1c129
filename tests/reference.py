# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Independent float64 NumPy references, written from the paper's formulas, not from our code."""

import math

import numpy as np


def wm_numpy(D, Wr, Lx, Ly, nx, ny, *, G, M=10, gamma=1.5, Wc, seed):
    """Eq. (4) literally, in polar form, float64: z(x, y) on x = ix·Lx/nx, y = iy·Ly/ny (m)."""
    n_max = math.floor(math.log(Wr / Wc) / math.log(gamma) + 1e-9)
    # documented convention: phases ~ U[0, 2π) from default_rng(seed), shape (M, n_max + 1)
    alpha = np.random.default_rng(seed).uniform(0.0, 2.0 * math.pi, size=(M, n_max + 1))
    x = np.arange(nx) * (Lx / nx)
    y = np.arange(ny) * (Ly / ny)
    X, Y = np.meshgrid(x, y)  # X[iy, ix]
    r = np.hypot(X, Y)
    theta = np.arctan2(Y, X)
    z = np.zeros_like(X)
    for m in range(1, M + 1):
        for n in range(n_max + 1):
            a = alpha[m - 1, n]
            arg = 2 * math.pi * gamma**n * r / Wr * np.cos(theta - math.pi * m / M) + a
            z += gamma ** ((D - 3) * n) * (math.cos(a) - np.cos(arg))
    pref = Wr * (G / Wr) ** (D - 3) * math.sqrt(math.log(gamma) / M)
    return pref * z, n_max
