# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The BCCG iteration with its scalar steps on the device: one read-back per iteration.

Launched by ``warptrunc.contact.iteration.bccg_device`` (``SolverSettings(loop="device")``). The lane
kernels, the partials ``part`` and their folded rows ``sums`` are those of
``kernels/contact/bccg.py`` and ``warptrunc.contact.influence.LaneReduction``; what the host loop
of ``warptrunc.contact.iteration.bccg`` reads back after each reduction (the offset of load control, the
Polak–Ribière β, the projection's count, the scale to the load) is instead folded by a one-thread
kernel into the solve's scalar array ``s`` (float64, indices ``S_*`` below) and read by the next
kernel from there, so the host reads ``s`` once per iteration, after the residual. The folds sum
the rows in order (the host sums them with NumPy: the last bits may differ).
"""

from typing import Any

import warp as wp

from .cg import compact_walk
from .bccg import correct_walk, direction_walk, free_gap_walk, residual_walk
from ..lanes import declare_overloads

wp.set_module_options({"enable_backward": False})

S_OFF = wp.constant(0)  # rigid offset of the gaps (m), after load control's move
S_SETOFF = wp.constant(1)  # offset at which the free set is taken (m)
S_TOTAL = wp.constant(2)  # Σ q after the last step (N; the load after scaling)
S_DU = wp.constant(3)  # largest change of u in the last step (m)
S_VIOL = wp.constant(4)  # largest amount projected in the last step (N)
S_NPROJ = wp.constant(5)  # pixels projected in the last step (count)
S_RZOLD = wp.constant(6)  # r·z of the last direction
S_BETA = wp.constant(7)  # Polak–Ribière β of this direction
S_MEAN = wp.constant(8)  # mean of z over the free set (load control)
S_FLAG = wp.constant(9)  # 1: u misses the projection's corrections; 2: Σ q ≤ 0, not scaled
S_SCALE = wp.constant(10)  # load / Σ q (0: none)
S_RES = wp.constant(11)  # 11 … 19: the residual kernel's nine sums, in its column order
S_LOAD = wp.constant(20)  # the load of load control (N)
S_SIZE = 24


@wp.func
def fold(sums: wp.array2d(dtype=wp.float64), col: int, is_max: int) -> wp.float64:
    """Σ (or max, from 0) over the rows of one column of the folded partials, in row order."""
    acc = wp.float64(0.0)
    for k in range(sums.shape[0]):
        if is_max != 0:
            acc = wp.max(acc, sums[k, col])
        else:
            acc += sums[k, col]
    return acc


@wp.kernel
def loop_offset_kernel(sums: wp.array2d(dtype=wp.float64), s: wp.array[wp.float64]):
    """One thread (load control): the free set at the present offset, then the offset moved
    by the mean gap over it (columns 0, 1 of ``bccg_sums_kernel``)."""
    n_f = fold(sums, 0, 0)
    s_g = fold(sums, 1, 0)
    s[S_SETOFF] = s[S_OFF]
    if n_f > wp.float64(0.0):
        s[S_OFF] = s[S_OFF] + s_g / n_f


@wp.kernel
def loop_residual_kernel(sums: wp.array2d(dtype=wp.float64), s: wp.array[wp.float64]):
    """One thread: the nine sums of ``bccg_residual_kernel`` (maxima in columns 4, 5, 6) into
    s[S_RES …]."""
    for j in range(9):
        m = int(0)
        if j >= 4 and j <= 6:
            m = 1
        s[S_RES + j] = fold(sums, j, m)


@wp.kernel
def loop_dot_kernel(
    sums: wp.array2d(dtype=wp.float64),
    load_control: int,
    restart: int,
    s: wp.array[wp.float64],
):
    """One thread: from [Σ c·z, Σ r·z, Σ r·z_old] the mean of z on the free set (load control),
    r·z made mean-free, and β = max(0, (r·z − r·z_old)/(r·z)_old) unless ``restart``."""
    s_z = fold(sums, 0, 0)
    rz = fold(sums, 1, 0)
    rzo = fold(sums, 2, 0)
    n_f = s[S_RES + 0]
    mean = wp.float64(0.0)
    if load_control != 0 and n_f > wp.float64(0.0):
        mean = s_z / n_f
    rz = rz - mean * s[S_RES + 1]
    beta = wp.float64(0.0)
    rz_old = s[S_RZOLD]
    if restart == 0 and rz_old > wp.float64(0.0):
        beta = wp.max(wp.float64(0.0), (rz - rzo) / rz_old)
    s[S_RZOLD] = rz
    s[S_BETA] = beta
    s[S_MEAN] = mean


@wp.kernel
def step_length_loop_kernel(
    sums: wp.array2d(dtype=wp.float64),
    s: wp.array[wp.float64],
    inv_n: wp.float64,
    tau: wp.array[wp.float64],
):
    """One thread: ``step_length_kernel`` (τ = Σ c·g·t / (t·K·t) from columns 0 and 1) with the
    free-set count read from s[S_RES]."""
    s_gt = fold(sums, 0, 0)
    t_k_t = fold(sums, 1, 0) * inv_n
    step = wp.float64(0.0)
    if s[S_RES + 0] > wp.float64(0.0) and t_k_t > wp.float64(0.0):
        step = s_gt / t_k_t
    tau[0] = step


@wp.kernel
def loop_update_kernel(
    sums: wp.array2d(dtype=wp.float64),
    load_control: int,
    s: wp.array[wp.float64],
):
    """One thread: [n projected, max projected, Σ q, max abs(τ·K·t)] of ``bccg_update_kernel``
    into s; in load control the scale to the load s[S_LOAD] (N), and Σ q becomes the load."""
    load = s[S_LOAD]
    n_p = fold(sums, 0, 0)
    viol = fold(sums, 1, 1)
    total = fold(sums, 2, 0)
    du = fold(sums, 3, 1)
    s[S_NPROJ] = n_p
    s[S_VIOL] = viol
    s[S_DU] = du
    s[S_FLAG] = wp.float64(0.0)
    s[S_SCALE] = wp.float64(0.0)
    s[S_TOTAL] = total
    if load_control != 0:
        if total > wp.float64(0.0):
            s[S_SCALE] = load / total
        else:
            s[S_FLAG] = wp.float64(2.0)
        s[S_TOTAL] = load


@wp.kernel
def compact_gated_kernel(
    q: wp.array2d(dtype=Any),
    lin: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    offsets: wp.array[wp.int32],
    s: wp.array[wp.float64],
    cap: int,
    stride: int,
    chunk: int,
    index: wp.array[wp.int32],
    value: wp.array[wp.float64],
):
    """``compact_changes_kernel`` (scale 1) when 0 < s[S_NPROJ] ≤ ``cap`` (the list's length);
    nothing otherwise."""
    n_p = int(s[S_NPROJ])
    if n_p > 0 and n_p <= cap:
        compact_walk(wp.tid(), q, lin, mask, wp.float64(1.0), offsets, stride, chunk, index, value)


@wp.kernel
def correct_gated_kernel(
    table: wp.array2d(dtype=Any),
    periodic: int,
    index: wp.array[wp.int32],
    value: wp.array[wp.float64],
    s: wp.array[wp.float64],
    cap: int,
    stride: int,
    chunk: int,
    u: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """``bccg_correct_kernel`` for the s[S_NPROJ] listed changes when 0 < s[S_NPROJ] ≤ ``cap``;
    otherwise u is left and part[i, 0] = 0."""
    lane = wp.tid()
    n_p = int(s[S_NPROJ])
    d_max = wp.float64(0.0)
    if n_p > 0 and n_p <= cap:
        d_max = correct_walk(lane, table, periodic, index, value, n_p, stride, chunk, u)
    part[lane, 0] = d_max


@wp.kernel
def loop_correct_kernel(sums: wp.array2d(dtype=wp.float64), cap: int, s: wp.array[wp.float64]):
    """One thread: the correction's largest change of u added to s[S_DU]; more projected pixels
    than ``cap``: flag 1 (u misses them; the host transforms afresh)."""
    n_p = int(s[S_NPROJ])
    if n_p > 0 and n_p <= cap:
        s[S_DU] = s[S_DU] + fold(sums, 0, 1)
    elif n_p > cap:
        s[S_FLAG] = wp.float64(int(s[S_FLAG]) | 1)


@wp.kernel
def loop_exact_kernel(sums: wp.array2d(dtype=wp.float64), s: wp.array[wp.float64]):
    """One thread: s[S_DU] = max(s[S_DU], the largest change of u by the transform afresh)."""
    s[S_DU] = wp.max(s[S_DU], fold(sums, 0, 1))


@wp.kernel
def scale_gated_kernel(s: wp.array[wp.float64], q: wp.array2d(dtype=Any), u: wp.array2d(dtype=Any)):
    """q ← f·q, u ← f·u with f = s[S_SCALE] (load control; nothing when f = 0)."""
    f = s[S_SCALE]
    if f > wp.float64(0.0):
        iy, ix = wp.tid()
        q[iy, ix] = q.dtype(f * wp.float64(q[iy, ix]))
        u[iy, ix] = u.dtype(f * wp.float64(u[iy, ix]))


@wp.kernel
def residual_loop_kernel(
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    s: wp.array[wp.float64],
    hf: wp.float64,
    stride: int,
    chunk: int,
    r: wp.array2d(dtype=Any),
    mask: wp.array2d(dtype=wp.uint8),
    part: wp.array2d(dtype=wp.float64),
):
    """``bccg_residual_kernel`` with the offsets read from s[S_SETOFF] and s[S_OFF]."""
    residual_walk(wp.tid(), q, u, h, s[S_SETOFF], s[S_OFF], hf, stride, chunk, r, mask, part)


@wp.kernel
def sums_loop_kernel(
    q: wp.array2d(dtype=Any),
    u: wp.array2d(dtype=Any),
    h: wp.array2d(dtype=Any),
    s: wp.array[wp.float64],
    hf: wp.float64,
    stride: int,
    chunk: int,
    part: wp.array2d(dtype=wp.float64),
):
    """``bccg_sums_kernel`` at the offset s[S_OFF]: part[i] = [n free, Σ_free g]."""
    free_gap_walk(wp.tid(), q, u, h, s[S_OFF], hf, stride, chunk, part)


@wp.kernel
def direction_loop_kernel(
    z: wp.array2d(dtype=Any),
    s: wp.array[wp.float64],
    mask: wp.array2d(dtype=wp.uint8),
    r: wp.array2d(dtype=Any),
    stride: int,
    chunk: int,
    t: wp.array2d(dtype=Any),
    z_old: wp.array2d(dtype=Any),
    part: wp.array2d(dtype=wp.float64),
):
    """``bccg_direction_kernel`` with the mean and β read from s[S_MEAN], s[S_BETA]."""
    direction_walk(wp.tid(), z, s[S_MEAN], s[S_BETA], mask, r, stride, chunk, t, z_old, part)


declare_overloads(
    (
        compact_gated_kernel,
        correct_gated_kernel,
        scale_gated_kernel,
        residual_loop_kernel,
        sums_loop_kernel,
        direction_loop_kernel,
    )
)
