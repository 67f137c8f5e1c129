# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Polonsky & Keer's constrained CG (``SolverSettings.algorithm="pk"``), the elastic loop of
:class:`~warptrunc.contact.ContactSolver`: ContactMechanics' iteration, one convolution per
iteration while the projection changes at most ``direct_max`` forces (the module docstring of
:mod:`warptrunc.contact.solver` describes it)."""

from __future__ import annotations

import math
from typing import Any

import warp as wp

from ...kernels.contact import cg as _k
from ...kernels.contact import spectral as _kr

__all__ = ["PKSolves"]


class PKSolves:
    """The Polonsky–Keer solve of :class:`~warptrunc.contact.ContactSolver` (a base class
    holding methods only; the solver's maps and settings are its own)."""

    def _compact_changes(self, before: Any, scale: float) -> None:
        """List the pixels whose force the last projection changed into ``change_index`` and
        ``change_value`` (the change in N, in a fixed order), for the direct summation of their
        displacements: q against ``before`` (the forces before the projection, where it acted)
        times ``scale``. Used by the PK, capped and BCCG loops."""
        red = self.hs.reduction
        wp.utils.array_scan(self.lane_count, self.lane_offset, inclusive=False)
        wp.launch(
            _k.compact_changes_kernel,
            dim=red.lanes,
            inputs=[
                self.q,
                before,
                self.mask,
                wp.float64(scale),
                self.lane_offset,
                *red.geometry(self.shape[0] * self.shape[1]),
            ],
            outputs=[self.change_index, self.change_value],
            device=self.device,
        )

    def _exact_or_listed(self, spec: Any, exact: bool, n_changed: int, scale: float) -> int:
        """After a step of the PK or capped loop: ``exact`` puts W·Q̂/N of the forces afresh
        into ``spec`` (u = K·q after the inverse transform), else the projection's changes, if
        any, are listed (:meth:`_compact_changes`, against ``lin``) and ``spec`` keeps K·t.
        Returns the transforms run (1 or 0)."""
        if exact:
            self.hs.forward(self.q_buf, spec)
            self.hs.spectral(_kr.SPECTRUM_APPLY, spec)
            return 1
        if n_changed > 0:
            self._compact_changes(self.lin, scale)
        return 0

    def _solve_pk(self, depth: float | None, load: float | None) -> dict[str, Any]:
        """One solve at approach ``depth`` (m) or ``load`` (N), warm-started; the info dict."""
        load_control = load is not None
        if load_control:
            offset = 0.0  # as ContactMechanics: the first gap is measured from offset 0
        else:
            offset = float(depth) - self.h_max
        red, hs, dev = self.hs.reduction, self.hs, self.device
        n_map = self.shape[0] * self.shape[1]
        inv_n = 1.0 / hs.n_total
        self._warm_start(offset)
        n_transforms = 2
        n_c, s_g, s_gg, _ = self._sums(offset)
        self.t.zero_()
        g_old, cg = 1.0, False
        last_total = last_height = None
        info: dict[str, Any] = {"converged": False}
        update_cols = (False, False, False, False, True, False, False, False)
        advance_cols = (True, False, False, False, True, False, False)
        periodic = int(self.substrate == "periodic")
        for it in range(1, self.maxiter + 1):
            if load_control:  # offset: mean gap over the CG set is zero (ContactMechanics)
                new = offset + s_g / n_c if n_c > 0 else 0.0
                d = offset - new
                s_gg, s_g, offset = s_gg + 2 * d * s_g + d * d * n_c, s_g + d * n_c, new
            g, a_cg = s_gg, n_c
            beta = g / g_old if (cg and g_old > 0) else 0.0
            red.launch(
                _k.cg_direction_kernel,
                n_map,
                [self.q, self.u, self.h, wp.float64(offset), wp.float64(beta)],
                [self.t, self.mask],
            )
            spec = hs.work
            hs.forward(self.t_buf, spec)  # T̂
            # N·t·K·t by Parseval, and T̂ ← W·T̂/N in the same pass (not yet known whether K·t
            # is needed: a transform of q afresh overwrites it)
            hs.spectral(_kr.SPECTRUM_APPLY, spec, col=1)
            wp.launch(
                _k.step_length_kernel,
                dim=1,
                inputs=[red.fold((False, False)), wp.float64(n_c), wp.float64(inv_n)],
                outputs=[self.tau],
                device=dev,
            )
            red.launch(
                _k.update_force_kernel,
                n_map,
                [self.t, self.u, self.h, wp.float64(offset), self.tau, int(load_control)],
                [self.q, self.mask, self.lin, self.lane_count],
            )
            _, t_k_t, n_nc, n_zero, max_tens, total, tau, n_changed = red.read(
                update_cols
            )  # sync point
            n_changed = int(n_changed)
            n_transforms += 1
            if n_c > 0 and not t_k_t > 0.0:
                g = 0.0
            scale = 1.0
            exact = it == 1 or it % self.refresh == 0 or n_changed > self.direct_max
            if load_control:
                if total != 0.0:
                    scale = load / total
                    wp.launch(
                        _k.rescale_force_kernel,
                        dim=self.shape,
                        inputs=[
                            self.u,
                            self.h,
                            wp.float64(offset),
                            wp.float64(tau),
                            wp.float64(scale),
                            self.mask,
                        ],
                        outputs=[self.q],
                        device=dev,
                    )
                else:
                    self.mask.fill_(1)
                    wp.launch(
                        _k.fill_map_kernel,
                        dim=self.shape,
                        inputs=[self.mask, wp.float64(load / n_map)],
                        outputs=[self.q],
                        device=dev,
                    )
                    exact = True
            # u = K·q afresh, or the projection's few corrections listed in a fixed order
            n_transforms += self._exact_or_listed(spec, exact, n_changed, scale)
            r = hs.inverse(spec)  # K·q (exact) or K·t (linear)
            n_transforms += 1
            red.launch(
                _k.advance_kernel,
                n_map,
                [
                    r,
                    int(not exact),
                    wp.float64(tau),
                    wp.float64(scale),
                    hs.table,
                    periodic,
                    self.change_index,
                    self.change_value,
                    0 if exact else n_changed,
                    self.q,
                    self.h,
                    wp.float64(offset),
                    self.mask,
                ],
                [self.u],
            )
            du, n_c, s_g, s_gg, pen, s_gap, total = red.read(advance_cols)  # sync point
            del r
            g_old = g
            cg = n_nc == 0 and n_zero == 0
            rms_pen = math.sqrt(
                max(g, 0.0) / a_cg if a_cg > 0 else max(g, 0.0)
            )  # g ≥ 0 up to round-off
            ok = True
            if load_control:
                ok = total != 0 and abs((total - load) / total) < self.thermotol
                height = self.h_max + offset
                if last_height is not None:
                    ok = ok and self._steady(height, last_height)
                last_height = height
            elif last_total is not None:
                ok = self._steady(total, last_total)
            last_total = total
            res = max(rms_pen, pen, du)
            ok = ok and rms_pen < self.pentol and pen < self.pentol and du < self.pentol
            ok = ok and max_tens < self.forcetol
            info = self._iteration_info(
                offset, total, s_gap / n_map, it, n_transforms, res, max_tens, ok, n_contact=n_c
            )
            if ok:
                break
        self.offset = offset
        return info
