# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The isotropic power spectral density C(q) that the contact theories read, and its moments.

:class:`IsotropicPSD` holds C(q) (m⁴) sampled on wavevector magnitudes q (1/m) in Persson's
normalisation, made from a self-affine surface (:class:`~warptrunc.selfaffine.SelfAffineSpec`,
:meth:`IsotropicPSD.from_self_affine`), from the terms of
a Weierstrass–Mandelbrot surface (:meth:`IsotropicPSD.from_wm`) or from a height map
(:meth:`IsotropicPSD.from_height_map`, the radially averaged periodogram of
:func:`warptrunc.spectra.radial_psd`). Everything is float64 NumPy on the host.

Conventions
-----------
Persson's C(q) = (2π)⁻² ∫ d²x ⟨h(x) h(0)⟩ e^(−iq·x), so that

    ⟨h²⟩ = ∫ d²q C(q) = 2π ∫ q C(q) dq.

The other conventions in use, for the same surface:

- :mod:`warptrunc.descriptors` and :mod:`warptrunc.spectra` use the spatial frequency f = q/2π
  (1/m) with ⟨h²⟩ = ∫ d²f C_f(f): C_f(f) = (2π)² C(q);
- Jacobs, Junge & Pastewka (2017) write ⟨h²⟩ = (2π)⁻² ∫ d²q C^iso(q): C^iso = (2π)² C (the same
  numbers as C_f, on the q axis);
- the one-sided profile PSD C₁(f) (m³) of a line scan is another quantity (a projection of the
  2-D spectrum), not a rescaling.

The isotropic moments μ_k = ∫ d²q ‖q‖^k C(q) = 2π ∫ q^(k+1) C(q) dq give μ₀ = ⟨h²⟩,
μ₂ = ⟨‖∇h‖²⟩ and μ₄ = ⟨(∇²h)²⟩; Nayak's profile moments (one direction) are m₀ = μ₀,
m₂ = μ₂/2 = ⟨(∂h/∂x)²⟩ and m₄ = 3μ₄/8 = ⟨(∂²h/∂x²)²⟩.

Between its samples C(q) is a power law (a straight line in log–log; a straight line where a
sample is zero), or, for an estimate from a map, a straight line (``interpolation="linear"``:
the integrals are then the trapezoid sums of the periodogram, which keep Parseval's variance
where a line spectrum puts its power into single annuli); it is zero outside [q₀, q_max]. The
integrals over the spectrum are exact for the interpolant, so a piecewise power law
(:meth:`IsotropicPSD.from_self_affine`) has exact moments.

References
----------
Persson, Albohr, Tartaglino, Volokitin & Tosatti (2005), J. Phys.: Condens. Matter 17, R1,
doi:10.1088/0953-8984/17/1/R01. Jacobs, Junge & Pastewka (2017), Surf. Topogr.: Metrol. Prop.
5, 013001, doi:10.1088/2051-672X/aa51f8. Nayak (1971), J. Lubr. Technol. 93, 398,
doi:10.1115/1.3451608.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.special import exprel

from ..wm_params import WMSpec
from ._common import columns

__all__ = [
    "INTERPOLATIONS",
    "IsotropicPSD",
    "self_affine_band",
    "self_affine_c0",
    "self_affine_moment_per_c0",
]

INTERPOLATIONS = ("power-law", "linear")
"""How :class:`IsotropicPSD` interpolates between its samples."""

_x, _w = np.polynomial.legendre.leggauss(8)
_GAUSS = (0.5 * (_x + 1.0), 0.5 * _w)  # nodes and weights on [0, 1]


def self_affine_band(spec: Any) -> tuple[float, float, float, float]:
    """The band of a self-affine spectrum: its Hurst exponent and its three wavenumbers.

    Parameters
    ----------
    spec : SelfAffineSpec
        The spectrum (:class:`~warptrunc.selfaffine.SelfAffineSpec`).

    Returns
    -------
    tuple of float
        (H, q_L, q_r, q_s): the Hurst exponent (dimensionless), the long cut-off, the roll-off
        (q_L when it has none) and the short cut-off (1/m).
    """
    g = spec.grid()
    return float(spec.hurst), g["q_long"], g["q_roll"], g["q_short"]


def self_affine_moment_per_c0(spec: Any, k: float) -> float:
    """The isotropic moment μ_k of a self-affine spectrum per unit C₀, in closed form (m^(−2−k)).

    Parameters
    ----------
    spec : SelfAffineSpec
        The spectrum (:class:`~warptrunc.selfaffine.SelfAffineSpec`).
    k : float
        Order: 0 (⟨h²⟩), 2 (⟨‖∇h‖²⟩), 4 (⟨(∇²h)²⟩) (dimensionless).

    Returns
    -------
    float
        μ_k/C₀ = 2π ∫ q^(k+1) C(q)/C₀ dq (m^(−2−k)).

    Notes
    -----
    With ζ = q_s/q_r: μ_k/(2π C₀) = (q_r^(k+2) − q_L^(k+2))/(k + 2) + q_r^(k+2) (ζ^(k−2H) − 1)/(k − 2H)
    (q_r^(k+2) ln ζ when k = 2H).
    """
    H, q_l, q_r, q_s = self_affine_band(spec)
    flat = (q_r ** (k + 2) - q_l ** (k + 2)) / (k + 2)
    e = k - 2 * H
    zeta = q_s / q_r
    tail = math.log(zeta) if e == 0 else (zeta**e - 1.0) / e
    return 2 * math.pi * (flat + q_r ** (k + 2) * tail)


def self_affine_c0(spec: Any) -> float:
    """C₀ of the continuous spectrum that has the spec's rms height or rms slope.

    Parameters
    ----------
    spec : SelfAffineSpec
        The spectrum (:class:`~warptrunc.selfaffine.SelfAffineSpec`); its ``rms_slope`` when
        given, else its ``rms_height`` (1 µm when neither is).

    Returns
    -------
    float
        C₀ (m⁴): h′_rms²/μ₂ or h_rms²/μ₀ per unit C₀.

    Notes
    -----
    A map of the spec on its grid (:func:`~warptrunc.selfaffine.self_affine_surface`) has the
    discrete sums' C₀ instead (``Surface.params["C0_m4"]``), which the continuous one
    approaches as the modes fill the band.
    """
    if spec.rms_slope is not None:
        return spec.rms_slope**2 / self_affine_moment_per_c0(spec, 2)
    h = 1e-6 if spec.rms_height is None else spec.rms_height
    return h**2 / self_affine_moment_per_c0(spec, 0)


@dataclass(frozen=True, eq=False)
class IsotropicPSD:
    """An isotropic 2-D power spectral density C(q) on wavevectors q, Persson's normalisation.

    ⟨h²⟩ = 2π ∫ q C(q) dq (module docstring: the conventions, and how C relates to the
    frequency spectra of :mod:`warptrunc.spectra`). Made by :meth:`from_self_affine`,
    :meth:`from_wm` or :meth:`from_height_map`, or from any samples.

    Raises
    ------
    ValueError
        Fewer than two samples, q not strictly increasing and > 0, or C negative or not finite.
    """

    wavevector: np.ndarray
    """(k,) float64 wavevector magnitudes q, strictly increasing, > 0 (1/m)."""
    psd: np.ndarray
    """(k,) float64 C(q) ≥ 0 (m⁴)."""
    source: str = "samples"
    """What the spectrum was made from: ``"self-affine"``, ``"weierstrass-mandelbrot"``,
    ``"height map"`` or ``"samples"``."""
    interpolation: str = "power-law"
    """Between samples: ``"power-law"`` (log–log linear) or ``"linear"`` (module docstring)."""
    noise_wavevector: float = math.inf
    """For a spectrum estimated from a map, the q (1/m) above which the estimate is not the
    surface's (pixel, leakage, noise; :meth:`from_height_map`); inf for a model spectrum."""
    params: dict[str, Any] = field(default_factory=dict)
    """What it was made from (SI units): the spec's fields, the window, the pixel."""

    def __post_init__(self) -> None:
        q = np.array(self.wavevector, dtype=np.float64).reshape(-1)
        c = np.array(self.psd, dtype=np.float64).reshape(-1)
        if q.size < 2 or c.shape != q.shape:
            raise ValueError(
                f"wavevector and psd need the same length ≥ 2, got {q.size} and {c.size}"
            )
        if not (np.all(np.isfinite(q)) and q[0] > 0 and np.all(np.diff(q) > 0)):
            raise ValueError("wavevector must be finite, > 0 and strictly increasing (1/m)")
        if not np.all(np.isfinite(c) & (c >= 0)):
            raise ValueError("psd must be finite and ≥ 0 (m⁴)")
        if self.interpolation not in INTERPOLATIONS:
            raise ValueError(
                f"interpolation must be one of {INTERPOLATIONS}, got {self.interpolation!r}"
            )
        q.setflags(write=False)
        c.setflags(write=False)
        object.__setattr__(self, "wavevector", q)
        object.__setattr__(self, "psd", c)
        object.__setattr__(self, "noise_wavevector", float(self.noise_wavevector))

    # --- construction ------------------------------------------------------------------------

    @classmethod
    def from_self_affine(cls, source: Any = None, *, points_per_decade: int = 32) -> IsotropicPSD:
        """The self-affine spectrum of a spec or of a generated map, sampled on a logarithmic grid.

        Parameters
        ----------
        source : SelfAffineSpec or Surface, optional
            A :class:`~warptrunc.selfaffine.SelfAffineSpec` (C₀ of the continuous spectrum,
            :func:`self_affine_c0`), or a map of :func:`~warptrunc.selfaffine.self_affine_surface`
            (its own C₀, from the discrete sums: the spectrum the map has); default
            ``SelfAffineSpec()``.
        points_per_decade : int
            Samples per decade of q (count); q_L, q_r and q_s are always samples, so the
            interpolant is the spectrum itself and its moments are exact.

        Returns
        -------
        IsotropicPSD
            ``source="self-affine"``, ``params`` the spec's fields and C₀ (m⁴).
        """
        from ..selfaffine import SelfAffineSpec

        params = getattr(source, "params", None)
        if isinstance(params, dict):  # a generated map
            if params.get("generator") != "self-affine":
                raise ValueError(
                    f"a Surface must be a self-affine map, got generator {params.get('generator')!r}"
                )
            names = [f.name for f in dataclasses.fields(SelfAffineSpec)]
            spec = SelfAffineSpec(**{k: params[k] for k in names})
            spec = (
                spec.replace(L=tuple(spec.L), n=tuple(spec.n)) if isinstance(spec.L, list) else spec
            )
            c0 = float(params["C0_m4"])
        else:
            spec = SelfAffineSpec() if source is None else source
            c0 = self_affine_c0(spec)
        ppd = int(points_per_decade)
        if ppd < 1:
            raise ValueError(f"points_per_decade must be ≥ 1, got {points_per_decade!r}")
        H, q_l, q_r, q_s = self_affine_band(spec)
        parts = []
        for lo, hi in ((q_l, q_r), (q_r, q_s)):
            if hi > lo:
                n = max(2, math.ceil(math.log10(hi / lo) * ppd) + 1)
                parts.append(np.geomspace(lo, hi, n))
        q = np.unique(np.concatenate(parts))
        q[0], q[-1] = q_l, q_s
        c = np.where(q < q_r, c0, c0 * (np.maximum(q, q_r) / q_r) ** (-2 * (1 + H)))
        params = {**spec.to_dict(), "q_L": q_l, "q_r": q_r, "q_s": q_s, "c0": c0}
        return cls(q, c, "self-affine", "power-law", math.inf, params)

    @classmethod
    def from_wm(cls, source: Any, *, device: Any = None) -> IsotropicPSD:
        """The equivalent isotropic spectrum of a Weierstrass–Mandelbrot surface (Eq. 4).

        Parameters
        ----------
        source : WMSpec or Surface
            The WM parameters, or a surface made by :func:`warptrunc.wm_surface` (its
            ``params`` hold the terms' parameters and the height ``scale``). For a spec scaled
            to R_t the scale depends on the realisation's extremes, so the surface is
            generated (on ``device``) to read it; with G given it is Eq. 4's prefactor.
        device : str, optional
            Warp device for that generation; see :func:`warptrunc.resolve_device`.

        Returns
        -------
        IsotropicPSD
            ``source="weierstrass-mandelbrot"``: the samples q₀γ^(j/2), j = −1 … 2n_max + 1
            (the rings and the edges between them); ``params`` holds D, W_r, M, γ, n_max and
            the scale (m).

        Notes
        -----
        Eq. 4 as :func:`warptrunc.wm_surface` evaluates it is h = s Σ_{m,n} γ^((D−3)n)
        [cos α_mn − cos(k_mn·x + α_mn)] with ‖k_mn‖ = q_n = q₀γⁿ, q₀ = 2π/W_r, along the M
        directions πm/M, and s the height scale (m). Over the random phases its spectrum is a
        set of lines: ring n carries the variance σ_n² = M s² γ^(2(D−3)n)/2 on the circle
        ‖q‖ = q_n. Spreading each ring over its share of ln q, [q_n γ^(−1/2), q_n γ^(1/2)]
        (the continuous spectrum of the WM function, Berry & Lewis 1980), gives

            C(q) = M s² (q/q₀)^(−2H) / (4π q² ln γ),  H = 3 − D,

        on [q₀γ^(−1/2), q_{n_max} γ^(1/2)], zero outside: a self-affine spectrum with no
        roll-off. Its moments differ from the line sums Σ_n σ_n² q_n^k by the factor
        sinh(a_k)/a_k, a_k = (k − 2H) ln γ/2 (for γ = 1.5, H = 0.5: +0.7 % for ⟨h²⟩ and
        ⟨‖∇h‖²⟩, +6.3 % for ⟨(∇²h)²⟩); :func:`warptrunc.slope.wm_slope_statistics` gives the
        line sums themselves.

        References
        ----------
        Berry & Lewis (1980), Proc. R. Soc. Lond. A 370, 459, doi:10.1098/rspa.1980.0044.
        Yan & Komvopoulos (1998), J. Appl. Phys. 84, 3617, doi:10.1063/1.368536.
        """
        if isinstance(source, WMSpec):
            terms = source.terms()
            D, wr, m, gamma, n_max = terms.D, terms.Wr, terms.M, terms.gamma, terms.n_max
            if source.G is not None:
                scale = wr * (source.G / wr) ** (D - 3.0) * math.sqrt(math.log(gamma) / m)
            else:
                from ..wm import wm_surface

                scale = float(wm_surface(source, device=device).params["scale"])
        else:
            p = getattr(source, "params", None)
            if not isinstance(p, dict) or p.get("generator") != "weierstrass-mandelbrot":
                raise ValueError(
                    "source must be a WMSpec or a surface made by wm_surface, got "
                    f"{type(source).__name__}"
                )
            D, wr, m, gamma = float(p["D"]), float(p["Wr"]), int(p["M"]), float(p["gamma"])
            n_max, scale = int(p["n_max"]), float(p["scale"])
        q0 = 2 * math.pi / wr
        q = q0 * gamma ** (np.arange(-1, 2 * n_max + 2) / 2.0)
        H = 3.0 - D
        c = m * scale**2 * (q / q0) ** (-2 * H) / (4 * math.pi * q**2 * math.log(gamma))
        params = {"D": D, "Wr": wr, "M": m, "gamma": gamma, "n_max": n_max, "scale": scale}
        return cls(q, c, "weierstrass-mandelbrot", "power-law", math.inf, params)

    @classmethod
    def from_height_map(
        cls,
        surface: Any,
        pixel_size: float | tuple[float, float] | None = None,
        *,
        window: str = "hann",
    ) -> IsotropicPSD:
        """The radially averaged periodogram of a height map, with its noise floor.

        Parameters
        ----------
        surface : Surface or (ny, nx) ndarray
            The heights (m); an array needs ``pixel_size``.
        pixel_size : float or (float, float), optional
            dx or (dx, dy) (m), for an array.
        window : {"hann", "none"}
            Window of the periodogram (:func:`warptrunc.spectra.radial_psd`): ``"hann"`` for a
            map that is not periodic (a scan), ``"none"`` for a periodic one.

        Returns
        -------
        IsotropicPSD
            ``source="height map"``: q = 2πf at the annuli of :func:`~warptrunc.spectra.radial_psd`
            (Δq = 2π/max(L_x, L_y) up to the Nyquist wavevector π/max(dx, dy)) and
            C(q) = C_f(f)/(2π)², linear between samples, with one more sample half an annulus
            beyond each end (the end value) so that the integrals are the sums over the annuli; ``params`` holds the window, dx, dy (m) and the modes per
            annulus; ``noise_wavevector`` as in the Notes.

        Notes
        -----
        ``noise_wavevector`` is the smaller of π/(2·max(dx, dy)) (wavelengths of 4 pixels:
        below that the window's smoothing and the corners beyond the Nyquist circle distort the
        periodogram) and the start of the rise that the variance carried per half decade of q
        (sampled every 0.05 decade) makes up to the largest q, when it rises by more than a
        factor 2 there. Above the roll-off of a self-affine surface that variance falls as
        q^(−2H); where it rises, the spectrum is flatter than q⁻² (H < 0), which no self-affine
        surface gives and white noise (C flat), leakage and aliasing do. For a self-affine spectrum S plus white noise N the
        minimum lies where S = N/H, just below the crossing S = N.
        """
        from ..spectra import radial_psd
        from ..surface import Surface, from_heights

        if not isinstance(surface, Surface):
            if pixel_size is None:
                raise ValueError("a height array needs pixel_size (m)")
            dx, dy = (pixel_size, pixel_size) if np.isscalar(pixel_size) else pixel_size
            surface = from_heights(np.asarray(surface), float(dx), float(dy))
        est = radial_psd(surface, window=window)
        q = 2 * math.pi * est.frequency
        c = est.psd / (2 * math.pi) ** 2
        # each annulus spans ±Δq/2 about its sample: extend the ends by half an annulus at the
        # end values, so that the integrals are the sums over the annuli
        half = 0.5 * (q[1] - q[0]) if q.size > 1 else 0.5 * q[0]
        q = np.concatenate(([q[0] - half], q, [q[-1] + half]))
        c = np.concatenate((c[:1], c, c[-1:]))
        pixel = max(surface.dx, surface.dy)
        noise = _noise_wavevector(q, c, math.pi / (2 * pixel))
        params = {
            "window": window,
            "dx": float(surface.dx),
            "dy": float(surface.dy),
            "n_modes": est.n_modes.tolist(),
        }
        return cls(q, c, "height map", "linear", noise, params)

    # --- the interpolant and its integrals ---------------------------------------------------

    def at(self, q: Any) -> np.ndarray:
        """C at wavevectors ``q`` by the interpolant (zero outside the samples' range).

        Parameters
        ----------
        q : array_like
            Wavevectors (1/m).

        Returns
        -------
        ndarray
            C(q) (m⁴), the shape of ``q``.
        """
        qa = np.asarray(q, dtype=np.float64)
        x, c = self.wavevector, self.psd
        i = np.clip(np.searchsorted(x, qa, side="right") - 1, 0, x.size - 2)
        q0, q1, c0, c1 = x[i], x[i + 1], c[i], c[i + 1]
        t = (qa - q0) / (q1 - q0)
        pos = (c0 > 0) & (c1 > 0) & (self.interpolation == "power-law")
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            s = np.log(np.where(pos, c1, 1.0) / np.where(pos, c0, 1.0)) / np.log(q1 / q0)
            power = c0 * (qa / q0) ** s
        out = np.where(pos, power, c0 + t * (c1 - c0))
        return np.where((qa >= x[0]) & (qa <= x[-1]), out, 0.0)

    def cumulative_moment(self, k: float) -> np.ndarray:
        """2π ∫ q^(k+1) C(q) dq from the first sample up to each sample.

        Parameters
        ----------
        k : float
            Order: 0 gives ⟨h²⟩ (m²), 2 gives ⟨‖∇h‖²⟩ (dimensionless), 4 gives ⟨(∇²h)²⟩ (1/m²),
            from the wavevectors up to each q.

        Returns
        -------
        (k,) ndarray
            The cumulative moment at each sample (m^(2−k)), 0 at the first.
        """
        return np.concatenate(([0.0], np.cumsum(2 * math.pi * _segments(self, k))))

    def moment(self, k: float) -> float:
        """The isotropic moment μ_k = 2π ∫ q^(k+1) C(q) dq over the whole spectrum.

        Parameters
        ----------
        k : float
            Order (dimensionless); see :meth:`cumulative_moment`.

        Returns
        -------
        float
            μ_k (m^(2−k)).
        """
        return float(2 * math.pi * _segments(self, k).sum())

    @property
    def m0(self) -> float:
        """Nayak's m₀ = ⟨h²⟩ (m²)."""
        return self.moment(0)

    @property
    def m2(self) -> float:
        """Nayak's m₂ = ⟨(∂h/∂x)²⟩ = ⟨‖∇h‖²⟩/2, per direction (dimensionless)."""
        return self.moment(2) / 2

    @property
    def m4(self) -> float:
        """Nayak's m₄ = ⟨(∂²h/∂x²)²⟩ = 3⟨(∇²h)²⟩/8, per direction (1/m²)."""
        return 3 * self.moment(4) / 8

    @property
    def h_rms(self) -> float:
        """Rms height √⟨h²⟩ (m)."""
        return math.sqrt(self.moment(0))

    @property
    def slope_rms(self) -> float:
        """Rms slope h′_rms = √⟨‖∇h‖²⟩ (dimensionless)."""
        return math.sqrt(self.moment(2))

    @property
    def curvature_rms(self) -> float:
        """h″_rms = √⟨(∇²h)²⟩, the rms Laplacian, as :mod:`warptrunc.slope` defines it (1/m)."""
        return math.sqrt(self.moment(4))

    @property
    def magnification(self) -> float:
        """ζ = q_max/q₀, the range of scales the spectrum spans (dimensionless)."""
        return float(self.wavevector[-1] / self.wavevector[0])

    # --- derived spectra ---------------------------------------------------------------------

    def band(self, q_min: float | None = None, q_max: float | None = None) -> IsotropicPSD:
        """The spectrum restricted to [q_min, q_max] (the same interpolant, zero outside).

        Parameters
        ----------
        q_min, q_max : float, optional
            Bounds (1/m), inside the samples' range; default: the first and the last sample.

        Returns
        -------
        IsotropicPSD
            Samples at the bounds and those between; ``params`` adds ``band``.
        """
        x = self.wavevector
        lo = x[0] if q_min is None else float(q_min)
        hi = x[-1] if q_max is None else float(q_max)
        if not x[0] * (1 - 1e-12) <= lo < hi <= x[-1] * (1 + 1e-12):
            raise ValueError(
                f"need {x[0]:.6g} ≤ q_min < q_max ≤ {x[-1]:.6g} 1/m, got {lo!r}, {hi!r}"
            )
        lo, hi = max(lo, x[0]), min(hi, x[-1])
        q = np.concatenate(([lo], x[(x > lo) & (x < hi)], [hi]))
        return IsotropicPSD(
            q,
            self.at(q),
            self.source,
            self.interpolation,
            self.noise_wavevector,
            {**self.params, "band": [lo, hi]},
        )

    def refined(self, points_per_decade: int = 64) -> IsotropicPSD:
        """The same spectrum with samples added so that no interval spans more than
        1/``points_per_decade`` decade.

        Parameters
        ----------
        points_per_decade : int
            Largest spacing, as samples per decade (count).

        Returns
        -------
        IsotropicPSD
            The added samples lie on the interpolant, which they leave unchanged (and with it
            every integral).
        """
        ppd = int(points_per_decade)
        if ppd < 1:
            raise ValueError(f"points_per_decade must be ≥ 1, got {points_per_decade!r}")
        x = self.wavevector
        n = np.maximum(1, np.ceil(np.log10(x[1:] / x[:-1]) * ppd - 1e-9).astype(np.int64))
        seg = np.repeat(np.arange(n.size), n)
        start = np.repeat(np.cumsum(n) - n, n)
        frac = (np.arange(seg.size) - start) / n[seg]
        q = np.concatenate((x[seg] * (x[seg + 1] / x[seg]) ** frac, x[-1:]))
        c = self.at(q)
        c[np.concatenate((np.cumsum(n) - n, [q.size - 1]))] = self.psd  # the samples themselves
        return IsotropicPSD(
            q, c, self.source, self.interpolation, self.noise_wavevector, dict(self.params)
        )

    def to_dict(self) -> dict[str, Any]:
        """Columns ``wavevector_per_m``, ``psd_m4``, ``source`` and ``noise_wavevector_per_m``.

        Returns
        -------
        dict
            (k,) columns; the scalars repeated (``params`` is left out).
        """
        return columns(
            self,
            {
                "wavevector": "wavevector_per_m",
                "psd": "psd_m4",
                "noise_wavevector": "noise_wavevector_per_m",
            },
            skip=("params",),
        )


def _segments(psd: IsotropicPSD, k: float) -> np.ndarray:
    """∫ q^(k+1) C(q) dq over each interval of the interpolant ((k−1,) array).

    Power law between positive samples, C = C_i (q/q_i)^s: the integral is
    C_i q_i^(k+2) ln r · exprel(e ln r), e = k + 2 + s, r = q_(i+1)/q_i (exact, and stable
    when e ln r → 0). Linear C: 8-point Gauss–Legendre on each interval, exact for the
    polynomial q^(k+1)·C of an integer k ≤ 13.
    """
    q, c = psd.wavevector, psd.psd
    q0, q1, c0, c1 = q[:-1], q[1:], c[:-1], c[1:]
    lr = np.log(q1 / q0)
    pos = (c0 > 0) & (c1 > 0) & (psd.interpolation == "power-law")
    s = np.log(np.where(pos, c1, 1.0) / np.where(pos, c0, 1.0)) / lr
    power = c0 * q0 ** (k + 2) * lr * exprel((k + 2 + s) * lr)
    u, w = _GAUSS
    dq = (q1 - q0)[:, None]
    qq = q0[:, None] + dq * u[None, :]
    cc = c0[:, None] * (1 - u[None, :]) + c1[:, None] * u[None, :]
    linear = (qq ** (k + 1) * cc * w[None, :]).sum(axis=1) * dq[:, 0]
    return np.where(pos, power, linear)


def _noise_wavevector(q: np.ndarray, c: np.ndarray, q_pixel: float) -> float:
    """The noise floor of a periodogram (see :meth:`IsotropicPSD.from_height_map`) (1/m)."""
    dq = np.gradient(q)
    var = 2 * math.pi * q * c * dq  # variance carried by each annulus (m²)
    lq = np.log10(q)
    cum = np.concatenate(([0.0], np.cumsum(var)))
    centres = np.arange(lq[0] + 0.25, lq[-1] - 0.25 + 1e-9, 0.05)
    if centres.size < 3:
        return float(q_pixel)
    lo = np.searchsorted(lq, centres - 0.25)
    hi = np.searchsorted(lq, centres + 0.25)
    band = cum[hi] - cum[lo]  # variance per half decade around each centre
    # the rising run that ends at the top (5 % wiggles allowed), if it rises by more than 2×
    k = band.size - 1
    while k > 0 and band[k - 1] <= 1.05 * band[k]:
        k -= 1
    if band[-1] > 2.0 * band[k:].min():
        k += int(np.argmin(band[k:]))
        return float(min(10 ** centres[k], q_pixel))
    return float(q_pixel)
