# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Streamed WM generation + truncation: maps larger than device (or host) memory.

Kernels: ``warptrunc.kernels.wm`` (tables, tile GEMM / register-blocked product, affine) and
``warptrunc.kernels.truncation`` (contact histogram), through the drivers of ``warptrunc.wm``
and ``warptrunc.truncation``.

The WM sum is a matrix product S = c0 + P·Q (``warptrunc.wm``): any row band of the map is
P[r0:r1]·Q, so the map never needs to exist as a whole. Two passes over the row bands:

1. generate each band's raw sum S − c0 and reduce it to its min and max (nothing kept);
2. from the global extremes, fix the scale (R_t/(max S − min S), or Eq. 4's prefactor with G),
   the top height z_top and the thresholds z_top − ω_k; then regenerate each band (same tables,
   same kernels, bands starting at multiples of the product's row block, so the heights are
   bit-identical to the in-memory map), scale it and add its contact histogram to one int64
   histogram.

Device memory: the two tables (≈ 2·K·n·4 bytes, K = 2·n_terms padded) and one band. The result
is the :class:`~warptrunc.truncation.TruncationCurve` that ``truncate(wm_surface(...))`` gives,
count for count. Reached through :func:`warptrunc.truncate` (``stream=``).

Islands of a streamed surface (counts and areas, labels per band, border rows merged by
union-find): ``warptrunc.islands.streamed``.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import warp as wp

from .._support.device import as_device, free_memory_bytes, resolve_device
from .._support.docs import fill_doc
from .._support.limits import band_pixel_limit, row_bands
from .._support.outputs import jsonable
from .._support.progress import progress_bar
from .._support.validate import check_int
from ..kernels import wm as _kwm
from ..params import param_info
from ..surface import Surface
from ..wm import WMSpec, WMTerms, height_scale, pad_to, surface_params, wm_product, wm_tables
from .curve import (
    DEEP_FRACTION,
    TruncationCurve,
    depth_grid,
    depth_thresholds,
    histogram_bands,
)
from .settings import TRUNCATION_DOCS

__all__ = [
    "STREAM_GIVEN",
    "TOO_BIG",
    "StreamedTruncation",
    "fits_in_memory",
    "in_memory_bytes",
    "stream_reason",
]

TOO_BIG = "the map needs more than half of the free memory"
"""Why a WM surface is streamed when streaming was not asked for (``stream="auto"``)."""
STREAM_GIVEN = "--stream given"
"""Why a WM surface is streamed when ``stream=True`` (``warptrunc analyze --stream``)."""

_DEFAULT_BAND_PIXELS = 2**28  # 1 GiB of float32 per band: a progress step every few ms on a GPU


@dataclass(frozen=True, eq=False)
class StreamedTruncation:
    """A streamed truncation analysis: the curve, the surface it describes, how it was run."""

    curve: TruncationCurve
    """The truncation curve, as ``truncate(wm_surface(...))`` would give it."""
    surface: dict[str, Any] = field(default_factory=dict)
    """Scalar metadata of the (never assembled) surface, as ``Surface.to_dict()``: grid (m),
    ``Rt_m`` (m), generation parameters, ``scale`` (m) and ``G_equivalent`` (m)."""
    band_rows: int = 0
    """Rows per band (the last band may be shorter)."""
    n_bands: int = 0
    """Number of row bands in each pass."""

    def to_dict(self) -> dict[str, Any]:
        """The curve's columns (one row per depth).

        Returns
        -------
        dict of str to (n+1,) ndarray
            :meth:`TruncationCurve.to_dict` of :attr:`curve`: ``depth_m`` (m),
            ``depth_fraction_of_Rt``, ``n_contact_pixels``, ``contact_area_m2`` (m²) and
            ``area_fraction``.
        """
        return self.curve.to_dict()


def as_wm_spec(spec_or_params) -> WMTerms:
    """A :class:`WMTerms`, from a :class:`WMSpec`, its terms, a mapping of ``wm_spec`` keywords,
    or the ``params`` of a WM surface (``nx, ny, Lx, Ly`` are mapped to ``n`` and ``L``)."""
    if isinstance(spec_or_params, WMTerms):
        return spec_or_params
    if isinstance(spec_or_params, WMSpec):
        return spec_or_params.terms()
    if not isinstance(spec_or_params, Mapping):
        raise TypeError(
            "spec_or_params must be a WMSpec or a mapping of wm_spec parameters, got "
            f"{type(spec_or_params).__name__}"
        )
    kw = dict(spec_or_params)
    if "nx" in kw or "ny" in kw:
        kw["n"] = (kw.pop("nx"), kw.pop("ny"))
    if "Lx" in kw or "Ly" in kw:
        kw["L"] = (kw.pop("Lx"), kw.pop("Ly"))
    return WMSpec(**{k: kw[k] for k in param_info(WMSpec) if k in kw}).terms()


def in_memory_bytes(spec_or_params, device: wp.DeviceLike = None) -> tuple[int, int]:
    """(device bytes, host bytes) that ``truncate(wm_surface(...))`` needs at peak.

    Device: the float32 map, the tables and, on the CPU, the padded product buffer. Host: the
    ``Surface`` copy and its validation temporaries (a boolean mask); on the CPU device the two
    add up in the same memory.

    Parameters
    ----------
    spec_or_params : WMTerms or mapping
        The WM surface: a :class:`~warptrunc.wm.WMTerms`, a mapping of :func:`~warptrunc.wm.wm_spec`
        keywords, or the ``params`` of a WM surface (``nx``, ``ny``, ``Lx``, ``Ly`` become
        ``n`` and ``L``).
    device : str or warp.context.Device, optional
        Warp device the map would be made on; :func:`warptrunc.resolve_device`'s choice when
        None.

    Returns
    -------
    device_bytes, host_bytes : int
        Peak bytes on the device and on the host.

    Raises
    ------
    TypeError
        ``spec_or_params`` is neither a WMTerms nor a mapping.
    ValueError
        Invalid WM parameters (from :func:`~warptrunc.wm.wm_spec`).
    """
    spec = as_wm_spec(spec_or_params)
    device = as_device(device)
    n = spec.nx * spec.ny
    K = pad_to(2 * spec.n_terms, _kwm.TILE_K)
    tables = 4 * K * (spec.nx + spec.ny + 256)
    dev = 4 * n + tables
    host = 4 * n + n  # the Surface copy + np.isfinite mask
    if not device.is_cuda:
        dev += 4 * n if spec.nx % _kwm.COLS else 0
    return dev, host


def fits(spec: WMTerms, device: wp.context.Device) -> bool:
    """Whether the in-memory path fits ``device`` (resolved); see :func:`fits_in_memory`.

    Parameters
    ----------
    spec : WMTerms
        The WM surface.
    device : warp.context.Device
        The resolved Warp device.

    Returns
    -------
    bool
        On a CUDA device: device bytes ≤ half its free memory and host bytes ≤ half the
        host's free memory (:func:`in_memory_bytes`); on the CPU: their sum ≤ half the
        host's free memory.
    """
    # at most half of the free memory: the rest stays for the pool's slack, the plots, the
    # islands; past that, streaming (two passes of the product, no host copy) is faster anyway
    dev, host = in_memory_bytes(spec, device)
    if device.is_cuda:
        host_free = free_memory_bytes(wp.get_device("cpu"))
        return dev <= 0.5 * free_memory_bytes(device) and host <= 0.5 * host_free
    return dev + host <= 0.5 * free_memory_bytes(device)


class WMBands:
    """Tables on the device and a reusable band buffer: ``raw(r0, r1)`` = S − c0 on those rows."""

    def __init__(self, spec: WMTerms, device, band_rows: int | None):
        if spec.method != "tile":
            raise ValueError(
                f"streamed generation needs method='tile' (row bands of the table product), "
                f"got method={spec.method!r}"
            )
        self.spec, self.device = spec, device
        align = int(_kwm.TILE_M) if device.is_cuda else int(_kwm.ROWS)
        if band_rows is None:
            budget = min(band_pixel_limit(), _DEFAULT_BAND_PIXELS, free_memory_bytes(device) // 16)
            band_rows = max(1, budget // spec.nx)
        else:
            band_rows = check_int("band_rows", band_rows, 1, spec.ny)
        # bands start at multiples of the product's row block, so that each band's products are
        # those of the in-memory map; rows beyond the flat-launch limit are not allowed
        rows = max(align, -(-band_rows // align) * align)
        while rows > align and rows * spec.nx > band_pixel_limit():
            rows -= align
        self.bands = row_bands(spec.ny, spec.nx, rows=rows, align=align)
        self.rows, self.align = rows, align
        band_bytes = 4 * rows * (spec.nx + _kwm.COLS)
        self.p, self.q, self.c0 = wm_tables(spec, device, map_bytes=band_bytes)
        self.buffer = wp.empty((min(rows, spec.ny), spec.nx), dtype=wp.float32, device=device)

    def raw(self, r0: int, r1: int) -> tuple[wp.array, float, float]:
        rows = r1 - r0
        p = self.p[r0 : r0 + pad_to(rows, self.align)]  # a view: the same rows of the same table
        z = self.buffer[:rows]
        lo, hi = wm_product(p, self.q, z)  # sync point
        return z, lo, hi


def extremes_pass(bands: WMBands, progress: bool) -> tuple[float, float, float, float, float]:
    """Global extremes of S − c0, then the scale and the extremes of the scaled heights (m)."""
    spec = bands.spec
    lo, hi = math.inf, -math.inf
    with progress_bar(
        total=len(bands.bands), desc="stream pass 1/2 (extremes)", unit="band", enabled=progress
    ) as bar:
        for r0, r1 in bands.bands:
            _z, blo, bhi = bands.raw(r0, r1)
            lo, hi = min(lo, blo), max(hi, bhi)
            bar.update()
    scale = height_scale(spec, lo, hi, bands.device)
    # the scaled extremes by the same kernel as the heights (the affine map is monotone, so
    # they are the scaled map's min and max bit for bit)
    ext = wp.array(np.array([[lo, hi]], dtype=np.float32), device=bands.device)
    wp.launch(
        _kwm.affine_kernel, dim=ext.shape, inputs=[ext, bands.c0, float(scale)], device=bands.device
    )
    zlo, zhi = (float(v) for v in ext.numpy()[0])  # sync point
    return lo, hi, float(scale), zlo, zhi


def wm_bands(
    spec_or_params, *, band_rows: int | None = None, device: wp.DeviceLike = None
) -> Iterator[tuple[int, int, np.ndarray]]:
    """Yield ``(r0, r1, heights)``: the WM surface's rows r0..r1 (m, float32 host array), band
    by band, equal bit for bit to ``wm_surface(...).heights[r0:r1]`` (a first pass over all
    bands finds the extremes for the R_t scaling). For checks and for writing large maps.

    Parameters
    ----------
    spec_or_params : WMTerms or mapping
        The WM surface, as for :func:`in_memory_bytes`; its ``method`` must be ``"tile"``.
    band_rows : int, optional
        Rows per band, in [1, ny], rounded up to the product's row block; default: a band
        of at most 2²⁸ pixels that fits a sixteenth of the free device memory.
    device : str or warp.context.Device, optional
        Warp device that generates the bands; :func:`warptrunc.resolve_device`'s choice
        when None.

    Yields
    ------
    r0, r1 : int
        First row and one past the last row of the band.
    heights : (r1 − r0, nx) float32 ndarray
        The band's heights z (m), a fresh host copy.

    Raises
    ------
    TypeError
        ``spec_or_params`` is neither a WMTerms nor a mapping.
    ValueError
        Invalid WM parameters, a ``method`` other than ``"tile"``, or ``band_rows`` out of
        range (raised when the first band is requested).
    """
    spec = as_wm_spec(spec_or_params)
    device = resolve_device(device)
    bands = WMBands(spec, device, band_rows)
    _lo, _hi, scale, _zlo, _zhi = extremes_pass(bands, False)
    for r0, r1 in bands.bands:
        z, _, _ = bands.raw(r0, r1)
        wp.launch(_kwm.affine_kernel, dim=z.shape, inputs=[z, bands.c0, scale], device=device)
        # sync point; copy: on the CPU, numpy() is a view of the reused buffer
        yield r0, r1, z.numpy().copy()


@fill_doc(TRUNCATION_DOCS)
def banded_truncation(
    spec: WMTerms,
    n_increments: int,
    *,
    max_depth: float | None,
    max_depth_fraction: float,
    band_rows: int | None,
    device: wp.context.Device,
    progress: bool,
) -> StreamedTruncation:
    """The streamed path of :func:`warptrunc.truncate` on a resolved ``device``: the curve of
    a WM surface generated band by band, with the surface's metadata and the band layout (the
    CLI reports them).

    Two passes over the bands: the first finds the extremes of the unscaled sum (for the R_t
    scaling), the second scales each band and adds its histogram of contact indices. The
    counts are those of ``truncate(wm_surface(...))``.

    Parameters
    ----------
    spec : WMTerms
        The WM surface; ``method`` must be ``"tile"``.
    {depth_range}
    band_rows : int or None
        Rows per band, as for :func:`wm_bands`.
    device : warp.context.Device
        The resolved Warp device.
    progress : bool
        Show a progress bar per pass.

    Returns
    -------
    StreamedTruncation
        The curve A_c(ω_k), the surface's scalar metadata, rows per band and band count.

    Raises
    ------
    ValueError
        A ``method`` other than ``"tile"``, ``band_rows`` or the depth parameters out of range.
    """
    bands = WMBands(spec, device, band_rows)
    _lo, _hi, scale, zlo, zhi = extremes_pass(bands, progress)
    Rt = float(np.float64(zhi) - np.float64(zlo))
    depth = depth_grid(Rt, n_increments, max_depth=max_depth, max_depth_fraction=max_depth_fraction)
    t, _, _, thr, inv_step = depth_thresholds(None, depth, device, (zlo, zhi))
    hist = np.zeros(depth.size, dtype=np.int64)
    deep = depth[-1] > DEEP_FRACTION * Rt  # picks the GPU histogram kernel, as truncate() does
    with progress_bar(
        total=len(bands.bands), desc="stream pass 2/2 (histogram)", unit="band", enabled=progress
    ) as bar:
        # last band first: pass 1 left its raw sum in the buffer (one band fewer to generate;
        # integer counts do not depend on the order)
        for i, (r0, r1) in enumerate(reversed(bands.bands)):
            z = bands.buffer[: r1 - r0] if i == 0 else bands.raw(r0, r1)[0]
            wp.launch(_kwm.affine_kernel, dim=z.shape, inputs=[z, bands.c0, scale], device=device)
            hist += histogram_bands(z, t, zhi, inv_step, device, deep=deep)
            bar.update()
    counts = np.cumsum(hist).astype(np.int64)
    lx, ly = spec.nx * spec.dx, spec.ny * spec.dy  # as Surface.lx, Surface.ly
    pixel_area = spec.dx * spec.dy
    curve = TruncationCurve(
        depth=depth,
        threshold=thr,
        n_contact_pixels=counts,
        contact_area=counts * pixel_area,
        apparent_area=lx * ly,
        pixel_area=pixel_area,
        n_pixels=spec.nx * spec.ny,
        z_top=zhi,
        Rt=Rt,
    )
    params = surface_params(spec, scale)
    meta = {
        "nx": spec.nx,
        "ny": spec.ny,
        "dx_m": spec.dx,
        "dy_m": spec.dy,
        "lx_m": lx,
        "ly_m": ly,
        "Rt_m": Rt,
        **{k: jsonable(v, nonfinite="text") for k, v in params.items()},
    }
    return StreamedTruncation(curve, meta, bands.rows, len(bands.bands))


def stream_reason(
    source, stream: bool | str, device: wp.DeviceLike = None
) -> tuple[WMTerms | None, str | None]:
    """Whether a surface is truncated in memory or by row bands: the one decision of
    :func:`warptrunc.truncate` and :func:`warptrunc.analyze`.

    Parameters
    ----------
    source : Surface, WMSpec, WMTerms or mapping
        A height map in memory, or a WM surface to generate (as ``as_wm_spec`` takes it).
    stream : {"auto", True, False}
        Generate a WM surface by row bands (True), whole (False), or by bands only when the map
        needs more than half of the free device or host memory ("auto", ``fits``).
    device : str or warp.context.Device, optional
        Warp device the map would be made on; :func:`warptrunc.resolve_device`'s choice when
        None.

    Returns
    -------
    spec : WMTerms or None
        The WM surface's terms; None for a :class:`~warptrunc.Surface`.
    reason : str or None
        Why it is streamed (:data:`STREAM_GIVEN`, :data:`TOO_BIG`); None for the in-memory path.

    Raises
    ------
    ValueError
        ``stream`` is not one of the three, or ``stream=True`` with a Surface.
    """
    if stream not in ("auto", True, False):
        raise ValueError(f"stream must be 'auto', True or False, got {stream!r}")
    if isinstance(source, Surface):
        if stream is True:
            raise ValueError(
                "stream=True applies to generated surfaces (a WM spec or its params), not to a "
                "Surface"
            )
        return None, None
    spec = as_wm_spec(source)
    if stream is True:
        return spec, STREAM_GIVEN
    if stream == "auto" and not fits(spec, resolve_device(device)):
        return spec, TOO_BIG
    return spec, None


def fits_in_memory(spec_or_params, device: wp.DeviceLike = None) -> bool:
    """Whether ``truncate(wm_surface(...))`` needs at most half of the free memory of ``device``
    and of the host (which holds the ``Surface`` copy); see :func:`in_memory_bytes`.

    Parameters
    ----------
    spec_or_params : WMTerms or mapping
        The WM surface, as for :func:`in_memory_bytes`.
    device : str or warp.context.Device, optional
        Warp device; :func:`warptrunc.resolve_device`'s choice when None.

    Returns
    -------
    bool
        True when the in-memory path fits; when False, ``truncate(spec, stream="auto")``
        streams.


    Raises
    ------
    TypeError
        ``spec_or_params`` is neither a WMTerms nor a mapping.
    ValueError
        Invalid WM parameters.
    """

    return fits(as_wm_spec(spec_or_params), resolve_device(device))
