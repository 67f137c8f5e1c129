# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Flat-punch indentation in silico: the paper's experiment (§ 4.1, Fig. 6) on a height map.

:func:`indent` (``api``) presses finite rigid circular flat punches (``punch``) on a rough
surface at increasing peak loads with partial unloadings (``protocol``), measures the unloading
stiffness of the elastic–plastic contact two ways, and sets the elastic solution and Eq. 2
truncation on the same punch disks beside it (``truncated``); a tilted or rough punch face
(``face``) makes the punch the experiment's; the result and its power-law fits
E_c/E = β·[F/(E·A)]^α are an :class:`IndentationResult` (``results``). The figure is
:func:`warptrunc.plot.indentation`; the command line ``warptrunc indent``.
"""

from .api import indent
from .face import PunchFace, make_face
from .protocol import (
    ALUMINIUM_HARDNESS,
    PAPER_PEAK_LOADS,
    PAPER_PUNCH_DIAMETERS,
    IndentProtocol,
    default_material,
    make_solver,
    run_cycles,
)
from .punch import (
    PlacementOverlapWarning,
    PunchWindow,
    disk_mask,
    lens_fraction,
    place_punches,
    punch_window,
)
from .results import MODELS, IndentationResult, modulus_from_stiffness
from .truncated import disk_truncation, truncation_at_loads

__all__ = [
    "ALUMINIUM_HARDNESS",
    "MODELS",
    "PAPER_PEAK_LOADS",
    "PAPER_PUNCH_DIAMETERS",
    "IndentProtocol",
    "IndentationResult",
    "PlacementOverlapWarning",
    "PunchFace",
    "PunchWindow",
    "default_material",
    "disk_mask",
    "disk_truncation",
    "indent",
    "lens_fraction",
    "make_face",
    "make_solver",
    "modulus_from_stiffness",
    "place_punches",
    "punch_window",
    "run_cycles",
    "truncation_at_loads",
]
