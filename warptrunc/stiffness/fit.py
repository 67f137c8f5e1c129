# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The power-law fit y = β·x^α of stiffness curves and of two arrays (paper §4.4).

The one home of power-law fits (:func:`fit_power_law` → :class:`PowerLawFit`): every fit of
warptrunc — ``analyze``, sweeps, ``compare``, ``indent``, ``reproduce`` — goes through it. The
curves it fits are built in :mod:`warptrunc.stiffness.curve`.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .._support.docs import SHARED_DOCS, fill_doc
from .._support.validate import DEFAULT_MIN_PIXELS as _DEFAULT_MIN_PIXELS
from .._support.validate import check_int
from ..material import Material

if TYPE_CHECKING:
    from .curve import StiffnessCurve

__all__ = [
    "DEFAULT_MIN_PIXELS",
    "NORMALISATION_E",
    "NORMALISATION_ESTAR",
    "NORMALISATION_NONE",
    "PowerLawFit",
    "fit_power_law",
]

#: Default fit range: increments with at least this many contact pixels (see README,
#: "Fit range"); the first increments, where a handful of pixels touch, are left out.
DEFAULT_MIN_PIXELS = _DEFAULT_MIN_PIXELS


NORMALISATION_E = "E_c/E"
""":attr:`PowerLawFit.normalisation` of a stiffness-curve fit: β is that of
E_c/E = β·[F/(E·A)]^α with E the Young's modulus of the rough body (the paper's Figs. 6 and 9
and Table 3); ``beta_contact_modulus`` is that of E_c/E*."""

NORMALISATION_ESTAR = "E_c/E*"
"""The ``normalisation`` of a stiffness-curve fit written before the one normalisation (an old
``fit.json``): its ``beta`` was that of E_c/E*, E* the contact modulus, and ``beta_young`` that
of E_c/E. :meth:`PowerLawFit.from_dict` reads such a dict with that meaning."""

NORMALISATION_NONE = "y = beta*x^alpha"
""":attr:`PowerLawFit.normalisation` of a fit of two arrays: β is the prefactor of y = β·x^α."""


@dataclass(frozen=True)
class PowerLawFit:
    """Least-squares power law y = β·x^α, fitted as log y = log β + α·log x.

    For a :class:`StiffnessCurve`, y = E_c/E and x = F/(E·A), E the Young's modulus of the
    rough body (:data:`NORMALISATION_E`): ``beta`` is the β of the paper's Figs. 6 and 9 and
    Table 3; ``beta_contact_modulus`` that of E_c/E*, E* the contact modulus (a factor E/E*
    = 1 − ν² smaller against a rigid flat, α the same).
    """

    alpha: float
    """Exponent α (dimensionless)."""
    beta: float
    """Amplitude β (unit of y per unit of x^α): for a stiffness curve, that of
    E_c/E = β·[F/(E·A)]^α with E the Young's modulus (dimensionless; see
    :attr:`normalisation`)."""
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
    beta_contact_modulus: float = math.nan
    """For a stiffness curve: β* of E_c/E* = β*·[F/(E·A)]^α with E* the contact modulus,
    β·E/E* (dimensionless); NaN for a fit of two arrays or of a curve without a material."""
    normalisation: str = NORMALISATION_E
    """Which quantity ``beta`` belongs to: :data:`NORMALISATION_E` (E_c/E, E the Young's
    modulus) for a stiffness curve, :data:`NORMALISATION_NONE` (y = β·x^α) for two arrays."""
    r: float = math.nan
    """Pearson correlation of log x and log y of a fit of two arrays (dimensionless; NaN when y
    is constant, and for a stiffness curve)."""

    def to_dict(self) -> dict[str, Any]:
        """Plain dict of the fields (JSON-serialisable).

        Returns
        -------
        dict of str to Any
            One key per field; ``depth_window`` is a ``[lo, hi]`` list (m) or None. For a
            stiffness curve ``r`` is left out (it is not computed there).
        """
        d = asdict(self)
        d["depth_window"] = None if self.depth_window is None else list(self.depth_window)
        if self.normalisation == NORMALISATION_E:
            del d["r"]
        return d

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> PowerLawFit:
        """A fit from :meth:`to_dict` (or a ``fit.json``), old ones read with their meaning.

        Parameters
        ----------
        d : dict
            The fields; unknown keys (``provenance``, ``surface``, …) are ignored. A dict
            whose ``normalisation`` is :data:`NORMALISATION_ESTAR` (written before the one
            normalisation) held β of E_c/E* in ``beta`` and β of E_c/E in ``beta_young``: they
            become ``beta_contact_modulus`` and ``beta``.

        Returns
        -------
        PowerLawFit
            With ``beta`` that of E_c/E (E the Young's modulus) for a stiffness curve.
        """
        d = dict(d)
        if d.get("normalisation") == NORMALISATION_ESTAR:
            d["beta_contact_modulus"] = d["beta"]
            d["beta"] = d.pop("beta_young", math.nan)
            d["normalisation"] = NORMALISATION_E
        names = {f.name for f in fields(cls)}
        kw = {k: (math.nan if v is None else v) for k, v in d.items() if k in names}
        if kw.get("depth_window") is not None and kw["depth_window"] is not math.nan:
            kw["depth_window"] = tuple(kw["depth_window"])
        else:
            kw["depth_window"] = None
        return cls(**kw)

    @fill_doc(SHARED_DOCS)
    def to_json(self, path: str | Path) -> Path:
        """Write :meth:`to_dict` as JSON.

        {write_path}

        {returns_path}
            ``path``. Besides the fields of :meth:`to_dict`, the object holds ``provenance``
            (version, commit, command line, time).
        """
        from .._support.provenance import provenance

        path = Path(path)
        path.write_text(json.dumps({**self.to_dict(), "provenance": provenance()}, indent=2) + "\n")
        return path


def fit_power_law(
    sc: StiffnessCurve | Any,
    y: Any = None,
    *,
    min_pixels: int = DEFAULT_MIN_PIXELS,
    depth_window: tuple[float, float] | None = None,
    min_points: int = 3,
) -> PowerLawFit:
    """Fit a power law y = β·x^α by least squares in log–log space.

    ``fit_power_law(sc)`` fits a stiffness curve, E_c/E = β·[F/(E·A)]^α with E the Young's
    modulus (the paper's §4.4);
    ``fit_power_law(x, y)`` fits two arrays, y = β·x^α (k against F, β against δ, …). Every
    power-law fit of warptrunc is this function.

    Parameters
    ----------
    sc : StiffnessCurve or (m,) array_like
        The curves to fit, or the abscissae x (any unit) when ``y`` is given.
    y : (m,) array_like, optional
        Ordinates (any unit); pairs where x or y is not positive and finite are left out.
    min_pixels : int
        Stiffness curve: use only increments with at least this many contact pixels (≥ 1).
        ``1`` keeps every increment with non-zero load. Default :data:`DEFAULT_MIN_PIXELS`.
    depth_window : (float, float), optional
        Stiffness curve: use only depths ω with lo ≤ ω ≤ hi (m).
    min_points : int
        Two arrays: fewest pairs for a fit (≥ 2).

    Returns
    -------
    PowerLawFit
        α, β, r² and, for a stiffness curve, ``beta_contact_modulus`` and the depth and F/(E·A) range of
        the increments used; for two arrays, Pearson ``r`` of the logs and NaN ranges.

    Raises
    ------
    ValueError
        If ``min_pixels`` is not an integer ≥ 1, ``depth_window`` is not (lo, hi) with
        0 ≤ lo < hi, fewer than 3 increments (``min_points`` pairs) remain in the fit range, or x
        does not vary.

    Notes
    -----
    Stiffness curve: increments with zero load (ω = 0) are always left out (log 0); the line is
    solved by the centred normal equations and r² is that of the regression of log(E_c/E) on
    log(F/(E·A)) (NaN when E_c/E does not vary over the range: no regression to measure). β* = β·E/E* (``beta_contact_modulus``): E_c/E* differs from E_c/E by the
    constant E/E*, which shifts log y and leaves α unchanged. An object without a ``material``
    (duck-typed curves: ``load``, ``n_contact_pixels``, ``depth``, ``F_over_EA`` and
    ``Ec_over_E`` arrays) gets NaN there.

    Two arrays: the line by :func:`numpy.polyfit` of natural logs,
    r² = 1 − Σ residual²/Σ(log y − mean)², r by :func:`numpy.corrcoef`.

    Examples
    --------
    >>> fit = fit_power_law(stiffness_curve(tc), min_pixels=100)
    >>> fit.alpha, fit.beta, fit.beta_contact_modulus, fit.r2
    >>> fit_power_law([1.0, 2.0, 4.0], [3.0, 6.0, 12.0]).alpha  # y = 3·x
    """
    if y is not None:
        return _fit_arrays(sc, y, min_points=check_int("min_points", min_points, 2))
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
    # E_c/E constant over the range (the same few contact pixels at every increment): no
    # regression to measure, so r² is undefined (NaN) rather than a value of round-off noise
    flat = float(np.ptp(y)) <= 1e-12 * max(1.0, abs(ym))
    r2 = math.nan if flat else 1.0 - float(resid @ resid) / ss_tot
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
        beta_contact_modulus=_beta_contact_modulus(
            float(np.exp(logb)), getattr(sc, "material", None)
        ),
    )


def _beta_contact_modulus(beta: float, material: Material | None) -> float:
    """β·E/E*: the β of E_c/E* from that of E_c/E (NaN without a material)."""
    return math.nan if material is None else beta * (material.E / material.contact_modulus)


def _fit_arrays(x: Any, y: Any, *, min_points: int) -> PowerLawFit:
    """:func:`fit_power_law` of two arrays (see there)."""
    x = np.asarray(x, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    if x.shape != y.shape or x.ndim != 1:
        raise ValueError(f"x and y must be 1-D of one length, got shapes {x.shape} and {y.shape}")
    ok = (x > 0) & (y > 0) & np.isfinite(x) & np.isfinite(y)
    n = int(np.count_nonzero(ok))
    if n < min_points:
        raise ValueError(f"only {n} positive finite pairs to fit; need at least {min_points}")
    lx, ly = np.log(x[ok]), np.log(y[ok])
    if not np.ptp(lx) > 0:
        raise ValueError("x does not vary over the fit: no slope to fit")
    alpha, logb = (float(v) for v in np.polyfit(lx, ly, 1))
    r = float(np.corrcoef(lx, ly)[0, 1]) if np.ptp(ly) > 0 else math.nan
    res = ly - (alpha * lx + logb)
    ss = float(np.sum((ly - ly.mean()) ** 2))
    r2 = 1.0 - float(np.sum(res**2)) / ss if ss > 0 else 1.0
    nan = math.nan
    return PowerLawFit(
        alpha=alpha,
        beta=math.exp(logb),
        r2=r2,
        n_points=n,
        depth_min=nan,
        depth_max=nan,
        F_over_EA_min=nan,
        F_over_EA_max=nan,
        min_pixels=0,
        depth_window=None,
        normalisation=NORMALISATION_NONE,
        r=r,
    )
