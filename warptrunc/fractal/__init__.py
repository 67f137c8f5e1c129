# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Fractal dimension D of a height map by the paper's four methods (Table 1, Table 3, Fig. 10).

=========  ===================  ============================================  ================
method     name in the paper    measure M(r) at scale r                       D from the slope
=========  ===================  ============================================  ================
``"tri"``  triangulation D_tri  triangular-prism area / projected area        D = 2 − slope
``"box"``  box counting D_box   number of cubes of side ε crossed             D = −slope
``"vs"``   vert. sections D_vs  profile structure function ⟨Δz(τ)²⟩           D = 3 − slope/2
``"sp"``   power spectrum D_sp  variance per logarithmic frequency band       D = 3 + slope/2
=========  ===================  ============================================  ================

The slope is the least-squares slope of log₁₀ M against log₁₀ r over the *fit range*, a
subrange of the evaluated *scales*; both are user-settable and are returned in
:class:`FractalFit` with r² of the fit. The per-box and per-pixel passes run in Warp kernels
(``warptrunc.kernels.fractal``); the spectrum runs where the surface lives: CuPy's cuFFT on a
CUDA surface when CuPy is installed, else NumPy (see :mod:`warptrunc.descriptors`).

Triangulation and box counting need heights and lengths in one unit, and the result depends
on how heights compare with lengths. ``height_scaling`` chooses the convention
(:data:`HEIGHT_SCALINGS`): ``"cube"`` (default) maps the height range onto the lateral
extent first, as Gwyddion does, so D is independent of units and amplitude; ``"si"`` uses
metres as measured, so D approaches 3 − H only where the surface is rough at the scale of the
boxes and drifts to 2 on smooth, gently sloped surfaces (a 1 µm-rms map over 1 mm gives
D ≈ 2.0 whatever its H). Every :class:`FractalFit` of these two methods records the convention
in ``options["height_scaling"]``. The calibration loop of Fig. 4 matches D of simulated and
measured surfaces with the *same* method and options.

Invariances (tested in ``tests/test_fractal.py``):

=====================  ======  ======  ======  ======
transformation         tri     box     vs      sp
=====================  ======  ======  ======  ======
z + constant           yes     yes¹    yes     yes
a·z (a > 0)            cube³   cube³   yes     yes
transposition (z.T)    yes     yes     yes²    yes
=====================  ======  ======  ======  ======

¹ cubes are stacked from the lowest point, so a shift changes only float32 rounding;
² with ``axis="both"`` (x and y profiles pooled);
³ yes with ``height_scaling="cube"`` (default), no with ``"si"``.

Layout: shared parts (:class:`FractalFit`, the fit, the height conventions) in
``_common``; the cell methods ``tri``/``box`` in ``boxes``; ``vs`` in ``sections``; ``sp`` in
``spectrum``; :func:`self_affine_surface` in ``synthetic``. Every name is importable from
``warptrunc.fractal``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import warp as wp

from .._support.docs import SHARED_DOCS, fill_doc
from ..surface import Surface
from ._common import (  # noqa: F401
    DEFAULT_HEIGHT_SCALING,
    HEIGHT_SCALINGS,
    METHODS,
    FractalFit,
    check_scaling,
    check_sizes,
    cube_height_factor,
    fit_log_log,
    scaled_upload,
    upload,
)
from .boxes import (
    box_counting,
    box_fit,
    default_box_sizes,  # noqa: F401  (examples/benchmark_fractal.py)
    tri_fit,
    triangular_prism,
)
from .sections import (
    default_lags,  # noqa: F401  (examples/benchmark_fractal.py)
    vertical_sections,
    vs_fit,
)
from .spectrum import power_spectrum
from .synthetic import self_affine_surface

__all__ = [
    "DEFAULT_HEIGHT_SCALING",
    "HEIGHT_SCALINGS",
    "METHODS",
    "FractalFit",
    "box_counting",
    "fractal_dimension",
    "fractal_dimensions",
    "power_spectrum",
    "self_affine_surface",
    "triangular_prism",
    "vertical_sections",
]


# --- all at once ---------------------------------------------------------------------------------

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
