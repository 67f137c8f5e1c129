# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Shared parts of the fractal-dimension methods: the :class:`FractalFit` result, the height
conventions' check and scaling, input checks, the device upload and the log-log fit (the method
keys and the conventions are declared in :mod:`warptrunc.fractal.settings`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import warp as wp

from .._support.device import resolve_device
from .._support.validate import check_range
from ..kernels import fractal as _k
from ..surface import Surface
from ..truncation.curve import surface_device, surface_range
from .settings import HEIGHT_SCALINGS

FRACTAL_DOCS = {
    "{surface}": "surface : Surface\n    Height map (m).",
    "{device}": "device : str, optional\n    Warp device.",
    "{raises}": (
        "Raises\n------\nTypeError\n    If ``surface`` is not a :class:`~warptrunc.Surface`.\nValueError"
    ),
}
"""Docstring text the fractal-dimension methods share, written once (:func:`fill_doc`)."""


def check_scaling(height_scaling: str) -> str:
    if height_scaling not in HEIGHT_SCALINGS:
        raise ValueError(f"height_scaling must be one of {HEIGHT_SCALINGS}, got {height_scaling!r}")
    return height_scaling


def cube_height_factor(
    surface: Surface, z_min: float | None = None, z_max: float | None = None
) -> float:
    """Factor of the ``"cube"`` convention: (N − 1)·√(dx·dy)/(max z − min z) (dimensionless).

    Heights times this factor span the map's lateral extent (N = max(nx, ny)).

    Parameters
    ----------
    surface : Surface
        Height map; its grid size and pixel spacings dx, dy (m) are used.
    z_min, z_max : float, optional
        Lowest and highest height (m); both default to the extremes of ``surface.heights``
        (read when either is None).

    Returns
    -------
    float
        The factor (m/m, dimensionless); 1.0 when the height range is not positive (flat map).
    """
    if z_min is None or z_max is None:
        z = surface.heights
        z_min, z_max = float(np.min(z)), float(np.max(z))
    rng = float(z_max) - float(z_min)
    if not rng > 0:
        return 1.0
    return (max(surface.nx, surface.ny) - 1) * math.sqrt(surface.dx * surface.dy) / rng


def scaled_upload(zd: wp.array, surface: Surface, height_scaling: str) -> wp.array:
    """The device heights for a method: as measured ("si") or mapped into the cube (on the
    device, from the surface's recorded or reduced extremes)."""
    if height_scaling == "si":
        return zd
    lo, hi = surface_range(surface, zd.flatten(), zd.device)
    out = wp.empty(zd.shape, dtype=wp.float32, device=zd.device)
    wp.launch(
        _k.cube_scale_kernel,
        dim=zd.shape,
        inputs=[zd, float(lo), cube_height_factor(surface, lo, hi)],
        outputs=[out],
        device=zd.device,
    )
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
        """Number of scales inside the fit range (count)."""
        return int(np.count_nonzero(self.fitted))

    def to_dict(self) -> dict[str, Any]:
        """Columns ``scale_m``, ``measure``, ``fitted`` and the scalars of the fit.

        Returns
        -------
        dict of str to Any
            ``method``, ``D``, ``r2``, ``slope``, ``intercept``, ``fit_min_m`` and ``fit_max_m``
            (m) as scalars; ``scale_m`` (m), ``measure`` and ``fitted`` as (k,) arrays.
            ``options`` is not included.
        """
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


def upload(surface: Surface, device: wp.DeviceLike) -> wp.array:
    if not isinstance(surface, Surface):
        raise TypeError(
            f"surface must be a warptrunc.Surface, got {type(surface).__name__}; wrap a height "
            "array with warptrunc.from_heights(z, dx)"
        )
    # where a device surface lives unless told otherwise; cached per device on the surface
    return surface.device_heights(resolve_device(surface_device(surface, device)))


def check_sizes(name: str, sizes: Sequence[int] | None, surface: Surface, default) -> np.ndarray:
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


def fit_log_log(
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


def row_chunks(ncx: int, s: int) -> tuple[int, int]:
    chunk = max(1, 32 // s)
    return chunk, (ncx + chunk - 1) // chunk
