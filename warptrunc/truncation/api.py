# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
""":func:`truncate`, the one entry point of the truncation analysis: a :class:`Surface` in
memory (``curve``), or a WM surface given by its parameters, generated whole or by row bands
(``stream``) when it does not fit the device."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Literal

import warp as wp

from .._support.device import resolve_device
from .._support.docs import fill_doc
from ..surface import Surface
from ..wm import WMTerms, surface_from_spec
from .curve import TruncationCurve, surface_device, truncate_surface
from .settings import TRUNCATION_DOCS
from .stream import banded_truncation, stream_reason

__all__ = ["truncate"]


@fill_doc(TRUNCATION_DOCS)
def truncate(
    surface: Surface | WMTerms | Mapping,
    n_increments: int = 200,
    *,
    max_depth: float | None = None,
    max_depth_fraction: float = 0.1,
    stream: bool | Literal["auto"] = "auto",
    band_rows: int | None = None,
    progress: bool = False,
    device: wp.DeviceLike = None,
) -> TruncationCurve:
    """Truncated area A_c(ω) of a surface at n + 1 equally spaced depths.

    Parameters
    ----------
    surface : Surface, WMTerms or mapping
        The height map (m), or a WM surface to generate: a :func:`warptrunc.wm.wm_spec`, a
        mapping of its keywords (``D``, ``Wr`` (m), ``L`` (m), ``n``, ``Rt`` (m), ``G`` (m),
        ``M``, ``gamma``, ``Wc`` (m), ``cutoff``, ``seed``), or the ``params`` of a surface
        from :func:`warptrunc.wm_surface`.
    {n_increments}
    {max_depth}
    {max_depth_fraction}
        0.1 by default: the stiffness fit reads the first contact, where the truncation model
        holds (paper §3).
    stream : {"auto", True, False}
        For a WM surface: generate it by row bands and never hold it whole (True), generate it
        whole (False), or stream only when the map needs more than half of the free device or
        host memory ("auto"). A :class:`Surface` is always in memory (True raises).
    band_rows : int, optional
        Rows per band when streaming, rounded up to the product's row block (128 on CUDA, 8 on
        the CPU). Default: about 2²⁸ pixels per band, less where free memory is short.
    progress : bool
        Show a progress bar over the bands of each streamed pass.
    {device}

    Returns
    -------
    TruncationCurve
        The same counts, pixel for pixel, whichever path ran.

    Notes
    -----
    The depths are ω_k = k·ω_max/n, k = 0..n. In memory: one pass over the heights; each
    pixel's contact index (the first k with z ≥ z_top − ω_k) is found in a Warp kernel and
    counted in an integer atomic histogram; the cumulative sum gives the number of contact
    pixels at every depth. Streamed: two passes
    (extremes, then histogram) regenerate the same bands with the same tables and kernels, so
    the scaled heights are bit-identical to the in-memory map; device memory holds the tables
    and one band.
    """
    spec, streamed = stream_reason(surface, stream, device)
    opts = {"max_depth": max_depth, "max_depth_fraction": max_depth_fraction}
    if spec is None:
        device = resolve_device(surface_device(surface, device))
        return truncate_surface(surface, n_increments, **opts, device=device)
    device = resolve_device(device)
    if streamed:
        return banded_truncation(
            spec, n_increments, **opts, band_rows=band_rows, device=device, progress=progress
        ).curve
    return truncate_surface(surface_from_spec(spec, device), n_increments, **opts, device=device)
