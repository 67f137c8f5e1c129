# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The contact solver for a map on the devices asked: :func:`contact_solver`.

One device: :class:`~warptrunc.contact.ContactSolver`; several (a count, a list, or
``"auto"`` when the map does not fit one): its subclass
:class:`~warptrunc.contact.sharded.ShardedContactSolver`, whose map is split in row slabs over
JAX devices. Every entry point that takes a ``devices`` argument (``solve_contact``,
``bem_check``, ``compare``, ``indent``, ``sweep``) makes its solver here.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .settings import SolverSettings
from .solver import ContactSolver

__all__ = ["contact_solver"]


def contact_solver(
    heights: Any,
    pixel_size: Any,
    contact_modulus: float,
    *,
    settings: SolverSettings | None = None,
    hardness: float = math.inf,
    device: Any = None,
    devices: Any = None,
) -> ContactSolver:
    """A contact solver of ``heights`` on one device or spread over several.

    Parameters
    ----------
    heights : (ny, nx) array_like
        Heights z (m) of the rough surface; a finite 2-D map (ny a multiple of the device count
        when spread).
    pixel_size : float or (float, float)
        Pixel sides (dx, dy) (m).
    contact_modulus : float
        Contact modulus E* (Pa).
    settings : SolverSettings, optional
        Solver settings (default ``SolverSettings()``); an adhesion law runs on one device.
    hardness : float
        Hardness H (Pa), the local pressure cap, in (0, inf]; ``inf`` (default): elastic.
    device : str or warp Device, optional
        The Warp device of a one-device solver (default: CUDA if present).
    devices : list, int or "auto", optional
        JAX devices or their names (``["cuda:0", "cuda:1"]``), a count (the first N devices of
        JAX's default backend), or ``"auto"``: ``device`` when the solver fits it, else the
        fewest devices that fit (:func:`~warptrunc.contact.sharded.devices.choose_devices`).
        None (default), one device or a list of one: the one-device solver.

    Returns
    -------
    ContactSolver
        A :class:`~warptrunc.contact.ContactSolver`, or a
        :class:`~warptrunc.contact.sharded.ShardedContactSolver` (a subclass; JAX,
        ``warptrunc[distributed]``) for two or more devices.

    Raises
    ------
    ValueError
        A bad ``devices`` (the message names the value and what is allowed), an adhesion law
        over several devices, and what the solver refuses.
    ImportError
        Several devices without JAX.
    MemoryError
        When the solver's memory exceeds the free memory, before anything is allocated.
    """
    kw = {"settings": settings, "hardness": hardness, "device": device, "devices": devices}
    if devices is not None:
        from .sharded.devices import choose_devices

        if choose_devices(devices, np.shape(heights), settings, device) is not None:
            from .sharded.solver import ShardedContactSolver  # it refuses an adhesion law

            return ShardedContactSolver(heights, pixel_size, contact_modulus, **kw)
    return ContactSolver(heights, pixel_size, contact_modulus, **kw)
