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
from .._progress import progress_bar
from .._validate import check_int, check_range
from ..kernels import islands as _ki
from ..surface import Surface
from ..truncation.curve import contact_index_map, depth_grid, surface_device, surface_range
from .fits import slit_from_sums
from .labelling import (
    _islands,
    check_connectivity,
    check_index_size,
    check_surface,
)
from .results import (
    MIN_PIXELS,
    IslandCurve,
    Islands,
    IslandSizes,
)
from .topology import topology_hist

# --- carried forest across depths -----------------------------------------------------------------

_BLOCK = 256  # threads per block of the statistics kernels (CUDA)
_STRIDE_THREADS = 1 << 16  # most threads striding over the candidate roots of one increment


class Forest:
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
        check_index_size(n)
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
            # roots live on the device only: a double buffer as large as the final contact set,
            # their number per increment in ``root_counts`` (never read back during the loop)
            cap = max(1, int(self.first[n1]))
            self.roots = wp.empty(cap, dtype=wp.int32, device=device)
            self.roots_next = wp.empty(cap, dtype=wp.int32, device=device)
            self.root_counts = wp.zeros(n1, dtype=wp.int32, device=device)
            self.hist = wp.zeros((n1, max(1, n.bit_length())), dtype=wp.int64, device=device)
            self.slit_sums = wp.zeros((n1, 6), dtype=wp.float64, device=device)
            self.min_pixels, self.aspect = 1, 1.0

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

    def _record_statistics(self) -> None:
        """Record the statistics launches once (replayed with new scalars at every increment,
        which costs far less host time than a full ``wp.launch``): merge and compaction for
        both parities of the roots double buffer, and the pixel additions. The merge and the
        compaction have a fixed grid that strides over the candidates counted on the device."""
        dev = self.device
        if dev.is_cuda:
            threads, blocks = _STRIDE_THREADS, _STRIDE_THREADS // _BLOCK
        else:  # a CPU launch runs its threads one after the other: one lane does it all
            threads = blocks = 1
        acc = [self.area, self.edges_x, self.edges_y]
        bufs = (self.roots, self.roots_next)
        self._merge, self._compact = [], []
        for src, dst in (bufs, bufs[::-1]):
            self._merge.append(
                wp.launch(
                    _ki.merge_linked_stride_kernel,
                    dim=threads,
                    inputs=[src, self.root_counts, -1, self.order, 0, 0, self.link, 0, threads],
                    outputs=[self.parent, *acc],
                    device=dev,
                    record_cmd=True,
                )
            )
            self._compact.append(
                wp.launch_tiled(
                    _ki.compact_roots_kernel,
                    dim=blocks,
                    inputs=[src, -1, self.order, 0, 0, self.parent, *acc, 0, self.min_pixels,
                            self.aspect, blocks],
                    outputs=[self.root_counts, dst, self.hist, self.slit_sums],
                    block_dim=_BLOCK,
                    device=dev,
                    record_cmd=True,
                )
            )  # fmt: skip
        self._add = wp.launch(
            _ki.add_pixels_kernel,
            dim=1,
            inputs=[self.order, 0, self.idx, 0, self.ny, self.nx, self.periodic],
            outputs=[self.parent, *acc],
            device=dev,
            record_cmd=True,
        )
        self._parity = 0

    def _update_statistics(self, k: int, start: int, count: int) -> None:
        """Merge the accumulators of the roots hooked at k, add the new pixels, compact the
        surviving roots and add them to row k of the histogram and the slit sums: all on the
        device, no read-back (the number of roots stays in ``root_counts``)."""
        if int(self.first[k + 1]) == 0:  # nothing in contact yet (host-known)
            return
        if not hasattr(self, "_merge"):
            self._record_statistics()
        p = self._parity
        m = self._merge[p]
        for name, v in (("kprev", k - 1), ("start", start), ("count", count), ("k", k)):
            m.set_param_by_name(name, v)
        m.launch()
        if count > 0:
            a = self._add
            a.set_dim(count)
            a.set_param_by_name("start", start)
            a.set_param_by_name("k", k)
            a.launch()
        c = self._compact[p]
        for name, v in (("kprev", k - 1), ("start", start), ("count", count), ("k", k)):
            c.set_param_by_name(name, v)
        c.launch()
        self._parity = 1 - p

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
    connectivity = check_connectivity(connectivity)
    n1 = check_int("n_depths", n_depths, 1)
    if not isinstance(index, wp.array) or index.ndim != 2 or index.dtype != wp.int32:
        raise ValueError(
            f"index must be a 2-D warp array of int32, got {type(index).__name__} "
            f"{getattr(index, 'dtype', '')} with shape {getattr(index, 'shape', None)}"
        )
    ny, nx = index.shape
    check_index_size(ny * nx)  # before the flat view (Warp refuses 1-D arrays ≥ 2³¹)
    flat = index.reshape((ny * nx,))
    forest = Forest(flat, (ny, nx), n1, connectivity, periodic, False, index.device)
    for _ in range(n1):
        forest.step()
    return forest.island_counts()


def _index_at_depths(surface: Surface, depth: np.ndarray, device) -> wp.array:
    """Flat int32 contact index of every pixel against arbitrary non-decreasing depths."""
    z = surface.device_heights(device).flatten()  # no host round trip for device surfaces
    _lo, z_top = surface_range(surface, z, device)
    thr = (np.float64(z_top) - depth).astype(np.float32)
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
        Warp device; default: where a device-resident surface lives, else
        :func:`warptrunc.resolve_device`'s choice.

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
    surface = check_surface(surface)
    connectivity = check_connectivity(connectivity)
    d = _check_depths(depths, surface.rt)
    device = resolve_device(surface_device(surface, device))
    order = np.argsort(d, kind="stable")
    ds = d[order]
    uniq, inverse = np.unique(ds, return_inverse=True)
    ny, nx = surface.ny, surface.nx
    check_index_size(ny * nx)  # before allocating
    check_memory(ny * nx * 40, device, "island labelling at several depths")
    idx = _index_at_depths(surface, uniq, device)
    forest = Forest(idx, (ny, nx), uniq.size, connectivity, periodic, False, device)
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
        _ = found[-1].labels  # host copy now: one depth's labels on the device at a time
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
        Warp device; default: where a device-resident surface lives, else
        :func:`warptrunc.resolve_device`'s choice.

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
    are hooked. The list of roots, its length, the log2 area histogram and the slit-island sums
    (n, Σx, Σy, Σx², Σxy, Σy² of x = log10 A, y = log10 L over the islands ≥ ``min_pixels``,
    float64) stay on the device and are read back once after the last increment: no increment
    waits for the host. The fit is the least-squares fit of :func:`slit_island_fit` from those
    sums (equal to it to ~1e-12 relative). Perimeter and χ come from :func:`topology_curve`'s
    histograms.
    """
    surface = check_surface(surface)
    connectivity = check_connectivity(connectivity)
    min_pixels = check_int("min_pixels", min_pixels, 1)
    device = resolve_device(surface_device(surface, device))
    depth = depth_grid(
        surface.rt, n_increments, max_depth=max_depth, max_depth_fraction=max_depth_fraction
    )
    n1 = depth.size
    ny, nx = surface.ny, surface.nx
    check_index_size(ny * nx)  # before allocating
    check_memory(ny * nx * (52 if statistics else 32), device, "island curve")
    snaps: set[int] = set()
    if snapshot_depths is not None:
        sd = _check_depths(snapshot_depths, surface.rt)
        snaps = {int(np.argmin(np.abs(depth - v))) for v in sd}
    idx = contact_index_map(surface, depth, device=device, as_warp=True).reshape((ny * nx,))
    topo = topology_hist(idx, (ny, nx), n1, connectivity, periodic, device)
    forest = Forest(idx, (ny, nx), n1, connectivity, periodic, statistics, device)

    if statistics:
        forest.min_pixels, forest.aspect = min_pixels, surface.dy / surface.dx
    sizes: list[IslandSizes] = []
    steps: Any = range(n1)
    if progress:
        steps = progress_bar(steps, desc="islands", unit="depth")
    for k in steps:
        forest.step()
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
    nbins = max(1, (ny * nx).bit_length())
    slit = np.full((n1, 2), math.nan)
    slit_n = np.zeros(n1, dtype=np.int64)
    if statistics:  # the only read-backs of the statistics: once, after the last increment
        roots_count = forest.root_counts.numpy().astype(np.int64)
        if not np.array_equal(roots_count, n_islands):
            raise RuntimeError("internal error: island counts of the two bookkeepings differ")
        area_hist = forest.hist.numpy()
        slit, slit_n = slit_from_sums(forest.slit_sums.numpy())
    else:
        area_hist = np.zeros((n1, nbins), dtype=np.int64)
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
        area_histogram=area_hist,
        sizes=tuple(sizes),
        rt=surface.rt,
        dx=surface.dx,
        dy=surface.dy,
        connectivity=connectivity,
        periodic=bool(periodic),
        min_pixels=min_pixels,
        params=dict(surface.params),
    )
