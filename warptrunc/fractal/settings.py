# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Which fractal methods run and with which options: the method keys, the height conventions
and :class:`FractalSettings` (the options of ``warptrunc describe``; ``calibrate`` takes its
height convention).

Declared once with :func:`warptrunc.params.param`. No Warp here: the command-line parsers import
this module.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..params import Parameters, check_fields, param

__all__ = [
    "DEFAULT_HEIGHT_SCALING",
    "HEIGHT_SCALINGS",
    "HEIGHT_SCALING_DOC",
    "METHODS",
    "FractalSettings",
    "height_options",
]

METHODS = ("tri", "box", "vs", "sp")
"""Method keys, in the order of Table 1."""

HEIGHT_SCALINGS = ("cube", "si")
"""Height conventions of the triangulation and cube-counting methods (``height_scaling=``):

``"cube"``
    Gwyddion's convention: before the prisms or cubes are built, the heights are mapped onto
    the lateral extent — z′ = (z − min z)·(N − 1)·h/(max z − min z), with h = √(dx·dy) and
    N = max(nx, ny) pixels per side — so the map fills a cube and D does not depend on the
    height unit or amplitude (Gwyddion ``libprocess/fractals.c``,
    ``gwy_data_field_fractal_triangulation`` scales height differences by
    2^k/(max − min) on a (2^k + 1)² grid in pixel units, and
    ``gwy_data_field_fractal_cubecounting`` cuts the height range into as many levels as there
    are boxes per side).
``"si"``
    Heights and lengths as measured, in metres: D then depends on the height amplitude
    relative to the pixel size (it drifts to 2 on gently sloped maps).
"""

DEFAULT_HEIGHT_SCALING = "cube"
"""Default of ``height_scaling`` (see the README's evidence table: it recovers 3 − H of
self-affine surfaces far better than ``"si"``)."""

HEIGHT_SCALING_DOC = (
    "height convention of D_tri and D_box: 'cube' maps the height range onto the lateral "
    "extent first (Gwyddion's; independent of units and amplitude), 'si' uses metres as "
    "measured (D drifts to 2 on gently sloped maps)"
)
"""The description of a ``height_scaling`` field (written once)."""


def height_options(method: str, height_scaling: str) -> dict[str, Any]:
    """The options of ``method`` that carry the height convention: ``{"height_scaling": ...}``
    for ``"tri"`` and ``"box"``, none for ``"vs"`` and ``"sp"`` (which do not depend on it).

    Parameters
    ----------
    method : {"tri", "box", "vs", "sp"}
        The fractal method.
    height_scaling : {"cube", "si"}
        The height convention (:data:`HEIGHT_SCALINGS`).

    Returns
    -------
    dict
        Keyword options of the method's function.
    """
    return {"height_scaling": height_scaling} if method in ("tri", "box") else {}


@dataclass(frozen=True)
class FractalSettings(Parameters):
    """The fractal methods to run on a map and their options (Table 1's four D).

    Examples
    --------
    >>> FractalSettings(methods=("vs", "sp"), sp_kind="radial").options()
    {'vs': {'axis': 'both'}, 'sp': {'kind': 'radial'}}
    """

    methods: tuple[str, ...] = param(
        METHODS, "fractal methods to run", choices=METHODS, many=True, sweep=False
    )
    height_scaling: str = param(
        DEFAULT_HEIGHT_SCALING, HEIGHT_SCALING_DOC, choices=HEIGHT_SCALINGS, sweep=False
    )
    sp_kind: str = param(
        "profile",
        "spectrum of the power-spectrum method",
        choices=("profile", "radial"),
        sweep=False,
    )
    vs_axis: str = param(
        "both",
        "profile direction of the vertical-sections method",
        choices=("both", "x", "y"),
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self)

    def options(self) -> dict[str, dict[str, Any]]:
        """The per-method options of :func:`~warptrunc.fractal.fractal_dimensions`, for the
        methods run, in their order.

        Returns
        -------
        dict of str to dict
            ``{"tri": {"height_scaling": ...}, "box": {...}, "vs": {"axis": ...},
            "sp": {"kind": ...}}``, restricted to ``methods``.
        """
        every = {
            "tri": height_options("tri", self.height_scaling),
            "box": height_options("box", self.height_scaling),
            "vs": {"axis": self.vs_axis},
            "sp": {"kind": self.sp_kind},
        }
        return {m: every[m] for m in self.methods}
