# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Fractal dimension D of a height map by the paper's four methods (Table 1, Table 3, Fig. 10).

=========  ===================  ============================================  ================
method     name in the paper    measure M(r) at scale r                       D from the slope
=========  ===================  ============================================  ================
``"tri"``  triangulation D_tri  triangular-prism area / projected area        D = 2 − slope
``"box"``  box counting D_box   number of cubes of side ε crossed             D = −slope
``"vs"``   vert. sections D_vs  profile structure function ⟨Δz(τ)²⟩           D = 3 − slope/2
``"sp"``   power spectrum D_sp  variance per logarithmic frequency band       D = 3 + slope/2
=========  ===================  ============================================  ================

The slope is the least-squares slope of log₁₀ M against log₁₀ r over the *fit range*, a
subrange of the evaluated *scales*; both are user-settable and are returned in
:class:`FractalFit` with r² of the fit. The per-box and per-pixel passes run in Warp kernels
(``warptrunc.kernels.fractal``); the spectrum runs where the surface lives: CuPy's cuFFT on a
CUDA surface when CuPy is installed, else NumPy (see :mod:`warptrunc.descriptors`).

Triangulation and box counting need heights and lengths in one unit, and the result depends
on how heights compare with lengths. ``height_scaling`` chooses the convention
(:data:`HEIGHT_SCALINGS`): ``"cube"`` (default) maps the height range onto the lateral
extent first, as Gwyddion does, so D is independent of units and amplitude; ``"si"`` uses
metres as measured, so D approaches 3 − H only where the surface is rough at the scale of the
boxes and drifts to 2 on smooth, gently sloped surfaces (a 1 µm-rms map over 1 mm gives
D ≈ 2.0 whatever its H). Every :class:`FractalFit` of these two methods records the convention
in ``options["height_scaling"]``. The calibration loop of Fig. 4 matches D of simulated and
measured surfaces with the *same* method and options.

Invariances (tested in ``tests/test_fractal.py``):

=====================  =====  =====  =====  =====
transformation          tri    box    vs     sp
=====================  =====  =====  =====  =====
z + constant            yes    yes¹   yes    yes
a·z (a > 0)             cube³  cube³  yes    yes
transposition (z.T)     yes    yes    yes²   yes
=====================  =====  =====  =====  =====

¹ cubes are stacked from the lowest point, so a shift changes only float32 rounding;
² with ``axis="both"`` (x and y profiles pooled);
³ yes with ``height_scaling="cube"`` (default), no with ``"si"``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import warp as wp

from ._device import resolve_device
from ._validate import check_range
from .descriptors import band_variance, roll_off_wavelength
from .kernels import fractal as _k
from .surface import Surface
from .truncation import _where, surface_range

__all__ = [
    "DEFAULT_HEIGHT_SCALING",
    "HEIGHT_SCALINGS",
    "METHODS",
    "FractalFit",
    "box_counting",
    "fractal_dimension",
    "fractal_dimensions",
    "power_spectrum",
    "self_affine_surface",
    "triangular_prism",
    "vertical_sections",
]

METHODS = ("tri", "box", "vs", "sp")
"""Method keys, in the order of Table 1."""

HEIGHT_SCALINGS = ("cube", "si")
"""Height conventions of the triangulation and cube-counting methods (``height_scaling=``):

``"cube"``
    Gwyddion's convention: before the prisms or cubes are built, the heights are mapped onto
    the lateral extent — z′ = (z − min z)·(N − 1)·h/(max z − min z), with h = √(dx·dy) and
    N = max(nx, ny) pixels per side — so the map fills a cube and D does not depend on the
    height unit or amplitude (Gwyddion ``libprocess/fractals.c``,
    ``gwy_data_field_fractal_triangulation`` scales height differences by
    2^k/(max − min) on a (2^k + 1)² grid in pixel units, and
    ``gwy_data_field_fractal_cubecounting`` cuts the height range into as many levels as there
    are boxes per side).
``"si"``
    Heights and lengths as measured, in metres: D then depends on the height amplitude
    relative to the pixel size (it drifts to 2 on gently sloped maps).
"""

DEFAULT_HEIGHT_SCALING = "cube"
"""Default of ``height_scaling`` (see the README's evidence table: it recovers 3 − H of
self-affine surfaces far better than ``"si"``)."""


def _check_scaling(height_scaling: str) -> str:
    if height_scaling not in HEIGHT_SCALINGS:
        raise ValueError(
            f"height_scaling must be one of {HEIGHT_SCALINGS}, got {height_scaling!r}"
        )
    return height_scaling


def cube_height_factor(surface: Surface, z_min: float | None = None, z_max: float | None = None) -> float:
    """Factor of the ``"cube"`` convention: (N − 1)·√(dx·dy)/(max z − min z) (dimensionless).

    Heights times this factor span the map's lateral extent (N = max(nx, ny)); 1 for a flat map.
    ``z_min``, ``z_max`` (m) default to the extremes of ``surface.heights``.
    """
    if z_min is None or z_max is None:
        z = surface.heights
        z_min, z_max = float(np.min(z)), float(np.max(z))
    rng = float(z_max) - float(z_min)
    if not rng > 0:
        return 1.0
    return (max(surface.nx, surface.ny) - 1) * math.sqrt(surface.dx * surface.dy) / rng


def _scaled_upload(zd: wp.array, surface: Surface, height_scaling: str) -> wp.array:
    """The device heights for a method: as measured ("si") or mapped into the cube (on the
    device, from the surface's recorded or reduced extremes)."""
    if height_scaling == "si":
        return zd
    lo, hi = surface_range(surface, zd.flatten(), zd.device)
    out = wp.empty(zd.shape, dtype=wp.float32, device=zd.device)
    wp.launch(
        _k.cube_scale_kernel, dim=zd.shape,
        inputs=[zd, float(lo), cube_height_factor(surface, lo, hi)], outputs=[out],
        device=zd.device,
    )  # fmt: skip
    return out


@dataclass(frozen=True, eq=False)
class FractalFit:
    """A fractal dimension from a log-log fit of a measure against a scale."""

    method: str
    """``"tri"``, ``"box"``, ``"vs"`` or ``"sp"``."""
    D: float
    """Fractal dimension (dimensionless, 2 ≤ D ≤ 3 for a surface; not clipped)."""
    r2: float
    """Coefficient of determination r² of the log-log fit (dimensionless)."""
    slope: float
    """Slope of log₁₀ measure against log₁₀ scale (dimensionless)."""
    intercept: float
    """Intercept of the fit (log₁₀ of the measure's unit)."""
    scale: np.ndarray
    """(k,) float64 scales r: box side, lag or wavelength 1/f (m)."""
    measure: np.ndarray
    """(k,) float64 measure M(r): area ratio (dimensionless), cube count, structure function
    (m²) or band variance (m²)."""
    fitted: np.ndarray
    """(k,) bool, True for the scales inside the fit range."""
    fit_range: tuple[float, float]
    """(r_min, r_max) of the fit (m)."""
    options: dict[str, Any] = field(default_factory=dict)
    """Method options used (profile method, window, ...), JSON-serialisable."""

    @property
    def n_fitted(self) -> int:
        """Number of scales in the fit."""
        return int(np.count_nonzero(self.fitted))

    def to_dict(self) -> dict[str, Any]:
        """Columns ``scale_m``, ``measure``, ``fitted`` and the scalars of the fit."""
        return {
            "method": self.method,
            "D": self.D,
            "r2": self.r2,
            "slope": self.slope,
            "intercept": self.intercept,
            "fit_min_m": self.fit_range[0],
            "fit_max_m": self.fit_range[1],
            "scale_m": self.scale,
            "measure": self.measure,
            "fitted": self.fitted,
        }


# --- shared helpers ------------------------------------------------------------------------------


def _upload(surface: Surface, device: wp.DeviceLike) -> wp.array:
    if not isinstance(surface, Surface):
        raise TypeError(
            f"surface must be a warptrunc.Surface, got {type(surface).__name__}; wrap a height "
            "array with warptrunc.from_heights(z, dx)"
        )
    # where a device surface lives unless told otherwise; cached per device on the surface
    return surface.device_heights(resolve_device(_where(surface, device)))


def _default_box_sizes(surface: Surface) -> np.ndarray:
    smax = max(4, (min(surface.nx, surface.ny) - 1) // 8)
    return 2 ** np.arange(int(math.log2(smax)) + 1)


def _check_sizes(name: str, sizes: Sequence[int] | None, surface: Surface, default) -> np.ndarray:
    if sizes is None:
        sizes = default(surface)
    s = np.unique(np.asarray(sizes))
    nmin = min(surface.nx, surface.ny)
    if s.ndim != 1 or s.size < 2 or not np.all(s == np.round(s)):
        raise ValueError(f"{name} must be at least 2 distinct integers, got {sizes!r}")
    s = s.astype(np.int64)
    if s[0] < 1 or s[-1] > nmin - 1:
        raise ValueError(
            f"{name} must lie in [1, {nmin - 1}] pixels for a map of shape "
            f"{surface.shape}, got {sizes!r}"
        )
    return s


def _fit(
    method: str,
    scale: np.ndarray,
    measure: np.ndarray,
    fit_range: tuple[float, float] | None,
    d_of_slope,
    options: dict[str, Any],
) -> FractalFit:
    scale = np.asarray(scale, dtype=np.float64)
    measure = np.asarray(measure, dtype=np.float64)
    if fit_range is None:
        lo, hi = float(scale.min()), float(scale.max())
    else:
        if len(fit_range) != 2:
            raise ValueError(f"fit_range must be (min, max) in m, got {fit_range!r}")
        lo = check_range("fit_range[0]", fit_range[0], 0.0, lo_open=False, unit="m")
        hi = check_range("fit_range[1]", fit_range[1], lo, lo_open=False, unit="m")
    rel = 1e-9
    fitted = (scale >= lo * (1 - rel)) & (scale <= hi * (1 + rel)) & (measure > 0)
    if np.count_nonzero(fitted) < 2:
        raise ValueError(
            f"{method}: fit_range ({lo:.4g}, {hi:.4g}) m holds {int(np.count_nonzero(fitted))} "
            f"usable scale(s); the evaluated scales span [{scale.min():.4g}, {scale.max():.4g}] m"
        )
    x = np.log10(scale[fitted])
    y = np.log10(measure[fitted])
    slope, intercept = np.polyfit(x, y, 1)
    res = y - (slope * x + intercept)
    sst = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - float(np.sum(res**2)) / sst if sst > 0 else 1.0
    return FractalFit(
        method=method,
        D=float(d_of_slope(slope)),
        r2=r2,
        slope=float(slope),
        intercept=float(intercept),
        scale=scale,
        measure=measure,
        fitted=fitted,
        fit_range=(lo, hi),
        options=options,
    )


def _chunks(ncx: int, s: int) -> tuple[int, int]:
    chunk = max(1, 32 // s)
    return chunk, (ncx + chunk - 1) // chunk


# --- the four methods ---------------------------------------------------------------------------


def triangular_prism(
    surface: Surface,
    *,
    box_sizes: Sequence[int] | None = None,
    fit_range: tuple[float, float] | None = None,
    height_scaling: str = DEFAULT_HEIGHT_SCALING,
    device: wp.DeviceLike = None,
) -> FractalFit:
    """D_tri by the triangular prism method (Clarke 1986).

    Parameters
    ----------
    surface : Surface
        Height map (m).
    box_sizes : sequence of int, optional
        Cell sides s (pixels) to evaluate. Defaults to the powers of two from 1 to
        max(4, (min(nx, ny) − 1) // 8).
    fit_range : (float, float), optional
        Range of cell sides r = s·√(dx·dy) used in the fit (m). Defaults to all evaluated sizes.
    height_scaling : {"cube", "si"}
        ``"cube"`` (default): heights mapped onto the lateral extent first, as Gwyddion does
        (see :data:`HEIGHT_SCALINGS`); ``"si"``: heights in metres as measured.
    device : str, optional
        Warp device.

    Returns
    -------
    FractalFit
        ``scale`` = r (m), ``measure`` = A(r)/A_proj, the prism area over the projected area of
        the cells (dimensionless, ≥ 1).

    Notes
    -----
    The map is divided into cells of s × s pixels whose corners are grid points; each cell is
    covered by four triangles joining two neighbouring corners to an apex above the cell centre
    at the mean height of the four corners. With A(r) ∝ r^(2 − D), D = 2 − slope of
    log A(r) against log r. With ``height_scaling="si"`` heights and lengths are in metres,
    so D depends on the height amplitude (see the module docstring); with ``"cube"`` it does
    not. Invariant to z + c and to transposition.

    References
    ----------
    K. C. Clarke, Computation of the fractal dimension of topographic surfaces using the
    triangular prism surface area method, Comput. Geosci. 12 (1986) 713–722,
    doi:10.1016/0098-3004(86)90047-6.
    """
    zd = _upload(surface, device)
    return _tri(zd, surface, box_sizes, fit_range, height_scaling)


def _tri(zd, surface, box_sizes, fit_range, height_scaling=DEFAULT_HEIGHT_SCALING) -> FractalFit:
    sizes = _check_sizes("box_sizes", box_sizes, surface, _default_box_sizes)
    zd = _scaled_upload(zd, surface, _check_scaling(height_scaling))
    ratio = np.empty(sizes.size)
    for i, s in enumerate(sizes):
        ncy, ncx = (surface.ny - 1) // s, (surface.nx - 1) // s
        chunk, nch = _chunks(ncx, int(s))
        out = wp.zeros((ncy, nch), dtype=wp.float64, device=zd.device)
        wp.launch(
            _k.prism_area_kernel,
            dim=(ncy, nch),
            inputs=[zd, int(s), s * surface.dx, s * surface.dy, chunk],
            outputs=[out],
            device=zd.device,
        )
        area = float(out.numpy().sum())  # sync point
        ratio[i] = area / (ncx * s * surface.dx * ncy * s * surface.dy)
    h = math.sqrt(surface.dx * surface.dy)
    return _fit(
        "tri",
        sizes * h,
        ratio,
        fit_range,
        lambda k: 2.0 - k,
        {"box_sizes": sizes.tolist(), "height_scaling": height_scaling},
    )


def box_counting(
    surface: Surface,
    *,
    box_sizes: Sequence[int] | None = None,
    fit_range: tuple[float, float] | None = None,
    height_scaling: str = DEFAULT_HEIGHT_SCALING,
    device: wp.DeviceLike = None,
) -> FractalFit:
    """D_box by cube counting.

    Parameters
    ----------
    surface : Surface
        Height map (m).
    box_sizes : sequence of int, optional
        Cube sides s (pixels) to evaluate; default as :func:`triangular_prism`.
    fit_range : (float, float), optional
        Range of cube sides ε = s·√(dx·dy) used in the fit (m). Defaults to all.
    height_scaling : {"cube", "si"}
        ``"cube"`` (default): heights mapped onto the lateral extent first, so that the height
        range holds as many cubes as a side holds boxes (Gwyddion's cube counting; see
        :data:`HEIGHT_SCALINGS`); ``"si"``: heights in metres as measured.
    device : str, optional
        Warp device.

    Returns
    -------
    FractalFit
        ``scale`` = ε (m), ``measure`` = N(ε), the number of cubes crossed, scaled to the whole
        map when the cells do not tile it exactly (dimensionless).

    Notes
    -----
    Space is tiled by cubes of lateral side s pixels and height ε = s·√(dx·dy), stacked from the
    lowest point of the map. In each cell (the (s + 1)² grid points of :func:`triangular_prism`)
    the surface crosses ⌊(max − z_min)/ε⌋ − ⌊(min − z_min)/ε⌋ + 1 cubes. With N(ε) ∝ ε^−D,
    D = −slope of log N against log ε. Invariant to z + c (up to float32 rounding) and to
    transposition; to a height scale factor only with ``height_scaling="cube"``.

    References
    ----------
    B. B. Mandelbrot, The Fractal Geometry of Nature, Freeman, 1982; N. Sarkar and
    B. B. Chaudhuri, An efficient differential box-counting approach to compute fractal
    dimension of image, IEEE Trans. Syst. Man Cybern. 24 (1994) 115–120, doi:10.1109/21.259692.
    """
    zd = _upload(surface, device)
    return _box(zd, surface, box_sizes, fit_range, height_scaling)


def _box(zd, surface, box_sizes, fit_range, height_scaling=DEFAULT_HEIGHT_SCALING) -> FractalFit:
    sizes = _check_sizes("box_sizes", box_sizes, surface, _default_box_sizes)
    h = math.sqrt(surface.dx * surface.dy)
    z0 = surface_range(surface, zd.flatten(), zd.device)[0]
    if _check_scaling(height_scaling) == "cube":
        zd, z0 = _scaled_upload(zd, surface, height_scaling), 0.0
    counts = np.empty(sizes.size)
    for i, s in enumerate(sizes):
        ncy, ncx = (surface.ny - 1) // s, (surface.nx - 1) // s
        chunk, nch = _chunks(ncx, int(s))
        out = wp.zeros((ncy, nch), dtype=wp.int64, device=zd.device)
        wp.launch(
            _k.box_count_kernel,
            dim=(ncy, nch),
            inputs=[zd, int(s), float(s * h), z0, chunk],
            outputs=[out],
            device=zd.device,
        )
        n = int(out.numpy().sum())  # sync point
        counts[i] = n * ((surface.nx - 1) * (surface.ny - 1)) / (ncx * s * ncy * s)
    return _fit(
        "box", sizes * h, counts, fit_range, lambda k: -k,
        {"box_sizes": sizes.tolist(), "height_scaling": height_scaling},
    )  # fmt: skip


def _default_lags(surface: Surface) -> np.ndarray:
    tmax = max(4, (min(surface.nx, surface.ny) - 1) // 8)
    return np.unique(np.round(np.geomspace(1, tmax, 16)).astype(np.int64))


def vertical_sections(
    surface: Surface,
    *,
    lags: Sequence[int] | None = None,
    fit_range: tuple[float, float] | None = None,
    axis: str = "both",
    device: wp.DeviceLike = None,
) -> FractalFit:
    """D_vs from vertical sections: profile dimension + 1, profiles by their structure function.

    Parameters
    ----------
    surface : Surface
        Height map (m).
    lags : sequence of int, optional
        Lags τ (pixels). Defaults to 16 logarithmically spaced integers from 1 to
        max(4, (min(nx, ny) − 1) // 8).
    fit_range : (float, float), optional
        Range of lag lengths τ·dx (τ·dy for y profiles) used in the fit (m). Defaults to
        lags up to W_r/4 (W_r from :func:`warptrunc.descriptors.roll_off_wavelength`), where
        the structure function of a surface with a roll-off still follows its power law, and
        at least the four smallest lags.
    axis : {"both", "x", "y"}
        Profiles along x (rows), along y (columns), or both pooled.
    device : str, optional
        Warp device.

    Returns
    -------
    FractalFit
        ``scale`` = lag length (m), ``measure`` = V(τ) = ⟨(z(p + τ) − z(p))²⟩ (m²), averaged over
        all pairs of all profiles. With ``axis="both"`` and dx ≠ dy the x and y points are
        concatenated (x first) and fitted together.

    Notes
    -----
    The surface is cut by vertical planes along its rows and columns; each section is a
    self-affine profile with V(τ) ∝ τ^(2H), whose fractal (profile) dimension is
    D_p = 2 − H (the variogram / structure-function method). The surface dimension is
    D_vs = D_p + 1 = 3 − slope/2. Invariant to z + c, to a height scale factor, and (with
    ``axis="both"``) to transposition.

    References
    ----------
    B. B. Mandelbrot, The Fractal Geometry of Nature, Freeman, 1982; T. Gneiting, H. Ševčíková
    and D. B. Percival, Estimators of fractal dimension: assessing the roughness of time series
    and spatial data, Stat. Sci. 27 (2012) 247–277, doi:10.1214/11-STS370.
    """
    zd = _upload(surface, device)
    return _vs(zd, surface, lags, fit_range, axis)


def _vs(zd, surface, lags, fit_range, axis) -> FractalFit:
    if axis not in ("both", "x", "y"):
        raise ValueError(f"axis must be 'both', 'x' or 'y', got {axis!r}")
    taus = _check_sizes("lags", lags, surface, _default_lags)
    lag_d = wp.array(taus.astype(np.int32), dtype=wp.int32, device=zd.device)
    ny, nx = surface.ny, surface.nx
    parts = []
    # GPU: one thread per column (coalesced); CPU: one per row (contiguous, threads run serially)
    kernel, width = (
        (_k.structure_function_rows_kernel, ny)
        if zd.device.is_cpu
        else (_k.structure_function_kernel, nx)
    )
    for ax in ("x", "y") if axis == "both" else (axis,):
        out = wp.zeros((taus.size, width), dtype=wp.float64, device=zd.device)
        wp.launch(
            kernel,
            dim=(taus.size, width),
            inputs=[zd, lag_d, 1 if ax == "x" else 0],
            outputs=[out],
            device=zd.device,
        )
        sums = out.numpy().sum(axis=1)  # sync point
        pairs = ny * (nx - taus) if ax == "x" else nx * (ny - taus)
        h = surface.dx if ax == "x" else surface.dy
        parts.append((taus * h, sums, pairs.astype(np.float64)))
    if len(parts) == 2 and math.isclose(surface.dx, surface.dy, rel_tol=1e-12):
        scale = parts[0][0]
        v = (parts[0][1] + parts[1][1]) / (parts[0][2] + parts[1][2])
    else:
        scale = np.concatenate([p[0] for p in parts])
        v = np.concatenate([p[1] / p[2] for p in parts])
    if fit_range is None:
        wr, _ = roll_off_wavelength(surface)
        fourth = float(np.sort(scale)[min(3, scale.size - 1)])
        fit_range = (0.0, max(wr / 4.0, fourth))
    return _fit(
        "vs",
        scale,
        v,
        fit_range,
        lambda k: 3.0 - 0.5 * k,
        {"lags": taus.tolist(), "axis": axis, "profile_method": "structure function"},
    )


def power_spectrum(
    surface: Surface,
    *,
    kind: str = "profile",
    bins_per_decade: int = 10,
    fit_range: tuple[float, float] | None = None,
    window: str = "hann",
) -> FractalFit:
    """D_sp from the power spectrum, fitted on the variance per logarithmic frequency band.

    Parameters
    ----------
    surface : Surface
        Height map (m).
    kind : {"profile", "radial"}
        Profile spectra (x and y averaged for square maps with square pixels, else x), or the
        2-D spectrum over annuli. ``"profile"`` is the default because it is robust to the
        line spectrum of WM surfaces (see Notes).
    bins_per_decade : int
        Logarithmic bands per decade b.
    fit_range : (float, float), optional
        Range of wavelengths 1/f (m) of the band centres used in the fit. Defaults to
        [4·max(dx, dy), min(W_r, min(Lx, Ly)/4)] with W_r from
        :func:`warptrunc.descriptors.roll_off_wavelength`: the self-affine range between the
        roll-off and the pixel scale, leaving out the mode-poor lowest bands and the top octave
        (smoothed by the window, and where the profile spectrum of a 2-D map bends down
        because the 2-D spectrum stops at the Nyquist frequency).
    window : {"hann", "none"}
        Window of the periodogram.

    Returns
    -------
    FractalFit
        ``scale`` = 1/f of the band centres (m), ``measure`` = band variance (m²), sorted by
        increasing scale.

    Notes
    -----
    For a self-affine surface the 2-D PSD falls as C(f) ∝ f^−2(1+H) and the profile PSD as
    C₁(f) ∝ f^−(1+2H); the variance in a band of fixed logarithmic width then scales as
    f^−2H, i.e. as λ^(2H) in wavelength. D_sp = 3 + slope/2 with the slope taken against
    f (3 − slope/2 against λ, as returned). Invariant to z + c, to a height scale factor and
    to transposition.

    A Weierstrass–Mandelbrot spectrum is a set of lines: M directions × (n_max + 1) radii
    f_n = γⁿ/W_r. In the 2-D spectrum all M lines of one n fall on the same radius, so a band
    holds zero, one or two radii depending on how the bands fall against γ, and the fitted
    D_sp jumped by −1.7 … +0.2 in our tests (``kind="radial"``). Along a profile, line (m, n)
    appears at f_n·|cos θ_m|: M distinct frequencies per n that fill the bands evenly; summing
    the variance of each band (rather than averaging a PSD in narrow bins, most of them empty)
    then follows f^−2H. Measured with the defaults (3 seeds each): WM surfaces, 256² and 512²,
    W_r = L/8: D_sp − D_in between −0.07 and +0.01 for D_in = 2.2 … 2.8; random-phase
    surfaces, 512²: −0.03 … −0.02 (the profile spectrum of a 2-D map bends down near the
    Nyquist frequency).
    """
    if not isinstance(surface, Surface):
        _upload(surface, "cpu")  # raises the TypeError
    f, var, nm = band_variance(surface, kind=kind, bins_per_decade=bins_per_decade, window=window)
    lam = 1.0 / f
    order = np.argsort(lam)
    lam, var, nm = lam[order], var[order], nm[order]
    if fit_range is None:
        wr, _ = roll_off_wavelength(surface, window=window)
        hi = min(wr, min(surface.lx, surface.ly) / 4.0)
        lo = 4.0 * max(surface.dx, surface.dy)
        fit_range = (lo, max(hi, lo))
    return _fit(
        "sp",
        lam,
        var,
        fit_range,
        lambda k: 3.0 - 0.5 * k,
        {"kind": kind, "bins_per_decade": int(bins_per_decade), "window": window},
    )


# --- all at once ---------------------------------------------------------------------------------

_OPTION_NAMES = {
    "tri": {"box_sizes", "fit_range", "height_scaling"},
    "box": {"box_sizes", "fit_range", "height_scaling"},
    "vs": {"lags", "fit_range", "axis"},
    "sp": {"kind", "bins_per_decade", "fit_range", "window"},
}


def fractal_dimension(
    surface: Surface, method: str = "tri", *, device: wp.DeviceLike = None, **options: Any
) -> FractalFit:
    """D by one method: ``"tri"``, ``"box"``, ``"vs"`` or ``"sp"``.

    Parameters
    ----------
    surface : Surface
        Height map (m).
    method : {"tri", "box", "vs", "sp"}
        Estimator (see the module docstring).
    device : str, optional
        Warp device (``"sp"`` ignores it and runs where the surface lives, see
        :mod:`warptrunc.descriptors`).
    **options
        Keyword options of the method's function (:func:`triangular_prism`,
        :func:`box_counting`, :func:`vertical_sections`, :func:`power_spectrum`).

    Returns
    -------
    FractalFit
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    bad = set(options) - _OPTION_NAMES[method]
    if bad:
        raise ValueError(
            f"unknown option(s) {sorted(bad)} for method {method!r}; allowed: "
            f"{sorted(_OPTION_NAMES[method])}"
        )
    if method == "tri":
        return triangular_prism(surface, device=device, **options)
    if method == "box":
        return box_counting(surface, device=device, **options)
    if method == "vs":
        return vertical_sections(surface, device=device, **options)
    return power_spectrum(surface, **options)


def fractal_dimensions(
    surface: Surface,
    methods: Sequence[str] = METHODS,
    *,
    options: dict[str, dict[str, Any]] | None = None,
    device: wp.DeviceLike = None,
) -> dict[str, FractalFit]:
    """D by several methods, uploading the map once.

    Parameters
    ----------
    surface : Surface
        Height map (m).
    methods : sequence of str
        Subset of ``("tri", "box", "vs", "sp")``.
    options : dict, optional
        Per-method keyword options, e.g. ``{"vs": {"axis": "x"}, "sp": {"kind": "profile"}}``.
    device : str, optional
        Warp device.

    Returns
    -------
    dict
        ``{method: FractalFit}`` in the order of ``methods``.
    """
    options = dict(options or {})
    for m in list(methods) + list(options):
        if m not in METHODS:
            raise ValueError(f"method must be one of {METHODS}, got {m!r}")
    for m, o in options.items():
        bad = set(o) - _OPTION_NAMES[m]
        if bad:
            raise ValueError(f"unknown option(s) {sorted(bad)} for method {m!r}")
    zd = _upload(surface, device) if set(methods) - {"sp"} else None
    out: dict[str, FractalFit] = {}
    for m in methods:
        o = options.get(m, {})
        hs = o.get("height_scaling", DEFAULT_HEIGHT_SCALING)
        if m == "tri":
            out[m] = _tri(zd, surface, o.get("box_sizes"), o.get("fit_range"), hs)
        elif m == "box":
            out[m] = _box(zd, surface, o.get("box_sizes"), o.get("fit_range"), hs)
        elif m == "vs":
            out[m] = _vs(zd, surface, o.get("lags"), o.get("fit_range"), o.get("axis", "both"))
        else:
            out[m] = power_spectrum(surface, **o)
    return out


# --- synthetic self-affine surfaces ---------------------------------------------------------------


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
        Hurst exponent, 0 < H < 1; the fractal dimension is D = 3 − H.
    n : int or (int, int)
        Pixels per side, or (nx, ny).
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

    Notes
    -----
    Fourier amplitudes are Gaussian with variance C(f) ∝ f^−2(1+H) (flat below 1/W_r), the
    DC term is zero, and the real part of the inverse FFT is taken, so the map is periodic.
    """
    from ._validate import check_int, pair

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
