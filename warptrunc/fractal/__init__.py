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

Layout: the method keys, the height conventions and :class:`FractalSettings` (which methods,
which options; no Warp) in ``settings``; :func:`fractal_dimension` and
:func:`fractal_dimensions` in ``dimensions``; shared parts (:class:`FractalFit`, the fit, the
height scaling) in ``_common``; the cell methods ``tri``/``box`` in ``boxes``; ``vs`` in
``sections``; ``sp`` in ``spectrum``; :func:`self_affine_surface` in ``synthetic``. Every
public name is importable from ``warptrunc.fractal`` (imported on first use).
"""

from .._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "DEFAULT_HEIGHT_SCALING": ".settings",
        "HEIGHT_SCALINGS": ".settings",
        "METHODS": ".settings",
        "FractalFit": "._common",
        "FractalSettings": ".settings",
        "box_counting": ".boxes",
        "default_box_sizes": ".boxes",
        "default_lags": ".sections",
        "fractal_dimension": ".dimensions",
        "fractal_dimensions": ".dimensions",
        "height_options": ".settings",
        "power_spectrum": ".spectrum",
        "self_affine_surface": ".synthetic",
        "triangular_prism": ".boxes",
        "vertical_sections": ".sections",
    },
)
