# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Input checks with messages that name the parameter, its value and the allowed range."""

from __future__ import annotations

import math

import numpy as np

HEIGHT_LIMIT_M = 1e37
"""Largest height magnitude (m) a map may hold: a round bound below a quarter of the float32
maximum (3.4·10³⁸/4 = 8.5·10³⁷), up to which float32 heights (on the device) and their
differences stay finite; the ranges of R_t say ``(0, 1e+37] m``."""

DEFAULT_MIN_PIXELS = 10
"""Default fit range: increments with at least this many contact pixels (see README, "Fit
range"); the first increments, where a handful of pixels touch, are left out. Here, with no
Warp import, for the command-line parsers; :mod:`warptrunc.stiffness` exports it."""

MAX_INCREMENTS = 1_000_000
"""Most depth increments of one truncation curve (a bound on the work of one run).

A step below 10⁻⁶·ω_max is finer than float32 heights resolve when ω_max is a tenth of R_t or
more (float32 holds about 7 significant digits), and every increment is a row of curve.csv
(writing a row takes about 15 µs: 10⁶ rows are 15 s and 150 MB)."""

MAX_SEEDS = 1_000_000
"""Most seeds of one sweep grid, and most cases (D × δ × seeds) of one store."""


def check_range(
    name: str,
    value: float,
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = True,
    hi_open: bool = True,
    unit: str = "",
) -> float:
    """Return ``float(value)`` if it is finite and inside the interval, else raise ValueError."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    lo_s = "-inf" if lo is None else f"{lo:g}"
    hi_s = "inf" if hi is None else f"{hi:g}"
    interval = f"{'(' if lo_open else '['}{lo_s}, {hi_s}{')' if hi_open else ']'}"
    bad = not math.isfinite(v)
    if lo is not None:
        bad |= v <= lo if lo_open else v < lo
    if hi is not None:
        bad |= v >= hi if hi_open else v > hi
    if bad:
        u = f" {unit}" if unit else ""
        raise ValueError(f"{name} must be in {interval}{u}, got {value!r}")
    return v


def check_int(name: str, value: int, lo: int, hi: int | None = None) -> int:
    """Return ``int(value)`` if it is an integer in [lo, hi], else raise ValueError."""
    if isinstance(value, bool) or not float(value).is_integer():
        raise ValueError(f"{name} must be an integer, got {value!r}")
    v = int(value)
    if v < lo or (hi is not None and v > hi):
        hi_s = "inf)" if hi is None else f"{hi}]"
        raise ValueError(f"{name} must be an integer in [{lo}, {hi_s}, got {value!r}")
    return v


def check_height_map(z: np.ndarray, name: str = "heights") -> np.ndarray:
    """Return ``z`` as a C-contiguous float32 2-D array, refusing non-2-D or non-finite input."""
    z = np.asarray(z)
    if z.ndim != 2:
        raise ValueError(f"{name} must be 2-D (ny, nx), got shape {z.shape}")
    if z.shape[0] < 1 or z.shape[1] < 1:
        raise ValueError(f"{name} must not be empty, got shape {z.shape}")
    if not np.issubdtype(z.dtype, np.number) or np.iscomplexobj(z):
        raise ValueError(f"{name} must hold real numbers, got dtype {z.dtype}")
    bad = ~np.isfinite(z)
    if bad.any():
        iy, ix = np.argwhere(bad)[0]
        raise ValueError(
            f"{name} contains {int(bad.sum())} NaN/inf values (first at iy={iy}, ix={ix}); "
            "fill or mask them first"
        )
    big = HEIGHT_LIMIT_M  # heights and their differences stay finite
    peak = float(np.max(np.abs(z)))
    if peak > big:
        raise ValueError(
            f"{name} reach {peak:.3g} in magnitude, beyond what float32 heights hold with finite "
            f"differences (±{big:.3g}); check the height unit"
        )
    return np.ascontiguousarray(z, dtype=np.float32)


def pair(name: str, value, cast=float) -> tuple:
    """Accept a scalar or a 2-sequence and return an (x, y) pair."""
    if np.ndim(value) == 0:
        return cast(value), cast(value)
    v = tuple(value)
    if len(v) != 2:
        raise ValueError(f"{name} must be a scalar or an (x, y) pair, got {value!r}")
    return cast(v[0]), cast(v[1])
