# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Cells that converge in the pixel size: each (punch, placement, peak load) cell is solved
again at half the pixel until its unloading stiffness K has converged over two halvings.

A WM surface is analytic (Eq. 4): the window under a punch can be generated again at a finer
pixel with the same content — the same terms (phases, W_r, cut-off W_c) and the map's height
scale frozen, never scaled again to R_t (:func:`warptrunc.wm.wm_window`). A height map read
from a file has no such source: nothing is refined, and its cells are judged by the
contact-pixel rule alone (and flagged so: ``note`` ``read-map``). A tilted or rough punch face
is evaluated again at the finer pixel centres from its own definition (a plane; a band-limited
Fourier sum of fixed seed and cut-offs; a bilinear read face): the same face at every pixel
(:mod:`warptrunc.indent.face`).

**The one rule**, per cell and contact model, on K: the pixel p is halved while the cell is not
resolved; after at least two halvings (K at p, p/2, p/4, …, the last three taken) K is
extrapolated to a zero pixel by Richardson's rule with the observed order (:func:`richardson`)
and the cell is **resolved** when that extrapolation's error estimate is within
``resolution_tol`` of the extrapolated K, the three solves converged and the contact holds at
least ``min_contact_pixels`` pixels at the finest. The contact area A is extrapolated the same
way and reported with its discretisation error (``area_extrapolated``, ``area_error``); it is not
the rule (the perimeter of a contact of few pixels per shortest wavelength converges slowly
while K already has), but ``area_resolved`` says whether A meets the same tolerance, for the
fits' rule systematic (:mod:`warptrunc.indent.fits`). Refinement stops at ``refine_max`` (the
pixel p/refine_max; below 4 no cell can be resolved by the rule) or when the finer window
cannot be solved (then the cells keep their last pixel). No cell is given up early: the contact
area of a coarse grid says little about the finer one.

**Sub-windows.** When the whole finer window of a punch exceeds ``max_window_pixels`` (or does
not fit the device's memory), the cells are solved on a sub-window of it: the rectangle that
holds, at the coarser pixel, every pixel of the disk within a gap margin of contact (the
contact and its interaction range: twice the largest height step between neighbouring pixels
of the disk, the most a finer sample between them can rise), grown by
:data:`SUB_WINDOW_GUARD` coarse pixels. The disk's pixels outside it carry no pressure; on the
free half-space the solution is that of the whole window as long as the contact stays inside,
which is checked after each solve (the finer contact's bounding box at least
:data:`SUB_WINDOW_GUARD` fine pixels from every cut edge; else the sub-window is grown and the
cell solved again). Saturation counts the whole disk's pixels; truncation reads the finest whole
window (``truncation_pixel_size``).

A cell is **saturated** when every pixel of the punch face touches (complete contact) or when
its K is already within ``resolution_tol`` of the complete-contact plateau 2E*·a of the face
(Sneddon's flat punch, ``plateau``): such a cell measures the punch, not the roughness. Only the
cells that need it are solved again: the loads of one punch that are not resolved, loaded
straight to each peak (the state at a peak is that of monotonic loading to it,
:mod:`warptrunc.indent.cycles`), the first solve starting where the coarser grid put the rigid
plane.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .punch import PunchWindow, disk_bounds, punch_window, punch_window_at

SUB_WINDOW_GUARD = 2
"""Pixels between a sub-window's cut edge and the contact's bounding box: coarse pixels added
around the near-contact set, and the finer contact's least distance to a cut edge (count)."""

__all__ = [
    "NOTES",
    "SUB_WINDOW_GUARD",
    "CellRefinement",
    "WindowSource",
    "refine_cells",
    "richardson",
]

NOTES = {
    "resolved": "K's Richardson error over the last two halvings within the tolerance, with "
    "enough contact pixels",
    "refine-max": "not resolved at the finest pixel allowed (refine_max)",
    "memory": "the finer window (or the sub-window that holds the contact) does not fit "
    "max_window_pixels or the device's free memory",
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
        self,
        diameter: float | None,
        centre: tuple[float, float],
        factor: int = 1,
        face: Any = None,
        region: tuple[int, int, int, int] | None = None,
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
        region : (int, int, int, int), optional
            A sub-window: (iy0, ix0, iy1, ix1) of the map at this factor's pixel, inclusive
            (:func:`~warptrunc.indent.punch.punch_window_at`); factor > 1 only.

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
            region=region,
        )

    def disk_bounds(
        self, diameter: float, centre: tuple[float, float], factor: int
    ) -> tuple[int, int, int, int]:
        """The rows and columns of the disk on the map at pixel dx/factor.

        Parameters
        ----------
        diameter : float
            Punch diameter d (m).
        centre : (float, float)
            Punch centre (x, y) (m).
        factor : int
            Refinement of the pixel.

        Returns
        -------
        (int, int, int, int)
            (iy0, ix0, iy1, ix1), inclusive (:func:`~warptrunc.indent.punch.disk_bounds`).
        """
        ny, nx = self.heights.shape
        dx, dy = self.pixel_size
        return disk_bounds((ny * factor, nx * factor), (dx / factor, dy / factor), diameter, centre)


def richardson(coarse: Any, mid: Any, fine: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Richardson extrapolation to a zero pixel of values at pixels p, p/2 and p/4.

    Parameters
    ----------
    coarse, mid, fine : array_like
        The value at the three pixels (any unit; broadcast together).

    Returns
    -------
    extrapolated : ndarray
        With d₁ = mid − coarse, d₂ = fine − mid and r = d₂/d₁: where 0 < r < 1 (monotone
        convergence, observed order q = −log₂ r), fine + d₂·r′/(1 − r′) with r′ = max(r, ¼)
        (the order taken at most 2, so that a change that happens to be small is not trusted
        as a high order); elsewhere (oscillating, or not converging) ``fine``.
    error : ndarray
        abs(extrapolated − fine) where 0 < r < 1, else max(abs(d₁), abs(d₂)): the estimate of
        the discretisation error of ``fine`` (same unit). For first-order convergence (r = ½)
        it is abs(d₂).
    order : ndarray
        The observed order q (dimensionless); NaN where not monotone.
    """
    k0, k1, k2 = (np.asarray(v, np.float64) for v in (coarse, mid, fine))
    d1, d2 = k1 - k0, k2 - k1
    with np.errstate(divide="ignore", invalid="ignore"):
        r = d2 / d1
        mono = (d1 != 0) & np.isfinite(r) & (r > 0) & (r < 1)
        re = np.maximum(np.where(mono, r, 0.5), 0.25)
        step = d2 * re / (1.0 - re)
        order = np.where(mono, -np.log2(np.where(mono, r, 1.0)), np.nan)
    ext = np.where(mono, k2 + step, k2)
    err = np.where(mono, np.abs(step), np.maximum(np.abs(d1), np.abs(d2)))
    return ext, err, order


@dataclass(frozen=True, eq=False)
class CellRefinement:
    """The cells of one punch placement and one contact model after refinement."""

    cycles: dict[str, np.ndarray]
    """:func:`~warptrunc.indent.cycles.run_cycles` columns, each cell at its final pixel."""
    factor: np.ndarray
    """(m,) int64: the final pixel is the map's divided by this factor (1, 2, 4, …)."""
    pixel_size: np.ndarray
    """(m,) float64: the final pixel side dx/factor (m)."""
    n_disk_pixels: np.ndarray
    """(m,) int64: pixels of the whole punch face at the final pixel."""
    change: np.ndarray
    """(m,) float64: abs(K(p)/K(2p) − 1) at the last halving; NaN if never halved."""
    area_change: np.ndarray
    """(m,) float64: abs(A(p)/A(2p) − 1) at the last halving; NaN if never halved."""
    stiffness_extrapolated: np.ndarray
    """(m,) float64: Barber's K extrapolated to a zero pixel over the last two halvings
    (:func:`richardson`), K at the final pixel after one (N/m); NaN if never halved."""
    stiffness_error: np.ndarray
    """(m,) float64: the error estimate of K at the final pixel (N/m): :func:`richardson`'s
    over two halvings, abs(K(p) − K(2p)) after one; NaN if never halved."""
    area_extrapolated: np.ndarray
    """(m,) float64: the contact area extrapolated likewise (m²)."""
    area_error: np.ndarray
    """(m,) float64: the discretisation error estimate of the contact area at the final pixel
    (m²)."""
    resolved: np.ndarray
    """(m,) bool: the one rule (on K, over at least two halvings) is met at the final pixel; on
    a map that is not refined (a read map, an aliased WM map, ``refine_max = 1``) the
    contact-pixel rule alone: converged with at least ``min_contact_pixels`` contact pixels."""
    area_resolved: np.ndarray
    """(m,) bool: the contact area meets the same rule too (its error estimate within the
    tolerance); on a map that is not refined, :attr:`resolved`."""
    saturated: np.ndarray
    """(m,) bool: every pixel of the punch face touches at the final pixel, or K within the
    tolerance of the complete-contact plateau."""
    sub_window: np.ndarray
    """(m,) bool: the final solve ran on a sub-window of the punch's window."""
    note: np.ndarray
    """(m,) str: why the refinement stopped (:data:`NOTES`)."""
    truncation_factor: np.ndarray
    """(m,) int64: the factor of the whole window truncation reads for the cell (the finest
    whole window at or above the final pixel)."""
    windows: dict[int, PunchWindow] = field(default_factory=dict)
    """factor → the whole window solved at that pixel."""

    @property
    def in_fit(self) -> np.ndarray:
        """(m,) bool: resolved, not saturated and converged: the cells a fit may use."""
        return self.resolved & ~self.saturated & np.asarray(self.cycles["converged"], bool)


def _padded_pixels(bounds: tuple[int, int, int, int]) -> int:
    from ..contact.halfspace import fft_size

    iy0, ix0, iy1, ix1 = bounds
    return fft_size(iy1 - iy0 + 1) * fft_size(ix1 - ix0 + 1)


class _Grow(Exception):
    """A sub-window that cannot hold the contact within ``max_window_pixels``."""


def _store(cur: dict[str, np.ndarray], ii: np.ndarray, new: dict[str, np.ndarray], m: int) -> None:
    for k, v in new.items():
        v = np.asarray(v)
        if k not in cur:
            fill = -1 if v.dtype.kind in "iu" else (False if v.dtype.kind == "b" else np.nan)
            cur[k] = np.full((m, *v.shape[1:]), fill, dtype=v.dtype)
        cur[k][ii] = v


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
        The cycles solved on ``window`` (:func:`~warptrunc.indent.cycles.run_cycles`), one
        per peak load; with ``near_box`` and ``contact_box`` ((m, 4) int, window pixels) when
        the cells may need sub-windows.
    solve : callable
        ``solve(window, idx, factor, approach)`` → the cycles of the peak loads ``idx``
        (increasing indices) on a finer ``window`` (pixel / ``factor``; a whole window or a
        sub-window), as ``run_cycles`` returns them (with the boxes when ``first`` has them);
        ``approach`` ((len(idx),) m) is the coarser grid's rigid plane at each of them, as
        approaches on the finer window (the start, ``run_cycles(approach=)``).
    protocol : IndentProtocol
        The rule: ``resolution_tol`` (largest relative error estimate of K, dimensionless),
        ``min_contact_pixels`` (fewest contact pixels of a resolved cell), ``refine_max``
        (largest refinement factor, a power of 2; 1: nothing is refined) and
        ``max_window_pixels`` (largest window solved whole; beyond it, sub-windows).
    windows : dict of int to PunchWindow, optional
        Whole windows already generated for this punch placement (factor → window), shared
        between contact models; filled here.
    plateau : float, optional
        Complete-contact stiffness 2E*·a of the punch face (N/m): cells with
        K ≥ (1 − ``resolution_tol``)·plateau are saturated too. None: complete contact only.

    Returns
    -------
    CellRefinement
    """
    tol = protocol.resolution_tol
    fewest = protocol.min_contact_pixels
    refine_max = protocol.refine_max
    max_px = protocol.max_window_pixels
    m = int(np.asarray(first["unloading_stiffness"]).size)
    cur = {k: np.array(v, copy=True) for k, v in first.items()}
    wins = {} if windows is None else windows
    wins.setdefault(1, window)
    n_lev = round(math.log2(max(refine_max, 1))) + 1
    kk = np.full((m, n_lev), math.nan)
    aa = np.full((m, n_lev), math.nan)
    okk = np.zeros((m, n_lev), bool)
    ncc = np.zeros((m, n_lev), np.int64)

    def record(lev: int, ii: np.ndarray, cyc: dict[str, np.ndarray]) -> None:
        kk[ii, lev] = np.asarray(cyc["unloading_stiffness"], np.float64)
        aa[ii, lev] = np.asarray(cyc["contact_area"], np.float64)
        okk[ii, lev] = np.asarray(cyc["converged"], bool)
        ncc[ii, lev] = np.asarray(cyc["n_contact"], np.int64)

    record(0, np.arange(m), cur)
    factor = np.ones(m, np.int64)
    level = np.zeros(m, np.int64)
    n_disk = np.full(m, window.n_disk_pixels, np.int64)
    top = np.full(m, window.top)  # top of the window each cell was last solved on
    origin = np.tile(np.asarray(window.origin, np.int64), (m, 1))
    sub = np.zeros(m, bool)
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
    d, centre, face = window.diameter, window.centre, window.face
    f = 1
    while active.any() and f < refine_max:
        f2, lev = 2 * f, round(math.log2(2 * f))
        idx = np.flatnonzero(active)
        bounds = source.disk_bounds(d, centre, f2) if refined else (0, 0, 0, 0)
        groups: list[tuple[PunchWindow, np.ndarray]] = []
        if _padded_pixels(bounds) <= max_px:
            try:
                w2 = wins.get(f2)
                if w2 is None:
                    w2 = wins[f2] = source.window(d, centre, f2, face)
                groups = [(w2, idx)]
            except MemoryError:
                groups = []
        if not groups:  # sub-windows that hold the contact
            groups, too_big = _sub_windows(source, cur, idx, origin, bounds, f2, max_px, window)
            note[too_big] = "memory"
            active[too_big] = False
        while groups:
            w2, ii = groups.pop(0)
            try:
                new, w2 = _solve_checked(
                    source, solve, w2, ii, f2, top, cur, bounds, max_px, window
                )
            except MemoryError:
                if w2.is_sub_window:
                    note[ii], active[ii] = "memory", False
                    continue
                wins.pop(f2, None)  # the whole window's solver does not fit: sub-windows
                more, too_big = _sub_windows(source, cur, ii, origin, bounds, f2, max_px, window)
                note[too_big], active[too_big] = "memory", False
                groups.extend(more)
                continue
            except _Grow:
                note[ii], active[ii] = "memory", False
                continue
            _store(cur, ii, new, m)
            record(lev, ii, new)
            factor[ii], level[ii] = f2, lev
            n_disk[ii] = w2.n_disk_pixels
            top[ii] = w2.top
            origin[ii] = w2.origin
            sub[ii] = w2.is_sub_window
            if lev >= 2:
                ext, err, _q = richardson(kk[ii, lev - 2], kk[ii, lev - 1], kk[ii, lev])
                good = (
                    okk[ii, lev - 2 : lev + 1].all(axis=1)
                    & (ncc[ii, lev] >= fewest)
                    & np.isfinite(ext)
                    & (err <= tol * np.abs(ext))
                )
                resolved[ii[good]] = True
                note[ii[good]] = "resolved"
                active[ii[good]] = False
        f = f2
    rows = np.arange(m)
    k_ext, k_err, a_ext, a_err = (np.full(m, math.nan) for _ in range(4))
    change, area_change = np.full(m, math.nan), np.full(m, math.nan)
    area_resolved = np.zeros(m, bool)
    two = level >= 2
    if two.any():
        r, lv = rows[two], level[two]
        k_ext[two], k_err[two], _ = richardson(kk[r, lv - 2], kk[r, lv - 1], kk[r, lv])
        a_ext[two], a_err[two], _ = richardson(aa[r, lv - 2], aa[r, lv - 1], aa[r, lv])
        area_resolved[two] = (
            okk[r, lv] & okk[r, lv - 1] & okk[r, lv - 2]
            & (ncc[r, lv] >= fewest)
            & np.isfinite(a_ext[two])
            & (a_err[two] <= tol * np.abs(a_ext[two]))
        )  # fmt: skip
    one = level == 1
    if one.any():
        k_ext[one], a_ext[one] = kk[one, 1], aa[one, 1]
        k_err[one] = np.abs(kk[one, 1] - kk[one, 0])
        a_err[one] = np.abs(aa[one, 1] - aa[one, 0])
    halved = level >= 1
    with np.errstate(divide="ignore", invalid="ignore"):
        lv = level[halved]
        change[halved] = np.abs(kk[rows[halved], lv] / kk[rows[halved], lv - 1] - 1.0)
        area_change[halved] = np.abs(aa[rows[halved], lv] / aa[rows[halved], lv - 1] - 1.0)
    n_contact = np.asarray(cur["n_contact"], np.int64)
    if not refined:  # the contact-pixel rule alone
        resolved = np.asarray(cur["converged"], bool) & (n_contact >= fewest)
        area_resolved = resolved.copy()
    area_resolved &= resolved
    dx, _dy = window.pixel_size
    saturated = n_contact >= n_disk
    if plateau is not None and math.isfinite(plateau) and plateau > 0:
        k = np.asarray(cur["unloading_stiffness"], np.float64)
        saturated |= np.isfinite(k) & (k >= (1.0 - tol) * plateau)
    whole = np.array(sorted(wins))
    tfac = np.array([whole[whole <= fc].max() for fc in factor], np.int64)
    return CellRefinement(
        cur,
        factor,
        dx / factor.astype(np.float64),
        n_disk,
        change,
        area_change,
        k_ext,
        k_err,
        a_ext,
        a_err,
        resolved,
        area_resolved,
        saturated,
        sub,
        note.astype(str),
        tfac,
        wins,
    )


def _region_of(
    box: np.ndarray, origin: np.ndarray, bounds: tuple[int, int, int, int]
) -> tuple[int, int, int, int] | None:
    """The fine-pixel region (inclusive, map coordinates at the finer factor) of a coarse
    near-contact box (window coordinates of a window at ``origin``), grown by the guard and
    clipped to the disk's bounds; None for an unknown box."""
    if box is None or np.any(np.asarray(box) < 0):
        return None
    y0, x0, y1, x1 = (int(v) for v in box)
    oy, ox = (int(v) for v in origin)
    g = SUB_WINDOW_GUARD
    by0, bx0, by1, bx1 = bounds
    return (
        max(by0, 2 * (oy + y0 - g)),
        max(bx0, 2 * (ox + x0 - g)),
        min(by1, 2 * (oy + y1 + g) + 1),
        min(bx1, 2 * (ox + x1 + g) + 1),
    )


def _union(regions: list[tuple[int, int, int, int]]) -> tuple[int, int, int, int]:
    return (
        min(r[0] for r in regions),
        min(r[1] for r in regions),
        max(r[2] for r in regions),
        max(r[3] for r in regions),
    )


def _sub_windows(
    source: WindowSource,
    cur: dict[str, np.ndarray],
    idx: np.ndarray,
    origin: np.ndarray,
    bounds: tuple[int, int, int, int],
    f2: int,
    max_px: int,
    window: PunchWindow,
) -> tuple[list[tuple[PunchWindow, np.ndarray]], np.ndarray]:
    """Sub-windows of the cells ``idx`` at factor ``f2``: one for all when their union fits
    ``max_px``, else one per cell; the cells whose own does not fit (or whose near-contact box
    is unknown) are returned apart."""
    boxes = cur.get("near_box")
    regions = {
        int(i): (None if boxes is None else _region_of(boxes[i], origin[i], bounds)) for i in idx
    }
    unknown = np.array([i for i in idx if regions[int(i)] is None], np.int64)
    known = [int(i) for i in idx if regions[int(i)] is not None]
    if not known:
        return [], unknown
    union = _union([regions[i] for i in known])
    make = lambda reg: source.window(  # noqa: E731
        window.diameter, window.centre, f2, window.face, region=reg
    )
    if _padded_pixels(union) <= max_px:
        return [(make(union), np.asarray(known, np.int64))], unknown
    out, big = [], list(unknown)
    for i in known:
        if _padded_pixels(regions[i]) <= max_px:
            out.append((make(regions[i]), np.asarray([i], np.int64)))
        else:
            big.append(i)
    return out, np.asarray(big, np.int64)


def _cut_edges(w: PunchWindow, bounds: tuple[int, int, int, int]) -> tuple[int, int, int, int]:
    """The window's extent in the map's pixels (inclusive, disk pixels only) and, per side,
    whether it cuts the disk: (y0, x0, y1, x1) with -1 on the sides that do not cut."""
    iy, ix = np.nonzero(w.mask)
    oy, ox = w.origin
    ext = (oy + int(iy.min()), ox + int(ix.min()), oy + int(iy.max()), ox + int(ix.max()))
    by0, bx0, by1, bx1 = bounds
    return (
        ext[0] if ext[0] > by0 else -1,
        ext[1] if ext[1] > bx0 else -1,
        ext[2] if ext[2] < by1 else -1,
        ext[3] if ext[3] < bx1 else -1,
    )


def _solve_checked(
    source: WindowSource,
    solve: Callable,
    w2: PunchWindow,
    ii: np.ndarray,
    f2: int,
    top: np.ndarray,
    cur: dict[str, np.ndarray],
    bounds: tuple[int, int, int, int],
    max_px: int,
    window: PunchWindow,
) -> tuple[dict[str, np.ndarray], PunchWindow]:
    """Solve the cells ``ii`` on ``w2``; on a sub-window, check that every cell's finer
    contact stays :data:`SUB_WINDOW_GUARD` pixels inside each cut edge, else grow the
    sub-window (three times its size) and solve again, while it fits ``max_px``."""
    g = SUB_WINDOW_GUARD
    for _ in range(8):
        plane = top[ii] - np.asarray(cur["displacement"], np.float64)[ii]
        new = solve(w2, ii, f2, w2.top - plane)
        if not w2.is_sub_window:
            return new, w2
        cb = new.get("contact_box")
        if cb is None:
            raise _Grow
        cut = _cut_edges(w2, bounds)
        oy, ox = w2.origin
        ok = True
        for b in np.asarray(cb):
            if np.any(b < 0):
                continue  # no contact
            y0, x0, y1, x1 = oy + b[0], ox + b[1], oy + b[2], ox + b[3]
            if (
                (cut[0] >= 0 and y0 - cut[0] < g)
                or (cut[1] >= 0 and x0 - cut[1] < g)
                or (cut[2] >= 0 and cut[2] - y1 < g)
                or (cut[3] >= 0 and cut[3] - x1 < g)
            ):
                ok = False
        if ok:
            return new, w2
        iy, ix = np.nonzero(w2.mask)
        hy, hx = int(iy.max() - iy.min()) + 1, int(ix.max() - ix.min()) + 1
        y0, x0 = oy + int(iy.min()), ox + int(ix.min())
        by0, bx0, by1, bx1 = bounds
        grown = (
            max(by0, y0 - hy),
            max(bx0, x0 - hx),
            min(by1, y0 + 2 * hy - 1),
            min(bx1, x0 + 2 * hx - 1),
        )
        if _padded_pixels(grown) > max_px:
            raise _Grow
        w2 = source.window(window.diameter, window.centre, f2, window.face, region=grown)
    raise _Grow
