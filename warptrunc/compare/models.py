# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Eq. 2, island-resolved truncation and elastic BEM on one map: :func:`compare_models` →
:class:`ModelComparison`, and the k–F power law of each route (:func:`warptrunc.fit_power_law`;
see :mod:`warptrunc.compare`)."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
import warp as wp

from ..contact.settings import ELASTIC_TRUNCATION, CurveSettings, SolverSettings
from ..stiffness import Material, fit_power_law, island_stiffness_curve, stiffness_curve
from ..surface import Surface
from ..truncation.settings import TruncationSettings
from .design import APPROACH_FRACTIONS, MapStudy

__all__ = [
    "APPROACH_FRACTIONS",
    "GOOD",
    "LOW_FRACTION",
    "ROUTES",
    "ModelComparison",
    "compare_models",
]

ROUTES = ("eq2", "islands", "bem")
"""The three routes (Eq. 2, island-resolved truncation, elastic BEM), in the order of the
tables."""

GOOD = 0.2
"""abs(ratio − 1) ≤ GOOD: a model "within ±20 %" of the elastic solution in the summaries."""

LOW_FRACTION = 0.1
"""Largest d/R_t of the low-approach α fit (the paper's fit range, ω ≤ 0.1·R_t, §4.4)."""


@dataclass(frozen=True, eq=False)
class ModelComparison:
    """F, k and A by Eq. 2, island-resolved truncation and elastic BEM at m approaches."""

    depth: np.ndarray
    """(m,) float64 approach d = truncation depth ω (m)."""
    depth_fraction: np.ndarray
    """(m,) float64 d/R_t (dimensionless)."""
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
    bem_mean_gap: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """(m,) float64 elastic mean gap ū between the flat and the deformed surface over the map (m)."""

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
            raise ValueError(
                f"ratio of ('eq2'|'islands', 'stiffness'|'load'), got {model!r}, {quantity!r}"
            )
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
            Use only approaches with d/R_t ≤ this (dimensionless); default all.

        Returns
        -------
        dict of str to dict
            ``{"eq2" | "islands" | "bem": fit}``, each fit a dict ``alpha`` (dimensionless),
            ``prefactor`` c of k = c·F^α (N/m per N^α), ``r2`` and ``n_points`` from
            :func:`warptrunc.fit_power_law` (NaN values below 3 usable points).
        """
        sel = np.ones(self.depth.size, bool)
        if max_fraction is not None:
            sel = self.depth_fraction <= max_fraction * (1 + 1e-9)
        return {
            m: _k_vs_F(getattr(self, f"{m}_load")[sel], getattr(self, f"{m}_stiffness")[sel])
            for m in ROUTES
        }

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
            "bem_mean_gap_m": self.bem_mean_gap,
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


def _k_vs_F(load: Any, stiffness: Any) -> dict[str, float]:
    """k = c·F^α by :func:`warptrunc.fit_power_law` of two arrays, as the dict the comparison
    files hold: ``alpha``, ``prefactor`` c (N/m per N^α), ``r2``, ``n_points``; NaN values when
    fewer than 3 pairs with F > 0 and k > 0 remain (or F does not vary).

    k ∝ F^α is the paper's E_c/E = β[F/(E·A)]^α at a fixed apparent area A, so α is the same
    exponent as in Table 3 and in Pohrt & Popov (2012)."""
    F = np.asarray(load, dtype=np.float64)
    k = np.asarray(stiffness, dtype=np.float64)
    try:
        f = fit_power_law(F, k)
    except ValueError:
        n = int(np.count_nonzero((F > 0) & (k > 0) & np.isfinite(F) & np.isfinite(k)))
        return {"alpha": math.nan, "prefactor": math.nan, "r2": math.nan, "n_points": n}
    return {"alpha": f.alpha, "prefactor": f.beta, "r2": f.r2, "n_points": f.n_points}


def compare_models(
    surface: Surface,
    fractions: Any = APPROACH_FRACTIONS,
    *,
    material: Material | None = None,
    truncation: TruncationSettings | None = None,
    settings: SolverSettings | None = None,
    progress: bool = False,
    device: wp.DeviceLike = None,
    devices: Any = None,
) -> ModelComparison:
    """F, k and A by Eq. 2, by island-resolved truncation and by the elastic solver.

    Parameters
    ----------
    surface : Surface
        The rough height map (m), pressed against a rigid flat.
    fractions : sequence of float
        Approaches d/R_t, strictly increasing, in (0, 1) (dimensionless).
    material : Material, optional
        Elastic constants; E* = ``material.contact_modulus`` is used by all three routes (the
        elastic route is elastic: the hardness is not read).
    truncation : TruncationSettings, optional
        Its ``increments`` (from 0 to the largest d, for the load integrals of the truncation
        models), ``beta_prime`` (β' of both truncation models) and ``connectivity`` (the
        islands' neighbourhood) are read; default
        :data:`~warptrunc.contact.settings.ELASTIC_TRUNCATION` (400 increments: with the
        default fractions every approach is a grid depth; elsewhere k and F are interpolated
        linearly between grid depths).
    settings : SolverSettings, optional
        The elastic solver's precision, substrate, tolerances and iteration limit
        (:class:`~warptrunc.contact.SolverSettings`; default ``SolverSettings()``, the free
        half-space). With an adhesive ``settings.adhesion`` the elastic route's load is the
        whole traction's, its area the repulsive contact and its stiffness Barber's at a fixed
        contact area; the truncation routes are not adhesive.
    progress : bool
        Report the elastic solves on stderr (a bar on a terminal, else lines).
    device : str, optional
        Warp device of all three routes.
    devices : int, "auto" or list, optional
        Spread the elastic solves over several devices (``contact_solver(..., devices=...)``;
        JAX); default None: ``device`` alone.

    Returns
    -------
    ModelComparison

    Notes
    -----
    The truncation depth ω of a row is its approach d; both truncation models come from one
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
    from ..contact.curve import solve_contact
    from ..islands.depths import island_curve
    from ..islands.settings import IslandSettings

    material = Material() if material is None else material
    truncation = ELASTIC_TRUNCATION if truncation is None else truncation
    settings = SolverSettings() if settings is None else settings
    fr = np.asarray(MapStudy(surface, fractions=fractions).fractions, dtype=np.float64)
    beta_prime, increments = truncation.beta_prime, truncation.increments
    connectivity = truncation.connectivity
    Rt = float(surface.Rt)
    d = fr * Rt
    depths = TruncationSettings(
        increments=increments, max_depth=float(d[-1]), connectivity=connectivity
    )
    ic = island_curve(
        surface, truncation=depths, settings=IslandSettings(snapshots=None), device=device
    )
    sc = stiffness_curve(_AreaCurve(ic), material, beta_prime=beta_prime)
    si = island_stiffness_curve(ic, material, beta_prime=beta_prime)

    def at(v: np.ndarray) -> np.ndarray:
        return np.interp(d, ic.depth, v)

    nearest = np.abs(ic.depth[:, None] - d[None, :]).argmin(axis=0)
    cc = solve_contact(
        surface,
        d,
        material=material.replace(hardness=math.inf),
        settings=settings,
        curve=CurveSettings(stiffness="barber"),
        progress=progress,
        device=device,
        devices=devices,
    )
    record = {
        "material": asdict(material),
        "contact_modulus_Pa": material.contact_modulus,
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
        settings=record,
        bem_mean_gap=np.asarray(cc.mean_gap, dtype=np.float64),
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
