# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic boundary-element cross-check of truncation analysis on the same height map.

The elastic contact of the rough surface against a rigid flat is solved at given approaches δ
with a boundary-element (FFT) half-space and the constrained conjugate-gradient (Polonsky–Keer)
method [2]_: by default warptrunc's own solver on the surface's Warp device
(:mod:`warptrunc.contact.solver`), or ContactMechanics' [1]_ on the CPU (``solver=
"contactmechanics"``, the same discretisation and stopping criterion, as a reference). The same
approaches are fed to the truncation formulas of :mod:`warptrunc.stiffness` and the two are
compared.

ContactMechanics and SurfaceTopography are an optional extra (``pip install "warptrunc[bem]"``),
imported only when that solver is chosen.

References
----------
.. [1] L. Pastewka, M.O. Robbins, Contact area of rough spheres: Large scale simulations and
   simple scaling laws, Appl. Phys. Lett. 108, 221601 (2016). doi:10.1063/1.4950802
.. [2] I.A. Polonsky, L.M. Keer, A numerical method for solving rough contact problems based on
   the multi-level multi-summation and conjugate gradient techniques, Wear 231, 206 (1999).
   doi:10.1016/S0043-1648(99)00113-1
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import warp as wp

from .._support.outputs import write_columns_csv
from .._support.results import all_converged_property
from ..slope import slope_record
from ..stiffness import Material, flat_punch_stiffness, stiffness_curve
from ..surface import Surface
from ..truncation.api import truncate
from ..truncation.settings import TruncationSettings
from .runs import contactmechanics_versions, require_bem, run_contactmechanics, run_warptrunc
from .settings import ELASTIC_TRUNCATION, BemCheckSettings, SolverSettings

__all__ = ["BemCheck", "bem_check", "require_bem"]

_PADDING = {
    "free": "zero-padded to 2nx × 2ny by FreeFFTElasticHalfSpace (Hockney): the map is an "
    "isolated patch, no force outside it",
    "periodic": "none: the map repeats periodically; q = 0 mode given the stiffness of the "
    "lowest non-zero wavevector (library default), so F(δ) depends on that convention",
}


@dataclass(frozen=True, eq=False)
class BemCheck:
    """Truncation against an elastic boundary-element solution, one row per approach δ."""

    depth: np.ndarray
    """(m,) approach δ of the rigid flat, measured from the first touch at the highest point (m);
    the truncation depth ω of the same row is δ."""
    depth_fraction: np.ndarray
    """(m,) δ/R_t (dimensionless)."""
    bem_load: np.ndarray
    """(m,) BEM normal load F_BEM (N)."""
    bem_area: np.ndarray
    """(m,) BEM real contact area A_BEM = pixels with compressive force × pixel area (m²)."""
    bem_stiffness: np.ndarray
    """(m,) BEM stiffness k_BEM = dF/dδ, by central differences or Barber's punch (N/m)."""
    trunc_area: np.ndarray
    """(m,) truncated area A' (pixels with z ≥ z_top − δ, m²)."""
    trunc_load: np.ndarray
    """(m,) truncation load F' = ∫₀^δ k' dω (trapezoidal rule on the truncation grid, N)."""
    trunc_stiffness: np.ndarray
    """(m,) truncation stiffness k' = β'·(2/√π)·E*·√A' (N/m), Eq. (2)."""
    converged: np.ndarray
    """(m,) bool: the solve at δ and those of its stiffness (finite differences or Barber's
    punch) converged."""
    n_iterations: np.ndarray
    """(m,) int64 CG iterations of the solve at δ."""
    solve_time: np.ndarray
    """(m,) wall time of the row's solves (s)."""
    edge_contact: np.ndarray
    """(m,) bool: BEM contact reaches the border of the map (free boundary: the map ends there)."""
    settings: dict[str, Any] = field(default_factory=dict)
    """Solver settings, elastic constants, versions and the surface description (JSON-able);
    ``theory``: the spectrum the theory columns read and the small-load κ
    (:func:`warptrunc.theory.columns.kappa_record`)."""
    theory: dict[str, np.ndarray] = field(default_factory=dict)
    """(m,) columns of Persson's and GW's predictions at the nominal pressure F_BEM/A₀ of each
    row (:data:`warptrunc.theory.columns.THEORY_COLUMNS`: areas m², mean gap m, stiffness N/m,
    κ); empty when the map's spectrum could not be had."""

    @property
    def load_ratio(self) -> np.ndarray:
        """(m,) F'/F_BEM (dimensionless)."""
        return _ratio(self.trunc_load, self.bem_load)

    @property
    def stiffness_ratio(self) -> np.ndarray:
        """(m,) k'/k_BEM (dimensionless)."""
        return _ratio(self.trunc_stiffness, self.bem_stiffness)

    @property
    def area_ratio(self) -> np.ndarray:
        """(m,) A'/A_BEM (dimensionless)."""
        return _ratio(self.trunc_area, self.bem_area)

    all_converged = all_converged_property()

    def to_dict(self) -> dict[str, np.ndarray]:
        """Columns (SI units in the names) in the order of ``bem.csv``.

        Returns
        -------
        dict of str to ndarray
            One ``(m,)`` column per field and ratio, m the number of depths: ``depth_m`` (m),
            ``depth_fraction_of_Rt`` (dimensionless), ``bem_load_N`` and ``trunc_load_N``
            (N), ``bem_area_m2`` and ``trunc_area_m2`` (m²), ``bem_stiffness_N_per_m`` and
            ``trunc_stiffness_N_per_m`` (N/m), ``load_ratio``, ``stiffness_ratio``,
            ``area_ratio`` (truncation over BEM, dimensionless), ``converged``,
            ``n_iterations``, ``solve_time_s`` (s) and ``edge_contact``, then the theory
            columns (:attr:`theory`).
        """
        return {
            "depth_m": self.depth,
            "depth_fraction_of_Rt": self.depth_fraction,
            "bem_load_N": self.bem_load,
            "bem_area_m2": self.bem_area,
            "bem_stiffness_N_per_m": self.bem_stiffness,
            "trunc_area_m2": self.trunc_area,
            "trunc_load_N": self.trunc_load,
            "trunc_stiffness_N_per_m": self.trunc_stiffness,
            "load_ratio": self.load_ratio,
            "stiffness_ratio": self.stiffness_ratio,
            "area_ratio": self.area_ratio,
            "converged": self.converged,
            "n_iterations": self.n_iterations,
            "solve_time_s": self.solve_time,
            "edge_contact": self.edge_contact,
            **self.theory,
        }

    def summary(self) -> dict[str, Any]:
        """Ranges of the ratios and the solve times (the numbers of the README table).

        Returns
        -------
        dict
            ``load_ratio``, ``stiffness_ratio``, ``area_ratio``: ``[min, max]`` over the
            finite values (dimensionless), or None when none is finite; ``all_converged``,
            ``n_not_converged``, ``any_edge_contact``; ``time_per_solve_s`` (total solve time
            over the number of solves in ``settings["solves"]``, else over 3 solves per depth)
            and ``total_solve_time_s`` (s); ``kappa``: the small-load κ of the BEM beside
            Persson's and BGT's (:func:`warptrunc.theory.columns.kappa_record`), or None.
        """
        out: dict[str, Any] = {}
        for name, r in (
            ("load_ratio", self.load_ratio),
            ("stiffness_ratio", self.stiffness_ratio),
            ("area_ratio", self.area_ratio),
        ):
            ok = np.isfinite(r)
            out[name] = [float(r[ok].min()), float(r[ok].max())] if ok.any() else None
        out["all_converged"] = self.all_converged
        out["n_not_converged"] = int(np.count_nonzero(~self.converged))
        out["any_edge_contact"] = bool(np.any(self.edge_contact))
        n_solves = len(self.settings.get("solves", [])) or 3 * self.depth.size
        out["time_per_solve_s"] = float(self.solve_time.sum() / n_solves)
        out["total_solve_time_s"] = float(self.solve_time.sum())
        out["kappa"] = self.settings.get("theory", {}).get("kappa")
        return out

    def to_csv(self, path: str | Path) -> Path:
        """Write :meth:`to_dict` as CSV (full float64 precision).

        Parameters
        ----------
        path : str or Path
            The CSV file to write (overwritten if it exists).

        Returns
        -------
        Path
            ``path``.
        """
        return write_columns_csv(path, self.to_dict())

    def to_json(self, path: str | Path, *, warnings: list | None = None) -> Path:
        """Write the columns, :meth:`summary` and the settings as JSON.

        Parameters
        ----------
        path : str or Path
            The JSON file to write (overwritten if it exists).
        warnings : list of dict, optional
            Plausibility warnings of the map (:mod:`warptrunc.plausibility`), written under
            ``warnings`` (an empty list when None).

        Returns
        -------
        Path
            ``path``. The file has keys ``summary``, ``settings``, ``columns`` (lists) and
            ``provenance`` (version, commit, command, device, time); non-finite floats are
            written as null or ``"inf"`` (strict JSON).
        """
        from .._support.provenance import provenance

        path = Path(path)
        d: dict[str, Any] = {"summary": self.summary(), "settings": self.settings}
        d["provenance"] = provenance(self.settings.get("device"))
        d["columns"] = {k: v.tolist() for k, v in self.to_dict().items()}
        d["warnings"] = list(warnings or [])
        path.write_text(json.dumps(_strict(d), indent=1, default=str, allow_nan=False) + "\n")
        return path


def _strict(v: Any) -> Any:
    """Strict JSON: non-finite floats become None (NaN ratio: no BEM contact) or "inf"."""
    if isinstance(v, dict):
        return {k: _strict(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_strict(x) for x in v]
    if isinstance(v, float) and not math.isfinite(v):
        return None if math.isnan(v) else str(v)
    return v


def _ratio(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    out = np.full(a.shape, np.nan)
    np.divide(a, b, out=out, where=b > 0)
    return out


def bem_check(
    surface: Surface,
    *,
    check: BemCheckSettings | None = None,
    truncation: TruncationSettings | None = None,
    material: Material | None = None,
    settings: SolverSettings | None = None,
    progress: bool = True,
    device: wp.DeviceLike = None,
    devices: Any = None,
) -> BemCheck:
    """Compare truncation with an elastic boundary-element contact solution at approaches δ.

    Parameters
    ----------
    surface : Surface
        The rough height map (m). It is pressed against a rigid flat.
    check : BemCheckSettings, optional
        The approaches δ (fractions of R_t, or depths in m below R_t), the elastic solver
        (warptrunc's CCG on ``device``, or ContactMechanics' on the CPU, the ``bem`` extra, the
        reference it is tested against) and the stiffness method (the central difference
        k_BEM = [F(δ(1+h)) − F(δ(1−h))]/(2hδ) with both solvers, or Barber's flat punch of the
        contact set, warptrunc only: one linear solve instead of two contact solves)
        (:class:`~warptrunc.contact.BemCheckSettings`; default ``BemCheckSettings()``).
    truncation : TruncationSettings, optional
        Its ``increments`` (the truncation grid from 0 to the largest δ, for the load integral)
        and ``beta_prime`` (β' of Eq. 2, as in ``analyze``) are read; default
        :data:`~warptrunc.contact.settings.ELASTIC_TRUNCATION` (400 increments).
    material : Material, optional
        Elastic constants; E* = ``material.contact_modulus`` is used by both methods.
    settings : SolverSettings, optional
        The elastic solver's substrate, tolerances and iteration limit (both solvers) and
        precision (warptrunc's; ContactMechanics is float64). ``"free"``: non-periodic
        half-space (``FreeFFTElasticHalfSpace``, zero-padded to 2nx × 2ny, so the map is an
        isolated patch with no contact outside it). ``"periodic"``:
        ``PeriodicFFTElasticHalfSpace``, for maps that are periodic; the mean (q = 0)
        displacement of a periodic half-space is undefined and ContactMechanics gives that mode
        the stiffness of the lowest non-zero wavevector, so there F(δ) and k depend on that
        convention while F against A_BEM does not. The absolute force tolerance is
        ``pressure_tol·E*·dx·dy`` (N); ``pentol`` None: rms height/(10·mean n). An adhesive
        ``settings.adhesion`` (:class:`~warptrunc.contact.adhesion.Adhesion`) is solved by
        warptrunc's solver only: the BEM load is then the whole
        traction's (the law's pull included), the BEM area the repulsive contact, and Barber's
        stiffness that of the repulsive contact at a fixed area; the solves must approach
        monotonically (with the central difference, δ_i(1 + h) < δ_(i+1)(1 − h)), as the
        adhesive contact is a loading history. Truncation is not adhesive.
    progress : bool
        Report the solves on stderr (a bar on a terminal, else lines).
    device : str, optional
        Warp device for the truncation part and warptrunc's solver.
    devices : int, "auto" or list, optional
        Spread warptrunc's solver over several devices (``contact_solver(..., devices=...)``;
        JAX); default None: ``device`` alone. When spread, the surface's device copies are
        released after the truncation part (:meth:`~warptrunc.Surface.release_device_copies`;
        its heights stay on the host), so that the solve has the GPUs' memory.

    Returns
    -------
    BemCheck

    Raises
    ------
    ValueError
        A depth not below R_t of the map; an adhesion law with ContactMechanics, or with
        approaches that go back.
    ImportError
        ``solver="contactmechanics"`` without the ``bem`` extra.
    MemoryError
        warptrunc's solver would not fit the device (checked before allocating).

    Notes
    -----
    ContactMechanics solves a rigid rough indenter on an elastic flat with the contact modulus;
    within the half-space (small-slope) approximation this is the same problem as an elastic
    rough body of reduced modulus E* on a rigid flat. The heights ``z[iy, ix]`` are passed
    transposed (ContactMechanics puts x first). The flat's rigid-body offset is
    δ − max z, so δ = 0 is first touch, the truncation depth's reference. Truncation uses the
    formulas of :func:`warptrunc.stiffness.stiffness_curve`: k' at δ from the exact pixel count
    A'(δ); F'(δ) by linear interpolation of its trapezoidal load on ``increments`` steps.
    Every solve is warm-started from the displacement of the previous one.
    """
    check = BemCheckSettings() if check is None else check
    truncation = ELASTIC_TRUNCATION if truncation is None else truncation
    material = Material() if material is None else material
    settings = SolverSettings() if settings is None else settings
    adhesion = settings.adhesion
    if adhesion.active and check.solver != "warptrunc":
        raise ValueError(
            f"adhesion ({adhesion.law}) is solved by warptrunc's solver only, got solver "
            f"{check.solver!r}"
        )
    if check.solver == "contactmechanics":
        require_bem()  # fail early, before the truncation part
    increments, beta_prime = truncation.increments, truncation.beta_prime
    substrate, fd_step, pressure_tol = settings.substrate, check.fd_step, settings.pressure_tol

    Rt = float(surface.Rt)
    d = check.approaches(Rt)
    if adhesion.active and check.stiffness == "central":
        order = np.stack([d * (1 - check.fd_step), d, d * (1 + check.fd_step)], axis=1).ravel()
        if np.any(np.diff(order) <= 0):
            raise ValueError(
                "with adhesion the solves must approach monotonically (a loading history): "
                f"the central difference's δ(1 ± {check.fd_step:g}) of successive approaches "
                "overlap; space the approaches wider, lower fd_step, or take stiffness barber"
            )
    contact_modulus = material.contact_modulus
    slope = slope_record(surface, limit=settings.slope_limit)  # the half-space's small-slope regime

    # truncation, the same formulas as `analyze`
    curve = truncate(surface, increments, max_depth=float(d[-1]), device=device)
    sc = stiffness_curve(curve, material, beta_prime=beta_prime)
    z = surface.heights
    z_top = np.float32(z.max())
    n_trunc = np.array([np.count_nonzero(z >= np.float32(z_top - v)) for v in d], dtype=np.int64)
    trunc_area = n_trunc * surface.pixel_area
    trunc_stiffness = flat_punch_stiffness(
        np.sqrt(trunc_area), contact_modulus, beta_prime=beta_prime
    )
    trunc_load = np.interp(d, sc.depth, sc.load)

    if devices not in (None, 1) and check.solver != "contactmechanics":
        surface.release_device_copies()  # the GPUs' memory to JAX: the heights on the host
    kw = {"material": material, "settings": settings, "check": check, "progress": progress}
    if check.solver == "contactmechanics":
        out, conv, nit, edge, solves, extra = run_contactmechanics(surface, d, **kw)
    else:
        out, conv, nit, edge, solves, extra = run_warptrunc(
            surface, d, **kw, device=device, devices=devices
        )
    theory, theory_record = _theory(surface, out["F"], out["A"], material, substrate)
    settings = {
        **extra,
        "substrate": substrate,
        "adhesion": adhesion.to_dict() if adhesion.active else None,
        "padding": _PADDING[substrate],
        "contact_modulus_Pa": contact_modulus,
        "material": asdict(material),
        "beta_prime": beta_prime,
        "fd_step": fd_step,
        "pressure_tol": pressure_tol,
        "forcetol_N": pressure_tol * contact_modulus * surface.pixel_area,
        "maxiter": settings.maxiter,
        "increments": increments,
        "Rt_m": Rt,
        "grid": [surface.nx, surface.ny],
        "pixel_size_m": [surface.dx, surface.dy],
        "versions": contactmechanics_versions(),
        "surface": {**surface.to_dict(), "slope": slope},
        "solves": solves,
        "theory": theory_record,
    }
    return BemCheck(
        depth=d,
        depth_fraction=d / Rt,
        bem_load=out["F"],
        bem_area=out["A"],
        bem_stiffness=out["k"],
        trunc_area=trunc_area,
        trunc_load=trunc_load,
        trunc_stiffness=trunc_stiffness,
        converged=conv,
        n_iterations=nit,
        solve_time=out["t"],
        edge_contact=edge,
        settings=settings,
        theory=theory,
    )


def _theory(
    surface: Surface, load: np.ndarray, area: np.ndarray, material: Material, substrate: str
) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    """The theory columns of the rows and their record: the spectrum read (its source, its
    wavevector range, a map's noise floor) and the small-load κ."""
    from ..theory.columns import kappa_record, surface_spectrum, theory_columns

    a0 = surface.lx * surface.ly
    try:
        psd = surface_spectrum(surface)
    except ValueError as exc:  # a map without a spectrum to read (e.g. constant)
        return {}, {"error": str(exc)}
    cols = theory_columns(psd, load, a0, material=material, area=area)
    q = psd.wavevector
    record = {
        "spectrum": {
            "source": psd.source,
            "q_min_per_m": float(q[0]),
            "q_max_per_m": float(q[-1]),
            "noise_wavevector_per_m": psd.noise_wavevector,
            "noise_wavelength_m": 2 * math.pi / psd.noise_wavevector
            if math.isfinite(psd.noise_wavevector)
            else None,
            "h_rms_m": psd.h_rms,
            "slope_rms": psd.slope_rms,
        },
        "nominal_pressure": "F_BEM/A₀, A₀ the map's area",
        "stiffness": "Persson's and GW's K·A₀ = −dF/dū"
        + (
            ""
            if substrate == "periodic"
            else "; on the free half-space k_BEM = dF/dδ is not −dF/dū (δ holds the bulk "
            "displacement under the patch)"
        ),
        "kappa": kappa_record(cols, area, a0, pixel_area=surface.pixel_area),
    }
    return cols, record
