# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Adhesive contact (an :class:`~warptrunc.contact.adhesion.Adhesion` law): the solve of
:class:`~warptrunc.contact.ContactSolver` with the law's tractions between the surfaces.

The problem. The traction on a pixel is the wall's reaction r ≥ 0 (where the gap is closed)
plus the law's force a(g) ≤ 0 at the pixel's gap g (Maugis–Dugdale [1]_: −σ₀·dx·dy below h₀;
exponential: −(w/ρ)·exp(−g/ρ)·dx·dy); the gap is g = K·(r + a) − h − offset ≥ 0 with
r·g = 0. Equilibria are the stationary points of the total energy ½·p·K·p − p·(h + offset) +
Σ φ(g)·dx·dy over the admissible gaps; the energy is not convex (φ is concave), so a contact
has several equilibria at one approach, and which one a loading history reaches is the
physics of adhesive hysteresis: the jump-in on approach, the adhesive neck on retraction, the
jump-out at pull-off.

The method: a fixed point on the law's forces, each step a non-adhesive solve. For fixed
forces a, r solves the non-adhesive contact of the *effective heights* h − K·a (the surface
pulled towards the flat by a): the bound-constrained problem min ½·r·K·r − r·(h − K·a +
offset), r ≥ 0, which the solver's own iteration (BCCG or Polonsky–Keer, free or periodic,
float32 or float64, displacement or load control, on any device) solves exactly as it
solves every contact. Then a ← a(g) at the new gaps, the heights h − K·a afresh (one
convolution), and again, warm-started, until the effective heights move by less than the
penetration tolerance ``pentol`` (the change times c/(1 − c) as well, c the observed ratio of
two successive changes, so that a slowly contracting iteration does not stop early). In
load control the non-adhesive solve takes the load F − Σa.

Why this method. The map a → a(g(a)) is monotone: more tension closes every gap (the
half-space's influence coefficients are all positive) and a closed gap pulls harder (the law's
force decreases towards contact), so from an equilibrium the iterates move one way, to the
nearest equilibrium in that direction — the one a quasi-static loading history reaches — or
past every one, which is a jump (in or out). Near a stable equilibrium it contracts (its rate
is the spectral radius of K·diag(−∂a/∂g), below 1 where the energy's Hessian
K⁻¹ + diag(∂a/∂g) is positive); for Maugis–Dugdale it stops exactly, when the cohesive zone
stops changing. It reuses the non-adhesive solver unchanged — its preconditioner, its
free-boundary transforms pruned to the map, its float32 path, its GPU kernels — where a
minimisation in the gap (Rey, Anciaux & Molinari 2017 [2]_, tamaas' ``PolonskyKeerRey`` with an
adhesion functional) needs K⁻¹ on the map, which the free (zero-padded) half-space does not
have without a solve over the padded grid (ContactEngineering's ``Adhesion`` minimises over
the padded displacements instead). The cost: one convolution per update and a warm-started
solve, short once the contact set settles.

The state the solver keeps between solves: q holds the wall's reaction r (so the contact set
is q > 0: the repulsive contact), u = K·r, ``adh`` the law's forces a and h the effective
heights h − K·a (the original heights are ``h_surface``); the gap u − h − offset is the whole
traction's. The pressure of :meth:`~warptrunc.contact.ContactSolver.maps` is (r + a)/(dx·dy),
the load Σr + Σa. Barber's punch [3]_ (:meth:`~warptrunc.contact.ContactSolver.punch_stiffness`)
takes the repulsive contact set: with adhesion it is the stiffness at a fixed contact area (the
unloading stiffness 2E*a of a circular contact), not dF/dδ along an adhesive curve, whose
contact edge moves with the adhesive stresses.

References
----------
.. [1] D. Maugis, J. Colloid Interface Sci. 150, 243 (1992). doi:10.1016/0021-9797(92)90285-T
.. [2] J. Rey, G. Anciaux, J.-F. Molinari, Normal adhesive contact on rough surfaces: efficient
   algorithm for FFT-based BEM resolution, Comput. Mech. 60, 69 (2017).
   doi:10.1007/s00466-017-1392-5
.. [3] J.R. Barber, Proc. R. Soc. A 459, 53 (2003). doi:10.1098/rspa.2002.1038
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
from collections.abc import Iterator
from typing import Any

import numpy as np
import warp as wp

from ...kernels.contact import adhesion as _ka
from ..halfspace import DTYPES
from ..results import ContactState

__all__ = ["AdhesiveSolves"]

RATE_CAP = 0.99
"""The largest contraction ratio c of two successive changes of the effective heights taken
into the stopping test (its factor c/(1 − c) is then at most 99)."""

INEXACT = 0.1
"""While the effective heights still move, each non-adhesive solve stops at this fraction of
their last change (or at ``pentol``, whichever is larger): the law's forces move them again,
so the solve need not be more exact; the last solve is at ``pentol``."""

THERMOTOL_LOOSE = 1e-3
"""The largest relative tolerance on the total force of those inexact solves."""


class AdhesiveSolves:
    """The adhesive solve of :class:`~warptrunc.contact.ContactSolver` (a base class holding
    methods only; the solver's maps and settings are its own)."""

    def _allocate_adhesion(self, h_dev: np.ndarray) -> None:
        """The law's force map and the original heights (``h`` becomes the effective ones)."""
        sc = DTYPES[self.dtype][0]
        self.adh_buf, self.adh = self.hs.map_buffer()  # the law's pixel forces a (N, ≤ 0)
        self.h_surface = wp.array(h_dev, dtype=sc, device=self.device)  # original heights (m)
        self._adhesive_sum = 0.0  # Σ a of the forces in adh (N)

    def _reset_adhesion(self) -> None:
        """No adhesive forces: the effective heights are the original ones."""
        self.adh_buf.zero_()
        wp.copy(self.h, self.h_surface)
        self._adhesive_sum = 0.0

    def _law_args(self) -> list:
        """The law's arguments of the kernels: its number, w·dx·dy (J) and its range (m)."""
        dx, dy = self.pixel_size
        law = self.adhesion
        return [law.code, wp.float64(law.work * dx * dy), wp.float64(law.range)]

    def _update_law(self) -> tuple[float, float, float]:
        """a ← a(g) at the gaps of the current state, and the effective heights h − K·a afresh
        (one convolution, skipped when no force changed). Returns (the largest change of the
        effective heights (m), Σ a (N), the attractive pixels)."""
        red = self.hs.reduction
        n_map = self.shape[0] * self.shape[1]
        red.launch(
            _ka.adhesive_force_kernel,
            n_map,
            [self.q, self.u, self.h, wp.float64(self.offset), *self._law_args()],
            [self.adh],
        )
        da, s_a, n_att, _ = red.read((True, False, False, False))  # sync point
        if da == 0.0:
            return 0.0, float(s_a), float(n_att)
        ka = self.hs.apply(self.adh_buf)
        red.launch(_ka.effective_heights_kernel, n_map, [self.h_surface, ka], [self.h])
        del ka
        return float(red.read((True,))[0]), float(s_a), float(n_att)  # sync point

    def _solve_adhesive(self, depth: float | None, load: float | None) -> ContactState:
        """One adhesive solve at approach ``depth`` (m) or ``load`` (N; may be tensile),
        warm-started from the current state (module docstring). Returns its state."""
        tol = float(self.pentol)
        n_it, n_conv, n_updates = 0, 0.0, 0
        s_a = self._adhesive_sum
        info: dict[str, Any] = {}
        conv, separated = False, False
        dh_last: float | None = None
        loose = 1.0  # the tolerance of the next non-adhesive solve, in units of pentol
        n_att = 0.0
        final = False  # the forces have settled: one last solve at the full tolerance
        for _ in range(self.maxiter):
            if load is not None and not load - s_a > 0.0:
                separated = True  # the law's forces hold more than the load: no wall contact
                break
            with self._tolerances(1.0 if final else loose):
                info = self._solve_elastic(depth, None if load is None else load - s_a)
            n_it += info["n_iterations"]
            n_conv += info["n_convolutions"]
            if final:
                conv = bool(info["converged"])
                break
            dh, s_a, n_att = self._update_law()
            n_updates += 1
            if dh == 0.0:  # no force changed: the state is the solution
                if loose == 1.0:
                    conv = bool(info["converged"])
                    break
                final = True
                continue
            n_conv += 1.0
            rate = 0.0 if not dh_last else min(RATE_CAP, dh / dh_last)
            dh_last = dh
            final = dh * max(1.0, rate / (1.0 - rate)) < tol
            loose = max(1.0, INEXACT * dh / tol)
        self._adhesive_sum = float(s_a)
        if not info:
            info = self._separated(self.offset)
        self._point = self._point_of(info, capped=True) if conv else None
        state = self._state(info, None)
        dx, dy = self.pixel_size
        return dataclasses.replace(
            state,
            load=float(info["load"]) + self._adhesive_sum,
            n_iterations=int(n_it),
            n_convolutions=float(n_conv),
            converged=bool(conv and not separated),
            adhesive_force=self._adhesive_sum,
            n_attractive=int(n_att),
            attractive_area=float(n_att) * dx * dy,
            n_adhesion_updates=int(n_updates),
        )

    @contextlib.contextmanager
    def _tolerances(self, factor: float) -> Iterator[None]:
        """The solver's ``pentol`` and ``thermotol`` times ``factor`` (≥ 1; ``thermotol`` at
        most ``THERMOTOL_LOOSE``) for the non-adhesive solves inside."""
        pentol, thermotol = self.pentol, self.thermotol
        if factor > 1.0:
            self.pentol = pentol * factor
            self.thermotol = max(thermotol, min(THERMOTOL_LOOSE, thermotol * factor))
        try:
            yield
        finally:
            self.pentol, self.thermotol = pentol, thermotol

    def _separated(self, offset: float) -> dict[str, Any]:
        """The info dict of a load-controlled solve whose load the law's forces hold without
        any wall contact (not converged: there is no equilibrium with a contact)."""
        return {
            "depth": offset + self.h_max,
            "load": 0.0,
            "mean_gap": math.nan,
            "n_iterations": 0,
            "n_convolutions": 0.0,
            "residual": math.inf,
            "max_tensile_force": 0.0,
            "converged": False,
            "n_contact": 0,
        }

    def _adhesive_pressure(self, q: np.ndarray) -> np.ndarray:
        """The whole traction's pixel forces (N): the wall's ``q`` plus the law's forces."""
        return q + self.adh.numpy().astype(np.float64)  # sync point
