# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The options shared by every case of a sweep (:class:`SweepOptions`) and the parameters a
grid may vary as axes (:data:`AXIS_SPECS`, :func:`axis_names`, :func:`option_name`)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict, dataclass, fields, replace
from typing import Any

from .._support.validate import MAX_INCREMENTS, check_int, check_range
from ..material import Material
from ..params import check_fields, param_info, param_like, sweep_fields
from ..stiffness import DEFAULT_MIN_PIXELS
from ..wm_params import WMSpec

__all__ = ["AXIS_SPECS", "FRACTAL_METHODS", "SweepOptions", "axis_names", "option_name"]

AXIS_SPECS = (WMSpec, Material)
"""The parameter classes whose sweepable fields (:func:`warptrunc.params.sweep_fields`) a grid
may name as axes."""

_CORE = ("D", "Rt")
"""Not extra axes: D is one of the grid's own axes, R_t = δ·W_r follows from δ."""

FRACTAL_METHODS = ("tri", "box", "vs", "sp")
"""Methods of :func:`warptrunc.fractal_dimensions` that ``fractal_methods`` may name."""

_OMIT_WHEN_EMPTY = ("min_pixels_fraction", "fractal_methods", "bem_fractions")

@dataclass(frozen=True)
class SweepOptions:
    """Generation, truncation, material and fit options shared by every case (SI units).

    Names follow ``warptrunc analyze``; R_t is not an option: each case has R_t = δ·W_r.
    The generation and material fields are declared by :class:`~warptrunc.WMSpec` and
    :class:`~warptrunc.Material` (:func:`warptrunc.params.param_like`: same default, unit,
    range and description); ``E_flat`` and ``nu_flat`` are Material's ``E_i`` and ``nu_i``
    under the names that the stores and their case ids have always used.
    """

    Wr: float = param_like(WMSpec, "Wr")
    L: float | tuple[float, float] = param_like(WMSpec, "L")
    n: int | tuple[int, int] = param_like(WMSpec, "n", ge=8)
    M: int = param_like(WMSpec, "M")
    gamma: float = param_like(WMSpec, "gamma")
    Wc: float | None = param_like(WMSpec, "Wc")
    cutoff: str = param_like(WMSpec, "cutoff")
    increments: int = 200
    """Number of depth increments n."""
    max_depth_fraction: float = 0.1
    """ω_max as a fraction of R_t (dimensionless)."""
    max_depth: float | None = None
    """ω_max (m); overrides the fraction."""
    E: float = param_like(Material, "E")
    nu: float = param_like(Material, "nu")
    E_flat: float = param_like(Material, "E_i", cli="E-flat")
    nu_flat: float = param_like(Material, "nu_i", cli="nu-flat")
    beta_prime: float = 1.0
    """Geometric factor β' of Eq. 2."""
    min_pixels: tuple[int, ...] = (DEFAULT_MIN_PIXELS,)
    """Fit ranges: one row per value (increments with at least this many contact pixels)."""
    depth_window: tuple[float, float] | None = None
    """Fit only depths lo ≤ ω ≤ hi (m)."""
    min_pixels_fraction: tuple[float, ...] = ()
    """More fit ranges, relative to each case: one row per value f in (0, 1], fitting the
    increments with at least max(DEFAULT_MIN_PIXELS, ⌈f·final contact pixels⌉) contact pixels
    (the deep part of each curve). Stored with ``min_pixels`` = that resolved count."""
    fractal_methods: tuple[str, ...] = ()
    """Measure the fractal dimension of each generated surface by these methods of
    :func:`warptrunc.fractal_dimensions` (``"tri"``, ``"box"``, ``"vs"``, ``"sp"``; that
    function's default options). Columns ``D_<method>``, ``D_<method>_r2`` and
    ``fractal_options`` (JSON: each fit's scalars and options). Off by default."""
    bem_fractions: tuple[float, ...] = ()
    """Elastic solves per case at approaches δ = f·R_t (measured R_t), f in (0, 1): the free
    half-space solver :func:`warptrunc.contact.solve_contact` (Barber stiffness) against Eq. 2's
    truncation values at the same depth, in wide columns ``<quantity>_<f>``
    (:data:`warptrunc.sweep.read.BEM_QUANTITIES`). Off by default."""

    def __post_init__(self) -> None:
        s = object.__setattr__
        check_fields(self, keep_pairs=True)  # the WMSpec and Material fields, by their metadata
        s(self, "increments", check_int("increments", self.increments, 1, MAX_INCREMENTS))
        s(self, "max_depth_fraction",
          check_range("max_depth_fraction", self.max_depth_fraction, 0, 1, hi_open=False))  # fmt: skip
        if self.max_depth is not None:
            s(self, "max_depth", check_range("max_depth", self.max_depth, 0, None, unit="m"))
        s(self, "beta_prime", check_range("beta_prime", self.beta_prime, 0, None))
        mp = (self.min_pixels,) if isinstance(self.min_pixels, int) else tuple(self.min_pixels)
        if not mp or len(set(mp)) != len(mp):
            raise ValueError(f"min_pixels must hold distinct values, got {self.min_pixels!r}")
        s(self, "min_pixels", tuple(check_int("min_pixels", v, 1) for v in mp))
        if self.depth_window is not None:
            lo, hi = (float(v) for v in self.depth_window)
            if not 0 <= lo < hi:
                raise ValueError(
                    f"depth_window must be (lo, hi) with 0 ≤ lo < hi (m), got {self.depth_window!r}"
                )
            s(self, "depth_window", (lo, hi))
        fr = self.min_pixels_fraction
        fr = (fr,) if isinstance(fr, (int, float)) else tuple(fr)
        fr = tuple(check_range("min_pixels_fraction", v, 0, 1, hi_open=False) for v in fr)
        if len(set(fr)) != len(fr):
            raise ValueError(f"min_pixels_fraction must hold distinct values, got {fr!r}")
        s(self, "min_pixels_fraction", fr)
        fm = (self.fractal_methods,) if isinstance(self.fractal_methods, str) else tuple(self.fractal_methods)
        for m in fm:
            if m not in FRACTAL_METHODS:
                raise ValueError(f"fractal_methods must be among {FRACTAL_METHODS}, got {m!r}")
        if len(set(fm)) != len(fm):
            raise ValueError(f"fractal_methods must not repeat, got {fm!r}")
        s(self, "fractal_methods", fm)
        bf = self.bem_fractions
        bf = (bf,) if isinstance(bf, (int, float)) else tuple(bf)
        bf = tuple(check_range("bem_fractions", v, 0, 1) for v in bf)
        if len(set(bf)) != len(bf):
            raise ValueError(f"bem_fractions must hold distinct values, got {bf!r}")
        s(self, "bem_fractions", tuple(sorted(bf)))

    def to_dict(self) -> dict[str, Any]:
        """The options as JSON-ready values (tuples as lists).

        Options added after the store format was fixed (``min_pixels_fraction``,
        ``fractal_methods``, ``bem_fractions``) appear only when set, so the case ids and ``sweep.json`` of
        stores made without them stay valid.

        Returns
        -------
        dict of str to Any
            One entry per field (SI units), tuples converted to lists.
        """
        d = asdict(self)
        for k in _OMIT_WHEN_EMPTY:
            if not d[k]:
                del d[k]
        return {k: list(v) if isinstance(v, tuple) else v for k, v in d.items()}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> SweepOptions:
        """Inverse of :meth:`to_dict`; unknown names raise ValueError.

        Parameters
        ----------
        d : dict of str to Any
            Field values; lists become tuples, missing fields take their defaults.

        Returns
        -------
        SweepOptions
            The validated options.

        Raises
        ------
        ValueError
            If ``d`` names an unknown option or a value is out of range.
        """
        names = {f.name for f in fields(cls)}
        bad = sorted(set(d) - names)
        if bad:
            raise ValueError(f"unknown sweep options {bad}; allowed: {sorted(names)}")
        kw = {k: tuple(v) if isinstance(v, list) else v for k, v in d.items()}
        return cls(**kw)

    def material(self):
        """The :class:`warptrunc.Material` of these options.

        Returns
        -------
        Material
            ``E``, ``nu``, ``E_flat`` and ``nu_flat`` as E, ν, E_i, ν_i (Pa, dimensionless).
        """

        return Material(E=self.E, nu=self.nu, E_i=self.E_flat, nu_i=self.nu_flat)

    def wm_spec(self, D: float, Rt: float, seed: int = 0) -> WMSpec:
        """The :class:`~warptrunc.WMSpec` of one case: these options' generation fields.

        Parameters
        ----------
        D : float
            Input fractal dimension D_in (dimensionless).
        Rt : float
            Peak-to-valley height R_t (m).
        seed : int
            Phase seed.

        Returns
        -------
        WMSpec
        """
        mine = {f.name for f in fields(self)}
        kw = {k: getattr(self, k) for k in param_info(WMSpec) if k in mine}
        return WMSpec(D=D, Rt=Rt, seed=seed, **kw)

    def with_axes(self, values: dict[str, Any]) -> SweepOptions:
        """These options with a case's extra-axis values in place (validated).

        Parameters
        ----------
        values : dict of str to Any
            Field name (of :class:`~warptrunc.WMSpec` or :class:`~warptrunc.Material`: ``E_i``
            and ``nu_i`` are this object's ``E_flat`` and ``nu_flat``) → value.

        Returns
        -------
        SweepOptions

        Raises
        ------
        ValueError
            An axis that is no option of the sweep.
        """
        if not values:
            return self
        mine = {f.name for f in fields(self)}
        kw = {}
        for name, v in values.items():
            opt = option_name(name)
            if opt not in mine or opt in _NOT_AXES:
                raise ValueError(
                    f"the sweep cannot vary {name!r}: it is not an option of the sweep "
                    f"(axes it can vary: {', '.join(axis_names(AXIS_SPECS, runnable=True))})"
                )
            kw[opt] = v
        return replace(self, **kw)


_OPTION_OF = {"E_i": "E_flat", "nu_i": "nu_flat"}
"""Axis (parameter field) → SweepOptions field, where the names differ."""


def option_name(name: str) -> str:
    """The :class:`SweepOptions` field that holds parameter field ``name``.

    Parameters
    ----------
    name : str
        A field of :class:`~warptrunc.WMSpec` or :class:`~warptrunc.Material`.

    Returns
    -------
    str
        ``E_flat`` for ``E_i``, ``nu_flat`` for ``nu_i`` (the stores' names), else ``name``.
    """
    return _OPTION_OF.get(name, name)

_NOT_AXES = ("L", "n", "cutoff")


def axis_names(specs: Sequence[type] = AXIS_SPECS, *, runnable: bool = False) -> list[str]:
    """The fields that a grid may name as extra axes: sweepable fields of ``specs`` but D and R_t.

    Parameters
    ----------
    specs : sequence of type
        Parameter classes.
    runnable : bool
        Only those that :func:`~warptrunc.sweep.run_sweep` can vary (a field of
        :class:`SweepOptions`).

    Returns
    -------
    list of str
    """
    mine = {f.name for f in fields(SweepOptions)}
    out = []
    for spec in specs:
        for name in sweep_fields(spec):
            if name in _CORE or name in out:
                continue
            if runnable and option_name(name) not in mine:
                continue
            out.append(name)
    return out


