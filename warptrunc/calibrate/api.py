# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The calibration loop of Fig. 4: WM inputs (D_in, R_t') that reproduce a scan's descriptors.

1. Targets: D by a chosen method (with its options), R_rms, W_r, R_t, the scan's size and
   resolution — measured on a scan (:func:`target_from_surface`) or typed in
   (:class:`CalibrationTarget`).
2. D loop: find D_in such that the mean D_out of WM surfaces (one per seed) generated at the
   scan's size and resolution with the scan's W_r and R_t matches the target D within the
   tolerance: ``rtol``·D (the paper: error < 5 %), or ``scatter_sd`` standard deviations of
   D_out over the seeds where that is tighter (a difference inside the scatter of D between
   realisations is all the loop can resolve).
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

from dataclasses import dataclass
from typing import Any

import numpy as np
import warp as wp

from .._support.docs import SHARED_DOCS, fill_doc
from .._support.outputs import jsonable
from .._support.progress import progress_bar
from ..descriptors import roll_off_wavelength, surface_statistics
from ..fractal import fractal_dimension
from ..surface import Surface
from ..wm import wm_surface
from ._root_find import CalibrationError, find_root
from .settings import CalibrationSettings, CalibrationTarget

__all__ = [
    "Calibration",
    "CalibrationError",
    "CalibrationSettings",
    "CalibrationTarget",
    "calibrate",
    "calibrated_surface",
    "target_from_surface",
]


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
    """True when abs(D_out − D) ≤ :attr:`tolerance` at (D_in', R_t'): the evaluation after the
    R_t loop, the last of the history."""
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
    tolerance: float = float("nan")
    """The tolerance on D met by a converged calibration: the smaller of rtol·D and
    scatter_sd times the sample sd of D_out over the seeds at the first D_in
    (dimensionless)."""
    tolerance_basis: str = "rtol"
    """Which bound set :attr:`tolerance`: ``"rtol"`` or ``"scatter"``."""
    reason: str | None = None
    """Why the calibration did not converge (None when it did)."""

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
            ``Rrms_m`` (m), ``converged``, ``rtol``, ``tolerance`` (on D, absolute),
            ``tolerance_basis`` (``"rtol"`` or ``"scatter"``), ``reason`` (why not converged,
            or None), ``iterations``, ``seeds``, ``D_bounds``,
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
            "tolerance": self.tolerance,
            "tolerance_basis": self.tolerance_basis,
            "reason": self.reason,
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
    settings: CalibrationSettings | None = None,
    *,
    Wr: float | None = None,
    device: wp.DeviceLike = None,
) -> CalibrationTarget:
    """Measure the calibration targets on a scan.

    Parameters
    ----------
    surface : Surface
        The measured height map (m), levelled and without missing points.
    settings : CalibrationSettings, optional
        Its ``method`` (the fractal method whose D is matched) and ``height_scaling`` (the
        height convention of ``"tri"`` and ``"box"``) are read; its defaults when None.
    Wr : float, optional
        Roll-off wavelength (m). Defaults to :func:`warptrunc.descriptors.roll_off_wavelength`
        of the scan; a scan too small to resolve it raises ValueError asking for ``Wr``.
    {warp_device}

    Returns
    -------
    CalibrationTarget
    """
    settings = CalibrationSettings() if settings is None else settings
    method = settings.method
    opts = settings.method_options()
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
    settings: CalibrationSettings | None = None,
    progress: bool = True,
    device: wp.DeviceLike = None,
) -> Calibration:
    """Find D_in and R_t' of WM surfaces that reproduce the targets (Fig. 4).

    Parameters
    ----------
    target : CalibrationTarget
        Descriptors to match (D by ``target.method`` with ``target.method_options``).
    settings : CalibrationSettings, optional
        The seeds averaged at every evaluation, the tolerance on D (abs(D_out − D) ≤ rtol·D,
        the paper's 5 %, or ``scatter_sd`` standard deviations of D_out over the seeds where
        that is tighter), the first D_in (default the target D, as in the paper,
        clipped to ``D_bounds``), the search interval ``D_bounds`` inside (2, 3) (a result on a
        bound is flagged by :attr:`Calibration.bound`), the evaluations per D loop
        (``max_iter``), the D-loop/R_t-loop rounds (``max_rounds``: a round is repeated only
        when D_out at R_t' leaves the tolerance, which happens for amplitude-dependent methods)
        and the WM inputs ``M``, ``gamma``, ``cutoff``
        (:class:`~warptrunc.calibrate.settings.CalibrationSettings`; its defaults when None; its
        ``method``, ``height_scaling`` and output fields are not read here).
    progress : bool
        Report the evaluations on stderr (a bar on a terminal, a line per evaluation
        otherwise).
    {warp_device}

    Returns
    -------
    Calibration
        ``converged`` is False when D_out at (D_in', R_t') leaves the tolerance in each of
        ``max_rounds`` rounds (the result is that of the last round).

    Raises
    ------
    CalibrationError
        The target D lies outside the D_out reached at the bounds of ``D_bounds`` (the message
        gives that range), or a D loop did not reach the tolerance within ``max_iter``
        evaluations.
    """
    settings = CalibrationSettings() if settings is None else settings
    rtol, (lo, hi) = settings.rtol, settings.D_bounds
    max_iter, max_rounds, seeds = settings.max_iter, settings.max_rounds, settings.seeds
    x0 = target.D if settings.D_start is None else settings.D_start
    x0 = min(max(x0, lo), hi)
    hist: list[tuple[float, float, float, float, float]] = []
    spread: list[float] = []  # sample sd of D_out over the seeds, per evaluation
    wm_opts = settings.wm_options()

    bar = progress_bar(total=max_iter * max_rounds, enabled=progress, desc="calibrate", unit="eval")

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
        spread.append(float(np.std(ds, ddof=1)) if len(ds) > 1 else 0.0)
        bar.update(1)
        bar.set_postfix(D_in=f"{d_in:.4f}", D_out=f"{out[0]:.4f}", target=f"{target.D:.4f}")
        return out

    Rt = target.Rt
    d_in = x0
    try:
        first = evaluate(x0, Rt)
        atol, basis = rtol * target.D, "rtol"
        if settings.scatter_sd > 0 and spread[0] > 0 and settings.scatter_sd * spread[0] < atol:
            atol, basis = settings.scatter_sd * spread[0], "scatter"
        known = (x0, first[0])
        converged, reason = False, None
        for _ in range(max_rounds):
            try:
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
            except CalibrationError as exc:
                # the scatter tolerance out of reach: the closest evaluation within rtol·D is
                # the result, reported as not converged
                near = [h for h in hist if h[1] == Rt and abs(h[2] - target.D) <= rtol * target.D]
                if basis != "scatter" or not near:
                    raise
                d_in = min(near, key=lambda h: abs(h[2] - target.D))[0]
                reason = str(exc).split(" Evaluations (D_in")[0].split(" Use another method")[0]
            # R_t' from the evaluation at the chosen D_in (R_rms ∝ R_t for fixed D_in, seeds)
            rms_at = next(h[4] for h in reversed(hist) if h[0] == d_in and h[1] == Rt)
            Rt = Rt * target.Rrms / rms_at
            d_out, d_std, rms = evaluate(d_in, Rt)
            if abs(d_out - target.D) <= atol:
                converged, reason = True, None
                break
            if reason is not None:
                break
            known = (d_in, d_out)
        if not converged and reason is None:
            reason = (
                f"D_out at R_t' leaves the tolerance in each of {max_rounds} rounds (D_out "
                f"depends on the amplitude for this method)"
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
        converged=converged,
        rtol=rtol,
        tolerance=float(atol),
        tolerance_basis=basis,
        reason=reason,
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
    return Surface(
        s.heights, s.dx, s.dy, {**s.params, "calibration": jsonable(info, nonfinite="text")}
    )


# --- root search on a noisy, non-decreasing function -------------------------------------------
