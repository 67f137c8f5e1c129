# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Contact islands: labelling, island statistics at every depth, slit-island analysis and the
applicable truncation depth (paper §4.3, Fig. 8, Table 2, Eq. 5).

Kernels: ``warptrunc.kernels.label`` (union-find labelling of one mask),
``warptrunc.kernels.islands`` (carried forest across depths, per-island statistics) and
``warptrunc.kernels.euler`` (total perimeter and Euler characteristic by histograms).

Conventions
-----------
*Contact* at depth ω: ``z >= z_top − ω`` compared in float32, exactly as
:func:`warptrunc.truncate`.

*Connectivity* 4 (default) or 8. Two contact pixels are in one island when they share an edge
(4) or an edge or a corner (8). The default is 4 because two pixels touching at a corner only
meet at a point of zero width: for contact they are separate spots, and the truncated area
between them does not carry load across. With 4-connectivity of the contact set, holes are
8-connected, and vice versa; the Euler characteristic below follows the same pairing.

*Labels* are 1..n in raster order (C order, x fastest) of each island's first pixel, 0 for
non-contact. They do not depend on the device or on thread scheduling, and equal
``scipy.ndimage.label`` with the matching structure.

*Perimeter* of an island: the total length of the pixel edges between one of its pixels and a
non-contact pixel, dy per edge crossed along x and dx per edge crossed along y; the shores of
enclosed holes count too. Outside a bounded domain counts as non-contact, so an island cut by
the border is closed along it; with ``periodic=True`` the map wraps around instead. This
"city-block" length overestimates an oblique boundary (by 4/π on average for isotropic
boundaries, up to √2), a factor that does not depend on island size, so it moves the
intercept of a slit-island fit, not its exponent.

*Euler characteristic* χ of the contact set: islands minus enclosed holes (non-contact
components not touching the border, connectivity 8 for contact connectivity 4 and vice
versa). With ``periodic=True``, χ is that of the set on the torus (χ = islands − holes only for
sets that do not wrap around).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import warp as wp

from ._device import check_memory, resolve_device
from ._validate import check_int, check_range
from .kernels import euler as _ke
from .kernels import islands as _ki
from .kernels import label as _kl
from .surface import Surface
from .truncation import contact_index_map, depth_grid

__all__ = [
    "Indicators",
    "IslandCurve",
    "IslandSizes",
    "Islands",
    "SlitIslandFit",
    "TopologyCurve",
    "applicable_depth",
    "island_counts_device",
    "island_curve",
    "islands_at_depth",
    "islands_at_depths",
    "label_device",
    "label_islands",
    "slit_island_fit",
    "topology_curve",
]

MIN_PIXELS = 10
"""Default smallest island (pixels) in a slit-island fit: below ~10 pixels the pixel-edge
perimeter of an island is set by the grid (1 pixel: L = 4·dx, A = dx²), not by the surface."""

MIN_ISLANDS = 5
"""Fewest islands for a slit-island fit; fewer give NaN."""

_SEGMENT = 32  # pixels per thread in island_stats_kernel


# --- result objects -------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Islands:
    """The islands of one contact mask: labels and per-island area and perimeter."""

    labels: np.ndarray
    """(ny, nx) int32 island labels 1..n in raster order of first pixel, 0 = no contact."""
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

    def to_dict(self) -> dict[str, Any]:
        """Columns as 1-D arrays, one row per island."""
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

    def to_dict(self) -> dict[str, Any]:
        """Columns as 1-D arrays, one row per island."""
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
        """Scalars, JSON-serialisable."""
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
    rt: float
    """Peak-to-valley height R_t (m)."""
    connectivity: int
    """4 or 8."""
    periodic: bool
    """Whether the map wraps around."""

    def to_dict(self) -> dict[str, Any]:
        """Columns as 1-D arrays, one row per depth."""
        return {
            "depth_m": self.depth,
            "depth_fraction_of_Rt": self.depth / self.rt,
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
    rt: float
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

    @property
    def depth_fraction(self) -> np.ndarray:
        """(n+1,) float64 ω/R_t (dimensionless)."""
        return self.depth / self.rt

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

    def to_dict(self) -> dict[str, Any]:
        """Columns as 1-D arrays, one row per depth (the first eight are islands.csv)."""
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
    rt: float
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
        """Scalars, JSON-serialisable; depths in % of R_t and in m."""
        pct = 100.0 / self.rt

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
            "rt_m": self.rt,
            "exponent_tolerance": self.exponent_tolerance,
            "min_islands": self.min_islands,
            "persist_fraction_of_Rt": self.persist,
            "plateau_range_fraction_of_Rt": [num(v) for v in self.plateau_range],
            "smooth": self.smooth,
        }


# --- validation -----------------------------------------------------------------------------------


def _check_connectivity(connectivity: int) -> int:
    if isinstance(connectivity, bool) or connectivity not in (4, 8):
        raise ValueError(f"connectivity must be 4 or 8, got {connectivity!r}")
    return int(connectivity)


def _check_mask(mask: np.ndarray) -> np.ndarray:
    """Return a C-contiguous uint8 0/1 copy of a 2-D boolean or integer mask."""
    m = np.asarray(mask)
    if m.ndim != 2:
        raise ValueError(f"mask must be 2-D (ny, nx), got shape {m.shape}")
    if m.shape[0] < 1 or m.shape[1] < 1:
        raise ValueError(f"mask must not be empty, got shape {m.shape}")
    if not (m.dtype == np.bool_ or np.issubdtype(m.dtype, np.integer)):
        raise ValueError(
            f"mask must be boolean or integer (non-zero = contact), got dtype {m.dtype}; "
            "threshold height maps with islands_at_depth"
        )
    return np.ascontiguousarray(m != 0, dtype=np.uint8)


def _check_surface(surface: Surface) -> Surface:
    if not isinstance(surface, Surface):
        raise TypeError(
            f"surface must be a warptrunc.Surface (wrap a height map with "
            f"warptrunc.from_heights(z, dx)), got {type(surface).__name__}"
        )
    return surface


def _check_index_size(n: int) -> None:
    # flat int32 indices, and the radix sort's 2·N buffers
    if 2 * n >= 2**31:
        raise ValueError(f"grid of {n} pixels is too large for int32 indices (limit 2**30)")


# --- labelling of one mask ------------------------------------------------------------------------


def label_device(
    mask: wp.array, connectivity: int = 4, *, periodic: bool = False
) -> tuple[wp.array, int]:
    """Label a device-resident contact mask; the building block of :func:`label_islands`.

    Parameters
    ----------
    mask : (ny, nx) warp array of uint8
        Contact mask, non-zero = contact, contiguous, on the device to run on.
    connectivity : {4, 8}
        Neighbourhood of an island (see the module Notes).
    periodic : bool
        Wrap the map around in x and y.

    Returns
    -------
    labels : (ny, nx) warp array of int32
        1..n in raster order of each island's first pixel, 0 for no contact (same device).
    n : int
        Number of islands (read back from the device: a sync point).

    Notes
    -----
    On a GPU: lock-free parallel union-find (see :func:`label_islands`). On the CPU, where a
    Warp launch runs on one thread, the same union-find runs as one raster-order pass followed
    by an in-place relabelling pass, in a single launch. Both give identical labels.
    """
    connectivity = _check_connectivity(connectivity)
    _check_mask_array(mask)
    if mask.device.is_cpu:
        return _label_sequential(mask, connectivity, periodic)
    return _label_parallel(mask, connectivity, periodic)


def _check_mask_array(mask: wp.array) -> None:
    if not isinstance(mask, wp.array) or mask.ndim != 2 or mask.dtype != wp.uint8:
        raise ValueError(
            f"mask must be a 2-D warp array of uint8, got {type(mask).__name__} "
            f"{getattr(mask, 'dtype', '')} with shape {getattr(mask, 'shape', None)}"
        )
    if not mask.is_contiguous:
        raise ValueError("mask must be a contiguous warp array")
    _check_index_size(mask.shape[0] * mask.shape[1])


def _label_sequential(mask: wp.array, connectivity: int, periodic: bool) -> tuple[wp.array, int]:
    """One-thread raster-order union-find (the CPU path of :func:`label_device`)."""
    ny, nx = mask.shape
    labels = wp.empty(ny * nx, dtype=wp.int32, device=mask.device)
    count = wp.zeros(1, dtype=wp.int32, device=mask.device)
    wp.launch(
        _kl.label_sequential_kernel,
        dim=1,
        inputs=[mask.reshape((ny * nx,)), ny, nx, connectivity, int(bool(periodic))],
        outputs=[labels, count],
        device=mask.device,
    )
    return labels.reshape((ny, nx)), int(count.numpy()[0])  # sync point


def _label_parallel(mask: wp.array, connectivity: int, periodic: bool) -> tuple[wp.array, int]:
    """Lock-free parallel union-find (the GPU path of :func:`label_device`)."""
    ny, nx = mask.shape
    n = ny * nx
    device = mask.device
    flat = mask.reshape((n,))
    parent = wp.empty(n, dtype=wp.int32, device=device)
    flag = wp.empty(n, dtype=wp.int32, device=device)
    rank = wp.empty(n, dtype=wp.int32, device=device)
    per = int(bool(periodic))
    wp.launch(
        _kl.init_parent_kernel,
        dim=(ny, nx),
        inputs=[flat, nx, _SEGMENT],
        outputs=[parent],
        device=device,
    )
    wp.launch(
        _kl.hook_kernel,
        dim=(ny, nx),
        inputs=[flat, ny, nx, connectivity, per],
        outputs=[parent],
        device=device,
    )
    wp.launch(
        _kl.compress_flag_kernel, dim=(ny, nx), inputs=[nx], outputs=[parent, flag], device=device
    )
    wp.utils.array_scan(flag, rank, inclusive=True)
    n_islands = int(rank[n - 1 : n].numpy()[0])  # sync point
    # labels overwrite the scan: a root's slot is rewritten with its own value, and no thread
    # reads the slot of a non-root
    wp.launch(
        _kl.write_labels_kernel,
        dim=(ny, nx),
        inputs=[parent, rank, nx],
        outputs=[rank],
        device=device,
    )
    return rank.reshape((ny, nx)), n_islands


def _stats_from_labels(
    labels: wp.array,
    n_islands: int,
    ny: int,
    nx: int,
    periodic: bool,
    device: wp.context.Device,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per-label (pixels, edges along x, edges along y) for labels 1..n, as int64 ndarrays."""
    acc = wp.zeros((3, n_islands + 1), dtype=wp.int64, device=device)
    nseg = (nx + _SEGMENT - 1) // _SEGMENT
    wp.launch(
        _ki.island_stats_kernel,
        dim=(ny, nseg),
        inputs=[labels.reshape((ny * nx,)), ny, nx, int(bool(periodic)), _SEGMENT],
        outputs=[acc[0], acc[1], acc[2]],
        device=device,
    )
    a = acc.numpy()[:, 1:]  # sync point
    return a[0], a[1], a[2]


def _islands(
    labels: wp.array,
    n_islands: int,
    shape: tuple[int, int],
    dx: float,
    dy: float,
    connectivity: int,
    periodic: bool,
    depth: float,
    device: wp.context.Device,
    keep_labels: bool = True,
) -> Islands | IslandSizes:
    ny, nx = shape
    area_px, ex, ey = _stats_from_labels(labels, n_islands, ny, nx, periodic, device)
    area = area_px * (dx * dy)
    perimeter = ex * dy + ey * dx
    if not keep_labels:
        return IslandSizes(depth=depth, area_pixels=area_px, area=area, perimeter=perimeter)
    return Islands(
        labels=labels.numpy().reshape(ny, nx),
        n_islands=n_islands,
        area_pixels=area_px,
        area=area,
        perimeter=perimeter,
        edges_x=ex,
        edges_y=ey,
        dx=dx,
        dy=dy,
        connectivity=connectivity,
        periodic=bool(periodic),
        depth=depth,
    )


def label_islands(
    mask: np.ndarray,
    dx: float = 1.0,
    dy: float | None = None,
    *,
    connectivity: int = 4,
    periodic: bool = False,
    device: wp.DeviceLike = None,
) -> Islands:
    """Label the islands of a contact mask and measure their areas and perimeters.

    Parameters
    ----------
    mask : (ny, nx) ndarray of bool or int
        Contact mask ``m[iy, ix]``, non-zero = contact.
    dx : float
        Pixel spacing along x (m). The default 1 makes areas and perimeters pixel units.
    dy : float, optional
        Pixel spacing along y (m); ``dx`` when omitted.
    connectivity : {4, 8}
        Neighbourhood of an island. 4 (default): pixels touching at a corner only are separate
        islands (see the module Notes).
    periodic : bool
        Wrap the map around in x and y.
    device : str, optional
        Warp device; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    Islands

    Notes
    -----
    Lock-free union-find on the device: every contact pixel unites with its forward neighbours,
    hooking the larger root under the smaller by compare-and-swap, so each island's root is its
    first pixel in raster order; roots are flagged, scanned (count → scan → write) and numbered
    1..n. The result equals ``scipy.ndimage.label(mask, structure)`` with the cross (4) or the
    3×3 block (8) structure, for any device and any thread order.

    Examples
    --------
    >>> import numpy as np
    >>> isl = label_islands(np.array([[1, 0, 1], [1, 0, 0]], bool), device="cpu")
    >>> isl.n_islands, isl.area_pixels.tolist(), isl.perimeter.tolist()
    (2, [2, 1], [6.0, 4.0])
    """
    m = _check_mask(mask)
    connectivity = _check_connectivity(connectivity)
    dx = check_range("dx", dx, 0.0, unit="m")
    dy = dx if dy is None else check_range("dy", dy, 0.0, unit="m")
    device = resolve_device(device)
    check_memory(m.size * 29, device, "island labelling")
    mw = wp.array(m, dtype=wp.uint8, device=device)
    labels, n = label_device(mw, connectivity, periodic=periodic)
    return _islands(labels, n, m.shape, dx, dy, connectivity, periodic, math.nan, device)


# --- carried forest across depths -----------------------------------------------------------------


class _Forest:
    """One union-find forest carried through increasing depths (see ``kernels/islands.py``)."""

    def __init__(
        self,
        idx: wp.array,
        shape: tuple[int, int],
        n1: int,
        connectivity: int,
        periodic: bool,
        statistics: bool,
        device: wp.context.Device,
    ) -> None:
        ny, nx = shape
        n = ny * nx
        _check_index_size(n)
        self.idx, self.ny, self.nx, self.n, self.n1 = idx, ny, nx, n, n1
        self.connectivity, self.periodic = connectivity, int(bool(periodic))
        self.statistics, self.device = statistics, device
        # stable sort of the pixels by contact index: bucket k holds the pixels touching at k,
        # in raster order
        keys = wp.empty(2 * n, dtype=wp.int32, device=device)
        wp.copy(keys, idx, count=n)
        order = wp.empty(2 * n, dtype=wp.int32, device=device)
        wp.launch(_ki.iota_kernel, dim=n, outputs=[order], device=device)
        wp.utils.radix_sort_pairs(keys, order, n, end_bit=max(1, int(n1).bit_length()))
        first = wp.empty(n1 + 2, dtype=wp.int32, device=device)
        wp.launch(_ki.bucket_start_kernel, dim=n, inputs=[keys, n], outputs=[first], device=device)
        self.first = first.numpy().astype(np.int64)  # sync point
        del keys
        self.order = order
        self.parent = wp.empty(n, dtype=wp.int32, device=device)
        self.link = wp.empty(n, dtype=wp.int32, device=device)
        wp.launch(
            _ki.init_forest_kernel,
            dim=n,
            inputs=[n1],
            outputs=[self.parent, self.link],
            device=device,
        )
        self.k = -1
        self._hook = wp.launch(
            _ki.hook_depth_kernel,
            dim=1,
            inputs=[order, 0, idx, 0, ny, nx, connectivity, self.periodic],
            outputs=[self.parent, self.link],
            device=device,
            record_cmd=True,
        )
        if statistics:
            self.area = wp.zeros(n, dtype=wp.int32, device=device)
            self.edges_x = wp.zeros(n, dtype=wp.int32, device=device)
            self.edges_y = wp.zeros(n, dtype=wp.int32, device=device)
            self.roots = wp.empty(1, dtype=wp.int32, device=device)
            self.n_roots = 0

    def bucket(self, k: int) -> tuple[int, int]:
        """(start, count) of bucket k in the sorted order."""
        s = int(self.first[k])
        return s, int(self.first[k + 1]) - s

    def step(self) -> None:
        """Add the pixels of the next increment and unite them with their active neighbours."""
        k = self.k + 1
        if k >= self.n1:
            raise RuntimeError("no increment left")
        start, count = self.bucket(k)
        if count > 0:
            h = self._hook
            h.set_dim(count)
            h.set_param_by_name("start", start)
            h.set_param_by_name("k", k)
            h.launch()
        if self.statistics:
            self._update_statistics(k, start, count)
        self.k = k

    def _update_statistics(self, k: int, start: int, count: int) -> None:
        dev, n_roots = self.device, self.n_roots
        ncand = n_roots + count
        if ncand == 0:
            return
        acc = [self.area, self.edges_x, self.edges_y]
        wp.launch(
            _ki.merge_linked_kernel,
            dim=ncand,
            inputs=[self.roots, n_roots, self.order, start, self.link, k],
            outputs=[self.parent, *acc],
            device=dev,
        )
        if count > 0:
            wp.launch(
                _ki.add_pixels_kernel,
                dim=count,
                inputs=[self.order, start, self.idx, k, self.ny, self.nx, self.periodic],
                outputs=[self.parent, *acc],
                device=dev,
            )
        flag = wp.empty(ncand, dtype=wp.int32, device=dev)
        wp.launch(
            _ki.root_flag_kernel,
            dim=ncand,
            inputs=[self.roots, n_roots, self.order, start, self.parent],
            outputs=[flag],
            device=dev,
        )
        rank = wp.empty(ncand, dtype=wp.int32, device=dev)
        wp.utils.array_scan(flag, rank, inclusive=True)
        n_new = int(rank[ncand - 1 : ncand].numpy()[0])  # sync point
        roots = wp.empty(max(n_new, 1), dtype=wp.int32, device=dev)
        wp.launch(
            _ki.write_roots_kernel,
            dim=ncand,
            inputs=[self.roots, n_roots, self.order, start, flag, rank],
            outputs=[roots],
            device=dev,
        )
        self.roots, self.n_roots = roots, n_new

    def root_stats(self, min_pixels: int) -> tuple[np.ndarray, ...]:
        """(root, pixels, edges_x, edges_y) of the current islands with ≥ min_pixels, as int64
        ndarrays sorted by root (= label order)."""
        dev, nr = self.device, self.n_roots
        if nr == 0:
            e = np.zeros(0, dtype=np.int64)
            return e, e, e, e
        flag = wp.empty(nr, dtype=wp.int32, device=dev)
        wp.launch(
            _ki.big_flag_kernel,
            dim=nr,
            inputs=[self.roots, self.area, int(min_pixels)],
            outputs=[flag],
            device=dev,
        )
        rank = wp.empty(nr, dtype=wp.int32, device=dev)
        wp.utils.array_scan(flag, rank, inclusive=True)
        m = int(rank[nr - 1 : nr].numpy()[0])  # sync point
        if m == 0:
            e = np.zeros(0, dtype=np.int64)
            return e, e, e, e
        out = wp.empty((4, m), dtype=wp.int32, device=dev)
        wp.launch(
            _ki.gather_stats_kernel,
            dim=nr,
            inputs=[self.roots, flag, rank, self.area, self.edges_x, self.edges_y],
            outputs=[out[0], out[1], out[2], out[3]],
            device=dev,
        )
        a = out.numpy().astype(np.int64)  # sync point
        o = np.argsort(a[0], kind="stable")
        return a[0][o], a[1][o], a[2][o], a[3][o]

    def area_histogram(self, hist: wp.array, k: int) -> None:
        """Add the current islands to row k of the log2 area histogram."""
        if self.n_roots > 0:
            wp.launch(
                _ki.area_histogram_kernel,
                dim=self.n_roots,
                inputs=[self.roots, self.area, k],
                outputs=[hist],
                device=self.device,
            )

    def labels(self) -> tuple[wp.array, int]:
        """Labels (flat int32, 1..n raster order) of the contact set at the current increment."""
        dev, n = self.device, self.n
        flag = wp.empty(n, dtype=wp.int32, device=dev)
        wp.launch(
            _ki.active_labels_flag_kernel,
            dim=n,
            inputs=[self.idx, self.k],
            outputs=[self.parent, flag],
            device=dev,
        )
        rank = wp.empty(n, dtype=wp.int32, device=dev)
        wp.utils.array_scan(flag, rank, inclusive=True)
        n_islands = int(rank[n - 1 : n].numpy()[0])  # sync point
        wp.launch(
            _ki.active_labels_write_kernel,
            dim=n,
            inputs=[self.idx, self.k, self.parent, rank],
            outputs=[rank],
            device=dev,
        )
        return rank, n_islands

    def island_counts(self) -> np.ndarray:
        """(n1,) int64 islands at every increment (valid up to the current one)."""
        diff = wp.zeros(self.n1, dtype=wp.int64, device=self.device)
        wp.launch(
            _ki.island_count_diff_kernel,
            dim=self.n,
            inputs=[self.idx, self.link, self.n1],
            outputs=[diff],
            device=self.device,
        )
        return np.cumsum(diff.numpy())  # sync point


def island_counts_device(
    index: wp.array,
    n_depths: int,
    connectivity: int = 4,
    *,
    periodic: bool = False,
) -> np.ndarray:
    """Island count at every depth from a device-resident contact-index map, fastest path.

    Parameters
    ----------
    index : (ny, nx) warp array of int32
        Contact index of every pixel: the first depth increment k at which it touches, or
        ``n_depths`` when it never does (as from ``contact_index_map(..., as_warp=True)``).
    n_depths : int
        Number of depths n + 1.
    connectivity : {4, 8}
        Neighbourhood of an island.
    periodic : bool
        Wrap the map around in x and y.

    Returns
    -------
    (n_depths,) int64 ndarray
        Islands at increments 0..n.

    Notes
    -----
    One stable radix sort of the pixels by contact index, then one union pass per increment
    over the pixels touching at that increment, then one difference histogram of the
    increments at which islands start and end (see :func:`island_curve`). No labelling at any
    depth.
    """
    connectivity = _check_connectivity(connectivity)
    n1 = check_int("n_depths", n_depths, 1)
    if not isinstance(index, wp.array) or index.ndim != 2 or index.dtype != wp.int32:
        raise ValueError(
            f"index must be a 2-D warp array of int32, got {type(index).__name__} "
            f"{getattr(index, 'dtype', '')} with shape {getattr(index, 'shape', None)}"
        )
    ny, nx = index.shape
    flat = index.reshape((ny * nx,))
    forest = _Forest(flat, (ny, nx), n1, connectivity, periodic, False, index.device)
    for _ in range(n1):
        forest.step()
    return forest.island_counts()


def _thresholds(surface: Surface, depth: np.ndarray) -> tuple[np.ndarray, float]:
    z_top = float(surface.heights.max())
    return (np.float64(z_top) - depth).astype(np.float32), z_top


def _index_at_depths(surface: Surface, depth: np.ndarray, device) -> wp.array:
    """Flat int32 contact index of every pixel against arbitrary non-decreasing depths."""
    thr, _ = _thresholds(surface, depth)
    z = wp.array(surface.heights.reshape(-1), dtype=wp.float32, device=device)
    t = wp.array(thr, dtype=wp.float32, device=device)
    idx = wp.empty(z.shape[0], dtype=wp.int32, device=device)
    wp.launch(
        _ki.contact_index_search_kernel, dim=z.shape[0], inputs=[z, t], outputs=[idx], device=device
    )
    return idx


def _check_depths(depths: Any, rt: float) -> np.ndarray:
    d = np.atleast_1d(np.asarray(depths, dtype=np.float64))
    if d.ndim != 1 or d.size == 0:
        raise ValueError(f"depths must be a non-empty 1-D sequence of depths (m), got {depths!r}")
    if not np.all(np.isfinite(d)) or np.any(d < 0):
        raise ValueError(f"depths must be finite and ≥ 0 (m), got {depths!r}")
    return d


def islands_at_depths(
    surface: Surface,
    depths: Sequence[float] | np.ndarray,
    *,
    connectivity: int = 4,
    periodic: bool = False,
    device: wp.DeviceLike = None,
) -> list[Islands]:
    """Islands of the contact sets at several depths, from one forest carried across them.

    Parameters
    ----------
    surface : Surface
        The height map (m).
    depths : sequence of float
        Truncation depths ω (m), any order; a pixel is in contact when
        ``z >= float32(z_top − ω)``.
    connectivity : {4, 8}
        Neighbourhood of an island.
    periodic : bool
        Wrap the map around in x and y.
    device : str, optional
        Warp device; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    list of Islands
        In the order of ``depths``.

    Notes
    -----
    Islands only merge as ω grows. The depths are sorted, every pixel gets the index of the
    first depth at which it touches, and the pixels are added to one union-find forest depth
    after depth; at each requested depth the forest is compressed and relabelled (count → scan →
    write). The labels equal those of :func:`label_islands` on each mask.
    """
    surface = _check_surface(surface)
    connectivity = _check_connectivity(connectivity)
    d = _check_depths(depths, surface.rt)
    device = resolve_device(device)
    order = np.argsort(d, kind="stable")
    ds = d[order]
    uniq, inverse = np.unique(ds, return_inverse=True)
    ny, nx = surface.ny, surface.nx
    check_memory(ny * nx * 40, device, "island labelling at several depths")
    idx = _index_at_depths(surface, uniq, device)
    forest = _Forest(idx, (ny, nx), uniq.size, connectivity, periodic, False, device)
    found: list[Islands] = []
    for k in range(uniq.size):
        forest.step()
        labels, n = forest.labels()
        found.append(
            _islands(
                labels.reshape((ny, nx)),
                n,
                (ny, nx),
                surface.dx,
                surface.dy,
                connectivity,
                periodic,
                float(uniq[k]),
                device,
            )
        )
    out: list[Islands] = [None] * d.size  # type: ignore[list-item]
    for j, o in enumerate(order):
        out[o] = found[inverse[j]]
    return out


def islands_at_depth(
    surface: Surface,
    depth: float,
    *,
    connectivity: int = 4,
    periodic: bool = False,
    device: wp.DeviceLike = None,
) -> Islands:
    """Islands of the contact set ``z >= z_top − ω`` at one depth ω (m).

    See :func:`islands_at_depths` for the parameters.
    """
    check_range("depth", depth, 0.0, lo_open=False, unit="m")
    return islands_at_depths(
        surface, [depth], connectivity=connectivity, periodic=periodic, device=device
    )[0]


# --- slit-island analysis -------------------------------------------------------------------------


def _fit_loglog(area: np.ndarray, perimeter: np.ndarray) -> tuple[float, float, float]:
    x = np.log10(area)
    y = np.log10(perimeter)
    xm, ym = x.mean(), y.mean()
    sxx = float(np.sum((x - xm) ** 2))
    if not sxx > 0:
        return math.nan, math.nan, math.nan
    sxy = float(np.sum((x - xm) * (y - ym)))
    syy = float(np.sum((y - ym) ** 2))
    slope = sxy / sxx
    r2 = sxy * sxy / (sxx * syy) if syy > 0 else 1.0
    return slope, float(ym - slope * xm), r2


def slit_island_fit(
    islands: Islands | IslandSizes,
    *,
    min_pixels: int = MIN_PIXELS,
    min_islands: int = MIN_ISLANDS,
) -> SlitIslandFit:
    """Slit-island fit log10 L = exponent·log10 A + c over the islands at one depth (Eq. 5).

    Parameters
    ----------
    islands : Islands or IslandSizes
        Island areas A (m²) and perimeters L (m).
    min_pixels : int
        Smallest island used (pixels). Smaller islands have grid-dominated perimeters.
    min_islands : int
        Fewest islands for a fit; with fewer the result holds NaN.

    Returns
    -------
    SlitIslandFit

    Notes
    -----
    Mandelbrot's slit-island relation L ∝ A^((D−1)/2) for the sections of a self-affine surface
    of dimension D (paper Eq. 5 with D_vs): the exponent is (D − 1)/2, so D = 2·exponent + 1.
    Compact shapes give 0.5.

    References
    ----------
    Mandelbrot, Passoja & Paullay (1984), Nature 308, 721–722, doi:10.1038/308721a0.
    """
    min_pixels = check_int("min_pixels", min_pixels, 1)
    min_islands = check_int("min_islands", min_islands, 2)
    keep = np.asarray(islands.area_pixels) >= min_pixels
    n = int(keep.sum())
    if n < min_islands:
        return SlitIslandFit(math.nan, math.nan, math.nan, n, min_pixels)
    slope, c, r2 = _fit_loglog(np.asarray(islands.area)[keep], np.asarray(islands.perimeter)[keep])
    return SlitIslandFit(slope, c, r2, n, min_pixels)


# --- topology by histograms -----------------------------------------------------------------------


def _topology_hist(
    idx: wp.array, shape: tuple[int, int], n1: int, connectivity: int, periodic: bool, device
) -> np.ndarray:
    """(n1, 4) int64 cumulative [contact pixels, edges_x, edges_y, χ] at every increment."""
    ny, nx = shape
    per = int(bool(periodic))
    hist = wp.zeros((n1, 4), dtype=wp.int64, device=device)
    wp.launch(
        _ke.pixel_histogram_kernel,
        dim=(ny, nx),
        inputs=[idx, ny, nx, n1, per, int(connectivity == 4)],
        outputs=[hist],
        device=device,
    )
    if connectivity == 8:
        dim = (ny, nx) if periodic else (ny + 1, nx + 1)
        wp.launch(
            _ke.euler8_histogram_kernel,
            dim=dim,
            inputs=[idx, ny, nx, n1, per],
            outputs=[hist],
            device=device,
        )
    return np.cumsum(hist.numpy(), axis=0)  # sync point


def topology_curve(
    surface: Surface,
    n_increments: int = 200,
    *,
    max_depth: float | None = None,
    max_depth_fraction: float = 0.5,
    connectivity: int = 4,
    periodic: bool = False,
    device: wp.DeviceLike = None,
) -> TopologyCurve:
    """Total perimeter and Euler characteristic χ of the contact set at every depth, no labelling.

    Parameters
    ----------
    surface : Surface
        The height map (m).
    n_increments : int
        Number of depth increments n; depths ω_k = k·ω_max/n, k = 0..n (as :func:`truncate`).
    max_depth : float, optional
        Largest depth ω_max (m). Overrides ``max_depth_fraction``.
    max_depth_fraction : float
        ω_max as a fraction of R_t (dimensionless).
    connectivity : {4, 8}
        Connectivity of the contact set, which fixes the cell complex of χ.
    periodic : bool
        Wrap the map around in x and y.
    device : str, optional
        Warp device; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    TopologyCurve

    Notes
    -----
    One pass over the contact-index map: a boundary edge between pixels with contact indices
    a < b exists for increments a ≤ k < b (+1 at a, −1 at b); a cell of the complex exists from
    the increment at which its defining pixels are in contact (4-connectivity: the largest
    index of its pixels, on the complex of pixel centres; 8-connectivity: the smallest, on
    closed pixels). χ = V − E + F summed per increment by a difference histogram.
    """
    surface = _check_surface(surface)
    connectivity = _check_connectivity(connectivity)
    device = resolve_device(device)
    depth = depth_grid(
        surface.rt, n_increments, max_depth=max_depth, max_depth_fraction=max_depth_fraction
    )
    ny, nx = surface.ny, surface.nx
    idx = contact_index_map(surface, depth, device=device, as_warp=True).reshape((ny * nx,))
    h = _topology_hist(idx, (ny, nx), depth.size, connectivity, periodic, device)
    return TopologyCurve(
        depth=depth,
        n_contact_pixels=h[:, 0],
        contact_area=h[:, 0] * surface.pixel_area,
        edges_x=h[:, 1],
        edges_y=h[:, 2],
        total_perimeter=h[:, 1] * surface.dy + h[:, 2] * surface.dx,
        euler_characteristic=h[:, 3],
        rt=surface.rt,
        connectivity=connectivity,
        periodic=bool(periodic),
    )


# --- island curve ---------------------------------------------------------------------------------


def island_curve(
    surface: Surface,
    n_increments: int = 200,
    *,
    max_depth: float | None = None,
    max_depth_fraction: float = 0.5,
    connectivity: int = 4,
    periodic: bool = False,
    statistics: bool = True,
    min_pixels: int = MIN_PIXELS,
    snapshot_depths: Sequence[float] | None = None,
    progress: bool = False,
    device: wp.DeviceLike = None,
) -> IslandCurve:
    """Island count, sizes and slit-island exponent at every truncation depth (Fig. 8).

    Parameters
    ----------
    surface : Surface
        The height map (m).
    n_increments : int
        Number of depth increments n; depths ω_k = k·ω_max/n, k = 0..n.
    max_depth : float, optional
        Largest depth ω_max (m). Overrides ``max_depth_fraction``.
    max_depth_fraction : float
        ω_max as a fraction of R_t (dimensionless). The default 0.5 covers the island-count
        peak of the paper's surfaces.
    connectivity : {4, 8}
        Neighbourhood of an island.
    periodic : bool
        Wrap the map around in x and y.
    statistics : bool
        Also carry per-island areas and perimeters: slit-island fit and area histogram at every
        depth. ``False`` gives island counts, χ and total perimeter only (fastest).
    min_pixels : int
        Smallest island in the slit-island fits (pixels); see :data:`MIN_PIXELS`.
    snapshot_depths : sequence of float, optional
        Depths (m) at which to keep every island's area and perimeter (``sizes``); each is
        moved to the nearest increment.
    progress : bool
        Show a tqdm progress bar over the increments.
    device : str, optional
        Warp device; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    IslandCurve

    Notes
    -----
    The contact-index map (first increment at which each pixel touches) is computed once; the
    pixels are sorted by it, and one union-find forest is carried from depth to depth: at
    increment k only the pixels touching at k are united with their active neighbours. A root
    that gets hooked records the increment, and a pixel is an island root for
    idx ≤ k < link, so island counts at all depths follow from one difference histogram.
    Per-island areas and perimeters are integer accumulators on the roots, merged when roots
    are hooked. Perimeter and χ come from :func:`topology_curve`'s histograms.
    """
    surface = _check_surface(surface)
    connectivity = _check_connectivity(connectivity)
    min_pixels = check_int("min_pixels", min_pixels, 1)
    device = resolve_device(device)
    depth = depth_grid(
        surface.rt, n_increments, max_depth=max_depth, max_depth_fraction=max_depth_fraction
    )
    n1 = depth.size
    ny, nx = surface.ny, surface.nx
    check_memory(ny * nx * (44 if statistics else 32), device, "island curve")
    snaps: set[int] = set()
    if snapshot_depths is not None:
        sd = _check_depths(snapshot_depths, surface.rt)
        snaps = {int(np.argmin(np.abs(depth - v))) for v in sd}
    idx = contact_index_map(surface, depth, device=device, as_warp=True).reshape((ny * nx,))
    topo = _topology_hist(idx, (ny, nx), n1, connectivity, periodic, device)
    forest = _Forest(idx, (ny, nx), n1, connectivity, periodic, statistics, device)

    slit = np.full((n1, 2), math.nan)
    slit_n = np.zeros(n1, dtype=np.int64)
    nbins = max(1, (ny * nx).bit_length())
    hist = wp.zeros((n1, nbins), dtype=wp.int64, device=device)
    roots_count = np.zeros(n1, dtype=np.int64)
    sizes: list[IslandSizes] = []
    steps: Any = range(n1)
    if progress:
        from tqdm.auto import tqdm

        steps = tqdm(steps, desc="islands", unit="depth")
    for k in steps:
        forest.step()
        if statistics:
            roots_count[k] = forest.n_roots
            forest.area_histogram(hist, k)
            _, a, ex, ey = forest.root_stats(min_pixels)
            slit_n[k] = a.size
            if a.size >= MIN_ISLANDS:
                s, _, r2 = _fit_loglog(a * surface.pixel_area, ex * surface.dy + ey * surface.dx)
                slit[k] = s, r2
        if k in snaps:
            labels, n = forest.labels()
            sizes.append(
                _islands(
                    labels,
                    n,
                    (ny, nx),
                    surface.dx,
                    surface.dy,
                    connectivity,
                    periodic,
                    float(depth[k]),
                    device,
                    keep_labels=False,
                )
            )
    n_islands = forest.island_counts()
    if statistics and not np.array_equal(roots_count, n_islands):
        raise RuntimeError("internal error: island counts of the two bookkeepings differ")
    return IslandCurve(
        depth=depth,
        n_islands=n_islands.astype(np.int64),
        n_contact_pixels=topo[:, 0],
        contact_area=topo[:, 0] * surface.pixel_area,
        total_perimeter=topo[:, 1] * surface.dy + topo[:, 2] * surface.dx,
        euler_characteristic=topo[:, 3],
        slit_exponent=slit[:, 0],
        slit_r2=slit[:, 1],
        slit_n_islands=slit_n,
        area_histogram=hist.numpy(),
        sizes=tuple(sizes),
        rt=surface.rt,
        dx=surface.dx,
        dy=surface.dy,
        connectivity=connectivity,
        periodic=bool(periodic),
        min_pixels=min_pixels,
        params=dict(surface.params),
    )


# --- applicable depth (Table 2) -------------------------------------------------------------------


def _running(values: np.ndarray, window: int, how: str) -> np.ndarray:
    """Centred running mean or nan-median over ``window`` samples (window 1: unchanged)."""
    if window <= 1:
        return values.astype(np.float64)
    h = window // 2
    out = np.full(values.size, math.nan)
    for i in range(values.size):
        w = values[max(0, i - h) : i + h + 1]
        w = w[np.isfinite(w)]
        if w.size:
            out[i] = np.median(w) if how == "median" else w.mean()
    return out


def applicable_depth(
    curve: IslandCurve,
    *,
    exponent_tolerance: float = 0.05,
    min_islands: int = 50,
    plateau_width: float = 0.1,
    persist: float = 0.02,
    smooth: int = 5,
) -> Indicators:
    """Depths bounding the applicable range of the truncation method (Table 2, Fig. 8).

    Parameters
    ----------
    curve : IslandCurve
        Island statistics against depth (with ``statistics=True`` for the fractality depth).
    exponent_tolerance : float
        Relative drop X of the slit-island exponent below its plateau that ends fractality
        (dimensionless, 0 < X < 1).
    min_islands : int
        Fewest fitted islands (``curve.slit_n_islands``) for a depth's exponent to count; the
        first few contact spots give noisy fits.
    plateau_width : float
        Width of the plateau window, as a fraction of R_t (dimensionless).
    persist : float
        Depth span, as a fraction of R_t, over which the exponent must stay below the
        threshold for a drop to count (dimensionless); 0 accepts a single sample.
    smooth : int
        Odd window (depth samples) of a running mean of the growth rate and a running median
        of the exponent; 1 disables smoothing.

    Returns
    -------
    Indicators

    Notes
    -----
    * Maximum growth rate: the depth at which d(n/n_max)/d(ω/R_t), smoothed, is largest (the
      dashed lines of Fig. 8a).
    * Fractality depth ("the deepest depth at which the slit-island exponent stays
      constant"): only depths whose fit uses at least ``min_islands`` islands count. The
      plateau exponent β₀ is the median of the smoothed exponent over the first
      ``plateau_width``·R_t of those depths. Going deeper, the fractality depth is the last
      counted depth before the exponent first falls below (1 − X)·β₀ and stays below for
      every counted depth within the next ``persist``·R_t (the "obvious decrease" of §4.3; a
      rise does not end it, nor does a one-sample dip of a noisy fit). When it never falls,
      it is the deepest counted depth and ``fractal_depth_censored`` is set: the true value
      lies beyond the analysed range.
    * Island-count peak: the depth of the largest island count (the first one when tied).
    """
    tol = check_range("exponent_tolerance", exponent_tolerance, 0.0, 1.0)
    min_islands = check_int("min_islands", min_islands, MIN_ISLANDS)
    width = check_range("plateau_width", plateau_width, 0.0, unit="(fraction of R_t)")
    persist = check_range("persist", persist, 0.0, lo_open=False, unit="(fraction of R_t)")
    smooth = check_int("smooth", smooth, 1)
    if smooth % 2 == 0:
        raise ValueError(f"smooth must be odd, got {smooth!r}")
    frac = curve.depth_fraction
    growth = _running(curve.island_growth_rate, smooth, "mean")
    k_growth = int(np.nanargmax(growth)) if np.isfinite(growth).any() else 0
    k_peak = int(np.argmax(curve.n_islands))

    beta = np.where(curve.slit_n_islands >= min_islands, curve.slit_exponent, math.nan)
    beta = _running(beta, smooth, "median")
    beta[curve.slit_n_islands < min_islands] = math.nan
    fractal, plateau, censored = math.nan, math.nan, False
    lo = hi = math.nan
    ks = np.flatnonzero(np.isfinite(beta))
    if ks.size:
        lo = float(frac[ks[0]])
        hi = lo + width
        plateau = float(np.median(beta[ks[frac[ks] <= hi]]))
        low = beta[ks] < (1.0 - tol) * plateau
        drop = -1
        for i in np.flatnonzero(low):
            window = (frac[ks] >= frac[ks[i]]) & (frac[ks] <= frac[ks[i]] + persist + 1e-12)
            if low[window].all():
                drop = int(i)
                break
        if drop >= 0:
            fractal = float(curve.depth[ks[max(drop - 1, 0)]])
        else:
            fractal, censored = float(curve.depth[ks[-1]]), True
    return Indicators(
        max_growth_depth=float(curve.depth[k_growth]),
        fractal_depth=fractal,
        peak_depth=float(curve.depth[k_peak]),
        plateau_exponent=plateau,
        fractal_depth_censored=censored,
        rt=curve.rt,
        exponent_tolerance=tol,
        min_islands=min_islands,
        persist=persist,
        plateau_range=(lo, hi),
        smooth=smooth,
    )
