# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Several WM surfaces per launch: batched generation and truncation for light sweep cases.

A light case (no fractal dimensions, no elastic solve) of a small grid is a few hundred
microseconds of GPU work but about 1.5 ms of launches, allocations and synchronisations when
run alone (measured on an H100 at 512² and 2048²). :class:`WMBatch` generates B surfaces of
one grid in one launch per step (tables, tile GEMM, extremes, scaling, histogram), with device
buffers kept from batch to batch and two host waits per batch, each on an event of that
batch only (so a second batch can be queued while the host fits the first).

Every step evaluates the same float32/float64 expressions as the single-surface path
(:func:`warptrunc.wm.wm_surface` with ``method="tile"``, then :func:`warptrunc.truncate`), in
the same order within each tile, so the counts and curves equal those of
:func:`~warptrunc.sweep.engines.compute_case` on the same device (checked in the tests).
"""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

import numpy as np
import warp as wp

from .._support.device import check_memory
from .._support.reduce import height_range
from .._support.validate import check_int, check_range
from ..kernels import reduce as _kr
from ..kernels import truncation as _kt
from ..kernels import wm as _kw
from ..truncation.curve import TruncationCurve, curve_from_histogram, depth_grid
from ..wm import pad_to
from ..wm_params import wm_phases, wm_weights
from .grid import Case
from .options import SweepOptions

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
    slots : int
        Batches that may be in flight at once (≥ 1), each with its own buffers: 2 lets
        :meth:`submit` queue the next batch while the host fits the last one.

    Raises
    ------
    MemoryError
        The buffers would not fit the device's free memory.

    Notes
    -----
    A batch goes through :meth:`submit` (tables, product and the tile extremes, launched;
    returns at once on a GPU), :meth:`scale` (waits for the extremes, then launches the
    scaling and the histogram) and :meth:`collect` (waits for the histogram, returns the
    curves). On a GPU the small inputs travel through pinned host buffers and the results come
    back by asynchronous copies and events, so the host never waits for work queued after the
    batch it asks about. Every launch, copy and event goes to ``device``'s own stream, whatever
    Warp's default device is (a Dask worker pinned to cuda:1 keeps cuda:0 as its default).
    :meth:`truncate` does the three steps at once.
    """

    def __init__(
        self, options: SweepOptions, size: int, device: wp.context.Device, *, slots: int = 1
    ):
        o = self.options = options
        ref = o.wm_spec(2.5, 1.0).terms()
        self.device, self.size = device, int(size)
        self.nx, self.ny, self.T = ref.nx, ref.ny, ref.n_terms
        self.M, self.n_f = ref.M, ref.n_max + 1
        self.nn = np.tile(np.arange(self.n_f, dtype=np.float64), ref.M)
        self.K = pad_to(2 * self.T, _kw.TILE_K)
        self.grid = SimpleNamespace(
            nx=ref.nx,
            ny=ref.ny,
            pixel_area=ref.dx * ref.dy,
            apparent_area=(ref.nx * ref.dx) * (ref.ny * ref.dy),
        )
        self.dx, self.dy = ref.dx, ref.dy
        B, nx, ny, K, T = self.size, self.nx, self.ny, self.K, self.T
        n1 = o.increments + 1
        tiles = (B * nx * ny) // int(_kr.TILE) if device.is_cuda else 0
        per_slot = 4 * B * (nx * ny + K * (nx + ny)) + 8 * B * (n1 + 2 * T) + 8 * tiles
        check_memory(slots * per_slot, device, f"{slots} batch(es) of {B} WM surfaces of {nx}×{ny}")
        self.kx = wp.array(ref.kx, dtype=wp.float64, device=device)
        self.ky = wp.array(ref.ky, dtype=wp.float64, device=device)
        pinned = device.is_cuda

        def pair(shape, dtype):  # (device array, host staging array)
            d = wp.zeros(shape, dtype=dtype, device=device)
            return d, (
                wp.zeros(shape, dtype=dtype, device="cpu", pinned=pinned) if pinned else None
            )

        self._slots = []
        for _ in range(max(1, int(slots))):
            b = SimpleNamespace(
                p=wp.zeros((B * ny, K), dtype=wp.float32, device=device),
                q=wp.zeros((B * K, nx), dtype=wp.float32, device=device),
                z=wp.empty((B * ny, nx), dtype=wp.float32, device=device),
                alpha=pair((B, T), wp.float64),
                w=pair((B, T), wp.float64),
                c0=pair(B, wp.float64),
                scale=pair(B, wp.float64),
                t=pair(B * n1, wp.float32),
                top=pair(B, wp.float32),
                inv=pair(B, wp.float32),
                hist=pair((B, n1), wp.int64),
                lo=pair(max(tiles, 1), wp.float32),
                hi=pair(max(tiles, 1), wp.float32),
                event=wp.Event(device) if device.is_cuda else None,
                job=None,
            )
            self._slots.append(b)
        self._last = None

    def heights(self, i: int) -> np.ndarray:
        """Host copy of one surface of the last collected batch.

        Parameters
        ----------
        i : int
            Position of the surface in that batch.

        Returns
        -------
        (ny, nx) float32 ndarray
            Its heights (m), as :func:`warptrunc.wm_surface` would give on this device.
        """
        z = self._last.z if self._last is not None else self._slots[0].z
        return z[i * self.ny : (i + 1) * self.ny].numpy()

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
            batch's buffer until the buffer is used again (:meth:`heights`).

        Raises
        ------
        ValueError
            A case's parameters are out of range or its surface is flat (the caller retries
            the batch case by case, so that each case records its own error).
        """
        job = self.submit(cases)
        self.scale(job)
        return self.collect(job)

    def submit(self, cases: list[Case]) -> Any:
        """Queue the tables, product and tile extremes of ``cases`` on a free slot.

        Parameters
        ----------
        cases : list of Case
            At most ``size`` cases.

        Returns
        -------
        object
            The slot now holding the batch, for :meth:`scale` and :meth:`collect`.

        Raises
        ------
        ValueError
            A wrong number of cases, or a case's D, R_t or seed out of range.
        RuntimeError
            Every slot holds a batch not yet collected.
        """
        o, dev = self.options, self.device
        b = len(cases)
        if not 1 <= b <= self.size:
            raise ValueError(f"a batch holds 1 to {self.size} cases, got {b}")
        for c in cases:  # the checks of wm_spec that depend on the case
            check_range("D", c.D, 2.0, 3.0)
            check_range("Rt", c.delta * o.Wr, 0.0, unit="m")
            check_int("seed", c.seed, 0)
        s = next((x for x in self._slots if x.job is None), None)
        if s is None:
            raise RuntimeError("every slot holds a batch: collect one first")
        nx, ny, T, K = self.nx, self.ny, self.T, self.K
        alpha = np.stack([wm_phases(c.seed, self.M, self.n_f) for c in cases])
        w = np.stack([wm_weights(c.D, o.gamma, self.nn) for c in cases])
        self._put(s.alpha, alpha)
        self._put(s.w, w)
        p, q, z = s.p[: b * ny], s.q[: b * K], s.z[: b * ny]
        wp.launch(
            _kw.column_table_batch_kernel,
            dim=(b, T, nx),
            inputs=[self.kx, s.alpha[0][:b], self.dx, K],
            outputs=[q],
            device=dev,
        )
        wp.launch(
            _kw.row_table_batch_kernel,
            dim=(b, ny, T),
            inputs=[self.ky, s.w[0][:b], self.dy, ny],
            outputs=[p],
            device=dev,
        )
        tm = ny // int(_kw.TILE_M)
        wp.launch_tiled(
            _kw.wm_tile_gemm_batch_kernel,
            dim=(b * tm, nx // int(_kw.TILE_N)),
            inputs=[p, q, tm],
            outputs=[z],
            block_dim=256,
            device=dev,
        )
        if dev.is_cuda:  # whole tiles: nx·ny is a multiple of 128² = 2·TILE
            tiles = b * nx * ny // int(_kr.TILE)
            wp.launch_tiled(
                _kr.min_max_tile_kernel,
                dim=tiles,
                inputs=[z.flatten()],
                outputs=[s.lo[0][:tiles], s.hi[0][:tiles]],
                block_dim=256,
                device=dev,
            )
            self._get(s.lo, tiles)
            self._get(s.hi, tiles)
            dev.stream.record_event(s.event)  # this device's stream, not the default's
        s.job = SimpleNamespace(cases=cases, alpha=alpha, w=w, ext=None, depths=None, thr=None)
        return s

    def scale(self, s: Any) -> None:
        """Wait for the extremes of a batch, then queue its scaling and truncation histogram.

        Parameters
        ----------
        s : object
            The slot returned by :meth:`submit`.

        Raises
        ------
        ValueError
            A surface of the batch is flat (its slot is then free again).
        """
        o, dev, j = self.options, self.device, s.job
        b, ny, nx = len(j.cases), self.ny, self.nx
        z = s.z[: b * ny]
        if dev.is_cuda:
            wp.synchronize_event(s.event)
            tiles = b * nx * ny // int(_kr.TILE)
            lo_h = s.lo[1].numpy()[:tiles].reshape(b, -1)
            hi_h = s.hi[1].numpy()[:tiles].reshape(b, -1)
            raw = [(float(lo_h[i].min()), float(hi_h[i].max())) for i in range(b)]
        else:
            raw = [height_range(z[i * ny : (i + 1) * ny], dev) for i in range(b)]
        c0 = np.sum(j.w * np.cos(j.alpha), axis=1)
        scale = np.empty(b)
        for i, (c, (lo, hi)) in enumerate(zip(j.cases, raw, strict=True)):
            if not hi > lo:  # as warptrunc.wm.height_scale
                s.job = None
                raise ValueError("the WM sum is flat on this grid; cannot scale to Rt")
            scale[i] = c.delta * o.Wr / (hi - lo)
        self._put(s.c0, c0)
        self._put(s.scale, scale)
        wp.launch(
            _kw.affine_batch_kernel,
            dim=(b * ny, nx),
            inputs=[z, ny, s.c0[0][:b], s.scale[0][:b]],
            device=dev,
        )
        # exact float32 extremes of the scaled maps, as warptrunc.wm._generate records them
        j.ext = [
            tuple(float(np.float32((np.float64(v) + c0[i]) * scale[i])) for v in raw[i])
            for i in range(b)
        ]
        # depth_grid and the thresholds of truncation.curve.depth_thresholds for every
        # surface at once (the same float64 operations, element by element); depth_grid
        # checks the options on the first
        n, n1 = o.increments, o.increments + 1
        lo_hi = np.array(j.ext, dtype=np.float64)
        rt = lo_hi[:, 1] - lo_hi[:, 0]
        first = depth_grid(
            float(rt[0]), n, max_depth=o.max_depth, max_depth_fraction=o.max_depth_fraction
        )
        wmax = np.full(b, first[-1]) if o.max_depth is not None else o.max_depth_fraction * rt
        if not np.all(wmax > 0):
            s.job = None
            raise ValueError("a height map of the batch is flat: nothing to truncate")
        depths = np.arange(n1, dtype=np.float64)[None, :] * (wmax / n)[:, None]
        thr = (lo_hi[:, 1:2] - depths).astype(np.float32)
        inv = 1.0 / (depths[:, -1] / n)
        j.depths, j.thr = list(depths), list(thr)
        self._put(s.t, thr)
        self._put(s.top, lo_hi[:, 1].astype(np.float32))
        self._put(s.inv, inv.astype(np.float32))
        hist = s.hist[0][:b]
        hist.zero_()
        z4 = wp.array(ptr=z.ptr, dtype=wp.vec4, shape=(b, nx * ny // 4), device=dev)
        wp.launch(
            _kt.contact_histogram_batch_kernel,
            dim=(b, nx * ny // 4),
            inputs=[z4, s.t[0][: b * n1], s.top[0][:b], s.inv[0][:b]],
            outputs=[hist],
            device=dev,
        )
        if dev.is_cuda:
            self._get(s.hist, b * n1)
            dev.stream.record_event(s.event)  # this device's stream, not the default's

    def collect(self, s: Any) -> list[TruncationCurve]:
        """Wait for the histogram of a batch and return its truncation curves.

        Parameters
        ----------
        s : object
            The slot returned by :meth:`submit`, after :meth:`scale`.

        Returns
        -------
        list of TruncationCurve
            One per case of the batch, in order; the slot is free again.
        """
        j, b = s.job, len(s.job.cases)
        if self.device.is_cuda:
            wp.synchronize_event(s.event)
            h = s.hist[1].numpy()[:b]
        else:
            h = s.hist[0].numpy()[:b]
        s.job, self._last = None, s
        return [
            curve_from_histogram(h[i], j.depths[i], j.thr[i], j.ext[i], self.grid) for i in range(b)
        ]

    def release(self, s: Any) -> None:
        """Free the slot of a batch that failed between :meth:`submit` and :meth:`collect`.

        Parameters
        ----------
        s : object
            The slot returned by :meth:`submit`.
        """
        s.job = None

    def _put(self, pair, values: np.ndarray) -> None:
        """values → the device array of ``pair`` (through its pinned staging array on a GPU)."""
        d, h = pair
        flat = np.ascontiguousarray(values).reshape(-1)
        if h is None:
            d.flatten()[: flat.size].assign(flat)
            return
        h.numpy().reshape(-1)[: flat.size] = flat
        wp.copy(d, h, count=flat.size)

    def _get(self, pair, count: int) -> None:
        """Queue the copy of the first ``count`` values of ``pair``'s device array to its
        pinned host array (asynchronous)."""
        wp.copy(pair[1], pair[0], count=count)
