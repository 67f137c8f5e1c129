# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The calibration loop of Fig. 4: WM inputs (D_in, R_t') that reproduce a scan's descriptors.

1. Targets: D by a chosen method (with its options), R_rms, W_r, R_t, the scan's size and
   resolution — measured on a scan (:func:`target_from_surface`) or typed in
   (:class:`CalibrationTarget`).
2. D loop: find D_in such that the mean D_out of WM surfaces (one per seed) generated at the
   scan's size and resolution with the scan's W_r and R_t matches the target D within
   ``rtol`` (the paper: error < 5 %).
3. R_t loop: R_t' such that the mean R_rms matches. Heights are scaled to R_t, so R_rms is
   proportional to R_t for fixed D_in and seed, and R_t' = R_t · R_rms,target / R_rms.
   When D_out depends on the amplitude (``"tri"``, ``"box"`` in physical units), D_out is
   re-checked at R_t' and both loops repeat (at most ``max_rounds`` times).
4. :func:`calibrated_surface` generates the surface at the requested (high) resolution.

The D loop is a safeguarded root search on a noisy, possibly non-monotone function: all
evaluations are kept, an isotonic (non-decreasing) regression of D_out on D_in is fitted
(pool-adjacent-violators), and the next D_in is where that fit crosses the target (linear
interpolation inside the bracket, secant extrapolation outside it, clipped to
``D_bounds``). A target outside the range reached at the bounds raises
:class:`CalibrationError` with that range.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import warp as wp

from ._support.docs import SHARED_DOCS, fill_doc
from ._support.progress import progress_bar
from ._support.results import jsonable
from ._support.root_find import CalibrationError, find_root
from ._support.validate import check_int, check_range, pair
from .descriptors import roll_off_wavelength, surface_statistics
from .fractal import METHODS, fractal_dimension
from .surface import Surface
from .wm import wm_surface

__all__ = [
    "Calibration",
    "CalibrationError",
    "CalibrationTarget",
    "calibrate",
    "calibrated_surface",
    "target_from_surface",
]


@dataclass(frozen=True)
class CalibrationTarget:
    """Descriptors that the simulated surfaces must reproduce (SI units)."""

    D: float
    """Target fractal dimension by ``method`` (dimensionless, 2 < D < 3)."""
    method: str
    """Fractal method: ``"tri"``, ``"box"``, ``"vs"`` or ``"sp"``."""
    Rrms: float
    """Target R_rms (m)."""
    Rt: float
    """Peak-to-valley height of the scan, the R_t of the D loop's surfaces (m)."""
    Wr: float
    """Roll-off wavelength W_r (m)."""
    L: tuple[float, float]
    """Scan size (Lx, Ly) (m)."""
    n: tuple[int, int]
    """Scan resolution (nx, ny) (pixels)."""
    method_options: dict[str, Any] = field(default_factory=dict)
    """Options of the fractal method, used for the scan and the simulated surfaces alike."""
    source: str = ""
    """Where the targets come from (a file name, or ``"given"``)."""

    def __post_init__(self) -> None:
        if self.method not in METHODS:
            raise ValueError(f"method must be one of {METHODS}, got {self.method!r}")
        object.__setattr__(self, "D", check_range("D", self.D, 2.0, 3.0))
        object.__setattr__(self, "Rrms", check_range("Rrms", self.Rrms, 0.0, unit="m"))
        object.__setattr__(self, "Rt", check_range("Rt", self.Rt, 0.0, unit="m"))
        object.__setattr__(self, "Wr", check_range("Wr", self.Wr, 0.0, unit="m"))
        lx, ly = pair("L", self.L)
        object.__setattr__(
            self, "L", (check_range("Lx", lx, 0.0, unit="m"), check_range("Ly", ly, 0.0, unit="m"))
        )
        nx, ny = pair("n", self.n, int)
        object.__setattr__(self, "n", (check_int("nx", nx, 8), check_int("ny", ny, 8)))
        if self.Rrms >= self.Rt:
            raise ValueError(f"Rrms must be below Rt = {self.Rt!r} m, got {self.Rrms!r} m")
        object.__setattr__(self, "method_options", dict(self.method_options))

    def to_dict(self) -> dict[str, Any]:
        """Scalars (JSON-serialisable).

        Returns
        -------
        dict
            ``D``, ``method``, ``Rrms_m``, ``Rt_m``, ``Wr_m``, ``Lx_m``, ``Ly_m`` (m),
            ``nx``, ``ny`` (pixels), ``method_options`` (non-finite numbers as text) and
            ``source``.
        """
        return {
            "D": self.D,
            "method": self.method,
            "Rrms_m": self.Rrms,
            "Rt_m": self.Rt,
            "Wr_m": self.Wr,
            "Lx_m": self.L[0],
            "Ly_m": self.L[1],
            "nx": self.n[0],
            "ny": self.n[1],
            "method_options": jsonable(self.method_options, nonfinite="text"),
            "source": self.source,
        }


@dataclass(frozen=True, eq=False)
class Calibration:
    """Result of :func:`calibrate`: WM inputs and the evaluation history."""

    target: CalibrationTarget
    """The targets."""
    D_in: float
    """Calibrated input fractal dimension D_in' (dimensionless)."""
    Rt: float
    """Calibrated peak-to-valley input R_t' (m)."""
    D_out: float
    """Mean D_out over the seeds at (D_in', R_t') (dimensionless)."""
    D_out_std: float
    """Standard deviation of D_out over the seeds (dimensionless)."""
    Rrms: float
    """Mean R_rms over the seeds at (D_in', R_t') (m)."""
    converged: bool
    """True when abs(D_out − D) ≤ rtol·D at (D_in', R_t')."""
    rtol: float
    """Relative tolerance on D (dimensionless)."""
    seeds: tuple[int, ...]
    """Seeds averaged at every evaluation."""
    wm_options: dict[str, Any]
    """Other WM inputs (M, gamma, cutoff)."""
    history_D_in: np.ndarray
    """(k,) float64 D_in of every evaluation, in order (dimensionless)."""
    history_Rt: np.ndarray
    """(k,) float64 R_t of every evaluation (m)."""
    history_D_out: np.ndarray
    """(k,) float64 mean D_out of every evaluation (dimensionless)."""
    history_D_out_std: np.ndarray
    """(k,) float64 seed standard deviation of D_out (dimensionless)."""
    history_Rrms: np.ndarray
    """(k,) float64 mean R_rms of every evaluation (m)."""
    D_bounds: tuple[float, float] = (2.02, 2.98)
    """Search interval of D_in (dimensionless)."""

    @property
    def bound(self) -> str | None:
        """``"lower"`` or ``"upper"`` when D_in' is that bound of ``D_bounds``, else None.

        A calibration that ends on a bound met the target within ``rtol`` only there (or the
        bound is where the search stopped): not an interior match, so report it as such.
        """
        lo, hi = self.D_bounds
        if self.D_in <= lo + 1e-9:
            return "lower"
        return "upper" if self.D_in >= hi - 1e-9 else None

    @property
    def iterations(self) -> int:
        """Number of evaluations (each one surface per seed)."""
        return int(self.history_D_in.size)

    def to_dict(self) -> dict[str, Any]:
        """Scalars (``D_in``, ``Rt_m``, ...), ``target_*`` and the history columns.

        Returns
        -------
        dict
            Scalars ``D_in``, ``D_out``, ``D_out_std`` (dimensionless), ``Rt_m``, ``Wr_m``,
            ``Rrms_m`` (m), ``converged``, ``rtol``, ``iterations``, ``seeds``, ``D_bounds``,
            ``bound`` (``"lower"``, ``"upper"`` or None, see :attr:`bound`); the WM options
            as ``wm_<name>``; the target's :meth:`CalibrationTarget.to_dict` as
            ``target_<name>``; and the history arrays ``history_D_in``, ``history_Rt_m``,
            ``history_D_out``, ``history_D_out_std``, ``history_Rrms_m``, shape
            ``(iterations,)``.
        """

        out: dict[str, Any] = {
            "D_in": self.D_in,
            "Rt_m": self.Rt,
            "Wr_m": self.target.Wr,
            "D_out": self.D_out,
            "D_out_std": self.D_out_std,
            "Rrms_m": self.Rrms,
            "converged": self.converged,
            "rtol": self.rtol,
            "iterations": self.iterations,
            "seeds": list(self.seeds),
            "D_bounds": list(self.D_bounds),
            "bound": self.bound,
            **{f"wm_{k}": v for k, v in self.wm_options.items()},
            **{f"target_{k}": v for k, v in self.target.to_dict().items()},
            "history_D_in": self.history_D_in,
            "history_Rt_m": self.history_Rt,
            "history_D_out": self.history_D_out,
            "history_D_out_std": self.history_D_out_std,
            "history_Rrms_m": self.history_Rrms,
        }
        return out


@fill_doc(SHARED_DOCS)
def target_from_surface(
    surface: Surface,
    method: str = "tri",
    *,
    Wr: float | None = None,
    method_options: dict[str, Any] | None = None,
    device: wp.DeviceLike = None,
) -> CalibrationTarget:
    """Measure the calibration targets on a scan.

    Parameters
    ----------
    surface : Surface
        The measured height map (m), levelled and without missing points.
    method : {"tri", "box", "vs", "sp"}
        Fractal method whose D is matched.
    Wr : float, optional
        Roll-off wavelength (m). Defaults to :func:`warptrunc.descriptors.roll_off_wavelength`
        of the scan; a scan too small to resolve it raises ValueError asking for ``Wr``.
    method_options : dict, optional
        Options of the fractal method (see :func:`warptrunc.fractal.fractal_dimension`).
    {warp_device}

    Returns
    -------
    CalibrationTarget
    """
    opts = dict(method_options or {})
    d = fractal_dimension(surface, method, device=device, **opts).D
    st = surface_statistics(surface)
    if Wr is None:
        Wr, ok = roll_off_wavelength(surface)
        if not ok:
            raise ValueError(
                f"the scan ({surface.lx:.4g} m × {surface.ly:.4g} m) does not resolve its "
                f"roll-off wavelength (estimate {Wr:.4g} m ≥ a third of its size); give Wr"
            )
    if not 2.0 < d < 3.0:
        raise CalibrationError(
            f"the scan's D by {method!r} is {d:.4f}, outside (2, 3): no WM surface reaches it",
            (),
            (),
        )
    return CalibrationTarget(
        D=d,
        method=method,
        Rrms=st["Rrms"],
        Rt=st["Rt"],
        Wr=Wr,
        L=(surface.lx, surface.ly),
        n=(surface.nx, surface.ny),
        method_options=opts,
        source=str(surface.params.get("source", "")),
    )


@fill_doc(SHARED_DOCS)
def calibrate(
    target: CalibrationTarget,
    *,
    seeds: Sequence[int] = (0, 1, 2),
    rtol: float = 0.05,
    D_start: float | None = None,
    D_bounds: tuple[float, float] = (2.02, 2.98),
    max_iter: int = 12,
    max_rounds: int = 3,
    M: int = 10,
    gamma: float = 1.5,
    cutoff: str = "nyquist",
    progress: bool = True,
    device: wp.DeviceLike = None,
) -> Calibration:
    """Find D_in and R_t' of WM surfaces that reproduce the targets (Fig. 4).

    Parameters
    ----------
    target : CalibrationTarget
        Descriptors to match.
    seeds : sequence of int
        Seeds of the WM phases; D_out and R_rms are averaged over them at every evaluation.
    rtol : float
        Relative tolerance: abs(D_out − D) ≤ rtol·D (dimensionless). The paper uses 5 %.
    D_start : float, optional
        First D_in; default the target D (as in the paper), clipped to ``D_bounds``.
    D_bounds : (float, float)
        Search interval for D_in, inside (2, 3) (the WM model's range). A result on a bound is
        flagged by :attr:`Calibration.bound`.
    max_iter : int
        Largest number of evaluations of the D loop per round.
    max_rounds : int
        Largest number of D-loop/R_t-loop rounds (a round is repeated only when D_out at R_t'
        leaves the tolerance, which happens for amplitude-dependent methods).
    M, gamma, cutoff
        WM inputs (see :func:`warptrunc.wm.wm_surface`).
    progress : bool
        Show a tqdm progress bar.
    {warp_device}

    Returns
    -------
    Calibration

    Raises
    ------
    CalibrationError
        The target D lies outside the D_out reached at the bounds of ``D_bounds`` (the message
        gives that range), or the loop did not converge within ``max_iter`` evaluations.
    """

    rtol = check_range("rtol", rtol, 0.0, 1.0)
    lo, hi = (float(v) for v in D_bounds)
    if not 2.0 < lo < hi < 3.0:
        raise ValueError(f"D_bounds must satisfy 2 < lo < hi < 3, got {D_bounds!r}")
    max_iter = check_int("max_iter", max_iter, 2, 1000)
    max_rounds = check_int("max_rounds", max_rounds, 1, 100)
    seeds = tuple(int(s) for s in seeds)
    if not seeds:
        raise ValueError("seeds must not be empty")
    x0 = target.D if D_start is None else check_range("D_start", D_start, 2.0, 3.0)
    x0 = min(max(x0, lo), hi)
    hist: list[tuple[float, float, float, float, float]] = []
    wm_opts = {"M": M, "gamma": gamma, "cutoff": cutoff}

    bar = progress_bar(
        total=max_iter * max_rounds, enabled=progress, desc="calibrate", unit="eval"
    )

    def evaluate(d_in: float, Rt: float) -> tuple[float, float, float]:
        ds, rms = [], []
        for seed in seeds:
            s = wm_surface(
                d_in, target.Wr, L=target.L, n=target.n, Rt=Rt, seed=seed, device=device, **wm_opts
            )
            ds.append(fractal_dimension(s, target.method, device=device, **target.method_options).D)
            rms.append(surface_statistics(s)["Rrms"])  # on the device, no host copy
        out = (float(np.mean(ds)), float(np.std(ds)), float(np.mean(rms)))
        hist.append((d_in, Rt, *out))
        bar.update(1)
        bar.set_postfix(D_in=f"{d_in:.4f}", D_out=f"{out[0]:.4f}", target=f"{target.D:.4f}")
        return out

    atol = rtol * target.D
    Rt = target.Rt
    d_in = x0
    known = None
    try:
        for _ in range(max_rounds):
            d_in = find_root(
                lambda x, Rt=Rt: evaluate(x, Rt)[0],
                target.D,
                atol,
                (lo, hi),
                d_in,
                max_iter,
                what=f"D_out by {target.method!r}",
                known=known,
            )
            # R_t' from the evaluation at the chosen D_in (R_rms ∝ R_t for fixed D_in, seeds)
            rms_at = next(h[4] for h in reversed(hist) if h[0] == d_in and h[1] == Rt)
            Rt = Rt * target.Rrms / rms_at
            d_out, d_std, rms = evaluate(d_in, Rt)
            if abs(d_out - target.D) <= atol:
                break
            known = (d_in, d_out)
        else:
            raise CalibrationError(
                f"D_out by {target.method!r} drifts out of tolerance after rescaling to R_t' in "
                f"each of {max_rounds} rounds (last D_in = {d_in:.4f}, R_t' = {Rt:.4g} m, "
                f"D_out = {d_out:.4f}, target {target.D:.4f} ± {atol:.4f})"
            )
    finally:
        bar.close()
    h = np.array(hist, dtype=np.float64)
    return Calibration(
        target=target,
        D_in=float(d_in),
        Rt=float(Rt),
        D_out=d_out,
        D_out_std=d_std,
        Rrms=rms,
        converged=True,
        rtol=rtol,
        seeds=seeds,
        wm_options=wm_opts,
        history_D_in=h[:, 0],
        history_Rt=h[:, 1],
        history_D_out=h[:, 2],
        history_D_out_std=h[:, 3],
        history_Rrms=h[:, 4],
        D_bounds=(lo, hi),
    )


@fill_doc(SHARED_DOCS)
def calibrated_surface(
    calibration: Calibration,
    *,
    n: int | tuple[int, int] | None = None,
    L: float | tuple[float, float] | None = None,
    seed: int = 0,
    device: wp.DeviceLike = None,
) -> Surface:
    """Generate the calibrated WM surface, by default at the scan's size and resolution.

    Parameters
    ----------
    calibration : Calibration
        Result of :func:`calibrate`.
    n : int or (int, int), optional
        Pixels per side or (nx, ny); e.g. 10240 for the paper's simulated surfaces.
    L : float or (float, float), optional
        Side length(s) (m); default the scan's.
    seed : int
        Seed of the phases.
    {warp_device}

    Returns
    -------
    Surface
        ``params`` hold the WM inputs and ``calibration`` (the targets and D_out).

    Notes
    -----
    R_t' is kept as calibrated at the scan's resolution (paper §3.2); at a higher resolution the
    WM sum has more (finer) terms, so R_rms at fixed R_t' differs slightly from the target
    (−1.4 % from 1024² to 2048² in ``examples/calibrate_to_scan.py``).
    """

    t = calibration.target
    s = wm_surface(
        calibration.D_in,
        t.Wr,
        L=t.L if L is None else L,
        n=t.n if n is None else n,
        Rt=calibration.Rt,
        seed=seed,
        device=device,
        **calibration.wm_options,
    )
    info = {
        k: v
        for k, v in calibration.to_dict().items()
        if not k.startswith("history_") and not k.startswith("wm_")
    }
    return Surface(s.heights, s.dx, s.dy, {**s.params, "calibration": jsonable(info, nonfinite="text")})


# --- root search on a noisy, non-decreasing function -------------------------------------------


