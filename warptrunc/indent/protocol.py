# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The paper's indentation protocol (§ 4.1): its parameters, the default material, and the
load / partial-unload cycles under one punch.

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

import dataclasses
import math
import os
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._support.docs import SHARED_DOCS, fill_doc
from ..contact.bccg import PRECONDITION_ABOVE
from ..contact.settings import SolverSettings
from ..contact.solver import ContactSolver
from ..material import Material
from ..params import check_fields, param
from .punch import PunchWindow

__all__ = [
    "ALUMINIUM_HARDNESS",
    "PAPER_PEAK_LOADS",
    "PAPER_PUNCH_DIAMETERS",
    "IndentProtocol",
    "default_material",
    "make_solver",
    "run_cycles",
]

PAPER_PUNCH_DIAMETERS = (54.1e-6, 108.7e-6, 502.6e-6)
"""Diameters of the paper's flat diamond punches (m): FLT-D050, FLT-D100, FLT-D500 (§ 4.1)."""

PAPER_PEAK_LOADS = tuple(0.5 / 2**k for k in range(9, -1, -1))
"""The paper's ten peak loads (N): each twice the previous, the last 500 mN (§ 4.1)."""

ALUMINIUM_HARDNESS = 1.0e9
"""Hardness H assumed for a treated (precipitation-hardened) aluminium alloy (Pa), the local
pressure cap: an assumption, not the paper's (it names neither its alloy nor a hardness).

6061-T6: Vickers hardness about 107 HV ≈ 1.05 GPa (handbook value, e.g. ASM Handbook Vol. 2,
*Properties and Selection: Nonferrous Alloys and Special-Purpose Materials*); Tabor's
H ≈ 3σ_y with σ_y = 276 MPa gives 0.83 GPa (D. Tabor, *The Hardness of Metals*, Oxford, 1951).
1.0 GPa is a round value between the two; ``reproduce`` sweeps H instead of assuming it
(``docs/guide/indentation.md``)."""


def default_material(**kw: Any) -> Material:
    """An aluminium alloy as warptrunc assumes it, against diamond punches, with a hardness.

    The paper indents aluminium-alloy discs with diamond flat punches (§ 4.1) but states none
    of E, ν, E_i, ν_i or H: these values are assumptions with the sources given in
    :class:`~warptrunc.material.Material` and :data:`ALUMINIUM_HARDNESS`.

    Parameters
    ----------
    **kw
        Fields to change (``E``, ``nu``, ``hardness``).

    Returns
    -------
    Material
        E = 70 GPa, ν = 0.33, H = :data:`ALUMINIUM_HARDNESS`; diamond E_i = 1141 GPa,
        ν_i = 0.07 (Oliver & Pharr, J. Mater. Res. 7, 1564 (1992)).
    """
    return Material.against_diamond(**{"E": 70e9, "nu": 0.33, "hardness": ALUMINIUM_HARDNESS,
                                       **kw})  # fmt: skip


MATERIAL_DEFAULTS = {"E_i": 1141e9, "nu_i": 0.07, "hardness": ALUMINIUM_HARDNESS}
"""The fields of :func:`default_material` that differ from ``Material()`` (the CLI's defaults)."""


@dataclass(frozen=True)
class IndentProtocol:
    """The experiment of § 4.1: punches, peak loads, partial unloading and punch positions.

    The ``punch_*`` face fields make the punch the experiment's: a tilt held fixed and a rough
    face, generated or read (:mod:`warptrunc.indent.face`); by default an aligned smooth flat.

    Raises
    ------
    ValueError
        A field out of its range (the message names it, its value and the range), or peak
        loads that do not increase.

    Examples
    --------
    >>> IndentProtocol().peak_loads[-1]  # the paper's last peak (N)
    0.5
    >>> IndentProtocol(punch_diameters=None, placements=None).punch_diameters is None
    True
    """

    punch_diameters: tuple[float, ...] | None = param(
        PAPER_PUNCH_DIAMETERS, "punch diameters d; none = one flat larger than the map",
        unit="m", gt=0.0, many=True, optional=True, cli="punch-diameter",
        sweep=False,
    )  # fmt: skip
    peak_loads: tuple[float, ...] = param(
        PAPER_PEAK_LOADS, "peak loads F of the cycles, increasing", unit="N", gt=0.0,
        many=True, cli="peak-loads", sweep=False,
    )  # fmt: skip
    unload_fraction: float = param(
        0.1, "partial unloading of each cycle, as a fraction of its peak load", gt=0.0, lt=1.0,
        cli="unload-fraction",
    )
    placements: int | None = param(
        3, "punch positions per diameter (random, apart); none = one at the map centre",
        kind="int", ge=1, le=10_000, optional=True, sweep=False,
    )  # fmt: skip
    placement_seed: int = param(
        0, "seed of the random punch positions", kind="int", ge=0, le=2**32 - 1,
        cli="placement-seed", sweep=False,
    )  # fmt: skip
    overlap: str = param(
        "warn", "punches of one diameter that cannot be placed apart: 'warn' (placed as far "
        "apart as found, overlap reported) or 'error'", choices=("warn", "error"), sweep=False,
    )  # fmt: skip
    truncation_increments: int = param(
        1000, "depth increments of the Eq. 2 truncation curve under each punch", kind="int",
        ge=10, le=10_000_000, cli="truncation-increments", sweep=False,
    )  # fmt: skip
    resolution_tol: float = param(
        0.02, "a cell is resolved when its unloading stiffness and contact area change by less "
        "than this (relative) when the pixel is halved", gt=0.0, lt=1.0, cli="resolution-tol",
        sweep=False,
    )  # fmt: skip
    min_contact_pixels: int = param(
        100, "fewest contact pixels of a resolved cell", kind="int", ge=1, le=10**9,
        cli="min-contact-pixels", sweep=False,
    )  # fmt: skip
    refine_max: int = param(
        8, "largest refinement of the pixel (a power of 2; 1 = none): a WM map's punch windows "
        "are generated again at pixel/2, /4, … up to pixel/refine_max", kind="int", ge=1,
        le=1024, cli="refine-max", sweep=False,
    )  # fmt: skip
    punch_tilt_deg: float = param(
        0.0, "tilt θ of the punch face against the sample's mean plane, held fixed as the "
        "indenter's shaft holds it (degrees; 0.1° rises 0.88 µm over 502.6 µm)", ge=0.0, le=5.0,
        cli="punch-tilt",
    )  # fmt: skip
    punch_tilt_azimuth_deg: float = param(
        0.0, "direction of the tilted face's edge nearest the sample, from +x toward +y, the "
        "same for every placement (degrees)", ge=0.0, lt=360.0, cli="punch-tilt-azimuth",
        sweep=False,
    )  # fmt: skip
    punch_roughness: float = param(
        0.0, "rms R_q of a generated self-affine rough punch face, over the disk after "
        "levelling; 0 = smooth", unit="m", ge=0.0, cli="punch-roughness",
    )  # fmt: skip
    punch_hurst: float = param(
        0.8, "Hurst exponent H of the rough punch face, C(q) ∝ q^(−2−2H)", gt=0.0, le=1.0,
        cli="punch-hurst", sweep=False,
    )  # fmt: skip
    punch_cutoff_short: float | None = param(
        None, "shortest wavelength λ_s of the rough punch face; none = 2 pixels of the map",
        unit="m", gt=0.0, optional=True, cli="punch-cutoff-short", sweep=False,
    )  # fmt: skip
    punch_cutoff_long: float | None = param(
        None, "longest wavelength λ_L of the rough punch face; none = the punch diameter",
        unit="m", gt=0.0, optional=True, cli="punch-cutoff-long", sweep=False,
    )  # fmt: skip
    punch_face_seed: int = param(
        0, "seed of the rough punch face (one face per punch diameter, the same at every "
        "placement)", kind="int", ge=0, le=2**32 - 1, cli="punch-face-seed", sweep=False,
    )  # fmt: skip
    punch_face_file: str | None = None
    """A height map of the punch face (:func:`warptrunc.io.read_height_map`, heights toward the
    sample, its own pixel), centred on every punch, levelled over its disk and resampled
    bilinearly; instead of ``punch_roughness`` (:mod:`warptrunc.indent.face`). None: no file."""

    def __post_init__(self) -> None:
        check_fields(self)
        path = self.punch_face_file
        if path is not None:
            if not isinstance(path, (str, os.PathLike)) or not str(path):
                raise ValueError(f"punch_face_file must be a path, got {path!r}")
            object.__setattr__(self, "punch_face_file", str(path))
            if self.punch_roughness > 0:
                raise ValueError(
                    f"punch_roughness ({self.punch_roughness!r} m) and punch_face_file "
                    f"({str(path)!r}) both give the punch face's roughness; give one"
                )
        f = self.peak_loads
        if any(not b > a for a, b in zip(f, f[1:], strict=False)):
            raise ValueError(f"peak_loads must be strictly increasing (N), got {list(f)!r}")
        r = self.refine_max
        if r & (r - 1):
            raise ValueError(f"refine_max must be a power of 2 in [1, 1024], got {r!r}")

    def to_dict(self) -> dict[str, Any]:
        """The fields (SI; tuples as lists).

        Returns
        -------
        dict
        """
        return {f.name: (list(v) if isinstance(v := getattr(self, f.name), tuple) else v)
                for f in dataclasses.fields(self)}  # fmt: skip


# --- the cycles ---------------------------------------------------------------------------------


@fill_doc(SHARED_DOCS)
def make_solver(window: PunchWindow, material: Material, *, hardness: float,
                settings: SolverSettings | None = None, device: Any = None,
                devices: Any = None) -> ContactSolver:  # fmt: skip
    """A contact solver on a punch window, with the penetration tolerance of the disk's heights.

    Parameters
    ----------
    window : PunchWindow
        The punch and the heights under it.
    material : Material
        E* (Pa) for the solver.
    hardness : float
        Pressure cap H (Pa); inf = elastic.
    settings : SolverSettings, optional
        Solver settings; a finite punch needs the free half-space.
    {warp_device_obj}
    devices : int, "auto" or list, optional
        Spread the solver over several devices (``ContactSolver(..., devices=...)``; JAX);
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
    (``warptrunc.contact.bccg.PRECONDITION_ABOVE``): under a punch on a rough surface always
    preconditioning the large windows costs more convolutions than it saves.
    """
    settings = SolverSettings() if settings is None else settings
    if window.diameter is not None and settings.substrate != "free":
        raise ValueError(
            f"settings.substrate must be 'free' under a finite punch (the body around the punch "
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
    n_dev = devices if isinstance(devices, int) else (
        len(devices) if isinstance(devices, (list, tuple)) else 1)  # fmt: skip
    if n_dev > 1 and heights.shape[0] % n_dev:  # row slabs: whole rows of the floor below
        extra = n_dev - heights.shape[0] % n_dev
        heights = np.vstack([heights, np.full((extra, heights.shape[1]), window.floor)])
    return ContactSolver(heights, window.pixel_size, material.contact_modulus,
                         settings=settings, hardness=hardness, device=device,
                         devices=devices)  # fmt: skip


COLUMNS = (
    "displacement", "n_contact", "contact_area", "n_plastic", "plastic_area", "plastic_volume",
    "max_pressure", "unloading_stiffness", "partial_unloading_stiffness",
    "unloaded_displacement", "n_iterations", "converged",
)  # fmt: skip
"""Per-peak outputs of :func:`run_cycles`."""


@fill_doc(SHARED_DOCS)
def run_cycles(
    window: PunchWindow,
    peak_loads: Any,
    unload_fraction: float,
    material: Material,
    *,
    hardness: float,
    settings: SolverSettings | None = None,
    device: Any = None,
    step: Any = None,
    elastic: dict[str, np.ndarray] | None = None,
    approach: Any = None,
    devices: Any = None,
) -> dict[str, np.ndarray]:
    """Load / partial-unload cycles under one punch, at increasing peak loads.

    Parameters
    ----------
    window : PunchWindow
        The punch and the heights under it.
    peak_loads : (m,) array_like
        Increasing peak loads F (N).
    unload_fraction : float
        Partial unloading f of each cycle (dimensionless), in (0, 1).
    material : Material
        Elastic constants (E* for the solver).
    hardness : float
        Pressure cap H (Pa); inf = elastic.
    settings : SolverSettings, optional
        Contact-solver settings.
    {warp_device_obj}
    step : callable, optional
        Called once per cycle (a progress bar's ``update``).
    elastic : dict of str to (m,) ndarray, optional
        The elastic cycles (``hardness = inf``) of the same window, loads, unloading fraction
        and settings, as this function returns them. With a finite ``hardness`` the leading
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
    devices : int, "auto" or list, optional
        Spread the solver over several devices (:func:`make_solver`); default None.

    Returns
    -------
    dict of str to (m,) ndarray
        ``warptrunc.indent.protocol.COLUMNS``: at each peak the approach δ from first touch
        (m), contact pixels and area (m²), plastic pixels, area (m²) and volume (m³), the
        largest contact pressure (Pa), Barber's unloading stiffness and the partial-unloading
        secant (N/m), the approach after the partial unloading (m), the constrained-CG
        iterations of the peak solve and whether every solve of the cycle converged.
    """
    loads = np.asarray(peak_loads, dtype=np.float64)
    out: dict[str, list] = {c: [] for c in COLUMNS}
    n_reused = 0
    if elastic is not None and math.isfinite(hardness):
        below = (np.asarray(elastic["max_pressure"], np.float64) < hardness) & np.asarray(
            elastic["converged"], bool)  # fmt: skip
        if below.shape != loads.shape:
            raise ValueError(f"elastic has {below.size} cycles, peak_loads {loads.size}")
        n_reused = int(np.argmin(below)) if not below.all() else loads.size
        unyielded = {"n_plastic": 0, "plastic_area": 0.0, "plastic_volume": 0.0,
                     "unloaded_displacement": math.nan, "n_iterations": 0}  # fmt: skip
        for c in COLUMNS:
            v = elastic.get(c)
            out[c] = (list(np.asarray(v)[:n_reused]) if v is not None
                      else [unyielded[c]] * n_reused)  # fmt: skip
        if step is not None:
            for _ in range(n_reused):
                step()
    f = float(unload_fraction)
    reach = window.top - window.floor  # an approach this deep would reach outside the disk
    solver = (make_solver(window, material, hardness=hardness, settings=settings, device=device,
                          devices=devices)
              if n_reused < loads.size else None)  # fmt: skip
    if solver is not None and approach is not None:
        first = float(np.broadcast_to(np.asarray(approach, np.float64), loads.shape)[n_reused])
        if first > 0:
            solver.hint_approach(first)
    for load in loads[n_reused:]:
        solver.freeze_plastic(False)
        peak = solver.solve(load=float(load))
        p_max = solver.max_pressure()
        solver.freeze_plastic(True)  # the unloading below is elastic from the deformed surface
        k_barber, _, ok_barber = solver.punch_stiffness()
        low = solver.solve(load=(1.0 - f) * float(load))
        if not peak.depth < reach:
            raise RuntimeError(
                f"the punch approach {peak.depth:.4g} m reached the pixels outside the disk "
                f"({reach:.4g} m below its top); give punch_window a larger drop"
            )
        # the loads the solves reached (each within thermotol of its target)
        k_secant = ((peak.load - low.load) / (peak.depth - low.depth) if peak.depth > low.depth
                    else math.nan)  # fmt: skip
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
        out["converged"].append(peak.converged and low.converged and bool(ok_barber)
                                and math.isfinite(k_secant))  # fmt: skip
        if step is not None:
            step()
    if solver is not None:
        solver.freeze_plastic(False)
    types = {"n_contact": np.int64, "n_plastic": np.int64, "n_iterations": np.int64,
             "converged": bool}  # fmt: skip
    return {c: np.asarray(v, dtype=types.get(c, np.float64)) for c, v in out.items()}
