# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The memory model of :class:`~warptrunc.contact.ContactSolver`: its peak device memory, term
by term (:func:`memory_terms`, :func:`memory_bytes`), and the check against the device's free
memory that chooses the cuFFT plans and refuses a map that does not fit, before anything is
allocated (:func:`fft_plan_that_fits`). The solver over several devices has its own per-device
terms (:func:`~warptrunc.contact.sharded.grid.sharded_memory_terms`).

``ContactSolver.memory_terms`` and ``ContactSolver.memory_bytes`` are these functions, named
again in the solver's class so that its reference page lists them.
"""

from __future__ import annotations

import numpy as np
import warp as wp

from .._support.device import free_memory_bytes, release_cached_memory
from .._support.docs import fill_doc
from .halfspace import ElasticHalfSpace
from .influence import GRID_DOCS
from .settings import SolverSettings

__all__ = ["fft_plan_that_fits", "memory_bytes", "memory_terms"]


@fill_doc(GRID_DOCS)
def memory_terms(
    shape: tuple[int, int],
    substrate: str = "free",
    dtype: str = "float64",
    *,
    cuda: bool = True,
    direct_max: int = 24,
    algorithm: str = "bccg",
    fft_plan: str = "pruned",
    device: wp.DeviceLike = None,
    adhesion: bool = False,
) -> dict[str, int]:
    """The model of a solver's peak device memory, term by term (bytes).

    Parameters
    ----------
    {shape}
    {substrate}
    dtype : {"float64", "float32"}
        Precision of the maps.
    cuda : bool, optional
        On a CUDA device (cuFFT's work area and 65536 reduction lanes are counted).
    direct_max : int, optional
        Length of the list of changed forces (dimensionless count).
    algorithm : {"pk", "bccg"}, optional
        The iteration (:class:`~warptrunc.contact.SolverSettings`; default ``"bccg"``, its
        default); ``"bccg"`` holds one more map, its residual.
    fft_plan : {"pruned", "full"}, optional
        The half-space's cuFFT plans (``SolverSettings.fft_plan``; ``"full"`` counts a cuFFT
        work area as large as the work spectrum, free substrate on CUDA).
    device : str or warp Device, optional
        A CUDA device: cuFFT's work area is the one cuFFT asks for the plans
        (``ElasticHalfSpace.cufft_work_bytes``) instead of the estimate.
    adhesion : bool, optional
        An adhesion law (:class:`~warptrunc.contact.adhesion.Adhesion`): two more maps, the
        law's forces and the original heights.

    Returns
    -------
    dict of str to int
        The half-space's terms (:meth:`~warptrunc.contact.ElasticHalfSpace.memory_terms`:
        kernel spectrum, influence table, work spectrum, lane partials, cuFFT work area) and
        the solver's: ``"maps"``: h, u, q, t and q_lin (five (ny, nx) maps of the dtype; q
        and t hold no pad); ``"mask"``: one byte per pixel; ``"lists"``: the lane counts and
        offsets and the list of changed forces; ``"stiffness solve"``: the one more map
        Barber's punch needs (its residual; its unknown reuses q_lin's map). The peak is
        their sum, reached during :meth:`~warptrunc.contact.ContactSolver.punch_stiffness`;
        a solve needs all but the last term; with ``adhesion`` also ``"adhesion"``: the law's
        pixel forces and the original heights (two maps; the effective heights are h's map).
    """
    ny, nx = shape
    item = np.dtype(dtype).itemsize
    terms = ElasticHalfSpace.memory_terms(
        shape, substrate, dtype, cuda=cuda, fft_plan=fft_plan, device=device
    )
    lanes = 65536 if cuda else 64
    terms["maps"] = 5 * ny * nx * item
    terms["mask"] = ny * nx
    terms["lists"] = 2 * lanes * 4 + max(1, direct_max) * 12 + 8
    terms["stiffness solve"] = ny * nx * item
    if algorithm == "bccg":
        terms["bccg residual"] = ny * nx * item
    if adhesion:
        terms["adhesion"] = 2 * ny * nx * item
    return terms


@fill_doc(GRID_DOCS)
def memory_bytes(
    shape: tuple[int, int],
    substrate: str = "free",
    dtype: str = "float64",
    *,
    cuda: bool = True,
    algorithm: str = "bccg",
    fft_plan: str = "pruned",
    device: wp.DeviceLike = None,
    devices: int = 1,
    adhesion: bool = False,
) -> int:
    """Peak device memory of a solver and its stiffness solve (bytes; per device when spread).

    Parameters
    ----------
    {shape}
    substrate : {"free", "periodic"}
        Half-space (the free one transforms a 2ny × 2nx grid, pruned to the map).
    dtype : {"float64", "float32"}
        Precision of the maps.
    cuda : bool, optional
        On a CUDA device (default; cuFFT's work area counted).
    algorithm : {"pk", "bccg"}, optional
        The iteration (default ``"bccg"``, that of ``SolverSettings``); ``"bccg"`` holds one
        more map, its residual.
    fft_plan : {"pruned", "full"}, optional
        The half-space's cuFFT plans (``SolverSettings.fft_plan``); ``"full"`` adds a
        cuFFT work area as large as the work spectrum (free substrate on CUDA: + 16 B per
        map pixel in float32, + 32 in float64).
    device : str or warp Device, optional
        A CUDA device: cuFFT's work area as cuFFT asks for it, instead of the estimate.
    devices : int, optional
        Devices the map is spread over (``contact_solver(..., devices=n)``; dimensionless
        count, ≥ 1, default 1). Above 1: the bytes of one device, JAX's buffers included
        (:func:`~warptrunc.contact.sharded.grid.sharded_memory_bytes`; ``cuda``,
        ``algorithm``, ``fft_plan`` and ``device`` do not apply).
    adhesion : bool, optional
        With an adhesion law (one device only): two more maps (:func:`memory_terms`).

    Returns
    -------
    int
        The sum of :meth:`~warptrunc.contact.ContactSolver.memory_terms` (one device), or of
        the per-device terms (several). Per map pixel,
        free boundary, large maps: float32 4 (kernel spectrum) + 4 (table) + 16 (work
        spectrum) + ≤ 2 (cuFFT work area, estimated) + 20 (maps) + 1 (mask) + 4 (stiffness
        solve) + 4 (BCCG's residual) ≈ 55 B; float64 ≈ 109 B; periodic float32 ≈ 1 + 4 + 4
        + ≤ 0.5 + 20 + 1 + 4 + 4 ≈ 38.5 B. Without BCCG (``algorithm="pk"``) one map less;
        with adhesion two more (+ 8 B per pixel in float32, + 16 in float64).
    """
    if isinstance(devices, bool) or not isinstance(devices, int | np.integer) or devices < 1:
        raise ValueError(f"devices must be an integer ≥ 1, got {devices!r}")
    if devices > 1:
        if adhesion:
            raise ValueError("adhesion runs on one device: give devices=1")
        from .sharded.grid import sharded_memory_bytes

        return sharded_memory_bytes(shape, substrate, dtype, int(devices))
    terms = memory_terms(
        shape,
        substrate,
        dtype,
        cuda=cuda,
        algorithm=algorithm,
        fft_plan=fft_plan,
        device=device,
        adhesion=adhesion,
    )
    return int(sum(terms.values()))


def fft_plan_that_fits(
    device: wp.context.Device, shape: tuple[int, int], settings: SolverSettings
) -> str:
    """The half-space's cuFFT plans for a solver of a map of ``shape`` on ``device``, checked
    against the free memory.

    Parameters
    ----------
    device : warp Device
        The solver's device.
    shape : (int, int)
        Map size (ny, nx) (pixels).
    settings : SolverSettings
        Its ``substrate``, ``dtype``, ``algorithm``, ``fft_plan`` and ``adhesion`` (an adhesive
        law holds two more maps) are read.

    Returns
    -------
    str
        ``settings.fft_plan``; 'pruned' off CUDA and on the periodic substrate; for ``"auto"``,
        'full' when the solver then fits in the free memory, else 'pruned'.

    Raises
    ------
    MemoryError
        The solver does not fit with those plans (checked before anything is allocated;
        Warp's pooled blocks count as free on CUDA).
    """
    substrate, dtype = settings.substrate, settings.dtype
    cuda = device.is_cuda
    plan = settings.fft_plan if cuda and substrate == "free" else "pruned"

    def needs(p: str) -> int:  # with the work area cuFFT asks for, on CUDA
        return memory_bytes(
            shape,
            substrate,
            dtype,
            cuda=cuda,
            algorithm=settings.algorithm,
            fft_plan=p,
            device=device if cuda else None,
            adhesion=settings.adhesion.active,
        )

    free = free_memory_bytes(device)
    if plan == "auto":
        try:
            full = needs("full")
        except ValueError:  # cuFFT cannot make the 2-D plans at this size
            full = None
        if full is not None and full > free and cuda:
            free = release_cached_memory(device)
        plan = "full" if full is not None and full <= free else "pruned"
        need = full if plan == "full" else needs(plan)  # each plan made once to learn its size
    else:
        need = needs(plan)
    if need > free and cuda:
        free = release_cached_memory(device)  # pooled blocks are free for us too
    if need > free:
        from .sharded.grid import devices_needed

        spread = devices_needed(shape, substrate, dtype, free) if cuda else None
        hint = f", devices={spread} (that many such GPUs)" if spread else ""
        raise MemoryError(
            f"the contact solver for a {shape[0]}×{shape[1]} map ({substrate}, {dtype}, "
            f"fft_plan {plan!r}) needs {need / 1e9:.2f} GB, {free / 1e9:.2f} GB free on "
            f"{device} ({need} bytes needed, {free} free); use a smaller map, float32, "
            f"fft_plan='pruned', another device{hint}"
        )
    return plan
