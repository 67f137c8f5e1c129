# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Weierstrass–Mandelbrot (WM) rough surfaces, Eq. (4) of the paper, synthesised with Warp.

Kernels: ``warptrunc.kernels.wm`` (tables, tile GEMM, direct sum) and
``warptrunc.kernels.reduce`` (min/max for the R_t scaling).
"""

from __future__ import annotations

import math
import os
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np
import warp as wp

from ._support.device import as_device, check_memory, resolve_device
from ._support.docs import fill_doc
from ._support.reduce import height_range
from ._support.validate import HEIGHT_LIMIT_M
from .kernels import wm as _k
from .surface import Surface
from .params import numpydoc_fields
from .wm_params import WMSpec, WMTerms, spec_of_call, wm_spec

__all__ = [
    "WMSpec",
    "WMTerms",
    "wm_spec",
    "wm_surface",
    "wm_window",
]

WM_DOCS = {
    "{spec_device}": (
        "spec : WMTerms\n    The WM parameters, from :func:`wm_spec`.\n"
        "device : str or warp.context.Device, optional\n"
        "    Warp device; see :func:`warptrunc.resolve_device`."
    ),
}
"""Parameter text of the WM evaluators, written once (:func:`fill_doc`)."""


def pad_to(v: int, t: int) -> int:
    return -(-v // t) * t


def wm_tables(
    spec: WMTerms, device: wp.DeviceLike = None, *, map_bytes: int | None = None
) -> tuple[wp.array, wp.array, float]:
    """Row table P (ny_pad × K), column table Q (K × nx_pad) and c0: S = c0 + P·Q.

    K = 2·n_terms padded to the GEMM tile depth; rows/columns are padded for the product kernel
    of the device. Built in float64, stored as float32. ``map_bytes`` is the memory the caller
    will hold for heights besides the tables (default: the whole float32 map; the streamed
    path passes one band), checked before allocating.

    Parameters
    ----------
    spec : WMTerms
        The WM parameters and per-term tables.
    device : str or warp.context.Device, optional
        Warp device; a resolved device is used as is, else
        :func:`warptrunc.resolve_device`'s choice.
    map_bytes : int, optional
        Bytes of heights the caller will hold besides the tables (see above).

    Returns
    -------
    p : warp.array2d of float32
        Row table P, (ny_pad, K), on ``device``.
    q : warp.array2d of float32
        Column table Q, (K, nx_pad), on ``device``.
    c0 : float
        The constant Σ_t w_t cos α_t (dimensionless).

    Raises
    ------
    MemoryError
        The tables and ``map_bytes`` would not fit the device's free memory.
    """
    device = as_device(device)
    nx, ny, T = spec.nx, spec.ny, spec.n_terms
    gpu = device.is_cuda
    K = pad_to(2 * T, _k.TILE_K)
    ny_pad = pad_to(ny, _k.TILE_M) if gpu else pad_to(ny, _k.ROWS)
    nx_pad = pad_to(nx, _k.TILE_N) if gpu else pad_to(nx, _k.COLS)
    heights = 4 * nx * ny if map_bytes is None else map_bytes
    check_memory(
        heights + 4 * K * (nx_pad + ny_pad), device, f"a {nx}×{ny} WM surface with {T} terms"
    )
    f64 = lambda a: wp.array(np.ascontiguousarray(a, dtype=np.float64), device=device)  # noqa: E731
    kx, ky, alpha, w = f64(spec.kx), f64(spec.ky), f64(spec.alpha), f64(spec.w)
    p = wp.zeros((ny_pad, K), dtype=wp.float32, device=device)
    q = wp.zeros((K, nx_pad), dtype=wp.float32, device=device)
    launches = [
        (_k.column_table_kernel, (T, nx_pad), [kx, alpha, spec.dx, T, nx], q),
        (_k.row_table_kernel, (ny_pad, T), [ky, w, spec.dy, T, ny], p),
    ]
    run = lambda a: wp.launch(a[0], dim=a[1], inputs=a[2], outputs=[a[3]], device=device)  # noqa: E731
    if gpu:
        for a in launches:
            run(a)
    else:  # one CPU thread each (a Warp CPU launch is single-threaded and releases the GIL)
        wp.load_module(_k, device=device)
        with ThreadPoolExecutor(2) as ex:
            list(ex.map(run, launches))
    return p, q, float(np.sum(spec.w * np.cos(spec.alpha)))


def wm_product(
    p: wp.array, q: wp.array, z: wp.array, *, cpu_threads: int | None = None
) -> tuple[float, float]:
    """z = P·Q on z's device (tile GEMM on CUDA; threaded row bands on the CPU).

    Returns (min z, max z), from one reduction pass after the product (a sync point).

    Parameters
    ----------
    p : warp.array2d of float32
        Row table P from :func:`wm_tables` (or a view of its rows), on z's device.
    q : warp.array2d of float32
        Column table Q from :func:`wm_tables`.
    z : warp.array2d of float32
        Output, (ny, nx), the raw WM sum S − c0 (dimensionless); overwritten.
    cpu_threads : int, optional
        Python threads for the CPU product (default: the number of CPU cores, at most one
        per block of rows); ignored on CUDA.

    Returns
    -------
    tuple of (float, float)
        (min z, max z) (dimensionless), as Python floats.
    """
    device = z.device
    K = p.shape[1]
    if device.is_cuda:
        wp.launch_tiled(
            _k.wm_tile_gemm_kernel,
            dim=(p.shape[0] // _k.TILE_M, q.shape[1] // _k.TILE_N),
            inputs=[p, q],
            outputs=[z],
            block_dim=256,
            device=device,
        )
        return _extremes(z)
    # A Warp CPU launch runs on one thread: launch row bands from Python threads (the ctypes
    # call releases the GIL) so that every core works.
    qv = wp.array(ptr=q.ptr, dtype=_k.vec16, shape=(K, q.shape[1] // _k.COLS), device=device)
    ny, nx = z.shape
    nx_pad = q.shape[1]
    # the kernel stores 16-wide vectors: write straight into z when its rows are whole vectors
    out = z if nx == nx_pad else wp.empty((ny, nx_pad), dtype=wp.float32, device=device)
    outv = wp.array(ptr=out.ptr, dtype=_k.vec16, shape=(ny, nx_pad // _k.COLS), device=device)
    blocks = p.shape[0] // _k.ROWS
    n_threads = max(1, min(cpu_threads or os.cpu_count() or 1, blocks))
    bounds = np.linspace(0, blocks, n_threads + 1).astype(int)

    def band(b0: int, b1: int) -> None:
        if b1 > b0:
            wp.launch(
                _k.wm_rowblock_kernel,
                dim=(b1 - b0, q.shape[1] // _k.COLS),
                inputs=[p, qv, int(b0 * _k.ROWS)],
                outputs=[outv],
                device=device,
            )

    wp.load_module(_k, device=device)  # compile/load once, before the fan-out
    with ThreadPoolExecutor(n_threads) as ex:
        list(ex.map(band, bounds[:-1], bounds[1:]))
    if out is not z:
        wp.launch(_k.crop_kernel, dim=z.shape, inputs=[out], outputs=[z], device=device)
    # extremes by a separate pass: computing them in the register-blocked kernel pushed its
    # accumulators out of registers (measured 2–15× slower)
    return _extremes(z)


def _extremes(z: wp.array) -> tuple[float, float]:
    return height_range(z, z.device)  # sync point; 2-D: by row bands below 2³¹ pixels


def _raw_sum(spec: WMTerms, device, cpu_threads: int | None = None):
    """S − c0 as a (ny, nx) float32 Warp array, c0 (the constant Σ w·cos α), and the min and
    max of S − c0."""
    if spec.method == "direct":
        check_memory(4 * spec.nx * spec.ny, device, f"a {spec.nx}×{spec.ny} WM surface")
        f64 = lambda a: wp.array(np.ascontiguousarray(a, dtype=np.float64), device=device)  # noqa: E731
        z = wp.empty((spec.ny, spec.nx), dtype=wp.float32, device=device)
        wp.launch(
            _k.wm_direct_kernel,
            dim=(spec.ny, spec.nx),
            inputs=[f64(spec.kx), f64(spec.ky), f64(spec.alpha), f64(spec.w), spec.dx, spec.dy],
            outputs=[z],
            device=device,
        )
        return z, float(np.sum(spec.w * np.cos(spec.alpha))), *_extremes(z)
    p, q, c0 = wm_tables(spec, device)
    z = wp.empty((spec.ny, spec.nx), dtype=wp.float32, device=device)
    lo, hi = wm_product(p, q, z, cpu_threads=cpu_threads)
    return z, c0, lo, hi


@fill_doc(WM_DOCS)
def wm_heights(spec: WMTerms, device: wp.DeviceLike = None, *, cpu_threads: int | None = None):
    """Evaluate the unscaled WM sum S (dimensionless) on ``device``; returns a (ny, nx) wp.array.

    S = Σ_t w_t [cos α_t − cos(kx_t·x + ky_t·y + α_t)], so heights are z = scale·S.

    Parameters
    ----------
    {spec_device}
    cpu_threads : int, optional
        Python threads for the CPU product of the ``"tile"`` method (default: the number of
        CPU cores).

    Returns
    -------
    warp.array2d of float32
        (ny, nx) unscaled sum S (dimensionless) on ``device``.

    Raises
    ------
    MemoryError
        The map (and tables) would not fit the device's free memory.
    """
    device = resolve_device(device)
    z, c0, _lo, _hi = _raw_sum(spec, device, cpu_threads)
    wp.launch(_k.affine_kernel, dim=z.shape, inputs=[z, c0, 1.0], device=device)
    return z


@fill_doc(WM_DOCS)
def generate_on_device(spec: WMTerms, device: wp.DeviceLike = None) -> tuple[wp.array, float]:
    """Heights z = scale·S (m) as a (ny, nx) float32 Warp array on ``device``, and the scale.

    With ``spec.Rt`` set, scale = R_t/(max S − min S); otherwise the prefactor of Eq. (4).

    Parameters
    ----------
    {spec_device}

    Returns
    -------
    z : warp.array2d of float32
        (ny, nx) heights (m) on ``device``.
    scale : float
        Metres per unit of the raw sum S (m): R_t/(max S − min S), or
        W_r·(ln γ/M)^(1/2)·(G/W_r)^(D − 3).

    Raises
    ------
    ValueError
        ``spec.Rt`` is set but S is flat on this grid.
    MemoryError
        The map (and tables) would not fit the device's free memory.
    """

    z, scale, _ext = _generate(spec, resolve_device(device))
    return z, scale


def _generate(spec: WMTerms, device) -> tuple[wp.array, float, tuple[float, float]]:
    """:func:`generate_on_device` plus the exact float32 (min z, max z) of the result (m).

    The scaling kernel maps each raw value s to float32((float64(s) + c0)·scale), a monotone
    function for scale > 0; applying the same float64 operations to the raw extremes on the
    host therefore gives the extremes of the scaled map bit for bit, with no second pass.
    """
    z, c0, lo, hi = _raw_sum(spec, device)
    scale = height_scale(spec, lo, hi, device)
    wp.launch(_k.affine_kernel, dim=z.shape, inputs=[z, c0, float(scale)], device=device)
    ext = tuple(float(np.float32((np.float64(v) + c0) * scale)) for v in (lo, hi))
    return z, scale, ext


def reference_grid(spec: WMTerms) -> tuple[int, int] | None:
    """(nx, ny) of the grid over the map's L on which R_t is measured (``spec.Rt_pixel``), or
    None when that is the map's own grid."""
    if spec.Rt is None or getattr(spec, "Rt_pixel", None) is None:
        return None
    ref = (max(2, round(spec.Lx / spec.Rt_pixel)), max(2, round(spec.Ly / spec.Rt_pixel)))
    return None if ref == (spec.nx, spec.ny) else ref


def height_scale(spec: WMTerms, lo: float, hi: float, device: wp.DeviceLike = None) -> float:
    """Factor from the raw WM sum S − c0 to heights (m): R_t/(max − min) when ``spec.Rt`` is
    set (``lo``, ``hi``: the raw sum's extremes on the map; on the grid of ``spec.Rt_pixel``
    over L instead when it is set and differs, evaluated there on ``device``), else the
    prefactor of Eq. (4) times (G/W_r)^(D − 3)."""
    ref = reference_grid(spec)
    if ref is not None:
        nx, ny = ref
        grid = WMTerms(
            **{**spec.__dict__, "nx": nx, "ny": ny, "dx": spec.Lx / nx, "dy": spec.Ly / ny}
        )
        _z, _c0, lo, hi = _raw_sum(grid, resolve_device(device))
        del _z
    if spec.Rt is not None:
        if not hi > lo:
            raise ValueError("the WM sum is flat on this grid; cannot scale to Rt")
        return spec.Rt / (hi - lo)
    try:
        scale = _prefactor(spec) * (spec.G / spec.Wr) ** (spec.D - 3.0)
    except OverflowError:
        scale = math.inf
    if not scale * (hi - lo) <= HEIGHT_LIMIT_M:  # inf or NaN too
        raise ValueError(
            f"G = {spec.G!r} m gives heights of R_t = {scale * (hi - lo):.3g} m, beyond the "
            f"{HEIGHT_LIMIT_M:.3g} m float32 heights hold; use a larger G (heights grow as "
            f"G^(D − 3)) or give Rt"
        )
    return scale


def surface_params(spec: WMTerms, scale: float) -> dict:
    """The surface's ``params``: the spec's, the height ``scale`` (m) and the topothesy G (m)
    that gives this scale without R_t scaling (``G_equivalent``)."""
    params = spec.params()
    params["scale"] = scale
    params["G_equivalent"] = spec.Wr * (scale / _prefactor(spec)) ** (1.0 / (spec.D - 3.0))
    return params


def _prefactor(spec: WMTerms) -> float:
    return spec.Wr * math.sqrt(math.log(spec.gamma) / spec.M)


def wm_surface(
    spec: WMSpec | float | None = None, /, *args: Any, device: wp.DeviceLike = None, **params: Any
) -> Surface:
    """Generate a Weierstrass–Mandelbrot rough surface (paper Eq. 4).

        ``wm_surface(WMSpec(D=2.3, n=2048))``, ``wm_surface(D=2.3, n=2048)`` and, as before
        :class:`WMSpec` existed, ``wm_surface(2.3, 100e-6, n=2048)`` give the same surface.

        Parameters
        ----------
        spec : WMSpec or float, optional
            The parameters (a preset such as ``warptrunc.presets.TABLE1["GB300s"]`` is one); or the
            fractal dimension D, then ``Wr`` may follow positionally. Default: ``WMSpec()``.
        *args
            ``Wr`` (m), when ``spec`` is D.
        device : str, optional
            Warp device; see :func:`warptrunc.resolve_device`.
        **params
            Fields of :class:`WMSpec` (they override those of ``spec``). ``Rt`` scales the heights
            so that max − min = R_t (the paper's procedure, §3.2); set ``Rt=None`` and give ``G``
            for the unscaled formula. ``cutoff="nyquist"`` (default W_c = 2·max(dx, dy)) is the
            shortest wavelength the grid resolves (no term aliases); ``"pixel"`` (max(dx, dy)) is
            the paper's literal "smallest distance between two adjacent pixels", whose finest
            terms alias onto longer wavelengths. The phases α_mn are drawn on the host by
            ``numpy.random.default_rng(seed)`` in (m, n) order, so the same seed gives the same
            surface on every device. ``method="tile"``: separable tables and a Warp tile GEMM
            (fast); ``"direct"``: one thread per pixel summing every term with float64 phases
            (reference). The fields:

    {fields}

        Returns
        -------
        Surface
            Heights (m) and ``params`` holding every generation parameter, ``n_max`` (highest
            frequency index, the largest n with W_r/γ^n ≥ W_c), ``n_terms`` = M·(n_max + 1),
            ``scale`` (m per unit of the raw sum) and ``G_equivalent`` (the topothesy giving that
            scale).

        Raises
        ------
        ValueError
            A parameter out of its range (the message names it, its value and the range).
        TypeError
            More than two positional arguments, or a field given twice.

        Notes
        -----
        z(x, y) = W_r (G/W_r)^{D−3} (ln γ/M)^{1/2} Σ_{m=1}^{M} Σ_{n=0}^{n_max} γ^{(D−3)n}
        [cos α_mn − cos(2π γ^n r cos(θ − πm/M)/W_r + α_mn)], with r cos(θ − πm/M) =
        x cos(πm/M) + y sin(πm/M).

        References
        ----------
        Yan & Komvopoulos (1998), J. Appl. Phys. 84, 3617, doi:10.1063/1.368536.
    """
    terms = spec_of_call(spec, args, params, "wm_surface").terms()
    return surface_from_spec(terms, resolve_device(device))


wm_surface.__doc__ = wm_surface.__doc__.replace("    {fields}", numpydoc_fields(WMSpec, indent=12))


def surface_from_spec(spec: WMTerms, device: wp.context.Device) -> Surface:
    """The device-resident :class:`Surface` of ``spec`` on the resolved ``device``."""
    z, scale, extremes = _generate(spec, device)
    params = surface_params(spec, scale)
    # device-resident, no host copy until one is asked for; the recorded extremes are exact and
    # finite, and every height lies between them, so no validation pass is needed
    return Surface._on_device(z, spec.dx, spec.dy, params, extremes)


def wm_window(
    params: dict[str, Any],
    origin: tuple[int, int],
    shape: tuple[int, int],
    factor: int = 1,
    *,
    device: wp.DeviceLike = None,
) -> np.ndarray:
    """Rows and columns of a WM surface's map generated again, at its pixel or a finer one.

    The same terms as the map (phases, W_r, cut-off W_c, so n_max) and the map's height
    ``scale`` frozen: never scaled again to R_t, so a window at a finer pixel holds the same
    surface as the map, sampled more densely.

    Parameters
    ----------
    params : dict
        The map's ``Surface.params`` from :func:`wm_surface`: its generation parameters, ``Wc``,
        ``n_max`` and ``scale``.
    origin : (int, int)
        (iy0, ix0): the window's first row and column on the refined map of
        (ny·factor, nx·factor) pixels.
    shape : (int, int)
        (wy, wx): the window's rows and columns (refined pixels).
    factor : int
        Pixels dx/factor, dy/factor. Sample (iy, ix) of the refined map lies at
        (ix·dx/factor, iy·dy/factor), as the map's sample (iy, ix) lies at (ix·dx, iy·dy)
        (:func:`wm_surface`), so the refined sample (factor·i, factor·j) is the map's (i, j).
    device : str or warp.context.Device, optional
        Warp device; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    (wy, wx) ndarray of float32
        Heights (m): scale·S, S the raw WM sum of Eq. (4).

    Raises
    ------
    ValueError
        ``params`` not those of a WM map, its terms not reproduced (another n_max), or a
        window, origin or factor out of range.
    """
    if params.get("generator") != "weierstrass-mandelbrot":
        raise ValueError(
            f"params must be a WM surface's, got generator {params.get('generator')!r}"
        )
    f = int(factor)
    if f < 1:
        raise ValueError(f"factor must be an integer >= 1, got {factor!r}")
    wy, wx = (int(v) for v in shape)
    iy0, ix0 = (int(v) for v in origin)
    if wy < 1 or wx < 1 or iy0 < 0 or ix0 < 0:
        raise ValueError(f"window origin {origin!r} and shape {shape!r} must be >= 0 and >= 1")
    spec = WMSpec(
        D=params["D"],
        Wr=params["Wr"],
        L=(params["Lx"], params["Ly"]),
        n=(params["nx"], params["ny"]),
        M=params["M"],
        gamma=params["gamma"],
        Wc=params["Wc"],
        cutoff=params["cutoff"],
        seed=params["seed"],
        Rt=params.get("Rt"),
        G=params.get("G"),
        method=params["method"],
    )
    terms = spec.terms()
    if terms.n_max != params["n_max"]:
        raise ValueError(
            f"params give n_max = {terms.n_max}, the map has {params['n_max']}: not its terms"
        )
    dx, dy = terms.dx / f, terms.dy / f
    # the window's first sample lies at (x0, y0): fold k·x0 into the phases (float64, mod 2π)
    x0, y0 = ix0 * dx, iy0 * dy
    alpha = np.mod(terms.alpha + terms.kx * x0 + terms.ky * y0, 2.0 * math.pi)
    win = WMTerms(**{**terms.__dict__, "nx": wx, "ny": wy, "dx": dx, "dy": dy, "alpha": alpha})
    dev = resolve_device(device)
    z, _c0, _lo, _hi = _raw_sum(win, dev)
    c0 = float(np.sum(terms.w * np.cos(terms.alpha)))  # the map's constant, not the window's
    wp.launch(_k.affine_kernel, dim=z.shape, inputs=[z, c0, float(params["scale"])], device=dev)
    return z.numpy()
