# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The kernel spectrum of the half-space over several devices, built in pieces.

The free half-space's spectrum W is the one-device solver's
(:func:`~warptrunc.contact.influence.build_free_spectrum`): Love's coefficients of the map's
quadrant, mirrored in x, transformed along x (row slabs, one device each), a sharding constraint
to column slabs (XLA's all-to-all), mirrored in y and transformed along y, in float64, rounded
to the dtype. The periodic W is its closed form.

Both stages run in *pieces* of at most
:data:`~warptrunc.contact.sharded.grid.BUILD_PIECE_BYTES` of float64 input each — the x stage
over blocks of rows (``lax.map``), the y stage over blocks of columns (``lax.fori_loop`` writing
into its output) — so that a device holds, besides the x stage's result before and after the
all-to-all and W itself, one piece's temporaries. Built in one piece, XLA's temporaries of the
free build at 65536² over 4 devices came to 51.5 GB per device on the CPU compile, and the GPU
compile asked for one buffer of 60.8 GiB (4 × H200, 2026-11-27): more than the solve itself.
:func:`~warptrunc.contact.sharded.grid.build_bytes` is the model of the pieced build's peak.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..._support.docs import fill_doc
from ..influence import _love
from .grid import _pieces, _row_layout, _shard_map, host_array

__all__ = ["build_spectrum", "spectrum_programme", "unit_force_check"]

SPECTRUM_DOCS = {
    "{pixel_modulus}": (
        "pixel_size : (float, float)\n    Pixel sides (dx, dy) (m).\n"
        "contact_modulus : float\n    Contact modulus E* (Pa)."
    ),
}
SPECTRUM_DOCS["{layout}"] = (
    "layout : SlabLayout\n    The layout "
    "(:class:`~warptrunc.contact.sharded.fft.SlabLayout`).\n" + SPECTRUM_DOCS["{pixel_modulus}"]
)
"""The parameter text of this module's functions (:func:`~warptrunc._support.docs.fill_doc`)."""


@fill_doc(SPECTRUM_DOCS)
def build_spectrum(layout: Any, pixel_size: tuple[float, float], contact_modulus: float):
    """The kernel spectrum W's rows 0 … Ny//2 in column slabs (module docstring).

    Parameters
    ----------
    {layout}

    Returns
    -------
    (Ny//2 + 1, nkp) jax array
        W (m/N) in the layout's dtype, column slabs; the padded columns (beyond Nx//2) hold 1.
    """
    w = spectrum_programme(layout, pixel_size, contact_modulus)()
    big_y, _, _, nkp = layout.grid_shape
    assert w.shape == (big_y // 2 + 1, nkp)
    return w


@fill_doc(SPECTRUM_DOCS)
def spectrum_programme(layout: Any, pixel_size: tuple[float, float], contact_modulus: float):
    """The jitted programme that builds the kernel spectrum (:func:`build_spectrum` calls it;
    ``.lower().compile().memory_analysis()`` gives XLA's memory of the build without running
    it).

    Parameters
    ----------
    {layout}

    Returns
    -------
    callable
        ``jax.jit`` of a function of no arguments returning W (:func:`build_spectrum`).
    """
    jax, jnp = layout.jax, layout.jnp
    lax = jax.lax
    shard_map = _shard_map(jax)
    ny, nx = layout.shape
    big_y, _, nk, nkp = layout.grid_shape
    dx, dy = float(pixel_size[0]), float(pixel_size[1])
    area = dx * dy
    n_dev = len(layout.devices)
    out = layout.np_dtype
    rows_half = big_y // 2 + 1
    r, c = layout.row_spec, layout.col_spec

    if layout.substrate == "periodic":

        def periodic():
            fx = jnp.arange(nkp, dtype=jnp.float64)[None, :] / (nx * dx)
            fy = jnp.arange(rows_half, dtype=jnp.float64)[:, None] / (ny * dy)
            stiff = math.pi * contact_modulus * jnp.hypot(fx, fy)
            zero = math.pi * contact_modulus * (1 / (nx * dx) + 1 / (ny * dy)) / 2
            stiff = stiff.at[0, 0].set(zero)
            w = 1.0 / (stiff * area)  # the padded columns: 1 (K⁻¹ divides by W; data zero)
            return jnp.where(jnp.arange(nkp)[None, :] < nk, w, 1.0).astype(out)

        return jax.jit(periodic, out_shardings=layout.cols)

    piece_rows, _, n_rows = _row_layout(ny, nx, n_dev)

    def x_stage(j):  # (slab, 1) quadrant row numbers → x transform of the x-mirrored rows
        xs = jnp.arange(nx + 1, dtype=jnp.float64)[None, :] * dx

        def piece(jp):
            quad = _love(xs, jp.astype(jnp.float64) * dy, dx / 2, dy / 2, contact_modulus, xp=jnp)
            row = jnp.concatenate([quad, quad[:, nx - 1 : 0 : -1]], axis=1)  # 2nx
            return jnp.pad(jnp.fft.rfft(row, axis=1).real, ((0, 0), (0, nkp - nk)))

        n = j.shape[0] // piece_rows
        if n == 1:
            return piece(j)
        return lax.map(piece, j.reshape(n, piece_rows, 1)).reshape(j.shape[0], nkp)

    def y_stage(a):  # (n_rows, slab) → y transform of the y-mirrored columns, the dtype
        cols = a.shape[1]
        first = lax.axis_index("d") * cols  # this slab's first column of the half spectrum

        def piece(p, j0):
            p = p[: ny + 1]
            col = jnp.concatenate([p, p[ny - 1 : 0 : -1]], axis=0)  # 2ny
            w = jnp.fft.rfft(col, axis=0).real / area
            k = first + j0 + jnp.arange(p.shape[1])[None, :]
            return jnp.where(k < nk, w, 1.0).astype(out)

        b = _pieces(cols, 2 * ny * 8, cols)
        if b >= cols:
            return piece(a, 0)

        def block(i, acc):  # the last block overlaps the one before: the same values
            j0 = jnp.minimum(i * b, cols - b)
            w = piece(lax.dynamic_slice_in_dim(a, j0, b, axis=1), j0)
            return lax.dynamic_update_slice_in_dim(acc, w, j0, axis=1)

        acc = jnp.zeros_like(a[:rows_half], dtype=out)  # varying over the devices, as the pieces
        return lax.fori_loop(0, -(-cols // b), block, acc)

    def build():
        j = lax.with_sharding_constraint(jnp.arange(n_rows)[:, None], layout.rows)
        a = shard_map(x_stage, mesh=layout.mesh, in_specs=r, out_specs=r)(j)
        a = lax.with_sharding_constraint(a, layout.cols)  # all-to-all (XLA)
        return shard_map(y_stage, mesh=layout.mesh, in_specs=c, out_specs=c)(a)

    return jax.jit(build, out_shardings=layout.cols)


@fill_doc(SPECTRUM_DOCS)
def unit_force_check(hs: Any, pixel_size: tuple[float, float], contact_modulus: float) -> float:
    """Check the spread convolution against a closed form: a unit force on the centre pixel.

    The displacement under the force, u = K·e, is Love's coefficient of the pixel itself
    divided by the pixel's area (free half-space: the zero-padded circulant reproduces the
    linear convolution exactly), or the mean of the periodic spectrum over the whole grid (the
    inverse transform at the origin, summed without an FFT). One convolution, made once per
    layout, pixel size and modulus. It guards against a transform library that returns wrong
    numbers silently at some size: XLA's GPU FFT left inverse transforms of 2³¹ elements
    unscaled (openxla/xla#45009), which made a 65536² solve 131072 times too compliant.

    Parameters
    ----------
    hs : ShardedHalfSpace
        The half-space (:class:`~warptrunc.contact.sharded.fft.ShardedHalfSpace`).
    {pixel_modulus}

    Returns
    -------
    float
        The relative difference from the closed form (dimensionless).

    Raises
    ------
    RuntimeError
        The difference exceeds 10⁻³ (float32) or 10⁻⁸ (float64): the message gives both values.
    """
    lay = hs.layout
    jax, jnp = lay.jax, lay.jnp
    done = lay.steps.setdefault("unit_force_checked", {})
    key = (tuple(float(v) for v in pixel_size), float(contact_modulus))
    if key in done:
        return done[key]
    ny, nx = lay.shape
    i, j = ny // 2, nx // 2
    unit = jax.jit(
        lambda: jnp.zeros(lay.shape, lay.np_dtype).at[i, j].set(1), out_shardings=lay.rows
    )
    pick = jax.jit(lambda u: u[i, j], out_shardings=lay.replicated)
    got = float(host_array(pick(hs.apply(unit()))))
    dx, dy = (float(v) for v in pixel_size)
    if lay.substrate == "free":
        want = float(_love(0.0, 0.0, dx / 2, dy / 2, float(contact_modulus))) / (dx * dy)
    else:  # the mean over the whole grid of a spectrum even in x and y, from its half
        big_y, big_x, nk, nkp = lay.grid_shape
        wy = np.where(
            (np.arange(big_y // 2 + 1) == 0) | (2 * np.arange(big_y // 2 + 1) == big_y), 1.0, 2.0
        )
        c = np.arange(nkp)
        wx = np.where(c >= nk, 0.0, np.where((c == 0) | (2 * c == big_x), 1.0, 2.0))
        total = jax.jit(lambda w: jnp.sum(w.astype(jnp.float64) * wy[:, None] * wx[None, :]))
        want = float(host_array(total(hs.spectrum))) / (big_y * big_x)
    rel = abs(got - want) / abs(want)
    tol = 1e-3 if lay.np_dtype == np.float32 else 1e-8
    if not rel <= tol:
        raise RuntimeError(
            f"the contact solver's convolution over {len(lay.devices)} devices fails its check: "
            f"a unit force on pixel ({i}, {j}) of the {ny}×{nx} map ({lay.substrate}, "
            f"{lay.np_dtype.name}) gives u = {got:.6g} m, the closed form {want:.6g} m "
            f"(relative difference {rel:.3g} > {tol:g}); the FFT library returned wrong values "
            "at this size (see warptrunc.contact.sharded.grid.FFT_ELEMENTS_MAX)"
        )
    done[key] = rel
    return rel
