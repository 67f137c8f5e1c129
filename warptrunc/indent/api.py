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
        solution and are copied.
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
    cols: dict[str, list] = {}

    def add(name: str, values: Any) -> None:
        cols.setdefault(name, []).append(np.asarray(values))

    timings = {"elastic_plastic_s": 0.0, "elastic_s": 0.0, "truncation_s": 0.0}
    per_punch = []
    with progress_bar(total=len(windows) * m * (2 if two else 1), desc="indentation cycles",
                      unit="cycle", enabled=progress) as bar:  # fmt: skip
        for _i, j, w, frac in windows:
            t0 = time.perf_counter()
            ep = run_cycles(w, loads, protocol.unload_fraction, material, hardness=hardness,
                            settings=settings, device=dev, step=bar.update)  # fmt: skip
            t1 = time.perf_counter()
            el = (run_cycles(w, loads, protocol.unload_fraction, material, hardness=math.inf,
                             settings=settings, device=dev, step=bar.update)
                  if two else ep if elastic else None)  # fmt: skip
            t2 = time.perf_counter()
            tr = truncation_at_loads(w, loads, material.contact_modulus,
                                     n_increments=protocol.truncation_increments, device=dev)  # fmt: skip
            t3 = time.perf_counter()
            timings["elastic_plastic_s"] += t1 - t0
            timings["elastic_s"] += t2 - t1
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
                      "plastic_volume", "unloading_stiffness", "partial_unloading_stiffness",
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
    settings_info = {
        "surface": surface_info,
        "device": str(dev),
        "solver": "warptrunc constrained conjugate gradients (Polonsky & Keer 1999), free "
        "half-space on each punch's window" + (", pressure capped at H" if math.isfinite(hardness)
                                               else ""),
        "solver_settings": (SolverSettings() if settings is None else settings).to_dict(),
        "elastic_reference": bool(elastic),
        "punches": per_punch,
        "seconds": {**timings, "total_s": time.perf_counter() - t_start},
    }  # fmt: skip
    arrays = {k: np.concatenate(v) for k, v in cols.items()}
    return IndentationResult(**arrays, material=material, protocol=protocol, settings=settings_info)
