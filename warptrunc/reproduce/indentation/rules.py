# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The rules by which the ``indentation`` stage reads its numbers against the paper's text,
as functions of plain tables so that each can be checked by hand.

* :func:`hardness_range` — the hardness values H whose punch depth at the largest load lies in a
  band around the paper's "around 5 µm" (§ 4.1): the depths of the sweep's H values joined by
  straight lines in log H – log depth, and the band's edges found on those lines.
* :func:`depth_match` — the H of the sweep that best matches the target depth: the one nearest
  (in log H) to where the interpolated depth equals the target.
* :func:`depth_at_load` — the punch depth at one load: per punch the median and range over
  the indents, and the punch that goes deepest.
* :func:`agreement_depth` — how deep truncation stays within ±20 % of a contact model: the
  cells walked in order of their truncation depth ω, from the shallowest, until the first cell
  outside the band (the paper's "in the range 0 to … % R_t′", § 4.2).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["agreement_depth", "depth_at_load", "depth_match", "hardness_range"]


def _clean(hardness: Any, depth: Any) -> tuple[np.ndarray, np.ndarray]:
    """Finite, positive (H, depth) pairs sorted by H, as logarithms."""
    h = np.asarray([math.nan if v is None else v for v in hardness], np.float64)
    d = np.asarray([math.nan if v is None else v for v in depth], np.float64)
    ok = np.isfinite(h) & np.isfinite(d) & (h > 0) & (d > 0)
    order = np.argsort(h[ok])
    return np.log(h[ok][order]), np.log(d[ok][order])


def _exact(hardness: Any, log_h: float) -> float:
    """The value of ``hardness`` whose logarithm is ``log_h`` (as given, not exp(log))."""
    return float(
        min(
            (h for h in hardness if h is not None and 0 < h < math.inf),
            key=lambda h: abs(math.log(h) - log_h),
        )
    )


def hardness_range(hardness: Any, depth: Any, band: tuple[float, float]) -> dict[str, Any]:
    """The H values whose depth lies in ``band``, on the log–log lines between the sweep's points.

    Parameters
    ----------
    hardness : sequence of float
        Hardness values H of the sweep (Pa); inf and None are left out.
    depth : sequence of float
        Punch depth at the largest load for each H (m); None or NaN: left out.
    band : (float, float)
        Lowest and highest depth taken as consistent (m), 0 < low < high.

    Returns
    -------
    dict
        ``intervals``: [[H_low, H_high], …] (Pa) where the interpolated depth lies in the band,
        merged and increasing; ``low``, ``high``: their ends (None when empty); ``contiguous``;
        ``open_below`` / ``open_above``: the band is met at the sweep's softest / hardest H, so a
        softer / harder H may fit too (the sweep does not say); ``n_points`` (H values used).

    Raises
    ------
    ValueError
        ``band`` not 0 < low < high.
    """
    lo, hi = (float(v) for v in band)
    if not 0 < lo < hi:
        raise ValueError(f"band must be (low, high) depths with 0 < low < high (m), got {band!r}")
    x, y = _clean(hardness, depth)
    a, b = math.log(lo), math.log(hi)
    spans: list[list[float]] = []
    if x.size == 1 and a <= y[0] <= b:
        spans.append([x[0], x[0]])
    for i in range(x.size - 1):
        y0, y1 = y[i], y[i + 1]
        if y1 == y0:
            t0, t1 = (0.0, 1.0) if a <= y0 <= b else (1.0, 0.0)
        else:
            ta, tb = (a - y0) / (y1 - y0), (b - y0) / (y1 - y0)
            t0, t1 = max(0.0, min(ta, tb)), min(1.0, max(ta, tb))
        if t0 <= t1:
            spans.append([x[i] + t0 * (x[i + 1] - x[i]), x[i] + t1 * (x[i + 1] - x[i])])
    merged: list[list[float]] = []
    for s in spans:
        if merged and s[0] <= merged[-1][1] + 1e-12:
            merged[-1][1] = max(merged[-1][1], s[1])
        else:
            merged.append(list(s))
    iv = [[float(math.exp(u)), float(math.exp(v))] for u, v in merged]
    return {
        "intervals": iv,
        "low": iv[0][0] if iv else None,
        "high": iv[-1][1] if iv else None,
        "contiguous": len(iv) == 1,
        "open_below": bool(iv) and x.size > 0 and math.isclose(merged[0][0], x[0], abs_tol=1e-12),
        "open_above": bool(iv) and x.size > 0 and math.isclose(merged[-1][1], x[-1], abs_tol=1e-12),
        "n_points": int(x.size),
    }


def depth_match(
    hardness: Any, depth: Any, target: float, band: tuple[float, float]
) -> dict[str, Any]:
    """The sweep's H that best matches the target depth.

    Parameters
    ----------
    hardness : sequence of float
        Hardness values H of the sweep (Pa); inf and None are left out.
    depth : sequence of float
        Punch depth at the largest load for each H (m).
    target : float
        The depth to match (m), inside ``band``.
    band : (float, float)
        Depths taken as consistent (m).

    Returns
    -------
    dict
        ``H_target``: the H where the log–log line through the points first reaches ``target``
        (Pa; None when the sweep's depths do not bracket it); ``H_match``: the sweep's H nearest
        to ``H_target`` in log H or, when the target is not bracketed, the H whose depth in the
        band is nearest ``target`` in log depth (None when no depth of the sweep, interpolated
        or not, reaches the band); ``reason`` (one phrase).

    Raises
    ------
    ValueError
        ``target`` outside ``band``.
    """
    if not band[0] <= target <= band[1]:
        raise ValueError(f"target must lie in band {band!r} (m), got {target!r}")
    x, y = _clean(hardness, depth)
    t = math.log(target)
    h_target = None
    for i in range(x.size - 1):
        y0, y1 = y[i], y[i + 1]
        if min(y0, y1) <= t <= max(y0, y1):
            f = 0.0 if y1 == y0 else (t - y0) / (y1 - y0)
            h_target = math.exp(x[i] + f * (x[i + 1] - x[i]))
            break
    if x.size == 1 and y[0] == t:
        h_target = math.exp(x[0])
    if h_target is not None:
        k = int(np.argmin(np.abs(x - math.log(h_target))))
        return {
            "H_target": h_target,
            "H_match": _exact(hardness, x[k]),
            "reason": "the sweep's H nearest (log H) to the interpolated target",
        }
    inb = [k for k in range(x.size) if band[0] <= math.exp(y[k]) <= band[1]]
    if inb:  # only an end point of the sweep in the band (points that straddle it bracket it)
        k = min(inb, key=lambda k: abs(y[k] - t))
        return {
            "H_target": None,
            "H_match": _exact(hardness, x[k]),
            "reason": "the target is not bracketed; the H whose depth is nearest in the band",
        }
    return {"H_target": None, "H_match": None, "reason": "no depth of the sweep reaches the band"}


def agreement_depth(omega: Any, ratio: Any, good: float = 0.2) -> dict[str, Any]:
    """How deep truncation stays within ±``good`` of a model, walking the cells by depth.

    Parameters
    ----------
    omega : sequence of float
        Truncation depth ω of each cell (any unit; the result is in the same one).
    ratio : sequence of float
        E_c,trunc/E_c,model of each cell (dimensionless, > 0); None or NaN: the cell is left
        out.
    good : float
        Half-width of the band around 1 (dimensionless).

    Returns
    -------
    dict
        ``depth``: ω of the last cell inside the band before the first one outside, walking from
        the shallowest (None when the shallowest cell is outside); ``leaves_at``: ω of that
        first cell outside (None when every cell is inside: the agreement reaches the deepest
        cell); ``n_cells`` (cells with a ratio), ``n_in`` (cells walked inside the band),
        ``deepest`` (ω of the deepest cell), ``shallowest``.

    Notes
    -----
    Cells of equal ω are walked in the order given. The paper's ranges (§ 4.2, Table 2) are
    read the same way: agreement from 0 to a depth, then divergence.
    """
    w = np.asarray([math.nan if v is None else v for v in omega], np.float64)
    r = np.asarray([math.nan if v is None else v for v in ratio], np.float64)
    ok = np.isfinite(w) & np.isfinite(r) & (r > 0)
    w, r = w[ok], r[ok]
    order = np.argsort(w, kind="stable")
    depth = leaves = None
    n_in = 0
    for k in order:
        if abs(r[k] - 1.0) <= good + 1e-12:
            depth = float(w[k])
            n_in += 1
            continue
        leaves = float(w[k])
        break
    return {
        "depth": depth,
        "leaves_at": leaves,
        "n_cells": int(w.size),
        "n_in": n_in,
        "deepest": float(w.max()) if w.size else None,
        "shallowest": float(w.min()) if w.size else None,
    }


def depth_at_load(punch: Any, load: Any, depth: Any, ok: Any, at: float) -> dict[str, Any]:
    """The punch depth δ at load ``at``: per punch over its indents, and the deepest punch.

    Parameters
    ----------
    punch : sequence of float
        Punch diameter of each cell (m).
    load : sequence of float
        Peak load of each cell (N).
    depth : sequence of float
        Punch depth (approach from first touch) of each cell (m).
    ok : sequence of bool
        Cells that count (converged).
    at : float
        The load (N).

    Returns
    -------
    dict
        ``per_punch``: diameter → ``median``, ``min``, ``max`` (m) and ``n`` (indents);
        ``deepest``: the punch with the largest median and its numbers (None when no cell
        counts).
    """
    per: dict[float, dict[str, Any]] = {}
    for d in sorted({float(x) for x in punch}):
        v = [
            float(z)
            for x, f, z, good in zip(punch, load, depth, ok, strict=True)
            if good
            and math.isclose(x, d, rel_tol=1e-9)
            and math.isclose(f, at, rel_tol=1e-9)
            and z is not None
            and math.isfinite(z)
        ]
        if v:
            per[d] = {"median": float(np.median(v)), "min": min(v), "max": max(v), "n": len(v)}
    if not per:
        return {"per_punch": per, "deepest": None}
    d = max(per, key=lambda k: per[k]["median"])
    return {"per_punch": per, "deepest": {"punch_m": d, **per[d]}}
