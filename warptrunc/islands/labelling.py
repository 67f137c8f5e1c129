# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Labelling of one contact mask: validation, union-find on the device, per-island statistics."""

from __future__ import annotations

import math

import numpy as np
import warp as wp

from .._device import check_memory, resolve_device
from .._validate import check_range
from ..kernels import islands as _ki
from ..kernels import label as _kl
from ..surface import Surface
from .results import (
    SEGMENT,
    Islands,
    IslandSizes,
)

# --- validation -----------------------------------------------------------------------------------


def check_connectivity(connectivity: int) -> int:
    if isinstance(connectivity, bool) or connectivity not in (4, 8):
        raise ValueError(f"connectivity must be 4 or 8, got {connectivity!r}")
    return int(connectivity)


def check_mask(mask: np.ndarray) -> np.ndarray:
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


def check_surface(surface: Surface) -> Surface:
    if not isinstance(surface, Surface):
        raise TypeError(
            f"surface must be a warptrunc.Surface (wrap a height map with "
            f"warptrunc.from_heights(z, dx)), got {type(surface).__name__}"
        )
    return surface


def check_index_size(n: int) -> None:
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
    connectivity = check_connectivity(connectivity)
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
    check_index_size(mask.shape[0] * mask.shape[1])


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


def _label_parallel(
    mask: wp.array, connectivity: int, periodic: bool, *, quads: bool | None = None
) -> tuple[wp.array, int]:
    """Lock-free parallel union-find (the GPU path of :func:`label_device`).

    ``quads`` (default: whenever rows are a multiple of 4 pixels and the mask is 4-byte aligned)
    runs the memory-bound passes (init, compress, labels) one thread per 4 pixels, with a
    one-load fast path for background quads; the unions stay one pixel per thread.
    """
    ny, nx = mask.shape
    n = ny * nx
    device = mask.device
    flat = mask.reshape((n,))
    parent = wp.empty(n, dtype=wp.int32, device=device)
    flag = wp.empty(n, dtype=wp.int32, device=device)
    rank = wp.empty(n, dtype=wp.int32, device=device)
    per = int(bool(periodic))
    if quads is None:
        quads = nx % 4 == 0 and mask.ptr % 4 == 0
    if quads:
        q = n // 4
        as4 = lambda a, dtype: wp.array(ptr=a.ptr, dtype=dtype, shape=(q,), device=device)  # noqa: E731
        mask4, parent4 = as4(flat, wp.uint32), as4(parent, wp.vec4i)
        flag4, rank4 = as4(flag, wp.vec4i), as4(rank, wp.vec4i)
        wp.launch(
            _kl.init_parent4_kernel,
            dim=q,
            inputs=[mask4, flat, nx, SEGMENT],
            outputs=[parent4],
            device=device,
        )
        wp.launch(
            _kl.hook_flat_kernel,
            dim=n,
            inputs=[flat, ny, nx, connectivity, per],
            outputs=[parent],
            device=device,
        )
        wp.launch(
            _kl.compress_flag4_kernel,
            dim=q,
            inputs=[parent4],
            outputs=[parent, flag4],
            device=device,
        )
    else:
        dims = (ny, nx)
        wp.launch(
            _kl.init_parent_kernel,
            dim=dims,
            inputs=[flat, nx, SEGMENT],
            outputs=[parent],
            device=device,
        )
        wp.launch(
            _kl.hook_kernel,
            dim=dims,
            inputs=[flat, ny, nx, connectivity, per],
            outputs=[parent],
            device=device,
        )
        wp.launch(
            _kl.compress_flag_kernel, dim=dims, inputs=[nx], outputs=[parent, flag], device=device
        )
    wp.utils.array_scan(flag, rank, inclusive=True)
    n_islands = int(rank[n - 1 : n].numpy()[0])  # sync point
    # labels overwrite the scan: a root's slot is rewritten with its own value, and no thread
    # reads the slot of a non-root
    if quads:
        wp.launch(
            _kl.write_labels4_kernel,
            dim=q,
            inputs=[parent4, parent, rank],
            outputs=[rank4],
            device=device,
        )
    else:
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
    mask : (ny, nx) ndarray of bool or int, or warp array of uint8
        Contact mask ``m[iy, ix]``, non-zero = contact. A contiguous 2-D uint8 Warp array is
        labelled where it lives (no host pass, no copy); ``labels`` of the result then stay on
        that device until read.
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
    connectivity = check_connectivity(connectivity)
    dx = check_range("dx", dx, 0.0, unit="m")
    dy = dx if dy is None else check_range("dy", dy, 0.0, unit="m")
    if isinstance(mask, wp.array):  # device-resident mask: no host pass, no upload
        _check_mask_array(mask)
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
