# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
""":func:`indent`, the paper's nanoindentation experiment (§ 4.1, Fig. 6) run on a height map."""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

import numpy as np
import warp as wp

from .._support.device import resolve_device
from .._support.docs import SHARED_DOCS, fill_doc
from .._support.progress import progress_bar
from ..contact.settings import SolverSettings
from ..material import Material
from ..surface import Surface
from .face import DEFAULT_HURST, check_same_face, face_record, face_settings, punch_faces
from .placement import solve_placement
from .protocol import PAPER_PEAK_LOADS, PAPER_PUNCH_DIAMETERS, IndentProtocol, default_material
from .punch import PunchWindow, place_punches
from .refine import NOTES, WindowSource
from .results import IndentationResult

__all__ = ["indent"]


def _heights(surface: Any, pixel_size: Any) -> tuple[np.ndarray, tuple[float, float], dict, Any]:
    if isinstance(surface, Surface):
        dx, dy = (surface.dx, surface.dy) if pixel_size is None else _pair(pixel_size)
        return np.asarray(surface.heights), (dx, dy), surface.to_dict(), surface.params
    if pixel_size is None:
        raise ValueError("pixel_size (m) is required for a height array")
    from ..surface import from_heights

    dx, dy = _pair(pixel_size)
    s = from_heights(np.asarray(surface), dx, dy)  # validates (finite, 2-D)
    return np.asarray(s.heights), (dx, dy), s.to_dict(), None


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
    "displacement": "displacement_m", "n_contact": "n_contact_pixels", "contact_area": "contact_area_m2",
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
    if isinstance(cols, dict) and "n_contact_pixels" not in cols and "n_contact" in cols:
        cols = {**cols, "n_contact_pixels": cols["n_contact"]}  # columns written before issue 38
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
    resolution_tol: float = 0.02,
    min_contact_pixels: int = 100,
    refine_max: int = 8,
    punch_tilt_deg: float = 0.0,
    punch_tilt_azimuth_deg: float = 0.0,
    punch_roughness: float = 0.0,
    punch_hurst: float = DEFAULT_HURST,
    punch_cutoff_short: float | None = None,
    punch_cutoff_long: float | None = None,
    punch_face_seed: int = 0,
    punch_face_file: str | Path | None = None,
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
    resolution_tol : float
        A cell (punch, placement, peak) is resolved when Barber's K and the contact area
        change by less than this (relative) when the pixel is halved
        (:mod:`warptrunc.indent.refine`).
    min_contact_pixels : int
        Fewest contact pixels of a resolved cell.
    refine_max : int
        Largest refinement of the pixel, a power of 2: the punch windows of a WM surface are
        generated again (same terms, the map's height scale) at pixel/2, /4, … for the cells
        not yet resolved. 1: nothing is refined, the cells are judged by their contact pixels
        (so are those of a read map).
    punch_tilt_deg : float
        Tilt θ of every punch face against the sample's mean plane (degrees), in [0, 5]: a
        misaligned flat, held fixed as the indenter's shaft holds it (the punch translates,
        never rotates; Barber's K is that of the contact set). 0.1° rises 0.88 µm over
        502.6 µm.
    punch_tilt_azimuth_deg : float
        Direction of the tilted face's edge nearest the sample (degrees, from +x toward +y),
        the same at every placement; the tilt axis passes through the punch centre,
        perpendicular to it.
    punch_roughness : float
        rms R_q of a generated self-affine rough punch face (m), over the disk after levelling;
        0: smooth. One face per punch diameter (seed ``(punch_face_seed, diameter index)``),
        the same at every placement and realisation; the gap is the punch plane minus the sum
        of both surfaces' heights.
    punch_hurst : float
        Hurst exponent H of that face, in (0, 1]: C(q) ∝ q^(−2−2H).
    punch_cutoff_short : float, optional
        Its shortest wavelength λ_s (m); default 2 pixels of the map.
    punch_cutoff_long : float, optional
        Its longest wavelength λ_L (m); default the punch diameter.
    punch_face_seed : int
        Seed of the generated face (host NumPy: the same face on every device).
    punch_face_file : str or Path, optional
        A measured punch face, a height map read by :func:`warptrunc.io.read_height_map`,
        instead of ``punch_roughness``: centred on each punch, levelled over its disk and
        resampled to the window's pixel by bilinear interpolation
        (:mod:`warptrunc.indent.face`).
    progress : bool
        tqdm bar over the cycles (stderr).
    {warp_device_obj}
    devices : int, "auto" or list, optional
        Spread each contact solve (every punch window's cycles) over several devices (``ContactSolver(..., devices=...)``;
        JAX); default None: ``device`` alone. A window
        whose rows a device count does not divide gets rows of its floor added (no contact
        there: the same solution; :func:`~warptrunc.indent.protocol.make_solver`).

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
    protocol = IndentProtocol(
        punch_diameters=punch_diameter, peak_loads=peak_loads, unload_fraction=unload_fraction,
        placements=placements, placement_seed=seed, overlap=overlap,
        truncation_increments=truncation_increments, resolution_tol=resolution_tol,
        min_contact_pixels=min_contact_pixels, refine_max=refine_max,
        punch_tilt_deg=punch_tilt_deg, punch_tilt_azimuth_deg=punch_tilt_azimuth_deg,
        punch_roughness=punch_roughness, punch_hurst=punch_hurst,
        punch_cutoff_short=punch_cutoff_short, punch_cutoff_long=punch_cutoff_long,
        punch_face_seed=punch_face_seed,
        punch_face_file=None if punch_face_file is None else str(punch_face_file),
    )  # fmt: skip
    material = default_material() if material is None else material
    if not isinstance(material, Material):
        raise ValueError(f"material must be a warptrunc.Material, got {type(material).__name__}")
    hardness = material.hardness
    if settings is not None and not isinstance(settings, SolverSettings):
        raise ValueError(f"settings must be a SolverSettings, got {type(settings).__name__}")
    dev = resolve_device(device)
    z, (dx, dy), _info, _params = maps[0]
    ny, nx = z.shape
    lx, ly = nx * dx, ny * dy
    sources = [WindowSource(zz, px, par, device=dev) for zz, px, _info, par in maps]
    diameters = (None,) if protocol.punch_diameters is None else protocol.punch_diameters
    faces = punch_faces(protocol, diameters, max(dx, dy))
    windows: list[tuple[int, int, int, PunchWindow, float]] = []
    for i, d in enumerate(diameters):
        if d is None:
            centres, frac = np.array([[0.5 * lx, 0.5 * ly]]), np.zeros(1)
        else:
            centres, frac = place_punches(
                (lx, ly), d, protocol.placements, seed=(protocol.placement_seed, i),
                overlap=protocol.overlap,
            )  # fmt: skip
        for k, src in enumerate(sources):
            for j, c in enumerate(centres):
                w = src.window(d, (float(c[0]), float(c[1])), face=faces[i])
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
        given = _elastic_cycles(reuse, [t[1:] for t in windows], loads, material, settings)
    cols: dict[str, list] = {}
    timings = {"elastic_plastic_s": 0.0, "elastic_s": 0.0, "refinement_s": 0.0,
               "truncation_s": 0.0}  # fmt: skip
    per_punch = []
    n_reused = 0
    solve_elastic = (elastic and math.isfinite(hardness)) or (given is not None)
    with progress_bar(total=len(windows) * m * (2 if solve_elastic else 1),
                      desc="indentation cycles (map pixel)", unit="cycle",
                      enabled=progress) as bar:  # fmt: skip
        for r, (k, _i, j, w, frac) in enumerate(windows):
            rows, info = solve_placement(
                sources[k], w, protocol, material, settings=settings, device=dev, devices=devices,
                elastic=elastic, given=None if given is None else given[r], step=bar.update,
            )  # fmt: skip
            n_reused += info["reused"]
            for key, v in info["seconds"].items():
                timings[key] += v
            rows.update(placement=np.full(m, j, dtype=np.int64),
                        realisation=np.full(m, k, dtype=np.int64),
                        overlap_fraction=np.full(m, frac))  # fmt: skip
            for key, v in rows.items():
                cols.setdefault(key, []).append(np.asarray(v))
            per_punch.append({
                "realisation": k, "punch_diameter_m": w.diameter, "placement": j,
                "centre_m": list(w.centre), "window": [int(v) for v in (*w.origin, *w.mask.shape)],
                "n_punch_pixels": w.n_pixels, "overlap_fraction": frac,
                "disk_Rt_m": float(np.ptp(w.surface_disk_heights)),
                "refined_windows": info["windows"], **face_record(w),
            })  # fmt: skip
    algo = (SolverSettings() if settings is None else settings).algorithm
    settings_info = {
        "surface": maps[0][2] if len(maps) == 1 else [mp[2] for mp in maps],
        "device": str(dev),
        "solver": f"warptrunc contact solver, algorithm {algo!r} ("
        + ("bound-constrained CG, Vollebregt 2014" if algo == "bccg"
           else "constrained CG, Polonsky & Keer 1999")
        + "), free half-space on each punch's window"
        + (", pressure capped at H" if math.isfinite(hardness) else ""),
        "reused_elastic_cycles": n_reused,
        "solver_settings": (SolverSettings() if settings is None else settings).to_dict(),
        "elastic_reference": bool(elastic),
        "refinement": {
            "resolution_tol": protocol.resolution_tol, "refine_max": protocol.refine_max,
            "min_contact_pixels": protocol.min_contact_pixels,
            "maps": [{"refinable": src.refinable, "note": src.why_not} for src in sources],
            "notes": NOTES,
        },
        "punch_face": face_settings(diameters, faces),
        "punches": per_punch,
        "seconds": {**timings, "total_s": time.perf_counter() - t_start},
    }  # fmt: skip
    arrays = {k: np.concatenate(v) for k, v in cols.items()}
    return IndentationResult(**arrays, material=material, protocol=protocol, settings=settings_info)


def _realisations(surface: Any, pixel_size: Any) -> list[tuple]:
    """(heights, pixel, Surface.to_dict(), Surface.params or None) of each realisation; all of
    one size and pixel."""
    many = isinstance(surface, (list, tuple)) and surface and all(
        isinstance(v, Surface) for v in surface)  # fmt: skip
    maps = [_heights(v, pixel_size) for v in (surface if many else [surface])]
    z0, px0 = maps[0][:2]
    for z, px, *_ in maps[1:]:
        if z.shape != z0.shape or not np.allclose(px, px0, rtol=1e-12, atol=0):
            raise ValueError(
                f"surface: the realisations must share one size and pixel, got {z.shape} with "
                f"pixels {px} m against {z0.shape} with {px0} m"
            )
    return maps
