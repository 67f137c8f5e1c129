# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Cells that converge in the pixel size: each (punch, placement, peak load) cell is
solved again at half the pixel until its unloading stiffness and contact area stop changing.

A WM surface is analytic (Eq. 4): the window under a punch can be generated again at a finer
pixel with the same content — the same terms (phases, W_r, cut-off W_c) and the map's height
scale frozen, never scaled again to R_t (:func:`warptrunc.wm.wm_window`). A height map read
from a file has no such source: nothing is refined, and its cells are judged by the
contact-pixel rule alone. A tilted or rough punch face is evaluated again at the finer pixel
centres from its own definition (a plane; a band-limited Fourier sum of fixed seed and
cut-offs; a bilinear read face): the same face at every pixel (:mod:`warptrunc.indent.face`).

The rule, per cell and contact model: the pixel p is halved while the cell is not resolved; a
cell is **resolved** at p/2 when Barber's unloading stiffness K and the contact area A both
change by less than ``resolution_tol`` (relative) from p to p/2, both solves converged, and
the contact holds at least ``min_contact_pixels`` pixels at p/2. Refinement stops at
``refine_max`` (the pixel p/refine_max) or when the device's memory cannot hold the finer
window's solver (then the cells keep their last pixel). No cell is given up early: the
contact area of a coarse grid says little about the finer one (an elastic contact on one
coarse pixel spreads over many finer ones). A cell is **saturated** when every pixel
of the punch face touches (complete contact) or when its K is already within
``resolution_tol`` of the complete-contact plateau 2E*·a of the face (Sneddon's flat punch,
``plateau``): such a cell measures the punch, not the roughness, whatever the last pixels do. Only the cells that need it are solved again:
the loads of one punch that are not resolved, loaded straight to each peak (the state at a
peak is that of monotonic loading to it, :mod:`warptrunc.indent.protocol`), the first solve
starting where the coarser grid put the rigid plane.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .punch import PunchWindow, punch_window, punch_window_at

__all__ = ["NOTES", "CellRefinement", "WindowSource", "refine_cells"]

NOTES = {
    "resolved": "K and the contact area changed by less than the tolerance at the last halving, "
    "with enough contact pixels",
    "refine-max": "not resolved at the finest pixel allowed (refine_max)",
    "memory": "the finer window's solver does not fit the device's free memory",
    "read-map": "a read height map: nothing to generate again; judged by its contact pixels",
    "aliased": "a WM map whose cut-off W_c is below 2 pixels (aliased): a finer window would "
    "hold other content; judged by its contact pixels",
    "not-refined": "refine_max = 1: judged by its contact pixels",
    "whole-map": "a flat larger than the map: not refined; judged by its contact pixels",
}
"""``resolution_note`` of a cell → what it means."""


class WindowSource:
    """The punch windows of one map: at its own pixel and, for a WM map, at finer ones.

    Parameters
    ----------
    heights : (ny, nx) array_like
        The map's heights (m).
    pixel_size : (float, float)
        Pixel sides dx, dy (m).
    params : dict, optional
        The map's ``Surface.params``; a WM surface's (:func:`warptrunc.wm_surface`) make the
        map analytic, when its heights are those of its parameters.
    device : str or warp.context.Device, optional
        Warp device of the generation.
    """

    def __init__(
        self,
        heights: Any,
        pixel_size: tuple[float, float],
        params: dict[str, Any] | None = None,
        *,
        device: Any = None,
    ) -> None:
        self.heights = np.asarray(heights, dtype=np.float64)
        self.pixel_size = (float(pixel_size[0]), float(pixel_size[1]))
        self.params = params
        self.device = device
        self.why_not = self._why_not()

    @property
    def refinable(self) -> bool:
        """Whether windows can be generated at a finer pixel (a WM map, not aliased)."""
        return self.why_not is None

    def _why_not(self) -> str | None:
        """None for an analytic map, else the note of its cells ("read-map", "aliased")."""
        from ..wm import wm_window

        p = self.params or {}
        ny, nx = self.heights.shape
        dx, dy = self.pixel_size
        if p.get("generator") != "weierstrass-mandelbrot":
            return "read-map"
        try:
            same = (
                (p["nx"], p["ny"]) == (nx, ny)
                and math.isclose(p["Lx"] / p["nx"], dx, rel_tol=1e-9)
                and math.isclose(p["Ly"] / p["ny"], dy, rel_tol=1e-9)
            )
        except (KeyError, TypeError, ZeroDivisionError):
            return "read-map"
        if not same:
            return "read-map"
        if p["Wc"] < 2.0 * max(dx, dy) * (1 - 1e-9):
            return "aliased"
        # the heights must be those of the parameters (not a levelled or edited copy): a patch
        # at the map centre generated again
        sy, sx = min(16, ny), min(16, nx)
        o = ((ny - sy) // 2, (nx - sx) // 2)
        try:
            patch = wm_window(p, o, (sy, sx), 1, device=self.device)
        except (KeyError, ValueError, TypeError):
            return "read-map"
        ref = self.heights[o[0] : o[0] + sy, o[1] : o[1] + sx]
        if not np.allclose(
            patch, ref, rtol=0, atol=1e-5 * max(float(np.ptp(self.heights)), 1e-300)
        ):
            return "read-map"
        return None

    def window(
        self, diameter: float | None, centre: tuple[float, float], factor: int = 1, face: Any = None
    ) -> PunchWindow:
        """The punch window at pixel dx/factor, dy/factor.

        Parameters
        ----------
        diameter : float or None
            Punch diameter d (m); None: the whole map (factor 1 only).
        centre : (float, float)
            Punch centre (x, y) (m).
        factor : int
            Refinement of the pixel (1: the map's own pixels).
        face : PunchFace, optional
            The punch face (tilt, roughness), evaluated at the window's pixel centres: the
            same face at every factor (:mod:`warptrunc.indent.face`).

        Returns
        -------
        PunchWindow

        Raises
        ------
        ValueError
            ``factor`` > 1 on a map that cannot be refined, or for a flat larger than the map.
        """
        if factor == 1:
            return punch_window(self.heights, self.pixel_size, diameter, centre, face=face)
        if not self.refinable or diameter is None:
            raise ValueError(
                f"this map cannot be refined ({self.why_not or 'a flat'}): factor 1 only"
            )
        from ..wm import wm_window

        ny, nx = self.heights.shape
        dx, dy = self.pixel_size

        def generate(origin: tuple[int, int], shape: tuple[int, int]) -> np.ndarray:
            return wm_window(self.params, origin, shape, factor, device=self.device)

        return punch_window_at(
            generate,
            (ny * factor, nx * factor),
            (dx / factor, dy / factor),
            diameter,
            centre,
            face=face,
        )


@dataclass(frozen=True, eq=False)
class CellRefinement:
    """The cells of one punch placement and one contact model after refinement."""

    cycles: dict[str, np.ndarray]
    """:func:`~warptrunc.indent.protocol.run_cycles` columns, each cell at its final pixel."""
    factor: np.ndarray
    """(m,) int64: the final pixel is the map's divided by this factor (1, 2, 4, …)."""
    pixel_size: np.ndarray
    """(m,) float64: the final pixel side dx/factor (m)."""
    n_disk_pixels: np.ndarray
    """(m,) int64: pixels of the punch face at the final pixel."""
    change: np.ndarray
    """(m,) float64: abs(K(p)/K(2p) − 1) at the last halving; NaN if never halved."""
    area_change: np.ndarray
    """(m,) float64: abs(A(p)/A(2p) − 1) at the last halving; NaN if never halved."""
    resolved: np.ndarray
    """(m,) bool: the rule of the module is met at the final pixel; on a map that is not
    refined (a read map, an aliased WM map, ``refine_max = 1``) the contact-pixel rule alone:
    converged with at least ``min_contact_pixels`` contact pixels."""
    saturated: np.ndarray
    """(m,) bool: every pixel of the punch face touches at the final pixel."""
    note: np.ndarray
    """(m,) str: why the refinement stopped (:data:`NOTES`)."""
    windows: dict[int, PunchWindow] = field(default_factory=dict)
    """factor → the window solved at that pixel."""

    @property
    def in_fit(self) -> np.ndarray:
        """(m,) bool: resolved, not saturated and converged: the cells a fit may use."""
        return self.resolved & ~self.saturated & np.asarray(self.cycles["converged"], bool)


def refine_cells(
    source: WindowSource,
    window: PunchWindow,
    first: dict[str, np.ndarray],
    solve: Callable[[PunchWindow, np.ndarray, int, np.ndarray], dict[str, np.ndarray]],
    *,
    protocol: Any,
    windows: dict[int, PunchWindow] | None = None,
    plateau: float | None = None,
) -> CellRefinement:
    """Halve the pixel of the cells of one punch placement until they are resolved.

    Parameters
    ----------
    source : WindowSource
        The map the window comes from.
    window : PunchWindow
        The punch window at the map's pixel.
    first : dict of str to (m,) ndarray
        The cycles solved on ``window`` (:func:`~warptrunc.indent.protocol.run_cycles`), one
        per peak load.
    solve : callable
        ``solve(window, idx, factor, approach)`` → the cycles of the peak loads ``idx``
        (increasing indices) on a finer ``window`` (pixel / ``factor``), as ``run_cycles``
        returns them; ``approach`` ((len(idx),) m) is the coarser grid's rigid plane at each
        of them, as approaches on the finer window (the start, ``run_cycles(approach=)``).
    protocol : IndentProtocol
        The rule: ``resolution_tol`` (largest relative change of K and of A at the last
        halving, dimensionless), ``min_contact_pixels`` (fewest contact pixels of a resolved
        cell) and ``refine_max`` (largest refinement factor, a power of 2; 1: nothing is
        refined).
    windows : dict of int to PunchWindow, optional
        Windows already generated for this punch placement (factor → window), shared between
        contact models; filled here.
    plateau : float, optional
        Complete-contact stiffness 2E*·a of the punch face (N/m): cells with
        K ≥ (1 − ``resolution_tol``)·plateau are saturated too. None: complete contact only.

    Returns
    -------
    CellRefinement
    """
    resolution_tol = protocol.resolution_tol
    min_contact_pixels = protocol.min_contact_pixels
    refine_max = protocol.refine_max
    m = int(np.asarray(first["unloading_stiffness"]).size)
    cur = {k: np.array(v, copy=True) for k, v in first.items()}
    wins = {} if windows is None else windows
    wins.setdefault(1, window)
    factor = np.ones(m, np.int64)
    n_disk = np.full(m, window.n_pixels, np.int64)
    change = np.full(m, math.nan)
    area_change = np.full(m, math.nan)
    resolved = np.zeros(m, bool)
    note = np.full(m, "refine-max", dtype=object)
    refined = source.refinable and refine_max > 1 and window.diameter is not None
    if not source.refinable:
        note[:] = source.why_not
    elif refine_max <= 1:
        note[:] = "not-refined"
    elif window.diameter is None:
        note[:] = "whole-map"
    active = np.full(m, refined)
    f = 1
    while active.any() and f < refine_max:
        idx = np.flatnonzero(active)
        f2 = 2 * f
        try:
            w2 = wins.get(f2)
            if w2 is None:
                w2 = wins[f2] = source.window(window.diameter, window.centre, f2, window.face)
            # the coarser solution as the start: the rigid plane where it was, as approaches
            plane = wins[f].top - np.asarray(cur["displacement"], np.float64)[idx]
            new = solve(w2, idx, f2, w2.top - plane)
        except MemoryError:
            note[idx] = "memory"
            active[:] = False
            break
        k0 = np.asarray(cur["unloading_stiffness"], np.float64)[idx]
        a0 = np.asarray(cur["contact_area"], np.float64)[idx]
        ok0 = np.asarray(cur["converged"], bool)[idx]
        for k, v in new.items():
            cur[k][idx] = v
        factor[idx] = f2
        n_disk[idx] = w2.n_pixels
        with np.errstate(divide="ignore", invalid="ignore"):
            dk = np.abs(np.asarray(new["unloading_stiffness"], np.float64) / k0 - 1.0)
            da = np.abs(np.asarray(new["contact_area"], np.float64) / a0 - 1.0)
        change[idx], area_change[idx] = dk, da
        good = (
            ok0
            & np.asarray(new["converged"], bool)
            & (dk < resolution_tol)
            & (da < resolution_tol)
            & (np.asarray(new["n_contact"]) >= min_contact_pixels)
        )
        resolved[idx[good]] = True
        note[idx[good]] = "resolved"
        active[idx[good]] = False
        f = f2
    n_contact = np.asarray(cur["n_contact"], np.int64)
    if not refined:  # the contact-pixel rule alone
        resolved = np.asarray(cur["converged"], bool) & (n_contact >= min_contact_pixels)
    dx, _dy = window.pixel_size
    saturated = n_contact >= n_disk
    if plateau is not None and math.isfinite(plateau) and plateau > 0:
        k = np.asarray(cur["unloading_stiffness"], np.float64)
        saturated |= np.isfinite(k) & (k >= (1.0 - resolution_tol) * plateau)
    return CellRefinement(
        cur,
        factor,
        dx / factor.astype(np.float64),
        n_disk,
        change,
        area_change,
        resolved,
        saturated,
        note.astype(str),
        wins,
    )
