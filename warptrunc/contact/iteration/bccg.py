# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Preconditioned bound-constrained conjugate gradients (``SolverSettings.algorithm="bccg"``).

The contact problem at a fixed approach is the bound-constrained quadratic programme
min ½·q·K·q − q·(h + offset) over 0 ≤ q ≤ H·dx·dy (H = inf: elastic), with gradient the gap
g = K·q − h − offset. Polonsky & Keer's CG (:mod:`warptrunc.contact.solver`, the default
``"pk"``) needs O(√N) iterations on a contact of N pixels: K is a ``1/|k|`` operator, its condition
number on a contact set d pixels across grows as d, and under a flat punch close to complete
contact (the paper's 502.6 µm punch is 5147 pixels across at its pixel size) that means hundreds
to a thousand iterations per load. This solver follows Vollebregt (J. Optim. Theory Appl. 162,
931 (2014); J. Comput. Phys. 257, 333 (2014)):

* **Free set** (the variables the CG moves): 0 < q < H·dx·dy, plus the pixels at a bound whose
  gradient points into the box (q = 0 penetrating, g < 0; q at the cap with an open gap, g > 0).
  Pixels enter the set as soon as they penetrate, instead of one restart at a time.
* **Preconditioner** (while the free set covers more than ``settings.precondition_above`` of
  the map; by default always on maps of at least ``PRECONDITION_LARGE`` pixels, else from
  ``PRECONDITION_ABOVE``; else z = c·g): z = c·K⁻¹·(c·g), c the free set, with K⁻¹ the
  inverse of the half-space's circulant convolution (the spectrum 1/W on the padded grid:
  ``SPECTRUM_INVERSE``, one more convolution per iteration). On a fixed contact set it makes
  the CG iterations nearly independent of the grid (prototype, D = 2.5 WM map under a punch at
  81 % contact: 19, 21, 23, 24 iterations at 128², 256², 512², 1024² against 46, 62, 80, 108
  for plain CG).
* **Truncation, no restart**: after the step the forces are projected onto [0, H·dx·dy] and the
  CG continues with the Polak–Ribière β = max(0, r·(z − z_old)/(r_old·z_old)).
* **Load control** (elastic only; with a cap the approach is found by the secant of
  :mod:`warptrunc.contact.iteration.plastic`): the rigid offset moves so that the mean gap over the free
  set is zero, z is made mean-free on the set, and the forces are scaled to the load after each
  step (as in the default solver). The solve starts from the last approach or, after Barber's
  stiffness K (:meth:`~warptrunc.contact.ContactSolver.punch_stiffness`), from the approach it
  predicts, δ₀ + (F − F₀)/K (a lower bound on loading, since K is the unloading slope).

Displacements stay exact: u ← u − τ·K·t, plus K·Δq for the forces the projection changed, by
direct summation over the influence table when they are at most ``direct_max`` pixels (as in
the default solver), else u = K·q afresh (one more convolution); afresh every ``refresh``
iterations too. Stopping: the default solver's
criterion (rms and max gap over 0 < q < cap, penetration at zero force, open gaps at the cap,
the largest change of u below ``pentol``; the largest projected force below ``forcetol``; the
total force steady or at the target) tested on the state at the top of each iteration.
"""

from __future__ import annotations

import math
from typing import Any

import warp as wp

from ...kernels.contact import bccg as _kb
from ...kernels.contact import cg as _k
from ...kernels.contact import spectral as _kr

__all__ = ["BCCGSolves"]

PRECONDITION_LARGE = 1024 * 1024
"""Under the default ``SolverSettings.precondition_above=None``, a map of at least this many
pixels applies the preconditioner always, a smaller one while the free set covers more than
``PRECONDITION_ABOVE`` of it. The plain CG's iterations grow with the contact's width in
pixels, the preconditioned one's hardly: on D = 2.5 WM maps at 0.2·R_t (0.01–1 % contact;
NVIDIA H100, float32, pentol = 10⁻⁴·rms) always preconditioning took the cold iterations from
27 → 51 to 14 → 19 between 2048² and 16384² on a fixed-content family, and the warm solve at
16384² from 3.4 to 1.5 s; on the CPU it is faster at 1024², slower at 512² and below
(guide/performance.md). Under a punch (:func:`warptrunc.indent.cycles.make_solver`) the
default is ``PRECONDITION_ABOVE`` at every size: on one placement of the paper's punches on
GB300s (10240² over 1 mm, H = ∞) always preconditioning took 1678 convolutions to 2482."""

PRECONDITION_ABOVE = 0.02
"""The free-set fraction (dimensionless) above which smaller maps apply the preconditioner (on
the paper's punches at 512², Ps and GB300s, H = ∞ and 1 GPa, ten cycles, this rule took 5488
convolutions to 4606)."""

_HUGE = 1e300  # the "cap" of an elastic solve (N)


class BCCGSolves:
    """The preconditioned BCCG solve of :class:`~warptrunc.contact.ContactSolver` (a base class
    holding methods only; the solver's maps and settings are its own)."""

    def _precondition_above(self, *, barber: bool = False) -> float:
        """The free-set (or, for Barber's solve, ``barber``, contact-set) fraction above which
        the preconditioner applies: the settings', or by the default rule of
        ``PRECONDITION_LARGE`` (Barber's solve: ``PRECONDITION_ABOVE`` at every size, measured:
        always preconditioned it is 1.3× slower on the W_c = 2 px map at 16384², 2× faster on
        the fixed-content one; guide/performance.md)."""
        given = self.settings.precondition_above
        if given is not None:
            return float(given)
        large = self.shape[0] * self.shape[1] >= PRECONDITION_LARGE
        return 0.0 if large and not barber else PRECONDITION_ABOVE

    def _bccg_maps(self) -> tuple[Any, Any]:
        """The residual map (a transform input) and the last preconditioned residual (the
        solver's q_lin map, free while this solver runs)."""
        if getattr(self, "_r_buf", None) is None:
            self._r_buf, _ = self.hs.map_buffer()
        return self._r_buf, self.lin

    def _scale_to_load(self, load: float, total: float) -> bool:
        """Scale q and u (= K·q) to the ``load`` (N) from their ``total`` (N); without any force,
        spread the load evenly (u is then stale). Returns whether u is still K·q."""
        if total > 0.0:
            wp.launch(
                _kb.scale_state_kernel,
                dim=self.shape,
                inputs=[wp.float64(load / total)],
                outputs=[self.q, self.u],
                device=self.device,
            )
            return True
        self.mask.fill_(1)
        n_map = self.shape[0] * self.shape[1]
        wp.launch(
            _k.fill_map_kernel,
            dim=self.shape,
            inputs=[self.mask, wp.float64(load / n_map)],
            outputs=[self.q],
            device=self.device,
        )
        return False

    def _exact_u(self) -> float:
        """u ← K·q by a transform afresh (one convolution); returns the largest change of u (m;
        a synchronisation point)."""
        kq = self.hs.apply(self.q_buf)
        self.hs.reduction.launch(
            _kb.bccg_exact_kernel, self.shape[0] * self.shape[1], [kq], [self.u]
        )
        del kq
        return float(self.hs.reduction.read((True,))[0])

    def _bccg_start(self, offset: float, load: float | None, hf: float) -> float:
        """The start of a BCCG solve (both loops): the warm start at ``offset`` (m) projected
        onto the box [0, ``hf``] (N per pixel), scaled to ``load`` (N) in load control, then
        u = K·q afresh; returns Σ q (N; four convolutions in all)."""
        self._warm_start(offset)  # then projected onto the box
        wp.launch(
            _kb.clamp_force_kernel,
            dim=self.shape,
            inputs=[wp.float64(hf)],
            outputs=[self.q],
            device=self.device,
        )
        total = float(self._sums(offset)[3])  # Σ q (N)
        if load is not None:
            self._scale_to_load(load, total)
            total = float(load)
        self._exact_u()
        return total

    def _solve_bccg(self, offset: float, load: float | None, cap: float | None) -> dict[str, Any]:
        """One solve at ``offset`` (m; the start in load control) or at ``load`` (N), with the
        force cap ``cap`` (N per pixel; None: elastic). Returns the info dict of the default
        solver's solves. With ``settings.loop="device"`` or ``"graph"`` the iteration is
        :mod:`warptrunc.contact.iteration.bccg_device`'s, one read-back per iteration."""
        if getattr(self.settings, "loop", "host") in ("device", "graph"):
            return self._solve_bccg_device(offset, load, cap)
        red, hs, dev = self.hs.reduction, self.hs, self.device
        n_map = self.shape[0] * self.shape[1]
        inv_n = 1.0 / hs.n_total
        hf = _HUGE if cap is None else float(cap)
        load_control = load is not None
        r_buf, z_old = self._bccg_maps()
        pc_above = self._precondition_above()
        periodic = int(self.substrate == "periodic")
        total = self._bccg_start(offset, load, hf)
        n_transforms = 4
        self.t.zero_()
        z_old.zero_()
        rz_old = None
        last_pc = None
        du = None  # largest change of u in the last step (m); none yet
        viol = 0.0
        last: dict[str, float] = {}  # the previous iteration's total and height
        info: dict[str, Any] = {"converged": False}
        for it in range(1, self.maxiter + 1):
            set_offset = offset
            if load_control:
                red.launch(
                    _kb.bccg_sums_kernel,
                    n_map,
                    [self.q, self.u, self.h, wp.float64(offset), wp.float64(hf)],
                    [],
                )
                n_f, s_g = red.read((False, False))  # sync point
                if n_f > 0:
                    offset = offset + s_g / n_f
            red.launch(
                _kb.bccg_residual_kernel,
                n_map,
                [
                    self.q,
                    self.u,
                    self.h,
                    wp.float64(set_offset),
                    wp.float64(offset),
                    wp.float64(hf),
                ],
                [r_buf, self.mask],
            )
            (n_f, s_r, n_cg, s_gg, g_max, pen, open_cap, n_c, s_gap) = red.read(
                (False, False, False, False, True, True, True, False, False)
            )  # sync point
            # convergence of the state reached by the last step (module docstring)
            sums = (n_f, s_r, n_cg, s_gg, g_max, pen, open_cap, n_c, s_gap)
            info, stop = self._bccg_stop(
                sums, offset, total, load, du, viol, it, n_transforms, last
            )
            if stop:
                break
            # preconditioned residual z = c·K⁻¹·r (on a large free set; else z = r)
            use_pc = n_f > pc_above * n_map
            if use_pc != last_pc:
                rz_old = None  # another preconditioner: the CG restarts
            last_pc = use_pc
            if use_pc:
                z = hs.apply(r_buf, inverse=True)
                n_transforms += 2
            else:
                z = r_buf
            red.launch(_kb.bccg_dot_kernel, n_map, [z, r_buf, z_old, self.mask], [])
            s_z, rz, rzo = red.read((False, False, False))  # sync point
            mean = s_z / n_f if load_control else 0.0
            rz -= mean * s_r
            beta = 0.0  # Polak–Ribière (z_old is mean-free on its own set; r·z_old as it is)
            if rz_old is not None and rz_old > 0.0:
                beta = max(0.0, (rz - rzo) / rz_old)
            rz_old = rz
            red.launch(
                _kb.bccg_direction_kernel,
                n_map,
                [z, wp.float64(mean), wp.float64(beta), self.mask, r_buf],
                [self.t, z_old],
            )
            del z
            spec = hs.work
            hs.forward(self.t_buf, spec)
            hs.spectral(_kr.SPECTRUM_APPLY, spec, col=1)
            wp.launch(
                _k.step_length_kernel,
                dim=1,
                inputs=[red.fold((False, False)), wp.float64(n_f), wp.float64(inv_n)],
                outputs=[self.tau],
                device=dev,
            )
            kt = hs.inverse(spec)
            n_transforms += 2
            red.launch(
                _kb.bccg_update_kernel,
                n_map,
                [kt, self.tau, wp.float64(hf), self.t],
                [self.q, self.u, r_buf, self.mask, self.lane_count],
            )
            del kt
            n_proj, viol, total, du = red.read((False, True, False, True))  # sync point
            n_proj = int(n_proj)
            exact = it % self.refresh == 0 or n_proj > self.direct_max
            if n_proj > 0 and not exact:
                # the projection's few corrections by direct summation (r is free until the
                # next residual: it holds the projected pixels' forces before the projection)
                self._compact_changes(r_buf, 1.0)
                red.launch(
                    _kb.bccg_correct_kernel,
                    n_map,
                    [hs.table, periodic, self.change_index, self.change_value, n_proj],
                    [self.u],
                )
                du += float(red.read((True,))[0])  # sync point
            if load_control:
                if not self._scale_to_load(load, total):
                    exact = True  # u no longer K·q: transform afresh
                total = float(load)
            if exact:
                du = max(du, self._exact_u())
                n_transforms += 2
        self.offset = offset
        return info

    def _punch_pcg(self, x: Any, res: Any, n_set: float, rtol: float) -> tuple[float, int, bool]:
        """Barber's punch (K·x = 1 m on the contact set, ``mask``) by CG preconditioned with
        c·K⁻¹·c, from x = 0 and res = 1 m on the set; k = Σx (N/m). Returns (k, iterations,
        converged)."""
        red, hs = self.hs.reduction, self.hs
        n_map = self.shape[0] * self.shape[1]
        if n_set <= self._precondition_above(barber=True) * n_map:
            return self._punch_cg(x, res, n_set, rtol)  # a small set: plain CG
        scratch, _ = self._bccg_maps()  # the last z (unused here, a kernel output)
        d = self.t

        def direction(rz_old: float | None) -> float:
            """z = c·K⁻¹·c·res, d ← z + β·d with β = rz/rz_old (0 at the start); returns
            rz = Σ res·z."""
            z = hs.apply(res, inverse=True)
            red.launch(_kb.bccg_dot_kernel, n_map, [z, res, d, self.mask], [])
            rz = float(red.read((False, False))[1])  # sync point
            beta = 0.0 if rz_old is None else rz / rz_old
            red.launch(
                _kb.bccg_direction_kernel,
                n_map,
                [z, wp.float64(0.0), wp.float64(beta), self.mask, res],
                [d, scratch],
            )
            return rz

        rz = direction(None)
        k, it, ok = 0.0, 0, False
        for it in range(1, self.maxiter + 1):  # noqa: B007
            kd = hs.apply(self.t_buf, energy_column=0)
            d_k_d = red.read((False,))[0] / hs.n_total  # sync point
            if not d_k_d > 0.0:
                break
            alpha = rz / d_k_d
            red.launch(_k.punch_step_kernel, n_map, [kd, d, self.mask, wp.float64(alpha)], [x, res])
            del kd
            rr_new, k = red.read((False, False))  # sync point
            if math.sqrt(rr_new / n_set) < rtol:
                ok = True
                break
            rz = direction(rz)
        return float(k), it, ok
