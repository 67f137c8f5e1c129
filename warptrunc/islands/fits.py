# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Slit-island fits (Eq. 5) and the applicable-depth indicators of Table 2."""

from __future__ import annotations

import math

import numpy as np

from .._support.validate import check_int, check_range
from .results import (
    Indicators,
    IslandCurve,
    Islands,
    IslandSizes,
    SlitIslandFit,
)
from .settings import MIN_ISLANDS, MIN_PIXELS, IndicatorSettings

# --- slit-island analysis -------------------------------------------------------------------------


def _fit_loglog(area: np.ndarray, perimeter: np.ndarray) -> tuple[float, float, float]:
    x = np.log10(area)
    y = np.log10(perimeter)
    xm, ym = x.mean(), y.mean()
    sxx = float(np.sum((x - xm) ** 2))
    if not sxx > 0:
        return math.nan, math.nan, math.nan
    sxy = float(np.sum((x - xm) * (y - ym)))
    syy = float(np.sum((y - ym) ** 2))
    slope = sxy / sxx
    r2 = sxy * sxy / (sxx * syy) if syy > 0 else 1.0
    return slope, float(ym - slope * xm), r2


def slit_island_fit(
    islands: Islands | IslandSizes,
    *,
    min_pixels: int = MIN_PIXELS,
    min_islands: int = MIN_ISLANDS,
) -> SlitIslandFit:
    """Slit-island fit log10 L = exponent·log10 A + c over the islands at one depth (Eq. 5).

    Parameters
    ----------
    islands : Islands or IslandSizes
        Island areas A (m²) and perimeters L (m).
    min_pixels : int
        Smallest island used (pixels). Smaller islands have grid-dominated perimeters.
    min_islands : int
        Fewest islands for a fit; with fewer the result holds NaN.

    Returns
    -------
    SlitIslandFit

    Notes
    -----
    Mandelbrot's slit-island relation L ∝ A^((D−1)/2) for the sections of a self-affine surface
    of dimension D (paper Eq. 5 with D_vs): the exponent is (D − 1)/2, so D = 2·exponent + 1.
    Compact shapes give 0.5.

    References
    ----------
    Mandelbrot, Passoja & Paullay (1984), Nature 308, 721–722, doi:10.1038/308721a0.
    """
    min_pixels = check_int("min_pixels", min_pixels, 1)
    min_islands = check_int("min_islands", min_islands, 2)
    keep = np.asarray(islands.area_pixels) >= min_pixels
    n = int(keep.sum())
    if n < min_islands:
        return SlitIslandFit(math.nan, math.nan, math.nan, n, min_pixels)
    slope, c, r2 = _fit_loglog(np.asarray(islands.area)[keep], np.asarray(islands.perimeter)[keep])
    return SlitIslandFit(slope, c, r2, n, min_pixels)


# --- applicable depth (Table 2) -------------------------------------------------------------------


def _running(values: np.ndarray, window: int, how: str) -> np.ndarray:
    """Centred running mean or nan-median over ``window`` samples (window 1: unchanged)."""
    if window <= 1:
        return values.astype(np.float64)
    h = window // 2
    out = np.full(values.size, math.nan)
    for i in range(values.size):
        w = values[max(0, i - h) : i + h + 1]
        w = w[np.isfinite(w)]
        if w.size:
            out[i] = np.median(w) if how == "median" else w.mean()
    return out


def applicable_depth(curve: IslandCurve, settings: IndicatorSettings | None = None) -> Indicators:
    """Depths bounding the applicable range of the truncation method (Table 2, Fig. 8).

    Parameters
    ----------
    curve : IslandCurve
        Island statistics against depth (with ``statistics=True`` for the fractality depth).
    settings : IndicatorSettings, optional
        The relative drop X of the slit-island exponent that ends fractality
        (``exponent_tolerance``), the fewest fitted islands for a depth's exponent to count
        (``min_islands``), the plateau window and the span a drop must last (``plateau_width``,
        ``persist``, fractions of R_t) and the odd smoothing window (``smooth``, depth samples;
        1 disables smoothing) (:class:`~warptrunc.islands.settings.IndicatorSettings`; its
        defaults when None).

    Returns
    -------
    Indicators

    Notes
    -----
    * Maximum growth rate: the depth at which d(n/n_max)/d(ω/R_t), smoothed (a running mean
      over ``smooth`` samples), is largest (the dashed lines of Fig. 8a).
    * Fractality depth ("the deepest depth at which the slit-island exponent stays
      constant"): only depths whose fit uses at least ``min_islands`` islands count (the
      first few contact spots give noisy fits). The plateau exponent β₀ is the median of the
      smoothed exponent (a running median) over the first ``plateau_width``·R_t of those
      depths. Going deeper, the fractality depth is the last counted depth before the exponent
      first falls below (1 − X)·β₀ and stays below for every counted depth within the next
      ``persist``·R_t (the "obvious decrease" of §4.3; a rise does not end it, nor does a
      one-sample dip of a noisy fit; ``persist`` 0 accepts a single sample). When it never
      falls, it is the deepest counted depth and ``fractal_depth_censored`` is set: the true
      value lies beyond the analysed range.
    * Island-count peak: the depth of the largest island count (the first one when tied).
    """
    settings = IndicatorSettings() if settings is None else settings
    tol, min_islands = settings.exponent_tolerance, settings.min_islands
    width, persist, smooth = settings.plateau_width, settings.persist, settings.smooth
    frac = curve.depth_fraction
    growth = _running(curve.island_growth_rate, smooth, "mean")
    k_growth = int(np.nanargmax(growth)) if np.isfinite(growth).any() else 0
    k_peak = int(np.argmax(curve.n_islands))

    beta = np.where(curve.slit_n_islands >= min_islands, curve.slit_exponent, math.nan)
    beta = _running(beta, smooth, "median")
    beta[curve.slit_n_islands < min_islands] = math.nan
    fractal, plateau, censored = math.nan, math.nan, False
    lo = hi = math.nan
    ks = np.flatnonzero(np.isfinite(beta))
    if ks.size:
        lo = float(frac[ks[0]])
        hi = lo + width
        plateau = float(np.median(beta[ks[frac[ks] <= hi]]))
        low = beta[ks] < (1.0 - tol) * plateau
        drop = -1
        for i in np.flatnonzero(low):
            window = (frac[ks] >= frac[ks[i]]) & (frac[ks] <= frac[ks[i]] + persist + 1e-12)
            if low[window].all():
                drop = int(i)
                break
        if drop >= 0:
            fractal = float(curve.depth[ks[max(drop - 1, 0)]])
        else:
            fractal, censored = float(curve.depth[ks[-1]]), True
    return Indicators(
        max_growth_depth=float(curve.depth[k_growth]),
        fractal_depth=fractal,
        peak_depth=float(curve.depth[k_peak]),
        plateau_exponent=plateau,
        fractal_depth_censored=censored,
        Rt=curve.Rt,
        exponent_tolerance=tol,
        min_islands=min_islands,
        persist=persist,
        plateau_range=(lo, hi),
        smooth=smooth,
    )


def slit_from_sums(sums: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(n1, 2) [slope, r²] and (n1,) island counts of the slit-island fits from the per-depth
    sums [n, Σx, Σy, Σx², Σxy, Σy²] (x = log10 area, y = log10 perimeter, any units).

    The same least-squares fit as ``fits._fit_loglog``; centred sums from raw float64 sums,
    with the centred sum set to 0 (NaN slope, as there) when it is below 1e-12 of the raw one.
    """
    n = sums[:, 0]
    slit_n = np.rint(n).astype(np.int64)
    out = np.full((n.size, 2), math.nan)
    for k in np.flatnonzero(slit_n >= MIN_ISLANDS):
        c, sx, sy, sxx, sxy, syy = (float(v) for v in sums[k])
        cxx = sxx - sx * sx / c
        cxy = sxy - sx * sy / c
        cyy = syy - sy * sy / c
        if not cxx > 1e-12 * sxx:
            continue
        slope = cxy / cxx
        r2 = cxy * cxy / (cxx * cyy) if cyy > 1e-12 * syy else 1.0
        out[k] = slope, r2
    return out, slit_n


def slit_bootstrap(
    islands: Islands | IslandSizes,
    *,
    resamples: int = 200,
    level: float = 0.95,
    min_pixels: int = MIN_PIXELS,
    min_islands: int = MIN_ISLANDS,
    blocks: int = 4096,
    seed: int = 0,
) -> tuple[float, float, float]:
    """Slit-island exponent at one depth with a percentile bootstrap band over the islands.

    Parameters
    ----------
    islands : Islands or IslandSizes
        Island areas A (m²) and perimeters L (m) at one depth.
    resamples : int
        Bootstrap resamples (count).
    level : float
        Coverage of the percentile band (dimensionless, 0 < level < 1).
    min_pixels, min_islands : int
        As in :func:`slit_island_fit`.
    blocks : int
        Most resampling units (count): with more fitted islands than this, the islands are
        dealt at random into ``blocks`` blocks of (nearly) equal size and the blocks are
        resampled; with fewer, every island is a unit (the plain bootstrap).
    seed : int
        Seed of the resampling (a given seed gives the same band).

    Returns
    -------
    exponent, lo, hi : float
        The exponent of :func:`slit_island_fit` and the ``level`` percentile band of the
        resampled exponents (dimensionless); NaN with fewer than ``min_islands`` islands.

    Notes
    -----
    The least-squares slope depends on the islands only through the sums
    [n, Σx, Σy, Σx², Σxy, Σy²] (x = log10 A, y = log10 L), so a resample's slope comes from
    the sums of its units. Blocks of randomly assigned islands are independent and identically
    distributed, so resampling blocks gives the same variance of the sums as resampling
    islands to first order, at a cost independent of the island count.
    """
    resamples = check_int("resamples", resamples, 2)
    level = check_range("level", level, 0.0, 1.0)
    blocks = check_int("blocks", blocks, 2)
    fit = slit_island_fit(islands, min_pixels=min_pixels, min_islands=min_islands)
    if not math.isfinite(fit.exponent):
        return math.nan, math.nan, math.nan
    keep = np.asarray(islands.area_pixels) >= min_pixels
    x = np.log10(np.asarray(islands.area, np.float64)[keep])
    y = np.log10(np.asarray(islands.perimeter, np.float64)[keep])
    x0, y0 = x.mean(), y.mean()  # centred: the raw sums of large logs lose digits
    x, y = x - x0, y - y0
    terms = np.stack([np.ones_like(x), x, y, x * x, x * y, y * y], axis=1)
    rng = np.random.default_rng(seed)
    n = x.size
    if n > blocks:
        which = rng.permutation(n) % blocks
        unit = np.stack([np.bincount(which, weights=t, minlength=blocks) for t in terms.T], axis=1)
    else:
        unit = terms
    pick = rng.integers(0, unit.shape[0], size=(resamples, unit.shape[0]))
    s = unit[pick].sum(axis=1)  # (resamples, 6)
    c, sx, sy, sxx, sxy = s[:, 0], s[:, 1], s[:, 2], s[:, 3], s[:, 4]
    cxx = sxx - sx * sx / c
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = (sxy - sx * sy / c) / cxx
    slope = slope[np.isfinite(slope) & (cxx > 0)]
    if slope.size < 2:
        return fit.exponent, math.nan, math.nan
    q = 100 * (1 - level) / 2
    lo, hi = np.percentile(slope, [q, 100 - q])
    return fit.exponent, float(lo), float(hi)
