# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stiffness and load from truncated areas (paper Eqs. 1–3): :class:`StiffnessCurve`.

The one home of Eq. 2 (:func:`flat_punch_stiffness`), of the area model
(:func:`stiffness_curve`) and the island-resolved model (:func:`island_stiffness_curve`), and of
the load integral F = ∫k dω (``cumulative_load``). The power-law fit of these curves is in
:mod:`warptrunc.stiffness.fit`; everything is re-exported by :mod:`warptrunc.stiffness`.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .._support.docs import SHARED_DOCS, fill_doc
from .._support.outputs import write_columns_csv
from .._support.results import fields_to_dict
from .._support.validate import check_range
from ..material import Material
from ..params import field_docs
from ..truncation.curve import TruncationCurve
from ..truncation.settings import TRUNCATION_DOCS, TruncationSettings

__all__ = [
    "STIFFNESS_MODELS",
    "StiffnessCurve",
    "flat_punch_stiffness",
    "island_stiffness_curve",
    "stiffness_curve",
]

STIFFNESS_DOCS = {**TRUNCATION_DOCS, **field_docs(TruncationSettings, "beta_prime")}
"""Docstring blocks of the stiffness functions: β' from its declaration
(:class:`~warptrunc.truncation.settings.TruncationSettings`), and the shared ones."""


STIFFNESS_MODELS = ("area", "islands")
"""Values of :attr:`StiffnessCurve.model`: ``"area"`` = Eq. (2), one flat punch of the whole
truncated area; ``"islands"`` = one flat punch per island of the truncated set,
k = β'(2/√π)E*·Σ√A_i."""

_TWO_OVER_SQRT_PI = 2.0 / math.sqrt(math.pi)  # the flat-punch factor 2/√π of Eqs. (1)–(2)


@dataclass(frozen=True, eq=False)
class StiffnessCurve:
    """Stiffness k(ω), load F(ω) and their normalised forms at every truncation depth."""

    depth: np.ndarray
    """(n+1,) truncation depth ω (m)."""
    n_contact_pixels: np.ndarray
    """(n+1,) int64 contact pixels."""
    contact_area: np.ndarray
    """(n+1,) truncated area A_c (m²)."""
    stiffness: np.ndarray
    """(n+1,) k = β'·(2/√π)·E_r'·√A_c (N/m), Eq. (2); for ``model="islands"``
    k = β'·(2/√π)·E_r'·Σ_i √A_i over the islands."""
    load: np.ndarray
    """(n+1,) F(ω) = ∫₀^ω k dω' by the cumulative trapezoidal rule (N)."""
    Ec_over_E: np.ndarray
    """(n+1,) E_c/E with E the Young's modulus of the rough body (dimensionless), as the
    paper's Figs. 6 and 9 plot it: (E*/E)·β'·√(A_c/A), E_c = (√π/2)·k/√A (§4.1);
    (E*/E)·β'·Σ√A_i/√A for ``model="islands"``. Before the one normalisation (changelog) this
    column held E_c/E* (now :attr:`Ec_over_Estar`)."""
    F_over_EA: np.ndarray
    """(n+1,) F/(E·A) with E the Young's modulus of the rough body (dimensionless)."""
    Ec_over_Estar: np.ndarray
    """(n+1,) E_c/E* = β'·√(A_c/A) (dimensionless), Eq. (3): normalised by the contact modulus
    E* = ``material.contact_modulus`` instead, a constant factor E/E* = 1 − ν² (against a rigid
    flat) below :attr:`Ec_over_E`; β'·Σ√A_i/√A for ``model="islands"``."""
    material: Material
    """Elastic constants used."""
    beta_prime: float
    """Geometric factor β' (dimensionless)."""
    apparent_area: float
    """Apparent area A (m²)."""
    Rt: float
    """Peak-to-valley height R_t of the map (m)."""
    model: str = "area"
    """``"area"`` (Eq. 2, one punch of the truncated area) or ``"islands"`` (one punch per
    island, :func:`island_stiffness_curve`): one of :data:`STIFFNESS_MODELS`."""

    def to_dict(self) -> dict[str, np.ndarray]:
        """Columns in the order of ``curve.csv``.

        Returns
        -------
        dict of str to ndarray
            Eight (n+1,) columns: ``depth_m`` (m), ``n_contact_pixels`` (int64),
            ``contact_area_m2`` (m²), ``stiffness_N_per_m`` (N/m), ``load_N`` (N),
            ``Ec_over_E`` (E_c/E, E the Young's modulus), ``F_over_EA`` and ``Ec_over_Estar``
            (E_c/E*, E* the contact modulus), all dimensionless. The arrays are the fields
            themselves, not copies.
        """
        return fields_to_dict(
            self,
            {
                "depth": "depth_m",
                "contact_area": "contact_area_m2",
                "stiffness": "stiffness_N_per_m",
                "load": "load_N",
            },
            skip=("material", "beta_prime", "apparent_area", "Rt", "model"),
        )

    @fill_doc(SHARED_DOCS)
    def to_json(self, path: str | Path) -> Path:
        """Write the columns of :meth:`to_dict` (lists) plus the material and β' as JSON.

        {write_path}

        {returns_path}
            ``path``. Besides the columns, the object holds ``material`` (the fields of
            :class:`Material`), ``beta_prime``, ``apparent_area_m2`` (m²), ``Rt_m`` (R_t, m)
            and ``provenance`` (version, commit, command line, time).
        """
        from .._support.provenance import provenance

        path = Path(path)
        d = {k: v.tolist() for k, v in self.to_dict().items()}
        d.update(material=asdict(self.material), beta_prime=self.beta_prime)
        d.update(apparent_area_m2=self.apparent_area, Rt_m=self.Rt, provenance=provenance())
        path.write_text(json.dumps(d, indent=1, default=str) + "\n")
        return path

    @fill_doc(SHARED_DOCS)
    def to_csv(self, path: str | Path, islands: StiffnessCurve | None = None) -> Path:
        """Write the columns of :meth:`to_dict` as CSV (full float64 precision).

        Parameters
        ----------
        path : str or Path
            File to write (overwritten): a header row of the column names, then one row per
            truncation depth.
        islands : StiffnessCurve, optional
            The island-resolved model on the same depths (:func:`island_stiffness_curve`);
            appends ``stiffness_islands_N_per_m`` (N/m), ``load_islands_N`` (N),
            ``Ec_over_E_islands`` (E_c/E, E the Young's modulus) and ``Ec_over_Estar_islands``
            (E_c/E*), dimensionless, as ``analyze`` writes ``curve.csv``.

        {returns_path}
            ``path``.

        Raises
        ------
        ValueError
            If ``islands`` is not on the same depths.
        """
        cols = self.to_dict()
        if islands is not None:
            if not np.array_equal(islands.depth, self.depth):
                raise ValueError("islands must be on the same depths as this curve")
            cols = {
                **cols,
                "stiffness_islands_N_per_m": islands.stiffness,
                "load_islands_N": islands.load,
                "Ec_over_E_islands": islands.Ec_over_E,
                "Ec_over_Estar_islands": islands.Ec_over_Estar,
            }
        return write_columns_csv(path, cols)


@fill_doc(STIFFNESS_DOCS)
def flat_punch_stiffness(
    sqrt_area: Any,
    contact_modulus: float,
    *,
    beta_prime: float = 1.0,
) -> Any:
    """Normal stiffness of flat punches, k = β'·(2/√π)·E*·√A (paper Eq. 2).

    The one place Eq. (2) is written: :func:`stiffness_curve`, :func:`island_stiffness_curve`,
    the sweep's elastic columns and :func:`warptrunc.bem_check` call it.

    Parameters
    ----------
    sqrt_area : float or ndarray
        √A of the punch (m): √A_c for the whole truncated area (Eq. 2), or Σ_i √A_i for islands
        taken as independent punches.
    contact_modulus : float
        Contact modulus E* = E_r′ (Pa), :attr:`Material.contact_modulus`.
    {beta_prime}
        1 is the flat punch.

    Returns
    -------
    float or ndarray
        k (N/m), the shape of ``sqrt_area``.

    Raises
    ------
    ValueError
        If ``contact_modulus`` or ``beta_prime`` is not positive and finite.

    Notes
    -----
    Sneddon's flat punch of radius a, k = 2E*a, written with its area A = πa²:
    k = (2/√π)·E*·√A. β' corrects for a non-circular punch (Pharr, Oliver & Brotzen 1992).

    Examples
    --------
    >>> flat_punch_stiffness(math.sqrt(1e-6), Material().contact_modulus)  # 1 mm² punch (N/m)
    """
    contact_modulus = check_range("contact_modulus", contact_modulus, 0.0, unit="Pa")
    beta_prime = check_range("beta_prime", beta_prime, 0.0)
    return beta_prime * _TWO_OVER_SQRT_PI * contact_modulus * sqrt_area


@fill_doc(STIFFNESS_DOCS)
def stiffness_curve(
    curve: TruncationCurve,
    material: Material | None = None,
    *,
    beta_prime: float = 1.0,
) -> StiffnessCurve:
    """Stiffness, load and normalised curves from a truncation curve.

    Parameters
    ----------
    curve : TruncationCurve
        Truncated areas A_c(ω) (m²).
    material : Material, optional
        Elastic constants; default aluminium (E = 70 GPa, ν = 0.33) against a rigid flat.
    {beta_prime}
        1 is the flat punch.

    Returns
    -------
    StiffnessCurve
        k, F, E_c/E (E the Young's modulus), E_c/E* and F/(E·A) at each of the n+1 depths of ``curve`` (float64).

    Raises
    ------
    ValueError
        If ``beta_prime`` is not positive and finite.

    Notes
    -----
    k = β'·(2/√π)·E_r'·√A_c (Eq. 2, :func:`flat_punch_stiffness`);
    F(ω_k) = Σ_{j<k} ½(k_j + k_{j+1})(ω_{j+1} − ω_j) (cumulative trapezoidal rule, F(0) = 0);
    E_c/E* = β'·√(A_c/A) (Eq. 3, E_c = (√π/2)·k/√A) and E_c/E = (E*/E)·E_c/E*; F/(E·A) with
    E the Young's modulus of the rough body and A = Lx·Ly.

    Examples
    --------
    >>> tc = warptrunc.truncation_curve(surface, n_increments=200)
    >>> sc = stiffness_curve(tc, Material(E=200e9, nu=0.3))
    >>> sc.stiffness[-1]  # k at ω = R_t, full contact (N/m)
    """
    material = Material() if material is None else material
    beta_prime = check_range("beta_prime", beta_prime, 0.0)
    area = np.asarray(curve.contact_area, dtype=np.float64)
    k = flat_punch_stiffness(np.sqrt(area), material.contact_modulus, beta_prime=beta_prime)
    load = cumulative_load(k, curve.depth)
    A = curve.apparent_area
    return StiffnessCurve(
        depth=np.asarray(curve.depth, dtype=np.float64),
        n_contact_pixels=np.asarray(curve.n_contact_pixels, dtype=np.int64),
        contact_area=area,
        stiffness=k,
        load=load,
        Ec_over_E=(Ec := beta_prime * np.sqrt(area / A)) * _young_factor(material),
        F_over_EA=load / (material.E * A),
        Ec_over_Estar=Ec,
        material=material,
        beta_prime=beta_prime,
        apparent_area=A,
        Rt=curve.Rt,
    )


def _young_factor(material: Material) -> float:
    """E*/E: from E_c/E* (the contact modulus) to E_c/E (the Young's modulus of the rough body)."""
    return material.contact_modulus / material.E


def cumulative_load(stiffness: np.ndarray, depth: np.ndarray) -> np.ndarray:
    """F(ω_k) = Σ_{j<k} ½(k_j + k_{j+1})(ω_{j+1} − ω_j), F(ω_0) = 0 (N): the cumulative
    trapezoidal rule shared by both stiffness models."""
    k = np.asarray(stiffness, dtype=np.float64)
    dw = np.diff(np.asarray(depth, dtype=np.float64))
    return np.concatenate([[0.0], np.cumsum(0.5 * (k[1:] + k[:-1]) * dw)])


@fill_doc(STIFFNESS_DOCS)
def island_stiffness_curve(
    island_curve: Any,
    material: Material | None = None,
    *,
    beta_prime: float = 1.0,
) -> StiffnessCurve:
    """Island-resolved truncation: one flat punch per island of the truncated set.

    Parameters
    ----------
    island_curve : IslandCurve
        Islands at every depth, from :func:`warptrunc.islands.island_curve` with
        ``statistics=True`` (which carries Σ_i √A_i, m).
    material : Material, optional
        Elastic constants; default aluminium (E = 70 GPa, ν = 0.33) against a rigid flat.
    {beta_prime}
        1 is the flat punch.

    Returns
    -------
    StiffnessCurve
        ``model="islands"``: k, F, E_c/E, E_c/E* and F/(E·A) at each depth of ``island_curve``
        (float64); ``contact_area`` is the total truncated area A' (m²).

    Raises
    ------
    ValueError
        If ``island_curve`` was computed without statistics, or ``beta_prime`` is not positive.

    Notes
    -----
    k_isl = β'·(2/√π)·E_r'·Σ_i √A_i, the islands taken as independent flat punches (no elastic
    interaction between them), against Eq. (2)'s k' = β'·(2/√π)·E_r'·√(Σ_i A_i); since
    Σ√A_i ≥ √ΣA_i, k_isl ≥ k', with equality for one island. N equal islands give
    k_isl = √N·k'. F_isl = ∫₀^ω k_isl dω' by the cumulative trapezoidal rule, as Eq. (2)'s F;
    E_c/E* = β'·Σ√A_i/√A and E_c/E = (E*/E)·E_c/E*, so :func:`fit_power_law` applies unchanged.

    Examples
    --------
    >>> t = warptrunc.truncation.TruncationSettings()  # 200 depths to 0.1·R_t
    >>> ic = warptrunc.islands.island_curve(surface, truncation=t)
    >>> sc = island_stiffness_curve(ic)
    >>> fit_power_law(sc).alpha
    """
    material = Material() if material is None else material
    beta_prime = check_range("beta_prime", beta_prime, 0.0)
    s = getattr(island_curve, "sqrt_area_sum", None)
    if s is None:
        raise ValueError(
            "island_curve has no Σ√A_i: compute it with island_curve(..., "
            "settings=IslandSettings(statistics=True))"
        )
    s = np.asarray(s, dtype=np.float64)
    depth = np.asarray(island_curve.depth, dtype=np.float64)
    k = flat_punch_stiffness(s, material.contact_modulus, beta_prime=beta_prime)
    load = cumulative_load(k, depth)
    n = np.asarray(island_curve.n_contact_pixels, dtype=np.int64)
    A = getattr(island_curve, "apparent_area", None)
    if A is None:
        raise ValueError("island_curve has no apparent_area: compute it with island_curve()")
    A = float(A)
    return StiffnessCurve(
        depth=depth,
        n_contact_pixels=n,
        contact_area=np.asarray(island_curve.contact_area, dtype=np.float64),
        stiffness=k,
        load=load,
        Ec_over_E=(Ec := beta_prime * s / math.sqrt(A)) * _young_factor(material),
        F_over_EA=load / (material.E * A),
        Ec_over_Estar=Ec,
        material=material,
        beta_prime=beta_prime,
        apparent_area=A,
        Rt=float(island_curve.Rt),
        model="islands",
    )
