# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Preconditioned bound-constrained conjugate gradients (Vollebregt 2014): the lane kernels.

Launched by ``warptrunc.contact.iteration.bccg`` (``ContactSolver`` with ``algorithm="bccg"``). Array
layouts, the lane grid and the partials array ``part`` are those of ``kernels/contact/cg.py``;
``hf`` is the force cap H·dx·dy (N; a huge number when elastic). The gap is
``g = u − h − offset`` (m). The *free set* is the set the CG moves: 0 < q < hf, plus the bound
pixels whose gradient points into the box (q ≤ 0 with g < 0: a pixel at zero force that
penetrates; q ≥ hf with g > 0: a pixel at the cap whose gap is open). ``mask`` = 1 on it.
Float32 and float64 instances of every kernel (``wp.overload``); reductions are float64.
"""

from typing import Any

import warp as wp

from .cg import direct_sum
from ..lanes import declare_overloads, lane_next, lane_start

wp.set_module_options({"enable_backward": False})


@wp.func
def is_free(qv: wp.float64, g: wp.float64, hf: wp.float64) -> int:
    """1 if a pixel of force ``qv`` (N) and gap ``g`` (m) is in the free set, else 0."""
    free = int(0)
    if qv > wp.float64(0.0) and qv < hf:
        free = 1
    elif qv <= wp.float64(0.0) and g < wp.float64(0.0):
        free = 1
    elif qv >= hf and g > wp.float64(0.0):
        free = 1
    return free


@wp.func
def free_gap_walk(
    lane: int,
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    hf: wp.float64,
    stride: int,
    chunk: int,
    part: wp.array2d(dtype=wp.float64),
):
    """One lane of ``bccg_sums_kernel`` (shared with ``kernels/contact/bccg_device.py``)."""
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    n_f = wp.float64(0.0)
    s_g = wp.float64(0.0)
    while i < n:
        g = wp.float64(u[iy, ix]) - wp.float64(h[iy, ix]) - offset
        if is_free(wp.float64(q[iy, ix]), g, hf) != 0:
            n_f += wp.float64(1.0)
            s_g += g
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = n_f
    part[lane, 1] = s_g


@wp.kernel
def bccg_sums_kernel(
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    hf: wp.float64,
    stride: int,
    chunk: int,
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map (load control): part[i] = [n free, Σ_free g]."""
    free_gap_walk(wp.tid(), q, u, h, offset, hf, stride, chunk, part)


@wp.func
def residual_walk(
    lane: int,
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    set_offset: wp.float64,
    offset: wp.float64,
    hf: wp.float64,
    stride: int,
    chunk: int,
    r: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    part: wp.array2d(dtype=wp.float64),
):
    """One lane of ``bccg_residual_kernel`` (shared with ``kernels/contact/bccg_device.py``)."""
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    n_f = wp.float64(0.0)
    s_r = wp.float64(0.0)
    n_cg = wp.float64(0.0)
    s_gg = wp.float64(0.0)
    g_max = wp.float64(0.0)
    pen = wp.float64(0.0)
    open_cap = wp.float64(0.0)
    n_c = wp.float64(0.0)
    s_gap = wp.float64(0.0)
    while i < n:
        qv = wp.float64(q[iy, ix])
        d = wp.float64(u[iy, ix]) - wp.float64(h[iy, ix])
        g = d - offset
        s_gap += g
        rv = r.dtype(0.0)
        m = wp.uint8(0)
        if is_free(qv, d - set_offset, hf) != 0:
            rv = r.dtype(g)
            m = wp.uint8(1)
            n_f += wp.float64(1.0)
            s_r += g
        if qv > wp.float64(0.0):
            n_c += wp.float64(1.0)
            if qv < hf:
                n_cg += wp.float64(1.0)
                s_gg += g * g
                g_max = wp.max(g_max, wp.abs(g))
            else:
                open_cap = wp.max(open_cap, g)
        else:
            pen = wp.max(pen, -g)
        r[iy, ix] = rv
        mask[iy, ix] = m
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = n_f
    part[lane, 1] = s_r
    part[lane, 2] = n_cg
    part[lane, 3] = s_gg
    part[lane, 4] = g_max
    part[lane, 5] = pen
    part[lane, 6] = open_cap
    part[lane, 7] = n_c
    part[lane, 8] = s_gap


@wp.kernel
def bccg_residual_kernel(
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    set_offset: wp.float64,
    offset: wp.float64,
    hf: wp.float64,
    stride: int,
    chunk: int,
    r: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: the free set (gaps at ``set_offset``), r = free·g (gaps at
    ``offset``), mask = free; and the state's convergence sums. part[i] = [n free, Σ r,
    n(0 < q < hf), Σ_{0<q<hf} g², max_{0<q<hf} abs(g), max_{q≤0} (−g), max_{q≥hf} g, n(q > 0),
    Σ g over the map]."""
    residual_walk(wp.tid(), q, u, h, set_offset, offset, hf, stride, chunk, r, mask, part)


@wp.kernel
def bccg_dot_kernel(
    z: wp.array2d(dtype=Any),
    r: wp.array2d(dtype=Any),
    z_old: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    stride: int,
    chunk: int,
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: the preconditioned residual z (on the free set) against r and the
    last z. part[i] = [Σ c·z, Σ r·z, Σ r·z_old]."""
    lane = wp.tid()
    nx = r.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, r.shape[0] * nx, nx)
    s_z = wp.float64(0.0)
    s_rz = wp.float64(0.0)
    s_rzo = wp.float64(0.0)
    while i < n:
        if mask[iy, ix] != wp.uint8(0):
            zv = wp.float64(z[iy, ix])
            rv = wp.float64(r[iy, ix])
            s_z += zv
            s_rz += rv * zv
            s_rzo += rv * wp.float64(z_old[iy, ix])
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = s_z
    part[lane, 1] = s_rz
    part[lane, 2] = s_rzo


@wp.func
def direction_walk(
    lane: int,
    z: wp.array2d(dtype=Any),
    mean: wp.float64,
    beta: wp.float64,
    mask: wp.array2d(dtype=wp.uint8),
    r: wp.array2d(dtype=Any),
    stride: int,
    chunk: int,
    t: wp.array2d(dtype=Any),
    z_old: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """One lane of ``bccg_direction_kernel`` (shared with ``kernels/contact/bccg_device.py``)."""
    nx = r.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, r.shape[0] * nx, nx)
    s_rt = wp.float64(0.0)
    while i < n:
        zc = wp.float64(0.0)
        tv = wp.float64(0.0)
        if mask[iy, ix] != wp.uint8(0):
            zc = wp.float64(z[iy, ix]) - mean
            tv = zc + beta * wp.float64(t[iy, ix])
            s_rt += wp.float64(r[iy, ix]) * tv
        z_old[iy, ix] = z_old.dtype(zc)
        t[iy, ix] = t.dtype(tv)
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = s_rt


@wp.kernel
def bccg_direction_kernel(
    z: wp.array2d(dtype=Any),
    mean: wp.float64,
    beta: wp.float64,
    mask: wp.array2d(dtype=wp.uint8),
    r: wp.array2d(dtype=Any),
    stride: int,
    chunk: int,
    t: wp.array2d(dtype=Any),
    z_old: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: on the free set z_old ← z − mean, t ← z_old + β·t; both 0 elsewhere.
    part[i, 0] = Σ r·t."""
    direction_walk(wp.tid(), z, mean, beta, mask, r, stride, chunk, t, z_old, part)


@wp.kernel
def bccg_update_kernel(
    kt: wp.array2d(dtype=Any),
    tau_arr: wp.array[wp.float64],
    hf: wp.float64,
    t: wp.array2d(dtype=Any),
    stride: int,
    chunk: int,
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    lin: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    lane_count: wp.array[wp.int32],
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: q ← q − τ·t projected onto [0, hf] (τ = tau_arr[0]); u ← u − τ·K·t
    (exact unless the projection acted). A projected pixel gets mask bit 4 and lin = q − τ·t
    before the projection (``compact_changes_kernel`` then lists q − lin); lane_count[i] = their
    number in the lane. part[i] = [n projected, max amount projected (N), Σ q,
    max abs(τ·K·t)]."""
    lane = wp.tid()
    tau = tau_arr[0]
    nx = q.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, q.shape[0] * nx, nx)
    n_p = wp.float64(0.0)
    viol = wp.float64(0.0)
    total = wp.float64(0.0)
    du = wp.float64(0.0)
    count = int(0)
    while i < n:
        tv = wp.float64(t[iy, ix])
        qv = wp.float64(q[iy, ix])
        if tv != wp.float64(0.0):
            qv = qv - tau * tv
            q_lin = qv
            projected = int(0)
            if qv < wp.float64(0.0):
                viol = wp.max(viol, -qv)
                projected = 1
                qv = wp.float64(0.0)
            elif qv > hf:
                viol = wp.max(viol, qv - hf)
                projected = 1
                qv = hf
            if projected != 0:
                n_p += wp.float64(1.0)
                count += 1
                lin[iy, ix] = lin.dtype(q_lin)
                mask[iy, ix] = mask[iy, ix] | wp.uint8(4)
            q[iy, ix] = q.dtype(qv)
        step_u = tau * wp.float64(kt[iy, ix])
        u[iy, ix] = u.dtype(wp.float64(u[iy, ix]) - step_u)
        du = wp.max(du, wp.abs(step_u))
        total += qv
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = n_p
    part[lane, 1] = viol
    part[lane, 2] = total
    part[lane, 3] = du
    lane_count[lane] = count


@wp.func
def correct_walk(
    lane: int,
    table: wp.array2d(dtype=Any),
    periodic: int,
    index: wp.array[wp.int32],
    value: wp.array[wp.float64],
    n_changes: int,
    stride: int,
    chunk: int,
    u: wp.array2d(dtype=Any),
):
    """One lane of ``bccg_correct_kernel`` (shared with ``kernels/contact/bccg_device.py``); returns
    the lane's largest abs(correction) (m)."""
    nx = u.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, u.shape[0] * nx, nx)
    d_max = wp.float64(0.0)
    while i < n:
        acc = direct_sum(wp.float64(0.0), table, periodic, index, value, n_changes, iy, ix, nx)
        u[iy, ix] = u.dtype(wp.float64(u[iy, ix]) + acc)
        d_max = wp.max(d_max, wp.abs(acc))
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    return d_max


@wp.kernel
def bccg_correct_kernel(
    table: wp.array2d(dtype=Any),
    periodic: int,
    index: wp.array[wp.int32],
    value: wp.array[wp.float64],
    n_changes: int,
    stride: int,
    chunk: int,
    u: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: u ← u + Σ_k value_k·G(pixel − index_k), the projection's few force
    corrections (N) by direct summation over the influence table, in the list's fixed order.
    part[i, 0] = max abs(correction) (m)."""
    lane = wp.tid()
    part[lane, 0] = correct_walk(lane, table, periodic, index, value, n_changes, stride, chunk, u)


@wp.kernel
def bccg_exact_kernel(
    kq: wp.array2d(dtype=Any),
    stride: int,
    chunk: int,
    u: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: u ← K·q (a transform afresh). part[i, 0] = max abs(change of u)."""
    lane = wp.tid()
    nx = u.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, u.shape[0] * nx, nx)
    du = wp.float64(0.0)
    while i < n:
        un = kq[iy, ix]
        du = wp.max(du, wp.abs(wp.float64(un) - wp.float64(u[iy, ix])))
        u[iy, ix] = un
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = du


@wp.kernel
def clamp_force_kernel(hf: wp.float64, q: wp.array2d(dtype=Any)):
    """q ← min(max(q, 0), hf): a warm start projected onto the box."""
    iy, ix = wp.tid()
    qv = wp.float64(q[iy, ix])
    if qv < wp.float64(0.0):
        q[iy, ix] = q.dtype(0.0)
    elif qv > hf:
        q[iy, ix] = q.dtype(hf)


@wp.kernel
def scale_state_kernel(s: wp.float64, q: wp.array2d(dtype=Any), u: wp.array2d(dtype=Any)):
    """q ← s·q, u ← s·u (load control; u = K·q stays exact)."""
    iy, ix = wp.tid()
    q[iy, ix] = q.dtype(s * wp.float64(q[iy, ix]))
    u[iy, ix] = u.dtype(s * wp.float64(u[iy, ix]))


declare_overloads(
    (
        bccg_sums_kernel,
        bccg_residual_kernel,
        bccg_dot_kernel,
        bccg_direction_kernel,
        bccg_update_kernel,
        bccg_correct_kernel,
        bccg_exact_kernel,
        clamp_force_kernel,
        scale_state_kernel,
    )
)
