# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
""":func:`indent`, the paper's nanoindentation experiment (§ 4.1, Fig. 6) run on a height map."""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
import warp as wp

from .._support.device import resolve_device
from .._support.docs import SHARED_DOCS, fill_doc
from .._support.progress import progress_bar
from ..contact.settings import SolverSettings
from ..material import Material
from ..surface import Surface
from .protocol import (
    PAPER_PEAK_LOADS,
    PAPER_PUNCH_DIAMETERS,
    IndentProtocol,
    default_material,
    run_cycles,
)
from .punch import PunchWindow, place_punches, punch_window
from .results import IndentationResult, modulus_from_stiffness
from .truncated import truncation_at_loads

__all__ = ["indent"]


def _heights(surface: Any, pixel_size: Any) -> tuple[np.ndarray, tuple[float, float], dict]:
    if isinstance(surface, Surface):
        dx, dy = (surface.dx, surface.dy) if pixel_size is None else _pair(pixel_size)
        return np.asarray(surface.heights), (dx, dy), surface.to_dict()
    if pixel_size is None:
        raise ValueError("pixel_size (m) is required for a height array")
    from ..surface import from_heights

    dx, dy = _pair(pixel_size)
    s = from_heights(np.asarray(surface), dx, dy)  # validates (finite, 2-D)
    return np.asarray(s.heights), (dx, dy), s.to_dict()


def _pair(v: Any) -> tuple[float, float]:
    from .._support.validate import pair

    return pair("pixel_size", v)


def _check_loads(window: PunchWindow, protocol: IndentProtocol, hardness: float) -> None:
    """The largest peak load must stay below what the punch can carry, H × A."""
    if not math.isfinite(hardness):
        return
    fmax = protocol.peak_loads[-1]
    cap = hardness * min(window.area, window.n_pixels * window.pixel_area)
    if not fmax < cap:
        what = ("a flat as large as the map" if window.diameter is None
                else f"the {window.diameter:.6g} m punch")  # fmt: skip
        raise ValueError(
            f"peak_loads must stay below what {what} can carry, H × A = {hardness:.4g} Pa × "
            f"{cap / hardness:.4g} m² = {cap:.4g} N (allowed: (0, {cap:.4g}) N), got "
            f"{fmax!r} N; lower the loads or raise the hardness"
        )


_REUSED = {  # run_cycles column → to_dict column of an elastic run
    "displacement": "displacement_m", "n_contact": "n_contact", "contact_area": "contact_area_m2",
    "max_pressure": "max_pressure_Pa", "unloading_stiffness": "unloading_stiffness_N_per_m",
    "partial_unloading_stiffness": "partial_unloading_stiffness_N_per_m", "converged": "converged",
}  # fmt: skip


def _elastic_cycles(reuse: Any, windows: list, loads: np.ndarray, material: Material,
                    settings: SolverSettings | None) -> list[dict[str, np.ndarray]]:  # fmt: skip
    """Split an elastic run given as ``reuse`` into the run_cycles columns of each window,
    checking that it is one (H = inf, same E*, solver settings, punches, centres and loads)."""
    cols = reuse
    if isinstance(reuse, IndentationResult):
        if math.isfinite(reuse.material.hardness):
            raise ValueError(
                f"reuse must be an elastic run (material.hardness = inf), got hardness "
                f"{reuse.material.hardness!r} Pa"
            )
        if not math.isclose(reuse.material.contact_modulus, material.contact_modulus, rel_tol=1e-12):
            raise ValueError(
                f"reuse was run with E* = {reuse.material.contact_modulus!r} Pa, this run with "
                f"{material.contact_modulus!r} Pa; give the same elastic constants"
            )
        mine = (SolverSettings() if settings is None else settings).to_dict()
        if reuse.settings.get("solver_settings") != mine:
            raise ValueError("reuse was run with other solver settings; give the same settings")
        cols = reuse.to_dict()
    try:
        keys = (*_REUSED.values(), "punch_diameter_m", "placement", "peak_load_N", "centre_x_m",
                "centre_y_m")  # fmt: skip
        cols = {k: np.asarray(cols[k]) for k in keys}
    except (KeyError, TypeError) as e:
        raise ValueError(
            f"reuse must be an IndentationResult or its to_dict() columns, with max_pressure_Pa "
            f"(missing: {e})"
        ) from None
    m = loads.size
    if any(v.shape != (len(windows) * m,) for v in cols.values()):
        raise ValueError(
            f"reuse has {cols['peak_load_N'].size} rows, this run {len(windows) * m} "
            f"({len(windows)} punch placements × {m} peak loads)"
        )
    out = []
    for r, (_i, j, w, _f) in enumerate(windows):
        sl = slice(r * m, (r + 1) * m)
        d = np.nan if w.diameter is None else w.diameter
        same = (np.allclose(cols["punch_diameter_m"][sl], d, rtol=1e-12, atol=0, equal_nan=True)
                and np.all(cols["placement"][sl] == j)
                and np.allclose(cols["centre_x_m"][sl], w.centre[0], rtol=1e-12, atol=0)
                and np.allclose(cols["centre_y_m"][sl], w.centre[1], rtol=1e-12, atol=0)
                and np.allclose(cols["peak_load_N"][sl], loads, rtol=1e-12, atol=0))  # fmt: skip
        if not same:
            raise ValueError(
                f"reuse rows {sl.start}–{sl.stop - 1} are not the punch of diameter {d!r} m, "
                f"placement {j} at {w.centre} m with these peak loads; run it with the same "
                "surface, punches, placements, seed and loads"
            )
        out.append({k: cols[c][sl] for k, c in _REUSED.items()})
    return out


@fill_doc(SHARED_DOCS)
def indent(
    surface: Surface | Any,
    *,
    punch_diameter: float | tuple[float, ...] | None = PAPER_PUNCH_DIAMETERS,
    peak_loads: tuple[float, ...] = PAPER_PEAK_LOADS,
    unload_fraction: float = 0.1,
    material: Material | None = None,
    placements: int | None = 3,
    seed: int = 0,
    pixel_size: float | tuple[float, float] | None = None,
    settings: SolverSettings | None = None,
    elastic: bool = True,
    reuse: IndentationResult | dict[str, Any] | None = None,
    truncation_increments: int = 1000,
    overlap: str = "warn",
    progress: bool = False,
    device: wp.DeviceLike = None,
) -> IndentationResult:
    """Flat-punch indentation with partial unloadings, as the paper's experiment (§ 4.1).

    Rigid circular flat punches press on the rough surface at increasing peak loads; at each
    peak the unloading stiffness K is measured both ways (Barber's initial slope and the
    paper's partial-unloading secant) with the plastic state frozen, and turned into
    E_c = √π·K/(2√A). The elastic solution (H = ∞) and Eq. 2 truncation are computed on the
    same punch disks and placements.

    Parameters
    ----------
    surface : Surface or (ny, nx) array_like
        The rough surface: a :class:`warptrunc.Surface` or heights z (m).
    punch_diameter : float, sequence of float or None
        Punch diameters d (m); each at most the map's smaller side. Default: the paper's 54.1,
        108.7 and 502.6 µm. None: one flat larger than the map (every pixel can touch;
        A = Lx·Ly; one placement).
    peak_loads : sequence of float
        Peak loads F of the cycles (N), strictly increasing, below H × A of every punch.
        Default: the paper's ten levels, each twice the previous, the last 500 mN.
    unload_fraction : float
        Partial unloading of each cycle as a fraction f of its peak load (dimensionless), in
        (0, 1).
    material : Material, optional
        Default :func:`~warptrunc.indent.protocol.default_material`: aluminium alloy
        (E = 70 GPa, ν = 0.33, H = 1.0 GPa) against diamond (E_i = 1141 GPa, ν_i = 0.07).
        ``hardness = inf``: elastic.
    placements : int or None
        Punch positions per diameter, random, inside the map and apart; None: one punch at
        the map centre.
    seed : int
        Seed of the random positions (``IndentProtocol.placement_seed``).
    pixel_size : float or (float, float), optional
        Pixel sides (m); required for an array, taken from a Surface.
    settings : SolverSettings, optional
        Contact-solver settings (precision, tolerances, iteration limit); default the
        solver's, with the penetration tolerance of each disk's heights.
    elastic : bool
        Also solve the elastic contact (H = ∞) on the same punches (the ``elastic_*`` columns;
        NaN when off). With ``hardness = inf`` the elastic–plastic columns are the elastic
        solution and are copied. With a finite hardness the elastic cycles run first, and
        the leading cycles of each punch whose elastic peak pressure stays below H are copied
        into the elastic–plastic columns instead of solved again (no pixel reaches the cap
        there, so the two solutions are one; ``settings["reused_elastic_cycles"]``).
    reuse : IndentationResult or dict, optional
        An elastic run (``hardness = inf``) of the same surface, punches, placements, seed,
        peak loads, unloading fraction, E* and solver settings, or its ``to_dict()`` columns
        (``max_pressure_Pa`` among them): its cycles are taken as the elastic ones instead of
        solved, as above (several hardness values from one elastic run). Punches, centres
        and loads are checked; the settings only for an IndentationResult.
    truncation_increments : int
        Depth increments of the Eq. 2 truncation curve under each punch.
    overlap : {"warn", "error"}
        Punches of one diameter that cannot be placed apart: warn and report the overlap
        (``overlap_fraction``), or raise.
    progress : bool
        tqdm bar over the cycles (stderr).
    {warp_device_obj}

    Returns
    -------
    IndentationResult
        One row per punch × placement × peak load.

    Raises
    ------
    ValueError
        A parameter out of range (the message names it): a punch larger than the map, peak
        loads not increasing or above H × A, an unloading fraction outside (0, 1).

    Notes
    -----
    Each punch is solved on its bounding window of the map (:mod:`warptrunc.indent.punch`),
    on a free half-space. The approach δ is measured from first touch at the highest pixel
    inside the disk; so is the truncation depth ω. Cycles run load → peak → partial unload →
    next peak on one solver; since unloading and reloading below the previous peak are elastic,
    each peak's state is that of monotonic loading to it.

    References
    ----------
    .. [1] J.R. Barber, Proc. R. Soc. A 459, 53 (2003). doi:10.1098/rspa.2002.1038
    .. [2] W.C. Oliver, G.M. Pharr, J. Mater. Res. 7, 1564 (1992). doi:10.1557/JMR.1992.1564
    """
    t_start = time.perf_counter()
    z, (dx, dy), surface_info = _heights(surface, pixel_size)
    protocol = IndentProtocol(
        punch_diameters=punch_diameter, peak_loads=peak_loads, unload_fraction=unload_fraction,
        placements=placements, placement_seed=seed, overlap=overlap,
        truncation_increments=truncation_increments,
    )  # fmt: skip
    material = default_material() if material is None else material
    if not isinstance(material, Material):
        raise ValueError(f"material must be a warptrunc.Material, got {type(material).__name__}")
    hardness = material.hardness
    if settings is not None and not isinstance(settings, SolverSettings):
        raise ValueError(f"settings must be a SolverSettings, got {type(settings).__name__}")
    dev = resolve_device(device)
    ny, nx = z.shape
    lx, ly = nx * dx, ny * dy
    diameters = (None,) if protocol.punch_diameters is None else protocol.punch_diameters
    windows: list[tuple[int, int, PunchWindow, float]] = []
    for i, d in enumerate(diameters):
        if d is None:
            centres, frac = np.array([[0.5 * lx, 0.5 * ly]]), np.zeros(1)
        else:
            centres, frac = place_punches(
                (lx, ly), d, protocol.placements, seed=(protocol.placement_seed, i),
                overlap=protocol.overlap,
            )  # fmt: skip
        for j, c in enumerate(centres):
            w = punch_window(z, (dx, dy), d, (float(c[0]), float(c[1])))
            _check_loads(w, protocol, hardness)
            windows.append((i, j, w, float(frac[j])))
    loads = np.asarray(protocol.peak_loads, dtype=np.float64)
    m = loads.size
    two = elastic and math.isfinite(hardness)
    given = (None if reuse is None or not math.isfinite(hardness)
             else _elastic_cycles(reuse, windows, loads, material, settings))  # fmt: skip
    cols: dict[str, list] = {}

    def add(name: str, values: Any) -> None:
        cols.setdefault(name, []).append(np.asarray(values))

    timings = {"elastic_plastic_s": 0.0, "elastic_s": 0.0, "truncation_s": 0.0}
    per_punch = []
    n_reused = 0
    solve_elastic = two or (given is not None)
    with progress_bar(total=len(windows) * m * (2 if solve_elastic else 1),
                      desc="indentation cycles", unit="cycle", enabled=progress) as bar:  # fmt: skip
        for r, (_i, j, w, frac) in enumerate(windows):
            t0 = time.perf_counter()
            if given is not None:
                el = given[r]
                bar.update(m)
            elif two:  # first, so that the elastic–plastic run can take its unyielded cycles
                el = run_cycles(w, loads, protocol.unload_fraction, material, hardness=math.inf,
                                settings=settings, device=dev, step=bar.update)  # fmt: skip
            else:
                el = None
            t1 = time.perf_counter()
            ep = run_cycles(w, loads, protocol.unload_fraction, material, hardness=hardness,
                            settings=settings, device=dev, step=bar.update, elastic=el)  # fmt: skip
            if el is not None:
                below = (el["max_pressure"] < hardness) & el["converged"].astype(bool)
                n_reused += m if below.all() else int(np.argmin(below))
            if el is None and elastic:
                el = ep
            if not elastic:
                el = None
            t2 = time.perf_counter()
            tr = truncation_at_loads(w, loads, material.contact_modulus,
                                     n_increments=protocol.truncation_increments, device=dev)  # fmt: skip
            t3 = time.perf_counter()
            timings["elastic_plastic_s"] += t2 - t1
            timings["elastic_s"] += t1 - t0
            timings["truncation_s"] += t3 - t2
            nan = np.full(m, np.nan)
            add("punch_diameter", np.full(m, np.nan if w.diameter is None else w.diameter))
            add("placement", np.full(m, j, dtype=np.int64))
            add("centre_x", np.full(m, w.centre[0]))
            add("centre_y", np.full(m, w.centre[1]))
            add("overlap_fraction", np.full(m, frac))
            add("punch_area", np.full(m, w.area))
            add("n_punch_pixels", np.full(m, w.n_pixels, dtype=np.int64))
            add("peak_load", loads)
            for k in ("displacement", "n_contact", "contact_area", "plastic_area",
                      "plastic_volume", "max_pressure", "unloading_stiffness", "partial_unloading_stiffness",
                      "converged"):  # fmt: skip
                add(k, ep[k])
            add("E_c", modulus_from_stiffness(ep["unloading_stiffness"], w.area))
            add("E_c_partial", modulus_from_stiffness(ep["partial_unloading_stiffness"], w.area))
            for k in ("displacement", "contact_area", "unloading_stiffness",
                      "partial_unloading_stiffness"):  # fmt: skip
                add(f"elastic_{k}", nan if el is None else el[k])
            add("elastic_converged", np.zeros(m, bool) if el is None else el["converged"])
            add("truncation_depth", tr["depth"])
            add("truncation_contact_area", tr["contact_area"])
            add("truncation_stiffness", tr["stiffness"])
            per_punch.append({
                "punch_diameter_m": w.diameter, "placement": j, "centre_m": list(w.centre),
                "window": [int(v) for v in (*w.origin, *w.mask.shape)],
                "n_punch_pixels": w.n_pixels, "overlap_fraction": frac,
                "disk_Rt_m": float(np.ptp(w.disk_heights)),
            })  # fmt: skip
    algo = (SolverSettings() if settings is None else settings).algorithm
    settings_info = {
        "surface": surface_info,
        "device": str(dev),
        "solver": f"warptrunc contact solver, algorithm {algo!r} ("
        + ("bound-constrained CG, Vollebregt 2014" if algo == "bccg"
           else "constrained CG, Polonsky & Keer 1999")
        + "), free half-space on each punch's window"
        + (", pressure capped at H" if math.isfinite(hardness) else ""),
        "reused_elastic_cycles": n_reused,
        "solver_settings": (SolverSettings() if settings is None else settings).to_dict(),
        "elastic_reference": bool(elastic),
        "punches": per_punch,
        "seconds": {**timings, "total_s": time.perf_counter() - t_start},
    }  # fmt: skip
    arrays = {k: np.concatenate(v) for k, v in cols.items()}
    return IndentationResult(**arrays, material=material, protocol=protocol, settings=settings_info)
