# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""What the solve loops of :class:`~warptrunc.contact.ContactSolver` share: which iteration an
elastic solve runs, the warm start, the map sums, the stopping test on a steady quantity, and
the records a solve returns (the info dict of an iteration, the
:class:`~warptrunc.contact.ContactState` of a solve, the known point of F(δ) for load control).

The loops themselves are in :mod:`~warptrunc.contact.iteration.pk` (Polonsky–Keer),
:mod:`~warptrunc.contact.iteration.bccg` (BCCG with a read-back after each reduction, ``loop="host"``, the default),
:mod:`~warptrunc.contact.iteration.bccg_device` (BCCG with its scalar steps folded on the device and one
read-back per iteration, ``loop="device"``, and its CUDA-graph replay, ``loop="graph"``) and :mod:`~warptrunc.contact.iteration.plastic`
(the capped solves); every decision that chooses what to launch next is taken on the host, with
the code here. The memory model, where a multi-device path starts, is
:mod:`warptrunc.contact.memory` (whose docstring lists what lives where).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import warp as wp

from ...kernels.contact import cg as _k
from ...kernels.contact import spectral as _kr
from ..results import ContactState

__all__ = ["OPEN_GAP_FRACTION", "PENTOL_FLOOR", "SolveLoop"]

OPEN_GAP_FRACTION = 1e-2
"""Under the default ``SolverSettings.pentol=None``, the penetration tolerance of a solve is at
most this fraction of the mean gap over the open pixels (q = 0) of the state tested: near full
contact the gaps left are far smaller than rms height/(10·mean n), which then misplaces the
contact edges (a periodic wavy surface, λ = 2048 px, float64, at Westergaard's load of 99 %
contact: an open region of 18 px where the closed form has 20.5; within one pixel at 50, 90, 99
and 99.9 % with this rule, ``tests/test_westergaard.py``). Elsewhere the mean open gap is of the
order of the rms height and the rule leaves the tolerance as it was."""

PENTOL_FLOOR = 100.0
"""The adapted tolerance stays above this many machine epsilons (of the solver's dtype) of the
rms height, which the round-off of u and h allows (in float32 the adaptation is then small: it
cannot resolve gaps of 10⁻⁶ of the heights, guide/performance.md)."""


class SolveLoop:
    """The shared pieces of :class:`~warptrunc.contact.ContactSolver`'s solve loops (a base
    class holding methods only; the solver's maps and settings are its own)."""

    def _sums(self, offset: float) -> np.ndarray:
        red = self.hs.reduction
        red.launch(
            _kr.contact_sums_kernel,
            self.shape[0] * self.shape[1],
            [self.q, self.u, self.h, wp.float64(offset)],
            [],
        )
        return red.read((False, False, False, False))

    @staticmethod
    def _point_of(info: dict[str, Any], *, capped: bool) -> tuple[float, float, bool] | None:
        """(approach (m), load (N), on the capped curve) of a converged solve: a known point of
        the elastic F(δ) of the current surface (every converged solve is one: where the
        surface flowed, p = H and the gap is closed) and, when ``capped``, of the capped F(δ)
        too, for the next secant load control; None if it did not converge."""
        if info["converged"]:
            return float(info["depth"]), float(info["load"]), bool(capped)
        return None

    def _state(self, info: dict[str, Any], flow: tuple[int, int] | None) -> ContactState:
        self._depth = float(info["depth"])
        dx, dy = self.pixel_size
        n_c, n_p = (info["n_contact"], 0) if flow is None else flow
        return ContactState(
            depth=float(info["depth"]),
            load=float(info["load"]),
            n_contact=int(n_c),
            contact_area=n_c * dx * dy,
            n_plastic=int(n_p),
            plastic_area=n_p * dx * dy,
            plastic_volume=self.plastic_volume,
            mean_gap=float(info["mean_gap"]),
            n_iterations=int(info["n_iterations"]),
            n_convolutions=float(info["n_convolutions"]),
            residual=float(info["residual"]),
            max_tensile_force=float(info["max_tensile_force"]),
            converged=bool(info["converged"]),
        )

    def _pentol_now(self, s_gap: float, n_contact: float, n_map: int) -> float:
        """The penetration tolerance (m) of the state whose gaps sum to ``s_gap`` (m) with
        ``n_contact`` of its ``n_map`` pixels in contact: ``pentol`` as given, or by default
        the smaller of ``pentol`` and ``OPEN_GAP_FRACTION`` of the mean open gap, not below
        ``PENTOL_FLOOR`` machine epsilons of the rms height."""
        n_open = n_map - n_contact
        if self.settings.pentol is not None or n_open <= 0:
            return self.pentol
        eps = float(np.finfo(np.float32 if self.dtype == "float32" else np.float64).eps)
        rms = 10.0 * 0.5 * (self.shape[0] + self.shape[1]) * self.pentol  # default_pentol's
        adapted = OPEN_GAP_FRACTION * s_gap / n_open
        return min(self.pentol, max(adapted, PENTOL_FLOOR * eps * rms))

    def _bccg_stop(
        self,
        sums: Any,
        offset: float,
        total: float,
        load: float | None,
        du: float | None,
        viol: float,
        it: int,
        n_transforms: int,
        last: dict[str, float],
    ) -> tuple[dict[str, Any], bool]:
        """The BCCG loops' test of the state reached by the last step (host, device and
        sharded loops alike).

        ``sums`` are the residual kernel's nine (n free, Σ r, n(0 < q < cap), Σ g², max abs g,
        penetration, open gap at the cap, n(q > 0), Σ g); ``offset`` (m), ``total`` (N, the
        load after scaling in load control), ``load`` (N; None: displacement control), ``du``
        (m; None before the first step) and ``viol`` (N) those of the state; ``last`` holds
        the previous iteration's total and height and is updated. Returns the iteration's
        info dict and whether the solve stops: converged, or nothing free (every pixel at a
        bound with its gradient pointing out of the box, so the exact state satisfies the
        conditions of the solution)."""
        n_map = self.shape[0] * self.shape[1]
        (n_f, _s_r, n_cg, s_gg, g_max, pen, open_cap, n_c, s_gap) = (float(x) for x in sums)
        rms = math.sqrt(s_gg / n_cg) if n_cg > 0 else 0.0
        res = max(rms, g_max, pen, open_cap, 0.0 if du is None else du)
        tol = self._pentol_now(s_gap, n_c, n_map)  # pentol, adapted near full contact
        ok = du is not None and res < tol and viol < self.forcetol
        if load is not None:
            ok = ok and total != 0 and abs((total - load) / total) < self.thermotol
            height = self.h_max + offset
            ok = ok and self._steady(height, last.get("height"))
            last["height"] = height
        else:
            ok = ok and self._steady(total, last.get("total"))
        last["total"] = total
        info = self._iteration_info(
            offset, total, s_gap / n_map, it, n_transforms, res, viol, ok, n_contact=n_c
        )
        if ok:
            return info, True
        if n_f == 0:
            info["converged"] = pen <= self.pentol and open_cap <= self.pentol
            return info, True
        return info, False

    def _steady(self, new: float, old: float | None) -> bool:
        """Whether a quantity (a total force in N, a height in m) changed by less than
        ``thermotol`` relative to its new value since the last iteration (False without one)."""
        if old is None:
            return False
        return new == old or (new != 0 and abs((new - old) / new) < self.thermotol)

    def _iteration_info(
        self,
        offset: float,
        load: float,
        mean_gap: float,
        it: int,
        n_transforms: int,
        res: float,
        max_tensile: float,
        ok: bool,
        n_contact: int | None = None,
    ) -> dict[str, Any]:
        """The info dict of one iteration of a solve loop (PK, BCCG, capped): approach (m), load
        (N), mean gap (m), iterations, convolutions (two transforms each), residual (m), largest
        tensile force (N), converged, and the contact pixels when counted; a non-finite residual
        raises FloatingPointError (the solve diverged)."""
        if not math.isfinite(res):
            raise FloatingPointError(
                f"the contact solve diverged at iteration {it} (residual {res})"
            )
        info = {
            "depth": offset + self.h_max,
            "load": float(load),
            "mean_gap": mean_gap,
            "n_iterations": it,
            "n_convolutions": n_transforms / 2,
            "residual": float(res),
            "max_tensile_force": float(max_tensile),
            "converged": ok,
        }
        if n_contact is not None:
            info["n_contact"] = int(n_contact)
        return info

    def _warm_start(self, offset: float) -> None:
        """Warm start of a solve at ``offset`` (m): raise u where the map would penetrate and
        add K⁻¹·(that increase) to q (two transforms; q may leave its bounds)."""
        wp.launch(
            _k.clamp_displacement_kernel,
            dim=self.shape,
            inputs=[self.h, wp.float64(offset)],
            outputs=[self.u, self.t],
            device=self.device,
        )
        dq = self.hs.apply(self.t_buf, inverse=True)
        wp.launch(
            _k.add_map_kernel, dim=self.shape, inputs=[dq], outputs=[self.q], device=self.device
        )

    def _solve_elastic(self, depth: float | None, load: float | None) -> dict[str, Any]:
        """The elastic solve on the current heights (the path of H = inf), by the settings'
        algorithm: :mod:`warptrunc.contact.iteration.bccg` or :mod:`warptrunc.contact.iteration.pk`."""
        load_control = load is not None
        if self.settings.algorithm == "bccg":
            if load_control:
                start = self.offset if self._depth is not None else 0.0
                hint = getattr(self, "_approach_hint", None)
                if self._depth is None and hint is not None:  # a solution known elsewhere
                    start = hint - self.h_max
                if self._point is not None and self._slope:  # predicted by the last slope
                    start = self._point[0] - self.h_max + (load - self._point[1]) / self._slope
            else:
                start = float(depth) - self.h_max
            return self._solve_bccg(start, load, None)
        return self._solve_pk(depth, load)
