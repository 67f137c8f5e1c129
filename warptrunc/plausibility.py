# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Plausibility checks: warnings (not errors) about maps, fractal dimensions and fits.

Every check is one function returning a list of :class:`PlausibilityWarning` (empty when all
is well): a stable ``code``, a one-line ``message`` and ``details`` (JSON-serialisable, SI
units). The commands write them as a ``"warnings"`` list into every JSON output and print
each as one ``warning: <code>: <message>`` line on stderr (:func:`report`).

=====================  =====================================================================
code                   check
=====================  =====================================================================
``spikes``             :func:`check_spikes`: isolated pixels far off their neighbours
``dimension_range``    :func:`check_dimensions`: a measured D outside (2, 3)
``fit_*``              :func:`check_fit`: a power-law fit not worth reading
``fit_past_validity``  :func:`check_fit_depth`: the fit range runs past § 4.3's depths
=====================  =====================================================================

**Spike rule.** With d = z − median of the 8 neighbours of a pixel, σ_d = 1.4826·MAD of d
over the whole map (a robust scale of pixel-to-pixel roughness) and R_robust = P99.9 − P0.1
of the heights (a height range that a few spikes cannot move, unlike R_t), a pixel is a spike
when all three hold:

1. ``|d|`` > ``k``·σ_d (default k = 10): far outside the map's own pixel-scale roughness;
2. ``|d|`` > ``share``·R_robust (default share = 0.5): a jump of half the height range or more;
3. fewer than 4 of its 8 neighbours lie within ``|d|/2`` of it: a needle of a few pixels, not
   the top of a hill whose flanks rise to it.

The isolated high peaks that truncation starts from pass: on WM surfaces (D 2.1–2.9, 256²
and 512²) the largest ``|d|`` is below 7·σ_d and below 0.43·R_robust (D = 2.9, 256²; 0.29 at
512²), and on measured scans without artefacts below 30·σ_d and 0.15·R_robust. Flagged pixels
are only reported by default; ``mask_spikes`` (``--spikes mask``) replaces each with the median of
its 8 neighbours, so that R_t is recomputed without it.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, TextIO

import numpy as np

from ._support.docs import SHARED_DOCS, fill_doc

__all__ = [
    "FIT_MIN_CONTACT_PIXELS",
    "FIT_MIN_DECADES",
    "FIT_MIN_R2",
    "SPIKE_K",
    "SPIKE_SHARE",
    "PlausibilityWarning",
    "check_dimensions",
    "check_fit",
    "check_fit_depth",
    "check_spikes",
    "find_spikes",
    "fit_error_text",
    "mask_spikes",
    "report",
]

SPIKE_K = 10.0
"""Spike rule 1: ``|d|`` above this many robust standard deviations σ_d of d (dimensionless)."""
SPIKE_SHARE = 0.5
"""Spike rule 2: ``|d|`` above this share of R_robust = P99.9 − P0.1 (dimensionless)."""
SPIKE_DOCS = {
    **SHARED_DOCS,
    "{spike_rule}": (
        "k : float\n    Rule 1 of the spike rule (dimensionless).\n"
        "share : float\n    Rule 2 of the spike rule (dimensionless)."
    ),
}
SPIKE_DOCS["{spike_params}"] = SPIKE_DOCS["{surface}"] + "\n" + SPIKE_DOCS["{spike_rule}"]
"""Docstring text of the spike functions, written once (:func:`fill_doc`)."""
FIT_MIN_R2 = 0.9
"""A fit with r² below this is not worth reading (dimensionless)."""
FIT_MIN_DECADES = 0.5
"""A fit over less than this many decades of load F is not worth reading (decades)."""
FIT_MIN_CONTACT_PIXELS = 50
"""A fit whose deepest increment has fewer contact pixels is not worth reading (pixels): A_c
then moves in steps of 2 % of itself or more."""
_LISTED = 20  # locations listed in a warning's details


@dataclass(frozen=True)
class PlausibilityWarning:
    """One plausibility warning: something to look at, not an error."""

    code: str
    """Stable identifier (``"spikes"``, ``"dimension_range"``, ``"fit_r2"``, ...)."""
    message: str
    """One line for people."""
    details: dict[str, Any] = field(default_factory=dict)
    """JSON-serialisable numbers behind the message (SI units)."""

    def to_dict(self) -> dict[str, Any]:
        """``{"code", "message", "details"}``.

        Returns
        -------
        dict of str to Any
            The three fields; ``details`` is a copy.
        """
        return {"code": self.code, "message": self.message, "details": dict(self.details)}

    def __str__(self) -> str:
        return f"warning: {self.code}: {self.message}"


def report(warnings: Iterable[PlausibilityWarning], file: TextIO | None = None) -> list[dict]:
    """Print each warning as one ``warning: <code>: <message>`` line; return their dicts.

    Parameters
    ----------
    warnings : iterable of PlausibilityWarning
        The warnings.
    file : file-like, optional
        Where to print; default ``sys.stderr``.

    Returns
    -------
    list of dict
        :meth:`PlausibilityWarning.to_dict` of each, for the ``"warnings"`` key of a JSON
        output.
    """
    out = []
    for w in warnings:
        print(str(w), file=sys.stderr if file is None else file)
        out.append(w.to_dict())
    return out


# --- spikes ------------------------------------------------------------------------------------


def _neighbour_stack(z: np.ndarray, r0: int, r1: int) -> np.ndarray:
    """(8, r1 − r0, nx) heights of the 8 neighbours of rows r0..r1 (mirrored at the edges)."""
    ny, nx = z.shape
    lo, hi = max(r0 - 1, 0), min(r1 + 1, ny)
    block = z[lo:hi]
    top = 1 if r0 == 0 else 0
    bottom = 1 if r1 == ny else 0
    p = np.pad(block, ((top, bottom), (1, 1)), mode="reflect" if min(ny, nx) > 1 else "edge")
    n = r1 - r0
    return np.stack(
        [
            p[1 + dy : 1 + dy + n, 1 + dx : 1 + dx + nx]
            for dy in (-1, 0, 1)
            for dx in (-1, 0, 1)
            if (dy, dx) != (0, 0)
        ]
    )


def _bands(ny: int, nx: int) -> Iterable[tuple[int, int]]:
    rows = max(1, (1 << 20) // max(nx, 1))  # about 1 M pixels (64 MB of float64 stacks) a band
    for r0 in range(0, ny, rows):
        yield r0, min(ny, r0 + rows)


def _residual(z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(d, median of the 8 neighbours), float64, by row bands."""
    d = np.empty(z.shape, dtype=np.float64)
    med = np.empty(z.shape, dtype=np.float64)
    for r0, r1 in _bands(*z.shape):
        nb = _neighbour_stack(z, r0, r1).astype(np.float64)
        med[r0:r1] = np.median(nb, axis=0)
        d[r0:r1] = z[r0:r1] - med[r0:r1]
    return d, med


def find_spikes(
    heights: Any, *, k: float = SPIKE_K, share: float = SPIKE_SHARE
) -> tuple[np.ndarray, np.ndarray, dict[str, float]]:
    """Pixels that are spikes by the rule of this module's docstring.

    Parameters
    ----------
    heights : (ny, nx) array_like
        Heights z (m), finite.
    k : float
        Rule 1: ``|d|`` > k·σ_d (dimensionless, > 0).
    share : float
        Rule 2: ``|d|`` > share·R_robust (dimensionless, > 0).

    Returns
    -------
    iy, ix : (m,) int64 ndarray
        Row and column of each flagged pixel, in raster order.
    scales : dict of str to float
        ``sigma_d_m`` (σ_d, m), ``R_robust_m`` (m), ``Rt_m`` (m) and ``neighbour_median_m``,
        a (m,) list of the neighbour medians of the flagged pixels (m).

    Raises
    ------
    ValueError
        If ``k`` or ``share`` is not positive, or ``heights`` is not 2-D.
    """
    if not (k > 0 and math.isfinite(k)):
        raise ValueError(f"k must be a positive number of σ_d, got {k!r}")
    if not (share > 0 and math.isfinite(share)):
        raise ValueError(f"share must be a positive share of R_robust, got {share!r}")
    z = np.ascontiguousarray(heights, dtype=np.float32)
    if z.ndim != 2:
        raise ValueError(f"heights must be 2-D, got shape {z.shape}")
    empty = np.zeros(0, dtype=np.int64)
    Rt = float(z.max() - z.min()) if z.size else 0.0
    if min(z.shape) < 3 or Rt == 0.0:
        return (
            empty,
            empty,
            {"sigma_d_m": 0.0, "R_robust_m": 0.0, "Rt_m": Rt, "neighbour_median_m": []},
        )
    d64, med = _residual(z)
    sigma = 1.4826 * float(np.median(np.abs(d64 - np.median(d64))))
    p_lo, p_hi = np.percentile(z, [0.1, 99.9])
    r_robust = float(p_hi) - float(p_lo)
    ad = np.abs(d64)
    cand = (ad > k * sigma) & (ad > share * r_robust)
    iy, ix = np.nonzero(cand)
    keep = np.zeros(iy.size, dtype=bool)
    for j, (y, x) in enumerate(zip(iy, ix, strict=True)):  # few candidates: a loop is enough
        nb = _neighbour_stack(z, int(y), int(y) + 1)[:, 0, int(x)].astype(np.float64)
        close = np.count_nonzero(np.abs(nb - float(z[y, x])) < ad[y, x] / 2)
        keep[j] = close < 4
    iy, ix = iy[keep].astype(np.int64), ix[keep].astype(np.int64)
    scales = {
        "sigma_d_m": sigma,
        "R_robust_m": r_robust,
        "Rt_m": Rt,
        "neighbour_median_m": med[iy, ix].tolist(),
    }
    return iy, ix, scales


def _spike_warning(
    surface: Any, iy, ix, scales, k, share, action: str, passes: int = 1
) -> PlausibilityWarning:
    z = np.asarray(surface.heights)
    locs = [
        {
            "iy": int(y),
            "ix": int(x),
            "x_m": float(x * surface.dx),
            "y_m": float(y * surface.dy),
            "z_m": float(z[y, x]),
        }
        for y, x in zip(iy[:_LISTED], ix[:_LISTED], strict=True)
    ]
    first = locs[0]
    what = (
        "masked (replaced by the median of their 8 neighbours)"
        if action == "mask"
        else ("reported, not masked (--spikes mask replaces them)")
    )
    more = f" ({passes} passes of the rule)" if passes > 1 else ""
    return PlausibilityWarning(
        "spikes",
        f"{iy.size} spike pixel(s) (first at iy={first['iy']}, ix={first['ix']}): off the median "
        f"of their neighbours by more than {k:g}·σ_d and {share:g}·R_robust; {what}{more}",
        {
            "count": int(iy.size),
            "locations": locs,
            "listed": len(locs),
            "action": action,
            "k": k,
            "share": share,
            "sigma_d_m": scales["sigma_d_m"],
            "R_robust_m": scales["R_robust_m"],
            "Rt_m": scales["Rt_m"],
            "passes": passes,
        },
    )


@fill_doc(SPIKE_DOCS)
def check_spikes(
    surface: Any, *, k: float = SPIKE_K, share: float = SPIKE_SHARE
) -> list[PlausibilityWarning]:
    """Warn about spike pixels (reported, not changed).

    Parameters
    ----------
    {spike_params}

    Returns
    -------
    list of PlausibilityWarning
        One ``"spikes"`` warning with ``count``, the first 20 ``locations`` (``iy``, ``ix``,
        ``x_m``, ``y_m``, ``z_m``), σ_d, R_robust and R_t (m); empty when none is found.
    """
    iy, ix, scales = find_spikes(surface.heights, k=k, share=share)
    if iy.size == 0:
        return []
    return [_spike_warning(surface, iy, ix, scales, k, share, "report")]


@fill_doc(SPIKE_DOCS)
def mask_spikes(
    surface: Any, *, k: float = SPIKE_K, share: float = SPIKE_SHARE, passes: int = 1
) -> tuple[Any, list[PlausibilityWarning]]:
    """The surface with every spike pixel replaced by the median of its 8 neighbours.

    Parameters
    ----------
    {spike_params}
    passes : int
        Apply the rule again to the masked map (σ_d and R_robust recomputed from it) until a
        pass finds no spike or after this many passes (≥ 1). Spikes on more than 0.1 % of the
        map lift P99.9, and with it R_robust, so that one pass finds only the tallest of them.

    Returns
    -------
    surface : Surface
        A new surface (R_t recomputed from the masked heights; ``params`` records
        ``n_spikes_masked`` and ``Rt_raw_m``), or ``surface`` itself when none is found.
    warnings : list of PlausibilityWarning
        The ``"spikes"`` warning (``action: "mask"``; ``count`` over all passes, ``passes``
        the passes that found spikes), or empty.

    Notes
    -----
    Within a pass, neighbour medians are those of the map the pass starts from.
    """
    from .surface import Surface

    if not (isinstance(passes, (int, np.integer)) and passes >= 1):
        raise ValueError(f"passes must be an integer ≥ 1, got {passes!r}")
    z = np.array(surface.heights, dtype=np.float32)
    hit = np.zeros(z.shape, dtype=bool)
    first = None
    n_pass = 0
    for _ in range(int(passes)):
        iy, ix, scales = find_spikes(z, k=k, share=share)
        first = scales if first is None else first
        if iy.size == 0:
            break
        n_pass += 1
        z[iy, ix] = np.asarray(scales["neighbour_median_m"], dtype=np.float32)
        hit[iy, ix] = True
    if n_pass == 0:
        return surface, []
    iy, ix = (a.astype(np.int64) for a in np.nonzero(hit))
    params = {**surface.params, "n_spikes_masked": int(iy.size), "Rt_raw_m": first["Rt_m"]}
    w = _spike_warning(surface, iy, ix, first, k, share, "mask", n_pass)
    return Surface(z, surface.dx, surface.dy, params), [w]


# --- fractal dimensions --------------------------------------------------------------------------


def check_dimensions(dimensions: Mapping[str, float | None]) -> list[PlausibilityWarning]:
    """Warn about every measured fractal dimension outside (2, 3).

    Parameters
    ----------
    dimensions : mapping of str to float or None
        D by method (``{"sp": 3.4, "tri": 2.31}``; dimensionless); None or NaN (a method that
        did not fit) is skipped.

    Returns
    -------
    list of PlausibilityWarning
        One ``"dimension_range"`` warning per D ≤ 2 or ≥ 3 (``details``: ``method``, ``D``).
    """
    out = []
    for m, D in dimensions.items():
        if D is None or not math.isfinite(float(D)):
            continue
        D = float(D)
        if not 2.0 < D < 3.0:
            out.append(
                PlausibilityWarning(
                    "dimension_range",
                    f"D_{m} = {D:.4g} is outside (2, 3), the range of a rough surface: the map is "
                    "not self-affine over the scales this method fits (noise, tilt, form, spikes)",
                    {"method": m, "D": D},
                )
            )
    return out


# --- fits ----------------------------------------------------------------------------------------


def check_fit(
    fit: Any,
    curve: Any,
    *,
    min_r2: float = FIT_MIN_R2,
    min_decades: float = FIT_MIN_DECADES,
    min_contact_pixels: int = FIT_MIN_CONTACT_PIXELS,
    label: str = "fit",
) -> list[PlausibilityWarning]:
    """Warn when a power-law fit is not worth reading.

    Parameters
    ----------
    fit : PowerLawFit
        The fit (:func:`warptrunc.stiffness.fit_power_law`).
    curve : StiffnessCurve
        The curve it was fitted to.
    min_r2 : float
        Warn below this r² (dimensionless).
    min_decades : float
        Warn when F_max/F_min over the fit range is below 10^min_decades (decades).
    min_contact_pixels : int
        Warn when the deepest fitted increment has fewer contact pixels (pixels).
    label : str
        Name of the fit in the messages (``"fit"``, ``"islands fit"``).

    Returns
    -------
    list of PlausibilityWarning
        Codes ``fit_contact_pixels``, ``fit_r2``, ``fit_alpha`` (α outside (0, 1]) and
        ``fit_load_decades``; empty for a fit worth reading.
    """
    out = []
    sel = (np.asarray(curve.depth) >= fit.depth_min) & (np.asarray(curve.depth) <= fit.depth_max)
    n_last = int(np.asarray(curve.n_contact_pixels)[sel].max()) if sel.any() else 0
    base = {"alpha": fit.alpha, "r2": fit.r2, "n_points": fit.n_points}
    if n_last < min_contact_pixels:
        out.append(
            PlausibilityWarning(
                "fit_contact_pixels",
                f"{label}: only {n_last} contact pixels at the deepest fitted increment (< "
                f"{min_contact_pixels}): A_c moves by whole pixels, the fit reads the pixel staircase",
                {**base, "contact_pixels": n_last, "min_contact_pixels": min_contact_pixels},
            )
        )
    if not fit.r2 >= min_r2:
        out.append(
            PlausibilityWarning(
                "fit_r2",
                f"{label}: r² = {fit.r2:.3g} < {min_r2:g}: not a power law over this range",
                {**base, "min_r2": min_r2},
            )
        )
    if not 0.0 < fit.alpha <= 1.0:
        out.append(
            PlausibilityWarning(
                "fit_alpha",
                f"{label}: α = {fit.alpha:.4g} is outside (0, 1]",
                {**base, "allowed": [0.0, 1.0]},
            )
        )
    lo, hi = float(fit.F_over_EA_min), float(fit.F_over_EA_max)
    decades = math.log10(hi / lo) if lo > 0 and hi > 0 else 0.0
    if decades < min_decades:
        out.append(
            PlausibilityWarning(
                "fit_load_decades",
                f"{label}: the fit spans {decades:.3g} decades of load (< {min_decades:g})",
                {**base, "decades": decades, "min_decades": min_decades},
            )
        )
    return out


def fit_error_text(warnings: Iterable[PlausibilityWarning]) -> str | None:
    """The ``fit_error`` text of a fit with warnings from :func:`check_fit` (None: none).

    Parameters
    ----------
    warnings : iterable of PlausibilityWarning
        Warnings of one fit.

    Returns
    -------
    str or None
        ``"not worth reading: <message>; <message>"``, or None when there is no ``fit_*``
        warning other than ``fit_past_validity``.
    """
    msgs = [
        w.message for w in warnings if w.code.startswith("fit_") and w.code != "fit_past_validity"
    ]
    return "not worth reading: " + "; ".join(msgs) if msgs else None


def check_fit_depth(fit: Any, indicators: Any, *, label: str = "fit") -> list[PlausibilityWarning]:
    """Warn when the fit range runs past the applicable depth of § 4.3 (Table 2).

    Parameters
    ----------
    fit : PowerLawFit
        The fit.
    indicators : Indicators
        :func:`warptrunc.islands.applicable_depth` of the same map, from an island curve deep
        enough to contain the maximum growth rate of the island count (0.5·R_t covers it on the
        paper's surfaces).
    label : str
        Name of the fit in the messages.

    Returns
    -------
    list of PlausibilityWarning
        One ``"fit_past_validity"`` warning when the deepest fitted depth lies beyond the depth
        of maximum growth rate of the island number, or beyond the fractality depth (where the
        perimeter–area power law is lost; only when that depth is not censored).

    Notes
    -----
    The paper's Table 2 bounds the method by these two indicators: beyond them islands merge
    and interact, and the truncated set is no longer described by one fractal dimension.
    """
    limits = {"max_growth_rate_depth_m": float(indicators.max_growth_depth)}
    fd = float(indicators.fractal_depth)
    if math.isfinite(fd) and not indicators.fractal_depth_censored:
        limits["fractality_depth_m"] = fd
    bound = min(limits.values())
    if not fit.depth_max > bound:
        return []
    Rt = float(indicators.Rt)
    which = " and ".join(
        k.replace("_m", "").replace("_", " ") for k, v in limits.items() if fit.depth_max > v
    )
    return [
        PlausibilityWarning(
            "fit_past_validity",
            f"{label}: the fit range reaches ω = {100 * fit.depth_max / Rt:.3g} % of R_t, past the "
            f"{which} ({100 * bound / Rt:.3g} % of R_t), where § 4.3 (Table 2) ends the method's "
            "applicable range",
            {"fit_depth_max_m": float(fit.depth_max), **limits, "Rt_m": Rt},
        )
    ]
