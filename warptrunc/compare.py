# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""How good is truncation? Eq. 2, island-resolved truncation and elastic contact on one map.

Three routes to the load F, the stiffness k and the contact area A of a rough surface pressed
by a rigid flat to an approach δ (measured from first touch at the highest pixel):

``eq2``
    The paper's Eq. (2): the whole truncated set at ω = δ is one flat punch,
    k' = β'(2/√π)E*·√A', F' = ∫₀^δ k' dω (:func:`warptrunc.stiffness.stiffness_curve`).
``islands``
    Island-resolved truncation: each island of the truncated set is a punch of its own,
    k_isl = β'(2/√π)E*·Σ_i √A_i, F_isl = ∫₀^δ k_isl dω
    (:func:`warptrunc.stiffness.island_stiffness_curve`).
``bem``
    The elastic boundary-element solution of the same map on a free (zero-padded) half-space,
    :func:`warptrunc.contact.solve_contact`; k_BEM by Barber's theorem (the stiffness of a rigid
    flat punch shaped like the real contact area).

:func:`compare_models` does it for one surface (yours, or a generated one) and returns a
:class:`ModelComparison`. :func:`compare_study` runs a study over WM surfaces: the fractal
dimension D, the map size L/W_r at a fixed pixel size (size effect), the pixel size at a fixed
L (grid convergence), seeds; every case is stored as one Parquet file of one row per approach
(SI unit suffixes in the column names) under ``OUT/cases/``, written atomically, and a rerun
skips the cases already stored. :func:`load_comparison` reads the rows back into a pandas
DataFrame and :func:`summarize` turns them into the tables (ratios to BEM, mean and range over
seeds; the exponent α of k ∝ F^α by the three routes, fitted over the approaches).

Store layout::

    OUT/study.json              format tag, the study's parameters (strict JSON)
    OUT/cases/<case_id>.parquet one row per approach (columns: CASE_COLUMNS)

Scaling: in the half-space (small-slope) approximation all three routes are linear in the
height scale at a fixed δ/R_t (A unchanged, F ∝ R_t, k unchanged), so the ratios and α do not
depend on R_t; the study fixes R_t = ``Rt_over_Wr``·W_r.

References
----------
R. Pohrt, V.L. Popov, Normal contact stiffness of elastic solids with fractal rough surfaces,
Phys. Rev. Lett. 108, 104301 (2012). doi:10.1103/PhysRevLett.108.104301

L. Pastewka, N. Prodanov, B. Lorenz, M.H. Müser, M.O. Robbins, B.N.J. Persson, Finite-size
scaling in the interfacial stiffness of rough elastic contacts, Phys. Rev. E 87, 062809 (2013).
doi:10.1103/PhysRevE.87.062809

J.R. Barber, Bounds on the electrical resistance between contacting elastic rough bodies,
Proc. R. Soc. A 459, 53 (2003). doi:10.1098/rspa.2002.1038
"""

from __future__ import annotations

import io
import json
import math
import platform
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import warp as wp

from ._atomic import read_json, strict_json
from ._results import write_atomic
from ._validate import check_int, check_range
from .stiffness import Material, island_stiffness_curve, stiffness_curve
from .surface import Surface

__all__ = [
    "CASE_COLUMNS",
    "DEFAULT_FRACTIONS",
    "FORMAT",
    "GOOD",
    "MODELS",
    "ModelComparison",
    "compare_models",
    "compare_study",
    "fit_k_vs_F",
    "load_comparison",
    "study_cases",
    "summarize",
]

FORMAT = "warptrunc-compare/1"
"""Format tag of ``study.json``."""

DEFAULT_FRACTIONS = (0.02, 0.05, 0.1, 0.2, 0.3, 0.4)
"""Default approaches δ/R_t (dimensionless): from first islands to large contact."""

MODELS = ("eq2", "islands", "bem")
"""The three routes, in the order of the tables."""

GOOD = 0.2
"""|ratio − 1| ≤ GOOD: a model "within ±20 %" of the elastic solution in the summaries."""

LOW_FRACTION = 0.1
"""Largest δ/R_t of the low-approach α fit (the paper's fit range, ω ≤ 0.1·R_t, §4.4)."""

CASE_COLUMNS = (
    "case_id", "source", "D_in", "seed", "size_ratio", "Wr_m", "L_m", "n", "dx_m", "Rt_m",
    "Wc_m", "M", "gamma", "depth_fraction_of_Rt", "depth_m", "trunc_area_m2", "n_islands",
    "eq2_stiffness_N_per_m", "eq2_load_N", "islands_stiffness_N_per_m", "islands_load_N",
    "bem_stiffness_N_per_m", "bem_load_N", "bem_area_m2", "eq2_k_ratio", "eq2_F_ratio",
    "islands_k_ratio", "islands_F_ratio", "area_ratio", "converged", "n_iterations",
    "solve_time_s", "case_seconds", "device",
)  # fmt: skip
"""Columns of a case file, in order; SI units in the names. ``size_ratio`` is L/W_r; the
ratios are model/BEM (``area_ratio`` = A'/A_BEM); ``case_seconds`` is the case's wall time (s)."""


# --- one surface ----------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ModelComparison:
    """F, k and A by Eq. 2, island-resolved truncation and elastic BEM at m approaches."""

    depth: np.ndarray
    """(m,) float64 approach δ = truncation depth ω (m)."""
    depth_fraction: np.ndarray
    """(m,) float64 δ/R_t (dimensionless)."""
    trunc_area: np.ndarray
    """(m,) float64 truncated area A' (m²)."""
    n_islands: np.ndarray
    """(m,) int64 islands of the truncated set."""
    eq2_stiffness: np.ndarray
    """(m,) float64 k' = β'(2/√π)E*√A' (N/m), Eq. (2)."""
    eq2_load: np.ndarray
    """(m,) float64 F' = ∫k' dω (N)."""
    islands_stiffness: np.ndarray
    """(m,) float64 k_isl = β'(2/√π)E*·Σ√A_i (N/m)."""
    islands_load: np.ndarray
    """(m,) float64 F_isl = ∫k_isl dω (N)."""
    bem_stiffness: np.ndarray
    """(m,) float64 elastic k_BEM by Barber's punch (N/m)."""
    bem_load: np.ndarray
    """(m,) float64 elastic load F_BEM (N)."""
    bem_area: np.ndarray
    """(m,) float64 elastic contact area A_BEM (m²)."""
    converged: np.ndarray
    """(m,) bool: the elastic solve and its punch solve converged."""
    n_iterations: np.ndarray
    """(m,) int64 constrained-CG iterations of the elastic solve."""
    solve_time: np.ndarray
    """(m,) float64 wall time of the row's elastic solves (s)."""
    Rt: float
    """Peak-to-valley height R_t of the map (m)."""
    settings: dict[str, Any] = field(default_factory=dict)
    """Material, β', grid, solver settings (JSON-able)."""

    def ratio(self, model: str, quantity: str = "stiffness") -> np.ndarray:
        """Model over BEM at every approach.

        Parameters
        ----------
        model : {"eq2", "islands"}
            The truncation model.
        quantity : {"stiffness", "load"}
            k or F.

        Returns
        -------
        (m,) ndarray
            float64 ratio (dimensionless); NaN where the BEM value is 0.
        """
        if model not in ("eq2", "islands") or quantity not in ("stiffness", "load"):
            raise ValueError(f"ratio of ('eq2'|'islands', 'stiffness'|'load'), got {model!r}, "
                             f"{quantity!r}")  # fmt: skip
        return _ratio(getattr(self, f"{model}_{quantity}"), getattr(self, f"bem_{quantity}"))

    @property
    def area_ratio(self) -> np.ndarray:
        """(m,) A'/A_BEM (dimensionless)."""
        return _ratio(self.trunc_area, self.bem_area)

    def fits(self, max_fraction: float | None = None) -> dict[str, dict[str, float]]:
        """Power law k ∝ F^α of each route over the approaches.

        Parameters
        ----------
        max_fraction : float, optional
            Use only approaches with δ/R_t ≤ this (dimensionless); default all.

        Returns
        -------
        dict of str to dict
            ``{"eq2" | "islands" | "bem": fit}``, each fit as :func:`fit_k_vs_F` returns it.
        """
        sel = np.ones(self.depth.size, bool)
        if max_fraction is not None:
            sel = self.depth_fraction <= max_fraction * (1 + 1e-9)
        return {m: fit_k_vs_F(getattr(self, f"{m}_load")[sel], getattr(self, f"{m}_stiffness")[sel])
                for m in MODELS}  # fmt: skip

    def to_dict(self) -> dict[str, np.ndarray]:
        """1-D columns, SI units in the names.

        Returns
        -------
        dict of str to ndarray
            The per-approach columns of a case file (:data:`CASE_COLUMNS`), each (m,).
        """
        return {
            "depth_fraction_of_Rt": self.depth_fraction,
            "depth_m": self.depth,
            "trunc_area_m2": self.trunc_area,
            "n_islands": self.n_islands,
            "eq2_stiffness_N_per_m": self.eq2_stiffness,
            "eq2_load_N": self.eq2_load,
            "islands_stiffness_N_per_m": self.islands_stiffness,
            "islands_load_N": self.islands_load,
            "bem_stiffness_N_per_m": self.bem_stiffness,
            "bem_load_N": self.bem_load,
            "bem_area_m2": self.bem_area,
            "eq2_k_ratio": self.ratio("eq2"),
            "eq2_F_ratio": self.ratio("eq2", "load"),
            "islands_k_ratio": self.ratio("islands"),
            "islands_F_ratio": self.ratio("islands", "load"),
            "area_ratio": self.area_ratio,
            "converged": self.converged,
            "n_iterations": self.n_iterations,
            "solve_time_s": self.solve_time,
        }


def _ratio(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    out = np.full(np.shape(a), np.nan)
    np.divide(a, b, out=out, where=np.asarray(b) > 0)
    return out


def fit_k_vs_F(load: Any, stiffness: Any) -> dict[str, float]:
    """Least-squares power law k = c·F^α in log–log space.

    Parameters
    ----------
    load, stiffness : (m,) array_like
        Loads F (N) and stiffnesses k (N/m); pairs with F ≤ 0 or k ≤ 0 are left out.

    Returns
    -------
    dict
        ``alpha`` (dimensionless), ``prefactor`` c (N/m per N^α), ``r2`` and ``n_points``;
        NaN values when fewer than 3 points remain.

    Notes
    -----
    k ∝ F^α is the paper's E_c/E = β[F/(E·A)]^α at a fixed apparent area A, so α is the same
    exponent as in Table 3 and in Pohrt & Popov (2012).
    """
    F = np.asarray(load, dtype=np.float64)
    k = np.asarray(stiffness, dtype=np.float64)
    ok = (F > 0) & (k > 0) & np.isfinite(F) & np.isfinite(k)
    n = int(np.count_nonzero(ok))
    if n < 3:
        return {"alpha": math.nan, "prefactor": math.nan, "r2": math.nan, "n_points": n}
    x, y = np.log(F[ok]), np.log(k[ok])
    a, b = np.polyfit(x, y, 1)
    res = y - (a * x + b)
    ss = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - float(np.sum(res**2)) / ss if ss > 0 else 1.0
    return {"alpha": float(a), "prefactor": float(math.exp(b)), "r2": r2, "n_points": n}


def _approaches(Rt: float, fractions: Any) -> np.ndarray:
    fr = np.atleast_1d(np.asarray(fractions, dtype=np.float64))
    if fr.size == 0:
        raise ValueError("at least one approach fraction is needed, got none")
    for f in fr:
        check_range("fraction", f, 0.0, 1.0)
    if np.any(np.diff(fr) <= 0):
        raise ValueError(f"fractions must increase strictly, got {fr.tolist()!r}")
    return fr


def compare_models(
    surface: Surface,
    fractions: Any = DEFAULT_FRACTIONS,
    *,
    material: Material | None = None,
    beta_prime: float = 1.0,
    increments: int = 400,
    connectivity: int = 4,
    dtype: str = "float64",
    pressure_tol: float = 1e-5,
    pentol: float | None = None,
    maxiter: int = 10000,
    progress: bool = False,
    device: wp.DeviceLike = None,
) -> ModelComparison:
    """F, k and A by Eq. 2, by island-resolved truncation and by the elastic solver.

    Parameters
    ----------
    surface : Surface
        The rough height map (m), pressed against a rigid flat.
    fractions : sequence of float
        Approaches δ/R_t, strictly increasing, in (0, 1) (dimensionless).
    material : Material, optional
        Elastic constants; E* = ``material.reduced_modulus`` is used by all three routes.
    beta_prime : float
        Geometric factor β' of both truncation models (dimensionless).
    increments : int
        Depth increments from 0 to the largest δ for the load integrals of the truncation
        models. With the default 400 and the default fractions every approach is a grid depth;
        elsewhere k and F are interpolated linearly between grid depths.
    connectivity : {4, 8}
        Island neighbourhood of the island-resolved model.
    dtype : {"float64", "float32"}
        Precision of the elastic solver.
    pressure_tol, pentol, maxiter
        Elastic solver tolerances, see :class:`warptrunc.contact.ContactSolver`.
    progress : bool
        tqdm bar over the elastic solves.
    device : str, optional
        Warp device of all three routes.

    Returns
    -------
    ModelComparison

    Notes
    -----
    The truncation depth ω of a row is its approach δ; both truncation models come from one
    :func:`warptrunc.islands.island_curve` pass (statistics on, which carries Σ√A_i). The elastic
    contact is :func:`warptrunc.contact.solve_contact` on a free half-space (the map is an
    isolated patch), each approach warm-started from the previous one, stiffness by Barber's
    punch.

    Examples
    --------
    >>> s = warptrunc.wm_surface(2.5, 100e-6, L=1e-3, n=256, seed=0)
    >>> c = compare_models(s, (0.05, 0.1, 0.2))
    >>> c.ratio("eq2"), c.ratio("islands")  # k'/k_BEM, k_isl/k_BEM
    """
    from .contact import solve_contact
    from .islands import island_curve

    material = Material() if material is None else material
    beta_prime = check_range("beta_prime", beta_prime, 0.0)
    increments = check_int("increments", increments, 1, 10_000_000)
    Rt = float(surface.Rt)
    fr = _approaches(Rt, fractions)
    d = fr * Rt
    ic = island_curve(
        surface, increments, max_depth=float(d[-1]), connectivity=connectivity,
        statistics=True, device=device,
    )  # fmt: skip
    sc = stiffness_curve(_AreaCurve(ic), material, beta_prime=beta_prime)
    si = island_stiffness_curve(ic, material, beta_prime=beta_prime)

    def at(v: np.ndarray) -> np.ndarray:
        return np.interp(d, ic.depth, v)

    nearest = np.abs(ic.depth[:, None] - d[None, :]).argmin(axis=0)
    cc = solve_contact(
        surface, d, contact_modulus=material.reduced_modulus, substrate="free", dtype=dtype,
        stiffness="barber", pressure_tol=pressure_tol, pentol=pentol, maxiter=maxiter,
        progress=progress, device=device,
    )  # fmt: skip
    settings = {
        "material": asdict(material),
        "contact_modulus_Pa": material.reduced_modulus,
        "beta_prime": beta_prime,
        "increments": increments,
        "connectivity": connectivity,
        "grid": [surface.nx, surface.ny],
        "pixel_size_m": [surface.dx, surface.dy],
        "solver": dict(cc.settings),
    }
    return ModelComparison(
        depth=d,
        depth_fraction=fr,
        trunc_area=at(sc.contact_area),
        n_islands=ic.n_islands[nearest].astype(np.int64),
        eq2_stiffness=at(sc.stiffness),
        eq2_load=at(sc.load),
        islands_stiffness=at(si.stiffness),
        islands_load=at(si.load),
        bem_stiffness=np.asarray(cc.stiffness, dtype=np.float64),
        bem_load=np.asarray(cc.load, dtype=np.float64),
        bem_area=np.asarray(cc.area, dtype=np.float64),
        converged=np.asarray(cc.converged, dtype=bool),
        n_iterations=np.asarray(cc.n_iterations, dtype=np.int64),
        solve_time=np.asarray(cc.solve_time, dtype=np.float64),
        Rt=Rt,
        settings=settings,
    )


class _AreaCurve:
    """The fields of a TruncationCurve that ``stiffness_curve`` reads, from an IslandCurve (the
    same thresholds, hence the same pixel counts)."""

    def __init__(self, ic: Any):
        self.depth = ic.depth
        self.contact_area = ic.contact_area
        self.n_contact_pixels = ic.n_contact_pixels
        self.apparent_area = ic.apparent_area
        self.Rt = ic.Rt


# --- the study ------------------------------------------------------------------------------------


def study_cases(
    *,
    D: Any = (2.1, 2.5, 2.9),
    size_ratios: Any = (1, 3, 10, 30),
    pixels_per_Wr: int = 32,
    refine_ratio: float | None = 10,
    seeds: int = 3,
    Wr: float = 100e-6,
    Rt_over_Wr: float = 0.01,
    M: int = 10,
    gamma: float = 1.5,
) -> list[dict[str, Any]]:
    """The WM cases of a study: D × (L/W_r at a fixed pixel size, plus one halved pixel size)
    × seeds.

    Parameters
    ----------
    D : sequence of float
        Fractal dimensions, 2 < D < 3 (dimensionless).
    size_ratios : sequence of float
        Map sizes L/W_r (dimensionless); n = L/W_r × ``pixels_per_Wr`` pixels per side, so the
        pixel size dx = W_r/``pixels_per_Wr`` is the same in every size (size effect).
    pixels_per_Wr : int
        Pixels per roll-off wavelength of the base grid.
    refine_ratio : float, optional
        L/W_r at which the pixel size is halved once (grid convergence at fixed L); None for none.
        The refined map is the *same* WM surface (same phases, same cut-off W_c) sampled twice
        as finely, so the change measures each route's discretisation error, not added
        roughness.
    seeds : int
        Surfaces per (D, grid).
    Wr : float
        Roll-off wavelength W_r (m).
    Rt_over_Wr : float
        R_t/W_r, the paper's relative roughness δ (dimensionless); the ratios and α do not
        depend on it (see the module notes).
    M, gamma
        WM parameters, see :func:`warptrunc.wm_surface`. The cut-off W_c is the Nyquist
        wavelength of the base grid, 2·dx = 2·W_r/``pixels_per_Wr``, in every case.

    Returns
    -------
    list of dict
        One dict per case: ``case_id``, ``D_in``, ``seed``, ``size_ratio``, ``n``, ``L_m``,
        ``dx_m``, ``Wr_m``, ``Wc_m``, ``Rt_m``, ``M``, ``gamma``; smallest maps first.
    """
    pixels_per_Wr = check_int("pixels_per_Wr", pixels_per_Wr, 2)
    seeds = check_int("seeds", seeds, 1)
    grids = []
    for r in size_ratios:
        r = check_range("size_ratio", r, 0.0)
        grids.append((r, _pixels(r * pixels_per_Wr)))
    if refine_ratio is not None:
        grids.append((float(refine_ratio), _pixels(2 * refine_ratio * pixels_per_Wr)))
    grids = sorted(set(grids), key=lambda g: (g[1], g[0]))
    cases = []
    for r, n in grids:
        for Dv in D:
            Dv = check_range("D", Dv, 2.0, 3.0)
            for s in range(seeds):
                L = r * Wr
                cases.append({
                    "case_id": f"D{Dv:g}_L{r:g}Wr_n{n}_s{s}",
                    "source": "wm", "D_in": Dv, "seed": s, "size_ratio": r, "n": n, "L_m": L,
                    "dx_m": L / n, "Wr_m": Wr, "Wc_m": 2 * Wr / pixels_per_Wr,
                    "Rt_m": Rt_over_Wr * Wr, "M": M, "gamma": gamma,
                })  # fmt: skip
    return cases


def _pixels(v: float) -> int:
    n = round(v)
    if abs(n - v) > 1e-9 * max(1.0, v) or n < 4:
        raise ValueError(f"L/W_r × pixels per W_r must be a whole number ≥ 4 of pixels, got {v!r}")
    return int(n)


def _settings(fractions, material, beta_prime, increments, connectivity, dtype, pressure_tol,
              pentol, maxiter) -> dict[str, Any]:  # fmt: skip
    return {
        "fractions": [float(f) for f in fractions], "material": asdict(material),
        "E_star_Pa": material.reduced_modulus, "beta_prime": float(beta_prime),
        "increments": int(increments), "connectivity": int(connectivity), "dtype": dtype,
        "pressure_tol": float(pressure_tol), "pentol_m": pentol, "maxiter": int(maxiter),
        "substrate": "free", "stiffness_method": "barber",
    }  # fmt: skip


def compare_study(
    out: str | Path,
    cases: list[dict[str, Any]] | None = None,
    *,
    surface: Surface | None = None,
    fractions: Any = DEFAULT_FRACTIONS,
    material: Material | None = None,
    beta_prime: float = 1.0,
    increments: int = 400,
    connectivity: int = 4,
    dtype: str = "float64",
    pressure_tol: float = 1e-5,
    pentol: float | None = None,
    maxiter: int = 10000,
    overwrite: bool = False,
    progress: bool = True,
    device: wp.DeviceLike = None,
):
    """Run (or resume) a study of the three routes and store one Parquet file per case.

    Parameters
    ----------
    out : str or Path
        Store folder (``study.json``, ``cases/*.parquet``); created if needed.
    cases : list of dict, optional
        WM cases from :func:`study_cases`; default ``study_cases()``.
    surface : Surface, optional
        Your own map instead of WM cases: stored as the single case ``input``.
    fractions, material, beta_prime, increments, connectivity, dtype, pressure_tol, pentol, maxiter
        As in :func:`compare_models`; recorded in ``study.json``. A store made with other
        values is refused unless ``overwrite``.
    overwrite : bool
        Replace a store made with other settings (its case files are deleted).
    progress : bool
        tqdm bar over the cases.
    device : str, optional
        Warp device.

    Returns
    -------
    pandas.DataFrame
        The stored rows of ``cases`` (:func:`load_comparison`, other cases in the store left
        out).

    Raises
    ------
    ValueError
        If the store was made with other settings and ``overwrite`` is off.

    Notes
    -----
    A case counts as done once its file exists; each file is written to a temporary name and
    renamed (atomic), so an interrupted study resumes where it stopped.
    """
    from ._progress import progress_bar
    from .wm import wm_surface

    out = Path(out)
    material = Material() if material is None else material
    fractions = [float(f) for f in _approaches(1.0, fractions)]
    settings = _settings(fractions, material, beta_prime, increments, connectivity, dtype,
                         pressure_tol, pentol, maxiter)  # fmt: skip
    if surface is not None:
        if cases is not None:
            raise ValueError("give either cases (WM study) or surface (your map), not both")
        p = dict(surface.params)
        cases = [{
            "case_id": "input", "source": str(p.get("source", "input")),
            "D_in": float(p["D"]) if "D" in p else math.nan, "seed": int(p.get("seed", -1)),
            "size_ratio": (surface.lx / p["Wr"]) if "Wr" in p else math.nan,
            "n": surface.nx, "L_m": surface.lx, "dx_m": surface.dx,
            "Wr_m": float(p.get("Wr", math.nan)), "Rt_m": surface.Rt,
            "Wc_m": float(p.get("Wc") or math.nan),
            "M": int(p.get("M", -1)), "gamma": float(p.get("gamma", math.nan)),
        }]  # fmt: skip
    elif cases is None:
        cases = study_cases()
    ids = [c["case_id"] for c in cases]
    if len(set(ids)) != len(ids):
        raise ValueError("case_id values must be unique")
    _open_store(out, settings, overwrite)
    todo = [c for c in cases if not _case_path(out, c["case_id"]).exists()]
    bar = progress_bar(todo, desc="compare", unit="case", enabled=progress)
    for c in bar:
        t0 = time.perf_counter()
        if surface is not None:
            s = surface
        else:
            s = wm_surface(c["D_in"], c["Wr_m"], L=c["L_m"], n=c["n"], Rt=c["Rt_m"], M=c["M"],
                           gamma=c["gamma"], Wc=c["Wc_m"], seed=c["seed"], device=device)  # fmt: skip
        r = compare_models(
            s, fractions, material=material, beta_prime=beta_prime, increments=increments,
            connectivity=connectivity, dtype=dtype, pressure_tol=pressure_tol, pentol=pentol,
            maxiter=maxiter, device=device,
        )  # fmt: skip
        c = {**c, "Rt_m": r.Rt}
        _write_case(out, c, r, time.perf_counter() - t0)
        del s, r
    rows = load_comparison(out)
    return rows[rows["case_id"].isin(ids)].reset_index(drop=True)


def _case_path(out: Path, case_id: str) -> Path:
    return out / "cases" / f"{case_id}.parquet"


def _open_store(out: Path, settings: dict[str, Any], overwrite: bool) -> None:
    meta = out / "study.json"
    doc = {"format": FORMAT, "settings": settings}
    if meta.exists():
        old = read_json(meta)
        same = json.loads(strict_json(doc)) == json.loads(strict_json(
            {"format": old.get("format"), "settings": old.get("settings")}))  # fmt: skip
        if same:
            return
        if not overwrite:
            diff = sorted(k for k in settings if old.get("settings", {}).get(k) != settings[k])
            raise ValueError(
                f"{out} holds a comparison study made with other settings (differing: "
                f"{', '.join(diff) or 'format'}); use another folder, or overwrite"
            )
        for f in (out / "cases").glob("*.parquet"):
            f.unlink()
    import warp

    from . import __version__ as version

    doc["created"] = {"warptrunc_version": version, "warp_version": warp.config.version,
                      "host": platform.node()}  # fmt: skip
    write_atomic(meta, strict_json(doc))


def _write_case(out: Path, case: dict[str, Any], r: ModelComparison, seconds: float) -> None:
    import pandas as pd

    cols = r.to_dict()
    m = r.depth.size
    data: dict[str, Any] = {}
    for k in CASE_COLUMNS:
        if k in cols:
            data[k] = cols[k]
        elif k == "case_seconds":
            data[k] = np.full(m, seconds)
        elif k == "device":
            data[k] = [str(r.settings["solver"].get("device", ""))] * m
        else:
            data[k] = [case[k]] * m
    df = pd.DataFrame(data, columns=list(CASE_COLUMNS))
    buf = io.BytesIO()
    df.to_parquet(buf, index=False)
    write_atomic(_case_path(out, case["case_id"]), buf.getvalue())


def load_comparison(out: str | Path):
    """Every stored row of a comparison study.

    Parameters
    ----------
    out : str or Path
        The study's store folder.

    Returns
    -------
    pandas.DataFrame
        One row per (case, approach), columns :data:`CASE_COLUMNS`, sorted by case and δ/R_t.

    Raises
    ------
    FileNotFoundError
        If ``out`` holds no ``study.json``.
    """
    import pandas as pd

    out = Path(out)
    if not (out / "study.json").exists():
        raise FileNotFoundError(f"no comparison study in {out} (study.json missing)")
    files = sorted((out / "cases").glob("*.parquet"))
    if not files:
        return pd.DataFrame(columns=list(CASE_COLUMNS))
    df = pd.concat([pd.read_parquet(f) for f in files], ignore_index=True)
    return df.sort_values(["n", "size_ratio", "D_in", "seed", "depth_fraction_of_Rt"],
                          kind="stable").reset_index(drop=True)  # fmt: skip


def _stats(v) -> dict[str, float]:
    x = np.asarray(v, dtype=np.float64)
    x = x[np.isfinite(x)]
    if x.size == 0:
        return {"mean": math.nan, "min": math.nan, "max": math.nan, "n": 0}
    return {"mean": float(x.mean()), "min": float(x.min()), "max": float(x.max()), "n": int(x.size)}


def summarize(rows) -> dict[str, Any]:
    """The study's tables, recomputed from its rows.

    Parameters
    ----------
    rows : pandas.DataFrame
        Rows of :func:`load_comparison`.

    Returns
    -------
    dict
        ``ratios``: DataFrame, one row per (D_in, size_ratio, n, δ/R_t) with mean, min and max
        over seeds of k/k_BEM and F/F_BEM for ``eq2`` and ``islands`` and of A'/A_BEM, and the
        number of converged seeds. ``alpha``: DataFrame, one row per (D_in, size_ratio, n, range)
        with mean, min and max over seeds of α by the three routes; range ``all`` fits every
        approach, ``low`` those with δ/R_t ≤ :data:`LOW_FRACTION`.
    """
    import pandas as pd

    keys = ["D_in", "size_ratio", "n"]
    out_r = []
    for (Dv, r, n, f), g in rows.groupby([*keys, "depth_fraction_of_Rt"], sort=True, dropna=False):
        rec: dict[str, Any] = {"D_in": Dv, "size_ratio": r, "n": n, "depth_fraction_of_Rt": f,
                               "seeds": int(g["seed"].nunique()),
                               "converged": int(g["converged"].sum())}  # fmt: skip
        for col in ("eq2_k_ratio", "islands_k_ratio", "eq2_F_ratio", "islands_F_ratio",
                    "area_ratio"):  # fmt: skip
            s = _stats(g[col])
            for k in ("mean", "min", "max"):
                rec[f"{col}_{k}"] = s[k]
        out_r.append(rec)
    out_a = []
    for (Dv, r, n), g in rows.groupby(keys, sort=True, dropna=False):
        for rng, lim in (("all", None), ("low", LOW_FRACTION)):
            fits: dict[str, list[float]] = {m: [] for m in MODELS}
            for _, c in g.groupby("case_id", sort=True):
                c = c[c["depth_fraction_of_Rt"] <= lim * (1 + 1e-9)] if lim else c
                for m in MODELS:
                    fits[m].append(fit_k_vs_F(c[f"{m}_load_N"], c[f"{m}_stiffness_N_per_m"])["alpha"])
            rec = {"D_in": Dv, "size_ratio": r, "n": n, "range": rng,
                   "seeds": int(g["seed"].nunique())}  # fmt: skip
            for m in MODELS:
                s = _stats(fits[m])
                for k in ("mean", "min", "max"):
                    rec[f"alpha_{m}_{k}"] = s[k]
            out_a.append(rec)
    return {"ratios": pd.DataFrame(out_r), "alpha": pd.DataFrame(out_a)}
