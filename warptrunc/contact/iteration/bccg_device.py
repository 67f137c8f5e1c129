# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The BCCG solve with one read-back per iteration (``SolverSettings.loop="device"`` or ``"graph"``).

The iteration of :mod:`warptrunc.contact.iteration.bccg` reads a few numbers back after each of its
reductions: the mean gap of load control, then the residual's sums, then r·z for Polak–Ribière's
β, then the step's projected count, total force and change of u (and the direct correction's
change). Each read drains the device's queue, so on a GPU the device waits while the host
launches the next kernels, four to five times per iteration. Here those scalars are folded on the
device by one-thread kernels (``kernels/contact/bccg_device.py``) into the solve's scalar array and read
by the next kernels from there; the host reads the array once per iteration, after the residual,
and takes there, with the code of the host loop, every decision that chooses what to launch next:
convergence, the preconditioner (its restart), and a transform afresh.

Two decisions of the host loop come one iteration late, by construction identical in effect:

* more projected pixels than the direct correction's list (``direct_max``): the device skips the
  correction and flags u as stale; at the next read the host transforms afresh (u = K·q, as the
  host loop does right after the step) and computes the residual again;
* load control with no force left (Σ q ≤ 0): the device does not scale and flags it; at the next
  read the host spreads the load evenly and transforms afresh, as the host loop does.

The answers equal the host loop's at the same settings but for the order of the float64 sums of
a few hundred partials (``tests/test_device_loop.py``: loads within 10⁻¹⁰ relative, the same
contact set). ``loop="graph"`` captures the launches of a steady iteration (its step and the
next iteration's top: no host decision between them) in a CUDA graph on first use, one per
(preconditioned, load control, cap), and replays it; the restarts and the scheduled transforms
afresh are launched. Measured on an NVIDIA H200 (guide/performance.md, "One read-back per
iteration"): the read-backs saved are about what the one-thread folds cost on the device (each
folds 256 rows serially, about 0.12 ms), so the graph is 8 % faster than the host loop at 2048²
and 1-3 % slower from 8192², and the host loop stays the default.
"""

from __future__ import annotations

import warnings
from typing import Any

import warp as wp

from ...kernels.contact import bccg as _kb
from ...kernels.contact import bccg_device as _kl
from ...kernels.contact import spectral as _kr

__all__ = ["DeviceLoopSolves"]

_HUGE = 1e300  # the "cap" of an elastic solve (N)
_RES = int(_kl.S_RES)


class DeviceLoopSolves:
    """The device-folded BCCG solve of :class:`~warptrunc.contact.ContactSolver` (a base class
    holding methods only; the maps, settings and the host loop's helpers are the solver's)."""

    def _loop_scalars(self) -> wp.array:
        """The solve's scalar array (float64, ``kernels.contact.bccg_device.S_SIZE``), made once."""
        if getattr(self, "_s_loop", None) is None:
            self._s_loop = wp.zeros(_kl.S_SIZE, dtype=wp.float64, device=self.device)
        return self._s_loop

    def _loop_top(self, s: wp.array, hf: float, load_control: bool) -> None:
        """The top of an iteration (launches only): (load control) move the offset by the mean
        free gap, then the residual and its sums into the scalar array."""
        red, n_map = self.hs.reduction, self.shape[0] * self.shape[1]
        if load_control:
            red.launch(_kl.sums_loop_kernel, n_map, [self.q, self.u, self.h, s, wp.float64(hf)], [])
            wp.launch(
                _kl.loop_offset_kernel,
                dim=1,
                inputs=[red.fold((False, False))],
                outputs=[s],
                device=self.device,
            )
        r_buf, _ = self._bccg_maps()
        red.launch(
            _kl.residual_loop_kernel,
            n_map,
            [self.q, self.u, self.h, s, wp.float64(hf)],
            [r_buf, self.mask],
        )
        flags = (False, False, False, False, True, True, True, False, False)
        wp.launch(
            _kl.loop_residual_kernel,
            dim=1,
            inputs=[red.fold(flags)],
            outputs=[s],
            device=self.device,
        )

    def _loop_step(
        self,
        s: wp.array,
        hf: float,
        load_control: bool,
        use_pc: bool,
        restart: bool,
        refresh_now: bool,
    ) -> None:
        """The rest of an iteration (launches only): the (preconditioned) direction, the step
        and its projection, the direct correction of a few projected forces, the scale to the
        load, and u afresh when ``refresh_now``."""
        red, hs, dev = self.hs.reduction, self.hs, self.device
        n_map = self.shape[0] * self.shape[1]
        r_buf, z_old = self._bccg_maps()
        lc = int(load_control)
        z = hs.apply(r_buf, inverse=True) if use_pc else r_buf
        red.launch(_kb.bccg_dot_kernel, n_map, [z, r_buf, z_old, self.mask], [])
        wp.launch(
            _kl.loop_dot_kernel,
            dim=1,
            inputs=[red.fold((False, False, False)), lc, int(restart)],
            outputs=[s],
            device=dev,
        )
        red.launch(_kl.direction_loop_kernel, n_map, [z, s, self.mask, r_buf], [self.t, z_old])
        del z
        spec = hs.work
        hs.forward(self.t_buf, spec)
        hs.spectral(_kr.SPECTRUM_APPLY, spec, col=1)
        wp.launch(
            _kl.step_length_loop_kernel,
            dim=1,
            inputs=[red.fold((False, False)), s, wp.float64(1.0 / hs.n_total)],
            outputs=[self.tau],
            device=dev,
        )
        kt = hs.inverse(spec)
        red.launch(
            _kb.bccg_update_kernel,
            n_map,
            [kt, self.tau, wp.float64(hf), self.t],
            [self.q, self.u, r_buf, self.mask, self.lane_count],
        )
        del kt
        wp.launch(
            _kl.loop_update_kernel,
            dim=1,
            inputs=[red.fold((False, True, False, True)), lc],
            outputs=[s],
            device=dev,
        )
        if not refresh_now:
            # the projection's few corrections by direct summation, on the device's count
            cap_list = int(self.direct_max)
            wp.utils.array_scan(self.lane_count, self.lane_offset, inclusive=False)
            wp.launch(
                _kl.compact_gated_kernel,
                dim=red.lanes,
                inputs=[
                    self.q,
                    r_buf,
                    self.mask,
                    self.lane_offset,
                    s,
                    cap_list,
                    *red.geometry(n_map),
                ],
                outputs=[self.change_index, self.change_value],
                device=dev,
            )
            red.launch(
                _kl.correct_gated_kernel,
                n_map,
                [
                    hs.table,
                    int(self.substrate == "periodic"),
                    self.change_index,
                    self.change_value,
                    s,
                    cap_list,
                ],
                [self.u],
            )
            wp.launch(
                _kl.loop_correct_kernel,
                dim=1,
                inputs=[red.fold((True,)), cap_list],
                outputs=[s],
                device=dev,
            )
        if load_control:
            wp.launch(
                _kl.scale_gated_kernel,
                dim=self.shape,
                inputs=[s],
                outputs=[self.q, self.u],
                device=dev,
            )
        if refresh_now:
            # u afresh on schedule (the flag of a load left without force is handled at the
            # next read, which transforms afresh once more)
            kq = hs.apply(self.q_buf)
            red.launch(_kb.bccg_exact_kernel, n_map, [kq], [self.u])
            del kq
            wp.launch(
                _kl.loop_exact_kernel, dim=1, inputs=[red.fold((True,))], outputs=[s], device=dev
            )

    def _loop_iteration(self, key: tuple, launch) -> None:
        """Run ``launch`` (the launches of one iteration's step and the next top): replayed
        from a CUDA graph captured on first use (``settings.loop="graph"`` on a CUDA device),
        else launched. A capture that fails is recorded in ``graph_error`` and the solver
        launches from then on."""
        if self.settings.loop != "graph" or not self.device.is_cuda or self.graph_error():
            launch()
            return
        graphs = self.__dict__.setdefault("_loop_graphs", {})
        graph = graphs.get(key)
        if graph is None:
            launch()  # once uncaptured: the kernels' modules are loaded before the capture
            try:
                with wp.ScopedCapture(device=self.device, force_module_load=False) as cap:
                    launch()
            except Exception as exc:
                # the iteration ran uncaptured above; what the capture recorded never ran
                self._graph_error = f"{type(exc).__name__}: {exc}"
                warnings.warn(
                    f"contact solver: CUDA graph capture failed ({self._graph_error}); "
                    "the iterations are launched instead",
                    RuntimeWarning,
                    stacklevel=2,
                )
                return
            graphs[key] = cap.graph
            return  # the captured launches have not run: the uncaptured ones did
        wp.capture_launch(graph)

    def graph_error(self) -> str | None:
        """Why the CUDA graph of the iteration could not be captured (``loop="graph"``).

        Returns
        -------
        str or None
            The capture's error, as ``"<exception type>: <message>"``; None when the capture
            worked or was not tried (another loop, or not a CUDA device).
        """
        return getattr(self, "_graph_error", None)

    def _set_scalars(self, s: wp.array, values: dict[int, float]) -> None:
        """Write a few entries of the scalar array from the host (a small copy)."""
        host = s.numpy()
        for k, v in values.items():
            host[int(k)] = v
        s.assign(host)

    def _solve_bccg_device(
        self, offset: float, load: float | None, cap: float | None
    ) -> dict[str, Any]:
        """:meth:`~warptrunc.contact.iteration.bccg.BCCGSolves._solve_bccg` with one read-back per
        iteration (module docstring); same arguments and info dict."""
        n_map = self.shape[0] * self.shape[1]
        hf = _HUGE if cap is None else float(cap)
        load_control = load is not None
        _, z_old = self._bccg_maps()
        pc_above = self._precondition_above()
        s = self._loop_scalars()
        total = self._bccg_start(offset, load, hf)
        s.zero_()
        self._set_scalars(
            s,
            {
                _kl.S_OFF: offset,
                _kl.S_SETOFF: offset,
                _kl.S_TOTAL: total,
                _kl.S_LOAD: 0.0 if load is None else float(load),
            },
        )
        n_transforms = 4
        self.t.zero_()
        z_old.zero_()
        have_rz = False  # no direction yet (the host loop's rz_old is None)
        last_pc = None
        du = None  # largest change of u in the last step (m); none yet
        viol = 0.0
        last: dict[str, float] = {}  # the previous iteration's total and height
        info: dict[str, Any] = {"converged": False}
        self._loop_top(s, hf, load_control)
        v = s.numpy()  # sync point
        for it in range(1, self.maxiter + 1):
            top_offset = offset
            flag = int(v[_kl.S_FLAG])
            if flag and du is not None:
                # the step before projected more pixels than the list holds (1), or left no
                # force to scale to the load (2): as the host loop, u afresh after the step
                du = float(v[_kl.S_DU])
                if flag & 2:
                    self._scale_to_load(load, 0.0)
                du = max(du, self._exact_u())
                n_transforms += 2
                self._set_scalars(
                    s,
                    {
                        _kl.S_OFF: top_offset,
                        _kl.S_SETOFF: top_offset,
                        _kl.S_FLAG: 0.0,
                        _kl.S_DU: du,
                    },
                )
                self._loop_top(s, hf, load_control)
                v = s.numpy()  # sync point
            offset = float(v[_kl.S_OFF])
            if du is not None:
                du = float(v[_kl.S_DU])
                viol = float(v[_kl.S_VIOL])
                total = float(v[_kl.S_TOTAL])
            n_f = float(v[_RES])
            info, stop = self._bccg_stop(
                v[_RES : _RES + 9], offset, total, load, du, viol, it, n_transforms, last
            )
            if stop:
                break
            use_pc = n_f > pc_above * n_map
            restart = not have_rz or use_pc != last_pc
            last_pc, have_rz = use_pc, True
            refresh_now = it % self.refresh == 0

            def launch(use_pc=use_pc, restart=restart, refresh_now=refresh_now):
                self._loop_step(s, hf, load_control, use_pc, restart, refresh_now)
                self._loop_top(s, hf, load_control)

            if restart or refresh_now:
                launch()  # rare: not worth a graph
            else:
                self._loop_iteration((use_pc, load_control, hf), launch)
            n_transforms += 2 + 2 * int(use_pc) + 2 * int(refresh_now)
            du = 0.0  # a step was taken: the next read carries its change of u
            v = s.numpy()  # sync point
        self.offset = offset
        return info
