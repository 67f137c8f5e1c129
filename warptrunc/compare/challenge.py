# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The contact-mechanics challenge's problem, and its study beside the theories and truncation.

The problem (Müser et al. 2017): a periodic, isotropic self-affine surface, L = 100 µm,
Hurst H = 0.8, C(q) flat from the box down to the roll-off λ_r = 20 µm and a power law up to
the short cut-off λ_s = 0.1 µm, rms gradient h′_rms = 1, pressed against a rigid flat with
contact modulus E* = 25 MPa (:data:`warptrunc.presets.CHALLENGE` and
:data:`~warptrunc.presets.CHALLENGE_MATERIAL`); its adhesive variant adds a work of adhesion
w = 50 mJ/m² over the interaction range ρ = 2.071 nm (:data:`ADHESION`; not solved here).

- :func:`challenge_spec`: the challenge's surface on a grid of n² pixels (its 32768², or a
  coarser one with λ_s coarsened to 2 pixels and the spectrum kept);
- :func:`read_challenge_surface`: the challenge's own realisation, from its HDF5 file
  (SurfaceTopography's ``h5`` reader; the file is not shipped);
- :func:`challenge_study`: the elastic solution over nominal pressures p/E* = 10⁻⁴ … 10⁻¹ on
  the periodic half-space, converged in the pixel (the same content at N and 2N), with the
  relative contact area a_r(p), the mean gap ū(p), the stiffness K(p) = −dp/dū and, at one
  reference load, the distributions of pressure, gap and contact-patch area, each beside
  Persson's theory, Greenwood–Williamson (and Bush–Gibson–Thomas for a_r and K) and
  truncation (Eq. 2) on the same surface → :class:`ChallengeStudy` (a JSON record, a figure
  with :func:`warptrunc.plot.challenge.plot_challenge`).

References
----------
M.H. Müser, W.B. Dapp, R. Bugnicourt, P. Sainsot, N. Lesaffre, T.A. Lubrecht, B.N.J. Persson,
K. Harris, A. Bennett, K. Schulze, S. Rohde, P. Ifju, W.G. Sawyer, T. Angelini, H. Ashtari
Esfahani, M. Kadkhodaei, S. Akbarzadeh, J.-J. Wu, G. Vorlaufer, A. Vernes, S. Solhjoo,
A.I. Vakis, R.L. Jackson, Y. Xu, J. Streator, A. Rostami, D. Dini, S. Medina, G. Carbone,
F. Bottiglione, L. Afferrante, J. Monti, L. Pastewka, M.O. Robbins, J.A. Greenwood,
Meeting the contact-mechanics challenge, Tribol. Lett. 65, 118 (2017).
doi:10.1007/s11249-017-0900-2
"""

from __future__ import annotations

import math

import numpy as np

from ..presets import CHALLENGE
from ..selfaffine import SelfAffineSpec

__all__ = [
    "ADHESION",
    "PRESSURE_RANGE",
    "REFERENCE_PRESSURE",
    "SOURCE",
    "challenge_spec",
]

SOURCE = "Müser et al., Tribol. Lett. 65, 118 (2017), doi:10.1007/s11249-017-0900-2"
"""Where the challenge's problem is defined."""

ADHESION = {"work_of_adhesion": 0.05, "interaction_range": 2.071e-9}
"""The adhesive variant's interaction: work of adhesion w = 50 mJ/m² (J/m²) and range
ρ = 2.071 nm (m). Taken from ContactEngineering/Adhesion's ``soft_wall.py``, where they are given
in units of L and E*·L, not read from the paper's text; not used by the elastic study."""

PRESSURE_RANGE = (1e-4, 1e-1)
"""The nominal pressures p/E* of the study, smallest and largest (dimensionless)."""

NYQUIST_MARGIN = 1e-6
"""λ_s coarsened to 2 pixels is 2 pixels × (1 + this) (dimensionless): :func:`challenge_spec`."""

REFERENCE_PRESSURE = 1e-2
"""p/E* of the distributions (dimensionless): a choice of this study, inside the challenge's
range of loads; the load at which the challenge compared its distributions is not checked here."""


def challenge_spec(
    n: int = CHALLENGE.n, *, short_cutoff: float | None = None, seed: int = 0
) -> SelfAffineSpec:
    """The challenge's surface on an n² grid.

    Parameters
    ----------
    n : int
        Pixels per side (count); the challenge's grid is 32768 (3.05 nm pixels).
    short_cutoff : float, optional
        Shortest wavelength λ_s (m), at least the challenge's 0.1 µm and 2 pixels of the grid.
        Default: 0.1 µm, or 2 pixels where the grid is coarser than 2000² (λ_s below 2 pixels
        cannot be drawn): 2L/n·(1 + 10⁻⁶), so that the modes on the grid's Nyquist lines, which
        an even grid leaves out, lie outside the band on a finer grid as well.
    seed : int
        Seed of the random phases (:class:`~warptrunc.selfaffine.SelfAffineSpec`).

    Returns
    -------
    SelfAffineSpec
        With λ_s = 0.1 µm: :data:`~warptrunc.presets.CHALLENGE` on this grid (``rms_slope=1``).
        With a longer λ_s: the challenge's spectrum C(q) — its C₀, fixed by h′_rms = 1 over the
        challenge's modes — cut at λ_s, given as the rms height of the modes this grid holds
        (``rms_height``), so that the map's spectrum is the challenge's at every mode it keeps.
        The content above λ_s is the same surface; what the cut removes is the short-wavelength
        slope (h′_rms² grows as q_s^(2−2H): h′_rms = 0.86 at λ_s = 0.195 µm, 1024², and 0.73 at
        0.39 µm, 512²), while h_rms, set by the roll-off, hardly changes (0.7825 µm at 2048²,
        0.7822 µm at 512²).

    Raises
    ------
    ValueError
        ``n`` below 8, or ``short_cutoff`` below 0.1 µm or 2 pixels.

    Notes
    -----
    On a grid that holds every mode of the band (|m| ≤ L/λ_s = 1000 for the challenge, all
    inside a grid of 2048² or more) the discrete spectrum, and with the same seed the map, is
    the same surface on every grid: the 2048² map is the 32768² one sampled at 16 times the
    pixel (to the FFT's round-off). A given ``short_cutoff`` keeps the content fixed as the grid
    is refined (the grid study of :func:`challenge_study`).
    """
    n = int(n)
    if n < 8:
        raise ValueError(f"n must be at least 8 pixels, got {n}")
    lam_s = float(CHALLENGE.short_cutoff)
    two_px = 2.0 * CHALLENGE.L / n
    if short_cutoff is None:
        short_cutoff = lam_s if lam_s >= two_px else two_px * (1 + NYQUIST_MARGIN)
    short_cutoff = float(short_cutoff)
    if short_cutoff < lam_s * (1 - 1e-12):
        raise ValueError(
            f"short_cutoff must be at least the challenge's {lam_s:g} m, got {short_cutoff:g} m"
        )
    if short_cutoff < two_px * (1 - 1e-12):
        raise ValueError(
            f"short_cutoff = {short_cutoff:g} m is below 2 pixels of the {n}² grid "
            f"({two_px:g} m): use more pixels or a longer short_cutoff"
        )
    if short_cutoff <= lam_s * (1 + 1e-12):
        return CHALLENGE.replace(n=n, seed=seed)
    spec = CHALLENGE.replace(n=n, seed=seed, short_cutoff=short_cutoff)
    c0 = challenge_c0()
    s0 = _mode_sums(spec)[0]
    # the generator's C₀ = s² L²/(2π)² with h_rms = s √Σf²: the rms height that gives c0 here
    s = 2 * math.pi * math.sqrt(c0) / CHALLENGE.L
    return spec.replace(rms_slope=None, rms_height=s * math.sqrt(s0))


def challenge_c0() -> float:
    """C₀ (m⁴) of the challenge's spectrum: the plateau that gives h′_rms = 1 over its modes.

    Returns
    -------
    float
        s² L²/(2π)² with s = 1/√(Σ_m |q_m|² f(q_m)²) over the integer wavenumbers m of the band
        (f the spectrum's shape, 1 on the plateau), the normalisation of
        :func:`~warptrunc.selfaffine.self_affine_surface` on any grid that holds every mode.
    """
    s2 = _mode_sums(CHALLENGE)[1]
    return (CHALLENGE.rms_slope**2 / s2) * CHALLENGE.L**2 / (2 * math.pi) ** 2


def _mode_sums(spec: SelfAffineSpec) -> tuple[float, float]:
    """(Σ f², Σ |q|² f²) over the modes of ``spec``'s grid (float64, NumPy), as the generator
    sums them: the shape f of ``warptrunc.kernels.selfaffine``, the Nyquist rows and columns of
    an even grid left out. Only the wavenumbers up to the short cut-off are visited."""
    g = spec.grid()
    nx, ny, lx, ly = g["nx"], g["ny"], g["Lx"], g["Ly"]
    H, q_roll, q_long, q_short = spec.hurst, g["q_roll"], g["q_long"], g["q_short"]
    kx = min(nx // 2, int(q_short * lx / (2 * math.pi)) + 1)
    ky = min(ny // 2, int(q_short * ly / (2 * math.pi)) + 1)
    mx = np.arange(-kx, kx + 1)
    my = np.arange(-ky, ky + 1)
    mx = mx[~((nx % 2 == 0) & (np.abs(mx) == nx // 2))]
    my = my[~((ny % 2 == 0) & (np.abs(my) == ny // 2))]
    qx = 2 * math.pi * mx / lx
    qy = 2 * math.pi * my / ly
    q2 = qy[:, None] ** 2 + qx[None, :] ** 2
    q = np.sqrt(q2)
    tol = 1e-9
    inside = (q >= q_long * (1 - tol)) & (q <= q_short * (1 + tol)) & (q > 0)
    with np.errstate(divide="ignore"):
        f = np.where(q < q_roll, 1.0, (q / q_roll) ** (-(1.0 + H)))
    f2 = np.where(inside, f * f, 0.0)
    return float(f2.sum()), float((q2 * f2).sum())
