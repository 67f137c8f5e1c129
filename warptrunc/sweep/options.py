# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The parameter objects of a sweep: what every case computes (:class:`SweepOptions`), which
parameters a grid may vary as axes (:data:`AXIS_SPECS`, :func:`axis_names`), and where and how
the cases run (:class:`SweepExecution`).

Declared with :func:`warptrunc.params.param` (no Warp, no pandas, no Dask here: the command-line
parser imports this module).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, fields, replace
from typing import Any

from .._support.validate import DEFAULT_MIN_PIXELS, check_int
from ..material import Material
from ..params import Parameters, check_fields, param, param_info, param_like, sweep_fields
from ..truncation.settings import FitRange, TruncationSettings
from ..wm_params import WMSpec

__all__ = [
    "AXIS_SPECS",
    "FRACTAL_METHODS",
    "SweepExecution",
    "SweepOptions",
    "axis_names",
]

AXIS_SPECS = (WMSpec, Material)
"""The parameter classes whose sweepable fields (:func:`warptrunc.params.sweep_fields`) a grid
may name as axes."""

_CORE = ("D", "Rt")
"""Not extra axes: D is one of the grid's own axes, R_t = δ·W_r follows from δ."""

_NOT_AXES = ("L", "n", "cutoff")
"""Fields of :class:`SweepOptions` that no axis may vary (the grid of every case is the same)."""

FRACTAL_METHODS = ("tri", "box", "vs", "sp")
"""Methods of :func:`warptrunc.fractal_dimensions` that ``fractal_methods`` may name."""

_DISTINCT = ("min_pixels", "min_pixels_fraction", "fractal_methods", "bem_fractions")
"""Fields holding several values, none of which may repeat (each value is a row or a column)."""


@dataclass(frozen=True)
class SweepOptions(Parameters):
    """Generation, truncation, material and fit options shared by every case (SI units).

    Each field is declared once, where it belongs: the generation fields by
    :class:`~warptrunc.WMSpec`, the truncation fields by
    :class:`~warptrunc.truncation.settings.TruncationSettings`, the fit range by
    :class:`~warptrunc.truncation.settings.FitRange` and the material by
    :class:`~warptrunc.Material` (:func:`warptrunc.params.param_like`: same name, default, unit,
    range and description); R_t is not an option: each case has R_t = δ·W_r. The fields that
    only a sweep has (several fit ranges, relative fit ranges, fractal dimensions, elastic
    solves) are declared here; ``None`` turns each of them off.

    Examples
    --------
    >>> SweepOptions(n=512, min_pixels=(1, 10)).min_pixels
    (1, 10)
    """

    Wr: float = param_like(WMSpec, "Wr")
    L: float | tuple[float, float] = param_like(WMSpec, "L")
    n: int | tuple[int, int] = param_like(WMSpec, "n", ge=8)
    M: int = param_like(WMSpec, "M")
    gamma: float = param_like(WMSpec, "gamma")
    Wc: float | None = param_like(WMSpec, "Wc")
    cutoff: str = param_like(WMSpec, "cutoff")
    increments: int = param_like(TruncationSettings, "increments")
    max_depth_fraction: float = param_like(TruncationSettings, "max_depth_fraction")
    max_depth: float | None = param_like(TruncationSettings, "max_depth")
    E: float = param_like(Material, "E")
    nu: float = param_like(Material, "nu")
    E_i: float = param_like(Material, "E_i")
    nu_i: float = param_like(Material, "nu_i")
    beta_prime: float = param_like(TruncationSettings, "beta_prime")
    min_pixels: tuple[int, ...] = param_like(
        FitRange,
        "min_pixels",
        default=(DEFAULT_MIN_PIXELS,),
        many=True,
        doc="fit ranges: fit only increments with at least this many contact pixels (1 = all "
        "with load > 0); several values: one fit (row) each",
    )
    depth_window: tuple[float, float] | None = param_like(FitRange, "depth_window")
    min_pixels_fraction: tuple[float, ...] | None = param(
        None,
        "more fit ranges, relative to each case: one row per value f, fitting the "
        f"increments with at least max({DEFAULT_MIN_PIXELS}, ⌈f·final contact pixels⌉) contact "
        "pixels (stored with min_pixels = that count); none = no relative range",
        gt=0.0,
        le=1.0,
        many=True,
        optional=True,
        metavar="F",
        sweep=False,
    )
    fractal_methods: tuple[str, ...] | None = param(
        None,
        "measure D of each generated surface by these methods of fractal_dimensions "
        "(its default options): columns D_<method>, D_<method>_r2, fractal_options; none = no "
        "measurement",
        choices=FRACTAL_METHODS,
        many=True,
        optional=True,
        cli="fractal",
        metavar="METHOD",
        sweep=False,
    )
    bem_fractions: tuple[float, ...] | None = param(
        None,
        "elastic solves per case (free half-space, warptrunc.contact) at approaches "
        "δ = f·R_t (measured R_t) against Eq. 2 at the same depth: columns F_bem_N_<f>, "
        "A_bem_m2_<f>, k_bem_N_per_m_<f>, F_trunc_N_<f>, ..., the ratios F_ratio_<f>, "
        "A_ratio_<f>, k_ratio_<f> and bem_converged_<f>; none = no elastic solve",
        gt=0.0,
        lt=1.0,
        many=True,
        optional=True,
        metavar="F",
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self, keep_pairs=True)  # a pair stays a pair: it enters the case ids
        for name in _DISTINCT:
            v = getattr(self, name)
            if v is not None and len(set(v)) != len(v):
                raise ValueError(f"{name} must not repeat a value, got {v!r}")
        if self.bem_fractions is not None:
            object.__setattr__(self, "bem_fractions", tuple(sorted(self.bem_fractions)))

    def material(self) -> Material:
        """The :class:`warptrunc.Material` of these options.

        Returns
        -------
        Material
            ``E``, ``nu``, ``E_i`` and ``nu_i`` (Pa, dimensionless); purely elastic.
        """
        return Material(E=self.E, nu=self.nu, E_i=self.E_i, nu_i=self.nu_i)

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
            Field name (of :class:`~warptrunc.WMSpec` or :class:`~warptrunc.Material`) → value.

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
        for name in values:
            if name not in mine or name in _NOT_AXES:
                raise ValueError(
                    f"the sweep cannot vary {name!r}: it is not an option of the sweep "
                    f"(axes it can vary: {', '.join(axis_names(AXIS_SPECS, runnable=True))})"
                )
        return replace(self, **values)


def axis_names(specs: Sequence[type] = AXIS_SPECS, *, runnable: bool = False) -> list[str]:
    """The fields that a grid may name as extra axes: sweepable fields of ``specs`` but D and R_t.

    Parameters
    ----------
    specs : sequence of type
        Parameter classes.
    runnable : bool
        Only those that :func:`~warptrunc.sweep.run_sweep` can vary (a field of
        :class:`SweepOptions` other than the grid's size and cut-off).

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
            if runnable and (name not in mine or name in _NOT_AXES):
                continue
            out.append(name)
    return out


@dataclass(frozen=True)
class SweepExecution(Parameters):
    """Where and how the cases of a sweep run; nothing here changes a number of the results.

    ``SweepExecution()`` runs the cases in this process, one after another (several light
    surfaces per launch on a GPU). ``workers`` starts a local Dask cluster for the run;
    ``scheduler`` uses an existing one.

    Raises
    ------
    ValueError
        ``workers`` neither a count ≥ 1 nor ``"auto"``; ``workers`` and ``scheduler`` both
        given; a shard field out of its range.

    Examples
    --------
    >>> SweepExecution(workers=4, shard_seconds=2.0).distributed
    True
    """

    workers: int | str | None = None
    """Run on a local Dask cluster of this many worker processes (one thread each; ``"auto"``:
    one per visible CUDA device, 1 on a machine without one), started once for the whole run
    (:func:`warptrunc.sweep.cluster.open_client`); with CUDA devices and no ``device``, worker i
    is pinned to ``cuda:{i mod n_gpus}`` (dask-cuda's LocalCUDACluster where installed). The
    workers are spawned processes, so a script that passes ``workers`` needs the
    ``if __name__ == "__main__":`` guard. None: in this process."""
    scheduler: Any = None
    """An existing Dask cluster to use instead (e.g. ``"tcp://host:8786"``, a dask-jobqueue
    cluster's ``scheduler_address``, or a ``distributed.Client``). Its workers write their parts
    into the store themselves: the store must be on a filesystem that every worker shares."""
    devices: int | str | tuple | None = None
    """Spread each elastic solve (``bem_fractions``) over several devices
    (``contact_solver(..., devices=...)``; JAX): a count, ``"auto"`` or a sequence; None: the
    case's device alone. With ``workers`` or ``scheduler``, a count G: each worker takes G
    devices of its own and spreads its solves over them (:mod:`warptrunc.sweep.groups`;
    ``workers="auto"`` is then the devices present divided by G)."""
    shard_size: int | None = param(
        None,
        "with workers or a scheduler: cases per Dask task, each written by its worker "
        "as one part of the store; none = adaptive, about shard_seconds of work (from the "
        "median case time so far, at most 4096 cases, and at least two tasks per worker for "
        "what remains)",
        kind="int",
        ge=1,
        le=10**6,
        optional=True,
        sweep=False,
    )
    shard_seconds: float = param(
        1.0,
        "work per part of the store: the adaptive shard size with workers, and how much "
        "the in-process engine gathers before writing a part (0: whatever finished while the "
        "previous part was written); a hard kill loses at most about this much per worker",
        unit="s",
        ge=0.0,
        sweep=False,
    )
    max_retries: int = param(
        3,
        "resubmissions of a case whose Dask task was lost before it is recorded as failed",
        kind="int",
        ge=0,
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self)
        w = self.workers
        if isinstance(w, str) and w.strip().lower() == "auto":
            object.__setattr__(self, "workers", "auto")
        elif w is not None:
            if isinstance(w, str) and w.strip().isdigit():
                w = int(w.strip())
            object.__setattr__(self, "workers", check_int("workers", w, 1))
        if self.workers is not None and self.scheduler is not None:
            raise ValueError(
                "give workers (a local cluster) or scheduler (an existing one), not both"
            )
        if isinstance(self.devices, list):
            object.__setattr__(self, "devices", tuple(self.devices))

    @property
    def distributed(self) -> bool:
        """True when the cases run on a Dask cluster (``workers`` or ``scheduler``)."""
        return self.workers is not None or self.scheduler is not None

    @property
    def spread(self) -> bool:
        """True when each elastic solve is spread over several devices (``devices`` ≠ 1)."""
        return self.devices not in (None, 1)
