# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Surface slope and curvature: the quantities that say whether a half-space contact solve holds.

The boundary-element solver of :mod:`warptrunc.contact` (and every elastic number built on it)
assumes small surface slopes. This module measures them:

- :func:`slope_statistics` of a height map, by finite differences at the map's own pixel:
  h′_rms = √⟨‖∇h‖²⟩ (forward differences along x and y, dimensionless) and
  h″_rms = √⟨(∇²h)²⟩ (the five-point Laplacian on the interior pixels, 1/m), with the rms slope
  per decade of wavelength from the map's periodogram;
- :func:`wm_slope_statistics` of a Weierstrass–Mandelbrot surface from its terms (the spectrum
  is known): each term A·cos(k·x + α) contributes A²k²/2 to ⟨‖∇h‖²⟩ and A²k⁴/2 to ⟨(∇²h)²⟩,
  i.e. the moments m₂ and m₄ of its line spectrum;
- :func:`check_slope`: a :class:`~warptrunc.plausibility.PlausibilityWarning` when h′_rms exceeds
  :data:`SMALL_SLOPE_LIMIT`.

h″_rms is the rms of the Laplacian; SurfaceTopography's ``rms_curvature`` reports the mean
curvature, half of it (for an isotropic surface).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .plausibility import PlausibilityWarning

__all__ = [
    "SMALL_SLOPE_LIMIT",
    "SlopeStatistics",
    "check_slope",
    "slope_record",
    "slope_statistics",
    "slope_warnings",
    "spectrum_slope",
    "wm_slope_statistics",
]

SMALL_SLOPE_LIMIT = 0.5
"""Largest h′_rms (dimensionless) at which the half-space (small-slope) contact solution is taken
as a model of the surface. The linear-elastic half-space solution linearises the boundary
condition in the slope: its errors grow with h′² (the contact area of a wedge of slope θ against
the exact solution by about θ²/2 in relative terms), and numerical studies of rough contact keep
h′_rms ≲ 0.5–1 (Müser et al., Tribol. Lett. 65, 118 (2017), doi:10.1007/s11249-017-0900-2, whose
common test problem fixes h′_rms = 1 at the finest scale; Pastewka & Robbins, PNAS 111, 3298
(2014), doi:10.1073/pnas.1320846111). Commands take another limit where the user sets one."""


@dataclass(frozen=True)
class SlopeStatistics:
    """Rms height, slope and curvature of a surface at a stated pixel (SI units)."""

    h_rms: float
    """Rms height about the mean, √⟨(h − h̄)²⟩ (m)."""
    slope_rms: float
    """h′_rms = √⟨‖∇h‖²⟩ over both axes (dimensionless)."""
    curvature_rms: float
    """h″_rms = √⟨(∇²h)²⟩ (1/m); NaN where the map has fewer than 3 pixels a side."""
    method: str
    """``"finite differences"`` (of a map, at its pixel) or ``"spectrum"`` (the moments of a
    known spectrum)."""
    dx: float
    """Pixel size along x the slope was measured at (m); for a spectrum, the grid's."""
    dy: float
    """Pixel size along y (m)."""
    decade_edges: tuple[float, ...] = ()
    """Wavelength edges of the decades, longest first (m): decade i spans
    [decade_edges[i + 1], decade_edges[i])."""
    slope_rms_per_decade: tuple[float, ...] = ()
    """Rms slope of the content of each decade of wavelength (dimensionless); their squares sum
    to ``slope_rms²`` (to the periodogram's resolution for a map)."""
    details: dict[str, Any] = field(default_factory=dict)
    """What the numbers were computed from (e.g. ``{"shortest_wavelength_m": ...}``)."""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready fields (SI units; the per-decade values as lists).

        Returns
        -------
        dict
            ``h_rms_m``, ``slope_rms``, ``curvature_rms_per_m``, ``method``, ``dx_m``, ``dy_m``,
            ``decade_edges_m``, ``slope_rms_per_decade`` and ``details``.
        """
        return {
            "h_rms_m": self.h_rms,
            "slope_rms": self.slope_rms,
            "curvature_rms_per_m": self.curvature_rms,
            "method": self.method,
            "dx_m": self.dx,
            "dy_m": self.dy,
            "decade_edges_m": list(self.decade_edges),
            "slope_rms_per_decade": list(self.slope_rms_per_decade),
            "details": dict(self.details),
        }


def _decades(longest: float, shortest: float) -> np.ndarray:
    """Decade edges of wavelength from 10^ceil(log10 longest) down past ``shortest`` (m)."""
    top = math.ceil(math.log10(longest) - 1e-12)
    bottom = math.floor(math.log10(shortest) + 1e-12)
    return 10.0 ** np.arange(top, bottom - 1, -1, dtype=np.float64)


def _per_decade(wavelength: np.ndarray, slope_sq: np.ndarray, edges: np.ndarray) -> tuple:
    """Rms slope of the content whose wavelengths fall in each decade of ``edges``."""
    out = []
    for hi, lo in itertools.pairwise(edges):
        sel = (wavelength < hi) & (wavelength >= lo)
        out.append(float(math.sqrt(float(slope_sq[sel].sum()))))
    return tuple(out)


def slope_statistics(surface: Any, *, per_decade: bool = True, device: Any = None) -> SlopeStatistics:
    """Rms height, slope and curvature of a height map by finite differences at its pixel.

    Parameters
    ----------
    surface : Surface
        The height map (m), ``z[iy, ix]`` with pixel sizes ``dx``, ``dy`` (m).
    per_decade : bool
        Also the rms slope per decade of wavelength, from the map's periodogram (one real FFT
        of the map, float64, on the host).
    device : str or warp.context.Device, optional
        Where the sums run (a Warp kernel, one thread per row): the surface's device by default.

    Returns
    -------
    SlopeStatistics
        ``method="finite differences"``.

    Notes
    -----
    h′_rms² = ⟨(Δ_x h/dx)²⟩ + ⟨(Δ_y h/dy)²⟩ with forward differences over the (ny, nx − 1) and
    (ny − 1, nx) pixel pairs; h″_rms² = ⟨(∇²h)²⟩ with the five-point Laplacian
    (h[i, j+1] − 2h[i, j] + h[i, j−1])/dx² + (h[i+1, j] − 2h[i, j] + h[i−1, j])/dy² on the
    interior pixels. The sums run in float64 on the surface's device, row by row
    (``warptrunc.kernels.slope``). The per-decade values come from the periodogram ∣ĥ(q)∣² of the
    map with its mean removed and a Hann window (so that the jump between opposite edges of a map
    that is not periodic does not leak into the short wavelengths), normalised by the window's
    mean square: the slope content of wavevector q is q²∣ĥ(q)∣²/N² (Parseval), summed over the q
    whose wavelength 2π/‖q‖ lies in each decade.
    """
    import warp as wp

    from ._support.device import resolve_device
    from .kernels import slope as _k

    dev = resolve_device(device if device is not None else surface.device)
    z = surface.device_heights(dev)
    dx, dy = float(surface.dx), float(surface.dy)
    ny, nx = surface.ny, surface.nx
    sums = wp.zeros((ny, 5), dtype=wp.float64, device=dev)
    wp.launch(_k.slope_sums_kernel, dim=ny, inputs=[z, dx, dy], outputs=[sums], device=dev)
    h1, h2, gx, gy, lap = (float(v) for v in sums.numpy().sum(axis=0))  # sync point
    n = nx * ny
    sq = max(h2 - h1 * h1 / n, 0.0)  # Σ (h − h̄)², about the first height r
    mean = float(np.float64(z[0:1, 0:1].numpy()[0, 0])) + h1 / n
    n_lap = max(ny - 2, 0) * max(nx - 2, 0)
    slope_sq = (gx / (ny * (nx - 1)) if nx > 1 else 0.0) + (gy / ((ny - 1) * nx) if ny > 1 else 0.0)
    edges: tuple = ()
    decades: tuple = ()
    if per_decade and nx > 1 and ny > 1:
        h = np.asarray(surface.heights, dtype=np.float64) - mean
        wy, wx = np.hanning(ny + 2)[1:-1], np.hanning(nx + 2)[1:-1]  # no zero weights
        window = wy[:, None] * wx[None, :]
        spec = np.fft.rfft2(h * window)
        qx = 2 * np.pi * np.fft.rfftfreq(nx, dx)
        qy = 2 * np.pi * np.fft.fftfreq(ny, dy)
        q2 = qx[None, :] ** 2 + qy[:, None] ** 2
        power = np.abs(spec) ** 2 / (nx * ny) ** 2 / float(np.mean(window**2))
        power[:, 1:] *= 2.0  # the half spectrum stands for both halves ...
        if nx % 2 == 0:
            power[:, -1] /= 2.0  # ... except the Nyquist column, its own mirror
        with np.errstate(divide="ignore"):
            wavelength = np.where(q2 > 0, 2 * np.pi / np.sqrt(q2), np.inf)
        e = _decades(max(nx * dx, ny * dy), min(wavelength[np.isfinite(wavelength)]))
        edges, decades = tuple(float(v) for v in e), _per_decade(wavelength, q2 * power, e)
    return SlopeStatistics(
        h_rms=math.sqrt(sq / n),
        slope_rms=math.sqrt(slope_sq),
        curvature_rms=math.sqrt(lap / n_lap) if n_lap else math.nan,
        method="finite differences",
        dx=dx,
        dy=dy,
        decade_edges=edges,
        slope_rms_per_decade=decades,
        details={"nx": nx, "ny": ny},
    )


def wm_slope_statistics(terms: Any, scale: float) -> SlopeStatistics:
    """Rms height, slope and curvature of a WM surface from its terms (its line spectrum).

    Parameters
    ----------
    terms : WMTerms
        The surface's terms (:func:`warptrunc.wm.wm_spec`): wavevectors ``kx``, ``ky`` (rad/m)
        and weights ``w`` (dimensionless).
    scale : float
        The height scale (m) of the surface (``Surface.params["scale"]``: heights are
        scale·S with S the unscaled sum).

    Returns
    -------
    SlopeStatistics
        ``method="spectrum"``, at the grid's pixel ``terms.dx``, ``terms.dy``.

    Notes
    -----
    The surface is h = scale·Σ_t w_t[cos α_t − cos(k_t·x + α_t)]; over an area holding many
    periods of every term, ⟨h²⟩ − ⟨h⟩² → Σ_t A_t²/2, ⟨‖∇h‖²⟩ → Σ_t A_t²‖k_t‖²/2 and
    ⟨(∇²h)²⟩ → Σ_t A_t²‖k_t‖⁴/2 with A_t = scale·w_t (cross terms average out for distinct
    wavevectors). A finite map holds the longest terms for a few periods only, so its finite
    differences (:func:`slope_statistics`) differ from these by the sampling of those terms.
    """
    a2 = (scale * np.asarray(terms.w, dtype=np.float64)) ** 2
    k2 = np.asarray(terms.kx, dtype=np.float64) ** 2 + np.asarray(terms.ky, dtype=np.float64) ** 2
    wavelength = 2 * np.pi / np.sqrt(k2)
    e = _decades(float(wavelength.max()), float(wavelength.min()))
    return SlopeStatistics(
        h_rms=math.sqrt(float(a2.sum()) / 2),
        slope_rms=math.sqrt(float((a2 * k2).sum()) / 2),
        curvature_rms=math.sqrt(float((a2 * k2**2).sum()) / 2),
        method="spectrum",
        dx=float(terms.dx),
        dy=float(terms.dy),
        decade_edges=tuple(float(v) for v in e),
        slope_rms_per_decade=_per_decade(wavelength, a2 * k2 / 2, e),
        details={"shortest_wavelength_m": float(wavelength.min()), "n_terms": int(a2.size)},
    )


def check_slope(stats: SlopeStatistics, limit: float = SMALL_SLOPE_LIMIT) -> list[PlausibilityWarning]:
    """A ``"slope"`` warning when h′_rms exceeds the small-slope range of the half-space solver.

    Parameters
    ----------
    stats : SlopeStatistics
        The surface's slope (:func:`slope_statistics` or :func:`wm_slope_statistics`).
    limit : float
        Largest h′_rms taken as inside the range (dimensionless); default
        :data:`SMALL_SLOPE_LIMIT`.

    Returns
    -------
    list of PlausibilityWarning
        Empty, or one warning with ``slope_rms``, ``limit``, ``dx_m`` and ``method``.
    """
    if not stats.slope_rms > limit:
        return []
    return [
        PlausibilityWarning(
            "slope",
            f"h′_rms = {stats.slope_rms:.3g} at the {stats.dx * 1e9:.4g} nm pixel exceeds the "
            f"small-slope range of the half-space contact solution ({limit:g}): the elastic "
            "numbers (contact area, stiffness) are not a physical model of this surface at this "
            "pixel",
            {"slope_rms": stats.slope_rms, "limit": limit, "dx_m": stats.dx, "method": stats.method},
        )
    ]


def spectrum_slope(params: dict[str, Any]) -> SlopeStatistics | None:
    """The slope statistics of a generated surface from its known spectrum, or None.

    Parameters
    ----------
    params : dict
        A surface's ``params`` (or its ``to_dict()``): a WM surface's (``generator =
        "weierstrass-mandelbrot"``, its fields and ``scale``, m) or a self-affine one's
        (``generator = "self-affine"``, ``slope_rms``, ``curvature_rms_per_m``, ``h_rms_m``).

    Returns
    -------
    SlopeStatistics or None
        ``method="spectrum"``: for WM the moments of its terms (:func:`wm_slope_statistics`), for
        a self-affine map the discrete sums of its spectrum; None for any other surface (a map
        read from a file has no known spectrum).
    """
    gen = params.get("generator")
    if gen == "weierstrass-mandelbrot" and params.get("scale") is not None:
        from .wm_params import WMSpec

        nx, ny = params.get("nx"), params.get("ny")
        lx = params.get("Lx", params.get("lx_m"))
        ly = params.get("Ly", params.get("ly_m"))
        spec = WMSpec(D=params["D"], Wr=params["Wr"], L=(lx, ly), n=(nx, ny), M=params["M"],
                      gamma=params["gamma"], Wc=params["Wc"], cutoff=params["cutoff"],
                      seed=params["seed"], Rt=params.get("Rt"), G=params.get("G"),
                      Rt_pixel=params.get("Rt_pixel"))  # fmt: skip
        return wm_slope_statistics(spec.terms(), float(params["scale"]))
    if gen == "self-affine":
        dx = float(params.get("dx_m", math.nan))
        return SlopeStatistics(
            h_rms=float(params["h_rms_m"]),
            slope_rms=float(params["slope_rms"]),
            curvature_rms=float(params.get("curvature_rms_per_m", math.nan)),
            method="spectrum",
            dx=dx,
            dy=float(params.get("dy_m", dx)),
            details={"shortest_wavelength_m": 2 * math.pi / float(params["q_short"])},
        )
    return None


def slope_record(surface: Any = None, *, params: dict[str, Any] | None = None,
                 limit: float = SMALL_SLOPE_LIMIT) -> dict[str, Any]:  # fmt: skip
    """The slope regime of a surface as an output records it, at the pixel the computation used.

    Parameters
    ----------
    surface : Surface, optional
        The map the computation used: its finite differences are measured
        (:func:`slope_statistics`, no per-decade values). None for a streamed map, which is never
        held whole.
    params : dict, optional
        The surface's metadata (``Surface.to_dict()``; for a streamed map the only record): its
        known spectrum, where it has one (:func:`spectrum_slope`). Default: ``surface``'s.
    limit : float
        The small-slope limit the record and its warning use (dimensionless).

    Returns
    -------
    dict
        ``slope_rms`` and ``curvature_rms_per_m`` (the finite differences where the map is there,
        else the spectrum's), ``method`` (which), ``finite_differences`` and ``spectrum`` (each
        :meth:`SlopeStatistics.to_dict` or None), ``limit`` and ``small_slope`` (h′_rms ≤ limit).
    """
    params = dict(params if params is not None else surface.to_dict() if surface is not None else {})
    fd = slope_statistics(surface, per_decade=False) if surface is not None else None
    sp = spectrum_slope({**params, **getattr(surface, "params", {})})
    main = fd if fd is not None else sp
    return {
        "slope_rms": None if main is None else main.slope_rms,
        "curvature_rms_per_m": None if main is None else main.curvature_rms,
        "method": None if main is None else main.method,
        "finite_differences": None if fd is None else fd.to_dict(),
        "spectrum": None if sp is None else sp.to_dict(),
        "limit": limit,
        "small_slope": None if main is None else bool(main.slope_rms <= limit),
    }


def slope_warnings(record: dict[str, Any]) -> list[PlausibilityWarning]:
    """The ``"slope"`` warning of a :func:`slope_record`, where h′_rms exceeds its limit.

    Parameters
    ----------
    record : dict
        A :func:`slope_record`.

    Returns
    -------
    list of PlausibilityWarning
        Empty or one warning (:func:`check_slope`).
    """
    if record.get("slope_rms") is None:
        return []
    src = record["finite_differences"] or record["spectrum"]
    stats = SlopeStatistics(h_rms=src["h_rms_m"], slope_rms=src["slope_rms"],
                            curvature_rms=src["curvature_rms_per_m"], method=src["method"],
                            dx=src["dx_m"], dy=src["dy_m"])  # fmt: skip
    return check_slope(stats, record["limit"])
