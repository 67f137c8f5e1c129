# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The parameters of a truncation analysis: how the surface is truncated and which increments
the power-law fit reads (:class:`TruncationSettings`, :class:`FitRange`).

Declared once with :func:`warptrunc.params.param`: their defaults, units and ranges make the
options of ``warptrunc analyze``, ``islands`` and ``sweep``, their validation and their JSON.
No Warp here: the command-line parsers import this module.
"""

from __future__ import annotations

from dataclasses import dataclass

from .._support.docs import SHARED_DOCS
from .._support.validate import DEFAULT_MIN_PIXELS, MAX_INCREMENTS
from ..params import Parameters, check_fields, field_docs, param

__all__ = ["TRUNCATION_DOCS", "FitRange", "TruncationSettings"]


@dataclass(frozen=True)
class TruncationSettings(Parameters):
    """How the surface is truncated from its top (§ 2.2) and Eq. 2's punch model.

    The depths are ω_j = j·ω_max/n, j = 1..n, with ω_max = ``max_depth`` when given, else
    ``max_depth_fraction``·R_t.

    Examples
    --------
    >>> TruncationSettings(increments=400, max_depth_fraction=0.2).max_depth_fraction
    0.2
    """

    increments: int = param(
        200,
        "number of depth increments n",
        kind="int",
        ge=1,
        le=MAX_INCREMENTS,
    )
    max_depth_fraction: float = param(
        0.1,
        "largest depth ω_max as a fraction of R_t",
        gt=0.0,
        le=1.0,
    )
    max_depth: float | None = param(
        None,
        "largest depth ω_max; overrides the fraction; none = the fraction",
        unit="m",
        gt=0.0,
        optional=True,
    )
    beta_prime: float = param(1.0, "geometric factor β' of Eq. 2", gt=0.0)
    islands: bool | None = param(
        None,
        "also the island-resolved model k = β'(2/√π)E*·Σ√A_i; none = on for maps in "
        "memory, off when streamed",
        kind="bool",
        optional=True,
    )
    connectivity: int = param(
        4,
        "neighbourhood of an island, 4 or 8 neighbours (island counts, island-resolved model)",
        choices=(4, 8),
    )

    def __post_init__(self) -> None:
        check_fields(self)


@dataclass(frozen=True)
class FitRange(Parameters):
    """Which increments enter the power-law fit E_c/E = β·[F/(E·A)]^α (§ 4.4).

    ``rule="legacy"`` fits the increments to ω_max with at least ``min_pixels`` contact pixels
    (inside ``depth_window`` when given). ``rule="auto"`` does the same and, for a map read from a
    file with no range of the caller's own (``max_depth``, ``depth_window``, ``rt_percentile``),
    applies the automatic rule of :mod:`warptrunc.robust` when that fit is not worth reading.

    Examples
    --------
    >>> FitRange(min_pixels=50, depth_window=(0.0, 2e-6)).depth_window
    (0.0, 2e-06)
    """

    rule: str = param(
        "auto",
        "legacy: increments to ω_max with at least min-pixels contact pixels; auto: the "
        "same, and for a map read from a file with no range of its own the automatic rule of "
        "warptrunc.robust (spikes that set R_t masked, ω_max brought to between 50 contact "
        "pixels and 5 % of A in contact) when that fit is not worth reading",
        choices=("auto", "legacy"),
        cli="fit-range",
        sweep=False,
    )
    min_pixels: int = param(
        DEFAULT_MIN_PIXELS,
        "fit only increments with at least this many contact pixels (1 = all with load > 0)",
        kind="int",
        ge=1,
    )
    depth_window: tuple[float, float] | None = param(
        None,
        "fit only depths LO ≤ ω ≤ HI; none = every depth",
        unit="m",
        ge=0.0,
        length=2,
        increasing=True,
        optional=True,
        metavar=("LO", "HI"),
        sweep=False,
    )
    rt_percentile: tuple[float, float] | None = param(
        None,
        "robust R_t of a measured map: clip the heights to their LO-th and HI-th "
        "percentiles first (e.g. 0.1 99.9); the map must be in memory; none = no clipping",
        unit="%",
        ge=0.0,
        le=100.0,
        length=2,
        increasing=True,
        optional=True,
        metavar=("LO", "HI"),
        sweep=False,
    )
    spikes: bool = param(
        True,
        "let the automatic rule mask the spikes that set R_t of a map read from a file, "
        "and report the spikes where the rule does not run; false: the heights as given",
        kind="bool",
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self)


TRUNCATION_DOCS = {
    **SHARED_DOCS,
    **field_docs(TruncationSettings, "max_depth", "max_depth_fraction", "connectivity"),
    **field_docs(TruncationSettings, n_increments="increments"),
}
TRUNCATION_DOCS["{depth_range}"] = "\n".join(
    TRUNCATION_DOCS[k] for k in ("{n_increments}", "{max_depth}", "{max_depth_fraction}")
)
"""Docstring blocks of the functions that take truncation fields as parameters of their own
(``n_increments``, ``max_depth``, ``max_depth_fraction``, ``connectivity``; ``{depth_range}``:
the first three), from the declarations above, beside :data:`~warptrunc._support.docs.SHARED_DOCS`
(:func:`~warptrunc._support.docs.fill_doc`)."""
