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
  K = ΔF/Δδ = f·F / (δ(F) − δ((1 − f)·F)) from an elastic solve of the deformed surface.

Then it reloads to the next peak. In an elastic–perfectly-plastic model, unloading and
reloading up to the previous peak are elastic (no pixel reaches H again below the peak load),
so the state at each peak is that of monotonic loading to it: a run need not replay the partial
unloads (``tests/test_indent.py`` checks this on the results of :func:`warptrunc.indent`).

E_c = √π·K/(2√A), with A the punch area πd²/4 (§ 4.1), and Fig. 6's normalisations E_c/E and
F/(E·A) with E the Young's modulus of the rough body.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..contact.solver import ContactSolver, default_pentol
from ..material import Material
from ..params import check_fields, param
from .punch import PunchWindow

__all__ = [
    "ALUMINIUM_HARDNESS",
    "PAPER_PEAK_LOADS",
    "PAPER_PUNCH_DIAMETERS",
    "IndentProtocol",
    "default_material",
    "elastic_plastic_available",
    "run_cycles",
]

PAPER_PUNCH_DIAMETERS = (54.1e-6, 108.7e-6, 502.6e-6)
"""Diameters of the paper's flat diamond punches (m): FLT-D050, FLT-D100, FLT-D500 (§ 4.1)."""

PAPER_PEAK_LOADS = tuple(0.5 / 2**k for k in range(9, -1, -1))
"""The paper's ten peak loads (N): each twice the previous, the last 500 mN (§ 4.1)."""

ALUMINIUM_HARDNESS = 1.0e9
"""Hardness H of a treated (precipitation-hardened) aluminium alloy (Pa), the local pressure cap.

6061-T6: Vickers hardness 107 HV = 1.05 GPa (ASM Handbook Vol. 2, *Properties and Selection:
Nonferrous Alloys and Special-Purpose Materials*, ASM International, 1990,
doi:10.31399/asm.hb.v02.9781627081627); Tabor's H ≈ 3σ_y with σ_y = 276 MPa gives 0.83 GPa
(D. Tabor, *The Hardness of Metals*, Oxford, 1951). The paper does not name its alloy; 1.0 GPa is
a round value between the two."""


def default_material(**kw: Any) -> Material:
    """The paper's aluminium alloy against its diamond punches, with a hardness.

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
        aliases=("punch-diameters",), sweep=False,
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

    def __post_init__(self) -> None:
        check_fields(self)
        f = self.peak_loads
        if any(not b > a for a, b in zip(f, f[1:], strict=False)):
            raise ValueError(f"peak_loads must be strictly increasing (N), got {list(f)!r}")

    def to_dict(self) -> dict[str, Any]:
        """The fields (SI; tuples as lists).

        Returns
        -------
        dict
        """
        return {f.name: (list(v) if isinstance(v := getattr(self, f.name), tuple) else v)
                for f in dataclasses.fields(self)}  # fmt: skip


# --- the contact solver, through its present and its coming interface --------------------------


def _init_params() -> set[str]:
    return set(inspect.signature(ContactSolver.__init__).parameters)


def elastic_plastic_available() -> bool:
    """Whether :class:`~warptrunc.contact.ContactSolver` takes a ``hardness`` (elastic–plastic).

    Returns
    -------
    bool
    """
    return "hardness" in _init_params()


def get(state: Any, name: str, default: Any = None) -> Any:
    """A field of a solve's result: a ``ContactState`` attribute or a key of the older dict."""
    if isinstance(state, dict):
        return state.get(name, default)
    return getattr(state, name, default)


def make_solver(window: PunchWindow, material: Material, *, hardness: float,
                settings: Any = None, device: Any = None) -> ContactSolver:  # fmt: skip
    """A contact solver on a punch window, with the penetration tolerance of the disk's heights.

    The default tolerance (rms height/(10·mean n)) is taken over the disk only: the pixels
    outside it, far below, would inflate it.
    """
    pentol = default_pentol(window.disk_heights)
    if pentol == 0.0:  # a flat punch face: a small fraction of a pixel
        pentol = 1e-6 * min(window.pixel_size)
    accepted = _init_params()
    kw: dict[str, Any] = {"device": device}
    if math.isfinite(hardness):
        if "hardness" not in accepted:
            raise ValueError(
                f"hardness = {hardness!r} Pa needs the elastic–perfectly-plastic contact solver, "
                "which this version does not have; use hardness = inf (elastic)"
            )
        kw["hardness"] = hardness
    elif "hardness" in accepted:
        kw["hardness"] = math.inf
    if settings is not None and "settings" in accepted:
        if getattr(settings, "pentol", None) is None:
            settings = dataclasses.replace(settings, pentol=pentol)
        kw["settings"] = settings
    elif settings is not None:  # the older keywords, one per field of the settings
        fields = (f.name for f in dataclasses.fields(settings))
        kw.update({f: getattr(settings, f) for f in fields if f in accepted})
        if kw.get("pentol") is None:
            kw["pentol"] = pentol
    else:
        kw["pentol"] = pentol
    return ContactSolver(window.heights, window.pixel_size, material.contact_modulus, **kw)


def _solve_load(solver: ContactSolver, load: float, *, plastic: bool) -> Any:
    """Load-controlled solve; ``plastic=False`` freezes the plastic state (elastic unloading)."""
    if "plastic" in inspect.signature(solver.solve).parameters:
        return solver.solve(load=load, plastic=plastic)
    freeze = getattr(solver, "freeze_plastic", None)
    if freeze is not None:
        freeze(not plastic)
    return solver.solve(load=load)


def _freeze(solver: ContactSolver, frozen: bool) -> None:
    freeze = getattr(solver, "freeze_plastic", None)
    if freeze is not None:
        freeze(frozen)


COLUMNS = (
    "displacement", "n_contact", "contact_area", "n_plastic", "plastic_area", "plastic_volume",
    "unloading_stiffness", "partial_unloading_stiffness", "unloaded_displacement",
    "n_iterations", "converged",
)  # fmt: skip
"""Per-peak outputs of :func:`run_cycles`."""


def run_cycles(
    window: PunchWindow,
    peak_loads: Any,
    unload_fraction: float,
    material: Material,
    *,
    hardness: float,
    settings: Any = None,
    device: Any = None,
    step: Any = None,
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
    device : str or warp Device, optional
        Warp device.
    step : callable, optional
        Called once per cycle (a progress bar's ``update``).

    Returns
    -------
    dict of str to (m,) ndarray
        :data:`COLUMNS`: at each peak the approach δ from first touch (m), contact pixels and
        area (m²), plastic pixels, area (m²) and volume (m³), Barber's unloading stiffness and
        the partial-unloading secant (N/m), the approach after the partial unloading (m), the
        constrained-CG iterations of the peak solve and whether every solve of the cycle
        converged.
    """
    solver = make_solver(window, material, hardness=hardness, settings=settings, device=device)
    dx, dy = window.pixel_size
    out: dict[str, list] = {c: [] for c in COLUMNS}
    f = float(unload_fraction)
    for load in np.asarray(peak_loads, dtype=np.float64):
        peak = _solve_load(solver, float(load), plastic=True)
        _freeze(solver, True)
        k_barber, _, ok_barber = solver.punch_stiffness()
        n_c = int(get(peak, "n_contact"))
        n_p = int(get(peak, "n_plastic", 0))
        out["displacement"].append(float(get(peak, "depth")))
        out["n_contact"].append(n_c)
        out["contact_area"].append(float(get(peak, "contact_area", n_c * dx * dy)))
        out["n_plastic"].append(n_p)
        out["plastic_area"].append(float(get(peak, "plastic_area", n_p * dx * dy)))
        out["plastic_volume"].append(float(get(peak, "plastic_volume", 0.0)))
        out["n_iterations"].append(int(get(peak, "n_iterations")))
        low = _solve_load(solver, (1.0 - f) * float(load), plastic=False)
        d_peak, d_low = float(get(peak, "depth")), float(get(low, "depth"))
        k_secant = f * float(load) / (d_peak - d_low) if d_peak > d_low else math.nan
        _freeze(solver, False)
        out["unloading_stiffness"].append(float(k_barber))
        out["partial_unloading_stiffness"].append(k_secant)
        out["unloaded_displacement"].append(d_low)
        out["converged"].append(bool(get(peak, "converged")) and bool(get(low, "converged"))
                                and bool(ok_barber) and math.isfinite(k_secant))  # fmt: skip
        if step is not None:
            step()
    types = {"n_contact": np.int64, "n_plastic": np.int64, "n_iterations": np.int64,
             "converged": bool}  # fmt: skip
    return {c: np.asarray(v, dtype=types.get(c, np.float64)) for c, v in out.items()}
