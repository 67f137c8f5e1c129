# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Result objects of the island analysis (frozen dataclasses with ``to_dict()``)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._support.docs import SHARED_DOCS, fill_doc
from .._support.outputs import write_columns_csv

_DOCS = {
    **SHARED_DOCS,
    "{island_columns}": (
        "Returns\n-------\ndict of str to ndarray\n"
        "    (n,) columns, one row per island (areas in m², lengths in m)."
    ),
    "{depth_columns}": (
        "Returns\n-------\ndict of str to ndarray\n"
        "    Equal-length columns, one row per truncation depth ω (m)."
    ),
}
"""Docstring text of the results' writers and columns, written once (:func:`fill_doc`)."""

SEGMENT = 32  # pixels per thread in island_stats_kernel


class _LazyHostArray:
    """Dataclass field holding a NumPy array or a device (Warp) array; reading it returns NumPy,
    copying a device array to the host once, on first access (labels stay on the device until a
    host consumer asks)."""

    def __set_name__(self, owner: type, name: str) -> None:
        self._key = f"_{name}_store"

    def __get__(self, obj: Any, objtype: type | None = None) -> Any:
        if obj is None:  # no class-level default: the field stays required
            raise AttributeError(self._key)
        v = obj.__dict__[self._key]
        if not isinstance(v, np.ndarray):
            src = v
            v = np.array(src.numpy(), copy=True) if src.device.is_cpu else src.numpy()
            obj.__dict__[self._key] = v  # sync point, once
            obj.__dict__["_device_store"] = src
        return v

    def __set__(self, obj: Any, value: Any) -> None:
        obj.__dict__[self._key] = value
        if not isinstance(value, np.ndarray):
            obj.__dict__["_device_store"] = value


# --- result objects -------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Islands:
    """The islands of one contact mask: labels and per-island area and perimeter."""

    labels: np.ndarray = _LazyHostArray()  # type: ignore[assignment]
    """(ny, nx) int32 island labels 1..n in raster order of first pixel, 0 = no contact. Kept
    on the device where they were computed and copied to the host on first access; see
    :attr:`device_labels`."""
    n_islands: int
    """Number of islands n."""
    area_pixels: np.ndarray
    """(n,) int64 pixels of island 1..n."""
    area: np.ndarray
    """(n,) float64 island areas A (m²)."""
    perimeter: np.ndarray
    """(n,) float64 island perimeters L, pixel-edge length (m)."""
    edges_x: np.ndarray
    """(n,) int64 boundary edges crossed along x (each dy long)."""
    edges_y: np.ndarray
    """(n,) int64 boundary edges crossed along y (each dx long)."""
    dx: float
    """Pixel spacing along x (m)."""
    dy: float
    """Pixel spacing along y (m)."""
    connectivity: int
    """4 or 8."""
    periodic: bool
    """Whether the map wraps around."""
    depth: float = math.nan
    """Truncation depth ω of the mask (m); NaN for a mask given directly."""

    @property
    def device_labels(self) -> Any:
        """The labels as the (ny, nx) int32 Warp array they were computed in, or None when they
        were given as NumPy."""
        return self.__dict__.get("_device_store")

    @property
    def has_host_labels(self) -> bool:
        """True once the NumPy labels exist (the lazy copy has been made)."""
        return isinstance(self.__dict__.get("_labels_store"), np.ndarray)

    @fill_doc(_DOCS)
    def to_dict(self) -> dict[str, Any]:
        """Columns as 1-D arrays, one row per island.

        {island_columns}
        """
        return {
            "label": np.arange(1, self.n_islands + 1, dtype=np.int64),
            "area_pixels": self.area_pixels,
            "area_m2": self.area,
            "perimeter_m": self.perimeter,
        }


@dataclass(frozen=True, eq=False)
class IslandSizes:
    """Areas and perimeters of the islands at one depth, without the label map."""

    depth: float
    """Truncation depth ω (m)."""
    area_pixels: np.ndarray
    """(n,) int64 pixels per island, in label order (raster order of first pixel)."""
    area: np.ndarray
    """(n,) float64 island areas A (m²)."""
    perimeter: np.ndarray
    """(n,) float64 island perimeters L (m)."""

    @property
    def n_islands(self) -> int:
        """Number of islands."""
        return int(self.area_pixels.size)

    @fill_doc(_DOCS)
    def to_dict(self) -> dict[str, Any]:
        """Columns as 1-D arrays, one row per island.

        {island_columns}
        """
        return {
            "depth_m": np.full(self.n_islands, self.depth),
            "area_pixels": self.area_pixels,
            "area_m2": self.area,
            "perimeter_m": self.perimeter,
        }


@dataclass(frozen=True, eq=False)
class SlitIslandFit:
    """Least-squares fit of log10 L = exponent·log10 A + intercept over islands (Eq. 5)."""

    exponent: float
    """Slope (D − 1)/2 of log L against log A (dimensionless); NaN without a fit."""
    intercept: float
    """log10 of L (m) at A = 1 m²."""
    r2: float
    """Coefficient of determination of the fit (dimensionless)."""
    n_islands: int
    """Islands used (at least ``min_pixels`` pixels each)."""
    min_pixels: int
    """Smallest island used (pixels)."""

    @property
    def dimension(self) -> float:
        """Implied fractal dimension D = 2·exponent + 1 (dimensionless)."""
        return 2.0 * self.exponent + 1.0

    def to_dict(self) -> dict[str, Any]:
        """Scalars, JSON-serialisable.

        Returns
        -------
        dict of str to Any
            The scalar fields (lengths in m, areas in m²).
        """
        return {
            "exponent": self.exponent,
            "intercept": self.intercept,
            "r2": self.r2,
            "dimension": self.dimension,
            "n_islands": self.n_islands,
            "min_pixels": self.min_pixels,
        }


@dataclass(frozen=True, eq=False)
class TopologyCurve:
    """Total perimeter and Euler characteristic of the contact set at every depth."""

    depth: np.ndarray
    """(n+1,) float64 truncation depths ω_k (m)."""
    n_contact_pixels: np.ndarray
    """(n+1,) int64 contact pixels."""
    contact_area: np.ndarray
    """(n+1,) float64 truncated area A_c (m²)."""
    edges_x: np.ndarray
    """(n+1,) int64 boundary edges crossed along x (each dy long)."""
    edges_y: np.ndarray
    """(n+1,) int64 boundary edges crossed along y (each dx long)."""
    total_perimeter: np.ndarray
    """(n+1,) float64 total island perimeter (m)."""
    euler_characteristic: np.ndarray
    """(n+1,) int64 χ = islands − holes of the contact set."""
    Rt: float
    """Peak-to-valley height R_t (m)."""
    connectivity: int
    """4 or 8."""
    periodic: bool
    """Whether the map wraps around."""

    @fill_doc(_DOCS)
    def to_dict(self) -> dict[str, Any]:
        """Columns as 1-D arrays, one row per depth.

        {depth_columns}
        """
        return {
            "depth_m": self.depth,
            "depth_fraction_of_Rt": self.depth / self.Rt,
            "n_contact_pixels": self.n_contact_pixels,
            "contact_area_m2": self.contact_area,
            "total_perimeter_m": self.total_perimeter,
            "euler_characteristic": self.euler_characteristic,
        }


@dataclass(frozen=True, eq=False)
class IslandCurve:
    """Island statistics at every truncation depth of one height map (Fig. 8)."""

    depth: np.ndarray
    """(n+1,) float64 truncation depths ω_k (m)."""
    n_islands: np.ndarray
    """(n+1,) int64 number of islands."""
    n_contact_pixels: np.ndarray
    """(n+1,) int64 contact pixels."""
    contact_area: np.ndarray
    """(n+1,) float64 truncated area A_c (m²)."""
    total_perimeter: np.ndarray
    """(n+1,) float64 total island perimeter (m)."""
    euler_characteristic: np.ndarray
    """(n+1,) int64 χ = islands − holes of the contact set."""
    slit_exponent: np.ndarray
    """(n+1,) float64 slit-island exponent at each depth (dimensionless); NaN where fewer than
    ``MIN_ISLANDS`` islands have ``min_pixels`` pixels, or without statistics."""
    slit_r2: np.ndarray
    """(n+1,) float64 r² of each slit-island fit (dimensionless)."""
    slit_n_islands: np.ndarray
    """(n+1,) int64 islands used in each fit."""
    area_histogram: np.ndarray
    """(n+1, m) int64 islands per area bin [2^j, 2^(j+1)) pixels, j = 0..m−1; zeros without
    statistics."""
    sizes: tuple[IslandSizes, ...]
    """Areas and perimeters of every island at the snapshot depths."""
    Rt: float
    """Peak-to-valley height R_t (m)."""
    dx: float
    """Pixel spacing along x (m)."""
    dy: float
    """Pixel spacing along y (m)."""
    connectivity: int
    """4 or 8."""
    periodic: bool
    """Whether the map wraps around."""
    min_pixels: int
    """Smallest island in the slit-island fits (pixels)."""
    params: dict[str, Any] = field(default_factory=dict)
    """Provenance: the surface's parameters."""
    sqrt_area_sum: np.ndarray | None = None
    """(n+1,) float64 Σ_i √A_i over the islands at each depth (m), the island-resolved
    stiffness's sum (:func:`warptrunc.stiffness.island_stiffness_curve`); None without
    statistics."""
    apparent_area: float | None = None
    """Apparent area A of the map (m²); None when not recorded."""

    @property
    def depth_fraction(self) -> np.ndarray:
        """(n+1,) float64 ω/R_t (dimensionless)."""
        return self.depth / self.Rt

    @property
    def normalised_island_number(self) -> np.ndarray:
        """(n+1,) float64 island count over its maximum (Fig. 8a; dimensionless)."""
        top = self.n_islands.max()
        return self.n_islands / float(top) if top > 0 else np.zeros(self.depth.size)

    @property
    def island_growth_rate(self) -> np.ndarray:
        """(n+1,) float64 d(normalised island number)/d(ω/R_t) by central differences
        (dimensionless)."""
        if self.depth.size < 2:
            return np.zeros(self.depth.size)
        return np.gradient(self.normalised_island_number, self.depth_fraction)

    @property
    def slit_dimension(self) -> np.ndarray:
        """(n+1,) float64 D = 2·exponent + 1 implied by the slit-island fits."""
        return 2.0 * self.slit_exponent + 1.0

    @property
    def area_bin_edges(self) -> np.ndarray:
        """(m+1,) int64 edges 2^j of ``area_histogram`` (pixels)."""
        return 2 ** np.arange(self.area_histogram.shape[1] + 1, dtype=np.int64)

    @fill_doc(_DOCS)
    def to_dict(self) -> dict[str, Any]:
        """Columns as 1-D arrays, one row per depth (the first eight are islands.csv).

        {depth_columns}
        """
        return {
            "depth_m": self.depth,
            "depth_fraction_of_Rt": self.depth_fraction,
            "n_islands": self.n_islands,
            "euler_characteristic": self.euler_characteristic,
            "total_perimeter_m": self.total_perimeter,
            "contact_area_m2": self.contact_area,
            "slit_exponent": self.slit_exponent,
            "slit_r2": self.slit_r2,
            "slit_n_islands": self.slit_n_islands,
            "n_contact_pixels": self.n_contact_pixels,
            "normalised_island_number": self.normalised_island_number,
            "island_growth_rate": self.island_growth_rate,
        }

    @fill_doc(_DOCS)
    def to_csv(self, path: str | Path) -> Path:
        """Write the columns of :meth:`to_dict` as CSV, as ``warptrunc islands`` writes
        ``islands.csv`` (full float64 precision, ``nan`` where no fit exists).

        Parameters
        ----------
        path : str or Path
            File to write (overwritten): a header row of the column names, then one row per
            truncation depth.

        {returns_path}
            ``path``.
        """
        return write_columns_csv(path, self.to_dict())


@dataclass(frozen=True, eq=False)
class Indicators:
    """Depths bounding the applicable range of the truncation method (Table 2)."""

    max_growth_depth: float
    """Depth of the largest growth rate of the island number (m)."""
    fractal_depth: float
    """Deepest depth at which the slit-island exponent stays on its plateau (m); NaN without
    exponents."""
    peak_depth: float
    """Depth of the largest island count (m)."""
    plateau_exponent: float
    """Median slit-island exponent over the plateau range (dimensionless)."""
    fractal_depth_censored: bool
    """True when the exponent never left the plateau: ``fractal_depth`` is then the deepest
    depth analysed, a lower bound."""
    Rt: float
    """Peak-to-valley height R_t (m)."""
    exponent_tolerance: float
    """Allowed relative drop of the exponent below the plateau (dimensionless)."""
    min_islands: int
    """Fewest fitted islands for a depth's exponent to count."""
    persist: float
    """Depth span (fraction of R_t) a drop must last to count (dimensionless)."""
    plateau_range: tuple[float, float]
    """Depth range, as fractions of R_t, over which the plateau exponent is the median."""
    smooth: int
    """Window (depth samples) of the running mean / median applied before the search."""

    def to_dict(self) -> dict[str, Any]:
        """Scalars, JSON-serialisable; depths in % of R_t and in m.

        Returns
        -------
        dict of str to Any
            The indicator depths, in % of R_t and in m.
        """
        pct = 100.0 / self.Rt

        def num(v: float) -> float | None:
            return None if not math.isfinite(v) else float(v)

        return {
            "max_growth_rate_depth_percent_Rt": num(self.max_growth_depth * pct),
            "fractality_depth_percent_Rt": num(self.fractal_depth * pct),
            "island_peak_depth_percent_Rt": num(self.peak_depth * pct),
            "max_growth_rate_depth_m": num(self.max_growth_depth),
            "fractality_depth_m": num(self.fractal_depth),
            "island_peak_depth_m": num(self.peak_depth),
            "plateau_exponent": num(self.plateau_exponent),
            "plateau_dimension": num(2.0 * self.plateau_exponent + 1.0),
            "fractality_depth_censored": bool(self.fractal_depth_censored),
            "Rt_m": self.Rt,
            "exponent_tolerance": self.exponent_tolerance,
            "min_islands": self.min_islands,
            "persist_fraction_of_Rt": self.persist,
            "plateau_range_fraction_of_Rt": [num(v) for v in self.plateau_range],
            "smooth": self.smooth,
        }
