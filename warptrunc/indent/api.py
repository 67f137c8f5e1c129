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
from ..slope import slope_record
from ..surface import Surface
from .face import check_same_face, face_record, face_settings, placement_face, punch_faces
from .placement import solve_placement
from .protocol import IndentProtocol, default_material
from .punch import PunchWindow, place_punches
from .refine import NOTES, WindowSource
from .results import IndentationResult

__all__ = ["indent"]


def _heights(surface: Any, pixel_size: Any) -> tuple[np.ndarray, tuple[float, float], dict, Any]:
    if isinstance(surface, Surface):
        dx, dy = (surface.dx, surface.dy) if pixel_size is None else _pair(pixel_size)
        meta = {**surface.to_dict(), "slope": slope_record(surface)}  # h′_rms at the map's pixel
        return np.asarray(surface.heights), (dx, dy), meta, surface.params
    if pixel_size is None:
        raise ValueError("pixel_size (m) is required for a height array")
    from ..surface import from_heights

    dx, dy = _pair(pixel_size)
    s = from_heights(np.asarray(surface), dx, dy)  # validates (finite, 2-D)
    return np.asarray(s.heights), (dx, dy), {**s.to_dict(), "slope": slope_record(s)}, None


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
        what = (
            "a flat as large as the map"
            if window.diameter is None
            else f"the {window.diameter:.6g} m punch"
        )
        raise ValueError(
            f"peak_loads must stay below what {what} can carry, H × A = {hardness:.4g} Pa × "
            f"{cap / hardness:.4g} m² = {cap:.4g} N (allowed: (0, {cap:.4g}) N), got "
            f"{fmax!r} N; lower the loads or raise the hardness"
        )


_REUSED = {  # run_cycles column → to_dict column of an elastic run
    "displacement": "displacement_m",
    "n_contact": "n_contact_pixels",
    "contact_area": "contact_area_m2",
    "max_pressure": "max_pressure_Pa",
    "unloading_stiffness": "unloading_stiffness_N_per_m",
    "partial_unloading_stiffness": "partial_unloading_stiffness_N_per_m",
    "converged": "converged",
}


def _elastic_cycles(
    reuse: Any, windows: list, loads: np.ndarray, material: Material, solver: SolverSettings
) -> list[dict[str, np.ndarray]]:
    """Split an elastic run given as ``reuse`` into the run_cycles columns of each window,
    checking that it is one (H = inf, same E*, solver settings, punches, centres and loads)."""
    cols = reuse
    if isinstance(reuse, IndentationResult):
        if math.isfinite(reuse.material.hardness):
            raise ValueError(
                f"reuse must be an elastic run (material.hardness = inf), got hardness "
                f"{reuse.material.hardness!r} Pa"
            )
        if not math.isclose(
            reuse.material.contact_modulus, material.contact_modulus, rel_tol=1e-12
        ):
            raise ValueError(
                f"reuse was run with E* = {reuse.material.contact_modulus!r} Pa, this run with "
                f"{material.contact_modulus!r} Pa; give the same elastic constants"
            )
        if reuse.settings.get("solver_settings") != solver.to_dict():
            raise ValueError("reuse was run with other solver settings; give the same settings")
        cols = reuse.to_dict()
    if isinstance(cols, dict) and "n_contact_pixels" not in cols and "n_contact" in cols:
        cols = {**cols, "n_contact_pixels": cols["n_contact"]}  # the reproduce pieces' name
    try:
        keys = (
            *_REUSED.values(),
            "punch_diameter_m",
            "placement",
            "peak_load_N",
            "centre_x_m",
            "centre_y_m",
        )
        have = cols
        cols = {k: np.asarray(have[k]) for k in keys}
        n = cols["peak_load_N"].size
        det = have.get("detection_displacement_m")  # optional: NaN where not stored
        cols["detection_displacement_m"] = np.full(n, np.nan) if det is None else np.asarray(det)
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
        same = (
            np.allclose(cols["punch_diameter_m"][sl], d, rtol=1e-12, atol=0, equal_nan=True)
            and np.all(cols["placement"][sl] == j)
            and np.allclose(cols["centre_x_m"][sl], w.centre[0], rtol=1e-12, atol=0)
            and np.allclose(cols["centre_y_m"][sl], w.centre[1], rtol=1e-12, atol=0)
            and np.allclose(cols["peak_load_N"][sl], loads, rtol=1e-12, atol=0)
        )
        if not same:
            raise ValueError(
                f"reuse rows {sl.start}–{sl.stop - 1} are not the punch of diameter {d!r} m, "
                f"placement {j} at {w.centre} m with these peak loads; run it with the same "
                "surface, punches, placements, seed and loads"
            )
        out.append(
            {
                **{k: cols[c][sl] for k, c in _REUSED.items()},
                "detection_displacement": cols["detection_displacement_m"][sl],
            }
        )
    return out


@fill_doc(SHARED_DOCS)
def indent(
    surface: Surface | Any,
    *,
    protocol: IndentProtocol | None = None,
    material: Material | None = None,
    solver: SolverSettings | None = None,
    reuse: IndentationResult | dict[str, Any] | None = None,
    pixel_size: float | tuple[float, float] | None = None,
    progress: bool = False,
    device: wp.DeviceLike = None,
    devices: Any = None,
) -> IndentationResult:
    """Flat-punch indentation with partial unloadings, as the paper's experiment (§ 4.1).

    Rigid circular flat punches press on the rough surface at increasing peak loads; at each
    peak the unloading stiffness K is measured both ways (Barber's initial slope and the
    paper's partial-unloading secant) with the plastic state frozen, and turned into
    E_c = √π·K/(2√A). The elastic solution (H = ∞) and Eq. 2 truncation are computed on the
    same punch disks and placements.

    Parameters
    ----------
    surface : Surface, (ny, nx) array_like or list of Surface
        The rough surface: a :class:`warptrunc.Surface` or heights z (m); or several
        realisations of one surface (a list of Surfaces of one size and pixel: the same
        punches and placements on each, rows numbered by ``realisation``).
    protocol : IndentProtocol, optional
        The experiment (:class:`~warptrunc.indent.IndentProtocol`; its defaults when None: the
        paper's three punches, its five heaviest peak loads, two placements each, cells judged
        by their contact pixels; :data:`~warptrunc.indent.PAPER_PROTOCOL` is the paper's ten
        loads and three placements):

        - ``punch_diameters`` (m), each at most the map's smaller side; None: one flat larger
          than the map (every pixel can touch; A = Lx·Ly; one placement);
        - ``peak_loads`` (N), strictly increasing, below H × A of every punch;
        - ``unload_fraction``, the partial unloading of each cycle as a fraction of its peak;
        - ``placements`` per diameter, random, inside the map and apart (seed
          ``placement_seed``; ``overlap`` says what happens when they cannot be kept apart);
          None: one punch at the map centre;
        - ``truncation_increments`` of the Eq. 2 truncation curve under each punch;
        - ``resolution_tol``, ``min_contact_pixels``, ``refine_max``: a cell (punch,
          placement, peak) is resolved when Barber's K and the contact area change by less than
          ``resolution_tol`` (relative) when the pixel is halved, with at least
          ``min_contact_pixels`` in contact; the punch windows of a WM surface are generated
          again (same terms, the map's height scale) at pixel/2, /4, … up to
          pixel/``refine_max`` for the cells not yet resolved (:mod:`warptrunc.indent.refine`).
          ``refine_max = 1``: nothing is refined, the cells are judged by their contact pixels
          (so are those of a read map);
        - ``elastic``: also solve the elastic contact (H = ∞) on the same punches (the
          ``elastic_*`` columns; NaN when off). With ``hardness = inf`` the elastic–plastic
          columns are the elastic solution and are copied. With a finite hardness the elastic
          cycles run first, and the leading cycles of each punch whose elastic peak pressure
          stays below H are copied into the elastic–plastic columns instead of solved again (no
          pixel reaches the cap there, so the two solutions are one;
          ``settings["reused_elastic_cycles"]``);
        - ``face``, the punch face (:class:`~warptrunc.indent.face.PunchFaceSpec`): a tilt θ
          (degrees, held fixed: the punch translates, never rotates; Barber's K is that of the
          contact set) and a generated rough face (rms ``roughness``, one face per punch
          diameter from the seed ``(face.seed, diameter index)``, the same at every placement
          and realisation; the gap is the punch plane minus the sum of both surfaces' heights)
          or a measured one (``file``: centred on each punch, levelled over its disk and
          resampled to the window's pixel by bilinear interpolation).
    material : Material, optional
        Default :func:`~warptrunc.indent.protocol.default_material`: aluminium alloy
        (E = 70 GPa, ν = 0.33, H = 1.0 GPa) against diamond (E_i = 1141 GPa, ν_i = 0.07).
        ``hardness = inf``: elastic.
    solver : SolverSettings, optional
        Contact-solver settings (precision, tolerances, iteration limit, interaction law);
        default the solver's, with the penetration tolerance of each disk's heights. An
        adhesive ``solver.adhesion`` (:class:`~warptrunc.contact.adhesion.Adhesion`, the punch
        face's adhesion to the surface) needs ``hardness = inf``: the pressure cap and the
        plastic flow are not solved with adhesion (ValueError); the loads are then the whole
        traction's and Barber's stiffness that of the repulsive contact at a fixed area.
    reuse : IndentationResult or dict, optional
        An elastic run (``hardness = inf``) of the same surface, punches, placements, seed,
        peak loads, unloading fraction, E* and solver settings, or its ``to_dict()`` columns
        (``max_pressure_Pa`` among them): its cycles are taken as the elastic ones instead of
        solved, as ``protocol.elastic`` describes (several hardness values from one elastic
        run). Punches, centres and loads are checked; the settings and the face only for an
        IndentationResult.
    pixel_size : float or (float, float), optional
        Pixel sides (m); required for an array, taken from a Surface.
    progress : bool
        Report the cycles on stderr (a bar on a terminal, else a line every few seconds).
    {warp_device_obj}
    devices : int, "auto" or list, optional
        Spread each contact solve (every punch window's cycles) over several devices
        (``contact_solver(..., devices=...)``; JAX); default None: ``device`` alone. A window
        whose rows a device count does not divide gets rows of its floor added (no contact
        there: the same solution; :func:`~warptrunc.indent.cycles.make_solver`).

    Returns
    -------
    IndentationResult
        One row per realisation × punch × placement × peak load, each solved at its final
        pixel; the fits use the cells ``in_fit`` (resolved, not saturated, converged).

    Raises
    ------
    ValueError
        A parameter out of range (the message names it): a punch larger than the map, peak
        loads not increasing or above H × A, an unloading fraction outside (0, 1).

    Notes
    -----
    Each punch is solved on its bounding window of the map (:mod:`warptrunc.indent.punch`),
    on a free half-space. The approach δ is measured from first touch at the highest pixel
    inside the disk (of the composite, sample plus punch face, when the face is tilted or
    rough); the truncation depth ω from the sample's highest pixel (truncation reads the
    sample alone). Cycles run load → peak → partial unload →
    next peak on one solver; since unloading and reloading below the previous peak are elastic,
    each peak's state is that of monotonic loading to it.

    References
    ----------
    .. [1] J.R. Barber, Proc. R. Soc. A 459, 53 (2003). doi:10.1098/rspa.2002.1038
    .. [2] W.C. Oliver, G.M. Pharr, J. Mater. Res. 7, 1564 (1992). doi:10.1557/JMR.1992.1564
    """
    t_start = time.perf_counter()
    maps = _realisations(surface, pixel_size)
    protocol = IndentProtocol() if protocol is None else protocol
    if not isinstance(protocol, IndentProtocol):
        raise ValueError(
            f"protocol must be a warptrunc.IndentProtocol, got {type(protocol).__name__}"
        )
    material = default_material() if material is None else material
    if not isinstance(material, Material):
        raise ValueError(f"material must be a warptrunc.Material, got {type(material).__name__}")
    hardness = material.hardness
    solver = SolverSettings() if solver is None else solver
    if not isinstance(solver, SolverSettings):
        raise ValueError(f"solver must be a SolverSettings, got {type(solver).__name__}")
    law = solver.adhesion
    if law.active and math.isfinite(hardness):
        raise ValueError(
            f"adhesion ({law.law}) with a finite hardness ({hardness:g} Pa) is not solved: the "
            "pressure cap bounds the wall's reaction, and the plastic flow changes the heights "
            "the adhesive solve pulls on; give hardness = inf (--hardness inf)"
        )
    elastic = protocol.elastic
    dev = resolve_device(device)
    z, (dx, dy), _info, _params = maps[0]
    ny, nx = z.shape
    lx, ly = nx * dx, ny * dy
    sources = [WindowSource(zz, px, par, device=dev) for zz, px, _info, par in maps]
    diameters = (None,) if protocol.punch_diameters is None else protocol.punch_diameters
    faces = punch_faces(protocol.face, diameters, max(dx, dy))
    windows: list[tuple[int, int, int, PunchWindow, float]] = []
    for i, d in enumerate(diameters):
        if d is None:
            centres, frac = np.array([[0.5 * lx, 0.5 * ly]]), np.zeros(1)
        else:
            centres, frac = place_punches(
                (lx, ly),
                d,
                protocol.placements,
                seed=(protocol.placement_seed, i),
                overlap=protocol.overlap,
            )
        for k, src in enumerate(sources):
            for j, c in enumerate(centres):
                at = (float(c[0]), float(c[1]))
                sample = src.window(d, at) if protocol.face.tilt_reference == "local" else None
                face = placement_face(faces[i], protocol.face, k * len(centres) + j, sample)
                w = src.window(d, at, face=face)
                _check_loads(w, protocol, hardness)
                windows.append((k, i, j, w, float(frac[j])))
    windows.sort(key=lambda t: t[:3])  # realisation, punch, placement
    loads = np.asarray(protocol.peak_loads, dtype=np.float64)
    m = loads.size
    given = None
    if reuse is not None and math.isfinite(hardness):
        check_same_face(reuse, protocol)
        if protocol.refine_max > 1 or len(maps) > 1:
            raise ValueError(
                f"reuse needs refine_max = 1 and one surface (its elastic cycles are those of "
                f"the map's pixel), got refine_max = {protocol.refine_max} and {len(maps)} "
                "surfaces"
            )
        given = _elastic_cycles(reuse, [t[1:] for t in windows], loads, material, solver)
    cols: dict[str, list] = {}
    timings = {"elastic_plastic_s": 0.0, "elastic_s": 0.0, "refinement_s": 0.0, "truncation_s": 0.0}
    per_punch = []
    n_reused = 0
    solve_elastic = (elastic and math.isfinite(hardness)) or (given is not None)
    with progress_bar(
        total=len(windows) * m * (2 if solve_elastic else 1),
        desc="indentation cycles (map pixel)",
        unit="cycle",
        enabled=progress,
    ) as bar:
        for r, (k, _i, j, w, frac) in enumerate(windows):
            rows, info = solve_placement(
                sources[k],
                w,
                protocol,
                material,
                solver=solver,
                given=None if given is None else given[r],
                step=bar.update,
                device=dev,
                devices=devices,
            )
            n_reused += info["reused"]
            for key, v in info["seconds"].items():
                timings[key] += v
            rows.update(
                placement=np.full(m, j, dtype=np.int64),
                realisation=np.full(m, k, dtype=np.int64),
                overlap_fraction=np.full(m, frac),
            )
            for key, v in rows.items():
                cols.setdefault(key, []).append(np.asarray(v))
            per_punch.append(
                {
                    "realisation": k,
                    "punch_diameter_m": w.diameter,
                    "placement": j,
                    "centre_m": list(w.centre),
                    "window": [int(v) for v in (*w.origin, *w.mask.shape)],
                    "n_punch_pixels": w.n_pixels,
                    "overlap_fraction": frac,
                    "disk_Rt_m": float(np.ptp(w.surface_disk_heights)),
                    "refined_windows": info["windows"],
                    **face_record(w),
                }
            )
    algo = solver.algorithm
    settings_info = {
        "surface": maps[0][2] if len(maps) == 1 else [mp[2] for mp in maps],
        "device": str(dev),
        "solver": f"warptrunc contact solver, algorithm {algo!r} ("
        + (
            "bound-constrained CG, Vollebregt 2014"
            if algo == "bccg"
            else "constrained CG, Polonsky & Keer 1999"
        )
        + "), free half-space on each punch's window"
        + (", pressure capped at H" if math.isfinite(hardness) else ""),
        "reused_elastic_cycles": n_reused,
        "solver_settings": solver.to_dict(),
        "elastic_reference": bool(elastic),
        "refinement": {
            "resolution_tol": protocol.resolution_tol,
            "refine_max": protocol.refine_max,
            "min_contact_pixels": protocol.min_contact_pixels,
            "maps": [{"refinable": src.refinable, "note": src.why_not} for src in sources],
            "notes": NOTES,
        },
        "punch_face": face_settings(diameters, faces),
        "punches": per_punch,
        "seconds": {**timings, "total_s": time.perf_counter() - t_start},
    }
    arrays = {k: np.concatenate(v) for k, v in cols.items()}
    return IndentationResult(**arrays, material=material, protocol=protocol, settings=settings_info)


def _realisations(surface: Any, pixel_size: Any) -> list[tuple]:
    """(heights, pixel, Surface.to_dict(), Surface.params or None) of each realisation; all of
    one size and pixel."""
    many = (
        isinstance(surface, (list, tuple))
        and surface
        and all(isinstance(v, Surface) for v in surface)
    )
    maps = [_heights(v, pixel_size) for v in (surface if many else [surface])]
    z0, px0 = maps[0][:2]
    for z, px, *_ in maps[1:]:
        if z.shape != z0.shape or not np.allclose(px, px0, rtol=1e-12, atol=0):
            raise ValueError(
                f"surface: the realisations must share one size and pixel, got {z.shape} with "
                f"pixels {px} m against {z0.shape} with {px0} m"
            )
    return maps
