# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The 1-D root finder of the calibration's D loop (isotonic interpolation inside the bracket,
secant extrapolation outside it) and its error type, :class:`CalibrationError`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

__all__ = ["CalibrationError", "find_root", "isotonic", "unreachable"]


class CalibrationError(ValueError):
    """The target cannot be reached, or the loop ran out of evaluations.

    ``d_in`` and ``d_out`` hold the evaluations of the failed D loop (dimensionless).

    Parameters
    ----------
    message : str
        The error message.
    d_in : sequence of float, optional
        Input fractal dimensions D_in tried so far (dimensionless); stored as a list of float.
    d_out : sequence of float, optional
        Fractal dimensions D_out measured for them, same length (dimensionless).
    """


    def __init__(self, message: str, d_in: Sequence[float] = (), d_out: Sequence[float] = ()):
        super().__init__(message)
        self.d_in = [float(v) for v in d_in]
        self.d_out = [float(v) for v in d_out]


def isotonic(y: np.ndarray) -> np.ndarray:
    """Non-decreasing least-squares fit of ``y`` (pool adjacent violators, equal weights)."""
    vals: list[float] = []
    counts: list[int] = []
    for v in y:
        vals.append(float(v))
        counts.append(1)
        while len(vals) > 1 and vals[-2] > vals[-1]:
            c = counts[-2] + counts[-1]
            v2 = (vals[-2] * counts[-2] + vals[-1] * counts[-1]) / c
            vals[-2:] = [v2]
            counts[-2:] = [c]
    return np.repeat(vals, counts)


def find_root(
    f: Callable[[float], float],
    target: float,
    atol: float,
    bounds: tuple[float, float],
    x0: float,
    max_iter: int,
    *,
    what: str = "f",
    known: tuple[float, float] | None = None,
) -> float:
    """Return an x in ``bounds`` with |f(x) − target| ≤ atol, f noisy but non-decreasing
    on average; ``known`` = (x0, f(x0)) saves the first evaluation. Raises CalibrationError
    when unreachable or out of evaluations."""
    lo, hi = bounds
    xs: list[float] = []
    ys: list[float] = []
    x = x0
    streak = 0  # consecutive extrapolations in one direction: the minimum step doubles
    for it in range(max_iter):
        y = known[1] if (it == 0 and known is not None) else f(x)
        xs.append(x)
        ys.append(y)
        if abs(y - target) <= atol:
            return x
        order = np.argsort(xs)
        sx = np.asarray(xs)[order]
        sy = isotonic(np.asarray(ys)[order])
        # secant slope of the isotonic fit; 1 (D_out ≈ D_in) until two distinct points exist
        slope = 1.0
        if sx[-1] - sx[0] > 1e-6 and sy[-1] > sy[0]:
            slope = float(np.clip((sy[-1] - sy[0]) / (sx[-1] - sx[0]), 0.05, 20.0))
        if target < sy[0]:
            if sx[0] <= lo + 1e-9:
                unreachable(what, target, atol, xs, ys, bounds)
            streak = min(streak, 0) - 1
            step = max(1.2 * (sy[0] - target) / slope, 0.02 * 2 ** (-streak - 1))
            nxt = max(lo, sx[0] - step)
        elif target > sy[-1]:
            if sx[-1] >= hi - 1e-9:
                unreachable(what, target, atol, xs, ys, bounds)
            streak = max(streak, 0) + 1
            step = max(1.2 * (target - sy[-1]) / slope, 0.02 * 2 ** (streak - 1))
            nxt = min(hi, sx[-1] + step)
        else:
            streak = 0
            i = int(np.searchsorted(sy, target, side="left"))
            i = min(max(i, 1), sx.size - 1)
            x_a, x_b, y_a, y_b = sx[i - 1], sx[i], sy[i - 1], sy[i]
            nxt = (
                0.5 * (x_a + x_b)
                if y_b <= y_a
                else x_a + (target - y_a) * (x_b - x_a) / (y_b - y_a)
            )
            # keep clear of points already evaluated (noise would only repeat them)
            gap = 0.1 * (x_b - x_a)
            nxt = min(max(nxt, x_a + gap), x_b - gap)
        if min(abs(nxt - v) for v in xs) < 1e-4:
            break
        x = float(nxt)
    best = int(np.argmin(np.abs(np.asarray(ys) - target)))
    raise CalibrationError(
        f"{what} did not reach {target:.4f} ± {atol:.4f} in {len(xs)} evaluations; closest: "
        f"D_in = {xs[best]:.4f} → {ys[best]:.4f}. Evaluations (D_in → D_out): "
        + ", ".join(f"{a:.4f}→{b:.4f}" for a, b in zip(xs, ys, strict=True))
        + ". Raise max_iter, add seeds, or loosen rtol.",
        xs,
        ys,
    )


def unreachable(what, target, atol, xs, ys, bounds) -> None:
    i = int(np.argmin(xs)) if target < min(ys) else int(np.argmax(xs))
    side = "lower" if target < min(ys) else "upper"
    raise CalibrationError(
        f"{what} = {target:.4f} cannot be reached with D_in in [{bounds[0]:g}, {bounds[1]:g}]: "
        f"the {side} bound D_in = {xs[i]:.4f} gives {ys[i]:.4f} (tolerance ± {atol:.4f}); "
        f"D_out over the {len(xs)} evaluations spans [{min(ys):.4f}, {max(ys):.4f}]. Use another "
        "method, or check the target (for 'tri'/'box' D depends on R_t relative to the pixel "
        "size).",
        xs,
        ys,
    )
