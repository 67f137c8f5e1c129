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
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..material import Material
from ..params import Parameters, check_fields, param, param_like
from ..presets import CHALLENGE, CHALLENGE_MATERIAL
from ..selfaffine import SelfAffineSpec

if TYPE_CHECKING:
    import warp as wp

    from ..contact.settings import SolverSettings
    from ..surface import Surface

__all__ = [
    "ADHESION",
    "MIN_CONTACT_PIXELS",
    "PIXEL_TOLERANCE",
    "PRESSURE_RANGE",
    "REFERENCE_PRESSURE",
    "SOURCE",
    "ChallengeSettings",
    "ChallengeStudy",
    "challenge_patch_spec",
    "challenge_c0",
    "challenge_spec",
    "challenge_study",
    "gw_patch_area_density",
    "gw_pressure_density",
    "read_challenge_surface",
    "spectral_slope_rms",
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


@dataclass(frozen=True)
class ChallengeSettings(Parameters):
    """What :func:`challenge_study` solves: the grid, the grid study, the pressures (as p/E*).

    Raises
    ------
    ValueError
        A field out of its range, or ``p_min`` not below ``p_max``.

    Examples
    --------
    >>> ChallengeSettings(n=256).pressures(25e6).size
    13
    """

    n: int = param(
        512,
        "pixels per side of the generated surface (the grid study adds 2n)",
        kind="int",
        ge=8,
        le=1 << 16,
        sweep=False,
    )
    seed: int = param_like(SelfAffineSpec, "seed")
    short_cutoff: float | None = param(
        None,
        "shortest wavelength λ_s of the generated surface; none = the challenge's 0.1 µm, or "
        "2 pixels of n where that is coarser",
        unit="m",
        gt=0.0,
        optional=True,
    )
    refine: bool = param(
        True,
        "grid study: the same content at n and 2n pixels, the comparison on 2n",
        kind="bool",
        sweep=False,
    )
    p_min: float = param(PRESSURE_RANGE[0], "smallest nominal pressure p/E*", gt=0.0, lt=1.0)
    p_max: float = param(PRESSURE_RANGE[1], "largest nominal pressure p/E*", gt=0.0, lt=1.0)
    per_decade: int = param(4, "nominal pressures per decade", kind="int", ge=1, le=64)
    reference_pressure: float = param(
        REFERENCE_PRESSURE, "p/E* of the distributions of pressure, gap and patches", gt=0.0, lt=1.0
    )
    height_unit: float | None = param(
        None,
        "metres per unit of the heights of a map read from a file (an HDF5 file stores no "
        "unit); none = the factor that gives it h′_rms = 1",
        unit="m",
        gt=0.0,
        optional=True,
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self)
        if not self.p_min < self.p_max:
            raise ValueError(f"p_min ({self.p_min:g}) must be below p_max ({self.p_max:g})")

    def pressures(self, contact_modulus: float) -> np.ndarray:
        """The nominal pressures p (Pa): ``per_decade`` per decade from p_min·E* to p_max·E*.

        Parameters
        ----------
        contact_modulus : float
            E* (Pa).

        Returns
        -------
        (m,) ndarray
            Logarithmically spaced, both ends included (at least 3 values).
        """
        m = max(3, round(self.per_decade * math.log10(self.p_max / self.p_min)) + 1)
        return contact_modulus * np.geomspace(self.p_min, self.p_max, m)

    def spec(self) -> SelfAffineSpec:
        """The generated surface at ``n``, ``short_cutoff`` and ``seed``.

        Returns
        -------
        SelfAffineSpec
            :func:`challenge_spec` of these fields.
        """
        return challenge_spec(self.n, short_cutoff=self.short_cutoff, seed=self.seed)


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
    On a grid that holds every mode of the band (‖m‖ ≤ L/λ_s = 1000 for the challenge, all
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


def challenge_patch_spec(n: int = 512, *, seed: int = 0) -> SelfAffineSpec:
    """A periodic n² patch of the challenge's surface at the challenge's own pixel.

    The adhesive variant's range ρ = 2.071 nm is about the challenge's pixel (3.05 nm); on a
    coarser grid of the full 100 µm side one pixel spans a hundred ranges and the law is not
    resolved. This patch keeps the pixel and the spectrum and gives up the long wavelengths:
    side L_p = n·L/32768 (1.5625 µm at 512²), λ_s = 0.1 µm, and C(q) the challenge's (its C₀,
    :func:`challenge_c0`) at every mode the patch holds (wavelengths from L_p down to λ_s: on
    the power-law branch below the roll-off λ_r = 20 µm, and the plateau above it once
    L_p > λ_r, from 6554² on).

    Parameters
    ----------
    n : int
        Pixels per side (count), at least 64 (λ_s = 0.1 µm is 33 pixels, and the patch must hold
        wavelengths above it).
    seed : int
        Seed of the random phases.

    Returns
    -------
    SelfAffineSpec
        ``L`` = n·3.05 nm, ``n``, the challenge's Hurst exponent and λ_s, its roll-off where the
        patch holds it (else none), the scale as
        ``rms_height`` (the rms height of the patch's modes of the challenge's C(q); its h′_rms is
        below 1, the modes longer than L_p being gone).

    Raises
    ------
    ValueError
        ``n`` below 64.
    """
    n = int(n)
    if n < 64:
        raise ValueError(f"n must be at least 64 pixels for a patch that holds λ_s, got {n}")
    side = n * CHALLENGE.L / CHALLENGE.n
    c0 = challenge_c0()
    if side > CHALLENGE.rolloff:  # the patch holds the roll-off: the challenge's shape as it is
        spec = CHALLENGE.replace(n=n, L=side, seed=seed)
    else:
        # no roll-off inside the patch: the generator's shape is f = (q/q_L)^−(1+H), q_L = 2π/L_p;
        # the challenge's C(q) = C₀ (q/q_r)^−2(1+H) is C₀ (q_r/q_L)^2(1+H) f²
        spec = CHALLENGE.replace(n=n, L=side, seed=seed, rolloff=None)
        c0 *= (side / CHALLENGE.rolloff) ** (2 * (1 + CHALLENGE.hurst))
    s = 2 * math.pi * math.sqrt(c0) / side
    return spec.replace(rms_slope=None, rms_height=s * math.sqrt(_mode_sums(spec)[0]))


def challenge_c0() -> float:
    """C₀ (m⁴) of the challenge's spectrum: the plateau that gives h′_rms = 1 over its modes.

    Returns
    -------
    float
        s² L²/(2π)² with s = 1/√(Σ_m ‖q_m‖² f(q_m)²) over the integer wavenumbers m of the band
        (f the spectrum's shape, 1 on the plateau), the normalisation of
        :func:`~warptrunc.selfaffine.self_affine_surface` on any grid that holds every mode.
    """
    s2 = _mode_sums(CHALLENGE)[1]
    return (CHALLENGE.rms_slope**2 / s2) * CHALLENGE.L**2 / (2 * math.pi) ** 2


def _mode_sums(spec: SelfAffineSpec) -> tuple[float, float]:
    """(Σ f², Σ ‖q‖² f²) over the modes of ``spec``'s grid (float64, NumPy), as the generator
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


# --- the challenge's own map -----------------------------------------------------------------


def read_challenge_surface(
    path: str | Path, *, height_unit: float | None = None, channel: int | None = None
) -> Surface:
    """The challenge's own surface from its HDF5 file (SurfaceTopography's ``h5`` reader).

    Parameters
    ----------
    path : str or Path
        The challenge's ``.h5`` file (a 2-D dataset of heights; not shipped with warptrunc).
    height_unit : float, optional
        Metres per unit of the file's heights. Default: the factor that gives the map the
        challenge's rms gradient h′_rms = 1 (by the periodic spectrum of the map), since an
        HDF5 file stores no units.
    channel : int, optional
        The dataset to read when the file holds several (SurfaceTopography's channel index).

    Returns
    -------
    Surface
        Periodic heights z[iy, ix] (m) over L × L = 100 µm × 100 µm (the file's first index
        runs along x, as SurfaceTopography reads it); ``params`` hold ``source``, ``periodic``,
        ``height_unit_m`` (the factor used) and ``slope_rms`` (spectral, dimensionless).

    Raises
    ------
    ValueError
        The file holds no 2-D dataset, or a non-square one.
    MissingExtraError
        SurfaceTopography (a dependency of warptrunc) is missing.
    """
    from ..surface import from_heights

    path = Path(path)
    try:
        from SurfaceTopography import open_topography
    except ImportError:
        from ..io.scan import MissingExtraError

        raise MissingExtraError(
            f"{path}: reading the challenge's HDF5 file needs SurfaceTopography: "
            "pip install SurfaceTopography"
        ) from None
    reader = open_topography(str(path))
    if not reader.channels:
        raise ValueError(f"{path}: holds no 2-D dataset (no height map)")
    ch = reader.default_channel if channel is None else reader.channels[channel]
    nx, ny = (int(v) for v in ch.nb_grid_pts)
    if nx != ny:
        raise ValueError(f"{path}: the challenge's map is square, got {nx} × {ny} points")
    L = float(CHALLENGE.L)
    topo = reader.topography(channel_index=ch.index, physical_sizes=(L, L), periodic=True)
    z = np.asarray(topo.heights(), dtype=np.float64).T  # SurfaceTopography: h[ix, iy]
    z = z - z.mean()
    slope = spectral_slope_rms(z, L / nx)
    unit = 1.0 / slope if height_unit is None else float(height_unit)
    if not (math.isfinite(unit) and unit > 0):
        raise ValueError(f"height_unit must be a finite number > 0 (m per unit), got {unit!r}")
    return from_heights(
        z * unit,
        L / nx,
        source=str(path),
        reader="SurfaceTopography h5",
        dataset=str(ch.name),
        periodic=True,
        height_unit_m=unit,
        slope_rms=slope * unit,
    )


def spectral_slope_rms(z: np.ndarray, dx: float, dy: float | None = None) -> float:
    """h′_rms = √⟨‖∇h‖²⟩ of a periodic map by its discrete Fourier transform (dimensionless).

    Parameters
    ----------
    z : (ny, nx) array_like
        Heights (m) of a periodic map.
    dx, dy : float
        Pixel sides (m); ``dy`` defaults to ``dx``.

    Returns
    -------
    float
        √(Σ_q ‖q‖² ∣ĥ_q∣²)/(nx·ny) over the modes below the Nyquist wavenumbers (an even grid's
        Nyquist lines carry no gradient of a real map).
    """
    z = np.asarray(z, dtype=np.float64)
    dy = dx if dy is None else dy
    ny, nx = z.shape
    c = np.fft.rfft2(z)
    qx = 2 * math.pi * np.fft.rfftfreq(nx, d=dx)
    qy = 2 * math.pi * np.fft.fftfreq(ny, d=dy)
    if nx % 2 == 0:
        qx[-1] = 0.0
    if ny % 2 == 0:
        qy[ny // 2] = 0.0
    w = np.full(qx.size, 2.0)
    w[0] = 1.0
    if nx % 2 == 0:
        w[-1] = 1.0
    power = (qy[:, None] ** 2 + qx[None, :] ** 2) * np.abs(c) ** 2 * w[None, :]
    return float(math.sqrt(power.sum()) / (nx * ny))


# --- Greenwood–Williamson's distributions ----------------------------------------------------


def gw_pressure_density(
    summits: Any, separation: float, stress: Any, *, modulus: float
) -> np.ndarray:
    """The distribution of contact pressure over the nominal area of GW's Hertz contacts.

    Parameters
    ----------
    summits : SummitStatistics
        Density η (1/m²), radius R (m), mean height y_s and rms σ_s (m) of the summits
        (:func:`~warptrunc.theory.nayak_summits`; heights Gaussian).
    separation : float
        The flat's separation d from the mean plane (m), GW's d(p).
    stress : (k,) array_like
        Pressures σ > 0 (Pa).
    modulus : float
        E* (Pa).

    Returns
    -------
    (k,) ndarray
        P(σ) (1/Pa): ∫₀^∞ P dσ = A/A₀ and ∫₀^∞ σ P dσ = p of :func:`~warptrunc.theory.greenwood_williamson`.

    Notes
    -----
    A Hertz contact of interference w = z − d has radius a = √(Rw) and the pressure
    p₀√(1 − r²/a²), p₀ = (2E*/π)√(w/R); the area where it exceeds σ < p₀ is πa²(1 − σ²/p₀²),
    so its area density in σ is 2πa²σ/p₀² = π³R²σ/(2E*²), the same for every summit with
    p₀ > σ, i.e. with w > w_σ = π²Rσ²/(4E*²). Summed over the summits:
    P(σ) = η π³R²σ/(2E*²) · Pr(z > d + w_σ).
    """
    from scipy.special import ndtr

    s = np.asarray(stress, dtype=np.float64)
    eta, R = summits.density, summits.radius
    w_s = math.pi**2 * R * s**2 / (4 * modulus**2)
    tail = ndtr(-(separation + w_s - summits.height_mean) / summits.height_std)
    return eta * math.pi**3 * R**2 * s / (2 * modulus**2) * tail


def gw_patch_area_density(summits: Any, separation: float, area: Any) -> np.ndarray:
    """The number density of GW's contact areas a per unit nominal area (1/m⁴).

    Parameters
    ----------
    summits : SummitStatistics
        η (1/m²), R (m), y_s and σ_s (m) (Gaussian summit heights).
    separation : float
        d (m).
    area : (k,) array_like
        Contact areas a ≥ 0 (m²).

    Returns
    -------
    (k,) ndarray
        n(a) (1/m⁴): a summit at z > d touches over a = πR(z − d), so n(a) = η φ(d + a/(πR))/(πR)
        with φ the summits' height density; ∫ n da is the contacts per unit area and
        ∫ a n da is A/A₀.
    """
    a = np.asarray(area, dtype=np.float64)
    eta, R = summits.density, summits.radius
    z = (separation + a / (math.pi * R) - summits.height_mean) / summits.height_std
    phi = np.exp(-0.5 * z**2) / (math.sqrt(2 * math.pi) * summits.height_std)
    return eta * phi / (math.pi * R)


# --- the study -------------------------------------------------------------------------------

PIXEL_TOLERANCE = 0.05
"""Largest relative change of a_r and ū from N to 2N pixels (the same content) for the BEM to
count as converged in the pixel (dimensionless); loads with fewer than :data:`MIN_CONTACT_PIXELS`
contact pixels on the coarser grid are not judged."""

MIN_CONTACT_PIXELS = 100
"""Fewest contact pixels for a load to count as resolved: in the grid study's judgement, the
small-load κ and the fits of K(p) (count)."""

SMALL_LOAD_AREA_FRACTION = 0.05
"""The small-load range of κ and of the slope of K(p): a_r up to this (dimensionless)."""

TRUNCATION_MIN_PIXELS = 10
"""Truncated pixels below which a truncation row is not resolved (count)."""


@dataclass(frozen=True, eq=False)
class ChallengeStudy:
    """The challenge's problem solved over nominal pressures, beside the theories and truncation.

    The elastic (BEM) columns are those of the finer grid of the grid study; ``coarse_*`` the
    coarser one. Every array is (m,) over ``pressure``; SI units.
    """

    pressure: np.ndarray
    """(m,) nominal pressure p (Pa)."""
    area_fraction: np.ndarray
    """(m,) BEM relative contact area a_r = A/A₀ (dimensionless)."""
    mean_gap: np.ndarray
    """(m,) BEM mean gap ū over the map (m)."""
    stiffness: np.ndarray
    """(m,) BEM stiffness per unit nominal area K = −dp/dū (Pa/m), from the neighbouring loads
    (second-order differences of ū in ln p: K = −p/(dū/d ln p); one-sided at the ends)."""
    n_contact: np.ndarray
    """(m,) int64 contact pixels of the BEM solve."""
    converged: np.ndarray
    """(m,) bool: the BEM solve converged (both grids)."""
    coarse_area_fraction: np.ndarray
    """(m,) a_r on the coarser grid (dimensionless); NaN without a grid study."""
    coarse_mean_gap: np.ndarray
    """(m,) ū on the coarser grid (m); NaN without a grid study."""
    persson_area_fraction: np.ndarray
    """(m,) Persson's A/A₀ (dimensionless)."""
    persson_mean_gap: np.ndarray
    """(m,) Persson's ū (m), Yang & Persson's γ = 0.45."""
    persson_stiffness: np.ndarray
    """(m,) Persson's K = −dp/dū (Pa/m)."""
    gw_area_fraction: np.ndarray
    """(m,) GW's A/A₀ (Gaussian summit heights, dimensionless)."""
    gw_mean_gap: np.ndarray
    """(m,) GW's separation d of the flat from the mean plane (m)."""
    gw_stiffness: np.ndarray
    """(m,) GW's K = −dp/dd (Pa/m)."""
    bgt_area_fraction: np.ndarray
    """(m,) Bush–Gibson–Thomas' A/A₀ (dimensionless)."""
    bgt_mean_gap: np.ndarray
    """(m,) BGT's separation d (m)."""
    bgt_stiffness: np.ndarray
    """(m,) BGT's K = −dp/dd (Pa/m)."""
    truncation_area_fraction: np.ndarray
    """(m,) truncation's A'/A₀ at the depth ω where Eq. 2's load F'/A₀ is p (dimensionless)."""
    truncation_mean_gap: np.ndarray
    """(m,) the truncating plane's height over the mean plane, z_top − ω − z̄ (m): truncation
    leaves the surface undeformed, so this is its separation (GW's d, not a mean gap)."""
    truncation_stiffness: np.ndarray
    """(m,) Eq. 2's k'/A₀ = dp/dω (Pa/m)."""
    truncation_resolved: np.ndarray
    """(m,) bool: at least ``TRUNCATION_MIN_PIXELS`` truncated pixels and 10 depth
    increments below ω."""
    contact_modulus: float
    """E* (Pa)."""
    apparent_area: float
    """A₀ = L² (m²)."""
    slope_rms: float
    """h′_rms of the spectrum the theories read (dimensionless; the map's own for a generated one)."""
    h_rms: float
    """Rms height of that spectrum (m)."""
    grid_study: dict[str, Any] = field(default_factory=dict)
    """The grid study: ``n`` (the two grids), ``pixel_m``, ``short_cutoff_m`` (the content),
    ``max_change_area_fraction``, ``max_change_mean_gap`` (relative, over the resolved loads),
    ``loads_judged``, ``tolerance``, ``converged_in_pixel``, ``same_surface`` (the coarse map is
    the fine one at every second pixel, to float32 round-off); empty without one."""
    kappa: dict[str, Any] = field(default_factory=dict)
    """Small-load κ = a_r E* h′_rms/p: ``bem`` (mean over the loads with a_r ≤
    ``SMALL_LOAD_AREA_FRACTION`` and ≥ :data:`MIN_CONTACT_PIXELS` contact pixels), ``bem_range``,
    ``persson``, ``gw``, ``bgt`` at the same loads, ``persson_limit`` √(8/π), ``bgt_limit`` √(2π)."""
    stiffness_slope: dict[str, Any] = field(default_factory=dict)
    """d ln K/d ln p fitted over the same loads: ``bem``, ``persson``, ``gw``, ``bgt``,
    ``truncation`` (dimensionless; Persson's small-load limit is 1, K = p/u₀)."""
    distributions: dict[str, Any] = field(default_factory=dict)
    """At ``reference_pressure_Pa``: ``pressure`` (P(σ), 1/Pa), ``gap`` (P(u), 1/m) and
    ``patch_area`` (number density of contact patches per unit nominal area, 1/m⁴), each with the
    BEM's, Persson's (not for patches), GW's and truncation's (not for pressure) columns."""
    surface: dict[str, Any] = field(default_factory=dict)
    """The surface: its spec or file, the grid, h_rms, h′_rms (spectrum and finite
    differences: :func:`warptrunc.slope.slope_record`)."""
    settings: dict[str, Any] = field(default_factory=dict)
    """The problem's source, the material, the solver's settings, the truncation grid."""

    @property
    def kappa_curve(self) -> np.ndarray:
        """(m,) κ = a_r E* h′_rms / p of the BEM at every load (dimensionless)."""
        return self.area_fraction * self.contact_modulus * self.slope_rms / self.pressure

    def to_dict(self) -> dict[str, np.ndarray]:
        """1-D columns over the pressures, SI units in the names.

        Returns
        -------
        dict of str to ndarray
            ``pressure_Pa``, ``pressure_over_contact_modulus``; ``bem_area_fraction``,
            ``bem_mean_gap_m``, ``bem_stiffness_Pa_per_m``, ``bem_kappa``, ``bem_n_contact``,
            ``bem_converged``, ``coarse_area_fraction``, ``coarse_mean_gap_m``; for ``persson``,
            ``gw``, ``bgt`` and ``truncation``: ``<model>_area_fraction``,
            ``<model>_mean_gap_m``, ``<model>_stiffness_Pa_per_m``; ``truncation_resolved``.
        """
        out: dict[str, np.ndarray] = {
            "pressure_Pa": self.pressure,
            "pressure_over_contact_modulus": self.pressure / self.contact_modulus,
            "bem_area_fraction": self.area_fraction,
            "bem_mean_gap_m": self.mean_gap,
            "bem_stiffness_Pa_per_m": self.stiffness,
            "bem_kappa": self.kappa_curve,
            "bem_n_contact": self.n_contact,
            "bem_converged": self.converged,
            "coarse_area_fraction": self.coarse_area_fraction,
            "coarse_mean_gap_m": self.coarse_mean_gap,
        }
        for m in ("persson", "gw", "bgt", "truncation"):
            out[f"{m}_area_fraction"] = getattr(self, f"{m}_area_fraction")
            out[f"{m}_mean_gap_m"] = getattr(self, f"{m}_mean_gap")
            out[f"{m}_stiffness_Pa_per_m"] = getattr(self, f"{m}_stiffness")
        out["truncation_resolved"] = self.truncation_resolved
        return out

    def record(self) -> dict[str, Any]:
        """Everything, JSON-ready: ``columns`` (:meth:`to_dict` as lists), ``grid_study``,
        ``kappa``, ``stiffness_slope``, ``distributions``, ``surface``, ``settings`` and the
        scalars (SI).

        Returns
        -------
        dict
        """
        return {
            "problem": self.settings.get("problem", {}),
            "contact_modulus_Pa": self.contact_modulus,
            "apparent_area_m2": self.apparent_area,
            "slope_rms": self.slope_rms,
            "h_rms_m": self.h_rms,
            "grid_study": self.grid_study,
            "kappa": self.kappa,
            "stiffness_slope": self.stiffness_slope,
            "columns": {k: np.asarray(v).tolist() for k, v in self.to_dict().items()},
            "distributions": self.distributions,
            "surface": self.surface,
            "settings": self.settings,
        }

    def to_json(self, path: str | Path, *, warnings: list | None = None) -> Path:
        """Write :meth:`record` as strict JSON, with provenance and ``warnings``.

        Parameters
        ----------
        path : str or Path
            The file (overwritten).
        warnings : list of dict, optional
            Plausibility warnings (:mod:`warptrunc.plausibility`) to record.

        Returns
        -------
        Path
            ``path``; non-finite floats are written as null.
        """
        from .._support.outputs import strict_json
        from .._support.provenance import provenance

        path = Path(path)
        doc = {
            **self.record(),
            "provenance": provenance(self.settings.get("device")),
            "warnings": list(warnings or []),
        }
        path.write_text(strict_json(doc, indent=1))
        return path


def challenge_study(
    surface: Surface | SelfAffineSpec | None = None,
    study: ChallengeSettings | None = None,
    *,
    material: Material = CHALLENGE_MATERIAL,
    settings: SolverSettings | None = None,
    progress: bool = False,
    device: wp.DeviceLike = None,
) -> ChallengeStudy:
    """The challenge's problem on the periodic half-space, beside Persson, GW, BGT and truncation.

    Parameters
    ----------
    surface : Surface or SelfAffineSpec, optional
        The surface: a :class:`~warptrunc.selfaffine.SelfAffineSpec` (generated at its grid
        and, for the grid study, at twice its pixels), a periodic map (the challenge's own,
        :func:`read_challenge_surface`; refined for the grid study by Fourier interpolation,
        the same content) or None: the challenge's surface of ``study``
        (:meth:`ChallengeSettings.spec`).
    study : ChallengeSettings, optional
        The grid (when ``surface`` is None), whether to run the grid study (the same content at
        N and 2N pixels, the comparison on 2N), the nominal pressures and the reference one
        (default ``ChallengeSettings()``: 512² and 1024², 13 pressures from 10⁻⁴ E* to
        10⁻¹ E*, the distributions at 10⁻² E*).
    material : Material
        E* = ``material.contact_modulus`` (Pa); elastic (the hardness is not read).
    settings : SolverSettings, optional
        The solver's precision and tolerances; the substrate must be periodic (default:
        ``SolverSettings(substrate="periodic")``).
    progress : bool
        Report the solves on stderr.
    device : str, optional
        Warp device of the solves and of truncation.

    Returns
    -------
    ChallengeStudy

    Raises
    ------
    ValueError
        A free substrate, a non-square map.

    Notes
    -----
    The elastic solves are load-controlled (:func:`~warptrunc.contact.solve_contact`, loads
    p·A₀, each warm-started from the previous), the gap maps of the reference load from one
    solve more. The theories read the spectrum of the map (:func:`~warptrunc.theory.columns.surface_spectrum`:
    for a generated map its own; for a file its periodogram cut at its noise floor).
    Truncation is warptrunc's (:func:`~warptrunc.truncate`, :func:`~warptrunc.stiffness.stiffness_curve`,
    β' = 1) on the finer map: the depth ω at which F'(ω)/A₀ = p gives A'/A₀ and k'/A₀ by
    interpolation on 4000 increments. Islands are 4-connected on the torus
    (:func:`warptrunc.islands.label_islands` with ``periodic=True``). The solver and Persson's
    theory are small-slope theories; the challenge's h′_rms = 1 is outside that range as every
    half-space model of the challenge is (the record carries h′_rms).
    """
    from ..contact.curve import solve_contact
    from ..contact.settings import CurveSettings
    from ..contact.settings import SolverSettings as _Settings
    from ..slope import slope_record
    from ..theory import (
        KAPPA_BGT,
        KAPPA_PERSSON,
        bush_gibson_thomas,
        greenwood_williamson,
        persson_contact,
    )
    from ..theory.columns import surface_spectrum

    settings = _Settings(substrate="periodic") if settings is None else settings
    if settings.substrate != "periodic":
        raise ValueError(
            f"the challenge's problem is periodic: settings.substrate must be 'periodic', got "
            f"{settings.substrate!r}"
        )
    study = ChallengeSettings() if study is None else study
    material = material.replace(hardness=math.inf)
    modulus = float(material.contact_modulus)
    p = study.pressures(modulus)
    ref = float(study.reference_pressure) * modulus
    fine, coarse, origin = _grids(surface, study, device)
    a0 = fine.lx * fine.ly
    curve = CurveSettings(stiffness="none")
    kw = {"material": material, "settings": settings, "progress": progress, "device": device}
    bem = solve_contact(fine, loads=p * a0, curve=curve, **kw)
    nan = np.full(p.size, np.nan)
    grid: dict[str, Any] = {}
    coarse_ar, coarse_gap, conv = nan, nan, np.asarray(bem.converged, bool)
    ar = bem.area / a0
    if coarse is not None:
        cb = solve_contact(coarse, loads=p * a0, curve=curve, **kw)
        coarse_ar, coarse_gap = cb.area / a0, np.asarray(cb.mean_gap, dtype=np.float64)
        conv = conv & np.asarray(cb.converged, bool)
        grid = _grid_record(fine, coarse, cb, ar, bem.mean_gap, coarse_ar, coarse_gap, origin)
    gap = np.asarray(bem.mean_gap, dtype=np.float64)
    stiff = -p / np.gradient(gap, np.log(p))

    psd = surface_spectrum(fine, window="none")
    pc = persson_contact(psd, p, material=material)
    gw = greenwood_williamson(psd, p, material=material)
    bgt = bush_gibson_thomas(psd, p, material=material)
    tr = _truncation_at(fine, p, material, device)

    resolved = (ar <= SMALL_LOAD_AREA_FRACTION) & (bem.n_contact >= MIN_CONTACT_PIXELS) & conv
    slope = psd.slope_rms
    kappa = {
        "bem": None,
        "bem_range": None,
        "n_loads": int(resolved.sum()),
        "max_area_fraction": SMALL_LOAD_AREA_FRACTION,
        "min_contact_pixels": MIN_CONTACT_PIXELS,
        "persson_limit": KAPPA_PERSSON,
        "bgt_limit": KAPPA_BGT,
        "slope_rms": slope,
    }
    if resolved.any():
        k = ar[resolved] * modulus * slope / p[resolved]
        kappa.update(
            bem=float(k.mean()),
            bem_range=[float(k.min()), float(k.max())],
            persson=float(pc.kappa[resolved].mean()),
            gw=float(gw.kappa[resolved].mean()),
            bgt=float(bgt.kappa[resolved].mean()),
        )
    slopes = {"loads": int(resolved.sum()), "persson_small_load_limit": 1.0}
    for name, kk in (
        ("bem", stiff),
        ("persson", pc.stiffness),
        ("gw", gw.stiffness),
        ("bgt", bgt.stiffness),
        ("truncation", tr["stiffness"]),
    ):
        slopes[name] = _log_slope(
            p, kk, resolved & (tr["resolved"] if name == "truncation" else True)
        )

    dist = _distributions(fine, ref, psd, material, settings, tr, device)
    rec = slope_record(fine, limit=settings.slope_limit)
    surf = {
        "origin": origin,
        "grid": [fine.nx, fine.ny],
        "pixel_m": fine.dx,
        "L_m": fine.lx,
        "h_rms_spectrum_m": psd.h_rms,
        "slope_rms_spectrum": slope,
        "spectrum": {
            "source": psd.source,
            "q_min_per_m": float(psd.wavevector[0]),
            "q_max_per_m": float(psd.wavevector[-1]),
            "noise_wavevector_per_m": psd.noise_wavevector,
        },
        "slope": rec,
        "params": fine.to_dict(),
    }
    sett = {
        "problem": {
            "source": SOURCE,
            "surface": CHALLENGE.to_dict(),
            "contact_modulus_Pa": float(CHALLENGE_MATERIAL.contact_modulus),
            "adhesion": ADHESION,
            "adhesion_used": False,
        },
        "study": study.to_dict(),
        "material": material.to_dict(),
        "solver": dict(bem.settings),
        "truncation": {"increments": TRUNCATION_INCREMENTS, "beta_prime": 1.0},
        "gamma_persson": pc.gamma,
        "device": bem.settings.get("device"),
    }
    return ChallengeStudy(
        pressure=p,
        area_fraction=ar,
        mean_gap=gap,
        stiffness=stiff,
        n_contact=np.asarray(bem.n_contact, dtype=np.int64),
        converged=conv,
        coarse_area_fraction=np.asarray(coarse_ar, dtype=np.float64),
        coarse_mean_gap=np.asarray(coarse_gap, dtype=np.float64),
        persson_area_fraction=pc.area_fraction,
        persson_mean_gap=pc.mean_separation,
        persson_stiffness=pc.stiffness,
        gw_area_fraction=gw.area_fraction,
        gw_mean_gap=gw.separation,
        gw_stiffness=gw.stiffness,
        bgt_area_fraction=bgt.area_fraction,
        bgt_mean_gap=bgt.separation,
        bgt_stiffness=bgt.stiffness,
        truncation_area_fraction=tr["area_fraction"],
        truncation_mean_gap=tr["separation"],
        truncation_stiffness=tr["stiffness"],
        truncation_resolved=tr["resolved"],
        contact_modulus=modulus,
        apparent_area=a0,
        slope_rms=slope,
        h_rms=psd.h_rms,
        grid_study=grid,
        kappa=kappa,
        stiffness_slope=slopes,
        distributions=dist,
        surface=surf,
        settings=sett,
    )


TRUNCATION_INCREMENTS = 4000
"""Depth increments of the truncation route, up to the depth of the largest pressure (count)."""


def _grids(
    surface: Any, study: ChallengeSettings, device: Any
) -> tuple[Surface, Surface | None, dict]:
    """(fine, coarse or None, origin record): the same content at N and 2N (or N alone)."""
    from ..selfaffine import self_affine_surface
    from ..surface import Surface as _Surface
    from ..surface import from_heights

    refine = study.refine
    if surface is None:
        surface = study.spec()
    if isinstance(surface, SelfAffineSpec):
        spec = surface
        coarse = self_affine_surface(spec, device=device)
        origin = {"kind": "self-affine spec", "spec": spec.to_dict()}
        if not refine:
            return coarse, None, origin
        nx, ny = spec.grid()["nx"], spec.grid()["ny"]
        fine = self_affine_surface(spec.replace(n=(2 * nx, 2 * ny)), device=device)
        return fine, coarse, origin
    if not isinstance(surface, _Surface):
        raise TypeError(
            f"surface must be a Surface, a SelfAffineSpec or None, got {type(surface).__name__}"
        )
    if surface.nx != surface.ny or not math.isclose(surface.dx, surface.dy, rel_tol=1e-9):
        raise ValueError(
            f"the challenge's map is square with square pixels, got {surface.nx} × {surface.ny}"
        )
    origin = {"kind": "map", "params": surface.to_dict()}
    if not refine:
        return surface, None, origin
    from scipy.signal import resample

    z = np.asarray(surface.heights, dtype=np.float64)
    zz = resample(resample(z, 2 * surface.ny, axis=0), 2 * surface.nx, axis=1)
    fine = from_heights(
        zz,
        surface.dx / 2,
        surface.dy / 2,
        **{
            **surface.params,
            "refined_from": [surface.nx, surface.ny],
            "refinement": "Fourier interpolation (scipy.signal.resample)",
        },
    )
    return fine, surface, origin


def _grid_record(fine, coarse, cb, ar, gap, coarse_ar, coarse_gap, origin) -> dict[str, Any]:
    """The grid study's record (see :attr:`ChallengeStudy.grid_study`)."""
    judged = (np.asarray(cb.n_contact) >= MIN_CONTACT_PIXELS) & np.asarray(cb.converged, bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        da = np.abs(coarse_ar - ar) / ar
        dg = np.abs(coarse_gap - np.asarray(gap)) / np.abs(gap)
    za = np.asarray(coarse.heights, dtype=np.float64)
    zf = np.asarray(fine.heights, dtype=np.float64)[::2, ::2]
    same = float(np.abs(za - zf).max() / max(float(za.std()), 1e-300))
    ma = float(da[judged].max()) if judged.any() else math.nan
    mg = float(dg[judged].max()) if judged.any() else math.nan
    spec = origin.get("spec", {})
    return {
        "n": [coarse.nx, fine.nx],
        "pixel_m": [coarse.dx, fine.dx],
        "short_cutoff_m": spec.get("short_cutoff"),
        "change_area_fraction": da.tolist(),
        "change_mean_gap": dg.tolist(),
        "max_change_area_fraction": ma,
        "max_change_mean_gap": mg,
        "loads_judged": int(judged.sum()),
        "tolerance": PIXEL_TOLERANCE,
        "converged_in_pixel": bool(judged.any() and max(ma, mg) <= PIXEL_TOLERANCE),
        "same_surface_max_difference_over_h_rms": same,
    }


def _log_slope(p: np.ndarray, k: np.ndarray, sel: Any) -> float | None:
    """d ln K/d ln p by least squares over ``sel`` (None below 3 usable points)."""
    sel = np.asarray(sel, bool) & np.isfinite(k) & (k > 0)
    if sel.sum() < 3:
        return None
    return float(np.polyfit(np.log(p[sel]), np.log(k[sel]), 1)[0])


def _truncation_at(surface: Surface, p: np.ndarray, material: Material, device: Any) -> dict:
    """Truncation (Eq. 2, β' = 1) at the depths where F'/A₀ = p: A'/A₀, the plane's separation
    from the mean plane (m), k'/A₀ (Pa/m), resolved, and the depth ω (m) of each p."""
    from ..stiffness import stiffness_curve
    from ..truncation.api import truncate

    a0 = surface.lx * surface.ly
    Rt = float(surface.Rt)
    first = stiffness_curve(truncate(surface, 400, max_depth=Rt, device=device), material)
    pp = first.load / a0
    top = float(first.depth[np.searchsorted(pp, p[-1])]) if pp[-1] >= p[-1] else Rt
    top = min(Rt, top * 1.05)
    sc = stiffness_curve(
        truncate(surface, TRUNCATION_INCREMENTS, max_depth=top, device=device), material
    )
    pp = sc.load / a0
    inside = pp > 0
    lp = np.log(pp[inside])
    depth = np.interp(np.log(p), lp, sc.depth[inside], left=np.nan, right=np.nan)
    ok = np.isfinite(depth)
    area = np.interp(depth, sc.depth, sc.contact_area) / a0
    k = np.interp(depth, sc.depth, sc.stiffness) / a0
    npx = np.interp(depth, sc.depth, sc.n_contact_pixels.astype(np.float64))
    step = top / TRUNCATION_INCREMENTS
    z = np.asarray(surface.heights, dtype=np.float64)
    z_top, z_mean = float(z.max()), float(z.mean())
    resolved = ok & (npx >= TRUNCATION_MIN_PIXELS) & (depth >= 10 * step)
    return {
        "area_fraction": np.where(ok, area, np.nan),
        "separation": np.where(ok, z_top - depth - z_mean, np.nan),
        "stiffness": np.where(ok, k, np.nan),
        "resolved": resolved,
        "depth": depth,
        "curve": sc,
        "z_top": z_top,
        "z_mean": z_mean,
    }


def _density(values: np.ndarray, edges: np.ndarray, total: int) -> np.ndarray:
    """Histogram of ``values`` on ``edges`` per pixel of the map and per unit of the value."""
    counts, _ = np.histogram(values, bins=edges)
    return counts / (total * np.diff(edges))


def _distributions(
    surface: Surface, ref: float, psd: Any, material: Material, settings: Any, tr: dict, device: Any
) -> dict[str, Any]:
    """The distributions at the reference pressure ``ref`` (Pa): see
    :attr:`ChallengeStudy.distributions`."""
    from ..contact.curve import solve_contact
    from ..contact.settings import CurveSettings
    from ..islands.labelling import label_islands
    from ..theory import (
        greenwood_williamson,
        nayak_summits,
        persson_gap_distribution,
        persson_pressure_distribution,
    )

    a0 = surface.lx * surface.ly
    modulus = float(material.contact_modulus)
    cc = solve_contact(
        surface,
        loads=[ref * a0],
        material=material,
        settings=settings,
        curve=CurveSettings(stiffness="none", maps=True),
        device=device,
    )
    pm, g = np.asarray(cc.pressure[0]), np.asarray(cc.gap[0], dtype=np.float64)
    contact = pm > 0
    total = pm.size
    g = g - (float(g[contact].mean()) if contact.any() else 0.0)  # zero on the contact set
    g_open = np.clip(g[~contact], 0.0, None)
    a_r = float(contact.mean())
    gw = greenwood_williamson(psd, ref, material=material)
    d_gw = float(gw.separation[0])
    summits = nayak_summits(psd)

    # pressure
    top = float(pm.max()) if contact.any() else 2 * ref
    s_edges = np.linspace(0.0, top * (1 + 1e-9), 101)
    s_mid = 0.5 * (s_edges[1:] + s_edges[:-1])
    pp = persson_pressure_distribution(psd, ref, s_mid, material=material)
    pressure = {
        "stress_Pa": s_mid,
        "bin_edges_Pa": s_edges,
        "bem_density_per_Pa": _density(pm[contact], s_edges, total),
        "persson_density_per_Pa": pp.density,
        "gw_density_per_Pa": gw_pressure_density(summits, d_gw, s_mid, modulus=modulus),
        "bem_area_fraction": a_r,
        "persson_area_fraction": pp.area_fraction,
        "gw_area_fraction": float(gw.area_fraction[0]),
        "bem_mean_contact_pressure_Pa": float(pm[contact].mean()) if contact.any() else math.nan,
        "truncation": "no pressure field: Eq. 2 gives the load of the truncated set, not its "
        "distribution",
    }

    # gap
    omega = float(np.interp(math.log(ref), *_log_load_depth(tr, a0)))
    plane = tr["z_top"] - omega
    z = np.asarray(surface.heights, dtype=np.float64)
    below = plane - z[z < plane]
    u_top = float(max(g_open.max() if g_open.size else 0.0, below.max() if below.size else 0.0))
    u_edges = np.linspace(0.0, u_top * (1 + 1e-9), 101)
    u_mid = 0.5 * (u_edges[1:] + u_edges[:-1])
    pg = persson_gap_distribution(psd, ref, u_mid, material=material)
    h = psd.h_rms
    gw_gap = np.exp(-0.5 * ((d_gw - u_mid) / h) ** 2) / (math.sqrt(2 * math.pi) * h)
    gap = {
        "gap_m": u_mid,
        "bin_edges_m": u_edges,
        "bem_density_per_m": _density(g_open, u_edges, total),
        "persson_density_per_m": pg.density,
        "gw_density_per_m": gw_gap,
        "truncation_density_per_m": _density(below, u_edges, total),
        "bem_contact_fraction": a_r,
        "persson_contact_fraction": pg.contact_fraction,
        "bem_mean_gap_m": float(g.clip(0.0, None).mean()),
        "persson_mean_gap_m": pg.mean_separation,
        "gw_separation_m": d_gw,
        "truncation_separation_m": plane - tr["z_mean"],
        "truncation_depth_m": omega,
        "gw": "the undeformed surface's Gaussian heights (h_rms of the spectrum) below a rigid "
        "flat at GW's separation d: GW models no deformation between its summits",
        "truncation": "the undeformed map below the truncating plane at the depth where "
        "Eq. 2's F'/A₀ is the reference pressure",
    }

    # contact patches
    isl = label_islands(contact, surface.dx, surface.dy, periodic=True, device=device)
    tis = label_islands(z >= plane, surface.dx, surface.dy, periodic=True, device=device)
    areas = np.concatenate([isl.area, tis.area, [surface.dx * surface.dy]])
    a_lo = surface.dx * surface.dy * 0.5
    a_hi = float(areas.max()) * 1.5
    a_edges = np.geomspace(a_lo, a_hi, max(3, round(4 * math.log10(a_hi / a_lo)) + 1))
    a_mid = np.sqrt(a_edges[1:] * a_edges[:-1])
    patches = {
        "area_m2": a_mid,
        "bin_edges_m2": a_edges,
        "bem_density_per_m4": np.histogram(isl.area, bins=a_edges)[0] / (a0 * np.diff(a_edges)),
        "gw_density_per_m4": gw_patch_area_density(summits, d_gw, a_mid),
        "truncation_density_per_m4": np.histogram(tis.area, bins=a_edges)[0]
        / (a0 * np.diff(a_edges)),
        "bem_count": int(isl.n_islands),
        "gw_count": float(gw.contact_density[0] * a0),
        "truncation_count": int(tis.n_islands),
        "connectivity": 4,
        "periodic": True,
        "persson": "Persson's theory as implemented here gives no distribution of patch areas",
    }
    return {
        "reference_pressure_Pa": ref,
        "reference_pressure_over_contact_modulus": ref / modulus,
        "converged": bool(cc.converged[0]),
        "pressure": pressure,
        "gap": gap,
        "patch_area": patches,
    }


def _log_load_depth(tr: dict, a0: float) -> tuple[np.ndarray, np.ndarray]:
    """(ln p', ω) of the truncation curve where p' = F'/A₀ > 0, for interpolation."""
    sc = tr["curve"]
    pp = sc.load / a0
    inside = pp > 0
    return np.log(pp[inside]), sc.depth[inside]
