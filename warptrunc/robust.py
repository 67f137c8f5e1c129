# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Measured scans: an outlier-robust height range, and advice when the fit range is empty.

A measured scan's R_t is often set by a few spikes (dust, spikes of the instrument, unfilled
edges). Truncated to ω_max = 0.1·R_t from such a spike, the map touches a handful of pixels
and the power-law fit has no increments with ``min_pixels`` contact pixels.
:func:`clip_to_percentiles` clips the heights to the ``lo``-th and ``hi``-th percentiles
(``warptrunc analyze --rt-percentile 0.1 99.9``): R_t becomes P_hi − P_lo, and the pixels
above P_hi (a share of ``100 − hi`` %) touch at ω = 0. :func:`fit_range_advice` computes, for
one map, the option values that would give a non-empty fit range, so that the error message
can name them.
"""

from __future__ import annotations

import math

import numpy as np

from .surface import Surface

__all__ = [
    "AUTO_END_FRACTION",
    "AUTO_END_PIXELS",
    "MIN_FIT_POINTS",
    "auto_fit_range",
    "clip_to_percentiles",
    "fit_range_advice",
]

MIN_FIT_POINTS = 3
"""Fewest increments a power-law fit needs (``stiffness.fit_power_law``)."""


def clip_to_percentiles(surface: Surface, lo: float, hi: float) -> Surface:
    """The surface with heights clipped to their ``lo``-th and ``hi``-th percentiles.

    Parameters
    ----------
    surface : Surface
        The map (m).
    lo, hi : float
        Percentiles, 0 ≤ lo < hi ≤ 100 (%).

    Returns
    -------
    Surface
        Heights clipped to [P_lo, P_hi] (m); ``params`` records ``rt_percentile`` ([lo, hi]),
        ``Rt_raw_m`` (R_t before clipping, m), ``n_clipped_above`` and ``n_clipped_below``
        (pixels).
    """
    lo, hi = float(lo), float(hi)
    if not (0.0 <= lo < hi <= 100.0):
        raise ValueError(f"--rt-percentile LO HI needs 0 ≤ LO < HI ≤ 100 (%), got {lo!r} {hi!r}")
    z = np.asarray(surface.heights, dtype=np.float64)
    p_lo, p_hi = np.percentile(z, [lo, hi])
    if not p_hi > p_lo:
        raise ValueError(
            f"--rt-percentile {lo:g} {hi:g}: the percentiles are equal ({p_lo:.6g} m); the map is "
            "flat between them, widen the range"
        )
    params = dict(surface.params)
    params.update(
        rt_percentile=[lo, hi],
        Rt_raw_m=float(z.max() - z.min()),
        n_clipped_above=int(np.count_nonzero(z > p_hi)),
        n_clipped_below=int(np.count_nonzero(z < p_lo)),
    )
    return Surface(np.clip(z, p_lo, p_hi), surface.dx, surface.dy, params)


def _n_fit(zs_desc: np.ndarray, n: int, omega_max: float, m: int, window) -> int:
    """Increments k ≥ 1 with ≥ m pixels (and inside ``window``) on a sorted map."""
    k = np.arange(1, n + 1)
    depth = k * omega_max / n
    # pixels with z ≥ z_max − ω: count in a descending array
    counts = np.searchsorted(-zs_desc, -(zs_desc[0] - depth), side="right")
    sel = counts >= m
    if window is not None:
        sel &= (depth >= window[0]) & (depth <= window[1])
    return int(np.count_nonzero(sel))


def _ceil2(x: float) -> float:
    """``x`` rounded up to two significant digits."""
    if x <= 0:
        return x
    e = math.floor(math.log10(x)) - 1
    return math.ceil(x / 10**e) * 10**e


def fit_range_advice(
    heights: np.ndarray,
    *,
    increments: int,
    max_depth_fraction: float,
    max_depth: float | None,
    min_pixels: int,
    depth_window: tuple[float, float] | None,
) -> list[str]:
    """Option settings that give ≥ 3 fittable increments on this map (checked on the map).

    Parameters
    ----------
    heights : ndarray
        The truncated map (m), any shape.
    increments, max_depth_fraction, max_depth, min_pixels, depth_window
        The settings that failed (as the ``analyze`` options).

    Returns
    -------
    list of str
        One entry per option that fixes the fit range alone, e.g.
        ``"--max-depth-fraction 0.43"``; empty when none does.
    """
    z = np.asarray(heights, dtype=np.float64).ravel()
    zs = np.sort(z)[::-1]
    Rt = float(zs[0] - zs[-1])
    n, m = int(increments), int(min_pixels)
    out: list[str] = []
    if Rt <= 0:
        return out
    omega = max_depth if max_depth is not None else max_depth_fraction * Rt
    if n < MIN_FIT_POINTS:
        if _n_fit(zs, 200, omega, m, depth_window) >= MIN_FIT_POINTS:
            out.append("--increments 200")
        return out
    if depth_window is None and m <= zs.size:
        # depth at which the m-th pixel touches; ω_{n−2} must reach it
        need = (zs[0] - zs[m - 1]) * n / (n - MIN_FIT_POINTS + 1)
        for f in (_ceil2(1.02 * need / Rt), _ceil2(1.1 * need / Rt)):
            if f <= 1.0 and _n_fit(zs, n, f * Rt, m, None) >= MIN_FIT_POINTS:
                out.append(f"--max-depth-fraction {f:g}")
                break
    # the fewest pixels among the last three increments (inside the window)
    k = np.arange(1, n + 1)
    depth = k * omega / n
    if depth_window is not None:
        depth = depth[(depth >= depth_window[0]) & (depth <= depth_window[1])]
    if depth.size >= MIN_FIT_POINTS:
        counts = np.searchsorted(-zs, -(zs[0] - depth), side="right")
        c = int(np.sort(counts)[-MIN_FIT_POINTS])
        if 1 <= c < m:
            out.append(f"--min-pixels {c}")
    if depth_window is not None:
        d_all = k * omega / n
        counts = np.searchsorted(-zs, -(zs[0] - d_all), side="right")
        ok = d_all[counts >= m]
        if ok.size >= MIN_FIT_POINTS:
            out.append(f"--depth-window {ok[0]:.4g} {ok[-1]:.4g}")
    if max_depth is None and depth_window is None:
        p_lo, p_hi = np.percentile(z, [0.1, 99.9])
        zc = np.clip(zs, p_lo, p_hi)
        if p_hi > p_lo and _n_fit(zc, n, max_depth_fraction * (p_hi - p_lo), m, None) >= 3:
            share = (zs[0] - p_hi) / Rt
            out.append(
                f"--rt-percentile 0.1 99.9 (the highest 0.1 % of the pixels span {share:.0%} of R_t)"
            )
    return out



AUTO_END_FRACTION = 0.005
"""Automatic fit range: the deepest increment has this share of A in contact (dimensionless) ..."""
AUTO_END_PIXELS = 500
"""... and at least this many contact pixels (pixels)."""


def auto_fit_range(
    surface: Surface,
    *,
    end_fraction: float = AUTO_END_FRACTION,
    end_pixels: int = AUTO_END_PIXELS,
) -> tuple[Surface, float, dict]:
    """The map and ω_max of the automatic fit range, stated in contact pixels.

    Parameters
    ----------
    surface : Surface
        The map (m).
    end_fraction : float
        The deepest increment has a share ``end_fraction`` of the pixels in contact
        (dimensionless, 0 < f < 1) ...
    end_pixels : int
        ... and at least ``end_pixels`` of them (pixels; capped at the map's size).

    Returns
    -------
    surface : Surface
        ``surface`` with its spike pixels masked (:func:`warptrunc.plausibility.mask_spikes`),
        or ``surface`` itself when it has none.
    max_depth : float
        ω_max (m): from the highest pixel to the max(⌈f·N⌉, ``end_pixels``)-th highest one.
    info : dict
        The rule and its values, for ``fit.json``: ``rule`` (``"auto"``), ``end_fraction``,
        ``end_pixels``, ``end_contact_pixels``, ``spikes_masked`` (pixels) and
        ``max_depth_m`` (m).

    Raises
    ------
    ValueError
        If the map is flat over that range of pixels.

    Notes
    -----
    The depth range ends at a contact area, not at a share of R_t, which one spike or one pit
    sets; spike pixels (which would start the truncation alone) are masked first. The fit then
    uses the increments with at least ``min_pixels`` contact pixels, as the legacy range.
    """
    from .plausibility import mask_spikes

    if not 0.0 < end_fraction < 1.0:
        raise ValueError(f"end_fraction must be in (0, 1), got {end_fraction!r}")
    masked, found = mask_spikes(surface)
    z = np.asarray(masked.heights, dtype=np.float64).ravel()
    n = z.size
    end = min(max(math.ceil(end_fraction * n), int(end_pixels)), n)
    z_end = float(-np.partition(-z, end - 1)[end - 1])
    z_top = float(z.max())
    if not z_top > z_end:
        raise ValueError(
            f"the map is flat between its highest and {end}th highest pixels: no automatic fit "
            "range; give --fit-range legacy"
        )
    info = {"rule": "auto", "end_fraction": float(end_fraction), "end_pixels": int(end_pixels),
            "end_contact_pixels": end, "spikes_masked": found[0].details["count"] if found else 0,
            "max_depth_m": z_top - z_end}  # fmt: skip
    return masked, z_top - z_end, info
