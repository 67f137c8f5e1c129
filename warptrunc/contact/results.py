# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Result objects of the contact solver: one solve (:class:`ContactState`) and one row per
approach δ (:class:`ContactCurve`, host NumPy arrays)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._support.results import all_converged_property

__all__ = ["ContactCurve", "ContactState"]


@dataclass(frozen=True)
class ContactState:
    """The state after one solve of :meth:`warptrunc.contact.ContactSolver.solve`."""

    depth: float
    """Approach δ of the flat from first touch at the highest pixel of the original
    (undeformed) map (m)."""
    load: float
    """Normal load F = Σ pixel forces (N)."""
    n_contact: int
    """Pixels in contact (pressure p > 0), those at the hardness included; with adhesion the
    repulsive contact: the pixels where the gap is closed and the wall's reaction is positive."""
    contact_area: float
    """Real contact area A_c = n_contact·dx·dy (m²); with adhesion the repulsive area."""
    n_plastic: int
    """Pixels at the pressure cap (p = H); 0 for an elastic solve (H = inf). For a solve with
    the plastic state frozen, the pixels where p ≥ H."""
    plastic_area: float
    """Plastic area n_plastic·dx·dy (m²)."""
    plastic_volume: float
    """Volume removed by plastic flow so far, Σ plastic displacement·dx·dy (m³)."""
    mean_gap: float
    """Mean gap between the flat and the deformed surface over the map (m)."""
    n_iterations: int
    """Constrained-CG iterations of the solve (all trial solves in load control with H < inf)."""
    n_convolutions: float
    """FFT convolutions of the solve, (forward + inverse transforms)/2."""
    residual: float
    """Final max(rms penetration, max penetration or open gap at the cap, max abs(Δu)) (m),
    against ``pentol``."""
    max_tensile_force: float
    """Final largest tensile (or above-hardness) pixel force before projection (N), against
    ``forcetol``."""
    converged: bool
    """The solve met every stopping criterion before ``maxiter``."""
    adhesive_force: float = 0.0
    """Sum of the adhesion law's pixel forces (N, ≤ 0: tensile; included in ``load``); 0
    without adhesion."""
    n_attractive: int = 0
    """Pixels out of contact within the law's range and pulled by it (gap below h₀ or ρ); 0
    without adhesion."""
    attractive_area: float = 0.0
    """Attractive area n_attractive·dx·dy (m²)."""
    n_adhesion_updates: int = 0
    """Updates of the law's forces in the solve (each a non-adhesive solve on the effective
    heights, :mod:`warptrunc.contact.iteration.adhesive`); 0 without adhesion."""

    def to_dict(self) -> dict[str, Any]:
        """One row, SI units in the names.

        Returns
        -------
        dict of str to scalar
            ``depth_m`` (m), ``load_N`` (N), ``n_contact``, ``contact_area_m2`` (m²),
            ``n_plastic``, ``plastic_area_m2`` (m²), ``plastic_volume_m3`` (m³), ``mean_gap_m``
            (m), ``n_iterations``, ``n_convolutions``, ``residual_m`` (m),
            ``max_tensile_force_N`` (N), ``converged``, ``adhesive_force_N`` (N),
            ``n_attractive``, ``attractive_area_m2`` (m²), ``n_adhesion_updates``.
        """
        return {
            "depth_m": self.depth,
            "load_N": self.load,
            "n_contact": self.n_contact,
            "contact_area_m2": self.contact_area,
            "n_plastic": self.n_plastic,
            "plastic_area_m2": self.plastic_area,
            "plastic_volume_m3": self.plastic_volume,
            "mean_gap_m": self.mean_gap,
            "n_iterations": self.n_iterations,
            "n_convolutions": self.n_convolutions,
            "residual_m": self.residual,
            "max_tensile_force_N": self.max_tensile_force,
            "converged": self.converged,
            "adhesive_force_N": self.adhesive_force,
            "n_attractive": self.n_attractive,
            "attractive_area_m2": self.attractive_area,
            "n_adhesion_updates": self.n_adhesion_updates,
        }


@dataclass(frozen=True, eq=False)
class ContactCurve:
    """Elastic contact of a rough map against a rigid flat at m approaches (or loads).

    Rows are in the order solved; a solve that stopped at its iteration limit is kept and
    flagged (``converged`` False), never dropped.
    """

    depth: np.ndarray
    """(m,) float64 approach δ of the flat from first touch at the highest pixel (m)."""
    load: np.ndarray
    """(m,) float64 normal load F = Σ pixel forces (N)."""
    n_contact: np.ndarray
    """(m,) int64 pixels in contact (pressure > 0)."""
    area: np.ndarray
    """(m,) float64 real contact area A = n_contact × pixel area (m²)."""
    stiffness: np.ndarray
    """(m,) float64 normal contact stiffness k = dF/dδ (N/m); method in ``settings``."""
    mean_gap: np.ndarray
    """(m,) float64 mean gap between the flat and the deformed surface over the map (m)."""
    n_iterations: np.ndarray
    """(m,) int64 constrained-CG iterations of the solve at δ."""
    n_convolutions: np.ndarray
    """(m,) float64 FFT convolutions of that solve, counted as (forward + inverse transforms) / 2
    (including the warm start's one)."""
    residual: np.ndarray
    """(m,) float64 final max(rms penetration, max penetration, max abs(Δu)) (m), against pentol."""
    max_tensile_force: np.ndarray
    """(m,) float64 final largest tensile pixel force before projection (N), against forcetol."""
    converged: np.ndarray
    """(m,) bool: the solve at δ (and the solves of its stiffness) converged."""
    solve_time: np.ndarray
    """(m,) float64 wall time of the row's solves (s)."""
    n_plastic: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    """(m,) int64 pixels at the pressure cap p = H (all 0 when H = inf)."""
    plastic_area: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """(m,) float64 plastic area n_plastic × pixel area (m²)."""
    plastic_volume: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """(m,) float64 volume removed by plastic flow up to the row, Σ plastic displacement·dx·dy
    (m³)."""
    adhesive_force: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """(m,) float64 sum of the adhesion law's pixel forces (N, ≤ 0; part of ``load``; all 0
    without adhesion)."""
    n_attractive: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    """(m,) int64 pixels out of contact within the law's range (all 0 without adhesion)."""
    attractive_area: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """(m,) float64 attractive area n_attractive × pixel area (m²)."""
    pressure: np.ndarray | None = None
    """(m, ny, nx) float64 contact pressure (Pa; with adhesion the whole traction, tensile
    negative), with ``maps=True``; else None."""
    gap: np.ndarray | None = None
    """(m, ny, nx) float64 gap (m), with ``maps=True``; else None."""
    settings: dict[str, Any] = field(default_factory=dict)
    """Solver settings and tolerances (JSON-able)."""

    all_converged = all_converged_property()

    def to_dict(self) -> dict[str, np.ndarray]:
        """1-D columns, SI units in the names (maps and settings left out).

        Returns
        -------
        dict of str to ndarray
            One ``(m,)`` column per field, m the number of interferences: ``depth_m`` (m),
            ``load_N`` (N), ``n_contact`` (pixels), ``area_m2`` (m²), ``stiffness_N_per_m``
            (N/m), ``mean_gap_m`` (m), ``n_iterations``, ``n_convolutions``, ``residual_m``
            (m), ``max_tensile_force_N`` (N), ``converged``, ``solve_time_s`` (s), and
            ``n_plastic``, ``plastic_area_m2`` (m²), ``plastic_volume_m3`` (m³); with an
            adhesion law (``settings["adhesion"]``) also ``adhesive_force_N`` (N),
            ``n_attractive`` and ``attractive_area_m2`` (m²).
        """

        return {
            "depth_m": self.depth,
            "load_N": self.load,
            "n_contact": self.n_contact,
            "area_m2": self.area,
            "stiffness_N_per_m": self.stiffness,
            "mean_gap_m": self.mean_gap,
            "n_iterations": self.n_iterations,
            "n_convolutions": self.n_convolutions,
            "residual_m": self.residual,
            "max_tensile_force_N": self.max_tensile_force,
            "converged": self.converged,
            "solve_time_s": self.solve_time,
            "n_plastic": self.n_plastic,
            "plastic_area_m2": self.plastic_area,
            "plastic_volume_m3": self.plastic_volume,
            **(
                {
                    "adhesive_force_N": self.adhesive_force,
                    "n_attractive": self.n_attractive,
                    "attractive_area_m2": self.attractive_area,
                }
                if self.settings.get("adhesion")
                else {}
            ),
        }
