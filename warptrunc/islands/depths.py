# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Islands across truncation depths: the carried union-find forest, topology histograms and the island curve."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import warp as wp

from .._device import check_memory, resolve_device
from .._validate import check_int, check_range
from ..kernels import euler as _ke
from ..kernels import islands as _ki
from ..surface import Surface
from ..truncation import contact_index_map, depth_grid
from .fits import _fit_loglog
from .labelling import (
    _check_connectivity,
    _check_index_size,
    _check_surface,
    _islands,
)
from .results import (
    MIN_ISLANDS,
    MIN_PIXELS,
    IslandCurve,
    Islands,
    IslandSizes,
    TopologyCurve,
)

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
    _check_index_size(ny * nx)  # before the flat view (Warp refuses 1-D arrays ≥ 2³¹)
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
    _check_index_size(ny * nx)  # before allocating
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
    _check_index_size(ny * nx)  # before allocating
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
    _check_index_size(ny * nx)  # before allocating
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
