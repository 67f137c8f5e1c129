# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation analysis: truncated (contact) area A_c(ω) at increasing depth ω from the top.

Kernels: ``warptrunc.kernels.truncation`` (histogram, contact index) and
``warptrunc.kernels.reduce`` (min/max).

Depths are ω_k = k·ω_max/n, k = 0..n. A pixel is in contact at depth ω_k when
z ≥ z_top − ω_k, with z_top = max z; the comparison is made in float32 against float32
thresholds, exactly as ``numpy.count_nonzero(z >= t_k)`` would.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import warp as wp

from .._support.device import resolve_device
from .._support.docs import fill_doc
from .._support.limits import flat_row_bands, row_bands
from .._support.reduce import height_range
from .._support.validate import MAX_INCREMENTS, check_int, check_range
from ..kernels import truncation as _k
from ..surface import Surface
from .settings import TRUNCATION_DOCS

__all__ = [
    "TruncationCurve",
    "contact_histogram",
    "contact_index_device",
    "contact_index_map",
    "depth_grid",
    "height_range",
]


@dataclass(frozen=True, eq=False)
class TruncationCurve:
    """Truncated area against truncation depth for one height map."""

    depth: np.ndarray
    """(n+1,) float64 truncation depths ω_k (m), ω_0 = 0."""
    threshold: np.ndarray
    """(n+1,) float32 height thresholds z_top − ω_k (m) used in the comparison."""
    n_contact_pixels: np.ndarray
    """(n+1,) int64 number of pixels with z ≥ threshold."""
    contact_area: np.ndarray
    """(n+1,) float64 truncated area A_c = pixel area × n_contact_pixels (m²)."""
    apparent_area: float
    """Apparent area A = Lx·Ly (m²)."""
    pixel_area: float
    """Area of one pixel (m²)."""
    n_pixels: int
    """Total number of pixels."""
    z_top: float
    """Highest height max z (m)."""
    Rt: float
    """Peak-to-valley height R_t of the map (m)."""

    @property
    def area_fraction(self) -> np.ndarray:
        """(n+1,) float64 A_c/A (dimensionless)."""
        return self.n_contact_pixels / float(self.n_pixels)

    def to_dict(self) -> dict[str, Any]:
        """Columns as 1-D arrays (one row per depth).

        Returns
        -------
        dict of str to (n+1,) ndarray
            ``depth_m`` ω (m), ``depth_fraction_of_Rt`` ω/R_t (dimensionless; zeros for a flat
            map), ``n_contact_pixels`` (int64), ``contact_area_m2`` A_c (m²) and
            ``area_fraction`` A_c/A (dimensionless).
        """
        return {
            "depth_m": self.depth,
            "depth_fraction_of_Rt": self.depth / self.Rt if self.Rt > 0 else self.depth * 0,
            "n_contact_pixels": self.n_contact_pixels,
            "contact_area_m2": self.contact_area,
            "area_fraction": self.area_fraction,
        }


_BLOCKS_PER_SM = 8  # persistent blocks of the GPU histogram kernel
GPU_HISTOGRAM = "auto"
"""GPU histogram kernel: ``"auto"``, ``"block"`` (block-private shared-memory histogram),
``"vec4"`` (global atomics, 4 pixels per thread) or ``"pixel"`` (one thread per pixel).

``"auto"`` takes ``"vec4"`` when ω_max ≤ ``DEEP_FRACTION``·R_t (few pixels touch, so global
atomics rarely contend) and ``"block"`` otherwise. Measured on an H100, 10240², 201 bins,
``truncate`` with the generator's extremes: vec4 0.42 / 13.0 / 21.4 ms and block 0.54 / 1.09 /
1.34 ms at ω_max = 0.1 / 0.5 / 1.0·R_t. Every kernel gives the same integer counts; only the
speed depends on the choice."""
DEEP_FRACTION = 0.25


def contact_histogram(
    z: wp.array, t: wp.array, z_top: float, inv_step: float, device, *, deep: bool = True
) -> wp.array:
    """Histogram of contact indices of the flattened float32 map ``z`` (int64, on ``device``).

    Entry k (k < len(t)) counts the pixels whose first contact is at threshold ``t[k]``; the
    array may be longer than ``t`` (the extra entries are zero). No host synchronisation.
    ``deep``: whether many pixels are expected to touch (picks the GPU kernel under
    ``GPU_HISTOGRAM = "auto"``).

    Parameters
    ----------
    z : warp.array of float32
        The flattened heights (m), 1-D, fewer than 2³¹ pixels; read 4 at a time when its
        address is 16-byte aligned.
    t : warp.array of float32
        Non-increasing thresholds t_k = z_top − ω_k (m), on ``device``.
    z_top : float
        Highest height of the map (m).
    inv_step : float
        1/Δω, the inverse depth step (1/m), for the first guess of each pixel's index
        (corrected exactly against ``t``); 0 when there is no step.
    device : warp.context.Device
        The resolved device of ``z`` and ``t``.
    deep : bool
        Many pixels expected to touch (see above).

    Returns
    -------
    warp.array of int64
        Counts per contact index, length len(t) or more (``HIST_BINS`` with the block kernel),
        on ``device``; pixels that never touch are not counted.
    """
    n = z.shape[0]
    n1 = t.shape[0]
    n4 = n // 4 if z.ptr % 16 == 0 else 0
    mode = GPU_HISTOGRAM if device.is_cuda else "vec4"
    if mode == "auto":
        mode = "block" if deep else "vec4"
    if mode == "block" and (n1 > _k.HIST_BINS or n4 == 0):
        mode = "vec4"
    hist = wp.zeros(
        max(n1, int(_k.HIST_BINS)) if mode == "block" else n1, dtype=wp.int64, device=device
    )
    if mode == "pixel" or n4 == 0:
        n4 = 0
    elif mode == "block":
        z4 = wp.array(ptr=z.ptr, dtype=wp.vec4, shape=(n4,), device=device)
        blocks = max(1, min(-(-n4 // 256), _BLOCKS_PER_SM * device.sm_count))
        chunk = -(-n4 // blocks)
        wp.launch_tiled(
            _k.contact_histogram_block_kernel,
            dim=blocks,
            inputs=[z4, chunk, -(-chunk // 256), t, z_top, inv_step],
            outputs=[hist],
            block_dim=256,
            device=device,
        )
    else:
        z4 = wp.array(ptr=z.ptr, dtype=wp.vec4, shape=(n4,), device=device)
        wp.launch(
            _k.contact_histogram_vec4_kernel,
            dim=n4,
            inputs=[z4, t, z_top, inv_step],
            outputs=[hist],
            device=device,
        )
    if 4 * n4 < n:  # the remainder (or everything, unaligned), one thread per pixel
        wp.launch(
            _k.contact_histogram_kernel,
            dim=n - 4 * n4,
            inputs=[z[4 * n4 :], t, z_top, inv_step],
            outputs=[hist],
            device=device,
        )
    return hist


@fill_doc(TRUNCATION_DOCS)
def depth_grid(
    Rt: float,
    n_increments: int = 200,
    *,
    max_depth: float | None = None,
    max_depth_fraction: float = 0.1,
) -> np.ndarray:
    """Depths ω_k = k·ω_max/n, k = 0..n (m), float64.

    Parameters
    ----------
    Rt : float
        Peak-to-valley height R_t (m).
    {depth_range}

    Returns
    -------
    (n+1,) float64 ndarray
        Depths ω_k (m), from 0 to ω_max.

    Raises
    ------
    ValueError
        ``n_increments`` is not an integer in [1, 10⁶] (``MAX_INCREMENTS``),
        ``max_depth_fraction`` is outside
        (0, 1], ``max_depth`` is not positive and finite, or ω_max is 0 (a flat map).
    """
    n = check_int("n_increments", n_increments, 1, MAX_INCREMENTS)
    if max_depth is None:
        frac = check_range("max_depth_fraction", max_depth_fraction, 0.0, 1.0, hi_open=False)
        wmax = frac * Rt
    else:
        wmax = check_range("max_depth", max_depth, 0.0, unit="m")
    if not wmax > 0:
        raise ValueError(f"the height map is flat (R_t = {Rt!r} m): nothing to truncate")
    return np.arange(n + 1, dtype=np.float64) * (wmax / n)


def surface_device(surface: Surface, device: wp.DeviceLike) -> wp.DeviceLike:
    """``device``, or where a device-resident surface lives when it is None."""
    return getattr(surface, "device", None) if device is None else device


def upload_heights(surface: Surface, device) -> wp.array:
    """The (ny, nx) heights on ``device``: the surface's own device array, or its copy there
    (uploaded once per device and cached on the surface).

    Kept 2-D: a flattened map of 2³¹ pixels or more is not a valid Warp array; the flat
    kernels run over row bands (``warptrunc._support.limits``)."""
    if not isinstance(surface, Surface):
        raise TypeError(
            f"surface must be a warptrunc.Surface, got {type(surface).__name__}; wrap a height "
            "array with warptrunc.from_heights(z, dx)"
        )
    return surface.device_heights(device)


def histogram_bands(
    z: wp.array, t: wp.array, z_top: float, inv_step: float, device, *, deep: bool = True
) -> np.ndarray:
    """(len(t),) int64 host histogram of contact indices of ``z`` (1-D or 2-D, any size).

    :func:`contact_histogram` once per row band (each below 2³¹ pixels; bands of whole rows
    in multiples of 4, so that every band starts 16-byte aligned for the vec4 kernels), the
    band histograms summed on the host (one sync point per band)."""
    n1 = t.shape[0]
    total = np.zeros(n1, dtype=np.int64)
    for _r0, _r1, v in flat_row_bands(z):
        hist = contact_histogram(v, t, z_top, inv_step, device, deep=deep)
        total += hist.numpy()[:n1]  # sync point
    return total


def surface_range(surface: Surface, z: wp.array, device) -> tuple[float, float]:
    """(min z, max z) (m) of a surface: recorded by the generator or by its validation, else a
    device reduction of ``z`` (its heights on ``device``, 1-D or 2-D), then cached."""
    ext = surface._cached_extremes()
    if ext is None:
        ext = height_range(z, device)
        surface._cache_extremes(*ext)
    return ext


def depth_thresholds(z: wp.array, depth: np.ndarray, device, lo_hi=None):
    lo, hi = height_range(z, device) if lo_hi is None else lo_hi
    thr = (np.float64(hi) - depth).astype(np.float32)
    step = float(depth[-1] / (depth.size - 1)) if depth.size > 1 and depth[-1] > 0 else 0.0
    inv_step = 1.0 / step if step > 0 else 0.0
    return wp.array(thr, dtype=wp.float32, device=device), lo, hi, thr, inv_step


@fill_doc(TRUNCATION_DOCS)
def truncate_surface(
    surface: Surface,
    n_increments: int,
    *,
    max_depth: float | None,
    max_depth_fraction: float,
    device: wp.context.Device,
) -> TruncationCurve:
    """The in-memory path of :func:`warptrunc.truncate` on a resolved ``device``.

    One pass over the heights: each pixel's contact index (the first k with
    z ≥ z_top − ω_k) is found in a Warp kernel and counted in an integer atomic histogram;
    the cumulative sum gives the number of contact pixels at every depth.

    Parameters
    ----------
    surface : Surface
        The height map (m), already checked by the caller.
    {depth_range}
    device : warp.context.Device
        The resolved Warp device.

    Returns
    -------
    TruncationCurve
        A_c(ω_k) at the n + 1 depths of :func:`depth_grid`.

    Raises
    ------
    ValueError
        Out-of-range depth parameters, or a flat map (see :func:`depth_grid`).
    MemoryError
        The heights do not fit the device (a host surface is uploaded).
    """
    z = upload_heights(surface, device)
    lo, hi = surface_range(surface, z, device)  # recorded by the generator, or one reduction
    depth = depth_grid(
        float(np.float64(hi) - np.float64(lo)),
        n_increments,
        max_depth=max_depth,
        max_depth_fraction=max_depth_fraction,
    )
    t, lo, hi, thr, inv_step = depth_thresholds(z, depth, device, (lo, hi))
    Rt = float(np.float64(hi) - np.float64(lo))
    hist = histogram_bands(z, t, hi, inv_step, device, deep=depth[-1] > DEEP_FRACTION * Rt)
    return curve_from_histogram(hist, depth, thr, (lo, hi), surface)


def curve_from_histogram(
    hist: np.ndarray, depth: np.ndarray, thr: np.ndarray, lo_hi: tuple[float, float], grid: Any
) -> TruncationCurve:
    """The :class:`TruncationCurve` of a contact-index histogram (counts = its cumulative sum).

    ``depth`` (m) and ``thr`` (float32, m) as from :func:`depth_grid` and
    :func:`depth_thresholds`; ``lo_hi`` the map's (min z, max z) (m); ``grid`` anything with
    ``pixel_area`` (m²), ``apparent_area`` (m²), ``nx`` and ``ny`` (a :class:`Surface`)."""
    lo, hi = lo_hi
    counts = np.cumsum(hist)
    return TruncationCurve(
        depth=depth,
        threshold=thr,
        n_contact_pixels=counts.astype(np.int64),
        contact_area=counts * grid.pixel_area,
        apparent_area=grid.apparent_area,
        pixel_area=grid.pixel_area,
        n_pixels=grid.nx * grid.ny,
        z_top=hi,
        Rt=float(np.float64(hi) - np.float64(lo)),
    )


@fill_doc(TRUNCATION_DOCS)
def contact_index_map(
    surface: Surface,
    depth: np.ndarray,
    *,
    device: wp.DeviceLike = None,
) -> np.ndarray:
    """Per-pixel contact index: the first k with z ≥ z_top − depth[k], or len(depth) if none.

    Parameters
    ----------
    {surface}
    depth : (n+1,) array_like
        Non-decreasing, equally spaced truncation depths (m), starting at 0 (as from
        :func:`depth_grid`).
    {device}

    Returns
    -------
    (ny, nx) int32 ndarray
        The island labelling carries its union-find forest across depths in this order. The
        same map left on the device is :func:`contact_index_device`.
    """
    return contact_index_device(
        surface, depth, resolve_device(surface_device(surface, device))
    ).numpy()


@fill_doc(TRUNCATION_DOCS)
def contact_index_device(
    surface: Surface, depth: np.ndarray, device: wp.context.Device
) -> wp.array:
    """:func:`contact_index_map` as a (ny, nx) int32 Warp array left on the resolved ``device``.

    Parameters
    ----------
    {surface}
    depth : (n+1,) array_like
        Non-decreasing, equally spaced truncation depths (m), starting at 0 or more.
    device : warp.context.Device
        The resolved Warp device.

    Returns
    -------
    warp.array2d of int32
        (ny, nx) contact index of each pixel (len(depth) where it never touches), on
        ``device``.

    Raises
    ------
    ValueError
        ``depth`` is not a 1-D non-decreasing array of depths ≥ 0.
    TypeError
        ``surface`` is not a :class:`~warptrunc.Surface`.
    """

    depth = np.asarray(depth, dtype=np.float64)
    if depth.ndim != 1 or depth.size < 1 or np.any(np.diff(depth) < 0) or depth[0] < 0:
        raise ValueError("depth must be a 1-D non-decreasing array of depths ≥ 0 (m)")
    z = upload_heights(surface, device)
    t, _lo, hi, _thr, inv_step = depth_thresholds(
        z, depth, device, surface_range(surface, z, device)
    )
    index = wp.empty((surface.ny, surface.nx), dtype=wp.int32, device=device)
    for r0, r1 in row_bands(surface.ny, surface.nx):  # flat launches below 2³¹ pixels each
        wp.launch(
            _k.contact_index_kernel,
            dim=(r1 - r0) * surface.nx,
            inputs=[z[r0:r1].flatten(), t, hi, inv_step],
            outputs=[index[r0:r1].flatten()],
            device=device,
        )
    return index
