# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Labelling of one contact mask: validation, union-find on the device, per-island statistics."""

from __future__ import annotations

import math

import numpy as np
import warp as wp

from .._support.device import check_memory, resolve_device
from .._support.docs import fill_doc
from .._support.validate import check_range
from ..kernels import islands as _ki
from .results import (
    SEGMENT,
    Islands,
    IslandSizes,
)
from .settings import ISLAND_DOCS
from .streamed import label_in_bands
from .unionfind import (
    check_connectivity,
    check_index_size,
    check_mask,
    check_mask_array,
    label_device,
)

# --- validation -----------------------------------------------------------------------------------


# --- labelling of one mask ------------------------------------------------------------------------


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
    nseg = (nx + SEGMENT - 1) // SEGMENT
    wp.launch(
        _ki.island_stats_kernel,
        dim=(ny, nseg),
        inputs=[labels.reshape((ny * nx,)), ny, nx, int(bool(periodic)), SEGMENT],
        outputs=[acc[0], acc[1], acc[2]],
        device=device,
    )
    a = acc.numpy()[:, 1:]  # sync point
    return a[0], a[1], a[2]


def islands_from_labels(
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
        labels=labels.reshape((ny, nx)),  # copied to the host only when read
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


@fill_doc(ISLAND_DOCS)
def label_islands(
    mask: np.ndarray,
    dx: float = 1.0,
    dy: float | None = None,
    *,
    connectivity: int = 4,
    periodic: bool = False,
    band_rows: int | None = None,
    device: wp.DeviceLike = None,
) -> Islands:
    """Label the islands of a contact mask and measure their areas and perimeters.

    Parameters
    ----------
    mask : (ny, nx) ndarray of bool or int, or warp array of uint8
        Contact mask ``m[iy, ix]``, non-zero = contact. A contiguous 2-D uint8 Warp array is
        labelled where it lives (no host pass, no copy); ``labels`` of the result then stay on
        that device until read.
    dx : float
        Pixel spacing along x (m). The default 1 makes areas and perimeters pixel units.
    dy : float, optional
        Pixel spacing along y (m); ``dx`` when omitted.
    {connectivity}
        4 (default): pixels touching at a corner only are separate islands (see the module
        Notes).
    {periodic}
    band_rows : int, optional
        Label by row bands of this many rows, 1 ≤ band_rows ≤ ny, holding one band on the
        device at a time (masks beyond device memory or past the 2³⁰-pixel limit of the
        one-piece labelling); the borders are merged by union-find on the host and the labels,
        areas and perimeters equal the one-piece result. Host NumPy masks only; not with
        ``periodic``.
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
    connectivity = check_connectivity(connectivity)
    dx = check_range("dx", dx, 0.0, unit="m")
    dy = dx if dy is None else check_range("dy", dy, 0.0, unit="m")
    if band_rows is not None:
        if periodic or isinstance(mask, wp.array):
            raise ValueError(
                "band_rows labels a host (NumPy) mask of a bounded map; got "
                + ("periodic=True" if periodic else "a Warp array")
            )
        return label_in_bands(
            check_mask(mask), dx, dy, connectivity, band_rows, resolve_device(device)
        )
    if isinstance(mask, wp.array):  # device-resident mask: no host pass, no upload
        check_mask_array(mask)
        device = mask.device if device is None else resolve_device(device)
        shape = (int(mask.shape[0]), int(mask.shape[1]))
        check_index_size(shape[0] * shape[1])  # before allocating
        check_memory(shape[0] * shape[1] * 28, device, "island labelling")
        mw = mask if mask.device == device else mask.to(device)
    else:
        m = check_mask(mask)
        device = resolve_device(device)
        shape = m.shape
        check_index_size(m.size)  # before allocating
        check_memory(m.size * 29, device, "island labelling")
        mw = wp.array(m, dtype=wp.uint8, device=device)
    labels, n = label_device(mw, connectivity, periodic=periodic)
    return islands_from_labels(labels, n, shape, dx, dy, connectivity, periodic, math.nan, device)
