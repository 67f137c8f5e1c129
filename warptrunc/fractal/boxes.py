# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Cell-based methods: D_tri by triangular prisms and D_box by cube counting (Warp kernels)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import warp as wp

from .._support.docs import fill_doc
from ..kernels import fractal as _k
from ..surface import Surface
from ..truncation.curve import surface_range
from ._common import (
    FRACTAL_DOCS,
    FractalFit,
    check_scaling,
    check_sizes,
    fit_log_log,
    row_chunks,
    scaled_upload,
    upload,
)
from .settings import DEFAULT_HEIGHT_SCALING


def default_box_sizes(surface: Surface) -> np.ndarray:
    """Box sides of the triangulation and box counting: powers of two up to an eighth of the
    shorter side.

    Parameters
    ----------
    surface : Surface
        The height map (m).

    Returns
    -------
    ndarray of int64
        Box sides 1, 2, 4, … (pixels), the largest at most max(4, (min(nx, ny) − 1) // 8).
    """
    smax = max(4, (min(surface.nx, surface.ny) - 1) // 8)
    return 2 ** np.arange(int(math.log2(smax)) + 1)


@fill_doc(FRACTAL_DOCS)
def triangular_prism(
    surface: Surface,
    *,
    box_sizes: Sequence[int] | None = None,
    fit_range: tuple[float, float] | None = None,
    height_scaling: str = DEFAULT_HEIGHT_SCALING,
    device: wp.DeviceLike = None,
) -> FractalFit:
    """D_tri by the triangular prism method (Clarke 1986).

    Parameters
    ----------
    {surface}
    box_sizes : sequence of int, optional
        Cell sides s (pixels) to evaluate. Defaults to the powers of two from 1 to
        max(4, (min(nx, ny) − 1) // 8).
    fit_range : (float, float), optional
        Range of cell sides r = s·√(dx·dy) used in the fit (m). Defaults to all evaluated sizes.
    height_scaling : {"cube", "si"}
        ``"cube"`` (default): heights mapped onto the lateral extent first, as Gwyddion does
        (see :data:`HEIGHT_SCALINGS`); ``"si"``: heights in metres as measured.
    {device}

    Returns
    -------
    FractalFit
        ``scale`` = r (m), ``measure`` = A(r)/A_proj, the prism area over the projected area of
        the cells (dimensionless, ≥ 1).

    {raises}
        If ``box_sizes`` are not at least 2 distinct integers in [1, min(nx, ny) − 1],
        ``height_scaling`` is unknown, or ``fit_range`` holds fewer than 2 evaluated scales.

    Notes
    -----
    The map is divided into cells of s × s pixels whose corners are grid points; each cell is
    covered by four triangles joining two neighbouring corners to an apex above the cell centre
    at the mean height of the four corners. With A(r) ∝ r^(2 − D), D = 2 − slope of
    log A(r) against log r. With ``height_scaling="si"`` heights and lengths are in metres,
    so D depends on the height amplitude (see the module docstring); with ``"cube"`` it does
    not. Invariant to z + c and to transposition.

    References
    ----------
    K. C. Clarke, Computation of the fractal dimension of topographic surfaces using the
    triangular prism surface area method, Comput. Geosci. 12 (1986) 713–722,
    doi:10.1016/0098-3004(86)90047-6.
    """
    zd = upload(surface, device)
    return tri_fit(zd, surface, box_sizes, fit_range, height_scaling)


def tri_fit(zd, surface, box_sizes, fit_range, height_scaling=DEFAULT_HEIGHT_SCALING) -> FractalFit:
    sizes = check_sizes("box_sizes", box_sizes, surface, default_box_sizes)
    zd = scaled_upload(zd, surface, check_scaling(height_scaling))
    ratio = np.empty(sizes.size)
    for i, s in enumerate(sizes):
        ncy, ncx = (surface.ny - 1) // s, (surface.nx - 1) // s
        chunk, nch = row_chunks(ncx, int(s))
        out = wp.zeros((ncy, nch), dtype=wp.float64, device=zd.device)
        wp.launch(
            _k.prism_area_kernel,
            dim=(ncy, nch),
            inputs=[zd, int(s), s * surface.dx, s * surface.dy, chunk],
            outputs=[out],
            device=zd.device,
        )
        area = float(out.numpy().sum())  # sync point
        ratio[i] = area / (ncx * s * surface.dx * ncy * s * surface.dy)
    h = math.sqrt(surface.dx * surface.dy)
    return fit_log_log(
        "tri",
        sizes * h,
        ratio,
        fit_range,
        lambda k: 2.0 - k,
        {"box_sizes": sizes.tolist(), "height_scaling": height_scaling},
    )


@fill_doc(FRACTAL_DOCS)
def box_counting(
    surface: Surface,
    *,
    box_sizes: Sequence[int] | None = None,
    fit_range: tuple[float, float] | None = None,
    height_scaling: str = DEFAULT_HEIGHT_SCALING,
    device: wp.DeviceLike = None,
) -> FractalFit:
    """D_box by cube counting.

    Parameters
    ----------
    {surface}
    box_sizes : sequence of int, optional
        Cube sides s (pixels) to evaluate; default as :func:`triangular_prism`.
    fit_range : (float, float), optional
        Range of cube sides ε = s·√(dx·dy) used in the fit (m). Defaults to all.
    height_scaling : {"cube", "si"}
        ``"cube"`` (default): heights mapped onto the lateral extent first, so that the height
        range holds as many cubes as a side holds boxes (Gwyddion's cube counting; see
        :data:`HEIGHT_SCALINGS`); ``"si"``: heights in metres as measured.
    {device}

    Returns
    -------
    FractalFit
        ``scale`` = ε (m), ``measure`` = N(ε), the number of cubes crossed, scaled to the whole
        map when the cells do not tile it exactly (dimensionless).

    {raises}
        If ``box_sizes`` are not at least 2 distinct integers in [1, min(nx, ny) − 1],
        ``height_scaling`` is unknown, or ``fit_range`` holds fewer than 2 evaluated scales.

    Notes
    -----
    Space is tiled by cubes of lateral side s pixels and height ε = s·√(dx·dy), stacked from the
    lowest point of the map. In each cell (the (s + 1)² grid points of :func:`triangular_prism`)
    the surface crosses ⌊(max − z_min)/ε⌋ − ⌊(min − z_min)/ε⌋ + 1 cubes. With N(ε) ∝ ε^−D,
    D = −slope of log N against log ε. Invariant to z + c (up to float32 rounding) and to
    transposition; to a height scale factor only with ``height_scaling="cube"``.

    References
    ----------
    B. B. Mandelbrot, The Fractal Geometry of Nature, Freeman, 1982; N. Sarkar and
    B. B. Chaudhuri, An efficient differential box-counting approach to compute fractal
    dimension of image, IEEE Trans. Syst. Man Cybern. 24 (1994) 115–120, doi:10.1109/21.259692.
    """
    zd = upload(surface, device)
    return box_fit(zd, surface, box_sizes, fit_range, height_scaling)


def box_fit(zd, surface, box_sizes, fit_range, height_scaling=DEFAULT_HEIGHT_SCALING) -> FractalFit:
    sizes = check_sizes("box_sizes", box_sizes, surface, default_box_sizes)
    h = math.sqrt(surface.dx * surface.dy)
    z0 = surface_range(surface, zd.flatten(), zd.device)[0]
    if check_scaling(height_scaling) == "cube":
        zd, z0 = scaled_upload(zd, surface, height_scaling), 0.0
    counts = np.empty(sizes.size)
    for i, s in enumerate(sizes):
        ncy, ncx = (surface.ny - 1) // s, (surface.nx - 1) // s
        chunk, nch = row_chunks(ncx, int(s))
        out = wp.zeros((ncy, nch), dtype=wp.int64, device=zd.device)
        wp.launch(
            _k.box_count_kernel,
            dim=(ncy, nch),
            inputs=[zd, int(s), float(s * h), z0, chunk],
            outputs=[out],
            device=zd.device,
        )
        n = int(out.numpy().sum())  # sync point
        counts[i] = n * ((surface.nx - 1) * (surface.ny - 1)) / (ncx * s * ncy * s)
    return fit_log_log(
        "box",
        sizes * h,
        counts,
        fit_range,
        lambda k: -k,
        {"box_sizes": sizes.tolist(), "height_scaling": height_scaling},
    )
