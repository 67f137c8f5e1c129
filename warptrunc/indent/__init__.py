# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Flat-punch indentation in silico: the paper's experiment (§ 4.1, Fig. 6) on a height map.

:func:`indent` (``api``) presses finite rigid circular flat punches (``punch``) on a rough
surface at increasing peak loads with partial unloadings (``cycles``), as its
:class:`IndentProtocol` (``protocol``) says, measures the unloading stiffness of the
elastic–plastic contact two ways, and sets the elastic solution and Eq. 2 truncation on the
same punch disks beside it (``truncated``); a tilted or rough punch face (``face``,
:class:`PunchFaceSpec`) makes the punch the experiment's; each cell is refined in the pixel
size (``refine``, ``placement``); the result and its power-law fits E_c/E = β·[F/(E·A)]^α
(``fits``) are an :class:`IndentationResult` (``results``). :class:`IndentMaps` (``maps``) are
the generated maps of ``warptrunc indent``. The figure is :func:`warptrunc.plot.indentation`.

Every public name is importable from ``warptrunc.indent`` (imported on first use), so that the
parameter modules (``protocol``, ``face``, ``maps``) load without Warp.
"""

from .._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "ALUMINIUM_HARDNESS": ".protocol",
        "COLUMNS": ".cycles",
        "DEFAULT_PEAK_LOADS": ".protocol",
        "MAP_SIDE": ".maps",
        "MATERIAL_DEFAULTS": ".protocol",
        "MODELS": ".results",
        "PAPER_PEAK_LOADS": ".protocol",
        "PAPER_PROTOCOL": ".protocol",
        "PAPER_PUNCH_DIAMETERS": ".protocol",
        "IndentMaps": ".maps",
        "IndentProtocol": ".protocol",
        "IndentationResult": ".results",
        "PlacementOverlapWarning": ".punch",
        "PunchFace": ".face",
        "PunchFaceSpec": ".face",
        "PunchWindow": ".punch",
        "default_material": ".protocol",
        "disk_mask": ".punch",
        "disk_truncation": ".truncated",
        "indent": ".api",
        "lens_fraction": ".punch",
        "make_face": ".face",
        "make_solver": ".cycles",
        "modulus_from_stiffness": ".results",
        "place_punches": ".punch",
        "punch_window": ".punch",
        "run_cycles": ".cycles",
        "truncation_at_loads": ".truncated",
    },
)
