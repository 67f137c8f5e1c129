# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Several WM surfaces per launch: batched generation and truncation for light sweep cases.

A light case (no fractal dimensions, no elastic solve) of a small grid is a few hundred
microseconds of GPU work but about 1.5 ms of launches, allocations and synchronisations when
run alone (measured on an H100 at 512² and 2048²). :class:`WMBatch` generates B surfaces of
one grid in one launch per step (tables, tile GEMM, extremes, scaling, histogram), with device
buffers kept from batch to batch and two host synchronisations per batch.

Every step evaluates the same float32/float64 expressions as the single-surface path
(:func:`warptrunc.wm.wm_surface` with ``method="tile"``, then :func:`warptrunc.truncate`), in
the same order within each tile, so the counts and curves equal those of
:func:`~warptrunc.sweep.engines.compute_case` on the same device (checked in the tests).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import warp as wp

from .._device import check_memory
from ..kernels import reduce as _kr
from ..kernels import truncation as _kt
from ..kernels import wm as _kw
from ..truncation.curve import TruncationCurve, curve_from_histogram, depth_grid, host_thresholds
from ..wm import height_scale, pad_to
from ..wm_params import wm_spec
from .grid import Case, SweepOptions

__all__ = ["BATCH_PIXELS", "MAX_BATCH", "WMBatch", "batch_size"]

BATCH_PIXELS = 1 << 27
"""Most pixels generated in one batch (count): 2²⁷ float32 heights = 512 MiB."""
MAX_BATCH = 64
"""Most surfaces in one batch (count)."""


def batch_size(options: SweepOptions, device: wp.context.Device, *, force: bool = False) -> int:
    """Surfaces per batch for ``options`` on ``device``: 1 means one case at a time.

    Parameters
    ----------
    options : SweepOptions
        The sweep's options.
    device : warp.context.Device
        The resolved device.
    force : bool
        Batch on the CPU too (the tests do; a CPU gains nothing from batching).

    Returns
    -------
    int
        ⌊``BATCH_PIXELS``/(nx·ny)⌋ clipped to [1, ``MAX_BATCH``] when batching applies: a CUDA
        device (or ``force``), light cases (no ``fractal_methods``, no ``bem_fractions``),
        both sides multiples of the GEMM tile (128 pixels) and a truncation of at most 255
        increments; else 1.
    """
    o = options
    nx, ny = (o.n, o.n) if isinstance(o.n, int) else o.n
    if not (device.is_cuda or force) or o.fractal_methods or o.bem_fractions:
        return 1
    if nx % int(_kw.TILE_N) or ny % int(_kw.TILE_M) or o.increments + 1 > int(_kt.HIST_BINS):
        return 1
    return max(1, min(MAX_BATCH, BATCH_PIXELS // (nx * ny)))


class WMBatch:
    """Device buffers for up to ``size`` WM surfaces of one grid, reused from batch to batch.

    Parameters
    ----------
    options : SweepOptions
        The grid (``n``, ``L``, ``Wr``, ``M``, ``gamma``, ``Wc``, ``cutoff``) and the
        truncation (``increments``, ``max_depth``, ``max_depth_fraction``).
    size : int
        Surfaces per batch (≥ 1).
    device : warp.context.Device
        The resolved device.

    Raises
    ------
    MemoryError
        The buffers would not fit the device's free memory.
    """

    def __init__(self, options: SweepOptions, size: int, device: wp.context.Device):
        o = self.options = options
        ref = wm_spec(2.5, o.Wr, L=o.L, n=o.n, Rt=1.0, M=o.M, gamma=o.gamma, Wc=o.Wc,
                      cutoff=o.cutoff)  # fmt: skip
        self.device, self.size = device, int(size)
        self.nx, self.ny, self.T = ref.nx, ref.ny, ref.n_terms
        self.K = pad_to(2 * self.T, _kw.TILE_K)
        self.grid = SimpleNamespace(
            nx=ref.nx, ny=ref.ny, pixel_area=ref.dx * ref.dy,
            apparent_area=(ref.nx * ref.dx) * (ref.ny * ref.dy),
        )  # fmt: skip
        self.dx, self.dy = ref.dx, ref.dy
        B, nx, ny, K = self.size, self.nx, self.ny, self.K
        n1 = o.increments + 1
        check_memory(4 * B * (nx * ny + K * (nx + ny)) + 8 * B * n1, device,
                     f"a batch of {B} WM surfaces of {nx}×{ny}")  # fmt: skip
        self.kx = wp.array(ref.kx, dtype=wp.float64, device=device)
        self.ky = wp.array(ref.ky, dtype=wp.float64, device=device)
        self.p = wp.zeros((B * ny, K), dtype=wp.float32, device=device)
        self.q = wp.zeros((B * K, nx), dtype=wp.float32, device=device)
        self.z = wp.empty((B * ny, nx), dtype=wp.float32, device=device)
        self.hist = wp.zeros((B, n1), dtype=wp.int64, device=device)
        tiles = (B * nx * ny) // int(_kr.TILE)
        self.lo = wp.empty(tiles, dtype=wp.float32, device=device)
        self.hi = wp.empty(tiles, dtype=wp.float32, device=device)

    def heights(self, i: int) -> np.ndarray:
        """Host copy of surface ``i`` of the last batch: (ny, nx) float32 heights (m)."""
        return self.z[i * self.ny : (i + 1) * self.ny].numpy()

    def truncate(self, cases: list[Case]) -> list[TruncationCurve]:
        """Generate and truncate the surfaces of ``cases`` (at most ``size``) in one batch.

        Parameters
        ----------
        cases : list of Case
            D, δ = R_t/W_r and seed per surface (R_t = δ·W_r, m).

        Returns
        -------
        list of TruncationCurve
            One per case, in order, as :func:`warptrunc.truncate` of that case's
            :func:`warptrunc.wm_surface` would give on this device. The heights stay in the
            batch's buffer until the next call (:meth:`heights`).

        Raises
        ------
        ValueError
            A case's parameters are out of range or its surface is flat (the caller retries
            the batch case by case, so that each case records its own error).
        """
        o, dev = self.options, self.device
        b = len(cases)
        if not 1 <= b <= self.size:
            raise ValueError(f"a batch holds 1 to {self.size} cases, got {b}")
        specs = [
            wm_spec(c.D, o.Wr, L=o.L, n=o.n, Rt=c.delta * o.Wr, M=o.M, gamma=o.gamma, Wc=o.Wc,
                    cutoff=o.cutoff, seed=c.seed)
            for c in cases
        ]  # fmt: skip
        nx, ny, T, K = self.nx, self.ny, self.T, self.K
        alpha = wp.array(np.stack([s.alpha for s in specs]), dtype=wp.float64, device=dev)
        w = wp.array(np.stack([s.w for s in specs]), dtype=wp.float64, device=dev)
        p, q, z = self.p[: b * ny], self.q[: b * K], self.z[: b * ny]
        wp.launch(_kw.column_table_batch_kernel, dim=(b, T, nx),
                  inputs=[self.kx, alpha, self.dx, K], outputs=[q], device=dev)  # fmt: skip
        wp.launch(_kw.row_table_batch_kernel, dim=(b, ny, T),
                  inputs=[self.ky, w, self.dy, ny], outputs=[p], device=dev)  # fmt: skip
        tm = ny // int(_kw.TILE_M)
        wp.launch_tiled(_kw.wm_tile_gemm_batch_kernel, dim=(b * tm, nx // int(_kw.TILE_N)),
                        inputs=[p, q, tm], outputs=[z], block_dim=256, device=dev)  # fmt: skip
        raw = self._extremes(z, b)  # sync point
        c0 = np.array([np.sum(s.w * np.cos(s.alpha)) for s in specs])
        scale = np.array([height_scale(s, lo, hi) for s, (lo, hi) in zip(specs, raw, strict=True)])
        wp.launch(_kw.affine_batch_kernel, dim=(b * ny, nx),
                  inputs=[z, ny, wp.array(c0, dtype=wp.float64, device=dev),
                          wp.array(scale, dtype=wp.float64, device=dev)], device=dev)  # fmt: skip
        # exact float32 extremes of the scaled maps, as warptrunc.wm._generate records them
        ext = [tuple(float(np.float32((np.float64(v) + c0[i]) * scale[i])) for v in raw[i])
               for i in range(b)]  # fmt: skip
        depths, thrs, inv = [], [], []
        for lo, hi in ext:
            d = depth_grid(float(np.float64(hi) - np.float64(lo)), o.increments,
                           max_depth=o.max_depth, max_depth_fraction=o.max_depth_fraction)  # fmt: skip
            thr, inv_step = host_thresholds(d, hi)
            depths.append(d)
            thrs.append(thr)
            inv.append(inv_step)
        hist = self.hist[:b]
        hist.zero_()
        z4 = wp.array(ptr=z.ptr, dtype=wp.vec4, shape=(b, nx * ny // 4), device=dev)
        wp.launch(
            _kt.contact_histogram_batch_kernel, dim=(b, nx * ny // 4),
            inputs=[z4, wp.array(np.concatenate(thrs), dtype=wp.float32, device=dev),
                    wp.array(np.array([e[1] for e in ext], np.float32), device=dev),
                    wp.array(np.array(inv, np.float32), device=dev)],
            outputs=[hist], device=dev,
        )  # fmt: skip
        h = hist.numpy()  # sync point
        return [curve_from_histogram(h[i], depths[i], thrs[i], ext[i], self.grid) for i in range(b)]

    def _extremes(self, z: wp.array, b: int) -> list[tuple[float, float]]:
        """(min, max) of each of the first ``b`` raw maps (float32 values as Python floats)."""
        per = self.nx * self.ny
        if self.device.is_cuda:  # whole tiles: nx·ny is a multiple of 128² = 2·TILE
            tiles = b * per // int(_kr.TILE)
            lo, hi = self.lo[:tiles], self.hi[:tiles]
            wp.launch_tiled(_kr.min_max_tile_kernel, dim=tiles, inputs=[z.flatten()],
                            outputs=[lo, hi], block_dim=256, device=self.device)  # fmt: skip
            lo_h, hi_h = lo.numpy().reshape(b, -1), hi.numpy().reshape(b, -1)
            return [(float(lo_h[i].min()), float(hi_h[i].max())) for i in range(b)]
        from .._reduce import height_range

        return [height_range(z[i * self.ny : (i + 1) * self.ny], self.device) for i in range(b)]

