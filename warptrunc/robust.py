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
1. *Tilt.* When the least-squares plane of the map spans more height across it than the
   roughness about the plane does (R_robust = P99.9 − P0.1 of the levelled heights), the
   truncation would read the tilt: contact starts along the high side and spreads as a band.
   The plane is subtracted, as ``--level`` does (:func:`tilt_rule`). A surface's own longest
   wavelength makes a smaller plane: on WM surfaces with W_r = L it spans under 0.5·R_robust.
   A map read with ``--level`` is not levelled again.
2. *Spikes.* The spike rule of :mod:`warptrunc.plausibility` runs in passes, each on the map
   masked by the passes before (σ_d and R_robust recomputed), until a pass finds none (at
   most 10; a population of spikes on more than 0.1 % of the map lifts P99.9 and so R_robust,
   and one pass finds only its tallest). The spikes *dominate the top of the map* when its
   highest or its lowest pixel is one of them: they set the top that the truncation starts
   from, or R_t and with it ω_max. A fit from such a map is not worth reading either, and
   the spikes are masked (each replaced by the median of its 8 neighbours) for R_t and the
   truncation (:func:`spike_rule`). ``--spikes report`` keeps them (reported only).
3. *The default first.* The default fit is kept when it is worth reading
   (:func:`warptrunc.plausibility.check_fit`: r² ≥ 0.9, 0 < α ≤ 1, ≥ half a decade of load,
   ≥ 50 contact pixels at the deepest fitted increment), no spike sets R_t and no tilt was
   levelled.
4. *Depth.* Otherwise ω_max = 0.1·R_t of the (levelled, masked) map, brought to between 50
   pixels and 5 % of the map in contact at the deepest increment (:func:`adjust_depth`): with
   fewer than 50 contact pixels there, it extends to halfway between the depths at which the
   50th and the 51st highest pixels touch (a map of 32 × 32 pixels or more has 50 within 5 %
   of its area). While the fit over the range is not worth reading, the count doubles (from
   50, or from the pixels the range holds already: 100, 200, … within 5 % of the map) until
   it is; an extension stops at 0.5·R_t (the cap). With more than 5 % (R_t still set by
   pits), ω_max is cut back likewise to the ⌊0.05·N⌋-th highest pixel.
5. *Choice.* The first range whose fit is worth reading replaces the default one. When no
   range of the rule gives such a fit, ``analyze`` stops (:class:`AutoRangeError`, exit
   status 2) with one line: what the rule decided, why the fit of its deepest range is not
   worth reading, and the settings that give a fit worth reading on this map, each checked on
   it (:func:`refusal_advice`: ``--rt-percentile`` and ``--max-depth``, after ``--level`` and
   ``--spikes mask`` when the rule levelled or masked), or, when none does, what on the map
   keeps every range from one (a flat top of many pixels at the highest height, a large share
   of filled points). ``--fit-range legacy`` writes the default fit with its ``fit_error``.
   When neither the default range nor any range of the rule holds 3 fittable increments, the
   fit range's own error (with advice) stands.

Each decision is one ``warning:`` line (``auto_levelled``, ``auto_spikes_masked``,
``auto_depth_extended``, ``auto_depth_cut``) and a key of ``fit.json``'s ``fit_range``
(``levelled``, ``spikes_masked``, ``depth_extended``, ``depth_cut``), which also records the
rule chosen (``"legacy"`` or ``"auto"``) and why. Generated WM surfaces are not touched.
``compare`` and ``indent`` apply steps 0 and 2 to a map read from a file (spikes that set R_t
are masked as it is read).

:func:`clip_to_percentiles` clips the heights to the ``lo``-th and ``hi``-th percentiles
(``warptrunc analyze --rt-percentile 0.1 99.9``): R_t becomes P_hi − P_lo, and the pixels
above P_hi (a share of ``100 − hi`` %) touch at ω = 0. :func:`fit_range_advice` computes, for
one map, the option values that would give a non-empty fit range, so that the error message
can name them.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from .plausibility import (
    FIT_MIN_CONTACT_PIXELS,
    PlausibilityWarning,
    check_fit,
    check_fit_depth,
    fit_error_text,
    mask_spikes,
)
from .surface import Surface

__all__ = [
    "AUTO_CONTACT_PIXELS",
    "AUTO_MAX_CONTACT_SHARE",
    "AUTO_MAX_DEPTH_FRACTION",
    "MIN_FIT_POINTS",
    "MIN_MAP_SIDE",
    "REFUSAL_DEPTHS",
    "SPIKE_PASSES",
    "AutoRangeError",
    "adjust_depth",
    "automatic_range",
    "check_map_size",
    "clip_to_percentiles",
    "fit_range_advice",
    "refusal_advice",
    "spike_rule",
    "spike_warning",
    "tilt_rule",
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


# --- the automatic rule for maps read from files ----------------------------------------------

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
    sets = [
        end for end, at in (("top", z0 == z0.max()), ("bottom", z0 == z0.min())) if np.any(hit & at)
    ]
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
    where = (
        f"{n} spike pixel(s) (first at iy={loc['iy']}, ix={loc['ix']}; {passes} pass(es) "
        "of the spike rule)"
    )
    if masked is None:
        why = (
            "they set neither the highest nor the lowest pixel"
            if not sets
            else "the automatic range did not fit"
        )
        return [
            PlausibilityWarning(
                "spikes",
                f"{where}: reported, not masked: {why} (--spikes mask replaces them)",
                {**d, "action": "report", "sets": sets},
            )
        ]
    ends = " and ".join({"top": "highest", "bottom": "lowest"}[e] for e in sets)
    before, after = float(d["Rt_m"]), float(masked.Rt)
    return [
        PlausibilityWarning(
            "auto_spikes_masked",
            f"{where} include the {ends} pixel of the map: masked for R_t and the truncation, R_t "
            f"{before:.4g} m → {after:.4g} m (automatic rule; --spikes report keeps them)",
            {**d, "action": "mask", "sets": sets, "Rt_before_m": before, "Rt_after_m": after},
        )
    ]


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
    rec = {
        "from_m": float(max_depth),
        "to_m": new,
        "from_fraction": float(max_depth / Rt),
        "to_fraction": new / Rt,
        "contact_pixels_before": before,
        "contact_pixels": after,
        "target_contact_pixels": lo,
        "max_contact_share": float(max_share),
        "max_depth_fraction": float(max_fraction),
        "capped": bool(capped),
    }
    goal = (
        f"has at least {lo}"
        if action == "extended"
        else f"has at most {max_share:.0%} of the map ({hi} pixels)"
    )
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


def tilt_rule(surface: Surface) -> tuple[Surface, dict | None, list]:
    """The map levelled when its tilt spans more height than its roughness does.

    Parameters
    ----------
    surface : Surface
        The map read from a file (m); one read with ``level=True`` (``params["levelled"]``)
        is left as it is.

    Returns
    -------
    levelled : Surface
        ``surface`` minus its least-squares plane (``params["levelled"] = True``) when the
        plane's range over the map exceeds R_robust = P99.9 − P0.1 of the levelled heights;
        ``surface`` itself otherwise.
    record : dict or None
        The decision for ``fit.json`` (``plane_range_m``, ``roughness_range_m``,
        ``Rt_before_m``, ``Rt_after_m``, m), or None.
    warnings : list of PlausibilityWarning
        One ``"auto_levelled"`` warning, or empty.

    Notes
    -----
    Truncated from its highest pixel, a tilted map touches first along its high side, and the
    fit reads the plane rather than the roughness. A surface's own longest wavelength gives a
    plane too, but a small one: on WM surfaces with W_r = L (one wavelength across the map) the
    plane spans less than 0.5·R_robust. A plane that spans more than R_robust is the
    instrument's or the mounting's tilt.
    """
    from .io.repair import level_plane

    if surface.params.get("levelled"):
        return surface, None, []
    z = np.asarray(surface.heights, dtype=np.float64)
    flat = level_plane(z, surface.dx, surface.dy)
    span = float(np.ptp(z - flat))
    lo, hi = np.percentile(flat, [0.1, 99.9])
    rough = float(hi - lo)
    if not (rough > 0 and span > rough):
        return surface, None, []
    rec = {
        "plane_range_m": span,
        "roughness_range_m": rough,
        "Rt_before_m": float(np.ptp(z)),
        "Rt_after_m": float(np.ptp(flat)),
    }
    w = PlausibilityWarning(
        "auto_levelled",
        f"the least-squares plane spans {span:.4g} m across the map, more than the roughness "
        f"about it (P99.9 − P0.1 = {rough:.4g} m): a truncation would read the tilt; levelled "
        f"(the plane subtracted, as --level), R_t {rec['Rt_before_m']:.4g} m → "
        f"{rec['Rt_after_m']:.4g} m (automatic rule; --fit-range legacy keeps the map as read)",
        rec,
    )
    return Surface(flat, surface.dx, surface.dy, {**surface.params, "levelled": True}), rec, [w]


AUTO_DOUBLED = "; the fit on fewer was not worth reading, so the count doubled until it was"
"""How the ``auto_depth_extended`` warning says that the first count was not enough."""
AUTO_TOO_FEW = "; the range to fewer held fewer than 3 fittable increments"
"""... and that the range to the first count held no fit."""

REFUSAL_DEPTHS = (0.02, 0.05, 0.2, 0.3, 0.5)
"""Fractions of R_t tried as ``--max-depth`` by :func:`refusal_advice` (dimensionless)."""


class AutoRangeError(ValueError):
    """The automatic rule found no fit worth reading on a map read from a file; the message
    names what the rule decided, why the fit is not worth reading, and the option values that
    give one on this map (:func:`refusal_advice`)."""


def _legacy_state(fit, found, error, min_pixels: int) -> str | None:
    """Why the default fit is not worth reading (None: it is)."""
    if fit is None:
        return f"empty (fewer than 3 increments with ≥ {min_pixels} contact pixels)"
    why = fit_error_text(found)
    return None if why is None else f"not worth reading ({why.split(': ', 1)[1]})"


def _fit_on(
    surface: Surface,
    increments: int,
    max_depth: float,
    material,
    beta_prime: float,
    min_pixels: int,
    device,
) -> tuple:
    """(curve, stiffness curve, fit, its check_fit warnings) on ``surface`` to ``max_depth``;
    ValueError when the range holds fewer than 3 fittable increments."""
    from .stiffness import fit_power_law, stiffness_curve
    from .truncation.api import truncate

    curve = truncate(surface, increments, max_depth=max_depth, device=device)
    sc = stiffness_curve(curve, material, beta_prime=beta_prime)
    fit = fit_power_law(sc, min_pixels=min_pixels)
    return curve, sc, fit, check_fit(fit, sc)


def refusal_advice(
    surface: Surface,
    *,
    levelled: bool,
    spikes_masked: bool,
    material: Any,
    truncation: Any,
    min_pixels: int,
    device: Any = None,
) -> list[str]:
    """Option settings that give a fit worth reading on this map, each checked on it.

    Parameters
    ----------
    surface : Surface
        The map as read (m).
    levelled, spikes_masked : bool
        Whether the automatic rule levelled the map and masked spikes: the settings then start
        with ``--level`` and ``--spikes mask``, which do so as the map is read (one pass of the
        spike rule).
    material : Material
        Elastic constants of the analysis.
    truncation : TruncationSettings
        Its increments, ω_max as a fraction of R_t, and β′.
    min_pixels : int
        The fit range's ``min_pixels`` (pixels).
    device : str, optional
        Warp device.

    Returns
    -------
    list of str
        At most two settings, each with the α and r² it gives, e.g. ``"--level
        --rt-percentile 0.1 99.9 (α 0.49, r² 0.95)"``. Tried in this order: the robust height
        ranges ``--rt-percentile 0.1 99.9`` and ``1 99`` at the default depth, then
        ``--max-depth`` at the fractions :data:`REFUSAL_DEPTHS` of R_t, then each robust
        range with those fractions (``--max-depth-fraction``). A range of one's own turns the
        automatic rule off, so each is checked as the default fit on the map read with the
        settings' ``--level`` and ``--spikes mask``.
    """
    s = surface
    prefix = []
    if levelled:
        from .io.repair import level_plane

        flat = level_plane(np.asarray(s.heights, np.float64), s.dx, s.dy)
        s = Surface(flat, s.dx, s.dy, {**s.params, "levelled": True})
        prefix.append("--level")
    if spikes_masked:
        s, _ = mask_spikes(s)  # what --spikes mask does as the map is read
        prefix.append("--spikes mask")
    n, bp, frac = truncation.increments, truncation.beta_prime, truncation.max_depth_fraction
    clipped = {rng: clip_to_percentiles(s, *rng) for rng in ((0.1, 99.9), (1.0, 99.0))}
    pct = {rng: f"--rt-percentile {rng[0]:g} {rng[1]:g}" for rng in clipped}
    tries = [(pct[r], m, frac) for r, m in clipped.items()]
    tries += [(f"--max-depth {f * float(s.Rt):.3g}", s, f) for f in REFUSAL_DEPTHS]
    tries += [
        (f"{pct[r]} --max-depth-fraction {f:g}", m, f)
        for r, m in clipped.items()
        for f in REFUSAL_DEPTHS
    ]
    out: list[str] = []
    for option, mapped, fraction in tries:
        try:
            depth = fraction * float(mapped.Rt)
            _, _, fit, found = _fit_on(mapped, n, depth, material, bp, min_pixels, device)
        except ValueError:
            continue
        if not found:
            out.append(f"{' '.join([*prefix, option])} (α {fit.alpha:.2f}, r² {fit.r2:.2f})")
            if len(out) == 2:
                break
    return out


_SHORT = {
    "fit_r2": lambda d: f"r² {d['r2']:.3g} < {d['min_r2']:g}",
    "fit_alpha": lambda d: f"α {d['alpha']:.2f} outside (0, 1]",
    "fit_contact_pixels": lambda d: (
        f"{d['contact_pixels']} contact pixels < {d['min_contact_pixels']}"
    ),
    "fit_load_decades": lambda d: f"{d['decades']:.2f} decades of load < {d['min_decades']:g}",
}
"""The reason of each ``check_fit`` warning in a few words (the refusal's line)."""


def _diagnosis(surface: Surface) -> str:
    """What on the map keeps every range from a fit worth reading, where it can be named."""
    z = np.asarray(surface.heights)
    top = int(np.count_nonzero(z == z.max()))
    notes = []
    if top >= AUTO_CONTACT_PIXELS:
        notes.append(
            f"its highest height is shared by {top} pixels (a flat top: saturated or filled points)"
        )
    missing = int(surface.params.get("n_missing") or 0)
    if missing > 0.1 * z.size:
        notes.append(f"{missing / z.size:.0%} of its points were missing and filled")
    return ": " + " and ".join(notes) if notes else ""


def automatic_range(
    surface: Surface,
    legacy: tuple,
    *,
    material: Any,
    truncation: Any,
    fit_range: Any,
    indicators: Callable[[Surface], Any] | None = None,
    device: Any = None,
) -> tuple[tuple | None, dict, list]:
    """The automatic rule on a map read from a file, as :func:`warptrunc.analysis.analyze`
    applies it (the module docstring states the rule).

    Parameters
    ----------
    surface : Surface
        The map as read (m), at least 32 pixels a side.
    legacy : tuple
        The default range's result on ``surface``: (PowerLawFit or None, its warnings, the
        fit's ValueError or None).
    material : Material
        Elastic constants.
    truncation : TruncationSettings
        Increments, ω_max as a fraction of R_t, β′.
    fit_range : FitRange
        ``min_pixels``; ``spikes`` lets the rule mask the spikes that set R_t.
    indicators : callable, optional
        Surface → § 4.3's indicators (or None) of the map the automatic range is fitted on;
        None: none computed.
    device : str, optional
        Warp device.

    Returns
    -------
    result : tuple or None
        (surface, ω_max (m), TruncationCurve, StiffnessCurve, PowerLawFit, its warnings,
        indicators) on the automatic range, or None when the default result stands.
    record : dict
        ``fit.json``'s ``fit_range``: ``asked``, ``rule``, ``reason``, ``levelled``,
        ``spikes_masked``, ``depth_extended``, ``depth_cut`` (each None when not decided) and,
        for ``rule = "auto"``, ``max_depth_m`` (m).
    decided : list of PlausibilityWarning
        One warning line per decision (and the spikes reported but kept).

    Raises
    ------
    AutoRangeError
        No range of the rule gives a fit worth reading: the message names the decisions, the
        reason, and the settings that give one on this map (:func:`refusal_advice`).
    """
    n_inc, beta_prime = truncation.increments, truncation.beta_prime
    min_pixels, auto_spikes = fit_range.min_pixels, fit_range.spikes
    state = _legacy_state(*legacy, min_pixels)
    flat, tilt, tilt_w = tilt_rule(surface)
    masked, found, sets = spike_rule(flat) if auto_spikes else (flat, [], [])
    s = masked if sets else flat
    rec = {
        "asked": "auto",
        "rule": "legacy",
        "levelled": None,
        "spikes_masked": None,
        "depth_extended": None,
        "depth_cut": None,
    }
    if state is None and not sets and tilt is None:
        why = (
            "the default fit is worth reading"
            + (", no spike sets R_t" if auto_spikes else "")
            + " and no tilt spans more than the roughness"
        )
        return None, {**rec, "reason": why}, spike_warning(found, sets)
    ends = " and ".join({"top": "highest", "bottom": "lowest"}[e] for e in sets)
    state = state or (
        f"set by spikes (they include the {ends} pixel of the map)"
        if sets
        else "read on a tilted map"
    )
    z = np.asarray(s.heights)
    omega0 = truncation.max_depth_fraction * float(z.max() - z.min())
    omega, action, depth, depth_w = adjust_depth(z, omega0)

    def fit_to(omega):
        return _fit_on(s, n_inc, omega, material, beta_prime, min_pixels, device)

    fits = []  # (target, action, ω_max, record, warnings, curve, stiffness curve, fit, warnings)
    with contextlib.suppress(ValueError):
        fits.append((AUTO_CONTACT_PIXELS, action, omega, depth, depth_w, *fit_to(omega)))
    # no fit worth reading yet: the contact pixels of the deepest increment double (from 50,
    # or from those of a range that holds more already), within 5 % of A and 0.5·R_t
    held = int(np.count_nonzero(z >= np.float32(z.max()) - np.float32(omega)))
    target = AUTO_CONTACT_PIXELS if action == "extended" else max(AUTO_CONTACT_PIXELS, held)
    capped = action == "extended" and depth["capped"]
    while action != "cut" and not capped and not any(not f[-1] for f in fits):
        target *= 2
        o2, more, d2, w2 = adjust_depth(z, omega0, contact_pixels=target)
        if target > AUTO_MAX_CONTACT_SHARE * z.size or more is None:
            break
        capped = d2["capped"]
        with contextlib.suppress(ValueError):
            fits.append((target, more, o2, d2, w2, *fit_to(o2)))
    decided = tilt_w + spike_warning(found, sets, s if sets else None)
    if not fits and legacy[0] is None:  # nothing to fit either way: the fit range's error
        why = (f"the default fit is {state}; the automatic range holds fewer than 3 increments "
               f"with ≥ {min_pixels} contact pixels")  # fmt: skip
        return None, {**rec, "reason": why}, spike_warning(found, sets)
    good = [f for f in fits if not f[-1]]
    if not good:
        raise AutoRangeError(
            _refusal(surface, s, fits, tilt, sets, material, truncation, min_pixels, device)
        )
    target, action, omega, depth, depth_w, curve, sc, fit, found_fit = good[0]
    if action == "extended" and target > AUTO_CONTACT_PIXELS:  # the warning says why
        note = AUTO_DOUBLED if fits.index(good[0]) > 0 else AUTO_TOO_FEW
        _, _, depth, depth_w = adjust_depth(z, omega0, contact_pixels=target, note=note)
    ind = indicators(s) if indicators is not None else None
    if ind is not None:
        found_fit = found_fit + check_fit_depth(fit, ind)
    spikes = None
    if sets:
        d = decided[len(tilt_w)].details
        spikes = {k: d[k] for k in ("count", "passes", "sets", "Rt_before_m", "Rt_after_m")}
    rec = {
        **rec,
        "rule": "auto",
        "reason": f"the default fit is {state}",
        "levelled": tilt,
        "spikes_masked": spikes,
        "max_depth_m": omega,
    }
    if action is not None:
        rec[f"depth_{action}"] = depth
    return (s, omega, curve, sc, fit, found_fit, ind), rec, decided + depth_w


def _refusal(
    surface: Surface,
    s: Surface,
    fits: list,
    tilt,
    sets,
    material,
    truncation,
    min_pixels: int,
    device,
) -> str:
    """The one line of :class:`AutoRangeError`: ``surface`` as read, ``s`` as the rule made
    it, ``fits`` the ranges it tried."""
    name = str(surface.params.get("source") or "the map")
    done = (["levelled"] if tilt else []) + (["spikes masked"] if sets else [])
    if fits:
        depths = sorted({f[2] / float(s.Rt) for f in fits})
        span = f"{depths[0]:.2g}" + (f"–{depths[-1]:.2g}" if len(depths) > 1 else "")
        done.append(f"ω_max {span}·R_t")
        why = ", ".join(_SHORT[w.code](w.details) for w in fits[-1][-1] if w.code in _SHORT)
    else:
        why = f"fewer than 3 increments with ≥ {min_pixels} contact pixels"
    advice = refusal_advice(
        surface,
        levelled=tilt is not None,
        spikes_masked=bool(sets),
        material=material,
        truncation=truncation,
        min_pixels=min_pixels,
        device=device,
    )
    head = (
        f"{name}: no fit worth reading (automatic rule: {', '.join(done) or 'no decision'}; {why})"
    )
    tail = "; or --fit-range legacy: the default fit, flagged"
    if advice:
        return f"{head}; on this map these give one: " + "; ".join(advice) + tail
    return (
        f"{head}; no --rt-percentile or --max-depth gives one on this map"
        f"{_diagnosis(surface)}{tail}"
    )
