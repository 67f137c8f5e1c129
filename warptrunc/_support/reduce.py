# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Device reductions of height maps: the height range (min z, max z) of a float32 Warp array.

Kernels: ``warptrunc.kernels.reduce``. Used by WM synthesis (``warptrunc.wm``) and the
truncation drivers (``warptrunc.truncation``), so it sits below both.
"""

from __future__ import annotations

import numpy as np
import warp as wp

from .device import as_device
from .limits import flat_row_bands
from ..kernels import reduce as _kr

__all__ = ["height_range"]

_REDUCE_LANES = 65536


def height_range(z: wp.array, device: wp.DeviceLike = None) -> tuple[float, float]:
    """Return (min z, max z) (m) of a float32 Warp array, by a device reduction.

    ``z`` is 1-D, or 2-D (reduced by row bands of fewer than 2³¹ pixels: any size works).

    Parameters
    ----------
    z : warp.array of float32
        Heights (m), 1-D or 2-D, on ``device``.
    device : str or warp.context.Device, optional
        The device of ``z``; a resolved :class:`warp.context.Device` is used as is, anything
        else goes through :func:`warptrunc.resolve_device`.

    Returns
    -------
    tuple of (float, float)
        Lowest and highest height (m), float32 values as Python floats.

    """

    device = as_device(device)  # resolved once by the public caller
    if z.ndim == 2:
        parts = [_height_range_flat(v, device) for _r0, _r1, v in flat_row_bands(z)]
        return min(p[0] for p in parts), max(p[1] for p in parts)
    return _height_range_flat(z, device)


def _height_range_flat(z: wp.array, device: wp.context.Device) -> tuple[float, float]:
    n = z.shape[0]
    if device.is_cuda and n >= _kr.TILE:
        full = n // _kr.TILE
        lo = wp.empty(full, dtype=wp.float32, device=device)
        hi = wp.empty(full, dtype=wp.float32, device=device)
        wp.launch_tiled(
            _kr.min_max_tile_kernel,
            dim=full,
            inputs=[z],
            outputs=[lo, hi],
            block_dim=256,
            device=device,
        )
        parts_lo, parts_hi = [lo.numpy()], [hi.numpy()]  # sync point
        if n > full * _kr.TILE:  # the remainder (< TILE values) on the host
            tail = z[full * _kr.TILE :].numpy()
            parts_lo.append(tail)
            parts_hi.append(tail)
        return float(min(p.min() for p in parts_lo)), float(max(p.max() for p in parts_hi))
    out = wp.array(np.array([np.inf, -np.inf], dtype=np.float32), device=device)
    lanes = min(_REDUCE_LANES, max(1, n))
    chunk = 0 if device.is_cuda else -(-max(1, n) // lanes)  # CPU: contiguous chunks per lane
    wp.launch(_kr.min_max_kernel, dim=lanes, inputs=[z, lanes, chunk], outputs=[out], device=device)
    lo_v, hi_v = out.numpy()  # sync point
    return float(lo_v), float(hi_v)
