# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Islands across truncation depths: counts, statistics at chosen depths and the island curve
(the carried forest is in :mod:`warptrunc.islands.forest`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import warp as wp

from .._support.device import check_memory, resolve_device
from .._support.docs import fill_doc
from .._support.progress import progress_bar
from .._support.validate import check_int
from ..kernels import islands as _ki
from ..surface import Surface
from ..truncation.curve import (
    contact_index_device,
    depth_grid,
    surface_device,
    surface_range,
)
from ..truncation.settings import TruncationSettings
from .fits import slit_from_sums
from .forest import Forest
from .labelling import islands_from_labels
from .results import IslandCurve, Islands, IslandSizes
from .settings import ISLAND_DOCS, ISLANDS_TRUNCATION, IslandSettings
from .topology import topology_hist
from .unionfind import check_connectivity, check_index_size, check_surface

# --- carried forest across depths -----------------------------------------------------------------


@fill_doc(ISLAND_DOCS)
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
    {connectivity}
    {periodic}

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


def _check_depths(depths: Any, Rt: float) -> np.ndarray:
    d = np.atleast_1d(np.asarray(depths, dtype=np.float64))
    if d.ndim != 1 or d.size == 0:
        raise ValueError(f"depths must be a non-empty 1-D sequence of depths (m), got {depths!r}")
    if not np.all(np.isfinite(d)) or np.any(d < 0):
        raise ValueError(f"depths must be finite and ≥ 0 (m), got {depths!r}")
    return d


@fill_doc(ISLAND_DOCS)
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
    {surface}
    depths : sequence of float
        Truncation depths ω (m), any order; a pixel is in contact when
        ``z >= float32(z_top − ω)``.
    {label_options}

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
    d = _check_depths(depths, surface.Rt)
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
            islands_from_labels(
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


# --- island curve ---------------------------------------------------------------------------------


@fill_doc(ISLAND_DOCS)
def island_curve(
    surface: Surface,
    *,
    truncation: TruncationSettings = ISLANDS_TRUNCATION,
    settings: IslandSettings | None = None,
    progress: bool = False,
    device: wp.DeviceLike = None,
) -> IslandCurve:
    """Island count, sizes and slit-island exponent at every truncation depth (Fig. 8).

    Parameters
    ----------
    {surface}
    truncation : TruncationSettings
        The depths ω_k = k·ω_max/n, k = 0..n (``increments`` n, ``max_depth_fraction``,
        ``max_depth``) and the island ``connectivity``; its other fields are the stiffness
        model's and are not read. Default :data:`~warptrunc.islands.settings.ISLANDS_TRUNCATION`:
        200 increments to 0.5·R_t, not :func:`truncate`'s 0.1·R_t: the island count rises and
        falls again deeper than the stiffness fit reads, and 0.5 covers its peak on the paper's
        surfaces (Fig. 8).
    settings : IslandSettings, optional
        Periodic boundaries, per-island statistics (slit-island fit, area histogram and
        Σ√A_i, ``sqrt_area_sum``, at every depth; without them island counts, χ and total
        perimeter only, fastest), the smallest fitted island and the snapshot depths (as
        fractions of R_t, each moved to the nearest increment) whose every island's area and
        perimeter is kept in ``sizes`` (:class:`~warptrunc.islands.settings.IslandSettings`;
        its defaults when None).
    progress : bool
        Report the increments on stderr (a bar on a terminal, else lines).
    {device}

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
    float64) and Σ√A_i over all islands (int64 fixed point, exact and order-free) stay on the
    device and are read back once after the last increment: no increment
    waits for the host. The fit is the least-squares fit of :func:`slit_island_fit` from those
    sums (equal to it to ~1e-12 relative). Perimeter and χ come from :func:`topology_curve`'s
    histograms.

    Examples
    --------
    >>> from warptrunc.islands import IslandSettings, island_curve
    >>> from warptrunc.truncation import TruncationSettings
    >>> t = TruncationSettings(increments=50, max_depth_fraction=0.3)
    >>> c = island_curve(surface, truncation=t, settings=IslandSettings(snapshots=None))  # doctest: +SKIP
    """
    settings = IslandSettings() if settings is None else settings
    surface = check_surface(surface)
    connectivity = check_connectivity(truncation.connectivity)
    periodic, statistics = settings.periodic, settings.statistics
    min_pixels = settings.min_pixels
    device = resolve_device(surface_device(surface, device))
    depth = depth_grid(
        surface.Rt,
        truncation.increments,
        max_depth=truncation.max_depth,
        max_depth_fraction=truncation.max_depth_fraction,
    )
    n1 = depth.size
    ny, nx = surface.ny, surface.nx
    check_index_size(ny * nx)  # before allocating
    check_memory(ny * nx * (52 if statistics else 32), device, "island curve")
    snaps: set[int] = set()
    if statistics and settings.snapshots is not None:
        sd = np.array([f * surface.Rt for f in settings.snapshots], dtype=np.float64)
        snaps = {int(np.argmin(np.abs(depth - v))) for v in sd}
    idx = contact_index_device(surface, depth, device).reshape((ny * nx,))
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
                islands_from_labels(
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
        sqrt_area_sum = forest.sqrt_area_sum() * math.sqrt(surface.pixel_area)
    else:
        sqrt_area_sum = None
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
        Rt=surface.Rt,
        dx=surface.dx,
        dy=surface.dy,
        connectivity=connectivity,
        periodic=bool(periodic),
        min_pixels=min_pixels,
        params=dict(surface.params),
        sqrt_area_sum=sqrt_area_sum,
        apparent_area=float(surface.apparent_area),
    )
