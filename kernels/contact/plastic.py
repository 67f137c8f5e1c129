# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Constrained conjugate gradients with a pressure cap (elastic–perfectly-plastic contact):
the bound-constrained projection 0 ≤ q ≤ H·dx·dy and the plastic update of the heights.

Launched by ``warptrunc.contact.iteration.plastic`` (``ContactSolver`` with a finite hardness). Array
layouts, ``mask`` bits, the lane grid and the partials array ``part`` are those of
``kernels/contact/cg.py``; ``hf`` is the force cap H·dx·dy (N). The CG set is 0 < q < hf (pixels at
the cap have left it, as pixels at zero force have); the gap is ``g = u − h − offset`` (m) with
``h`` the current (plastically lowered) heights. Float32 and float64 instances of every kernel
(``wp.overload``); reductions are float64.
"""

from typing import Any

import warp as wp

from ..lanes import declare_overloads, lane_next, lane_start
from .cg import (
    advance_at,
    direction_at,
    fold_step,
    stepped_force,
    store_advance_partials,
    store_force,
    store_update_partials,
)

wp.set_module_options({"enable_backward": False})


@wp.kernel
def capped_sums_kernel(
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    hf: wp.float64,
    stride: int,
    chunk: int,
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map, start of a solve: part[i] = [n(0 < q < hf), Σ c·g, Σ c·g², Σ q]."""
    lane = wp.tid()
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    n_c = wp.float64(0.0)
    s_g = wp.float64(0.0)
    s_gg = wp.float64(0.0)
    s_q = wp.float64(0.0)
    cap = q.dtype(hf)
    while i < n:
        qv = q[iy, ix]
        s_q += wp.float64(qv)
        if qv > q.dtype(0.0) and qv < cap:
            g = wp.float64(u[iy, ix]) - wp.float64(h[iy, ix]) - offset
            n_c += wp.float64(1.0)
            s_g += g
            s_gg += g * g
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = n_c
    part[lane, 1] = s_g
    part[lane, 2] = s_gg
    part[lane, 3] = s_q


@wp.kernel
def capped_direction_kernel(
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    beta: wp.float64,
    hf: wp.float64,
    stride: int,
    chunk: int,
    t: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: CG set c = 0 < q < hf, t = c·(g + β·t), mask = c; part[i] = [Σ c·g·t]."""
    lane = wp.tid()
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    s_gt = wp.float64(0.0)
    cap = q.dtype(hf)
    while i < n:
        qv = q[iy, ix]
        in_set = qv > q.dtype(0.0) and qv < cap
        s_gt = direction_at(in_set, u, h, offset, beta, iy, ix, t, mask, s_gt)
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = s_gt


@wp.kernel
def capped_step_kernel(
    sums: wp.array2d(dtype=wp.float64),
    n_c: wp.float64,
    inv_n: wp.float64,
    fallback: wp.float64,
    tau: wp.array[wp.float64],
):
    """One thread: τ = Σ c·g·t / (t·K·t) (PK Eq. 15) from the folded columns 0 and 1; without a
    CG set or curvature τ = ``fallback`` (m⁻¹·N: the inverse self-influence of a pixel), so that
    pixels at the cap or at zero force can still change sides."""
    tau[0] = fold_step(sums, n_c, inv_n, fallback)


@wp.kernel
def capped_update_kernel(
    t: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    tau_arr: wp.array[wp.float64],
    hf: wp.float64,
    stride: int,
    chunk: int,
    q: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    lin: wp.array2d(dtype=Any),
    lane_count: wp.array[wp.int32],
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: q_lin = q − τ·c·t, projected on [0, hf]. Pixels at zero force that
    penetrate (g < 0) get q = min(−τ·g, hf/2); pixels at the cap whose gap is open (g > 0) get
    q = max(hf − τ·g, hf/2) (both: the active set changes). The bound hf/2 puts them into the
    CG set of the next iteration instead of across the whole interval, so that thousands of
    pixels changing sides at once (a cold start deep into plastic contact) do not flip between
    0 and hf with a step τ fitted to the few others. Changed pixels get mask bit 2 and
    lin = q_lin; lane_count[i] = their number. part[i, 2:8] = [n changing sides, n clamped
    (tensile or above the cap), max(tensile force, force above the cap) before the projection,
    Σ q, τ (lane 0), n changed]."""
    lane = wp.tid()
    tau = tau_arr[0]
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    n_nc = wp.float64(0.0)
    n_clamp = wp.float64(0.0)
    max_viol = wp.float64(0.0)
    total = wp.float64(0.0)
    zero = q.dtype(0.0)
    cap = q.dtype(hf)
    half = q.dtype(wp.float64(0.5) * hf)
    count = int(0)
    while i < n:
        m, qv = stepped_force(q, t, mask, tau, iy, ix)
        q_lin = qv
        changed = False
        if qv <= zero:
            max_viol = wp.max(max_viol, -wp.float64(qv))
            if qv < zero:
                n_clamp += wp.float64(1.0)
                changed = True
            qv = zero
            g = u[iy, ix] - h[iy, ix] - h.dtype(offset)
            if g < h.dtype(0.0):
                n_nc += wp.float64(1.0)
                changed = True
                qv = wp.min(-q.dtype(tau) * g, half)
        elif qv >= cap:
            max_viol = wp.max(max_viol, wp.float64(qv) - hf)
            if qv > cap:
                n_clamp += wp.float64(1.0)
                changed = True
            qv = cap
            g = u[iy, ix] - h[iy, ix] - h.dtype(offset)
            if g > h.dtype(0.0):
                n_nc += wp.float64(1.0)
                changed = True
                qv = wp.max(cap - q.dtype(tau) * g, half)
        count += store_force(changed, m, q_lin, qv, iy, ix, q, mask, lin)
        total += wp.float64(qv)
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    store_update_partials(lane, n_nc, n_clamp, max_viol, total, tau, count, part, lane_count)


@wp.kernel
def capped_advance_kernel(
    r: wp.array2d(dtype=Any),
    linear: int,
    tau: wp.float64,
    table: wp.array2d(dtype=Any),
    periodic: int,
    index: wp.array[wp.int32],
    value: wp.array[wp.float64],
    n_changes: int,
    q: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    hf: wp.float64,
    mask: wp.array2d(dtype=wp.uint8),
    stride: int,
    chunk: int,
    u: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: the new displacement, as ``advance_kernel`` of ``kernels/contact/cg.py``
    (``linear == 0``: u ← r = K·q; else u ← u − τ·r + the listed corrections). part[i] =
    [max |Δu|, n(0 < q < hf), Σ c·g, Σ c·g², max(penetration over the previous CG set, open gap
    at the cap), Σ g, Σ q] with c = 0 < q < hf and the new u."""
    lane = wp.tid()
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    du_max = wp.float64(0.0)
    n_c = wp.float64(0.0)
    s_g = wp.float64(0.0)
    s_gg = wp.float64(0.0)
    viol = wp.float64(0.0)
    s_gap = wp.float64(0.0)
    s_q = wp.float64(0.0)
    cap = q.dtype(hf)
    one = wp.float64(1.0)
    while i < n:
        du = advance_at(
            r, linear, tau, one, table, periodic, index, value, n_changes, iy, ix, nx, u
        )
        du_max = wp.max(du_max, du)
        g = wp.float64(u[iy, ix]) - wp.float64(h[iy, ix]) - offset
        s_gap += g
        qv = q[iy, ix]
        s_q += wp.float64(qv)
        if qv > q.dtype(0.0) and qv < cap:
            n_c += wp.float64(1.0)
            s_g += g
            s_gg += g * g
        if qv >= cap:
            viol = wp.max(viol, g)
        if (int(mask[iy, ix]) & 1) != 0:
            viol = wp.max(viol, -g)
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    store_advance_partials(lane, du_max, n_c, s_g, s_gg, viol, s_gap, s_q, part)


@wp.kernel
def plastic_flow_kernel(
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    offset: wp.float64,
    hf: wp.float64,
    apply: int,
    stride: int,
    chunk: int,
    h: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map, after a converged solve: where q ≥ hf and the flat penetrates
    (g < 0) the heights flow down to close the gap, h ← u − offset (when ``apply``). part[i] =
    [n(q > 0), n(q ≥ hf), Σ (h_old − h_new) (m, the stored change)]."""
    lane = wp.tid()
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    n_c = wp.float64(0.0)
    n_p = wp.float64(0.0)
    s_dw = wp.float64(0.0)
    cap = q.dtype(hf)
    while i < n:
        qv = q[iy, ix]
        if qv > q.dtype(0.0):
            n_c += wp.float64(1.0)
        if qv >= cap:
            n_p += wp.float64(1.0)
            if apply != 0:
                ho = h[iy, ix]
                hn = h.dtype(wp.float64(u[iy, ix]) - offset)
                if hn < ho:
                    h[iy, ix] = hn
                    s_dw += wp.float64(ho) - wp.float64(hn)
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = n_c
    part[lane, 1] = n_p
    part[lane, 2] = s_dw


declare_overloads(
    (
        capped_sums_kernel,
        capped_direction_kernel,
        capped_update_kernel,
        capped_advance_kernel,
        plastic_flow_kernel,
    )
)
