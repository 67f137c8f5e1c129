# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Depth as the instrument reads it, and where the pressure cap stops being the material.

**Threshold depth.** The solver measures the approach δ from first touch at the highest pixel
under the punch. An indenter has no such zero: it detects the surface when the force first
reaches a small threshold F_s (its surface-detection or contact criterion) and measures depth
from there. The threshold depth is h = δ(F) − δ(F_s), with δ(F_s) the approach of a load solve
at F_s on the same window and pixel, loaded monotonically (F_s is below every peak load, so the
state at each peak is unchanged). Since δ(F_s) ≥ 0, h ≤ δ. F_s is
``IndentProtocol.detection_load`` (:data:`DETECTION_LOAD` by default, stated in every output).
On a surface whose highest point is a lone spike that the first load flattens, δ counts the
spike's height and h does not.

**Bulk yield.** The pressure cap H limits each pixel's pressure; it cannot represent plastic
flow of the bulk under the whole punch. A rigid flat circular punch on a rigid–perfectly-plastic
half-space collapses at a mean pressure of 5.69·k (Tresca, k = σ_y/2; R.T. Shield, Proc. R. Soc.
A 233, 267 (1955)) = 2.84·σ_y, close to Prandtl's 2.97·σ_y in plane strain; with Tabor's
H ≈ 3·σ_y (D. Tabor, *The Hardness of Metals*, Oxford, 1951) that is
p_bulk = (2.84/3)·H = :data:`BULK_YIELD_FRACTION`·H. A cell whose mean punch pressure F/A
reaches p_bulk is flagged ``bulk_yield`` and left out of the fits: there the real alloy
sinks in bulk, which the cap model does not (a load above H·A it cannot carry at all, and
:func:`warptrunc.indent` refuses it).

Loads no Warp.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = [
    "BULK_YIELD_FRACTION",
    "BULK_YIELD_SOURCE",
    "DETECTION_LOAD",
    "DETECTION_SOURCE",
    "bulk_yield",
    "threshold_depth",
]

DETECTION_LOAD = 10e-6
"""Surface-detection force F_s of the threshold depth (N): 10 µN, an assumption of the order of
the contact-detection forces of nanoindenters (µN to tens of µN); the paper states none."""

DETECTION_SOURCE = (
    "depth from surface detection: h = delta(F) - delta(F_s), the approach at the "
    "detection load F_s subtracted (an assumption of the order of nanoindenters' contact "
    "criteria; the paper states none)"
)

BULK_YIELD_FRACTION = 2.84 / 3.0
"""p_bulk/H of the bulk-yield flag (dimensionless): Shield's collapse pressure of a flat circular
punch, 2.84·σ_y, with Tabor's H ≈ 3·σ_y."""

BULK_YIELD_SOURCE = (
    "mean punch pressure F/A >= 2.84 sigma_y (flat circular punch on a rigid-perfectly-plastic "
    "half-space, Tresca: R.T. Shield, Proc. R. Soc. A 233, 267 (1955)) with H = 3 sigma_y "
    "(Tabor 1951): F/A >= 0.947 H"
)


def threshold_depth(displacement: Any, detection_displacement: Any) -> np.ndarray:
    """h = δ(F) − δ(F_s): the depth from where the instrument detects the surface (m).

    Parameters
    ----------
    displacement : array_like
        Approach δ at the peak load, from first touch at the highest pixel (m).
    detection_displacement : array_like
        Approach δ(F_s) at the detection load on the same window and pixel (m).

    Returns
    -------
    ndarray of float64
        h (m); NaN where either is NaN.
    """
    return np.asarray(displacement, np.float64) - np.asarray(detection_displacement, np.float64)


def bulk_yield(load: Any, area: Any, hardness: float) -> np.ndarray:
    """Whether the mean punch pressure F/A reaches the bulk-yield pressure of the cap model.

    Parameters
    ----------
    load : array_like
        Peak load F (N).
    area : array_like
        Punch area A (m²).
    hardness : float
        H (Pa); inf: elastic, never flagged.

    Returns
    -------
    ndarray of bool
        F/A ≥ :data:`BULK_YIELD_FRACTION`·H.
    """
    f = np.asarray(load, np.float64)
    a = np.asarray(area, np.float64)
    if not math.isfinite(hardness):
        return np.zeros(np.broadcast(f, a).shape, bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        return f / a >= BULK_YIELD_FRACTION * float(hardness)
