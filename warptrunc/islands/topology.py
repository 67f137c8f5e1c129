# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Total perimeter and Euler characteristic χ of the contact set at every depth, without
labelling, by difference histograms over the contact-index map.

Kernels: ``warptrunc.kernels.euler`` (global-atomic kernels for the CPU, block-private
shared-memory kernels for CUDA). Used by :func:`topology_curve` and inside every
:func:`warptrunc.islands.island_curve`.
"""

from __future__ import annotations

import numpy as np
import warp as wp

from .._support.device import resolve_device
from .._support.docs import fill_doc
from ..kernels import euler as _ke
from ..surface import Surface
from ..truncation.curve import contact_index_device, depth_grid, surface_device
from .results import TopologyCurve
from .settings import ISLAND_DOCS
from .unionfind import check_connectivity, check_index_size, check_surface

__all__ = ["topology_curve"]

TOPOLOGY_KERNEL = "auto"
"""``"block"``: count the topology histograms per block in shared memory, then once per block
into the global histogram; ``"atomic"``: global atomics per pixel; ``"auto"``: block on CUDA,
atomic on the CPU (where a tile block is one thread). Both give the same integer histograms.
Measured on an H100, 10240², 201 increments to 0.5·R_t, 4-connectivity: 60 ms with global
atomics."""


def _topology_hist_blocks(
    idx: wp.array, shape: tuple[int, int], n1: int, connectivity: int, per: int, device
) -> np.ndarray:
    """(n1, 4) int64 difference histogram by the block-private kernels of ``kernels.euler``."""
    ny, nx = shape
    hist = wp.zeros(int(_ke.HIST_CELLS), dtype=wp.int64, device=device)

    bd = 256 if device.is_cuda else 1  # a CPU tile block runs one lane

    def launch(kernel, n: int, args: list) -> None:
        blocks = max(1, min(-(-n // bd), 8 * device.sm_count if device.is_cuda else 64))
        chunk = -(-n // blocks)
        wp.launch_tiled(
            kernel,
            dim=blocks,
            inputs=[*args, chunk, -(-chunk // bd)],
            outputs=[hist],
            block_dim=bd,
            device=device,
        )

    launch(
        _ke.pixel_histogram_block_kernel,
        ny * nx,
        [idx, ny, nx, n1, per, int(connectivity == 4)],
    )
    if connectivity == 8:
        vy, vx = (ny, nx) if per else (ny + 1, nx + 1)
        launch(_ke.euler8_histogram_block_kernel, vy * vx, [idx, ny, nx, n1, per, vy, vx])
    return hist.numpy().reshape(-1, 4)[:n1]  # sync point


def topology_hist(
    idx: wp.array, shape: tuple[int, int], n1: int, connectivity: int, periodic: bool, device
) -> np.ndarray:
    """(n1, 4) int64 cumulative [contact pixels, edges_x, edges_y, χ] at every increment."""
    ny, nx = shape
    per = int(bool(periodic))
    mode = (
        TOPOLOGY_KERNEL if TOPOLOGY_KERNEL != "auto" else ("block" if device.is_cuda else "atomic")
    )
    if mode == "block" and n1 <= _ke.HIST_BINS:
        return np.cumsum(_topology_hist_blocks(idx, shape, n1, connectivity, per, device), axis=0)
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


@fill_doc(ISLAND_DOCS)
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
    {surface}
    {n_increments}
        The depths are ω_k = k·ω_max/n, k = 0..n (as :func:`truncate`).
    {max_depth}
    {max_depth_fraction}
        0.5 by default, as :func:`island_curve` (the topology is read over the same depths as
        the island count).
    {connectivity}
        It fixes the cell complex of χ.
    {periodic}
    {device}

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
    surface = check_surface(surface)
    connectivity = check_connectivity(connectivity)
    device = resolve_device(surface_device(surface, device))
    depth = depth_grid(
        surface.Rt, n_increments, max_depth=max_depth, max_depth_fraction=max_depth_fraction
    )
    ny, nx = surface.ny, surface.nx
    check_index_size(ny * nx)  # before allocating
    idx = contact_index_device(surface, depth, device).reshape((ny * nx,))
    h = topology_hist(idx, (ny, nx), depth.size, connectivity, periodic, device)
    return TopologyCurve(
        depth=depth,
        n_contact_pixels=h[:, 0],
        contact_area=h[:, 0] * surface.pixel_area,
        edges_x=h[:, 1],
        edges_y=h[:, 2],
        total_perimeter=h[:, 1] * surface.dy + h[:, 2] * surface.dx,
        euler_characteristic=h[:, 3],
        Rt=surface.Rt,
        connectivity=connectivity,
        periodic=bool(periodic),
    )
