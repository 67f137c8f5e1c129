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
from .results import ContactCurve
from .settings import CurveSettings, SolverSettings
from .factory import contact_solver

__all__ = ["solve_contact"]


@fill_doc(SHARED_DOCS)
def solve_contact(
    heights: Any,
    depths: Any = None,
    *,
    loads: Any = None,
    pixel_size: Any = None,
    material: Material | None = None,
    settings: SolverSettings | None = None,
    curve: CurveSettings | None = None,
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
    material : Material, optional
        Elastic constants and hardness (:class:`warptrunc.Material`; default ``Material()``):
        E* = ``material.contact_modulus`` and H = ``material.hardness``. With a finite H the
        rows are a loading history: each solve starts from the plastic state the previous ones
        left (see :mod:`warptrunc.contact.iteration.plastic`).
    settings : SolverSettings, optional
        Precision, substrate, interaction law, tolerances and iteration limits of the solver
        (:class:`~warptrunc.contact.SolverSettings`; default ``SolverSettings()``). With an
        adhesive ``settings.adhesion`` (:class:`~warptrunc.contact.adhesion.Adhesion`) the
        rows are an approach–retract history: depths (or loads) may rise and fall, and be
        negative (the flat above first touch, a tensile load);
        :func:`~warptrunc.contact.hysteresis.force_approach` reads the cycle. Barber's
        stiffness is then that of the repulsive contact at a fixed area; the central
        difference is refused.
    curve : CurveSettings, optional
        The stiffness method of each row (Barber's punch, the central difference, none) and
        whether the pressure and gap maps are kept (:class:`~warptrunc.contact.CurveSettings`;
        default ``CurveSettings()``: Barber, no maps).
    progress : bool
        Report the rows on stderr (a bar on a terminal, else lines).
    {warp_device_obj}
    devices : int, "auto" or list, optional
        Spread the solver over several devices (``contact_solver(..., devices=...)``,
        :class:`~warptrunc.contact.sharded.ShardedContactSolver`; JAX); default None: one.

    Returns
    -------
    ContactCurve

    Raises
    ------
    ValueError
        Bad heights (NaN/inf, not 2-D), parameters out of range, neither or both of depths/loads,
        or the central difference with a finite hardness or with adhesion.
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
    from .._support.progress import progress_bar

    if hasattr(heights, "heights") and hasattr(heights, "dx"):
        if pixel_size is None:
            pixel_size = (heights.dx, heights.dy)
        heights = heights.heights
    if pixel_size is None:
        raise ValueError("pixel_size (m) is required for a height array")
    material = Material() if material is None else material
    settings = SolverSettings() if settings is None else settings
    curve = CurveSettings() if curve is None else curve
    stiffness, fd_step = curve.stiffness, curve.fd_step
    if (depths is None) == (loads is None):
        raise ValueError("give exactly one of depths (m) and loads (N)")
    key = "depth" if loads is None else "load"
    values = np.atleast_1d(np.asarray(depths if loads is None else loads, dtype=np.float64))
    if values.size == 0:
        raise ValueError(f"at least one {key} is needed, got none")
    adhesion = settings.adhesion
    for v in values:  # with adhesion any finite approach or load: the surfaces pull
        check_range(key, v, None if adhesion.active else 0.0, unit="m" if key == "depth" else "N")
    if stiffness == "central" and adhesion.active:
        raise ValueError(
            'the central difference (CurveSettings(stiffness="central")) solves at δ(1 ± h), '
            "which moves an adhesive contact along its hysteresis; with adhesion use "
            '"barber" (the stiffness at a fixed contact area) or "none"'
        )
    hardness = material.hardness
    if stiffness == "central" and math.isfinite(hardness):
        raise ValueError(
            'the central difference (CurveSettings(stiffness="central")) needs an elastic solve '
            f'(hardness = inf); with a finite hardness ({hardness:g} Pa) use "barber" (the '
            'unloading stiffness) or "none"'
        )
    solver = contact_solver(
        heights,
        pixel_size,
        material.contact_modulus,
        settings=settings,
        hardness=hardness,
        device=device,
        devices=devices,
    )
    substrate, dtype = settings.substrate, settings.dtype
    rows: list[dict[str, Any]] = []
    p_maps, g_maps = [], []
    for v in progress_bar(values, desc="contact solves", unit="solve", enabled=progress):
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
        if curve.maps:
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
    record = {
        "solver": "warptrunc constrained conjugate gradients (Polonsky & Keer 1999)",
        "substrate": substrate,
        "dtype": dtype,
        "contact_modulus_Pa": solver.contact_modulus,
        "stiffness_method": stiffness,
        "fd_step": fd_step,
        "pressure_tol": solver.pressure_tol,
        "forcetol_N": solver.forcetol,
        "pentol_m": solver.pentol,
        "thermotol": solver.thermotol,
        "maxiter": solver.maxiter,
        "refresh": solver.refresh,
        "direct_max": solver.direct_max,
        "device": "+".join(getattr(solver, "device_names", [])) or str(solver.device),
        "grid": [solver.shape[1], solver.shape[0]],
        "pixel_size_m": [dx, dy],
        "control": "displacement" if key == "depth" else "load",
        "hardness_Pa": hardness if math.isfinite(hardness) else None,
        "adhesion": adhesion.to_dict() if adhesion.active else None,
    }
    return ContactCurve(
        depth=col("depth"),
        load=col("load"),
        n_contact=n_contact,
        area=n_contact * (dx * dy),
        stiffness=col("stiffness"),
        mean_gap=col("mean_gap"),
        n_iterations=col("n_iterations", np.int64),
        n_convolutions=col("n_convolutions", np.float64),
        residual=col("residual"),
        max_tensile_force=col("max_tensile_force"),
        converged=col("converged", bool),
        solve_time=col("solve_time"),
        n_plastic=col("n_plastic", np.int64),
        plastic_area=col("plastic_area"),
        plastic_volume=col("plastic_volume"),
        adhesive_force=col("adhesive_force"),
        n_attractive=col("n_attractive", np.int64),
        attractive_area=col("attractive_area"),
        pressure=np.stack(p_maps) if curve.maps else None,
        gap=np.stack(g_maps) if curve.maps else None,
        settings=record,
    )
