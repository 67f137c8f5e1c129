# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The parameters of the island analysis: what :func:`~warptrunc.islands.island_curve` carries
across the depths (:class:`IslandSettings`, with the depths of :data:`ISLANDS_TRUNCATION`) and
how :func:`~warptrunc.islands.applicable_depth` reads the curve (:class:`IndicatorSettings`).

Declared once with :func:`warptrunc.params.param`: their defaults, units and ranges make the
options of ``warptrunc islands``, their validation and their JSON. No Warp here: the
command-line parser imports this module.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..params import Parameters, check_fields, field_docs, param
from ..truncation.settings import TRUNCATION_DOCS, TruncationSettings

__all__ = [
    "ISLANDS_TRUNCATION",
    "ISLAND_DOCS",
    "MIN_ISLANDS",
    "MIN_PIXELS",
    "IndicatorSettings",
    "IslandSettings",
]

MIN_PIXELS = 10
"""Default smallest island (pixels) in a slit-island fit: below ~10 pixels the pixel-edge
perimeter of an island is set by the grid (1 pixel: L = 4·dx, A = dx²), not by the surface."""

MIN_ISLANDS = 5
"""Fewest islands for a slit-island fit; fewer give NaN."""

ISLANDS_TRUNCATION = TruncationSettings(max_depth_fraction=0.5)
"""The depths of an island curve: 200 increments to ω_max = 0.5·R_t, not the 0.1·R_t of the
stiffness fit: the island count rises and falls again deeper than the stiffness fit reads, and
0.5 covers its peak on the paper's surfaces (Fig. 8). :func:`~warptrunc.islands.island_curve`
reads ``increments``, ``max_depth_fraction``, ``max_depth`` and ``connectivity``."""


@dataclass(frozen=True)
class IslandSettings(Parameters):
    """What the island curve carries at every depth besides the island count (§ 4.3, Fig. 8).

    Examples
    --------
    >>> IslandSettings(statistics=False).snapshots
    (0.1, 0.2, 0.3, 0.4)
    """

    periodic: bool = param(
        False,
        "wrap the map around in x and y (islands cut by the border join the other side)",
        kind="bool",
    )
    statistics: bool = param(
        True,
        "also carry every island's area and perimeter: slit-island fits, area histogram, "
        "Σ√A_i and the snapshots; false: island counts, χ and total perimeter only (fastest)",
        kind="bool",
    )
    min_pixels: int = param(
        MIN_PIXELS, "smallest island in the slit-island fits (pixels)", kind="int", ge=1
    )
    snapshots: tuple[float, ...] | None = param(
        (0.1, 0.2, 0.3, 0.4),
        "depths, as fractions of R_t, at which every island's area and "
        "perimeter is kept (slit_islands.png), each moved to the nearest increment; only with "
        "statistics; none = no snapshots",
        gt=0.0,
        le=1.0,
        many=True,
        optional=True,
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self)


@dataclass(frozen=True)
class IndicatorSettings(Parameters):
    """How the applicable-depth indicators of Table 2 are read off an island curve (§ 4.3).

    Raises
    ------
    ValueError
        A field out of its range, or an even ``smooth``.

    Examples
    --------
    >>> IndicatorSettings(min_islands=5).smooth
    5
    """

    exponent_tolerance: float = param(
        0.05,
        "relative drop X of the slit-island exponent below its plateau that ends fractality",
        gt=0.0,
        lt=1.0,
    )
    min_islands: int = param(
        50,
        "fewest fitted islands for a depth's exponent to count (the first contact spots "
        "give noisy fits)",
        kind="int",
        ge=MIN_ISLANDS,
    )
    plateau_width: float = param(
        0.1, "width of the plateau window, as a fraction of R_t", gt=0.0, le=1.0
    )
    persist: float = param(
        0.02,
        "depth span, as a fraction of R_t, a drop of the exponent must last to count "
        "(0: a single sample)",
        ge=0.0,
        le=1.0,
    )
    smooth: int = param(
        5,
        "odd window (depth samples) of the running mean of the growth rate and the running "
        "median of the exponent; 1: no smoothing",
        kind="int",
        ge=1,
    )

    def __post_init__(self) -> None:
        check_fields(self)
        if self.smooth % 2 == 0:
            raise ValueError(f"smooth must be odd, got {self.smooth!r}")


ISLAND_DOCS = {**TRUNCATION_DOCS, **field_docs(IslandSettings, "periodic")}
ISLAND_DOCS["{label_options}"] = "\n".join(
    ISLAND_DOCS[k] for k in ("{connectivity}", "{periodic}", "{device}")
)
"""Docstring blocks of the island functions: the truncation fields' and ``{periodic}`` from
their declarations, ``{label_options}`` (connectivity, periodic, device) and
:data:`~warptrunc._support.docs.SHARED_DOCS` (:func:`~warptrunc._support.docs.fill_doc`)."""
