# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Measured scans: the automatic rule of ``analyze``, a robust height range, advice.

A measured scan's R_t is often set by a few spikes (dust, spikes of the instrument, unfilled
edges). Truncated to ω_max = 0.1·R_t from such a spike, the map touches a handful of pixels
and the power-law fit has no increments with ``min_pixels`` contact pixels.

**The automatic rule** decides, for a map read from a file, what a careful user would when
the default fit (increments to ω_max = 0.1·R_t with ≥ ``min_pixels`` contact pixels) is empty
or not worth reading. ``analyze`` applies it with ``--fit-range auto`` (the default) and no
range of the caller's own (``--max-depth``, ``--depth-window``, ``--rt-percentile``):

0. *Size.* A map with fewer than 32 pixels on a side is refused, in one line naming its size
   (:func:`check_map_size`).
1. *Spikes.* The spike rule of :mod:`warptrunc.plausibility` runs in passes, each on the map
   masked by the passes before (σ_d and R_robust recomputed), until a pass finds none (at
   most 10; a population of spikes on more than 0.1 % of the map lifts P99.9 and so R_robust,
   and one pass finds only its tallest). The spikes *dominate the top of the map* when its
   highest or its lowest pixel is one of them: they set the top that the truncation starts
   from, or R_t and with it ω_max. A fit from such a map is not worth reading either, and
   the spikes are masked (each replaced by the median of its 8 neighbours) for R_t and the
   truncation (:func:`spike_rule`). ``--spikes report`` keeps them (reported only).
2. *The default first.* The default fit is kept when it is worth reading
   (:func:`warptrunc.plausibility.check_fit`: r² ≥ 0.9, 0 < α ≤ 1, ≥ half a decade of load,
   ≥ 50 contact pixels at the deepest fitted increment) and no spike sets R_t.
3. *Depth.* Otherwise ω_max = 0.1·R_t of the (masked) map, brought to between 50 pixels and
   5 % of the map in contact at the deepest increment (:func:`adjust_depth`): with fewer than
   50 contact pixels there, it extends to halfway between the depths at which the 50th and
   the 51st highest pixels touch (a map of 32 × 32 pixels or more has 50 within 5 % of its
   area), and when the fit over that range is not worth reading, the count doubles (100,
   200, … pixels, within 5 % of the map) until the fit is; an extension stops at 0.5·R_t
   (the cap). With more than 5 % (R_t still set by pits), ω_max is cut back likewise to the
   ⌊0.05·N⌋-th highest pixel.
4. *Choice.* When step 1 or 3 decided something, the fit over that range (the first worth
   reading, else the shallowest that fits) replaces the default one, with its warnings and
   ``fit_error`` if it is still not worth reading. When neither applies, or the new range
   holds fewer than 3 fittable increments, the default result (or its error, with advice)
   stands.

Each decision is one ``warning:`` line (``auto_spikes_masked``, ``auto_depth_extended``,
``auto_depth_cut``) and a key of ``fit.json``'s ``fit_range`` (``spikes_masked``,
``depth_extended``, ``depth_cut``), which also records the rule chosen (``"legacy"`` or
``"auto"``) and why. Generated WM surfaces are not touched. ``compare`` and ``indent`` apply
steps 0 and 1 to a map read from a file (spikes that set R_t are masked as it is read).

:func:`clip_to_percentiles` clips the heights to the ``lo``-th and ``hi``-th percentiles
(``warptrunc analyze --rt-percentile 0.1 99.9``): R_t becomes P_hi − P_lo, and the pixels
above P_hi (a share of ``100 − hi`` %) touch at ω = 0. :func:`fit_range_advice` computes, for
one map, the option values that would give a non-empty fit range, so that the error message
can name them.
"""

from __future__ import annotations

import math

import numpy as np

from .plausibility import FIT_MIN_CONTACT_PIXELS, PlausibilityWarning, mask_spikes
from .surface import Surface

__all__ = [
    "AUTO_CONTACT_PIXELS",
    "AUTO_MAX_CONTACT_SHARE",
    "AUTO_MAX_DEPTH_FRACTION",
    "MIN_FIT_POINTS",
    "MIN_MAP_SIDE",
    "SPIKE_PASSES",
    "adjust_depth",
    "check_map_size",
    "clip_to_percentiles",
    "fit_range_advice",
    "spike_rule",
    "spike_warning",
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


# --- the automatic rule for maps read from files (issue 41) ------------------------------------

MIN_MAP_SIDE = 32
"""A map read from a file with fewer pixels than this on a side is refused (pixels)."""
SPIKE_PASSES = 10
"""Most passes of the spike rule in the automatic rule (:func:`spike_rule`)."""
AUTO_CONTACT_PIXELS = FIT_MIN_CONTACT_PIXELS
"""The extended depth range ends where this many pixels are in contact (pixels): the fewest
with which a fit is worth reading (:data:`warptrunc.plausibility.FIT_MIN_CONTACT_PIXELS`)."""
AUTO_MAX_DEPTH_FRACTION = 0.5
"""The automatic depth range extends to at most this share of R_t (dimensionless): the depth
to which § 4.3's indicators are computed on generated maps."""
AUTO_MAX_CONTACT_SHARE = 0.05
"""The automatic depth range ends where at most this share of the map is in contact
(dimensionless): ≥ 50 pixels on a map of 32 × 32 or more."""


def check_map_size(surface: Surface, name: str = "the map") -> None:
    """Refuse a map with fewer than :data:`MIN_MAP_SIDE` pixels on a side.

    Parameters
    ----------
    surface : Surface
        The map read from a file.
    name : str
        How the message names the map (e.g. the file name).

    Raises
    ------
    ValueError
        One line naming the map's size and the 32-pixel minimum.
    """
    ny, nx = np.shape(surface.heights)
    if min(nx, ny) < MIN_MAP_SIDE:
        raise ValueError(
            f"{name} is {nx}×{ny} pixels (nx×ny): a truncation analysis needs at least "
            f"{MIN_MAP_SIDE} pixels a side ({AUTO_CONTACT_PIXELS} contact pixels within "
            f"{AUTO_MAX_CONTACT_SHARE:.0%} of the map); refused"
        )


def spike_rule(surface: Surface, *, passes: int = SPIKE_PASSES) -> tuple[Surface, list, list[str]]:
    """The spike pixels of a map, found by repeated passes, and whether they set R_t.

    Parameters
    ----------
    surface : Surface
        The map read from a file (m).
    passes : int
        Most passes of the spike rule (:func:`warptrunc.plausibility.mask_spikes`; each pass on
        the map masked by the ones before, σ_d and R_robust recomputed).

    Returns
    -------
    masked : Surface
        ``surface`` with every spike pixel replaced by the median of its 8 neighbours
        (``surface`` itself when there is none).
    found : list of PlausibilityWarning
        The ``"spikes"`` warning of :func:`~warptrunc.plausibility.mask_spikes` (count over all
        passes, first 20 locations), or empty.
    sets : list of str
        ``"top"`` when the highest pixel of ``surface`` is a spike pixel (the truncation would
        start from it), ``"bottom"`` when the lowest one is (it sets R_t, so ω_max); empty
        when the spikes dominate neither end of the height range.
    """
    masked, found = mask_spikes(surface, passes=passes)
    if not found:
        return surface, [], []
    z0 = np.asarray(surface.heights)
    hit = np.asarray(masked.heights) != z0
    sets = [end for end, at in (("top", z0 == z0.max()), ("bottom", z0 == z0.min()))
            if np.any(hit & at)]  # fmt: skip
    return masked, found, sets


def spike_warning(found: list, sets: list[str], masked: Surface | None = None) -> list:
    """The warning line of :func:`spike_rule`'s finding: masked (a decision) or reported.

    Parameters
    ----------
    found : list of PlausibilityWarning
        :func:`spike_rule`'s ``found`` (empty: no warning).
    sets : list of str
        :func:`spike_rule`'s ``sets``.
    masked : Surface, optional
        The masked map when the rule masked the spikes (R_t after masking); None when they are
        kept.

    Returns
    -------
    list of PlausibilityWarning
        ``"auto_spikes_masked"`` (``details``: those of ``"spikes"`` and ``sets``,
        ``Rt_before_m``, ``Rt_after_m``, m) when masked, ``"spikes"`` (``action: "report"``)
        when kept, or empty.
    """
    if not found:
        return []
    d = found[0].details
    n, loc, passes = d["count"], d["locations"][0], d["passes"]
    where = (f"{n} spike pixel(s) (first at iy={loc['iy']}, ix={loc['ix']}; {passes} pass(es) "
             "of the spike rule)")  # fmt: skip
    if masked is None:
        why = ("they set neither the highest nor the lowest pixel" if not sets
               else "the automatic range did not fit")  # fmt: skip
        return [PlausibilityWarning(
            "spikes", f"{where}: reported, not masked: {why} (--spikes mask replaces them)",
            {**d, "action": "report", "sets": sets},
        )]  # fmt: skip
    ends = " and ".join({"top": "highest", "bottom": "lowest"}[e] for e in sets)
    before, after = float(d["Rt_m"]), float(masked.Rt)
    return [PlausibilityWarning(
        "auto_spikes_masked",
        f"{where} include the {ends} pixel of the map: masked for R_t and the truncation, R_t "
        f"{before:.4g} m → {after:.4g} m (automatic rule; --spikes report keeps them)",
        {**d, "action": "mask", "sets": sets, "Rt_before_m": before, "Rt_after_m": after},
    )]  # fmt: skip


def adjust_depth(
    heights: np.ndarray,
    max_depth: float,
    *,
    contact_pixels: int = AUTO_CONTACT_PIXELS,
    max_share: float = AUTO_MAX_CONTACT_SHARE,
    max_fraction: float = AUTO_MAX_DEPTH_FRACTION,
    note: str = "",
) -> tuple[float, str | None, dict | None, list]:
    """ω_max brought to between ``contact_pixels`` pixels and ``max_share`` of A in contact.

    Parameters
    ----------
    heights : ndarray
        The map to truncate (m), any shape.
    max_depth : float
        ω_max of the default range (m).
    contact_pixels : int
        Pixels the deepest increment must have in contact (pixels).
    max_share : float
        Largest share of the map the deepest increment may have in contact (dimensionless,
        0 < s < 1).
    max_fraction : float
        An extended ω_max is at most this share of R_t (dimensionless, 0 < f ≤ 1).
    note : str
        Appended to the warning's reason (why ``contact_pixels`` is what it is).

    Returns
    -------
    max_depth : float
        ω_max (m): unchanged when the pixels with z ≥ z_top − ω_max number from
        ``contact_pixels`` to ⌊``max_share``·N⌋ (N pixels); else extended (too few) or cut (too
        many) to halfway between the depths at which the m-th and the (m+1)-th highest pixels
        touch, m = ``contact_pixels`` or ⌊``max_share``·N⌋ (above any tie there); an extension
        stops at ``max_fraction``·R_t.
    action : {"extended", "cut"} or None
        The decision; None when ω_max is unchanged.
    record : dict or None
        The decision for ``fit.json`` (``from_m``, ``to_m`` (m), ``from_fraction``,
        ``to_fraction`` (of R_t), ``contact_pixels_before``, ``contact_pixels``,
        ``target_contact_pixels`` (``contact_pixels`` given), ``max_contact_share``,
        ``max_depth_fraction``, ``capped`` (the extension stopped at ``max_fraction``·R_t)), or
        None.
    warnings : list of PlausibilityWarning
        One ``"auto_depth_extended"`` or ``"auto_depth_cut"`` warning, or empty.
    """
    if not 0.0 < max_share < 1.0:
        raise ValueError(f"max_share must be in (0, 1), got {max_share!r}")
    if not 0.0 < max_fraction <= 1.0:
        raise ValueError(f"max_fraction must be in (0, 1], got {max_fraction!r}")
    z = np.sort(np.asarray(heights, dtype=np.float32).ravel())[::-1].astype(np.float64)
    lo = int(contact_pixels)
    hi = max(math.floor(max_share * z.size), lo)
    top, Rt = z[0], z[0] - z[-1]
    before = int(np.count_nonzero(z >= np.float32(top - max_depth)))
    if lo <= before <= hi or z.size <= hi or not Rt > 0:
        return float(max_depth), None, None, []
    if before < lo:
        action, m = "extended", lo
    else:
        action, m = "cut", hi
        while m > lo and z[m - 1] == z[m]:  # stop above a tie
            m -= 1
    new = float(top - 0.5 * (z[m - 1] + z[m]))
    capped = action == "extended" and new > max_fraction * Rt
    new = min(new, max_fraction * Rt) if capped else new
    if not new > max_depth and action == "extended":
        return float(max_depth), None, None, []
    after = int(np.count_nonzero(z >= np.float32(top - new)))
    rec = {"from_m": float(max_depth), "to_m": new, "from_fraction": float(max_depth / Rt),
           "to_fraction": new / Rt, "contact_pixels_before": before, "contact_pixels": after,
           "target_contact_pixels": lo, "max_contact_share": float(max_share),
           "max_depth_fraction": float(max_fraction), "capped": bool(capped)}  # fmt: skip
    goal = (f"has at least {lo}" if action == "extended"
            else f"has at most {max_share:.0%} of the map ({hi} pixels)")  # fmt: skip
    if capped:
        goal += f" (stopped at {max_fraction:g}·R_t, the cap)"
    w = PlausibilityWarning(
        f"auto_depth_{action}",
        f"ω_max {action} from {rec['from_fraction']:.3g}·R_t ({max_depth:.4g} m, {before} contact "
        f"pixels) to {rec['to_fraction']:.3g}·R_t ({new:.4g} m, {after} contact pixels) so that "
        f"the deepest fitted increment {goal}{note} (automatic rule; --fit-range legacy keeps "
        "the default range)",
        rec,
    )
    return new, action, rec, [w]
