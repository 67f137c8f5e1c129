# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stiffness and load from truncated areas (paper Eqs. 1–3) and the power-law fit (§4.4).

Host-side float64 arithmetic on a :class:`~warptrunc.truncation.TruncationCurve`.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ._support.results import fields_to_dict
from ._support.table import write_columns_csv
from ._support.validate import check_int, check_range
from .material import Material
from .truncation import TruncationCurve

__all__ = [
    "DEFAULT_MIN_PIXELS",
    "Material",
    "PowerLawFit",
    "StiffnessCurve",
    "fit_power_law",
    "island_stiffness_curve",
    "stiffness_curve",
]

MODELS = ("area", "islands")
"""Stiffness models: ``"area"`` = Eq. (2), one flat punch of the whole truncated area;
``"islands"`` = one flat punch per island of the truncated set, k = β'(2/√π)E*·Σ√A_i."""

#: Default fit range: increments with at least this many contact pixels (see README,
#: "Fit range"); the first increments, where a handful of pixels touch, are left out.
DEFAULT_MIN_PIXELS = 10


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
    """(n+1,) E_c/E = β'·√(A_c/A) (dimensionless), Eq. (3); β'·Σ√A_i/√A for
    ``model="islands"``."""
    F_over_EA: np.ndarray
    """(n+1,) F/(E·A) (dimensionless)."""
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
    island, :func:`island_stiffness_curve`)."""

    def to_dict(self) -> dict[str, np.ndarray]:
        """Columns in the order of ``curve.csv``.

        Returns
        -------
        dict of str to ndarray
            Seven (n+1,) columns: ``depth_m`` (m), ``n_contact_pixels`` (int64),
            ``contact_area_m2`` (m²), ``stiffness_N_per_m`` (N/m), ``load_N`` (N),
            ``Ec_over_E`` and ``F_over_EA`` (dimensionless). The arrays are the fields
            themselves, not copies.
        """
        return fields_to_dict(
            self,
            {"depth": "depth_m", "contact_area": "contact_area_m2",
             "stiffness": "stiffness_N_per_m", "load": "load_N"},
            skip=("material", "beta_prime", "apparent_area", "Rt", "model"),
        )  # fmt: skip

    def to_json(self, path: str | Path) -> Path:
        """Write the columns of :meth:`to_dict` (lists) plus the material and β' as JSON.

        Parameters
        ----------
        path : str or Path
            File to write (overwritten).

        Returns
        -------
        Path
            ``path``. Besides the columns, the object holds ``material`` (the fields of
            :class:`Material`), ``beta_prime``, ``apparent_area_m2`` (m²), ``Rt_m`` (R_t, m)
            and ``provenance`` (version, commit, command line, time).
        """
        from ._support.provenance import provenance

        path = Path(path)
        d = {k: v.tolist() for k, v in self.to_dict().items()}
        d.update(material=asdict(self.material), beta_prime=self.beta_prime)
        d.update(apparent_area_m2=self.apparent_area, Rt_m=self.Rt, provenance=provenance())
        path.write_text(json.dumps(d, indent=1, default=str) + "\n")
        return path

    def to_csv(self, path: str | Path, islands: StiffnessCurve | None = None) -> Path:
        """Write the columns of :meth:`to_dict` as CSV (full float64 precision).

        Parameters
        ----------
        path : str or Path
            File to write (overwritten): a header row of the column names, then one row per
            truncation depth.
        islands : StiffnessCurve, optional
            The island-resolved model on the same depths (:func:`island_stiffness_curve`);
            appends ``stiffness_islands_N_per_m`` (N/m), ``load_islands_N`` (N) and
            ``Ec_over_E_islands`` (dimensionless), as ``analyze`` writes ``curve.csv``.

        Returns
        -------
        Path
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
            cols = {**cols, "stiffness_islands_N_per_m": islands.stiffness,
                    "load_islands_N": islands.load, "Ec_over_E_islands": islands.Ec_over_E}  # fmt: skip
        return write_columns_csv(path, cols)


@dataclass(frozen=True)
class PowerLawFit:
    """Least-squares fit of log(E_c/E) = log β + α·log(F/(E·A))."""

    alpha: float
    """Exponent α (dimensionless)."""
    beta: float
    """Amplitude β (dimensionless)."""
    r2: float
    """Coefficient of determination of the log–log fit (dimensionless)."""
    n_points: int
    """Number of increments used (count)."""
    depth_min: float
    """Smallest depth used (m)."""
    depth_max: float
    """Largest depth used (m)."""
    F_over_EA_min: float
    """Smallest F/(E·A) used (dimensionless)."""
    F_over_EA_max: float
    """Largest F/(E·A) used (dimensionless)."""
    min_pixels: int
    """Contact-pixel threshold of the fit range (pixels)."""
    depth_window: tuple[float, float] | None
    """Depth window of the fit range (m), if one was given."""

    def to_dict(self) -> dict[str, Any]:
        """Plain dict of the fields (JSON-serialisable).

        Returns
        -------
        dict of str to Any
            One key per field; ``depth_window`` is a ``[lo, hi]`` list (m) or None.
        """
        d = asdict(self)
        d["depth_window"] = None if self.depth_window is None else list(self.depth_window)
        return d

    def to_json(self, path: str | Path) -> Path:
        """Write :meth:`to_dict` as JSON.

        Parameters
        ----------
        path : str or Path
            File to write (overwritten).

        Returns
        -------
        Path
            ``path``. Besides the fields of :meth:`to_dict`, the object holds ``provenance``
            (version, commit, command line, time).
        """
        from ._support.provenance import provenance

        path = Path(path)
        path.write_text(json.dumps({**self.to_dict(), "provenance": provenance()}, indent=2) + "\n")
        return path


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
    beta_prime : float
        Geometric factor β' of Eq. (2) (dimensionless); 1 is the flat punch.

    Returns
    -------
    StiffnessCurve
        k, F, E_c/E and F/(E·A) at each of the n+1 depths of ``curve`` (float64).

    Raises
    ------
    ValueError
        If ``beta_prime`` is not positive and finite.

    Notes
    -----
    k = β'·(2/√π)·E_r'·√A_c (Eq. 2); F(ω_k) = Σ_{j<k} ½(k_j + k_{j+1})(ω_{j+1} − ω_j) (cumulative
    trapezoidal rule, F(0) = 0); E_c/E = β'·√(A_c/A) (Eq. 3); F/(E·A) with E the Young's
    modulus of the rough body and A = Lx·Ly.

    Examples
    --------
    >>> tc = warptrunc.truncation_curve(surface, n_increments=200)
    >>> sc = stiffness_curve(tc, Material(E=200e9, nu=0.3))
    >>> sc.stiffness[-1]  # k at ω = R_t, full contact (N/m)
    """
    material = Material() if material is None else material
    beta_prime = check_range("beta_prime", beta_prime, 0.0)
    area = np.asarray(curve.contact_area, dtype=np.float64)
    k = beta_prime * (2.0 / math.sqrt(math.pi)) * material.contact_modulus * np.sqrt(area)
    load = cumulative_load(k, curve.depth)
    A = curve.apparent_area
    return StiffnessCurve(
        depth=np.asarray(curve.depth, dtype=np.float64),
        n_contact_pixels=np.asarray(curve.n_contact_pixels, dtype=np.int64),
        contact_area=area,
        stiffness=k,
        load=load,
        Ec_over_E=beta_prime * np.sqrt(area / A),
        F_over_EA=load / (material.E * A),
        material=material,
        beta_prime=beta_prime,
        apparent_area=A,
        Rt=curve.Rt,
    )


def cumulative_load(stiffness: np.ndarray, depth: np.ndarray) -> np.ndarray:
    """F(ω_k) = Σ_{j<k} ½(k_j + k_{j+1})(ω_{j+1} − ω_j), F(ω_0) = 0 (N): the cumulative
    trapezoidal rule shared by both stiffness models."""
    k = np.asarray(stiffness, dtype=np.float64)
    dw = np.diff(np.asarray(depth, dtype=np.float64))
    return np.concatenate([[0.0], np.cumsum(0.5 * (k[1:] + k[:-1]) * dw)])


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
    beta_prime : float
        Geometric factor β' (dimensionless); 1 is the flat punch.

    Returns
    -------
    StiffnessCurve
        ``model="islands"``: k, F, E_c/E and F/(E·A) at each depth of ``island_curve``
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
    E_c/E = β'·Σ√A_i/√A, so :func:`fit_power_law` applies unchanged.

    Examples
    --------
    >>> ic = warptrunc.islands.island_curve(surface, 200, max_depth_fraction=0.1)
    >>> sc = island_stiffness_curve(ic)
    >>> fit_power_law(sc).alpha
    """
    material = Material() if material is None else material
    beta_prime = check_range("beta_prime", beta_prime, 0.0)
    s = getattr(island_curve, "sqrt_area_sum", None)
    if s is None:
        raise ValueError(
            "island_curve has no Σ√A_i: compute it with island_curve(..., statistics=True)"
        )
    s = np.asarray(s, dtype=np.float64)
    depth = np.asarray(island_curve.depth, dtype=np.float64)
    k = beta_prime * (2.0 / math.sqrt(math.pi)) * material.contact_modulus * s
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
        Ec_over_E=beta_prime * s / math.sqrt(A),
        F_over_EA=load / (material.E * A),
        material=material,
        beta_prime=beta_prime,
        apparent_area=A,
        Rt=float(island_curve.Rt),
        model="islands",
    )


def fit_power_law(
    sc: StiffnessCurve,
    *,
    min_pixels: int = DEFAULT_MIN_PIXELS,
    depth_window: tuple[float, float] | None = None,
) -> PowerLawFit:
    """Fit E_c/E = β·[F/(E·A)]^α by least squares in log–log space.

    Parameters
    ----------
    sc : StiffnessCurve
        The curves to fit.
    min_pixels : int
        Use only increments with at least this many contact pixels (≥ 1). ``1`` keeps every
        increment with non-zero load. Default :data:`DEFAULT_MIN_PIXELS`.
    depth_window : (float, float), optional
        Use only depths ω with lo ≤ ω ≤ hi (m).

    Returns
    -------
    PowerLawFit
        α, β, r² and the depth and F/(E·A) range of the increments used.

    Raises
    ------
    ValueError
        If ``min_pixels`` is not an integer ≥ 1, ``depth_window`` is not (lo, hi) with
        0 ≤ lo < hi, or fewer than 3 increments remain in the fit range.

    Notes
    -----
    Increments with zero load (ω = 0) are always left out (log 0). r² is that of the linear
    regression of log(E_c/E) on log(F/(E·A)).

    Examples
    --------
    >>> fit = fit_power_law(stiffness_curve(tc), min_pixels=100)
    >>> fit.alpha, fit.beta, fit.r2
    """
    min_pixels = check_int("min_pixels", min_pixels, 1)
    sel = (sc.load > 0) & (sc.n_contact_pixels >= min_pixels)
    if depth_window is not None:
        lo, hi = (float(v) for v in depth_window)
        if not (0 <= lo < hi):
            raise ValueError(
                f"depth_window must be (lo, hi) with 0 ≤ lo < hi (m), got {depth_window!r}"
            )
        sel &= (sc.depth >= lo) & (sc.depth <= hi)
    if np.count_nonzero(sel) < 3:
        raise ValueError(
            f"only {int(np.count_nonzero(sel))} increments in the fit range (min_pixels={min_pixels}, "
            f"depth_window={depth_window}); need at least 3: lower min_pixels or widen the window"
        )
    x = np.log(sc.F_over_EA[sel])
    y = np.log(sc.Ec_over_E[sel])
    # least squares by the centred normal equations (as np.polyfit(x, y, 1), ~5× faster)
    xm, ym = float(np.add.reduce(x)) / x.size, float(np.add.reduce(y)) / y.size
    xc, yc = x - xm, y - ym
    sxx = float(xc @ xc)
    if not sxx > 0:
        raise ValueError("F/(E·A) does not vary over the fit range: no slope to fit")
    alpha = float(xc @ yc) / sxx
    logb = ym - alpha * xm
    resid = yc - alpha * xc
    ss_tot = float(yc @ yc)
    r2 = 1.0 - float(resid @ resid) / ss_tot if ss_tot > 0 else 1.0
    d = sc.depth[sel]
    f = sc.F_over_EA[sel]
    return PowerLawFit(
        alpha=float(alpha),
        beta=float(np.exp(logb)),
        r2=r2,
        n_points=int(sel.sum()),
        depth_min=float(d.min()),
        depth_max=float(d.max()),
        F_over_EA_min=float(f.min()),
        F_over_EA_max=float(f.max()),
        min_pixels=min_pixels,
        depth_window=None if depth_window is None else (lo, hi),
    )
