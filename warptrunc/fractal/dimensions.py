# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""D by one of the four methods (:func:`fractal_dimension`) or by several on one upload of the
map (:func:`fractal_dimensions`): the dispatch over the methods of ``boxes``, ``sections`` and
``spectrum``."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import warp as wp

from .._support.docs import SHARED_DOCS, fill_doc
from ..surface import Surface
from ._common import FractalFit, upload
from .boxes import box_counting, box_fit, tri_fit, triangular_prism
from .sections import vertical_sections, vs_fit
from .settings import DEFAULT_HEIGHT_SCALING, METHODS
from .spectrum import power_spectrum

__all__ = ["fractal_dimension", "fractal_dimensions"]

_OPTION_NAMES = {
    "tri": {"box_sizes", "fit_range", "height_scaling"},
    "box": {"box_sizes", "fit_range", "height_scaling"},
    "vs": {"lags", "fit_range", "axis"},
    "sp": {"kind", "bins_per_decade", "fit_range", "window"},
}


def fractal_dimension(
    surface: Surface, method: str = "tri", *, device: wp.DeviceLike = None, **options: Any
) -> FractalFit:
    """D by one method: ``"tri"``, ``"box"``, ``"vs"`` or ``"sp"``.

    Parameters
    ----------
    surface : Surface
        Height map (m).
    method : {"tri", "box", "vs", "sp"}
        Estimator (see the module docstring).
    device : str, optional
        Warp device (``"sp"`` ignores it and runs where the surface lives, see
        :mod:`warptrunc.descriptors`).
    **options
        Keyword options of the method's function (:func:`triangular_prism`,
        :func:`box_counting`, :func:`vertical_sections`, :func:`power_spectrum`).

    Returns
    -------
    FractalFit
        The fit of the chosen method.

    Raises
    ------
    ValueError
        If ``method`` is unknown, an option does not belong to it, or the method rejects its
        input (see its function).

    Examples
    --------
    >>> fractal_dimension(surface, "box", box_sizes=[1, 2, 4, 8, 16]).D
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    bad = set(options) - _OPTION_NAMES[method]
    if bad:
        raise ValueError(
            f"unknown option(s) {sorted(bad)} for method {method!r}; allowed: "
            f"{sorted(_OPTION_NAMES[method])}"
        )
    if method == "tri":
        return triangular_prism(surface, device=device, **options)
    if method == "box":
        return box_counting(surface, device=device, **options)
    if method == "vs":
        return vertical_sections(surface, device=device, **options)
    return power_spectrum(surface, **options)


@fill_doc(SHARED_DOCS)
def fractal_dimensions(
    surface: Surface,
    methods: Sequence[str] = METHODS,
    *,
    options: dict[str, dict[str, Any]] | None = None,
    device: wp.DeviceLike = None,
) -> dict[str, FractalFit]:
    """D by several methods, uploading the map once.

    Parameters
    ----------
    surface : Surface
        Height map (m).
    methods : sequence of str
        Subset of ``("tri", "box", "vs", "sp")``.
    options : dict, optional
        Per-method keyword options, e.g. ``{"vs": {"axis": "x"}, "sp": {"kind": "profile"}}``.
    {warp_device}

    Returns
    -------
    dict
        ``{method: FractalFit}`` in the order of ``methods``.

    Raises
    ------
    ValueError
        If a method in ``methods`` or ``options`` is unknown, an option does not belong to its
        method, or a method rejects its input (see its function).
    """
    options = dict(options or {})
    for m in list(methods) + list(options):
        if m not in METHODS:
            raise ValueError(f"method must be one of {METHODS}, got {m!r}")
    for m, o in options.items():
        bad = set(o) - _OPTION_NAMES[m]
        if bad:
            raise ValueError(f"unknown option(s) {sorted(bad)} for method {m!r}")
    zd = upload(surface, device) if set(methods) - {"sp"} else None
    out: dict[str, FractalFit] = {}
    for m in methods:
        o = options.get(m, {})
        hs = o.get("height_scaling", DEFAULT_HEIGHT_SCALING)
        if m == "tri":
            out[m] = tri_fit(zd, surface, o.get("box_sizes"), o.get("fit_range"), hs)
        elif m == "box":
            out[m] = box_fit(zd, surface, o.get("box_sizes"), o.get("fit_range"), hs)
        elif m == "vs":
            out[m] = vs_fit(zd, surface, o.get("lags"), o.get("fit_range"), o.get("axis", "both"))
        else:
            out[m] = power_spectrum(surface, **o)
    return out
