# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Barber's incremental stiffness of :class:`~warptrunc.contact.ContactSolver`'s current contact:
a rigid flat punch shaped like the contact set (every pixel with p > 0), K·x = 1 m on the set,
k = Σx (N/m); by plain CG (``algorithm="pk"``) or CG preconditioned with c·K⁻¹·c
(``"bccg"``, :mod:`warptrunc.contact.iteration.bccg`).

References: J.R. Barber, Proc. R. Soc. A 459, 53 (2003), doi:10.1098/rspa.2002.1038 (the
incremental stiffness equals that of a rigid punch shaped like the contact area).
"""

from __future__ import annotations

import math

import numpy as np
import warp as wp

from ...kernels.contact import cg as _k
from ..halfspace import DTYPES

__all__ = ["PunchStiffness"]


class PunchStiffness:
    """Barber's punch solve of :class:`~warptrunc.contact.ContactSolver` (a base class holding
    methods only; the solver's maps and settings are its own)."""

    def _punch_solve(self, rtol: float | None = None) -> tuple[float, int, bool]:
        """:meth:`~warptrunc.contact.ContactSolver.punch_stiffness` (its docstring)."""
        if rtol is None:
            rtol = 1e-10 if self.dtype == "float64" else 1e-5
        sc = DTYPES[self.dtype][0]
        dev = self.device
        wp.launch(
            _k.contact_mask_kernel, dim=self.shape, inputs=[self.q], outputs=[self.mask], device=dev
        )
        x = self.lin  # q_lin is scratch between solves: the punch's unknown uses its map
        x.zero_()
        res = wp.zeros(self.shape, dtype=sc, device=dev)
        wp.launch(
            _k.fill_map_kernel,
            dim=self.shape,
            inputs=[self.mask, wp.float64(1.0)],
            outputs=[res],
            device=dev,
        )
        d = self.t  # the CCG direction is free now: the first direction is the residual
        wp.copy(d, res)
        n_set = float(np.count_nonzero(self.mask.numpy()))  # sync point
        if n_set == 0:
            return 0.0, 0, True
        if self.settings.algorithm == "bccg":
            k, it, ok = self._punch_pcg(x, res, n_set, rtol)
        else:
            k, it, ok = self._punch_cg(x, res, n_set, rtol)
        self.t.zero_()
        if ok and k > 0:
            self._slope = float(k)  # dF/dδ of unloading from here: the next secant's first step
        return float(k), it, ok

    def _punch_cg(
        self, x: wp.array, res: wp.array, n_set: float, rtol: float
    ) -> tuple[float, int, bool]:
        """Barber's punch by plain CG from x = 0, res = 1 m on the set, d = res (in self.t)."""
        dev, red, hs = self.device, self.hs.reduction, self.hs
        ny, nx = self.shape
        d = self.t
        rr, k, it, ok = n_set, 0.0, 0, False
        for it in range(1, self.maxiter + 1):  # noqa: B007
            kd = hs.apply(self.t_buf, energy_column=0)
            d_k_d = red.read((False,))[0] / hs.n_total  # sync point
            alpha = rr / d_k_d
            red.launch(
                _k.punch_step_kernel, ny * nx, [kd, d, self.mask, wp.float64(alpha)], [x, res]
            )
            rr_new, k = red.read((False, False))
            if math.sqrt(rr_new / n_set) < rtol:
                ok = True
                break
            wp.launch(
                _k.punch_direction_kernel,
                dim=self.shape,
                inputs=[res, self.mask, wp.float64(rr_new / rr)],
                outputs=[d],
                device=dev,
            )
            rr = rr_new
        return k, it, ok
