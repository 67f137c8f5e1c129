# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Adhesive contact: the interaction law's pixel forces and the effective heights.

Launched by ``warptrunc.contact.iteration.adhesive`` (``ContactSolver`` with an
:class:`~warptrunc.contact.adhesion.Adhesion` law). The solver keeps the wall's reaction
``q`` (N, ≥ 0, on the pixels where the gap is closed) apart from the law's pixel forces ``a``
(N, ≤ 0: tensile), and solves the non-adhesive problem of ``q`` on the effective heights
``h = h0 − K·a`` (m): then ``u = K·q`` and the gap ``g = u − h − offset`` (m) is the gap of the
whole traction ``q + a``. Array layouts, the lane walk and the partials array ``part`` are
those of ``kernels/contact/cg.py``. Laws (``law``): 1 Maugis–Dugdale, ``a = −σ₀·dx·dy`` where
``g < h₀`` (σ₀ = w/h₀), else 0; 2 exponential, ``a = −(w/ρ)·exp(−g/ρ)·dx·dy``; gaps below 0
(the round-off of a closed gap) count as 0, and so does the gap of a pixel the wall pushes
(q > 0: closed, its u − h − offset within the solve's tolerance of 0, which the law must not
read: for ρ near the tolerance it would make the forces of the contact jitter). ``work_area`` is w·dx·dy (J), ``length`` is h₀ or
ρ (m). Float32 and float64 instances of every kernel (``wp.overload``); reductions are float64.
"""

from typing import Any

import warp as wp

from ..lanes import declare_overloads, lane_next, lane_start

wp.set_module_options({"enable_backward": False})

LAW_MAUGIS = wp.constant(1)
LAW_EXPONENTIAL = wp.constant(2)


@wp.func
def law_force(law: int, g: wp.float64, work_area: wp.float64, length: wp.float64) -> wp.float64:
    """The law's force (N, ≤ 0) on a pixel at gap ``g`` (m)."""
    gp = wp.max(g, wp.float64(0.0))
    f = wp.float64(0.0)
    if law == LAW_MAUGIS:
        if gp < length:
            f = -work_area / length
    elif law == LAW_EXPONENTIAL:
        f = -(work_area / length) * wp.exp(-gp / length)
    return f


@wp.kernel
def adhesive_force_kernel(
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    law: int,
    work_area: wp.float64,
    length: wp.float64,
    stride: int,
    chunk: int,
    a: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: a ← the law's force at the gap of the current state.
    part[i] = [max abs(change of a) (N), Σ a (N, new), n attractive (q ≤ 0, a < 0 and
    g < length), Σ a (N, before)]."""
    lane = wp.tid()
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    da = wp.float64(0.0)
    s_a = wp.float64(0.0)
    n_att = wp.float64(0.0)
    s_old = wp.float64(0.0)
    while i < n:
        g = wp.float64(u[iy, ix]) - wp.float64(h[iy, ix]) - offset
        if q[iy, ix] > q.dtype(0.0):
            g = wp.float64(0.0)  # the wall pushes: the gap is closed (u − h − offset is within pentol of 0)
        old = wp.float64(a[iy, ix])
        new = wp.float64(a.dtype(law_force(law, g, work_area, length)))
        a[iy, ix] = a.dtype(new)
        da = wp.max(da, wp.abs(new - old))
        s_a += new
        s_old += old
        if q[iy, ix] <= q.dtype(0.0) and new < wp.float64(0.0) and g < length:
            n_att += wp.float64(1.0)
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = da
    part[lane, 1] = s_a
    part[lane, 2] = n_att
    part[lane, 3] = s_old


@wp.kernel
def effective_heights_kernel(
    h0: wp.array2d(dtype=Any),
    ka: wp.array2d(dtype=Any),
    stride: int,
    chunk: int,
    h: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: h ← h0 − K·a (the heights the wall's reaction sees, m).
    part[i, 0] = max abs(change of h) (m)."""
    lane = wp.tid()
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    dh = wp.float64(0.0)
    while i < n:
        new = h.dtype(wp.float64(h0[iy, ix]) - wp.float64(ka[iy, ix]))
        dh = wp.max(dh, wp.abs(wp.float64(new) - wp.float64(h[iy, ix])))
        h[iy, ix] = new
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = dh


declare_overloads((adhesive_force_kernel, effective_heights_kernel))
