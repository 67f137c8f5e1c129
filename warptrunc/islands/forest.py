# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The carried union-find forest: contact islands merged depth by depth, with per-island
statistics (kernels ``warptrunc.kernels.islands``). Driven by :mod:`warptrunc.islands.depths`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import warp as wp

from ..kernels import islands as _ki
from .unionfind import (
    check_index_size,
)

_BLOCK = 256  # threads per block of the statistics kernels (CUDA)


_STRIDE_THREADS = 1 << 16  # most threads striding over the candidate roots of one increment


def _launch_bucket(cmd: Any, start: int, count: int, k: int) -> None:
    """Launch the recorded ``cmd`` over the ``count`` pixels of bucket k from ``start`` (none
    when the bucket is empty)."""
    if count > 0:
        cmd.set_dim(count)
        cmd.set_param_by_name("start", start)
        cmd.set_param_by_name("k", k)
        cmd.launch()


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
            self.sqrt_sums = wp.zeros(n1, dtype=wp.int64, device=device)  # Σ√a, fixed point
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
        _launch_bucket(self._hook, start, count, k)
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
                    inputs=[
                        src,
                        -1,
                        self.order,
                        0,
                        0,
                        self.parent,
                        *acc,
                        0,
                        self.min_pixels,
                        self.aspect,
                        blocks,
                    ],
                    outputs=[self.root_counts, dst, self.hist, self.slit_sums, self.sqrt_sums],
                    block_dim=_BLOCK,
                    device=dev,
                    record_cmd=True,
                )
            )
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
        _launch_bucket(self._add, start, count, k)
        c = self._compact[p]
        for name, v in (("kprev", k - 1), ("start", start), ("count", count), ("k", k)):
            c.set_param_by_name(name, v)
        c.launch()
        self._parity = 1 - p

    def sqrt_area_sum(self) -> np.ndarray:
        """(n1,) float64 Σ_i √(area_i in pixels) over the islands at every increment
        (valid up to the current one; needs ``statistics``)."""
        q = self.sqrt_sums.numpy()  # sync point
        return q.astype(np.float64) / float(_ki.SQRT_SCALE)

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
