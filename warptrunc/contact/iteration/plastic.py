# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic–perfectly-plastic solves of :class:`~warptrunc.contact.ContactSolver` (a finite
``hardness``): the capped constrained CG, load control by the approach, and the plastic flow.

Elastic–perfectly-plastic contact (``hardness`` H < inf; kernels in
``warptrunc.kernels.contact.plastic``). The local pressure is capped: 0 ≤ p ≤ H, i.e. each
pixel force 0 ≤ q ≤ H·dx·dy. One solve at a fixed approach is the bound-constrained problem
min ½·q·K·q − q·(h + offset) over that box, solved by the same constrained CG with the hardness
bound of ContactMechanics' ``constrained_conjugate_gradients`` (Almqvist et al. 2007): the CG
set is 0 < q < H·dx·dy (pixels at the cap leave it as pixels at zero force do); after the step,
forces above the cap are clamped to it, tensile ones to zero; a pixel at zero force that
penetrates (g < 0) or a pixel at the cap whose gap is open (g > 0) changes sides (the CG
restarts). Unlike ContactMechanics, which then switches to an over-relaxation when almost all of
the contact is at the cap, such pixels are placed at half the cap (inside the CG set) rather
than across the interval, so that the next CG step, whose length is fitted to all of them, moves
them together; this converged in every case tried (cold starts up to 0.9·R_t, H/E* from 1e-3 to
3e-2), and the results equal ContactMechanics' ``PlasticNonSmoothContactSystem`` on the same
map (``tests/test_plastic.py``). Converged means, beside the elastic criteria, that no force
exceeds the cap by more than ``forcetol`` and no pixel at the cap has a gap above ``pentol``.
Then the plastic flow (Weber et al. 2018; ContactMechanics' ``PlasticTopography``): where
p = H the heights drop by the penetration, h ← u − offset, so that the gap there is zero; the
heights map on the device *is* the plastic state (the original map is kept on the host:
:meth:`~warptrunc.contact.ContactSolver.plastic_displacement` = h_original − h ≥ 0), so the
plastic solve needs no
more device memory than the elastic one. Load control with a cap finds the approach with
F(δ) = load by a safeguarded secant iteration (bracketed; regula falsi and bisection as
fallbacks) over displacement-controlled solves of the current surface, each warm-started from
the last, starting from the last converged state and the last load solve's slope, and lets the
surface flow once, after the last.

Path dependence. A later solve at a smaller approach or load is elastic from the deformed
surface (the plastic state only grows); ``plastic=False`` (or
:meth:`~warptrunc.contact.ContactSolver.freeze_plastic`)
solves without the cap and without flow. After a converged loading solve the state (q, u, h) is
itself a solution of the capped problem at that approach with zero further flow (p = H and
g = 0 where it flowed), and that problem has one solution (K is positive definite, the box is
convex). So unloading from a peak and reloading to it returns to the same state and adds no
plastic volume, and a load / partial-unload / reload history reaches each peak in the same state
as a monotonic loading through the same peaks: unloading is elastic and plastic flow happens only
at the cap, which an unloaded state does not reach (tested: no pixel reaches H while unloading).

References: A. Almqvist, F. Sahlin, R. Larsson, S. Glavatskih, Tribol. Int. 40, 574 (2007),
doi:10.1016/j.triboint.2005.11.008; B. Weber, T. Suhina, T. Junge, L. Pastewka, A.M. Brouwer,
D. Bonn, Nat. Commun. 9, 888 (2018), doi:10.1038/s41467-018-02981-y.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import warp as wp

from ...kernels.contact import plastic as _kp
from ...kernels.contact import spectral as _kr

__all__ = ["CappedSolves"]


class CappedSolves:
    """The capped solves of :class:`~warptrunc.contact.ContactSolver` (a base class holding
    methods only; the solver's maps and settings are its own)."""

    @property
    def _cap(self) -> float:
        dx, dy = self.pixel_size
        return self.hardness * dx * dy  # force cap per pixel (N)

    def _self_influence(self) -> float:
        """Displacement per unit force at the loaded pixel itself, G(0, 0) (m/N)."""
        if not hasattr(self, "_g00"):
            self._g00 = float(self.hs.table[0:1, 0:1].numpy()[0, 0])  # sync point
        return self._g00

    def _solve_capped(self, offset: float) -> dict[str, Any]:
        """Constrained CG with 0 ≤ q ≤ H·dx·dy at a fixed offset (m); the heights are not changed
        (that is :meth:`_flow`)."""
        if self.settings.algorithm == "bccg":
            return self._solve_bccg(offset, None, self._cap)
        red, hs, dev = self.hs.reduction, self.hs, self.device
        n_map = self.shape[0] * self.shape[1]
        inv_n = 1.0 / hs.n_total
        hf = wp.float64(self._cap)
        fallback = wp.float64(1.0 / self._self_influence())
        self._warm_start(offset)
        n_transforms = 2
        red.launch(
            _kp.capped_sums_kernel, n_map, [self.q, self.u, self.h, wp.float64(offset), hf], []
        )
        n_c, _, s_gg, _ = red.read((False, False, False, False))
        self.t.zero_()
        g_old, cg = 1.0, False
        last_total = None
        info: dict[str, Any] = {"converged": False}
        update_cols = (False, False, False, False, True, False, False, False)
        advance_cols = (True, False, False, False, True, False, False)
        periodic = int(self.substrate == "periodic")
        for it in range(1, self.maxiter + 1):
            g, a_cg = s_gg, n_c
            beta = g / g_old if (cg and g_old > 0) else 0.0
            red.launch(
                _kp.capped_direction_kernel,
                n_map,
                [self.q, self.u, self.h, wp.float64(offset), wp.float64(beta), hf],
                [self.t, self.mask],
            )
            spec = hs.work
            hs.forward(self.t_buf, spec)
            hs.spectral(_kr.SPECTRUM_APPLY, spec, col=1)
            wp.launch(
                _kp.capped_step_kernel,
                dim=1,
                inputs=[red.fold((False, False)), wp.float64(n_c), wp.float64(inv_n), fallback],
                outputs=[self.tau],
                device=dev,
            )
            red.launch(
                _kp.capped_update_kernel,
                n_map,
                [self.t, self.u, self.h, wp.float64(offset), self.tau, hf],
                [self.q, self.mask, self.lin, self.lane_count],
            )
            _, t_k_t, n_nc, n_clamp, max_viol, total, tau, n_changed = red.read(
                update_cols
            )  # sync point
            n_changed = int(n_changed)
            n_transforms += 1
            if n_c > 0 and not t_k_t > 0.0:
                g = 0.0
            exact = it == 1 or it % self.refresh == 0 or n_changed > self.direct_max
            n_transforms += self._exact_or_listed(spec, exact, n_changed, 1.0)
            r = hs.inverse(spec)
            n_transforms += 1
            red.launch(
                _kp.capped_advance_kernel,
                n_map,
                [
                    r,
                    int(not exact),
                    wp.float64(tau),
                    hs.table,
                    periodic,
                    self.change_index,
                    self.change_value,
                    0 if exact else n_changed,
                    self.q,
                    self.h,
                    wp.float64(offset),
                    hf,
                    self.mask,
                ],
                [self.u],
            )
            du, n_c, _, s_gg, viol, s_gap, total = red.read(advance_cols)  # sync point
            del r
            g_old = g
            cg = n_nc == 0 and n_clamp == 0
            rms_pen = math.sqrt(g / a_cg if a_cg > 0 else g)
            ok = self._steady(total, last_total)
            last_total = total
            res = max(rms_pen, viol, du)
            ok = ok and res < self.pentol and max_viol < self.forcetol and n_nc == 0
            info = self._iteration_info(
                offset, total, s_gap / n_map, it, n_transforms, res, max_viol, ok
            )
            if ok:
                break
        self.offset = offset
        return info

    def _solve_load_trial(self, load: float) -> dict[str, Any]:
        """Load control with the cap, starting with an elastic trial: the elastic solution of the
        current surface at the load (offset load control, no cap). Where no pixel reaches H it is
        the capped solution too (it satisfies the capped problem's conditions, which have one
        solution) and is kept; else the capped δ lies deeper (the cap only lowers F(δ)) and the
        secant starts at the trial's approach. Once a trial has failed, the later loads of the
        history (which reach further up the same asperities) go to the secant directly, until
        :meth:`reset`."""
        if getattr(self, "_trial_failed", False):
            return self._solve_load_secant(load, capped=True)
        trial = self._solve_elastic(None, load)
        n_plastic = self._flow(apply=False)[1]
        if trial["converged"] and n_plastic == 0:
            return trial
        self._trial_failed = True
        # a converged trial's approach is a lower bound of the capped one; an unconverged
        # trial (the offset iteration can stall under complete contact) tells nothing
        start = float(trial["depth"]) if trial["converged"] else None
        info = self._solve_load_secant(load, capped=True, start=start)
        info.update(
            n_iterations=info["n_iterations"] + trial["n_iterations"],
            n_convolutions=info["n_convolutions"] + trial["n_convolutions"],
        )
        return info

    def _solve_load_secant(
        self, load: float, *, capped: bool, start: float | None = None
    ) -> dict[str, Any]:
        """Load control by the approach: δ with F(δ) = load, by a safeguarded secant iteration
        on displacement-controlled solves of the current surface, capped (``capped``; the
        heights flow once, after the last) or elastic, each warm-started from the last.

        F(δ) is nondecreasing and piecewise smooth: its slope is the stiffness of the contact
        pixels below the cap (pixels at the cap carry H·dx·dy whatever δ), so it is linear while
        the contact set and the capped set stay (under complete contact, the flat punch's
        stiffness), and flat while every contact pixel is at the cap. The first step starts from
        the last converged state when it is a point of F on the current surface (every converged
        solve is on the elastic F; on the capped F, a capped solve or an elastic one with no
        pixel at the cap: no solve is needed there), with the slope of the last load solve's
        final secant or of :meth:`punch_stiffness` since; without one, from a lower bound of δ
        (the free half-space: F(δ) ≤ K·δ with K = 2E*a the stiffness of a flat circular punch
        of radius a = half the map's diagonal, which covers every pixel); then the secant of the last two iterates, kept inside
        the bracket [F < load, F > load] once there is one (regula falsi on the bracket when the
        secant leaves it or is flat, bisection when neither the bracket nor the load mismatch
        shrinks by half in two steps); before a bracket, flats are crossed by doubling steps.
        It stops when F is within ``thermotol``·load of the load, or when the bracket is narrower
        than the approach the solver can resolve (round-off of δ in its precision); the latter
        counts as converged, at the bracket end whose load is nearer.
        """
        n_it, n_conv = 0, 0.0
        tol = max(self.thermotol, 1e-9) * load
        lo, f_lo = 0.0, 0.0  # the flat at the original top: nothing penetrates, F = 0
        hi = f_hi = None
        prev: tuple[float, float] | None = None  # the last point of F before x
        x = None
        point = getattr(self, "_point", None)
        hint = getattr(self, "_slope", None)
        if point is not None and capped and not point[2]:
            point = None  # an elastic solution with pixels above the cap: not on the capped F
        if point is not None:
            point = point[:2]
        if point is not None and point[0] > 0 and abs(point[1] - load) > tol:
            prev = point
            if point[1] < load:
                lo, f_lo = point
            else:
                hi, f_hi = point
            if hint is not None and hint > 0:
                x = point[0] + (load - point[1]) / hint
                if hi is None:
                    x = min(x, 4 * point[0])
                elif not lo < x < hi:
                    x = None
        if start is not None and start > lo and (hi is None or start < hi):
            x = start
        if x is None:
            if hi is not None:
                x = lo + (load - f_lo) * (hi - lo) / (f_hi - f_lo)
            elif self._depth is not None and self._depth > 0:
                x = self._depth
            elif self._depth is None and getattr(self, "_approach_hint", None):
                x = self._approach_hint  # a solution known elsewhere (hint_approach)
            elif self.substrate == "free":
                dx, dy = self.pixel_size
                a = 0.5 * math.hypot(self.shape[1] * dx, self.shape[0] * dy)
                x = max(load / (2.0 * self.contact_modulus * a), float(self.pentol))
            else:
                x = max(float(self.pentol), 1e-2 * self._scale())
        eps = 1.2e-7 if self.dtype == "float32" else 2.3e-16
        info: dict[str, Any] = {}
        conv = True
        pts: list[tuple[float, float]] = [] if prev is None else [prev]  # points of F, in order
        flats: set[float] = set()  # approaches of points on a flat below the load
        history: list[tuple[float, float]] = []  # (bracket width, |F − load|) per bracketed step
        collapsed = False

        def solve_at(x: float) -> dict[str, Any]:
            return self._solve_capped(x - self.h_max) if capped else self._solve_elastic(x, None)

        n_bad = 0  # unconverged displacement solves
        for _ in range(200):
            info = solve_at(x)
            n_it += info["n_iterations"]
            n_conv += info["n_convolutions"]
            conv = info["converged"]
            f = info["load"]
            if not conv:
                # an unconverged solve's load is not a point of F: no bracket, no secant from
                # it; try nearby (a stall is a property of the approach, rarely of its neighbours)
                n_bad += 1
                if n_bad > 8:
                    break
                x = 0.5 * (lo + hi) if hi is not None and x != 0.5 * (lo + hi) else x * (1 + 1e-3)
                continue
            if abs(f - load) <= tol:
                break
            if f < load:
                lo, f_lo = x, f
                same = [p[0] for p in pts if p[1] < load and abs(p[1] - f) <= tol and p[0] != x]
                if same:
                    flats.update(same)
                    flats.add(x)
            else:
                hi, f_hi = x, f
            step = x - pts[-1][0] if pts else 0.0
            pts.append((x, f))
            # the secant of the two latest points off the flats
            ends = [p for p in pts if p[0] not in flats][-2:]
            cand = None
            if len(ends) == 2 and ends[1][0] != ends[0][0]:
                slope = (ends[1][1] - ends[0][1]) / (ends[1][0] - ends[0][0])
                if slope > 0:
                    self._slope = slope
                    cand = ends[1][0] + (load - ends[1][1]) / slope
            if hi is None:
                if x in flats or cand is None or not cand > x:  # a flat, or no slope: expand
                    if f <= 0 or x in flats:
                        grow = 2 * x
                    else:
                        grow = x * min(4.0, max(1.1, (load / f) ** (2 / 3)))
                    cand = max(grow, x + 2 * abs(step))
                x = min(cand, 4 * x)
                continue
            width = hi - lo
            if width <= max(1e-12 * hi, 8 * eps * (abs(self.h_max) + abs(hi))):
                collapsed = True
                break
            history.append((width, abs(f - load)))
            slow = len(history) >= 3 and (
                width > 0.5 * history[-3][0] and abs(f - load) > 0.5 * history[-3][1]
            )
            if slow or (lo in flats and not (cand is not None and lo < cand < hi)):
                x = 0.5 * (lo + hi)
                history.clear()
            elif cand is not None and lo < cand < hi:
                x = cand
            else:
                x = lo + (load - f_lo) * width / (f_hi - f_lo)
                x = min(max(x, lo + 1e-3 * width), hi - 1e-3 * width)
        else:
            conv = False
        if collapsed:
            best_lo = load - f_lo < f_hi - load
            if (x == lo) != best_lo:  # solve again at the nearer end (warm: a few iterations)
                info = solve_at(lo if best_lo else hi)
                n_it += info["n_iterations"]
                n_conv += info["n_convolutions"]
                conv = info["converged"]
        info = dict(info)
        info.update(
            n_iterations=n_it,
            n_convolutions=n_conv,
            converged=conv and (collapsed or abs(info["load"] - load) <= tol),
        )
        return info

    def _scale(self) -> float:
        """Height range of the original map (m), for a first guess of δ."""
        if self._h0 is not None:
            return float(np.ptp(self._h0)) or self.pentol
        return self.pentol

    def _flow(self, apply: bool) -> tuple[int, int]:
        """Count contact and capped pixels; with ``apply``, let the capped pixels flow (the
        heights there drop to close the gap) and add the removed volume to the state."""
        red = self.hs.reduction
        red.launch(
            _kp.plastic_flow_kernel,
            self.shape[0] * self.shape[1],
            [self.q, self.u, wp.float64(self.offset), wp.float64(self._cap), int(apply)],
            [self.h],
        )
        n_c, n_p, s_dw = red.read((False, False, False))  # sync point
        dx, dy = self.pixel_size
        self.plastic_volume += float(s_dw) * dx * dy
        return int(n_c), int(n_p)
