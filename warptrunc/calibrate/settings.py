# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The parameters of the calibration loop of Fig. 4 (:mod:`warptrunc.calibrate`): the
descriptors to reproduce (:class:`CalibrationTarget`) and how the loop runs
(:class:`CalibrationSettings`).

Declared once with :func:`warptrunc.params.param` (the WM parameters among them as
:class:`~warptrunc.WMSpec` declares them): their defaults, units and ranges make the options of
``warptrunc calibrate``, their validation and their JSON. No Warp here: the command-line parser
imports this module.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

from .._support.outputs import jsonable
from ..fractal.settings import METHODS, FractalSettings, height_options
from ..params import Parameters, check_fields, param, param_like
from ..wm_params import WMSpec

__all__ = ["CalibrationSettings", "CalibrationTarget"]


def _target_like(name: str, doc: str, **changes: Any) -> Any:
    """A required field declared like :class:`WMSpec`'s ``name`` (unit, range), with ``doc``."""
    meta = param_like(WMSpec, name, doc=doc, **changes).metadata
    return dataclasses.field(metadata=meta)


@dataclass(frozen=True)
class CalibrationTarget(Parameters):
    """Descriptors that the simulated surfaces must reproduce (SI units).

    Measured on a scan (:func:`~warptrunc.calibrate.target_from_surface`) or typed in. ``L``
    and ``n`` are kept as (x, y) pairs (a scalar is both).

    Raises
    ------
    ValueError
        A field out of its range (the message names the field, its value and the range), or
        ``Rrms`` not below ``Rt``.

    Examples
    --------
    >>> CalibrationTarget(D=2.4, method="vs", Rrms=2e-6, Rt=15e-6, Wr=125e-6, L=1e-3, n=64).n
    (64, 64)
    """

    D: float = _target_like("D", "target fractal dimension D by the method")
    method: str = param(dataclasses.MISSING, "fractal method of D", choices=METHODS, sweep=False)
    Rrms: float = param(dataclasses.MISSING, "target R_rms", unit="m", gt=0.0)
    Rt: float = _target_like(
        "Rt",
        "peak-to-valley height R_t of the scan, the R_t of the D loop's surfaces",
        optional=False,
    )
    Wr: float = _target_like("Wr", "roll-off wavelength W_r")
    L: tuple[float, float] = _target_like("L", "scan side L, or Lx Ly")
    n: tuple[int, int] = _target_like("n", "scan pixels per side, or nx ny", ge=8)
    method_options: dict[str, Any] = field(default_factory=dict)
    """Options of the fractal method, used for the scan and the simulated surfaces alike."""
    source: str = ""
    """Where the targets come from (a file name, or ``"given"``)."""

    def __post_init__(self) -> None:
        check_fields(self)
        for name in ("L", "n"):
            v = getattr(self, name)
            object.__setattr__(self, name, v if isinstance(v, tuple) else (v, v))
        if self.Rrms >= self.Rt:
            raise ValueError(f"Rrms must be below Rt = {self.Rt!r} m, got {self.Rrms!r} m")
        object.__setattr__(self, "method_options", dict(self.method_options))

    def to_dict(self) -> dict[str, Any]:
        """Scalars (JSON-serialisable).

        Returns
        -------
        dict
            ``D``, ``method``, ``Rrms_m``, ``Rt_m``, ``Wr_m``, ``Lx_m``, ``Ly_m`` (m),
            ``nx``, ``ny`` (pixels), ``method_options`` (non-finite numbers as text) and
            ``source``.
        """
        return {
            "D": self.D,
            "method": self.method,
            "Rrms_m": self.Rrms,
            "Rt_m": self.Rt,
            "Wr_m": self.Wr,
            "Lx_m": self.L[0],
            "Ly_m": self.L[1],
            "nx": self.n[0],
            "ny": self.n[1],
            "method_options": jsonable(self.method_options, nonfinite="text"),
            "source": self.source,
        }


@dataclass(frozen=True)
class CalibrationSettings(Parameters):
    """How the calibration loop runs (Fig. 4): the method matched, the seeds averaged, the
    tolerance and the search, the WM inputs that are not calibrated, and the surface written
    from the result (:func:`~warptrunc.calibrate.calibrated_surface`, ``warptrunc calibrate``'s
    surface.npz).

    Examples
    --------
    >>> CalibrationSettings(method="box", height_scaling="si").method_options()
    {'height_scaling': 'si'}
    """

    method: str = param(
        "tri",
        "fractal method whose D is matched, on the scan and the simulated surfaces alike",
        choices=METHODS,
        sweep=False,
    )
    height_scaling: str = param_like(FractalSettings, "height_scaling")
    seeds: tuple[int, ...] = param(
        (0, 1, 2),
        "seeds of the WM phases; D_out and R_rms are averaged over them at every evaluation",
        kind="seeds",
        sweep=False,
    )
    rtol: float = param(
        0.05,
        "relative tolerance on D: abs(D_out − D) ≤ rtol·D (the paper: 5 %), or the scatter "
        "tolerance where that is tighter",
        gt=0.0,
        lt=1.0,
    )
    scatter_sd: float = param(
        2.0,
        "tolerance on D in standard deviations of D_out over the seeds (measured at the first "
        "D_in): abs(D_out − D) ≤ scatter-sd·sd where that is tighter than rtol·D, since a "
        "difference inside the descriptor's own scatter is all a calibration can resolve; 0, "
        "or a single seed: rtol alone",
        ge=0.0,
        le=100.0,
    )
    D_start: float | None = param(
        None,
        "first D_in; none = the target D, clipped to D-bounds",
        gt=2.0,
        lt=3.0,
        optional=True,
        sweep=False,
    )
    D_bounds: tuple[float, float] = param(
        (2.02, 2.98),
        "search interval of D_in, inside (2, 3); a result on a bound is reported as such",
        gt=2.0,
        lt=3.0,
        length=2,
        increasing=True,
        metavar=("LO", "HI"),
        sweep=False,
    )
    max_iter: int = param(12, "evaluations of the D loop per round", kind="int", ge=2, le=1000)
    max_rounds: int = param(
        3,
        "rounds of the D loop and the R_t loop (a round repeats only while D_out at R_t' "
        "leaves the tolerance)",
        kind="int",
        ge=1,
        le=100,
    )
    M: int = param_like(WMSpec, "M")
    gamma: float = param_like(WMSpec, "gamma")
    cutoff: str = param_like(WMSpec, "cutoff")
    n_out: int | tuple[int, int] | None = param(
        None,
        "pixels per side of the calibrated surface written (or nx ny); none = the scan's",
        kind="int",
        ge=2,
        pair=True,
        optional=True,
        sweep=False,
    )
    seed_out: int = param_like(WMSpec, "seed", doc="seed of the phases of the surface written")

    def __post_init__(self) -> None:
        check_fields(self)

    def method_options(self) -> dict[str, Any]:
        """The options of ``method`` (its height convention for ``"tri"`` and ``"box"``).

        Returns
        -------
        dict
            Keyword options of :func:`~warptrunc.fractal.fractal_dimension`.
        """
        return height_options(self.method, self.height_scaling)

    def wm_options(self) -> dict[str, Any]:
        """The WM inputs that are not calibrated (``M``, ``gamma``, ``cutoff``).

        Returns
        -------
        dict
            Keywords of :func:`~warptrunc.wm_surface`.
        """
        return {"M": self.M, "gamma": self.gamma, "cutoff": self.cutoff}
