# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Weierstrass–Mandelbrot (WM) parameters: validation and the per-term tables (host).

Re-exported by ``warptrunc.wm``, which synthesises the surfaces.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ._support.validate import HEIGHT_LIMIT_M, check_range
from .params import Parameters, check_fields, numpydoc_fields, param, to_dict

__all__ = ["WMSpec", "WMTerms", "wm_spec"]


class WMTerms:
    """Validated WM parameters and the per-term tables (host, float64).

    Attributes are SI: ``Lx, Ly, dx, dy, Wr, Wc`` (m), ``G`` (m or None), ``Rt`` (m or None);
    ``kx, ky`` (rad/m), ``alpha`` (rad), ``w`` (dimensionless) have one entry per term
    t = (m − 1)·(n_max + 1) + n, m = 1..M, n = 0..n_max.

    Made by :func:`wm_spec`, which validates the values; the constructor itself checks
    nothing.

    Parameters
    ----------
    **kw
        The attributes, stored as given: ``D``, ``Wr``, ``Lx``, ``Ly``, ``nx``, ``ny``,
        ``dx``, ``dy``, ``M``, ``gamma``, ``Wc``, ``cutoff``, ``n_max``, ``n_terms``,
        ``seed``, ``G``, ``Rt``, ``method`` and the (n_terms,) float64 tables ``kx``, ``ky``,
        ``alpha``, ``w``.
    """

    def __init__(self, **kw):
        self.__dict__.update(kw)

    def params(self) -> dict:
        """JSON-serialisable generation parameters (SI units).

        Returns
        -------
        dict
            ``generator="weierstrass-mandelbrot"`` and ``D``, ``Wr``, ``Lx``, ``Ly`` (m),
            ``nx``, ``ny``, ``M``, ``gamma``, ``Wc`` (m), ``cutoff``, ``n_max``, ``n_terms``,
            ``seed``, ``G`` (m or None), ``Rt`` (m or None), ``Rt_pixel`` (m or None),
            ``method``.
        """
        keys = (
            "D Wr Lx Ly nx ny M gamma Wc cutoff n_max n_terms seed G Rt Rt_pixel method"
        ).split()
        return {"generator": "weierstrass-mandelbrot", **{k: getattr(self, k) for k in keys}}


def wm_spec(spec: WMSpec | float | None = None, /, *args: Any, **params: Any) -> WMTerms:
    """Validate the WM parameters and draw the phases on the host (see :func:`wm_surface`).

        Parameters
        ----------
        spec : WMSpec or float, optional
            The parameters; or, as before :class:`WMSpec` existed, the fractal dimension D
            (then ``Wr`` may follow as the second positional argument).
        *args
            ``Wr`` (m), when ``spec`` is D.
        **params
            Fields of :class:`WMSpec` (they override those of ``spec``):

    {fields}

        Returns
        -------
        WMTerms
            The validated parameters, dx, dy (m), n_max (the largest n with W_r/γ^n ≥ W_c),
            n_terms = M·(n_max + 1), and per term the wavevector components kx, ky (rad/m), the
            phase α (rad) and the weight w = γ^((D − 3)n) (dimensionless).

        Raises
        ------
        ValueError
            A parameter out of range, an unknown ``cutoff`` or ``method``, a default W_c not
            below W_r, or both or neither of ``Rt`` and ``G``.

        Notes
        -----
        The terms are those of the paper's Eq. (4), with the spatial frequency of term (m, n)
        k = 2πγⁿ/W_r along the direction θ = πm/M.
    """
    return spec_of_call(spec, args, params, "wm_spec").terms()


def spec_of_call(spec: Any, args: tuple, params: dict, where: str) -> WMSpec:
    """The :class:`WMSpec` of a call ``f(spec=None, /, *args, **params)``.

    ``spec`` is a :class:`WMSpec` (``params`` override its fields), None (``params`` alone),
    or, as the signature of ``wm_surface``/``wm_spec`` was before, D followed by ``Wr``.

    Parameters
    ----------
    spec : WMSpec, float or None
        The first positional argument.
    args : tuple
        The further positional arguments (at most ``Wr``, after D).
    params : dict
        The keyword arguments: fields of :class:`WMSpec`.
    where : str
        The function's name, for the messages.

    Returns
    -------
    WMSpec
        Validated.

    Raises
    ------
    TypeError
        Positional arguments beyond (D, Wr), or a field given twice.
    """
    if isinstance(spec, WMSpec):
        if args:
            raise TypeError(f"{where}: give the fields of a WMSpec as keywords, not positionally")
        return spec.replace(**params) if params else spec
    pos = () if spec is None and not args else (spec, *args)
    if len(pos) > 2:
        raise TypeError(f"{where} takes at most 2 positional arguments (D, Wr), got {len(pos)}")
    for k, v in zip(("D", "Wr"), pos):
        if k in params:
            raise TypeError(f"{where} got multiple values for argument {k!r}")
        params[k] = v
    return WMSpec(**params)


def _terms(s: WMSpec) -> WMTerms:
    """The per-term tables of ``s``, with the checks that need several fields."""
    D, Wr, M, gamma, cutoff, Wc = s.D, s.Wr, s.M, s.gamma, s.cutoff, s.Wc
    Lx, Ly = s.L if isinstance(s.L, tuple) else (s.L, s.L)
    nx, ny = s.n if isinstance(s.n, tuple) else (s.n, s.n)
    dx, dy = Lx / nx, Ly / ny
    if Wc is None:
        Wc = (2.0 if cutoff == "nyquist" else 1.0) * max(dx, dy)
        if Wc >= Wr:
            raise ValueError(
                f"the default cut-off W_c = {Wc:g} m ({cutoff}) is not below Wr = {Wr:g} m: "
                "use more pixels, a larger Wr, or give Wc"
            )
    Wc = check_range("Wc", Wc, 0.0, Wr, unit=f"m (must be below Wr = {Wr:g} m)")
    if s.Rt is not None and s.G is not None:
        raise ValueError("give either Rt (rescale to a peak-to-valley height) or G, not both")
    if s.Rt is None and s.G is None:
        raise ValueError("give Rt (m) or G (m) to set the vertical scale")
    # n_max: the largest n with wavelength Wr/γ^n ≥ Wc (1e-9 guards exact powers)
    n_max = math.floor(math.log(Wr / Wc) / math.log(gamma) + 1e-9)
    n_f = n_max + 1
    n_terms = M * n_f
    alpha = wm_phases(s.seed, M, n_f)
    m = np.repeat(np.arange(1, M + 1, dtype=np.float64), n_f)
    nn = np.tile(np.arange(n_f, dtype=np.float64), M)
    k = 2.0 * math.pi * gamma**nn / Wr
    theta = math.pi * m / M
    return WMTerms(
        D=D,
        Wr=Wr,
        Lx=Lx,
        Ly=Ly,
        nx=nx,
        ny=ny,
        dx=dx,
        dy=dy,
        M=M,
        gamma=gamma,
        Wc=Wc,
        cutoff=cutoff,
        n_max=n_max,
        n_terms=n_terms,
        seed=s.seed,
        G=s.G,
        Rt=s.Rt,
        Rt_pixel=s.Rt_pixel,
        method=s.method,
        kx=k * np.cos(theta),
        ky=k * np.sin(theta),
        alpha=alpha,
        w=wm_weights(D, gamma, nn),
    )


def wm_phases(seed: int, M: int, n_f: int) -> np.ndarray:
    """Phases α_mn (rad), drawn uniformly in [0, 2π) by ``numpy.random.default_rng(seed)`` in
    (m, n) order: (M·n_f,) float64, term t = (m − 1)·n_f + n."""
    return np.random.default_rng(seed).uniform(0.0, 2.0 * math.pi, size=(M, n_f)).reshape(-1)


def wm_weights(D: float, gamma: float, nn: np.ndarray) -> np.ndarray:
    """Term weights γ^((D − 3)·n) (dimensionless) for the frequency indices ``nn``."""
    return gamma ** ((D - 3.0) * nn)


@dataclass(frozen=True)
class WMSpec(Parameters):
    """The parameters of a Weierstrass–Mandelbrot surface (paper Eq. 4), declared once.

    Every field has a default, so ``WMSpec()`` is the default surface (D = 2.5, W_r = 100 µm,
    1 mm at 1024², R_t = 10 µm). Lengths are in metres. The command-line options of every
    command that generates a surface, the sweep axes and the documentation's parameter table
    are generated from these fields (:mod:`warptrunc.params`).

    Raises
    ------
    ValueError
        A field out of its range (the message names the field, its value and the range), or a
        cut-off W_c not below W_r.

    Examples
    --------
    >>> WMSpec(D=2.3, n=256).n_terms
    170
    """

    D: float = param(2.5, "fractal dimension D", gt=2.0, lt=3.0)
    Wr: float = param(100e-6, "roll-off wavelength W_r, the longest wavelength", unit="m", gt=0.0)
    L: float | tuple[float, float] = param(
        1e-3, "side length L, or Lx Ly", unit="m", gt=0.0, pair=True, sweep=False
    )
    n: int | tuple[int, int] = param(
        1024, "pixels per side, or nx ny", kind="int", ge=2, le=1 << 20, pair=True, sweep=False
    )
    Rt: float | None = param(
        10e-6,
        "target peak-to-valley height R_t; None (none) when G is given",
        unit="m",
        gt=0.0,
        le=HEIGHT_LIMIT_M,
        optional=True,
    )
    G: float | None = param(
        None,
        "topothesy G; when given, heights are not rescaled to R_t",
        unit="m",
        gt=0.0,
        optional=True,
        sweep=False,
    )
    Rt_pixel: float | None = param(
        None,
        "pixel size at which R_t is measured (a calibration scan's): the height scale is "
        "fixed on that grid over L, so finer grids resolve the same surface; none = the map's "
        "own pixel",
        unit="m",
        gt=0.0,
        optional=True,
        sweep=False,
    )
    M: int = param(10, "number of superposed ridges M", kind="int", ge=1, le=10_000)
    gamma: float = param(1.5, "frequency density γ", gt=1.0)
    Wc: float | None = param(
        None, "cut-off wavelength W_c (default from cutoff)", unit="m", gt=0.0, optional=True
    )
    cutoff: str = param(
        "nyquist",
        "default W_c: 'nyquist' = 2 pixel spacings (no aliasing), 'pixel' = 1 "
        "spacing (the paper's literal reading)",
        choices=("nyquist", "pixel"),
        sweep=False,
    )
    seed: int = param(
        0,
        "seed of the random phases α_mn (drawn on the host)",
        kind="int",
        ge=0,
        le=2**32 - 1,
        sweep=False,
    )
    method: str = param(
        "tile",
        "evaluation: 'tile' (separable GEMM) or 'direct' (per-pixel sum)",
        choices=("tile", "direct"),
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self)
        self.terms()  # the checks that need several fields (W_c < W_r, R_t or G)

    def kwargs(self) -> dict[str, Any]:
        """The keywords of :func:`wm_spec` / :func:`~warptrunc.wm_surface`.

        Returns
        -------
        dict
        """
        return to_dict(self) | {"L": self.L, "n": self.n}

    def terms(self) -> WMTerms:
        """The per-term tables (wavevectors, phases, weights) of these parameters.

        Returns
        -------
        WMTerms
        """
        return _terms(self)

    @property
    def n_terms(self) -> int:
        """Number of WM terms M·(n_max + 1)."""
        return self.terms().n_terms


wm_spec.__doc__ = wm_spec.__doc__.replace("    {fields}", numpydoc_fields(WMSpec, indent=12))
