# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Contact curves: :func:`solve_contact` runs a :class:`~warptrunc.contact.solver.ContactSolver`
over increasing approaches (or loads) and returns a :class:`~warptrunc.contact.results.ContactCurve`."""

from __future__ import annotations

import math
import time
from dataclasses import fields
from typing import Any

import numpy as np
import warp as wp

from .._support.docs import SHARED_DOCS, fill_doc
from .._support.validate import check_range
from ..material import Material
from ..params import check_value
from .results import ContactCurve
from .settings import SolverSettings
from .solver import ContactSolver

__all__ = ["STIFFNESS_METHODS", "solve_contact"]

STIFFNESS_METHODS = ("barber", "central", "none")


@fill_doc(SHARED_DOCS)
def solve_contact(
    heights: Any,
    depths: Any = None,
    *,
    loads: Any = None,
    pixel_size: Any = None,
    contact_modulus: float | None = None,
    material: Material | None = None,
    hardness: float | None = None,
    settings: SolverSettings | None = None,
    substrate: str = "free",
    dtype: str = "float64",
    stiffness: str = "barber",
    fd_step: float = 0.02,
    pressure_tol: float = 1e-5,
    pentol: float | None = None,
    thermotol: float = 1e-6,
    maxiter: int = 10000,
    maps: bool = False,
    progress: bool = False,
    device: wp.DeviceLike = None,
    devices: Any = None,
) -> ContactCurve:
    """Elastic (or elastic–perfectly-plastic) contact of a rough map against a rigid flat at
    increasing approaches or loads.

    Parameters
    ----------
    heights : Surface or (ny, nx) array_like
        The rough surface: a :class:`warptrunc.Surface` or heights z (m).
    depths : sequence of float, optional
        Approaches δ from first touch at the highest pixel (m); solved in the given order, each
        warm-started from the previous solution (increasing order is fastest).
    loads : sequence of float, optional
        Total loads F (N), instead of ``depths`` (load control).
    pixel_size : float or (float, float), optional
        Pixel sides (m); required for an array, taken from a Surface.
    contact_modulus : float, optional
        Contact modulus E* (Pa); default ``material.contact_modulus``. One of the two is needed.
    material : Material, optional
        Elastic constants and hardness (:class:`warptrunc.Material`): E* and H are read from it.
    hardness : float, optional
        Hardness H (Pa), the local pressure cap, in (0, inf]; default ``material.hardness``,
        else inf (elastic). With a finite H the rows are a loading history: each solve starts
        from the plastic state the previous ones left (see :mod:`warptrunc.contact.solver`).
    settings : SolverSettings, optional
        Solver settings (:class:`~warptrunc.contact.SolverSettings`); the keywords
        ``substrate``, ``dtype``, ``pressure_tol``, ``pentol``, ``thermotol`` and ``maxiter``
        override its fields when they differ from their defaults.
    substrate : {"free", "periodic"}
        Zero-padded isolated patch or periodic map (:mod:`warptrunc.contact.halfspace`).
    dtype : {"float64", "float32"}
        Precision of maps and FFTs.
    stiffness : {"barber", "central", "none"}
        k = dF/dδ by Barber's flat punch of the contact set (one linear CG solve; with H < inf
        the unloading stiffness of the deformed surface), by the central difference over
        δ(1 ± fd_step) (two more CCG solves; elastic only), or not at all (NaN).
    fd_step : float
        Relative step h of the central difference (dimensionless), in (0, 0.5).
    pressure_tol, pentol, thermotol, maxiter
        Tolerances and iteration limit, see :class:`ContactSolver`.
    maps : bool
        Keep pressure (Pa) and gap (m) maps of every row (host memory: 16 bytes per pixel per row).
    progress : bool
        tqdm bar over the rows (stderr).
    {warp_device_obj}
    devices : int, "auto" or list, optional
        Spread the solver over several devices (``ContactSolver(..., devices=...)``,
        :class:`~warptrunc.contact.sharded.ShardedContactSolver`; JAX); default None: one.

    Returns
    -------
    ContactCurve

    Raises
    ------
    ValueError
        Bad heights (NaN/inf, not 2-D), parameters out of range, neither or both of depths/loads,
        neither contact_modulus nor material, or ``stiffness="central"`` with a finite hardness.
    MemoryError
        The solver would not fit the device's free memory (checked before allocating).

    Notes
    -----
    Central differences with loads: k = ΔF/Δδ with the two loads F(1 ± h).

    References
    ----------
    .. [1] I.A. Polonsky, L.M. Keer, Wear 231, 206 (1999). doi:10.1016/S0043-1648(99)00113-1
    .. [2] J.R. Barber, Proc. R. Soc. A 459, 53 (2003). doi:10.1098/rspa.2002.1038
    """
    from tqdm.auto import tqdm

    if hasattr(heights, "heights") and hasattr(heights, "dx"):
        if pixel_size is None:
            pixel_size = (heights.dx, heights.dy)
        heights = heights.heights
    if pixel_size is None:
        raise ValueError("pixel_size (m) is required for a height array")
    if stiffness not in STIFFNESS_METHODS:
        raise ValueError(f"stiffness must be one of {STIFFNESS_METHODS}, got {stiffness!r}")
    fd_step = check_range("fd_step", fd_step, 0.0, 0.5)
    if (depths is None) == (loads is None):
        raise ValueError("give exactly one of depths (m) and loads (N)")
    key = "depth" if loads is None else "load"
    values = np.atleast_1d(np.asarray(depths if loads is None else loads, dtype=np.float64))
    if values.size == 0:
        raise ValueError(f"at least one {key} is needed, got none")
    for v in values:
        check_range(key, v, 0.0, unit="m" if key == "depth" else "N")
    if contact_modulus is None:
        if material is None:
            raise ValueError("give contact_modulus (Pa) or material (a warptrunc.Material)")
        contact_modulus = material.contact_modulus
    if hardness is None:
        hardness = math.inf if material is None else material.hardness
    hardness = float(check_value(Material, "hardness", hardness))
    if stiffness == "central" and math.isfinite(hardness):
        raise ValueError(
            'stiffness="central" needs an elastic solve (hardness = inf); with a finite hardness '
            f'({hardness:g} Pa) use "barber" (the unloading stiffness) or "none"'
        )
    given = {"substrate": substrate, "dtype": dtype, "pressure_tol": pressure_tol,
             "pentol": pentol, "thermotol": thermotol, "maxiter": maxiter}  # fmt: skip
    base = SolverSettings() if settings is None else settings
    defaults = SolverSettings()
    settings = base.replace(
        **{k: v for k, v in given.items() if settings is None or v != getattr(defaults, k)}
    )
    solver = ContactSolver(heights, pixel_size, contact_modulus, settings=settings,
                           hardness=hardness, device=device, devices=devices)  # fmt: skip
    substrate, dtype = settings.substrate, settings.dtype
    rows: list[dict[str, Any]] = []
    p_maps, g_maps = [], []
    for v in tqdm(values, desc="contact solves", unit="solve", disable=not progress):
        t0 = time.perf_counter()
        if stiffness == "central":
            lo = solver.solve(**{key: v * (1 - fd_step)})
            hi = solver.solve(**{key: v * (1 + fd_step)})
        state = solver.solve(**{key: v})
        conv = state.converged
        if stiffness == "barber":
            k, _, ok = solver.punch_stiffness()
            conv = conv and ok
        elif stiffness == "central":
            k = (hi.load - lo.load) / (hi.depth - lo.depth)
            conv = conv and lo.converged and hi.converged
        else:
            k = math.nan
        if maps:
            p, g = solver.maps()
            p_maps.append(p)
            g_maps.append(g)
        info = {f.name: getattr(state, f.name) for f in fields(state)}
        info.update(stiffness=k, converged=conv, solve_time=time.perf_counter() - t0)
        rows.append(info)

    def col(name, dt=np.float64):
        return np.array([r[name] for r in rows], dtype=dt)

    dx, dy = solver.pixel_size
    n_contact = col("n_contact", np.int64)
    settings = {
        "solver": "warptrunc constrained conjugate gradients (Polonsky & Keer 1999)",
        "substrate": substrate, "dtype": dtype, "contact_modulus_Pa": solver.contact_modulus,
        "stiffness_method": stiffness, "fd_step": fd_step, "pressure_tol": solver.pressure_tol,
        "forcetol_N": solver.forcetol, "pentol_m": solver.pentol, "thermotol": solver.thermotol,
        "maxiter": solver.maxiter, "refresh": solver.refresh,
        "direct_max": solver.direct_max,
        "device": "+".join(getattr(solver, "device_names", [])) or str(solver.device),
        "grid": [solver.shape[1], solver.shape[0]], "pixel_size_m": [dx, dy],
        "control": "displacement" if key == "depth" else "load", "hardness_Pa": hardness if math.isfinite(hardness) else None,
    }  # fmt: skip
    return ContactCurve(
        depth=col("depth"), load=col("load"), n_contact=n_contact, area=n_contact * (dx * dy),
        stiffness=col("stiffness"), mean_gap=col("mean_gap"),
        n_iterations=col("n_iterations", np.int64), n_convolutions=col("n_convolutions", np.float64),
        residual=col("residual"), max_tensile_force=col("max_tensile_force"),
        converged=col("converged", bool), solve_time=col("solve_time"),
        n_plastic=col("n_plastic", np.int64), plastic_area=col("plastic_area"),
        plastic_volume=col("plastic_volume"),
        pressure=np.stack(p_maps) if maps else None, gap=np.stack(g_maps) if maps else None,
        settings=settings,
    )  # fmt: skip
