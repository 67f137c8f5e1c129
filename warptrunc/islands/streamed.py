# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Islands labelled by row bands, borders merged by union-find: maps beyond memory (or past the
2³⁰-pixel limit of the in-memory labelling).

Kernels: ``warptrunc.kernels.stream_islands`` (contact mask, per-label areas) and the in-memory
labelling of one band (``warptrunc.islands.unionfind.label_device``).

Each band is labelled on its own (labels 1..n_b in raster order of each island's first pixel);
its labels are offset by the running count into provisional global labels (Python / int64).
Only three things leave the device per band: the areas of its labels (int64, one per island),
and its first and last row of labels. Across each band border, the pairs (label above, label
below) of contact pixels that touch (4-connected: same column; 8-connected: also the diagonal
columns) are the edges of a graph whose connected components (``scipy.sparse.csgraph``) are
the islands cut by borders. Each component keeps its smallest provisional label — the one
whose first pixel comes first in raster order — and the areas of the others are added to it.
Surviving labels in increasing order are therefore the islands in raster order of their first
pixel: the order of ``scipy.ndimage.label`` and of ``warptrunc.label_islands``.

Memory: one band of heights, mask and labels on the device; O(number of islands) on the host.
``label_islands(mask, ..., band_rows=)`` (through ``label_in_bands``) also keeps each band's
labels on the host, maps them to the final labels and counts perimeters there, so it returns the
same :class:`~warptrunc.islands.Islands` as the one-piece labelling. ``streamed_islands`` keeps
counts and areas only. Not covered: periodic wrapping.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import warp as wp

from .._support.device import resolve_device
from .._support.docs import fill_doc
from .._support.progress import progress_bar
from .._support.validate import check_int
from ..kernels import stream_islands as _k
from ..kernels import wm as _kwm
from ..truncation.stream import WMBands, as_wm_spec, extremes_pass
from .results import Islands
from .settings import ISLAND_DOCS
from .unionfind import check_connectivity, label_device

__all__ = ["BandedIslands", "streamed_islands"]


@dataclass(frozen=True, eq=False)
class BandedIslands:
    """Island count and areas of one contact mask, labelled by row bands."""

    area_pixels: np.ndarray
    """(n,) int64 area of each island in pixels, islands in raster order of their first pixel
    (the labels 1..n of ``scipy.ndimage.label``)."""
    depth: float
    """Truncation depth ω of the mask (m); NaN for a given mask."""
    n_bands: int
    """Number of row bands."""
    n_border_merges: int
    """Provisional labels merged into another across band borders."""

    @property
    def n_islands(self) -> int:
        """Number of islands."""
        return int(self.area_pixels.size)

    def to_dict(self) -> dict[str, Any]:
        """One row per island.

        Returns
        -------
        dict of str to (n_islands,) ndarray
            ``label`` (int64, 1..n_islands), ``area_pixels`` (pixels) and ``depth_m`` (the
            truncation depth ω repeated, m).
        """
        return {
            "label": np.arange(1, self.n_islands + 1, dtype=np.int64),
            "area_pixels": self.area_pixels,
            "depth_m": np.full(self.n_islands, self.depth),
        }


class _BandMerger:
    """Accumulates labelled bands top to bottom; :meth:`finish` merges across the borders."""

    def __init__(self, connectivity: int):
        self.connectivity = connectivity
        self.offset = 0
        self.areas: list[np.ndarray] = []
        self.above: list[np.ndarray] = []
        self.below: list[np.ndarray] = []
        self.prev_last: np.ndarray | None = None
        self.n_bands = 0

    def add(self, labels: wp.array, n: int) -> None:
        """Add the (rows, nx) int32 labels (1..n, 0 = none) of the next band."""
        rows = labels.shape[0]
        area = wp.zeros(n + 1, dtype=wp.int64, device=labels.device)
        flat = labels.flatten()
        wp.launch(
            _k.label_area_kernel,
            dim=flat.shape[0],
            inputs=[flat],
            outputs=[area],
            device=labels.device,
        )
        self.areas.append(area.numpy()[1:].copy())  # sync point
        first = self._global(labels[0:1].numpy()[0])
        last = self._global(labels[rows - 1 : rows].numpy()[0])
        if self.prev_last is not None:
            up, lo = self.prev_last, first
            shifts = (0,) if self.connectivity == 4 else (-1, 0, 1)
            for s in shifts:  # pixel (border row above, ix) touches (row below, ix + s)
                a = up[max(0, -s) : up.size - max(0, s)]
                b = lo[max(0, s) : lo.size - max(0, -s)]
                hit = (a > 0) & (b > 0)
                self.above.append(a[hit])
                self.below.append(b[hit])
        self.prev_last = last
        self.offset += n
        self.n_bands += 1

    def _global(self, row: np.ndarray) -> np.ndarray:
        row = row.astype(np.int64)
        return np.where(row > 0, row + self.offset, 0)

    def finish(self, depth: float) -> BandedIslands:
        area = np.concatenate(self.areas) if self.areas else np.zeros(0, np.int64)
        keep = np.ones(area.size, dtype=bool)
        root_of = np.arange(area.size + 1, dtype=np.int64)  # provisional label → its island's
        merged = 0
        if self.above and sum(a.size for a in self.above):
            from scipy.sparse import coo_matrix
            from scipy.sparse.csgraph import connected_components

            a, b = np.concatenate(self.above), np.concatenate(self.below)
            nodes = np.unique(np.concatenate([a, b]))  # sorted provisional labels
            ia, ib = np.searchsorted(nodes, a), np.searchsorted(nodes, b)
            graph = coo_matrix((np.ones(ia.size, np.int8), (ia, ib)), shape=(nodes.size,) * 2)
            n_comp, comp = connected_components(graph, directed=False)
            root = np.full(n_comp, np.iinfo(np.int64).max, dtype=np.int64)
            np.minimum.at(root, comp, nodes)  # the smallest label: first in raster order
            node_root = root[comp]
            moved = nodes != node_root
            np.add.at(area, node_root[moved] - 1, area[nodes[moved] - 1])
            keep[nodes[moved] - 1] = False
            root_of[nodes[moved]] = node_root[moved]
            merged = int(moved.sum())
        rank = np.zeros(area.size + 1, dtype=np.int64)
        rank[np.flatnonzero(keep) + 1] = np.arange(1, int(keep.sum()) + 1)
        self.final = rank[root_of]  # provisional label → final label 1..n (0 stays 0)
        return BandedIslands(area[keep], float(depth), self.n_bands, merged)


def _band_rows(band_rows: int, ny: int) -> int:
    return check_int("band_rows", band_rows, 1, ny)


@fill_doc(ISLAND_DOCS)
def label_in_bands(
    m: np.ndarray, dx: float, dy: float, connectivity: int, band_rows: int, device: wp.Device
) -> Islands:
    """The banded path of :func:`warptrunc.label_islands` (checked mask, resolved device).

    Each band is labelled on the device, its labels are kept on the host with the running
    offset, and after the border merge the provisional labels are mapped to the final 1..n (raster
    order of first pixel). Perimeters are then counted on the host from the label map: an edge
    between a contact pixel and a non-contact pixel (or the map border), dy long across x and dx
    long across y, as the in-memory path counts them.

    Parameters
    ----------
    m : (ny, nx) ndarray
        Contact mask (non-zero: contact), already checked by the caller.
    dx, dy : float
        Pixel spacings along x and y (m).
    {connectivity}
        Already checked.
    band_rows : int
        Rows of ``m`` per band, in [1, ny].
    device : warp.context.Device
        The resolved Warp device that labels each band.

    Returns
    -------
    Islands
        Same labels (int32, raster order of first pixel), areas (m²) and perimeters (m) as the
        in-memory path; ``periodic=False`` and ``depth`` NaN.

    Raises
    ------
    ValueError
        ``band_rows`` is not an integer in [1, ny].
    """

    rows = _band_rows(band_rows, m.shape[0])
    merger = _BandMerger(connectivity)
    labels = np.zeros(m.shape, dtype=np.int64)
    for r0 in range(0, m.shape[0], rows):
        band = wp.array(np.ascontiguousarray(m[r0 : r0 + rows], dtype=np.uint8), device=device)
        lab, n = label_device(band, connectivity)
        offset = merger.offset
        merger.add(lab, n)
        h = lab.numpy()  # sync point
        labels[r0 : r0 + rows] = np.where(h > 0, h.astype(np.int64) + offset, 0)
    found = merger.finish(math.nan)
    labels = merger.final[labels].astype(np.int32)
    n = found.n_islands
    ex, ey = _edge_counts(labels, n)
    return Islands(
        labels=labels,
        n_islands=n,
        area_pixels=found.area_pixels,
        area=found.area_pixels * (dx * dy),
        perimeter=ex * dy + ey * dx,
        edges_x=ex,
        edges_y=ey,
        dx=dx,
        dy=dy,
        connectivity=connectivity,
        periodic=False,
        depth=math.nan,
    )


def _edge_counts(labels: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(n,) int64 boundary edges of islands 1..n crossed along x and along y (bounded map)."""
    pad = np.pad(labels > 0, 1)  # outside the map: no contact
    inner = pad[1:-1, 1:-1]
    counts = []
    for shifts in (((1, 0), (1, 2)), ((0, 1), (2, 1))):  # x: left, right; y: below, above
        total = np.zeros(n + 1, dtype=np.int64)
        for dy_, dx_ in shifts:
            nb = pad[dy_ : dy_ + labels.shape[0], dx_ : dx_ + labels.shape[1]]
            total += np.bincount(labels[inner & ~nb], minlength=n + 1)
        counts.append(total[1:])
    return counts[0], counts[1]


@fill_doc(ISLAND_DOCS)
def streamed_islands(
    spec_or_params,
    depths: Sequence[float] | np.ndarray,
    *,
    band_rows: int | None = None,
    connectivity: int = 4,
    device: wp.DeviceLike = None,
    progress: bool = True,
) -> list[BandedIslands]:
    """Islands of a WM surface at several truncation depths, never holding the map.

    Parameters
    ----------
    spec_or_params : WMTerms or mapping
        The surface, as for :func:`warptrunc.truncation.truncate` with ``stream=True``.
    depths : sequence of float
        Truncation depths ω ≥ 0 (m); a pixel is in contact when ``z >= float32(z_top − ω)``,
        as in :func:`warptrunc.islands.islands_at_depths`.
    band_rows : int, optional
        Rows per band (rounded up to the product's row block); see ``truncate_streamed``.
    {connectivity}
    device : str, optional
        Warp device; see :func:`warptrunc.resolve_device`.
    progress : bool
        Report the bands on stderr (a bar on a terminal, else lines).

    Returns
    -------
    list of BandedIslands
        One per depth, in the order given.

    Notes
    -----
    Pass 1 finds the extremes (``warptrunc.stream``); pass 2 regenerates each band once and,
    for every depth, thresholds, labels and hands it to that depth's border merger.
    """

    spec = as_wm_spec(spec_or_params)
    connectivity = check_connectivity(connectivity)
    depth = np.asarray(depths, dtype=np.float64).reshape(-1)
    if depth.size == 0 or not np.all(np.isfinite(depth)) or np.any(depth < 0):
        raise ValueError(f"depths must be finite depths ≥ 0 (m), got {depths!r}")
    device = resolve_device(device)
    bands = WMBands(spec, device, band_rows)
    _lo, _hi, scale, _zlo, zhi = extremes_pass(bands, progress)
    thr = (np.float64(zhi) - depth).astype(np.float32)
    mergers = [_BandMerger(connectivity) for _ in depth]
    mask = wp.empty(bands.buffer.shape, dtype=wp.uint8, device=device)
    with progress_bar(
        total=len(bands.bands), desc="stream islands (bands)", unit="band", enabled=progress
    ) as bar:
        for r0, r1 in bands.bands:
            z, _, _ = bands.raw(r0, r1)
            wp.launch(_kwm.affine_kernel, dim=z.shape, inputs=[z, bands.c0, scale], device=device)
            m = mask[: r1 - r0]
            for t, merger in zip(thr, mergers, strict=True):
                wp.launch(
                    _k.contact_mask_kernel,
                    dim=z.size,
                    inputs=[z.flatten(), float(t)],
                    outputs=[m.flatten()],
                    device=device,
                )
                merger.add(*label_device(m, connectivity))
            bar.update()
    return [mg.finish(d) for mg, d in zip(mergers, depth, strict=True)]
