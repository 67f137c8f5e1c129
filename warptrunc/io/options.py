# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""How a height-map file is read: :class:`ReadOptions` (pixel spacing, height unit, missing
points, levelling, reader, channel, spikes), the keywords of
:func:`~warptrunc.io.read_height_map` as one parameter object. No Warp here: the command-line
parsers import this module."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..params import Parameters, check_fields, param
from .repair import FILL_METHODS

__all__ = ["ENGINES", "SPIKE_RULES", "ReadOptions"]

ENGINES = ("auto", "builtin", "surfacetopography")
"""Readers: ``builtin`` for .npz/.npy/.csv/.txt/.tsv, ``surfacetopography`` for instrument
files, ``auto`` by the suffix."""

SPIKE_RULES = ("auto", "report", "mask", "off")
"""What is done with spike pixels of a map read from a file (see :class:`ReadOptions`)."""


@dataclass(frozen=True)
class ReadOptions(Parameters):
    """Options for reading a height-map file (SI units).

    The first seven fields are the keywords of :func:`~warptrunc.io.read_height_map`
    (:meth:`reader_kwargs`); ``spikes`` says what the commands do with spike pixels
    (:mod:`warptrunc.plausibility`: off their neighbours' median by > 10 robust sigmas and by
    more than half the P0.1–P99.9 height range) once the map is read.
    """

    dx: float | None = param(
        None,
        "pixel spacing along x if not in the file; none = from the file",
        unit="m",
        gt=0.0,
        optional=True,
        sweep=False,
    )
    dy: float | None = param(
        None, "pixel spacing along y; none = dx", unit="m", gt=0.0, optional=True, sweep=False
    )
    height_unit: float = param(
        1.0,
        "metres per height unit, for files that declare none (e.g. 1e-6 for µm)",
        unit="m",
        gt=0.0,
        sweep=False,
    )
    missing: str = param(
        "error",
        "missing (NaN) points: stop with their count, or fill them",
        choices=("error", "fill"),
        sweep=False,
    )
    fill: str = param(
        "nearest",
        "fill method of missing points (with missing = fill)",
        choices=FILL_METHODS,
        sweep=False,
    )
    level: bool = param(False, "subtract the least-squares plane", kind="bool", sweep=False)
    engine: str = param(
        "auto",
        "reader: built-in for .npz/.npy/.csv/.txt/.tsv, SurfaceTopography otherwise",
        choices=ENGINES,
        sweep=False,
    )
    channel: int | None = param(
        None,
        "data channel of instrument files; none = the first",
        kind="int",
        ge=0,
        optional=True,
        sweep=False,
    )
    spikes: str = param(
        "report",
        "spike pixels: auto = reported, and masked where they include the highest or "
        "the lowest pixel (repeated passes); report = only as warnings; mask = each replaced by "
        "its neighbours' median (R_t recomputed); off = no check",
        choices=SPIKE_RULES,
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self)

    def reader_kwargs(self) -> dict[str, Any]:
        """The keywords of :func:`~warptrunc.io.read_height_map`.

        Returns
        -------
        dict
            ``dx``, ``dy`` (m), ``height_unit`` (m per unit), ``missing``, ``fill``, ``level``,
            ``engine``, ``channel``.
        """
        d = self.to_dict()
        d.pop("spikes")
        return d
