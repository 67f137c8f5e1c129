# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation under a finite punch: Eq. 2 on the pixels of one punch disk, read at given loads.

The truncated set at depth ω is {pixels of the disk with z ≥ z_top − ω}, z_top the highest pixel
inside the disk (where the punch first touches). The counts come from the same Warp histogram
kernels as :func:`warptrunc.truncate` (``warptrunc.kernels.truncation``), run on the disk's
pixels only, with float32 heights and float32 thresholds, so they equal
``numpy.count_nonzero(z_disk >= t_k)`` exactly. Stiffness and load follow
:func:`warptrunc.stiffness_curve`: k = β'·(2/√π)·E*·√A_c (Eq. 2) and F = ∫k dω by the cumulative
trapezoidal rule; here β' = 1 and the apparent area is the punch's, A = πd²/4. Truncation is
the paper's model of the sample: it reads the sample's heights alone, never a tilted or rough
punch face (:attr:`PunchWindow.surface_disk_heights`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import warp as wp

from .._support.device import resolve_device
from .._support.docs import SHARED_DOCS, fill_doc
from .._support.validate import check_int
from ..stiffness.curve import cumulative_load
from ..truncation.curve import TruncationCurve, curve_from_histogram, depth_grid, depth_thresholds
from ..truncation.curve import histogram_bands as _histogram
from .punch import PunchWindow

__all__ = ["disk_truncation", "truncation_at_loads"]


@dataclass(frozen=True)
class _DiskGrid:
    """What :func:`curve_from_histogram` reads of a grid: the disk as an n × 1 'map'."""

    pixel_area: float
    apparent_area: float
    nx: int
    ny: int = 1


def disk_truncation(
    window: PunchWindow,
    n_increments: int = 1000,
    *,
    max_depth: float | None = None,
    device: wp.DeviceLike = None,
) -> TruncationCurve:
    """Truncated area A_c(ω) of the pixels a punch can touch, at n + 1 equally spaced depths.

    Parameters
    ----------
    window : PunchWindow
        The punch and the heights under it (:func:`~warptrunc.indent.punch.punch_window`).
    n_increments : int
        Number of depth increments n.
    max_depth : float, optional
        Largest depth ω_max (m); default the height range of the disk (every disk pixel in
        contact at ω_max).
    device : str or warp Device, optional
        Warp device of the histogram kernels.

    Returns
    -------
    TruncationCurve
        ``n_contact_pixels[k]`` = count of disk pixels with z ≥ z_top − ω_k (float32 compare),
        ``contact_area`` (m²), ``apparent_area`` = the punch area A (m²), ``n_pixels`` = the
        pixels of the disk, ``z_top`` and ``Rt`` those of the disk (m).

    Raises
    ------
    ValueError
        ``n_increments`` out of range, or a flat disk without ``max_depth``.
    """
    n = check_int("n_increments", n_increments, 1, 10_000_000)
    dev = resolve_device(device)
    z32 = np.ascontiguousarray(window.surface_disk_heights, dtype=np.float32)
    lo, hi = float(z32.min()), float(z32.max())
    rng = float(np.float64(hi) - np.float64(lo))
    if max_depth is None and not rng > 0:
        raise ValueError("the heights under the punch are flat: give max_depth (m)")
    depth = depth_grid(rng, n, max_depth=rng if max_depth is None else max_depth)
    z = wp.array(z32, dtype=wp.float32, device=dev)
    t, _lo, _hi, thr, inv_step = depth_thresholds(z, depth, dev, (lo, hi))
    hist = _histogram(z, t, hi, inv_step, dev, deep=True)
    grid = _DiskGrid(window.pixel_area, window.area, int(z32.size))
    return curve_from_histogram(hist, depth, thr, (lo, hi), grid)


@fill_doc(SHARED_DOCS)
def truncation_at_loads(
    window: PunchWindow,
    loads: Any,
    contact_modulus: float,
    *,
    n_increments: int = 1000,
    device: wp.DeviceLike = None,
) -> dict[str, np.ndarray]:
    """Eq. 2 truncation of a punch disk read at given loads: depth, area and stiffness.

    Parameters
    ----------
    window : PunchWindow
        The punch and the heights under it.
    loads : (m,) array_like
        Loads F (N), > 0.
    contact_modulus : float
        E* (Pa).
    n_increments : int
        Depth increments of the truncation curve, from 0 to just past the depth where the
        load reaches max(loads).
    {warp_device_obj}

    Returns
    -------
    dict of str to (m,) ndarray
        ``depth`` ω (m) where F(ω) = F; ``n_contact`` (pixels) at the grid depth at or below ω;
        ``contact_area`` A_c (m²) and ``stiffness`` k = (2/√π)E*√A_c (N/m) interpolated
        linearly in ω between grid depths (the curve that F integrates).

    Notes
    -----
    Two truncation passes: one over the disk's whole height range (with
    ``n_increments`` increments) finds the depth ω_F where F(ω) first reaches max(loads); the
    second resolves [0, 1.05·ω_F] with ``n_increments`` increments, so that the smallest loads
    are resolved too. Between grid depths ω is interpolated linearly in F. Past the whole
    height range every disk pixel touches, k is constant and F grows linearly.
    """
    loads = np.asarray(loads, dtype=np.float64)
    c = (2.0 / math.sqrt(math.pi)) * float(contact_modulus)

    def curve(max_depth: float | None):
        tc = disk_truncation(window, n_increments, max_depth=max_depth, device=device)
        k = c * np.sqrt(tc.contact_area)
        return tc, k, cumulative_load(k, tc.depth)

    tc, k, f = curve(
        None if float(np.ptp(window.surface_disk_heights)) > 0 else window.pixel_size[0]
    )
    fmax = float(loads.max())
    if f[-1] >= fmax:
        j = int(np.searchsorted(f, fmax))
        w_f = float(tc.depth[min(j, tc.depth.size - 1)])
        tc, k, f = curve(max(1.05 * w_f, tc.depth[1]))
    depth = np.interp(loads, f, tc.depth)
    beyond = loads > f[-1]
    if beyond.any():  # every pixel of the disk touches: F grows as k_full·ω
        depth[beyond] = tc.depth[-1] + (loads[beyond] - f[-1]) / k[-1]
    idx = np.clip(np.searchsorted(tc.depth, depth, side="right") - 1, 0, tc.depth.size - 1)
    return {
        "depth": depth,
        "n_contact": tc.n_contact_pixels[idx],
        "contact_area": np.interp(depth, tc.depth, tc.contact_area),
        "stiffness": np.interp(depth, tc.depth, k),
    }
