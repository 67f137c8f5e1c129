# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Near full contact on the default tolerance: a periodic wavy surface against Westergaard's
closed form (issue 40, item 3).

A rigid sinusoid h(x) = Δ·cos(2πx/λ) pressed on an elastic half-space (contact modulus E*) at
the mean pressure p̄ touches over |x| < a of each period, with (Johnson, *Contact Mechanics*,
§ 13.2)

    p̄ / p* = sin²(πa/λ),    p* = π·E*·Δ/λ    (the mean pressure of complete contact),

so at a contact fraction f = 2a/λ the open (gap) region of a period is (1 − f)·λ wide. The first
test checks that closed form independently in float64 NumPy (the pressure distribution of
Westergaard's solution, its mean, and the gap it makes on a 1-D periodic half-space); the
others solve the problem with :class:`~warptrunc.contact.ContactSolver` on its defaults (float64,
load control) on a periodic map of λ = 2048 pixels by a few rows and count the open pixels of
every row: within one pixel of (1 − f)·λ at f = 50, 90, 99 and 99.9 % (1024, 204.8, 20.48,
2.048 px), every solve converged. The grid is cell-centred, pixel i at x = (i + ½)·dx, so the
trough of the sinusoid lies on a pixel edge and the open region covers whole pixels
symmetrically. float32 resolves the first two only (guide/performance.md, precision).
"""

import math

import numpy as np
import pytest

from warptrunc.contact import ContactSolver, SolverSettings

LAM = 2048  # pixels per period
ROWS = 4
DX = 1e-6  # m
E_STAR = 1e11  # Pa
DELTA = 1e-6  # m, amplitude of the sinusoid
P_STAR = math.pi * E_STAR * DELTA / (LAM * DX)  # Pa, complete contact


def mean_pressure(f: float) -> float:
    """Westergaard's mean pressure (Pa) at the contact fraction f = 2a/λ."""
    return P_STAR * math.sin(math.pi * f / 2) ** 2


def test_closed_form_is_westergaards_solution():
    """p(x) = 2p̄·cos(πx/λ)·√(sin²(πa/λ) − sin²(πx/λ))/sin²(πa/λ) on |x| < a has mean p̄ and,
    on a periodic half-space (u_k = 2p_k/(E*·|k|)), closes the gap to h exactly there and
    opens it outside: the relation p̄/p* = sin²(πa/λ) used below, in float64 NumPy."""
    n, lam = 1 << 16, 1.0
    x = (np.arange(n) - n // 2) * lam / n
    for f in (0.3, 0.9):
        a = f * lam / 2
        pbar = mean_pressure(f) * (LAM * DX) / (math.pi * E_STAR * DELTA)  # with Δ = λ/π, E* = 1
        s2 = math.sin(math.pi * a / lam) ** 2
        inside = np.abs(x) < a
        root = np.sqrt(np.clip(s2 - np.sin(np.pi * x / lam) ** 2, 0.0, None))
        p = np.where(inside, 2 * pbar * np.cos(np.pi * x / lam) * root / s2, 0.0)
        assert p.mean() == pytest.approx(pbar, rel=1e-4)
        k = 2 * np.pi * np.fft.fftfreq(n, d=lam / n)
        pk = np.fft.fft(p)
        uk = np.zeros_like(pk)
        uk[1:] = 2 * pk[1:] / np.abs(k[1:])  # E* = 1
        u = np.fft.ifft(uk).real
        h = (lam / math.pi) * np.cos(2 * np.pi * x / lam)  # Δ = λ/π: p* = π·E*·Δ/λ = 1
        gap = u - h
        gap -= gap[np.abs(x) < 0.5 * a].mean()
        scale = lam / math.pi
        assert np.abs(gap[inside]).max() < 2e-3 * scale  # closed in contact (grid error)
        assert gap[np.abs(x) > a + 4 * lam / n].min() > 0  # open outside


def _open_width(f: float, dtype: str = "float64") -> tuple[np.ndarray, bool]:
    x = (np.arange(LAM) + 0.5) * DX
    h = np.tile(DELTA * np.cos(2 * np.pi * x / (LAM * DX)), (ROWS, 1))
    solver = ContactSolver(
        h, DX, E_STAR, settings=SolverSettings(substrate="periodic", dtype=dtype), device="cpu"
    )
    state = solver.solve(load=mean_pressure(f) * h.size * DX * DX)
    p, _ = solver.maps()
    return (p <= 0).sum(axis=1), state.converged


@pytest.mark.parametrize("f", [0.5, 0.9, 0.99, 0.999])
def test_open_region_within_one_pixel_on_defaults(f):
    width, converged = _open_width(f)
    assert converged
    assert np.all(width == width[0])  # the rows agree: the problem is 1-D
    assert abs(width[0] - (1 - f) * LAM) <= 1.0, (width[0], (1 - f) * LAM)


@pytest.mark.parametrize("f", [0.5, 0.9])
def test_float32_resolves_the_first_two(f):
    width, converged = _open_width(f, "float32")
    assert converged
    assert abs(width[0] - (1 - f) * LAM) <= 1.0, (width[0], (1 - f) * LAM)
