# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Contact sets of a height map reduced to the blocks of a down-sampled picture.

A picture of a large map has fewer cells than the map has pixels: each cell stands for a block
of f×f pixels. Two ways to colour a block are offered (``pooling``):

``"area"`` (default)
    The block's share of red is the fraction of its pixels in contact: colour =
    grey + φ·(red − grey). The red in the picture then measures the contact area: the mean of
    φ over the blocks (weighted by their pixel counts) is A_c/A exactly, and a fully truncated
    block is pure red. Isolated single-pixel spots appear as faint tints.
``"any"``
    Max-pooling: a block is red when **any** of its pixels touches. Every contact spot stays
    visible, but the red area overstates A_c/A (by about 2× for a WM map with D = 2.5 at
    30 % of R_t and f = 4).

With f = 1 both are the contact mask itself.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import warp as wp

from .._support.docs import SHARED_DOCS, fill_doc
from ..surface import Surface
from ..truncation.curve import contact_index_map

POOLING = ("area", "any")
"""Ways to colour a block of pixels: by its contact fraction, or red when any pixel touches."""


def pool_blocks(a: np.ndarray, factor: int, how: str = "max") -> np.ndarray:
    """Reduce a 2-D array over blocks of ``factor``×``factor`` elements.

    Parameters
    ----------
    a : (ny, nx) ndarray
        Values (a bool mask, contact indices, or heights).
    factor : int
        Block side f ≥ 1. The last block row and column are partial when f does not divide
        the size.
    how : {"max", "min", "mean"}
        Reduction. ``"max"`` of a bool mask is "any pixel of the block"; ``"min"`` of a contact
        index map gives the block's first contact index; ``"mean"`` is computed in float64.

    Returns
    -------
    (ceil(ny/f), ceil(nx/f)) ndarray
        Same dtype as ``a`` for max/min, float64 for mean.

    Notes
    -----
    Works one block row at a time, so the extra memory is one row of blocks, not a copy of a.
    """
    a = np.asarray(a)
    if a.ndim != 2:
        raise ValueError(f"a must be 2-D, got shape {a.shape}")
    f = int(factor)
    if f < 1 or f != factor:
        raise ValueError(f"factor must be an integer ≥ 1, got {factor!r}")
    if how not in ("max", "min", "mean"):
        raise ValueError(f"how must be 'max', 'min' or 'mean', got {how!r}")
    ny, nx = a.shape
    if f == 1:
        return a.astype(np.float64) if how == "mean" else a.copy()
    xs = np.arange(0, nx, f)
    my = -(-ny // f)
    out = np.empty((my, xs.size), dtype=np.float64 if how == "mean" else a.dtype)
    for j in range(my):
        rows = a[j * f : (j + 1) * f]
        if how == "max":
            out[j] = np.maximum.reduceat(rows.max(axis=0), xs)
        elif how == "min":
            out[j] = np.minimum.reduceat(rows.min(axis=0), xs)
        else:
            s = np.add.reduceat(rows.sum(axis=0, dtype=np.float64), xs)
            out[j] = s / (rows.shape[0] * np.diff(np.append(xs, nx)))
    return out


def check_pooling(pooling: str) -> str:
    """Return ``pooling`` if it is one of :data:`POOLING`, else raise ValueError."""
    if pooling not in POOLING:
        raise ValueError(f"pooling must be one of {POOLING}, got {pooling!r}")
    return pooling


def check_depths(surface: Surface, depth_fractions, depths, *, upto_rt: bool = False) -> np.ndarray:
    """Depths ω (m) from ``depths`` or ``depth_fractions`` × R_t, validated.

    With ``upto_rt`` (pictures) every depth must lie in (0, R_t] and every fraction in (0, 1];
    otherwise depths may be any finite ω ≥ 0 and fractions any value in [0, 1].
    """
    Rt = surface.Rt
    if not Rt > 0:
        raise ValueError(f"the height map is flat (R_t = {Rt!r} m): nothing to truncate")
    if depths is None:
        fr = np.atleast_1d(np.asarray(depth_fractions, dtype=np.float64))
        ok = (fr > 0) if upto_rt else (fr >= 0)
        if fr.ndim != 1 or fr.size == 0 or not np.all(ok & (fr <= 1)):
            rng = "(0, 1]" if upto_rt else "[0, 1]"
            raise ValueError(
                f"depth_fractions must be in {rng} (fractions of R_t), got {depth_fractions!r}"
            )
        return fr * Rt
    d = np.atleast_1d(np.asarray(depths, dtype=np.float64))
    if upto_rt:
        if d.ndim != 1 or d.size == 0 or not np.all(np.isfinite(d) & (d > 0) & (d <= Rt)):
            raise ValueError(
                f"depths must be in (0, R_t] = (0, {Rt:.6g}] m for this map, got {depths!r}"
            )
    elif d.ndim != 1 or d.size == 0 or not np.all(np.isfinite(d) & (d >= 0)):
        raise ValueError(f"depths must be finite and ≥ 0 (m), got {depths!r}")
    return d


@fill_doc(SHARED_DOCS)
def block_contact(
    surface: Surface, depth: np.ndarray, factor: int, pooling: str = "area", device=None
) -> tuple[list[np.ndarray], np.ndarray]:
    """Per-block contact at each depth, and A_c/A at full resolution.

    Parameters
    ----------
    {surface}
    depth : (k,) ndarray
        Truncation depths ω (m), validated.
    factor : int
        Block side f (pixels).
    pooling : {"area", "any"}
        ``"area"``: the fraction of each block's pixels in contact (float32 in [0, 1]);
        ``"any"``: True when any pixel of the block is in contact (bool).
    device : str, optional
        Warp device for the contact index.

    Returns
    -------
    (list of k (ceil(ny/f), ceil(nx/f)) arrays, (k,) float64 A_c/A)
        A pixel is in contact when z ≥ float32(z_top − ω), as :func:`warptrunc.truncate`
        counts it.
    """

    check_pooling(pooling)
    uniq, rank = np.unique(depth, return_inverse=True)
    index = contact_index_map(surface, uniq, device=device)  # (ny, nx) int32
    counts = np.bincount(index.ravel(), minlength=uniq.size + 1)[: uniq.size]
    frac = (np.cumsum(counts) / float(index.size))[rank]
    if pooling == "any":
        pooled = pool_blocks(index, factor, "min")
        del index
        return [pooled <= r for r in rank], frac
    out = []
    for r in rank:
        out.append(pool_blocks(index <= r, factor, "mean").astype(np.float32))
    return out, frac


@fill_doc(SHARED_DOCS)
def contact_masks(
    surface: Surface,
    depth: Sequence[float],
    *,
    downsample: int = 1,
    device: wp.DeviceLike = None,
) -> np.ndarray:
    """Contact masks at the given depths, max-pooled over blocks of ``downsample`` × ``downsample`` pixels.

    Parameters
    ----------
    {surface}
    depth : (k,) array_like
        Truncation depths ω ≥ 0 (m), in any order.
    downsample : int
        Block side f; a block is in contact when any of its pixels is.
    device : str, optional
        Warp device for the contact index; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    (k, ceil(ny/f), ceil(nx/f)) bool ndarray
        ``mask[i]`` at depth ``depth[i]``. A pixel is in contact when
        z ≥ float32(z_top − ω), exactly as :func:`warptrunc.truncate` counts it.
    """
    d = check_depths(surface, None, depth)
    masks, _ = block_contact(surface, d, downsample, "any", device)
    return np.stack(masks)
