# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""D_vs from vertical sections: the profiles' structure function (Warp kernels)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import warp as wp

from .._support.docs import fill_doc
from ..descriptors import roll_off_wavelength
from ..kernels import fractal as _k
from ..surface import Surface
from ._common import FRACTAL_DOCS, FractalFit, check_sizes, fit_log_log, upload


def default_lags(surface: Surface) -> np.ndarray:
    """Lags of the vertical sections' structure function: 16 log-spaced lags up to an eighth of
    the shorter side.

    Parameters
    ----------
    surface : Surface
        The height map (m).

    Returns
    -------
    ndarray of int64
        Distinct lags τ (pixels) from 1 to max(4, (min(nx, ny) − 1) // 8).
    """
    tmax = max(4, (min(surface.nx, surface.ny) - 1) // 8)
    return np.unique(np.round(np.geomspace(1, tmax, 16)).astype(np.int64))


@fill_doc(FRACTAL_DOCS)
def vertical_sections(
    surface: Surface,
    *,
    lags: Sequence[int] | None = None,
    fit_range: tuple[float, float] | None = None,
    axis: str = "both",
    device: wp.DeviceLike = None,
) -> FractalFit:
    """D_vs from vertical sections: profile dimension + 1, profiles by their structure function.

    Parameters
    ----------
    {surface}
    lags : sequence of int, optional
        Lags τ (pixels). Defaults to 16 logarithmically spaced integers from 1 to
        max(4, (min(nx, ny) − 1) // 8).
    fit_range : (float, float), optional
        Range of lag lengths τ·dx (τ·dy for y profiles) used in the fit (m). Defaults to
        lags up to W_r/4 (W_r from :func:`warptrunc.descriptors.roll_off_wavelength`), where
        the structure function of a surface with a roll-off still follows its power law, and
        at least the four smallest lags.
    axis : {"both", "x", "y"}
        Profiles along x (rows), along y (columns), or both pooled.
    {device}

    Returns
    -------
    FractalFit
        ``scale`` = lag length (m), ``measure`` = V(τ) = ⟨(z(p + τ) − z(p))²⟩ (m²), averaged over
        all pairs of all profiles. With ``axis="both"`` and dx ≠ dy the x and y points are
        concatenated (x first) and fitted together.

    {raises}
        If ``lags`` are not at least 2 distinct integers in [1, min(nx, ny) − 1],
        ``axis`` is unknown, or ``fit_range`` holds fewer than 2 evaluated scales.

    Notes
    -----
    The surface is cut by vertical planes along its rows and columns; each section is a
    self-affine profile with V(τ) ∝ τ^(2H), whose fractal (profile) dimension is
    D_p = 2 − H (the variogram / structure-function method). The surface dimension is
    D_vs = D_p + 1 = 3 − slope/2. Invariant to z + c, to a height scale factor, and (with
    ``axis="both"``) to transposition.

    References
    ----------
    B. B. Mandelbrot, The Fractal Geometry of Nature, Freeman, 1982; T. Gneiting, H. Ševčíková
    and D. B. Percival, Estimators of fractal dimension: assessing the roughness of time series
    and spatial data, Stat. Sci. 27 (2012) 247–277, doi:10.1214/11-STS370.
    """
    zd = upload(surface, device)
    return vs_fit(zd, surface, lags, fit_range, axis)


def vs_fit(zd, surface, lags, fit_range, axis) -> FractalFit:
    if axis not in ("both", "x", "y"):
        raise ValueError(f"axis must be 'both', 'x' or 'y', got {axis!r}")
    taus = check_sizes("lags", lags, surface, default_lags)
    lag_d = wp.array(taus.astype(np.int32), dtype=wp.int32, device=zd.device)
    ny, nx = surface.ny, surface.nx
    parts = []
    # GPU: one thread per column (coalesced); CPU: one per row (contiguous, threads run serially)
    kernel, width = (
        (_k.structure_function_rows_kernel, ny)
        if zd.device.is_cpu
        else (_k.structure_function_kernel, nx)
    )
    for ax in ("x", "y") if axis == "both" else (axis,):
        out = wp.zeros((taus.size, width), dtype=wp.float64, device=zd.device)
        wp.launch(
            kernel,
            dim=(taus.size, width),
            inputs=[zd, lag_d, 1 if ax == "x" else 0],
            outputs=[out],
            device=zd.device,
        )
        sums = out.numpy().sum(axis=1)  # sync point
        pairs = ny * (nx - taus) if ax == "x" else nx * (ny - taus)
        h = surface.dx if ax == "x" else surface.dy
        parts.append((taus * h, sums, pairs.astype(np.float64)))
    if len(parts) == 2 and math.isclose(surface.dx, surface.dy, rel_tol=1e-12):
        scale = parts[0][0]
        v = (parts[0][1] + parts[1][1]) / (parts[0][2] + parts[1][2])
    else:
        scale = np.concatenate([p[0] for p in parts])
        v = np.concatenate([p[1] / p[2] for p in parts])
    if fit_range is None:
        wr, _ = roll_off_wavelength(surface)
        fourth = float(np.sort(scale)[min(3, scale.size - 1)])
        fit_range = (0.0, max(wr / 4.0, fourth))
    return fit_log_log(
        "vs",
        scale,
        v,
        fit_range,
        lambda k: 3.0 - 0.5 * k,
        {"lags": taus.tolist(), "axis": axis, "profile_method": "structure function"},
    )
