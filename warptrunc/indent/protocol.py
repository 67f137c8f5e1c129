# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The paper's indentation protocol (§ 4.1) as parameters: :class:`IndentProtocol` (punches,
peak loads, partial unloading, placements, refinement, the punch face), the paper's punches
and loads, and the material :func:`warptrunc.indent` assumes.

Loads no Warp (the command line's parser reads it); the cycles the protocol describes are run
by :mod:`warptrunc.indent.cycles`.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import Any

from ..material import DIAMOND, Material
from ..params import Parameters, check_fields, param
from .depth import DETECTION_LOAD
from .face import PunchFaceSpec

DEFAULT_MAX_WINDOW_PIXELS = 2**26
"""Largest punch window solved whole at a refined pixel by default (pixels): 8192², about
13 GB of solver state in float32 (``IndentProtocol.max_window_pixels``)."""

__all__ = [
    "ALUMINIUM_HARDNESS",
    "DEFAULT_PEAK_LOADS",
    "MATERIAL_DEFAULTS",
    "PAPER_PEAK_LOADS",
    "PAPER_PROTOCOL",
    "PAPER_PUNCH_DIAMETERS",
    "IndentProtocol",
    "default_material",
]

PAPER_PUNCH_DIAMETERS = (54.1e-6, 108.7e-6, 502.6e-6)
"""Diameters of the paper's flat diamond punches (m): FLT-D050, FLT-D100, FLT-D500 (§ 4.1)."""

PAPER_PEAK_LOADS = tuple(0.5 / 2**k for k in range(9, -1, -1))
"""The paper's ten peak loads (N): each twice the previous, the last 500 mN (§ 4.1)."""

DEFAULT_PEAK_LOADS = PAPER_PEAK_LOADS[-5:]
"""The peak loads of :class:`IndentProtocol` by default (N): the five heaviest of the paper's,
31.25–500 mN (1.2 decades). At a pixel of about 1 µm and H = 1 GPa their plastic contacts
hold about 35–535 pixels, so the three heaviest pass the 100 contact pixels of a resolved cell
on every punch; the paper's five lighter loads touch fewer than 20 pixels there (unresolved,
left out of every fit) and would cost as many solves again."""

ALUMINIUM_HARDNESS = 1.0e9
"""Hardness H assumed for a treated (precipitation-hardened) aluminium alloy (Pa), the local
pressure cap: an assumption, not the paper's (it names neither its alloy nor a hardness).

6061-T6: Vickers hardness about 107 HV ≈ 1.05 GPa (handbook value, e.g. ASM Handbook Vol. 2,
*Properties and Selection: Nonferrous Alloys and Special-Purpose Materials*); Tabor's
H ≈ 3σ_y with σ_y = 276 MPa gives 0.83 GPa (D. Tabor, *The Hardness of Metals*, Oxford, 1951).
1.0 GPa is a round value between the two; ``reproduce`` sweeps H instead of assuming it
(``docs/guide/indentation.md``)."""

MATERIAL_DEFAULTS = {**DIAMOND, "hardness": ALUMINIUM_HARDNESS}
"""The fields of :func:`default_material` that differ from ``Material()``: a diamond
counter-body and :data:`ALUMINIUM_HARDNESS` (the defaults of ``warptrunc indent``)."""


def default_material(**kw: Any) -> Material:
    """An aluminium alloy as warptrunc assumes it, against diamond punches, with a hardness.

    The paper indents aluminium-alloy discs with diamond flat punches (§ 4.1) but states none
    of E, ν, E_i, ν_i or H: these values are assumptions with the sources given in
    :class:`~warptrunc.material.Material` and :data:`ALUMINIUM_HARDNESS`.

    Parameters
    ----------
    **kw
        Fields to change (``E``, ``nu``, ``hardness``, ...).

    Returns
    -------
    Material
        ``Material()``'s E = 70 GPa, ν = 0.33 with :data:`MATERIAL_DEFAULTS`: H =
        :data:`ALUMINIUM_HARDNESS`, diamond E_i = 1141 GPa, ν_i = 0.07 (Oliver & Pharr,
        J. Mater. Res. 7, 1564 (1992)).
    """
    return Material(**{**MATERIAL_DEFAULTS, **kw})


@dataclass(frozen=True)
class IndentProtocol(Parameters):
    """The experiment of § 4.1: punches, peak loads, partial unloading, punch positions, the
    refinement of the cells in the pixel size and the punch face.

    The ``face`` (:class:`~warptrunc.indent.face.PunchFaceSpec`) makes the punch the
    experiment's: a tilt held fixed and a rough face, generated or read; by default an aligned
    smooth flat.

    Raises
    ------
    ValueError
        A field out of its range (the message names it, its value and the range), peak loads
        that do not increase, or a ``refine_max`` that is not a power of 2.

    Examples
    --------
    >>> IndentProtocol().peak_loads[-1]  # the paper's last peak (N)
    0.5
    >>> len(IndentProtocol().peak_loads), len(PAPER_PROTOCOL.peak_loads)
    (5, 10)
    >>> IndentProtocol(punch_diameters=None, placements=None).punch_diameters is None
    True
    """

    punch_diameters: tuple[float, ...] | None = param(
        PAPER_PUNCH_DIAMETERS,
        "punch diameters d; none = one flat larger than the map",
        unit="m",
        gt=0.0,
        many=True,
        optional=True,
        sweep=False,
    )
    peak_loads: tuple[float, ...] = param(
        DEFAULT_PEAK_LOADS,
        "peak loads F of the cycles, increasing (default the paper's five heaviest, 31.25–500 "
        "mN; the paper's ten: 0.98–500 mN, each twice the previous)",
        unit="N",
        gt=0.0,
        many=True,
        sweep=False,
    )
    unload_fraction: float = param(
        0.1,
        "partial unloading of each cycle, as a fraction of its peak load",
        gt=0.0,
        lt=1.0,
    )
    placements: int | None = param(
        2,
        "punch positions per diameter (random, apart; two give the fits' intervals over "
        "indents); none = one at the map centre",
        kind="int",
        ge=1,
        le=10_000,
        optional=True,
        sweep=False,
    )
    placement_seed: int = param(
        0,
        "seed of the random punch positions",
        kind="int",
        ge=0,
        le=2**32 - 1,
        sweep=False,
    )
    overlap: str = param(
        "warn",
        "punches of one diameter that cannot be placed apart: 'warn' (placed as far "
        "apart as found, overlap reported) or 'error'",
        choices=("warn", "error"),
        sweep=False,
    )
    truncation_increments: int = param(
        1000,
        "depth increments of the Eq. 2 truncation curve under each punch",
        kind="int",
        ge=10,
        le=10_000_000,
        sweep=False,
    )
    resolution_tol: float = param(
        0.02,
        "a refined cell is resolved when the error estimate of its unloading stiffness K "
        "(Richardson, over the last two halvings of the pixel) is below this, relative to the "
        "extrapolated K; its contact area is reported with the same estimate",
        gt=0.0,
        lt=1.0,
        sweep=False,
    )
    min_contact_pixels: int = param(
        100,
        "fewest contact pixels of a resolved cell",
        kind="int",
        ge=1,
        le=10**9,
        sweep=False,
    )
    refine_max: int = param(
        1,
        "largest refinement of the pixel (a power of 2; 1 = none, the cells judged by their "
        "contact pixels): a WM map's punch windows are generated again at pixel/2, /4, … up "
        "to pixel/refine_max, each halving four times the pixels of a solve",
        kind="int",
        ge=1,
        le=1024,
        sweep=False,
    )
    max_window_pixels: int = param(
        DEFAULT_MAX_WINDOW_PIXELS,
        "largest punch window solved whole at a refined pixel (rows × columns, 8192² by "
        "default); a larger one is cut to a sub-window that holds the contact and its "
        "interaction range",
        kind="int",
        ge=64,
        le=2**40,
        sweep=False,
    )
    detection_load: float | None = param(
        DETECTION_LOAD,
        "surface-detection force F_s: the threshold depth is measured from where the punch "
        "first carries F_s, as an indenter reads depth (10 µN: an assumption; none = only "
        "the depth from the highest point)",
        unit="N",
        gt=0.0,
        optional=True,
        sweep=False,
    )
    elastic: bool = param(
        True,
        "also solve the elastic contact (H = ∞) on the same punches (else its columns are NaN)",
        kind="bool",
        sweep=False,
    )
    face: PunchFaceSpec = field(default=PunchFaceSpec())
    """The punch face (:class:`~warptrunc.indent.face.PunchFaceSpec`): tilt and roughness,
    generated or read; default an aligned smooth flat."""

    def __post_init__(self) -> None:
        check_fields(self)
        if not isinstance(self.face, PunchFaceSpec):
            raise ValueError(
                f"face must be a warptrunc.indent.PunchFaceSpec, got {type(self.face).__name__}"
            )
        f = self.peak_loads
        if any(not b > a for a, b in itertools.pairwise(f)):
            raise ValueError(f"peak_loads must be strictly increasing (N), got {list(f)!r}")
        r = self.refine_max
        if r & (r - 1):
            raise ValueError(f"refine_max must be a power of 2 in [1, 1024], got {r!r}")
        if self.detection_load is not None and not self.detection_load < f[0]:
            raise ValueError(
                f"detection_load must be below the first peak load {f[0]!r} N (the surface is "
                f"detected before the first cycle), got {self.detection_load!r} N"
            )

    def to_dict(self) -> dict[str, Any]:
        """The fields (SI; tuples as lists), the face as a dict of its own.

        Returns
        -------
        dict
        """
        return {**super().to_dict(), "face": self.face.to_dict()}


PAPER_PROTOCOL = IndentProtocol(peak_loads=PAPER_PEAK_LOADS, placements=3)
"""The paper's design (§ 4.1) as ``warptrunc reproduce`` runs it: the three punches, the ten
peak loads 0.98–500 mN, three placements per punch, cells judged by their contact pixels
(``refine_max`` 1; a profile refines some punches). :class:`IndentProtocol`'s defaults are a
quicker run of the same experiment (:data:`DEFAULT_PEAK_LOADS`, two placements)."""
