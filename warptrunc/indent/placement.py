# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One punch placement of :func:`warptrunc.indent`: its cycles for each contact model, refined
in the pixel size (:mod:`.refine`), and Eq. 2 truncation on the same disk, as the rows of an
:class:`~warptrunc.indent.IndentationResult`."""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from ..contact.settings import SolverSettings
from ..material import Material
from .cycles import COLUMNS, run_cycles
from .depth import bulk_yield
from .protocol import IndentProtocol
from .punch import PunchWindow
from .refine import CellRefinement, WindowSource, refine_cells
from .results import modulus_from_stiffness
from .truncated import truncation_at_loads

__all__ = ["solve_placement"]

BOX_COLUMNS = ("contact_box", "near_box")
"""The near-contact boxes :func:`~warptrunc.indent.cycles.run_cycles` returns when asked."""


def _subset(cycles: dict[int, dict[str, Any]], idx: np.ndarray) -> dict[str, np.ndarray] | None:
    """The elastic cycles of loads ``idx`` solved at one pixel, when every one of them is."""
    if idx.size == 0 or not all(int(i) in cycles for i in idx):
        return None
    keys = cycles[int(idx[0])]
    return {c: np.asarray([cycles[int(i)][c] for i in idx]) for c in keys}


def solve_placement(
    source: WindowSource,
    w: PunchWindow,
    protocol: IndentProtocol,
    material: Material,
    *,
    solver: SolverSettings | None = None,
    given: dict[str, np.ndarray] | None = None,
    step: Any = None,
    device: Any = None,
    devices: Any = None,
) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    """The rows of one punch placement: both contact models refined, and truncation.

    Parameters
    ----------
    source : WindowSource
        The map (and, for a WM map, its finer windows).
    w : PunchWindow
        The punch window at the map's pixel.
    protocol : IndentProtocol
        Loads, unloading fraction, truncation increments, the refinement rule and ``elastic``
        (also solve the elastic contact, H = ∞, on the same punch: its columns; NaN when off).
    material : Material
        Elastic constants and the hardness H (inf: elastic).
    solver : SolverSettings, optional
        Contact-solver settings.
    given : dict of str to (m,) ndarray, optional
        The elastic cycles at the map's pixel, taken instead of solved (``indent``'s reuse).
    step : callable, optional
        Called once per cycle solved at the map's pixel (a progress bar's ``update``).
    device : warp.context.Device, optional
        Resolved Warp device.
    devices : int, "auto" or list, optional
        Spread each contact solve over several devices (``contact_solver(..., devices=...)``;
        JAX); default None: ``device`` alone.

    Returns
    -------
    rows : dict of str to (m,) ndarray
        The result columns of this placement's cells (field names of IndentationResult).
    info : dict
        ``seconds`` per phase, ``reused`` (elastic cycles copied), ``windows`` (factor →
        window shape) and ``why_not`` (None for a map refined).
    """
    loads = np.asarray(protocol.peak_loads, dtype=np.float64)
    m = loads.size
    hardness = material.hardness
    elastic = protocol.elastic
    two = elastic and math.isfinite(hardness)
    at_inf = material.replace(hardness=math.inf)
    # the complete-contact plateau of the face, 2E*·a = E*·d (Sneddon): K within the tolerance
    # of it is saturated
    plateau = None if w.diameter is None else material.contact_modulus * w.diameter
    windows: dict[int, PunchWindow] = {1: w}
    # the near-contact boxes a sub-window is cut to, when a refined whole window may not fit
    max_px = protocol.max_window_pixels
    boxes = (
        source.refinable
        and protocol.refine_max > 1
        and w.diameter is not None
        and w.mask.size * protocol.refine_max**2 > max_px
    )
    el_cache: dict[int, dict[int, dict[str, Any]]] = {}  # factor → load index → elastic cycle
    sec = {"elastic_s": 0.0, "elastic_plastic_s": 0.0, "refinement_s": 0.0, "truncation_s": 0.0}

    def cycles(
        win: PunchWindow,
        idx: np.ndarray,
        mat: Material,
        el: Any = None,
        bar: Any = None,
        approach: Any = None,
    ):
        at = protocol if idx.size == m else protocol.replace(peak_loads=tuple(loads[idx]))
        return run_cycles(
            win,
            at,
            mat,
            solver=solver,
            elastic=el,
            approach=approach,
            step=bar,
            boxes=boxes,
            device=device,
            devices=devices,
        )

    def keep(factor: int, idx: np.ndarray, out: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        by = el_cache.setdefault(factor, {})
        for r, i in enumerate(idx):
            by[int(i)] = {c: out[c][r] for c in (*COLUMNS, *BOX_COLUMNS) if c in out}
        return out

    every = np.arange(m)
    t0 = time.perf_counter()
    el0 = None
    if given is not None:
        el0 = keep(1, every, given)
        if step is not None:
            step(m)
    elif two:  # first, so that the elastic–plastic run can take its unyielded cycles
        el0 = keep(1, every, cycles(w, every, at_inf, bar=step))
    t1 = time.perf_counter()
    ep0 = cycles(w, every, material, el0, step)
    t2 = time.perf_counter()
    reused = 0
    if el0 is not None:
        below = (np.asarray(el0["max_pressure"]) < hardness) & np.asarray(el0["converged"], bool)
        reused = m if below.all() else int(np.argmin(below))
    el_ref: CellRefinement | None = None
    if two and given is None:
        el_ref = refine_cells(
            source,
            w,
            el0,
            lambda win, idx, k, a: keep(k, idx, cycles(win, idx, at_inf, approach=a)),
            protocol=protocol,
            windows=windows,
            plateau=plateau,
        )
    ep_ref = refine_cells(
        source,
        w,
        ep0,
        lambda win, idx, k, a: cycles(
            win, idx, material, _subset(el_cache.get(k, {}), idx), approach=a
        ),
        protocol=protocol,
        windows=windows,
        plateau=plateau,
    )
    if el_ref is None and given is not None:  # the given elastic cycles, judged as they are
        el_ref = refine_cells(
            source,
            w,
            el0,
            lambda *a: {},
            protocol=protocol.replace(refine_max=1),
            windows=windows,
            plateau=plateau,
        )
    if el_ref is None and elastic:  # H = inf: the elastic–plastic model is the elastic one
        el_ref = ep_ref
    t3 = time.perf_counter()
    rows = _rows(w, loads, ep_ref, el_ref)
    # the cap model does not hold where the bulk would yield under the whole punch
    rows["bulk_yield"] = bulk_yield(loads, w.area, hardness)
    rows["in_fit"] = rows["in_fit"] & ~rows["bulk_yield"]
    # Eq. 2 truncation on the disk at each cell's final pixel
    tr = {k: np.zeros(m) for k in ("depth", "contact_area", "stiffness")}
    for k in np.unique(ep_ref.truncation_factor):
        idx = np.flatnonzero(ep_ref.truncation_factor == k)
        t = truncation_at_loads(
            ep_ref.windows[int(k)],
            loads[idx],
            material.contact_modulus,
            n_increments=protocol.truncation_increments,
            device=device,
        )
        for c in tr:
            tr[c][idx] = t[c]
    rows.update(
        truncation_depth=tr["depth"],
        truncation_contact_area=tr["contact_area"],
        truncation_stiffness=tr["stiffness"],
        truncation_pixel_size=w.pixel_size[0] / ep_ref.truncation_factor.astype(np.float64),
    )
    t4 = time.perf_counter()
    sec.update(
        elastic_s=t1 - t0, elastic_plastic_s=t2 - t1, refinement_s=t3 - t2, truncation_s=t4 - t3
    )
    info = {
        "seconds": sec,
        "reused": reused,
        "why_not": source.why_not,
        "windows": {int(k): [int(v) for v in win.mask.shape] for k, win in windows.items()},
    }
    return rows, info


def _rows(
    w: PunchWindow, loads: np.ndarray, ep: CellRefinement, el: CellRefinement | None
) -> dict[str, np.ndarray]:
    """The result columns of one placement from its refined contact models."""
    m = loads.size
    c = ep.cycles
    rows: dict[str, np.ndarray] = {
        "punch_diameter": np.full(m, np.nan if w.diameter is None else w.diameter),
        "centre_x": np.full(m, w.centre[0]),
        "centre_y": np.full(m, w.centre[1]),
        "punch_area": np.full(m, w.area),
        "n_punch_pixels": ep.n_disk_pixels,
        "peak_load": loads,
        "E_c": modulus_from_stiffness(c["unloading_stiffness"], w.area),
        "E_c_partial": modulus_from_stiffness(c["partial_unloading_stiffness"], w.area),
        "pixel_size": ep.pixel_size,
        "resolution_change": ep.change,
        "area_change": ep.area_change,
        "stiffness_extrapolated": ep.stiffness_extrapolated,
        "stiffness_error": ep.stiffness_error,
        "contact_area_extrapolated": ep.area_extrapolated,
        "contact_area_error": ep.area_error,
        "resolved": ep.resolved,
        "area_resolved": ep.area_resolved,
        "saturated": ep.saturated,
        "sub_window": ep.sub_window,
        "in_fit": ep.in_fit,
        "resolution_note": ep.note,
    }
    for k in (
        "displacement",
        "n_contact",
        "contact_area",
        "plastic_area",
        "plastic_volume",
        "max_pressure",
        "unloading_stiffness",
        "partial_unloading_stiffness",
        "converged",
        "detection_displacement",
    ):
        rows[k] = np.asarray(c[k])
    nan = np.full(m, np.nan)
    e = None if el is None else el.cycles
    for k in (
        "displacement",
        "contact_area",
        "unloading_stiffness",
        "partial_unloading_stiffness",
        "detection_displacement",
    ):
        rows[f"elastic_{k}"] = nan if e is None else np.asarray(e[k], np.float64)
    off = np.zeros(m, bool)
    rows.update(
        elastic_converged=off if e is None else np.asarray(e["converged"], bool),
        elastic_pixel_size=nan if el is None else el.pixel_size,
        elastic_n_contact=np.zeros(m, np.int64)
        if e is None
        else np.asarray(e["n_contact"], np.int64),
        elastic_resolution_change=nan if el is None else el.change,
        elastic_stiffness_extrapolated=nan if el is None else el.stiffness_extrapolated,
        elastic_stiffness_error=nan if el is None else el.stiffness_error,
        elastic_contact_area_error=nan if el is None else el.area_error,
        elastic_resolved=off if el is None else el.resolved,
        elastic_area_resolved=off if el is None else el.area_resolved,
        elastic_saturated=off if el is None else el.saturated,
        elastic_in_fit=off if el is None else el.in_fit,
    )
    return rows
