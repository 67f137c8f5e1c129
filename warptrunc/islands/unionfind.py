# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Union-find labelling of one contact mask on the device (kernels ``warptrunc.kernels.label``)
and the input checks shared by every island driver; moved verbatim from ``labelling``.
"""

from __future__ import annotations

import functools

import numpy as np
import warp as wp

from .._support.docs import fill_doc
from ..kernels import label as _kl
from ..surface import Surface
from .results import (
    SEGMENT,
)
from .settings import ISLAND_DOCS


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
            "threshold height maps with islands_at_depths"
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


@fill_doc(ISLAND_DOCS)
def label_device(
    mask: wp.array, connectivity: int = 4, *, periodic: bool = False
) -> tuple[wp.array, int]:
    """Label a device-resident contact mask; the building block of :func:`label_islands`.

    Parameters
    ----------
    mask : (ny, nx) warp array of uint8
        Contact mask, non-zero = contact, contiguous, on the device to run on.
    {connectivity}
        See the module Notes.
    {periodic}

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
    check_mask_array(mask)
    if mask.device.is_cpu:
        return _label_sequential(mask, connectivity, periodic)
    return _label_parallel(mask, connectivity, periodic)


def check_mask_array(mask: wp.array) -> None:
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
    launch = functools.partial(wp.launch, device=device)  # every pass runs on the mask's device
    if quads is None:
        quads = nx % 4 == 0 and mask.ptr % 4 == 0
    if quads:
        q = n // 4
        as4 = lambda a, dtype: wp.array(ptr=a.ptr, dtype=dtype, shape=(q,), device=device)  # noqa: E731
        mask4, parent4 = as4(flat, wp.uint32), as4(parent, wp.vec4i)
        flag4, rank4 = as4(flag, wp.vec4i), as4(rank, wp.vec4i)
        launch(_kl.init_parent4_kernel, dim=q, inputs=[mask4, flat, nx, SEGMENT], outputs=[parent4])
        launch(
            _kl.hook_flat_kernel, dim=n, inputs=[flat, ny, nx, connectivity, per], outputs=[parent]
        )
        launch(_kl.compress_flag4_kernel, dim=q, inputs=[parent4], outputs=[parent, flag4])
    else:
        dims = (ny, nx)
        launch(_kl.init_parent_kernel, dim=dims, inputs=[flat, nx, SEGMENT], outputs=[parent])
        launch(
            _kl.hook_kernel, dim=dims, inputs=[flat, ny, nx, connectivity, per], outputs=[parent]
        )
        launch(_kl.compress_flag_kernel, dim=dims, inputs=[nx], outputs=[parent, flag])
    wp.utils.array_scan(flag, rank, inclusive=True)
    n_islands = int(rank[n - 1 : n].numpy()[0])  # sync point
    # labels overwrite the scan: a root's slot is rewritten with its own value, and no thread
    # reads the slot of a non-root
    if quads:
        launch(_kl.write_labels4_kernel, dim=q, inputs=[parent4, parent, rank], outputs=[rank4])
    else:
        launch(_kl.write_labels_kernel, dim=(ny, nx), inputs=[parent, rank, nx], outputs=[rank])
    return rank.reshape((ny, nx)), n_islands
