# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The load / partial-unload cycles of the paper's protocol (§ 4.1) under one punch, on a
contact solver of the punch's window (:func:`make_solver`).

Each cycle loads the punch to its peak load F (load control), then measures the unloading
stiffness two ways, with the plastic state frozen (the surface stays as the peak left it):

* **initial unloading slope** (Barber): K = the stiffness of a rigid flat punch shaped like the
  whole contact set at the peak (every pixel with p > 0, those at the hardness included),
  :meth:`ContactSolver.punch_stiffness`. Exact at the start of elastic unloading, since the edge
  pressures are finite (≤ H); never the loading tangent, which is lower.
* **the paper's protocol**: unload by ``unload_fraction``·F and take the secant
  K = ΔF/Δδ ≈ f·F / (δ(F) − δ((1 − f)·F)) from an elastic solve of the deformed surface (ΔF
  from the loads the two solves reached, each within the solver's ``thermotol`` of its
  target).

Then it reloads to the next peak. In an elastic–perfectly-plastic model, unloading and
reloading up to the previous peak are elastic (no pixel reaches H again below the peak load),
so the state at each peak is that of monotonic loading to it: a run need not replay the partial
unloads (``tests/test_indent.py`` checks this on the results of :func:`warptrunc.indent`).

E_c = √π·K/(2√A), with A the punch area πd²/4 (§ 4.1), and Fig. 6's normalisations E_c/E and
F/(E·A) with E the Young's modulus of the rough body.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._support.docs import SHARED_DOCS, fill_doc
from ..contact.iteration.bccg import PRECONDITION_ABOVE
from ..contact.settings import SolverSettings
from ..contact.factory import contact_solver
from ..contact.solver import ContactSolver
from ..material import Material
from .protocol import IndentProtocol
from .punch import PunchWindow

__all__ = ["COLUMNS", "make_solver", "run_cycles"]


@fill_doc(SHARED_DOCS)
def make_solver(
    window: PunchWindow,
    material: Material,
    *,
    solver: SolverSettings | None = None,
    device: Any = None,
    devices: Any = None,
) -> ContactSolver:
    """A contact solver on a punch window, with the penetration tolerance of the disk's heights.

    Parameters
    ----------
    window : PunchWindow
        The punch and the heights under it.
    material : Material
        E* (Pa) and the pressure cap H (Pa; inf = elastic) for the solver.
    solver : SolverSettings, optional
        Solver settings; a finite punch needs the free half-space.
    {warp_device_obj}
    devices : int, "auto" or list, optional
        Spread the solver over several devices (``contact_solver(..., devices=...)``; JAX);
        default None: ``device`` alone. When a count (or a list) does not divide the window's
        rows, rows at the window's floor are added below it: they never touch (an approach
        that deep is refused), so on the free half-space the solution is the same.

    Returns
    -------
    ContactSolver

    Raises
    ------
    ValueError
        A periodic substrate under a finite punch.

    Notes
    -----
    The default penetration tolerance (rms height/(10·mean n), ContactMechanics') takes the rms
    over the disk only (the pixels outside it, far below, would inflate it; a tilted face's
    plane taken out, so that a tilt does not loosen it) and n the window's sides. A flat disk gets 10⁻⁶ of a pixel side. The default BCCG preconditioner rule
    (``precondition_above=None``) becomes 2 % of the window at every size
    (``warptrunc.contact.iteration.bccg.PRECONDITION_ABOVE``): under a punch on a rough surface always
    preconditioning the large windows costs more convolutions than it saves.
    """
    settings = SolverSettings() if solver is None else solver
    if window.diameter is not None and settings.substrate != "free":
        raise ValueError(
            f"solver.substrate must be 'free' under a finite punch (the body around the punch "
            f"is the unloaded half-space), got {settings.substrate!r}"
        )
    if settings.pentol is None:
        # rms over the disk / (10·mean window side), not over the (1-D) list of disk pixels
        pentol = float(np.std(window.untilted_disk_heights)) / (10 * np.mean(window.mask.shape))
        if pentol == 0.0:  # a flat punch face
            pentol = 1e-6 * min(window.pixel_size)
        settings = settings.replace(pentol=pentol)
    if settings.precondition_above is None:
        settings = settings.replace(precondition_above=PRECONDITION_ABOVE)
    heights = window.heights
    n_dev = (
        devices
        if isinstance(devices, int)
        else (len(devices) if isinstance(devices, (list, tuple)) else 1)
    )
    if n_dev > 1 and heights.shape[0] % n_dev:  # row slabs: whole rows of the floor below
        extra = n_dev - heights.shape[0] % n_dev
        heights = np.vstack([heights, np.full((extra, heights.shape[1]), window.floor)])
    return contact_solver(
        heights,
        window.pixel_size,
        material.contact_modulus,
        settings=settings,
        hardness=material.hardness,
        device=device,
        devices=devices,
    )


COLUMNS = (
    "displacement",
    "n_contact",
    "contact_area",
    "n_plastic",
    "plastic_area",
    "plastic_volume",
    "max_pressure",
    "unloading_stiffness",
    "partial_unloading_stiffness",
    "unloaded_displacement",
    "n_iterations",
    "converged",
    "detection_displacement",
)
"""Per-peak outputs of :func:`run_cycles`."""


@fill_doc(SHARED_DOCS)
def run_cycles(
    window: PunchWindow,
    protocol: IndentProtocol,
    material: Material,
    *,
    solver: SolverSettings | None = None,
    elastic: dict[str, np.ndarray] | None = None,
    approach: Any = None,
    step: Any = None,
    boxes: bool = False,
    device: Any = None,
    devices: Any = None,
) -> dict[str, np.ndarray]:
    """Load / partial-unload cycles under one punch, at the protocol's increasing peak loads.

    Parameters
    ----------
    window : PunchWindow
        The punch and the heights under it.
    protocol : IndentProtocol
        Its ``peak_loads`` F (N, increasing; m of them) and ``unload_fraction`` f (the partial
        unloading of each cycle, dimensionless).
    material : Material
        Elastic constants (E* for the solver) and the pressure cap H (Pa; inf = elastic).
    solver : SolverSettings, optional
        Contact-solver settings.
    elastic : dict of str to (m,) ndarray, optional
        The elastic cycles (H = inf) of the same window, loads, unloading fraction and solver
        settings, as this function returns them. With a finite ``material.hardness`` the leading
        cycles whose elastic peak pressure stays below H (and which converged) are copied from
        it instead of solved: no pixel reaches the cap there, so the elastic solution is the
        elastic–perfectly-plastic one (the capped problem has one solution), no plastic flow
        occurs, and the surface the next cycle starts from is the original one. The cycles
        after the first that reaches H are solved, starting from the original surface (the
        state at a peak is that of monotonic loading to it).
    approach : (m,) array_like, optional
        A prediction of the approach at each peak (m), from a coarser grid of the same surface:
        the first load solve (that of the first cycle not copied from ``elastic``) starts
        there (:meth:`ContactSolver.hint_approach`; the answer is the same, the iterations
        fewer).
    step : callable, optional
        Called once per cycle (a progress bar's ``update``).
    boxes : bool
        Also return, per peak, the bounding boxes of the contact and of the pixels near it
        (``contact_box``, ``near_box``: (m, 4) int64 (iy0, ix0, iy1, ix1) in window pixels,
        inclusive, -1 where none or unknown): near = the disk's pixels whose gap is within
        ``gap_margin`` of contact, the set a sub-window at a finer pixel must hold
        (:mod:`warptrunc.indent.refine`). A copied elastic cycle takes the boxes of
        ``elastic`` when it has them.
    {warp_device_obj}
    devices : int, "auto" or list, optional
        Spread the solver over several devices (:func:`make_solver`); default None.

    Returns
    -------
    dict of str to (m,) ndarray
        :data:`COLUMNS`: at each peak the approach δ from first touch
        (m), contact pixels and area (m²), plastic pixels, area (m²) and volume (m³), the
        largest contact pressure (Pa), Barber's unloading stiffness and the partial-unloading
        secant (N/m), the approach after the partial unloading (m), the constrained-CG
        iterations of the peak solve, whether every solve of the cycle converged and the
        approach at the protocol's ``detection_load`` F_s (m, the same at every peak; solved
        before the first cycle solved, loading monotonically, or copied from ``elastic`` when
        every cycle is; NaN without a ``detection_load``: :mod:`warptrunc.indent.depth`).
    """
    loads = np.asarray(protocol.peak_loads, dtype=np.float64)
    hardness = material.hardness
    out: dict[str, list] = {c: [] for c in COLUMNS}
    box_cols = ("contact_box", "near_box") if boxes else ()
    for c in box_cols:
        out[c] = []
    margin = gap_margin(window) if boxes else 0.0
    n_reused = 0
    if elastic is not None and math.isfinite(hardness):
        below = (np.asarray(elastic["max_pressure"], np.float64) < hardness) & np.asarray(
            elastic["converged"], bool
        )
        if below.shape != loads.shape:
            raise ValueError(f"elastic has {below.size} cycles, peak_loads {loads.size}")
        n_reused = int(np.argmin(below)) if not below.all() else loads.size
        unyielded = {
            "n_plastic": 0,
            "plastic_area": 0.0,
            "plastic_volume": 0.0,
            "unloaded_displacement": math.nan,
            "n_iterations": 0,
            "detection_displacement": math.nan,
        }
        for c in COLUMNS:
            v = elastic.get(c)
            out[c] = list(np.asarray(v)[:n_reused]) if v is not None else [unyielded[c]] * n_reused
        for c in box_cols:
            v = elastic.get(c)
            out[c] = list(np.asarray(v)[:n_reused]) if v is not None else [[-1] * 4] * n_reused
        if step is not None:
            for _ in range(n_reused):
                step()
    f = float(protocol.unload_fraction)
    reach = window.top - window.floor  # an approach this deep would reach outside the disk
    cs = (
        make_solver(window, material, solver=solver, device=device, devices=devices)
        if n_reused < loads.size
        else None
    )
    if cs is not None and approach is not None:
        first = float(np.broadcast_to(np.asarray(approach, np.float64), loads.shape)[n_reused])
        if first > 0:
            cs.hint_approach(first)
    for load in loads[n_reused:]:
        cs.freeze_plastic(False)
        peak = cs.solve(load=float(load))
        p_max = cs.max_pressure()
        peak_boxes = _boxes(cs, window, margin) if boxes else ()  # before the unloading
        cs.freeze_plastic(True)  # the unloading below is elastic from the deformed surface
        k_barber, _, ok_barber = cs.punch_stiffness()
        low = cs.solve(load=(1.0 - f) * float(load))
        if not peak.depth < reach:
            raise RuntimeError(
                f"the punch approach {peak.depth:.4g} m reached the pixels outside the disk "
                f"({reach:.4g} m below its top); give punch_window a larger drop"
            )
        # the loads the solves reached (each within thermotol of its target)
        k_secant = (
            (peak.load - low.load) / (peak.depth - low.depth)
            if peak.depth > low.depth
            else math.nan
        )
        out["displacement"].append(peak.depth)
        out["n_contact"].append(peak.n_contact)
        out["contact_area"].append(peak.contact_area)
        out["n_plastic"].append(peak.n_plastic)
        out["plastic_area"].append(peak.plastic_area)
        out["plastic_volume"].append(peak.plastic_volume)
        out["max_pressure"].append(p_max)
        out["n_iterations"].append(peak.n_iterations)
        out["unloading_stiffness"].append(float(k_barber))
        out["partial_unloading_stiffness"].append(k_secant)
        out["unloaded_displacement"].append(low.depth)
        out["converged"].append(
            peak.converged and low.converged and bool(ok_barber) and math.isfinite(k_secant)
        )
        for c, b in zip(box_cols, peak_boxes, strict=True):
            out[c].append(b)
        if step is not None:
            step()
    f_s = protocol.detection_load
    det = math.nan
    if f_s is not None and cs is None and elastic is not None:
        det = float(np.asarray(elastic.get("detection_displacement", [math.nan]))[0])
    if cs is not None:
        cs.freeze_plastic(False)
        if f_s is not None:  # surface detection: loading from the original surface to F_s
            cs.reset()
            state = cs.solve(load=float(f_s))
            det = float(state.depth) if state.converged else math.nan
    out["detection_displacement"] = [det] * loads.size
    for c in box_cols:
        out[c] = np.asarray(out[c], np.int64).reshape(-1, 4)
    types = {
        "n_contact": np.int64,
        "n_plastic": np.int64,
        "n_iterations": np.int64,
        "converged": bool,
    }
    return {
        c: (v if c in box_cols else np.asarray(v, dtype=types.get(c, np.float64)))
        for c, v in out.items()
    }


def gap_margin(window: PunchWindow) -> float:
    """How near contact a pixel of the disk must be to belong to the contact's interaction
    range at a finer pixel (m): twice the largest height step between neighbouring disk pixels,
    the most a sample between them can rise above both on a surface whose content the pixel
    resolves (a WM map with W_c ≥ 2 pixels).

    Parameters
    ----------
    window : PunchWindow
        The punch and the heights under it.

    Returns
    -------
    float
        The margin (m); 0 for a flat disk.
    """
    z, mk = window.heights, window.mask
    steps = [0.0]
    for ax in (0, 1):
        both = np.logical_and(
            np.take(mk, range(1, mk.shape[ax]), axis=ax),
            np.take(mk, range(mk.shape[ax] - 1), axis=ax),
        )
        if both.any():
            steps.append(float(np.abs(np.diff(z, axis=ax))[both].max()))
    return 2.0 * max(steps)


def _box(sel: np.ndarray) -> list[int]:
    if not sel.any():
        return [-1, -1, -1, -1]
    rows, cols = np.flatnonzero(sel.any(axis=1)), np.flatnonzero(sel.any(axis=0))
    return [int(rows[0]), int(cols[0]), int(rows[-1]), int(cols[-1])]


def _boxes(cs: ContactSolver, window: PunchWindow, margin: float) -> tuple[list[int], list[int]]:
    """The contact's and the near-contact set's bounding boxes of the current solution."""
    p, gap = cs.maps()
    wy, wx = window.mask.shape
    p, gap = p[:wy, :wx], gap[:wy, :wx]
    contact = window.mask & (p > 0)
    near = window.mask & ((p > 0) | (np.abs(gap) <= margin))
    return _box(contact), _box(near)
