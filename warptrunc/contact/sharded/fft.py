# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The elastic half-space over several devices: JAX/XLA's sharded FFT and the row-slab layout
(:class:`ShardedHalfSpace`); the grid, its blocks and the per-device memory model are in
:mod:`~warptrunc.contact.sharded.grid`, the choice of devices in
:mod:`~warptrunc.contact.sharded.devices`.

Engine. JAX (``pip install "warptrunc[distributed]"``; imported only when a solver is spread
over several devices, never at ``import warptrunc``). One process drives the host's devices;
several processes (hosts) join through ``jax.distributed`` when
:data:`~warptrunc.contact.sharded.grid.PROCESS_ENV` is set, each putting its own slabs. It was
chosen over
cuFFTMp (nvmath-python) because it is in the GPU image and needs no MPI ranks; the cuFFTMp
runtime wheel (about 205 MB) is not.

Layout. The (ny, nx) maps are split in D equal slabs of rows (``ny`` a multiple of D), one per
device (``PartitionSpec("d", None)``). The padded convolution of a map is, as on one device
(:mod:`warptrunc.contact.transforms`), pruned: a real FFT along x of the map's rows (length Nx =
2nx free, nx periodic; local to each slab), the half spectrum's Nx//2 + 1 columns padded to a
multiple of D, a *sharding constraint* to column slabs (``PartitionSpec(None, "d")``; XLA turns
it into one all-to-all), the zero rows of the pad appended (free), the FFT along y (local), the
kernel spectrum W (held in column slabs, rows 0 … Ny//2, mirrored in y on the fly), the inverse
FFT along y keeping the map's ny rows, a sharding constraint back to row slabs (the second
all-to-all) and the inverse real FFT along x. The local FFTs run inside ``shard_map`` so that XLA
sees them as per-slab work (without it XLA's sharding propagation gathers whole maps); the
transposes are XLA's own: no hand-written all-to-all (``tests/test_sharded.py`` checks the
compiled programme: two all-to-alls, no all-gather).

The kernel spectrum W (:mod:`warptrunc.contact.sharded.spectrum`) is the one-device solver's
(:func:`~warptrunc.contact.influence.build_free_spectrum`): Love's coefficients mirrored in x, the x transform, then mirrored in y
and the y transform, in float64 on the devices (the x stage in row slabs, the y stage in column
slabs), rounded to the dtype; the periodic W is its closed form.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from ..._support.docs import fill_doc
from ..influence import GRID_DOCS
from .grid import _grid, _shard_map, column_blocks, import_jax, row_blocks

__all__ = [
    "ShardedHalfSpace",
    "SlabLayout",
    "slab_layout",
]


class SlabLayout:
    """The row-slab layout of a map over several JAX devices and its padded convolution.

    One per (shape, substrate, dtype, devices) (:func:`slab_layout` caches them), so that the
    solvers of one layout share their compiled programmes (``steps``); it holds no map.

    Parameters
    ----------
    shape : (int, int)
        Map size (ny, nx); ny a multiple of the number of devices.
    substrate : {"free", "periodic"}
        Zero-padded isolated patch or periodic map.
    dtype : {"float64", "float32"}
        Precision of the maps and transforms.
    devices : tuple of jax Device
        The devices, one row slab each (two or more).
    blocks : int, optional
        Blocks the column stage runs in (default 1;
        :func:`~warptrunc.contact.sharded.grid.column_blocks`).
    """

    def __init__(
        self,
        shape: tuple[int, int],
        substrate: str,
        dtype: str,
        devices: tuple[Any, ...],
        blocks: int = 1,
    ) -> None:
        jax = import_jax()
        import jax.numpy as jnp
        from jax.sharding import Mesh, NamedSharding
        from jax.sharding import PartitionSpec as P

        self.jax, self.jnp = jax, jnp
        self.shape = (int(shape[0]), int(shape[1]))
        self.substrate, self.dtype = substrate, dtype
        self.devices = list(devices)
        self.blocks = max(1, int(blocks))
        n_dev = len(self.devices)
        self.mesh = Mesh(np.array(self.devices, dtype=object), ("d",))
        self.row_spec, self.col_spec = P("d", None), P(None, "d")
        self.rows = NamedSharding(self.mesh, self.row_spec)
        self.cols = NamedSharding(self.mesh, self.col_spec)
        self.replicated = NamedSharding(self.mesh, P())
        self.grid_shape = _grid(self.shape, substrate, n_dev)
        big_y, big_x, _, _ = self.grid_shape
        self.n_total = big_y * big_x
        self.np_dtype = np.dtype(dtype)
        # donation reuses the state's buffers on accelerators (the CPU client warns and copies)
        self.donate = self.devices[0].platform != "cpu"
        self.steps: dict[str, Any] = {}  # the solver's jitted steps (sharded_steps.make_step)

    # --- the transforms (pure functions, for jax.jit) -------------------------------------

    def _stages(self):
        """The three local stages (x transform, y transform with W, inverse x transform)."""
        jnp = self.jnp
        ny, nx = self.shape
        big_y, big_x, nk, nkp = self.grid_shape
        slab = ny // len(self.devices)
        k = row_blocks(slab, big_x)  # FFT calls within FFT_ELEMENTS_MAX (openxla/xla#45009)

        def in_row_blocks(fn, x):
            if k == 1:
                return fn(x)
            out = self.jax.lax.map(fn, x.reshape(k, slab // k, x.shape[1]))
            return out.reshape(slab, out.shape[2])

        def rows_forward(x):
            s = in_row_blocks(lambda a: jnp.fft.rfft(a, n=big_x, axis=1), x)
            return jnp.pad(s, ((0, 0), (0, nkp - nk)))

        def columns_piece(s, w_half, inverse):
            if big_y > ny:
                s = jnp.pad(s, ((0, big_y - ny), (0, 0)))
            s = jnp.fft.fft(s, axis=0)
            mirror = w_half[1 : big_y - big_y // 2][::-1]
            w = jnp.concatenate([w_half, mirror], axis=0)
            s = s / w if inverse else s * w
            return jnp.fft.ifft(s, axis=0)[:ny]

        def columns(s, w_half, inverse):
            if self.blocks == 1:
                return columns_piece(s, w_half, inverse)
            lax = self.jax.lax
            c = s.shape[1]
            b = -(-c // self.blocks)

            def block(i, out):  # the last block overlaps the one before: same values
                j = jnp.minimum(i * b, c - b)
                piece = columns_piece(
                    lax.dynamic_slice_in_dim(s, j, b, axis=1),
                    lax.dynamic_slice_in_dim(w_half, j, b, axis=1),
                    inverse,
                )
                return lax.dynamic_update_slice_in_dim(out, piece, j, axis=1)

            return lax.fori_loop(0, self.blocks, block, jnp.zeros_like(s[:ny]))

        def rows_inverse(s):
            def inverse(a):
                return jnp.fft.irfft(a[:, :nk], n=big_x, axis=1)[:, :nx].astype(self.np_dtype)

            return in_row_blocks(inverse, s)

        return rows_forward, columns, rows_inverse

    def conv(self, x, w_half, inverse: bool = False):
        """K·x (or K⁻¹·x) of a row-sharded map, inside ``jax.jit``.

        Parameters
        ----------
        x : (ny, nx) jax array
            Pixel forces (N), or displacements (m) with ``inverse``; row slabs.
        w_half : (Ny//2 + 1, nkp) jax array
            The kernel spectrum
            (:meth:`~warptrunc.contact.sharded.fft.SlabLayout.build_spectrum`), column slabs.
        inverse : bool, optional
            False: K·x (m); True: K⁻¹·x (N).

        Returns
        -------
        (ny, nx) jax array
            The map, row slabs, in the dtype.
        """
        jax = self.jax
        shard_map = _shard_map(jax)
        rows_forward, columns, rows_inverse = self._stages()
        r, c = self.row_spec, self.col_spec
        s = shard_map(rows_forward, mesh=self.mesh, in_specs=r, out_specs=r)(x)
        s = jax.lax.with_sharding_constraint(s, self.cols)  # all-to-all (XLA)
        s = shard_map(
            lambda a, w: columns(a, w, inverse), mesh=self.mesh, in_specs=(c, c), out_specs=c
        )(s, w_half)
        s = jax.lax.with_sharding_constraint(s, self.rows)  # all-to-all (XLA)
        return shard_map(rows_inverse, mesh=self.mesh, in_specs=r, out_specs=r)(s)

    def apply(self, x, w_half, *, inverse: bool = False):
        """Apply K (or K⁻¹) to a row-sharded map (one jitted convolution).

        Parameters
        ----------
        x : (ny, nx) jax array
            Pixel forces (N), or displacements (m) with ``inverse``; row slabs.
        w_half : (Ny//2 + 1, nkp) jax array
            The kernel spectrum (:meth:`build_spectrum`).
        inverse : bool, optional
            False: K·x (m); True: K⁻¹·x (N).

        Returns
        -------
        (ny, nx) jax array
            The map, row slabs.
        """
        key = "apply_inverse" if inverse else "apply"
        fn = self.steps.get(key)
        if fn is None:
            fn = self.jax.jit(lambda a, w: self.conv(a, w, inverse), out_shardings=self.rows)
            self.steps[key] = fn
        return fn(x, w_half)

    def put(self, array: np.ndarray, dtype: Any = None):
        """Copy a host map to the devices in row slabs.

        Parameters
        ----------
        array : (ny, nx) ndarray
            The map (any units).
        dtype : numpy dtype, optional
            Its dtype on the devices (default the half-space's).

        Returns
        -------
        (ny, nx) jax array
            Row slabs.
        """
        a = np.ascontiguousarray(array, dtype=self.np_dtype if dtype is None else dtype)
        # each process (host) puts its own slabs: the same call over one or several processes
        return self.jax.make_array_from_callback(a.shape, self.rows, lambda index: a[index])

    def zeros(self, dtype: Any = None):
        """A zeroed map in row slabs, made on the devices.

        Parameters
        ----------
        dtype : numpy dtype, optional
            Default the layout's.

        Returns
        -------
        (ny, nx) jax array
            Zeros, row slabs.
        """
        return self.full(0, dtype)

    def full(self, value: Any, dtype: Any = None):
        """A map of one value in row slabs, made on the devices (one jitted programme per
        dtype, made once).

        Parameters
        ----------
        value : scalar
            The value (units of the map).
        dtype : numpy dtype, optional
            Default the layout's.

        Returns
        -------
        (ny, nx) jax array
            The map, row slabs.
        """
        dt = self.np_dtype if dtype is None else np.dtype(dtype)
        key = f"full_{dt.name}"
        fn = self.steps.get(key)
        if fn is None:
            jnp = self.jnp
            fn = self.jax.jit(lambda v: jnp.full(self.shape, v, dt), out_shardings=self.rows)
            self.steps[key] = fn
        return fn(value)

    # --- the kernel spectrum ----------------------------------------------------------------

    def build_spectrum(self, pixel_size: tuple[float, float], contact_modulus: float):
        """The kernel spectrum W's rows 0 … Ny//2 in column slabs
        (:func:`~warptrunc.contact.sharded.spectrum.build_spectrum`).

        Parameters
        ----------
        pixel_size : (float, float)
            Pixel sides (dx, dy) (m).
        contact_modulus : float
            Contact modulus E* (Pa).

        Returns
        -------
        (Ny//2 + 1, nkp) jax array
            W (m/N) in the dtype, column slabs; the padded columns (beyond Nx//2) hold 1.
        """
        from .spectrum import build_spectrum

        return build_spectrum(self, pixel_size, contact_modulus)


@functools.lru_cache(maxsize=16)
@fill_doc(GRID_DOCS)
def slab_layout(
    shape: tuple[int, int], substrate: str, dtype: str, devices: tuple[Any, ...], blocks: int = 1
) -> SlabLayout:
    """The layout of these arguments, made once (its compiled programmes are shared).

    Parameters
    ----------
    {shape}
    {substrate}
    {dtype}
    devices : tuple of jax Device
        The devices.
    blocks : int, optional
        Blocks of the column stage (default 1).

    Returns
    -------
    SlabLayout
        The layout.
    """
    return SlabLayout(shape, substrate, dtype, devices, blocks)


class ShardedHalfSpace:
    """Pixel-force → displacement operator K of an elastic half-space over several JAX devices:
    a :class:`SlabLayout` and the kernel spectrum.

    Parameters
    ----------
    shape : (int, int)
        Map size (ny, nx); ny a multiple of the number of devices.
    pixel_size : (float, float)
        Pixel sides (dx, dy) (m).
    contact_modulus : float
        Contact modulus E* (Pa).
    substrate : {"free", "periodic"}
        Zero-padded isolated patch or periodic map.
    dtype : {"float64", "float32"}
        Precision of the maps and transforms.
    devices : list of jax Device
        The devices, one row slab each (two or more).

    Notes
    -----
    The layout's attributes (``jax``, ``jnp``, ``rows``, ``np_dtype``, ``conv``, ``put``,
    ``zeros``, ...) are the half-space's too.
    """

    def __init__(
        self,
        shape: tuple[int, int],
        pixel_size: tuple[float, float],
        contact_modulus: float,
        *,
        substrate: str,
        dtype: str,
        devices: list[Any],
    ) -> None:
        shape = (int(shape[0]), int(shape[1]))
        blocks = column_blocks(shape, substrate, dtype, len(devices))
        self.layout = slab_layout(shape, substrate, dtype, tuple(devices), blocks)
        self.spectrum = self.layout.build_spectrum(pixel_size, float(contact_modulus))
        from .spectrum import unit_force_check

        self.check = unit_force_check(self, pixel_size, float(contact_modulus))

    def __getattr__(self, name: str) -> Any:
        if name == "layout":
            raise AttributeError(name)
        return getattr(self.layout, name)

    def apply(self, x, *, inverse: bool = False):
        """Apply K (or K⁻¹) to a row-sharded map.

        Parameters
        ----------
        x : (ny, nx) jax array
            Pixel forces (N), or displacements (m) with ``inverse``; row slabs.
        inverse : bool, optional
            False: K·x (m); True: K⁻¹·x (N).

        Returns
        -------
        (ny, nx) jax array
            The map, row slabs.
        """
        return self.layout.apply(x, self.spectrum, inverse=inverse)
