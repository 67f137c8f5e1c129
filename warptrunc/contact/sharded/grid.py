# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The grid of a contact solve spread over several devices, without JAX: the padded grid and its
slabs, the blocks and pieces its transforms run in (:data:`FFT_ELEMENTS_MAX`,
:func:`row_blocks`, :func:`column_blocks`, :data:`BUILD_PIECE_BYTES`), the per-device memory
model (:func:`sharded_memory_terms`, :func:`build_bytes`, :func:`sharded_memory_bytes`), and the
import of JAX itself (:func:`import_jax`), made only when a solve is spread. The modules that run
the spread solve (:mod:`~warptrunc.contact.sharded.fft`,
:mod:`~warptrunc.contact.sharded.spectrum`, :mod:`~warptrunc.contact.sharded.devices`) take
these from here.
"""

from __future__ import annotations

import numpy as np

from ..._support.docs import fill_doc
from ..influence import GRID_DOCS

__all__ = [
    "BLOCKS_ABOVE",
    "BUILD_PIECE_BYTES",
    "COLUMN_BLOCKS",
    "FFT_ELEMENTS_MAX",
    "PROCESS_ENV",
    "SHARDED_DOCS",
    "build_bytes",
    "column_blocks",
    "devices_needed",
    "host_array",
    "import_jax",
    "row_blocks",
    "sharded_memory_bytes",
    "sharded_memory_terms",
]


def import_jax():
    """JAX with 64-bit types enabled (the maps may be float64 and the sums are float64).

    Returns
    -------
    module
        The ``jax`` module.

    Raises
    ------
    ImportError
        JAX is not installed; the message gives the install line.
    """
    try:
        import jax
    except ImportError as exc:
        raise ImportError(
            f"a contact solve over several devices needs JAX ({exc}); install it with: "
            'pip install "warptrunc[distributed]" (on CUDA machines: pip install "jax[cuda12]")'
        ) from exc
    if not jax.config.jax_enable_x64:
        jax.config.update("jax_enable_x64", True)
    _join_processes(jax)
    return jax


PROCESS_ENV = ("WARPTRUNC_COORDINATOR", "WARPTRUNC_NUM_PROCESSES", "WARPTRUNC_PROCESS_ID")
"""Environment of a solve spread over several processes (hosts): the coordinator's
``host:port``, the number of processes and this one's index (0 … n − 1). Where the first is set,
the first JAX import joins them (``jax.distributed.initialize``); every process then runs the
same command on the same map, ``jax.devices()`` lists the devices of all of them, and a solve's
``devices=N`` counts over all of them."""


def _join_processes(jax) -> None:
    """``jax.distributed.initialize`` from :data:`PROCESS_ENV`, once (host devices: Gloo's
    collectives)."""
    import os

    address = os.environ.get(PROCESS_ENV[0], "").strip()
    if not address or getattr(_join_processes, "done", False):
        return
    try:
        n, rank = int(os.environ[PROCESS_ENV[1]]), int(os.environ[PROCESS_ENV[2]])
    except (KeyError, ValueError):
        raise ValueError(
            f"{PROCESS_ENV[0]}={address!r} needs {PROCESS_ENV[1]} (a count ≥ 1) and "
            f"{PROCESS_ENV[2]} (0 … count − 1) set as integers"
        ) from None
    if os.environ.get("JAX_PLATFORMS", "").strip() == "cpu":
        jax.config.update("jax_cpu_collectives_implementation", "gloo")
    jax.distributed.initialize(address, num_processes=n, process_id=rank)
    _join_processes.done = True


def host_array(x) -> np.ndarray:
    """A JAX array as a NumPy array on this host: the whole map, gathered from the other
    processes where they hold part of it (``process_allgather``).

    Parameters
    ----------
    x : jax array
        Any array (row slabs, replicated, a scalar).

    Returns
    -------
    ndarray
        Its values.
    """
    if getattr(x, "is_fully_addressable", True) or getattr(x, "is_fully_replicated", False):
        return np.asarray(x)
    from jax.experimental import multihost_utils

    return np.asarray(multihost_utils.process_allgather(x, tiled=True))


def _shard_map(jax):
    """``jax.shard_map`` (JAX ≥ 0.7) or ``jax.experimental.shard_map.shard_map`` before."""
    fn = getattr(jax, "shard_map", None)
    if fn is not None:
        return fn
    from jax.experimental.shard_map import shard_map

    def compat(f, *, mesh, in_specs, out_specs):
        return shard_map(f, mesh, in_specs=in_specs, out_specs=out_specs, check_rep=False)

    return compat


def _grid(shape: tuple[int, int], substrate: str, n_dev: int) -> tuple[int, int, int, int]:
    """(Ny, Nx, nk, nkp): the padded grid, its half spectrum's columns and those padded to a
    multiple of ``n_dev``."""
    ny, nx = shape
    big_y, big_x = (2 * ny, 2 * nx) if substrate == "free" else (ny, nx)
    nk = big_x // 2 + 1
    return big_y, big_x, nk, -(-nk // n_dev) * n_dev


COLUMN_BLOCKS = 4
"""Blocks of columns the y transforms of a large column slab run in, one after another (a
``fori_loop``), so that XLA holds one block's padded transform at a time: the convolution's
temporary memory drops from 2.5 to 1.5 padded half spectra of the slab (the CPU compile)."""

BLOCKS_ABOVE = 1 << 28
"""Bytes of a device's padded half spectrum above which its column stage runs in
``COLUMN_BLOCKS`` blocks (below, in one piece)."""


FFT_ELEMENTS_MAX = 1 << 30
"""Most elements one FFT call of a device may hold (input or output, batch included). XLA's GPU
FFT scales an inverse transform's output with cuBLAS, whose element count is a 32-bit int: at
2³¹ elements or more the scaling is skipped and the result is N times too large
(openxla/xla#45009, open in JAX 0.11.2). A 65536² map over 4 GPUs hit it exactly (16384 rows of
131072 padded columns per device): its loads came out about 10⁵ times too small. Transforms
that would hold more run in blocks (:func:`row_blocks`, :func:`column_blocks`)."""


def row_blocks(rows: int, length: int) -> int:
    """Blocks the row transforms of a slab run in: 1, or the fewest that divide ``rows`` and
    keep each FFT call within :data:`FFT_ELEMENTS_MAX` elements.

    Parameters
    ----------
    rows : int
        Rows of the slab (count).
    length : int
        Transform length along the rows, padding included (count).

    Returns
    -------
    int
        The number of blocks (dimensionless), a divisor of ``rows``.
    """
    need = -(-rows * length // FFT_ELEMENTS_MAX)
    if need <= 1:
        return 1
    return next(k for k in range(need, rows + 1) if rows % k == 0)


SHARDED_DOCS = {**GRID_DOCS, "{n_devices}": "n_devices : int\n    Devices (dimensionless count)."}
"""The sharded layout's shared parameter text (:func:`~warptrunc._support.docs.fill_doc`)."""


@fill_doc(SHARDED_DOCS)
def column_blocks(shape: tuple[int, int], substrate: str, dtype: str, n_devices: int) -> int:
    """Blocks of the column stage of a layout (``COLUMN_BLOCKS`` or 1, by ``BLOCKS_ABOVE``; more
    where a block's transform would exceed :data:`FFT_ELEMENTS_MAX` elements).

    Parameters
    ----------
    {shape}
    {substrate}
    {dtype}
    {n_devices}

    Returns
    -------
    int
        The number of blocks (dimensionless).
    """
    big_y, _, _, nkp = _grid(shape, substrate, n_devices)
    spectrum = big_y * (nkp // n_devices) * 2 * np.dtype(dtype).itemsize
    blocks = COLUMN_BLOCKS if spectrum > BLOCKS_ABOVE else 1
    return max(blocks, -(-big_y * (nkp // n_devices) // FFT_ELEMENTS_MAX))


@fill_doc(SHARDED_DOCS)
def sharded_memory_terms(
    shape: tuple[int, int], substrate: str, dtype: str, n_devices: int
) -> dict[str, int]:
    """Bytes one device holds for a solve spread over ``n_devices`` (the model; measured peaks:
    ``examples/benchmarks/benchmark_sharded.py``).

    Parameters
    ----------
    {shape}
    {substrate}
    {dtype}
    {n_devices}

    Returns
    -------
    dict of str to int
        Per device: ``"maps"``: h, q, u, t, the BCCG residual r, the preconditioned residual z
        and the last and new z − mean (eight slabs of the dtype; Barber's punch reuses them);
        ``"mask"``: one byte per pixel of the slab; ``"kernel spectrum"``: its rows 0 … Ny//2 in
        a column slab; ``"fft work (XLA)"``: the convolution's buffers, 2.5 padded half spectra
        of the slab, 1.5 when the column stage runs in blocks (:func:`column_blocks`; XLA's
        temporary memory of one convolution compiled for the CPU: ``tests/test_sharded.py``); ``"step temporaries"``: three float64 slabs, the rest of a
        CG step's temporary memory (its float64 intermediates; the CPU compile needs 0–3);
        float64 only, ``"step results"``: three more slabs, the CG step's results for t, q and u
        beside its donated arguments (measured on 2 × H200 at 32768²: the peak, 90.74 GB, is the
        step's compiled arguments, results and temporaries plus the maps held beside them, as
        if XLA's 12.88 GB of aliased results did not reuse their arguments; float32 peaks lie
        12–15 % under the model without this term).
    """
    ny, nx = shape
    item = np.dtype(dtype).itemsize
    big_y, _, _, nkp = _grid(shape, substrate, n_devices)
    slab = -(-ny // n_devices) * nx
    cols = nkp // n_devices
    blocks = column_blocks(shape, substrate, dtype, n_devices)
    return {
        "maps": 8 * slab * item,
        "mask": slab,
        "kernel spectrum": (big_y // 2 + 1) * cols * item,
        # 2.5 (1.5 in blocks) complex spectra of the slab
        "fft work (XLA)": (3 if blocks > 1 else 5) * big_y * cols * item,
        "step temporaries": 3 * slab * 8,
        **({"step results": 3 * slab * item} if item == 8 else {}),
    }


BUILD_PIECE_BYTES = 1 << 28
"""Float64 input bytes of one piece of the spectrum's build (256 MiB): the x stage's rows
(2·nx each) and the y stage's columns (2·ny each) are taken in blocks of at most this many
bytes."""


def _pieces(length: int, per_item_bytes: int, count: int) -> int:
    """Items per piece: at most ``count``, at least one, within :data:`BUILD_PIECE_BYTES`."""
    return int(max(1, min(count, BUILD_PIECE_BYTES // max(1, per_item_bytes))))


def _row_layout(ny: int, nx: int, n_dev: int) -> tuple[int, int, int]:
    """(rows per piece, rows per device, rows in all) of the free x stage: quadrant rows
    0 … ny, padded so that every device holds a whole number of pieces."""
    per_dev = -(-(ny + 1) // n_dev)
    piece = _pieces(ny + 1, 2 * nx * 8, per_dev)
    slab = -(-per_dev // piece) * piece
    return piece, slab, slab * n_dev


@fill_doc(SHARDED_DOCS)
def build_bytes(shape: tuple[int, int], substrate: str, dtype: str, n_devices: int) -> int:
    """Peak bytes one device holds while the spectrum is built (the model).

    Parameters
    ----------
    {shape}
    {substrate}
    {dtype}
    {n_devices}

    Returns
    -------
    int
        Bytes: W's column slab, and for the free half-space three float64 slabs of the x
        stage's result (in row slabs, in column slabs, and XLA's staging of the all-to-all
        between them: the CPU compile), plus four float64 pieces of at most
        :data:`BUILD_PIECE_BYTES` (a piece's input, its transform, the mirrored copy, the
        result); for the periodic one, two float64 copies of W's slab.
    """
    ny, nx = shape
    big_y, _, _, nkp = _grid(shape, substrate, n_devices)
    cols = nkp // n_devices
    w = (big_y // 2 + 1) * cols * np.dtype(dtype).itemsize
    if substrate == "periodic":
        return int(w + 2 * (big_y // 2 + 1) * cols * 8)
    _, slab_rows, n_rows = _row_layout(ny, nx, n_devices)
    x_slab = max(slab_rows * nkp, n_rows * cols) * 8
    return int(w + 3 * x_slab + 4 * min(BUILD_PIECE_BYTES, x_slab))


@fill_doc(SHARDED_DOCS)
def sharded_memory_bytes(shape: tuple[int, int], substrate: str, dtype: str, n_devices: int) -> int:
    """Peak bytes one device holds for a solve spread over ``n_devices`` (the model).

    Parameters
    ----------
    {shape}
    {substrate}
    {dtype}
    {n_devices}

    Returns
    -------
    int
        The larger of the solve's terms summed (:func:`sharded_memory_terms`) and the kernel
        spectrum's build, which comes first and alone (:func:`build_bytes`) (B).
    """
    steady = sum(sharded_memory_terms(shape, substrate, dtype, n_devices).values())
    return int(max(steady, build_bytes(shape, substrate, dtype, n_devices)))


@fill_doc(SHARDED_DOCS)
def devices_needed(
    shape: tuple[int, int], substrate: str, dtype: str, free_bytes: int, limit: int = 64
) -> int | None:
    """The fewest devices of ``free_bytes`` each that hold a solve spread over them.

    Parameters
    ----------
    {shape}
    {substrate}
    {dtype}
    free_bytes : int
        Free memory of each device (B).
    limit : int, optional
        Largest count tried (dimensionless).

    Returns
    -------
    int or None
        The count (2 or more, dividing ny), or None when none up to ``limit`` suffices.
    """
    for n in range(2, limit + 1):
        if shape[0] % n == 0:
            need = sharded_memory_bytes(shape, substrate, dtype, n)
            if need <= free_bytes:
                return n
    return None
