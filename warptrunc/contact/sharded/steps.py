# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The per-pixel steps of :class:`~warptrunc.contact.sharded.ShardedContactSolver`, in
``jax.numpy`` on the row slabs, one ``jax.jit`` programme each
(:func:`~warptrunc.contact.sharded.steps.make_step`).

Each step is the Warp kernel (or kernels) of the one-device solver named beside it, with the
same arithmetic: the maps in their dtype, gaps, sums and maxima in float64, the values cast to
the dtype where the kernel stores them. Sums are ``jnp.sum`` over the sharded maps (XLA's
all-reduce); a step's float64 sums come back as one vector (one read-back). Maxima start at 0,
as the lane kernels' do.
"""

from __future__ import annotations

from typing import Any

__all__ = ["make_step"]


def make_step(layout: Any, name: str):
    """Build the jitted step ``name`` of the sharded solvers of one layout.

    Parameters
    ----------
    layout : SlabLayout
        The layout (:class:`~warptrunc.contact.sharded.fft.SlabLayout`: the dtype, the
        shardings and the convolution).
    name : str
        One of ``"sums"``, ``"free_sums"``, ``"warm_start"``, ``"clamp"``, ``"scale"``,
        ``"fill"``, ``"exact_u"``, ``"residual"``, ``"dots"``, ``"precondition"``, ``"step"``,
        ``"flow"``, ``"max_force"``, ``"punch_start"``, ``"punch_step"``, ``"punch_cg"``,
        ``"punch_pc"``.

    Returns
    -------
    callable
        The jitted function (arguments and results: those of the calls in
        :class:`~warptrunc.contact.sharded.ShardedContactSolver`).

    Raises
    ------
    KeyError
        An unknown step.
    """
    hs = layout
    jax, jnp = hs.jax, hs.jnp
    dt = hs.np_dtype
    f64 = jnp.float64
    conv = hs.conv

    def d(a):
        return a.astype(f64)

    def vec(*xs):
        return jnp.stack([jnp.asarray(x, f64) for x in xs])

    def gmax(a):  # the lane kernels' maxima start at 0
        return jnp.maximum(jnp.max(a), 0.0)

    def is_free(qv, g, hf):  # kernels/contact/bccg.py is_free
        return ((qv > 0) & (qv < hf)) | ((qv <= 0) & (g < 0)) | ((qv >= hf) & (g > 0))

    def sums(q, u, h, offset):  # contact_sums_kernel
        c = q > 0
        g = d(u) - d(h) - offset
        return vec(
            jnp.sum(c),
            jnp.sum(jnp.where(c, g, 0.0)),
            jnp.sum(jnp.where(c, g * g, 0.0)),
            jnp.sum(jnp.where(c, d(q), 0.0)),
        )

    def free_sums(q, u, h, offset, hf):  # bccg_sums_kernel
        g = d(u) - d(h) - offset
        free = is_free(d(q), g, hf)
        return vec(jnp.sum(free), jnp.sum(jnp.where(free, g, 0.0)))

    def warm_start(q, u, h, offset, w):  # clamp_displacement_kernel, K⁻¹, add_map_kernel
        lo = h + jnp.asarray(offset, dt)
        below = u < lo
        du = jnp.where(below, lo - u, jnp.zeros((), dt))
        return q + conv(du, w, True), jnp.where(below, lo, u)

    def clamp(q, hf):  # clamp_force_kernel
        qv = d(q)
        return jnp.where(qv < 0, 0.0, jnp.where(qv > hf, hf, qv)).astype(dt)

    def scale(q, u, s):  # scale_state_kernel
        return (s * d(q)).astype(dt), (s * d(u)).astype(dt)

    def fill(q, value):  # fill_map_kernel with every mask bit set
        return jnp.full_like(q, value)

    def exact_u(q, u, w):  # apply, bccg_exact_kernel
        kq = conv(q, w)
        return kq, vec(gmax(jnp.abs(d(kq) - d(u))))[0]

    def residual(q, u, h, set_offset, offset, hf):  # bccg_residual_kernel
        qv = d(q)
        dd = d(u) - d(h)
        g = dd - offset
        free = is_free(qv, dd - set_offset, hf)
        inner = (qv > 0) & (qv < hf)
        r = jnp.where(free, g, 0.0).astype(dt)
        out = vec(
            jnp.sum(free),
            jnp.sum(jnp.where(free, g, 0.0)),
            jnp.sum(inner),
            jnp.sum(jnp.where(inner, g * g, 0.0)),
            gmax(jnp.where(inner, jnp.abs(g), 0.0)),
            gmax(jnp.where(qv <= 0, -g, 0.0)),
            gmax(jnp.where(qv >= hf, g, 0.0)),
            jnp.sum(qv > 0),
            jnp.sum(g),
        )
        return r, free, out

    def dots(z, r, z_old, mask):  # bccg_dot_kernel
        zv, rv = d(z), d(r)
        return vec(
            jnp.sum(jnp.where(mask, zv, 0.0)),
            jnp.sum(jnp.where(mask, rv * zv, 0.0)),
            jnp.sum(jnp.where(mask, rv * d(z_old), 0.0)),
        )

    def plain(r, z_old, mask, w):
        return r, dots(r, r, z_old, mask)

    def precondition(r, z_old, mask, w):  # apply(inverse), bccg_dot_kernel
        z = conv(r, w, True)
        return z, dots(z, r, z_old, mask)

    def step(z, mean, beta, mask, r, t, q, u, n_f, hf, w):
        # bccg_direction_kernel, forward + SPECTRUM_APPLY + inverse, step_length_kernel,
        # bccg_update_kernel (t·K·t in real space: Σ t·K·t over the map, = Parseval's sum)
        zc = jnp.where(mask, d(z) - mean, 0.0)
        tv = jnp.where(mask, zc + beta * d(t), 0.0)
        z_old, t = zc.astype(dt), tv.astype(dt)
        s_rt = jnp.sum(d(r) * tv)
        kt = conv(t, w)
        t64 = d(t)
        t_k_t = jnp.sum(t64 * d(kt))
        tau = jnp.where((n_f > 0) & (t_k_t > 0), s_rt / jnp.where(t_k_t > 0, t_k_t, 1.0), 0.0)
        moving = t64 != 0
        qv = jnp.where(moving, d(q) - tau * t64, d(q))
        neg = moving & (qv < 0)
        over = moving & ~neg & (qv > hf)
        viol = gmax(jnp.where(neg, -qv, jnp.where(over, qv - hf, 0.0)))
        qv = jnp.where(neg, 0.0, jnp.where(over, hf, qv))
        step_u = tau * d(kt)
        out = vec(jnp.sum(neg | over), viol, jnp.sum(qv), gmax(jnp.abs(step_u)))
        return t, z_old, qv.astype(dt), (d(u) - step_u).astype(dt), out

    def flow(q, u, h, offset, cap, apply):  # plastic_flow_kernel
        cap_d = jnp.asarray(cap, dt)
        at_cap = q >= cap_d
        hn = (d(u) - offset).astype(dt)
        lower = apply & at_cap & (hn < h)
        new = jnp.where(lower, hn, h)
        out = vec(jnp.sum(q > 0), jnp.sum(at_cap), jnp.sum(jnp.where(lower, d(h) - d(hn), 0.0)))
        return new, out

    def max_force(q):  # max_force_kernel
        return gmax(d(q))

    def punch_start(q):  # contact_mask_kernel, fill_map_kernel
        mask = q > 0
        return mask, jnp.zeros_like(q), jnp.where(mask, 1.0, 0.0).astype(dt), jnp.sum(mask)

    def punch_step(x, res, dd, mask, num, w):  # apply (energy), punch_step_kernel
        kd = conv(dd, w)
        d_k_d = jnp.sum(d(dd) * d(kd))
        alpha = jnp.where(d_k_d > 0, num / jnp.where(d_k_d > 0, d_k_d, 1.0), 0.0).astype(dt)
        xv = jnp.where(mask, x + alpha * dd, x)
        rv = jnp.where(mask, res - alpha * kd, res)
        out = vec(
            d_k_d, jnp.sum(jnp.where(mask, d(rv) ** 2, 0.0)), jnp.sum(jnp.where(mask, d(xv), 0.0))
        )
        return xv, rv, out

    def punch_cg(res, dd, mask, beta, w):  # punch_direction_kernel
        return jnp.where(mask, res + jnp.asarray(beta, dt) * dd, jnp.zeros((), dt))

    def punch_pc(res, dd, mask, rz_old, w):  # apply(inverse), bccg_dot/direction_kernel
        z = conv(res, w, True)
        rz = jnp.sum(jnp.where(mask, d(res) * d(z), 0.0))
        beta = jnp.where(rz_old != 0, rz / jnp.where(rz_old != 0, rz_old, 1.0), 0.0)
        return jnp.where(mask, d(z) + beta * d(dd), 0.0).astype(dt), rz

    rows, rep = hs.rows, hs.replicated
    table = {  # name: (function, output shardings, donated arguments)
        "sums": (sums, rep, ()),
        "free_sums": (free_sums, rep, ()),
        "warm_start": (warm_start, (rows, rows), (0, 1)),
        "clamp": (clamp, rows, (0,)),
        "scale": (scale, (rows, rows), (0, 1)),
        "fill": (fill, rows, (0,)),
        "exact_u": (exact_u, (rows, rep), (1,)),
        "residual": (residual, (rows, rows, rep), ()),
        "dots": (plain, (rows, rep), ()),
        "precondition": (precondition, (rows, rep), ()),
        "step": (step, (rows, rows, rows, rows, rep), (5, 6, 7)),
        "flow": (flow, (rows, rep), (2,)),
        "max_force": (max_force, rep, ()),
        "punch_start": (punch_start, (rows, rows, rows, rep), ()),
        "punch_step": (punch_step, (rows, rows, rep), (0, 1)),
        "punch_cg": (punch_cg, rows, ()),
        "punch_pc": (punch_pc, (rows, rep), ()),
    }
    fn, shardings, donate = table[name]
    return jax.jit(fn, out_shardings=shardings, donate_argnums=donate if hs.donate else ())
