# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Constrained conjugate gradients (Polonsky–Keer) for elastic contact: projections, updates
and the map kernels that every iteration shares.

Launched by ``warptrunc.contact.iteration.pk`` (the CG steps), ``warptrunc.contact.iteration.bccg``,
``warptrunc.contact.iteration.punch``, ``warptrunc.contact.iteration.loop`` and
``warptrunc.contact.solver`` (map copies, sums, masks); the spectral products and reductions are
in ``kernels/contact/spectral.py``. State arrays are float32 or float64 (one overload each) and
live on the (ny, nx) map: heights ``h`` (m), compressive pixel forces ``q`` (N, > 0 in contact),
surface displacements ``u`` (m), the CG direction ``t`` (m). ``q`` and ``t`` are views of (ny, Nx) buffers
whose columns ``nx … Nx−1`` are the zero pad of the free half-space (Nx = 2nx; Nx = nx for the
periodic one) and are never written here. The gap is ``g = u − h − offset`` (m), penetration where
``g < 0``. ``mask`` (ny, nx) uint8: bit 0 = in the CG set at the start of the iteration (q > 0),
bit 1 = penetrating without force (load control adds those later), bit 2 = the projection changed
the force in this iteration. Spectra are (Ny, Nx//2 + 1)
arrays of vec2 (re, im), the kernel spectrum ``w`` is real and even in y and stored for rows
0 … Ny//2 only.

Grids: the ``*_kernel`` launches with partial sums use ``lanes`` threads: on the GPU lane ``i``
walks the flattened array with stride ``lanes`` (coalesced), on the CPU lane ``i`` walks the
contiguous chunk ``[i·chunk, (i+1)·chunk)``. Every lane writes its float64 partials to
``part[i, j]`` without atomics; ``sum_lanes_kernel`` (``kernels/contact/spectral.py``) folds
them into a few rows in a fixed order, so the reductions are deterministic for a given device. Columns of ``part`` within one
iteration: 0 Σ c·g·t, 1 N·t·K·t, 2–5 the force update, 6 the step τ (lane 0 only), 7 the number
of forces the projection changed (those are listed by ``compact_changes_kernel`` and their
displacements summed directly over the influence table by ``advance_kernel``). Elementwise
kernels without reductions are one thread per map pixel, ``iy, ix = wp.tid()``.
"""

from typing import Any

import warp as wp

from ..lanes import declare_overloads, lane_next, lane_start

wp.set_module_options({"enable_backward": False})

BIG = wp.constant(1.0e300)


@wp.kernel
def clamp_displacement_kernel(
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    u: wp.array2d(dtype=Any),
    du: wp.array2d(dtype=Any),
):
    """Warm start, one thread per map pixel: u ← max(u, h + offset) (no initial penetration),
    du = the increment of u (≥ 0)."""
    iy, ix = wp.tid()
    lo = h[iy, ix] + h.dtype(offset)
    uo = u[iy, ix]
    if uo < lo:
        u[iy, ix] = lo
        du[iy, ix] = lo - uo
    else:
        du[iy, ix] = du.dtype(0.0)


@wp.kernel
def add_map_kernel(src: wp.array2d(dtype=Any), dst: wp.array2d(dtype=Any)):
    """One thread per map pixel: dst += src."""
    iy, ix = wp.tid()
    dst[iy, ix] = dst[iy, ix] + src[iy, ix]


@wp.kernel
def copy_map_kernel(src: wp.array2d(dtype=Any), dst: wp.array2d(dtype=Any)):
    """One thread per map pixel: dst[iy, ix] = src[iy, ix] (the pad of ``dst`` stays zero)."""
    iy, ix = wp.tid()
    dst[iy, ix] = src[iy, ix]


@wp.kernel
def fill_map_kernel(mask: wp.array2d(dtype=wp.uint8), value: wp.float64, x: wp.array2d(dtype=Any)):
    """One thread per map pixel: x = value where mask bit 0 is set, else 0."""
    iy, ix = wp.tid()
    if (int(mask[iy, ix]) & 1) != 0:
        x[iy, ix] = x.dtype(value)
    else:
        x[iy, ix] = x.dtype(0.0)


@wp.func
def direction_at(
    in_set: bool,
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    beta: wp.float64,
    iy: int,
    ix: int,
    t: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    s_gt: wp.float64,
) -> wp.float64:
    """One pixel of a CG direction (shared with ``kernels/contact/plastic.py``): with c =
    ``in_set``, t = c·(g + β·t) (PK Eq. 13) and mask = c; returns ``s_gt`` + c·g·t."""
    tv = t.dtype(0.0)
    m = wp.uint8(0)
    acc = s_gt
    if in_set:
        g = u[iy, ix] - h[iy, ix] - h.dtype(offset)
        tv = g + t.dtype(beta) * t[iy, ix]
        acc = s_gt + wp.float64(g) * wp.float64(tv)
        m = wp.uint8(1)
    t[iy, ix] = tv
    mask[iy, ix] = m
    return acc


@wp.kernel
def cg_direction_kernel(
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    beta: wp.float64,
    stride: int,
    chunk: int,
    t: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: CG set c = q > 0, t = c·(g + β·t) (PK Eq. 13), mask = c;
    part[i] = [Σ c·g·t]."""
    lane = wp.tid()
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    s_gt = wp.float64(0.0)
    while i < n:
        s_gt = direction_at(q[iy, ix] > q.dtype(0.0), u, h, offset, beta, iy, ix, t, mask, s_gt)
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = s_gt


@wp.func
def fold_step(
    sums: wp.array2d(dtype=wp.float64),
    n_c: wp.float64,
    inv_n: wp.float64,
    fallback: wp.float64,
) -> wp.float64:
    """The CG step τ = Σ c·g·t / (t·K·t) (PK Eq. 15) from the folded rows of columns 0
    (Σ c·g·t) and 1 (N·t·K·t) of the lane partials; ``fallback`` without a CG set or curvature
    (shared with ``kernels/contact/plastic.py``)."""
    s_gt = wp.float64(0.0)
    t_k_t = wp.float64(0.0)
    for k in range(sums.shape[0]):
        s_gt += sums[k, 0]
        t_k_t += sums[k, 1]
    t_k_t = t_k_t * inv_n
    step = fallback
    if n_c > wp.float64(0.0) and t_k_t > wp.float64(0.0):
        step = s_gt / t_k_t
    return step


@wp.kernel
def step_length_kernel(
    sums: wp.array2d(dtype=wp.float64),
    n_c: wp.float64,
    inv_n: wp.float64,
    tau: wp.array[wp.float64],
):
    """One thread: the CG step τ = Σ c·g·t / (t·K·t) from the folded rows of columns 0 (Σ c·g·t)
    and 1 (N·t·K·t) of the lane partials (PK Eq. 15); τ = 0 without a CG set or curvature. Kept on
    the device, so that the force update follows without a host round trip."""
    tau[0] = fold_step(sums, n_c, inv_n, wp.float64(0.0))


@wp.func
def stepped_force(
    q: wp.array2d(dtype=Any),
    t: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    tau: wp.float64,
    iy: int,
    ix: int,
):
    """A pixel's mask and its force after the CG step, q − τ·t on the CG set (mask bit 0), else
    q (shared with ``kernels/contact/plastic.py``): ``m, qv``."""
    m = mask[iy, ix]
    qv = q[iy, ix]
    if (int(m) & 1) != 0:
        qv = qv - q.dtype(tau) * t[iy, ix]
    return m, qv


@wp.func
def store_force(
    changed: bool,
    m: wp.uint8,
    q_lin: Any,
    qv: Any,
    iy: int,
    ix: int,
    q: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    lin: wp.array2d(dtype=Any),
) -> int:
    """One pixel of a force update (shared with ``kernels/contact/plastic.py``): q = ``qv``;
    where the projection ``changed`` it, mask = ``m`` with bit 2 and lin = ``q_lin``. Returns 1
    where changed, else 0."""
    c = int(0)
    if changed:
        mask[iy, ix] = m | wp.uint8(4)
        lin[iy, ix] = q_lin
        c = 1
    q[iy, ix] = qv
    return c


@wp.func
def store_update_partials(
    lane: int,
    n_nc: wp.float64,
    n_clamp: wp.float64,
    max_viol: wp.float64,
    total: wp.float64,
    tau: wp.float64,
    count: int,
    part: wp.array2d(dtype=wp.float64),
    lane_count: wp.array[wp.int32],
):
    """A lane's part[lane, 2:8] of a force update, [n changing sides, n clamped, largest
    violation, Σ q, τ (lane 0; 0 on the others, so that the column sums to τ), n changed], and
    lane_count[lane] = n changed (shared with ``kernels/contact/plastic.py``)."""
    part[lane, 2] = n_nc
    part[lane, 3] = n_clamp
    part[lane, 4] = max_viol
    part[lane, 5] = total
    if lane == 0:
        part[lane, 6] = tau
    else:
        part[lane, 6] = wp.float64(0.0)
    part[lane, 7] = wp.float64(count)
    lane_count[lane] = count


@wp.kernel
def update_force_kernel(
    t: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    tau_arr: wp.array[wp.float64],
    defer_nc: int,
    stride: int,
    chunk: int,
    q: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    lin: wp.array2d(dtype=Any),
    lane_count: wp.array[wp.int32],
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: q ← q − τ·c·t (= q_lin) with τ = tau_arr[0]; pixels with q ≤ 0 get
    q = 0 (tensile); those of them that penetrate (g < 0) get q = −τ·g (PK's set I_ol), or only
    bit 1 of the mask when ``defer_nc`` (load control rescales first). Pixels where the projection
    changed q (q_lin < 0, or I_ol) get mask bit 2 and lin = q_lin; lane_count[i] = their number in
    the lane. part[i, 2:8] = [n penetrating without force, n zeroed with q < 0, max tensile force,
    Σ q (after the update), τ (lane 0; 0 on the others, so that the column sums to τ), n changed].
    """
    lane = wp.tid()
    tau = tau_arr[0]
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    n_nc = wp.float64(0.0)
    n_zero = wp.float64(0.0)
    max_tens = wp.float64(0.0)
    total = wp.float64(0.0)
    zero = q.dtype(0.0)
    count = int(0)
    while i < n:
        m, qv = stepped_force(q, t, mask, tau, iy, ix)
        q_lin = qv
        changed = False
        if qv <= zero:
            changed = qv < zero
            max_tens = wp.max(max_tens, -wp.float64(qv))
            if qv < zero:
                n_zero += wp.float64(1.0)
            qv = zero
            g = u[iy, ix] - h[iy, ix] - h.dtype(offset)
            if g < h.dtype(0.0):
                n_nc += wp.float64(1.0)
                changed = True
                if defer_nc != 0:
                    m = m | wp.uint8(2)
                else:
                    qv = -q.dtype(tau) * g
        count += store_force(changed, m, q_lin, qv, iy, ix, q, mask, lin)
        total += wp.float64(qv)
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    store_update_partials(lane, n_nc, n_zero, max_tens, total, tau, count, part, lane_count)


@wp.kernel
def rescale_force_kernel(
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    tau: wp.float64,
    scale: wp.float64,
    mask: wp.array2d(dtype=wp.uint8),
    q: wp.array2d(dtype=Any),
):
    """Load control, one thread per map pixel: q ← scale·q, then q = −τ·g where mask bit 1
    (which is cleared; bit 2 is kept)."""
    iy, ix = wp.tid()
    qv = q[iy, ix] * q.dtype(scale)
    m = mask[iy, ix]
    if (int(m) & 2) != 0:
        qv = -q.dtype(tau) * (u[iy, ix] - h[iy, ix] - h.dtype(offset))
        mask[iy, ix] = m & wp.uint8(5)
    q[iy, ix] = qv


@wp.func
def compact_walk(
    lane: int,
    q: wp.array2d(dtype=Any),
    lin: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    scale: wp.float64,
    offsets: wp.array[wp.int32],
    stride: int,
    chunk: int,
    index: wp.array[wp.int32],
    value: wp.array[wp.float64],
):
    """One lane of ``compact_changes_kernel`` (shared with ``kernels/contact/bccg_device.py``)."""
    nx = q.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, q.shape[0] * nx, nx)
    k = offsets[lane]
    while i < n:
        if (int(mask[iy, ix]) & 4) != 0:
            index[k] = iy * nx + ix
            value[k] = wp.float64(q[iy, ix]) - scale * wp.float64(lin[iy, ix])
            k += 1
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)


@wp.kernel
def compact_changes_kernel(
    q: wp.array2d(dtype=Any),
    lin: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    scale: wp.float64,
    offsets: wp.array[wp.int32],
    stride: int,
    chunk: int,
    index: wp.array[wp.int32],
    value: wp.array[wp.float64],
):
    """Lanes over the map, in the walk of ``update_force_kernel``: the pixels with mask bit 2 (the
    projection changed q) and their force correction Δp = q − scale·q_lin (N), written from
    offsets[i] (the exclusive scan of its lane counts), so the list's order is fixed. ``index``
    holds iy·nx + ix."""
    compact_walk(wp.tid(), q, lin, mask, scale, offsets, stride, chunk, index, value)


@wp.func
def influence(table: wp.array2d(dtype=Any), periodic: int, dy: int, dx: int) -> wp.float64:
    """Displacement per unit force (m/N) at separation (dy, dx) pixels: the free half-space's
    table holds |dy|, |dx| ≥ 0 (Love's coefficient is even); the periodic one wraps."""
    ny = table.shape[0]
    nx = table.shape[1]
    if periodic != 0:
        if dy < 0:
            dy += ny
        if dx < 0:
            dx += nx
        return wp.float64(table[dy, dx])
    return wp.float64(table[wp.abs(dy), wp.abs(dx)])


@wp.func
def direct_sum(
    acc: wp.float64,
    table: wp.array2d(dtype=Any),
    periodic: int,
    index: wp.array[wp.int32],
    value: wp.array[wp.float64],
    n_changes: int,
    iy: int,
    ix: int,
    nx: int,
) -> wp.float64:
    """acc + Σ_k value_k·G(pixel (iy, ix) − index_k) (m): the displacement there of a few
    listed force changes (N) added by direct summation over the influence table, one term at a
    time in the list's fixed order."""
    for k in range(n_changes):
        j = index[k]
        jy = j // nx
        acc += value[k] * influence(table, periodic, iy - jy, ix - (j - jy * nx))
    return acc


@wp.func
def advance_at(
    r: wp.array2d(dtype=Any),
    linear: int,
    tau: wp.float64,
    scale: wp.float64,
    table: wp.array2d(dtype=Any),
    periodic: int,
    index: wp.array[wp.int32],
    value: wp.array[wp.float64],
    n_changes: int,
    iy: int,
    ix: int,
    nx: int,
    u: wp.array2d(dtype=Any),
) -> wp.float64:
    """One pixel of the new displacement of ``advance_kernel`` (shared with
    ``kernels/contact/plastic.py``): ``linear == 0``: u ← r; else u ← scale·(u − τ·r) + the
    listed corrections. Returns abs(Δu) (m)."""
    uo = u[iy, ix]
    un = r[iy, ix]
    if linear != 0:
        acc = direct_sum(
            scale * (wp.float64(uo) - tau * wp.float64(un)),
            table,
            periodic,
            index,
            value,
            n_changes,
            iy,
            ix,
            nx,
        )
        un = u.dtype(acc)
    u[iy, ix] = un
    return wp.abs(wp.float64(un) - wp.float64(uo))


@wp.func
def store_advance_partials(
    lane: int,
    du_max: wp.float64,
    n_c: wp.float64,
    s_g: wp.float64,
    s_gg: wp.float64,
    viol: wp.float64,
    s_gap: wp.float64,
    s_q: wp.float64,
    part: wp.array2d(dtype=wp.float64),
):
    """A lane's part[lane, 0:7] of a displacement advance, [max abs(Δu), n in the CG set, Σ c·g,
    Σ c·g², largest violation, Σ g, Σ q] (shared with ``kernels/contact/plastic.py``)."""
    part[lane, 0] = du_max
    part[lane, 1] = n_c
    part[lane, 2] = s_g
    part[lane, 3] = s_gg
    part[lane, 4] = viol
    part[lane, 5] = s_gap
    part[lane, 6] = s_q


@wp.kernel
def advance_kernel(
    r: wp.array2d(dtype=Any),
    linear: int,
    tau: wp.float64,
    scale: wp.float64,
    table: wp.array2d(dtype=Any),
    periodic: int,
    index: wp.array[wp.int32],
    value: wp.array[wp.float64],
    n_changes: int,
    q: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    offset: wp.float64,
    mask: wp.array2d(dtype=wp.uint8),
    stride: int,
    chunk: int,
    u: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: the new displacement. ``linear == 0``: u ← r (r = K·q, exact).
    ``linear != 0``: u ← scale·(u − τ·r) + Σ_k value_k·G(pixel − index_k) (r = K·t: the step by
    linearity, then the projection's few force corrections by direct summation over the
    influence table, in the list's fixed order). part[i] = [max |Δu|, n(q > 0), Σ c·g, Σ c·g²,
    max penetration over the previous CG set, Σ g, Σ q] with c = q > 0 and the new u."""
    lane = wp.tid()
    nx = h.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, h.shape[0] * nx, nx)
    du_max = wp.float64(0.0)
    n_c = wp.float64(0.0)
    s_g = wp.float64(0.0)
    s_gg = wp.float64(0.0)
    pen = wp.float64(0.0)
    s_gap = wp.float64(0.0)
    s_q = wp.float64(0.0)
    while i < n:
        du = advance_at(
            r, linear, tau, scale, table, periodic, index, value, n_changes, iy, ix, nx, u
        )
        du_max = wp.max(du_max, du)
        g = wp.float64(u[iy, ix]) - wp.float64(h[iy, ix]) - offset
        s_gap += g
        qv = q[iy, ix]
        if qv > q.dtype(0.0):
            n_c += wp.float64(1.0)
            s_g += g
            s_gg += g * g
            s_q += wp.float64(qv)
        if (int(mask[iy, ix]) & 1) != 0:
            pen = wp.max(pen, -g)
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    store_advance_partials(lane, du_max, n_c, s_g, s_gg, pen, s_gap, s_q, part)


@wp.kernel
def punch_step_kernel(
    kd: wp.array2d(dtype=Any),
    d: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    alpha: wp.float64,
    stride: int,
    chunk: int,
    x: wp.array2d(dtype=Any),
    res: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """Barber's flat punch (linear CG on the contact set), lanes over the map: x += α·d,
    res −= α·K·d on the set; part[i] = [Σ res², Σ x]."""
    lane = wp.tid()
    nx = mask.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, mask.shape[0] * nx, nx)
    s_rr = wp.float64(0.0)
    s_x = wp.float64(0.0)
    while i < n:
        if (int(mask[iy, ix]) & 1) != 0:
            xv = x[iy, ix] + x.dtype(alpha) * d[iy, ix]
            rv = res[iy, ix] - res.dtype(alpha) * kd[iy, ix]
            x[iy, ix] = xv
            res[iy, ix] = rv
            s_rr += wp.float64(rv) * wp.float64(rv)
            s_x += wp.float64(xv)
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = s_rr
    part[lane, 1] = s_x


@wp.kernel
def punch_direction_kernel(
    res: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    beta: wp.float64,
    d: wp.array2d(dtype=Any),
):
    """One thread per map pixel: d = res + β·d on the contact set, 0 elsewhere."""
    iy, ix = wp.tid()
    if (int(mask[iy, ix]) & 1) != 0:
        d[iy, ix] = res[iy, ix] + d.dtype(beta) * d[iy, ix]
    else:
        d[iy, ix] = d.dtype(0.0)


@wp.kernel
def contact_mask_kernel(q: wp.array2d(dtype=Any), mask: wp.array2d(dtype=wp.uint8)):
    """One thread per map pixel: mask = 1 where q > 0, else 0."""
    iy, ix = wp.tid()
    if q[iy, ix] > q.dtype(0.0):
        mask[iy, ix] = wp.uint8(1)
    else:
        mask[iy, ix] = wp.uint8(0)


@wp.kernel
def max_force_kernel(
    q: wp.array2d(dtype=Any),
    stride: int,
    chunk: int,
    part: wp.array2d(dtype=wp.float64),
):
    """Lanes over the map: part[i, 0] = the largest compressive pixel force max(q, 0) (N)."""
    lane = wp.tid()
    nx = q.shape[1]
    i, n, step, iy, ix, sy, sx = lane_start(lane, stride, chunk, q.shape[0] * nx, nx)
    qm = wp.float64(0.0)
    while i < n:
        qm = wp.max(qm, wp.float64(q[iy, ix]))
        i, iy, ix = lane_next(i, iy, ix, step, sy, sx, nx)
    part[lane, 0] = qm


declare_overloads(
    (
        clamp_displacement_kernel,
        add_map_kernel,
        copy_map_kernel,
        fill_map_kernel,
        cg_direction_kernel,
        update_force_kernel,
        compact_changes_kernel,
        rescale_force_kernel,
        advance_kernel,
        punch_step_kernel,
        punch_direction_kernel,
        contact_mask_kernel,
        max_force_kernel,
    )
)
