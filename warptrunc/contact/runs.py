# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The elastic solves of :func:`warptrunc.bem_check`: warptrunc's solver or ContactMechanics'.

Each ``run_*`` solves the approaches δ of a :class:`~warptrunc.contact.check.BemCheck` (with E*
of the :class:`~warptrunc.Material`, the tolerances of the
:class:`~warptrunc.contact.SolverSettings` and the stiffness method of the
:class:`~warptrunc.contact.BemCheckSettings`) and returns ``(columns, converged, n_iterations, edge_contact, solves, settings)``: F (N), A (m²),
k (N/m) and the row's time (s) per δ, the flags, one dict per solve and the solver's settings.
ContactMechanics (the ``bem`` extra) is imported only by :func:`require_bem`.
"""

from __future__ import annotations

import importlib.metadata
import time
from typing import Any

import numpy as np

from .._support.docs import fill_doc
from ..material import Material
from .results import ContactState
from .settings import BemCheckSettings, SolverSettings
from .factory import contact_solver
from .solver import default_pentol

__all__ = [
    "EXTRA_HINT",
    "contactmechanics_versions",
    "edge_contact",
    "pentol_or_default",
    "require_bem",
]
# run_warptrunc and run_contactmechanics are bem-check's two routes (warptrunc.bem_check), not
# entry points of their own: one public function solves a contact, solve_contact.

RUN_DOCS = {
    "{surface_approaches}": (
        "surface : Surface\n    The rough height map (m), on the host.\n"
        "d : (m,) ndarray\n    Approaches δ (m), increasing.\n"
        "material : Material\n    Its contact modulus E* (Pa) is the half-space's.\n"
        "settings : SolverSettings\n    Substrate, ``pressure_tol`` (forcetol = "
        "pressure_tol·E*·dx·dy, N), ``pentol`` (m; None: :func:`pentol_or_default`'s default) "
        "and ``maxiter``.\n"
        "check : BemCheckSettings\n    Its ``stiffness`` and ``fd_step`` (the relative step h of "
        "the central difference, dimensionless).\n"
        "progress : bool\n    Report the solves on stderr (a bar on a terminal, else lines)."
    ),
}
"""Parameter text of both solvers' runs, written once (:func:`fill_doc`)."""

EXTRA_HINT = 'pip install "warptrunc[bem]"'


def require_bem() -> tuple[Any, Any, Any, Any]:
    """Import ContactMechanics; raise ImportError naming the extra when it is missing.

    Returns
    -------
    (FreeFFTElasticHalfSpace, PeriodicFFTElasticHalfSpace, NonSmoothContactSystem, Topography)
    """
    import warnings

    try:
        with warnings.catch_warnings():  # NuMPI without mpi4py: its serial stub, as intended here
            warnings.filterwarnings("ignore", "Could not import mpi4py", ImportWarning)
            from ContactMechanics import FreeFFTElasticHalfSpace, PeriodicFFTElasticHalfSpace
            from ContactMechanics.Systems import NonSmoothContactSystem
            from SurfaceTopography import Topography
    except ImportError as exc:
        raise ImportError(
            f"the elastic boundary-element check needs ContactMechanics and SurfaceTopography "
            f"({exc}); install them with: {EXTRA_HINT}"
        ) from exc
    return FreeFFTElasticHalfSpace, PeriodicFFTElasticHalfSpace, NonSmoothContactSystem, Topography


def contactmechanics_versions() -> dict[str, str]:
    """Installed versions of ContactMechanics, SurfaceTopography and muGrid (for provenance).

    Returns
    -------
    dict of str to str
        ``{"contactmechanics": ..., "surfacetopography": ..., "mugrid": ...}``: each package's
        version string, or ``"not installed"``.
    """
    out = {}
    for pkg in ("contactmechanics", "surfacetopography", "mugrid"):
        try:
            out[pkg] = importlib.metadata.version(pkg)
        except importlib.metadata.PackageNotFoundError:
            out[pkg] = "not installed"
    return out


def edge_contact(contact: np.ndarray) -> bool:
    """True when a contact pixel lies on the border of the map.

    Parameters
    ----------
    contact : (ny, nx) ndarray of bool
        Contact mask (any 2-D array whose truth value marks contact).

    Returns
    -------
    bool
        True if any pixel of the first or last row or column is in contact.
    """
    return bool(
        contact[0, :].any() or contact[-1, :].any() or contact[:, 0].any() or contact[:, -1].any()
    )


def pentol_or_default(h: np.ndarray, pentol: float | None) -> tuple[float, str]:
    """(pentol (m), where it came from): the given one, else ContactMechanics' default.

    Parameters
    ----------
    h : ndarray
        Heights (m), used only when ``pentol`` is None.
    pentol : float or None
        Penetration tolerance (m), or None for the default.

    Returns
    -------
    pentol : float
        ``pentol`` itself, or :func:`~warptrunc.contact.solver.default_pentol` of ``h``
        (ContactMechanics' heuristic rms height/(10·mean n)) (m).
    source : str
        ``"given"`` or ``"default: rms height/(10·mean n)"``.
    """
    if pentol is None:  # ContactMechanics' heuristic, computed here (its own call is deprecated)
        return default_pentol(h), "default: rms height/(10·mean n)"
    return pentol, "given"


def _run_columns(m: int) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray, np.ndarray]:
    """Zeroed columns of m approaches: F, A, k and t (a dict of float64), converged, iterations
    and edge contact."""
    out = {k: np.zeros(m) for k in ("F", "A", "k", "t")}
    return out, np.zeros(m, dtype=bool), np.zeros(m, dtype=np.int64), np.zeros(m, dtype=bool)


@fill_doc(RUN_DOCS)
def run_contactmechanics(
    surface,
    d: np.ndarray,
    *,
    material: Material,
    settings: SolverSettings,
    check: BemCheckSettings,
    progress: bool = True,
):
    """ContactMechanics' solves, three per approach (δ(1 − h), δ, δ(1 + h)), warm-started.

    The solves run on the CPU in float64 (``NonSmoothContactSystem.minimize_proxy``), each one
    started from the displacements of the previous solve. k is the central difference
    [F(δ(1 + h)) − F(δ(1 − h))]/(2hδ).

    Parameters
    ----------
    {surface_approaches}

    Returns
    -------
    columns : dict of str to (m,) ndarray
        ``"F"`` load at δ (N), ``"A"`` contact area at δ (m²), ``"k"`` stiffness (N/m),
        ``"t"`` wall time of the row's three solves (s).
    converged : (m,) ndarray of bool
        All three solves of the row succeeded.
    n_iterations : (m,) ndarray of int64
        Iterations of the solve at δ.
    edge_contact : (m,) ndarray of bool
        :func:`edge_contact` of the contact at δ.
    solves : list of dict
        One dict per solve (``depth_m``, ``success``, ``n_iterations``, ``message``,
        ``load_N``), in solve order.
    settings : dict
        Solver name and description, half-space class, stiffness method, ``pentol_m`` and
        ``pentol_source``.

    Raises
    ------
    ImportError
        ContactMechanics or SurfaceTopography is not installed (:func:`require_bem`).

    Notes
    -----
    The substrate is ``FreeFFTElasticHalfSpace`` or ``PeriodicFFTElasticHalfSpace``; the
    stiffness is always the central difference (``check.stiffness`` is not read).
    """
    from .._support.progress import progress_bar

    Free, Periodic, System, Topography = require_bem()
    contact_modulus, substrate = material.contact_modulus, settings.substrate
    fd_step, maxiter = check.fd_step, settings.maxiter
    h = np.ascontiguousarray(surface.heights.T, dtype=np.float64)  # ContactMechanics: x first
    sizes = (surface.lx, surface.ly)
    topo = Topography(h, physical_sizes=sizes, periodic=substrate == "periodic")
    half_space = (Free if substrate == "free" else Periodic)(h.shape, contact_modulus, sizes)
    system = System(half_space, topo)
    forcetol = settings.pressure_tol * contact_modulus * surface.pixel_area
    pentol, pentol_note = pentol_or_default(h, settings.pentol)
    h_max = float(h.max())
    m = d.size
    out, conv, nit, edge = _run_columns(m)
    solves: list[dict[str, Any]] = []
    u0 = None

    def solve(delta: float) -> tuple[float, dict[str, Any], np.ndarray]:
        nonlocal u0
        kw: dict[str, Any] = {
            "offset": delta - h_max,
            "forcetol": forcetol,
            "pentol": pentol,
            "maxiter": maxiter,
        }
        if u0 is not None:
            kw["initial_displacements"] = u0
        r = system.minimize_proxy(**kw)
        u0 = r.x
        f = np.asarray(r.jac)  # per-pixel force on the map, compressive > 0 (N)
        info = {
            "depth_m": delta,
            "success": bool(r.success),
            "n_iterations": int(r.nit),
            "message": str(r.message),
            "load_N": float(f.sum()),
        }
        return float(f.sum()), info, f

    bar = progress_bar(total=3 * m, desc="BEM solves", unit="solve", enabled=progress)
    for i, delta in enumerate(d):
        t0 = time.perf_counter()
        lo, i_lo, _ = solve(delta * (1 - fd_step))
        bar.update()
        F, i_mid, f = solve(delta)
        bar.update()
        hi, i_hi, _ = solve(delta * (1 + fd_step))
        bar.update()
        out["t"][i] = time.perf_counter() - t0
        contact = f > 0
        out["F"][i] = F
        out["A"][i] = np.count_nonzero(contact) * surface.pixel_area
        out["k"][i] = (hi - lo) / (2 * fd_step * delta)
        conv[i] = i_lo["success"] and i_mid["success"] and i_hi["success"]
        nit[i] = i_mid["n_iterations"]
        edge[i] = edge_contact(contact)
        solves += [i_lo, i_mid, i_hi]
    bar.close()
    extra = {
        "solver": "contactmechanics",
        "solver_description": "ContactMechanics NonSmoothContactSystem.minimize_proxy "
        "(constrained conjugate gradients, Polonsky & Keer 1999), CPU, float64",
        "half_space": type(half_space).__name__,
        "stiffness_method": "central difference of F over δ(1 ± fd_step)",
        "pentol_m": pentol,
        "pentol_source": pentol_note,
    }
    return out, conv, nit, edge, solves, extra


@fill_doc(RUN_DOCS)
def run_warptrunc(
    surface,
    d: np.ndarray,
    *,
    material: Material,
    settings: SolverSettings,
    check: BemCheckSettings,
    progress: bool = True,
    device: Any = None,
    devices: Any = None,
):
    """warptrunc's solves on ``device``: δ(1 − h), δ, δ(1 + h) (central) or δ and Barber's punch.

    One :class:`~warptrunc.contact.solver.ContactSolver` serves all solves.

    Parameters
    ----------
    {surface_approaches}
    device : str or warp.context.Device or None
        Warp device of the solver.
    devices : int, "auto" or list, optional
        Spread the solver over several devices (``contact_solver(..., devices=...)``,
        :class:`~warptrunc.contact.sharded.ShardedContactSolver`; JAX); default None: one.

    Returns
    -------
    columns : dict of str to (m,) ndarray
        ``"F"`` load at δ (N), ``"A"`` contact area at δ (m²), ``"k"`` stiffness (N/m),
        ``"t"`` wall time of the row's solves (s).
    converged : (m,) ndarray of bool
        The row's contact solves (and, for Barber, the punch solve) converged.
    n_iterations : (m,) ndarray of int64
        Iterations of the solve at δ.
    edge_contact : (m,) ndarray of bool
        :func:`edge_contact` of the contact at δ.
    solves : list of dict
        One dict per contact solve (``depth_m``, ``success``, ``n_iterations``,
        ``n_convolutions``, ``load_N``, ``residual_m``, ``message``; ``punch_iterations`` on
        the solve at δ with Barber's method), in solve order.
    settings : dict
        Solver name and description, stiffness method, ``pentol_m``, ``pentol_source``,
        ``device`` and ``dtype``.

    Notes
    -----
    ``check.stiffness`` ``"central"``: k = [F(δ(1 + h)) − F(δ(1 − h))]/(2hδ), three contact
    solves per row; ``"barber"``: Barber's flat punch of the contact set at δ (one contact
    solve and one linear solve per row). The other fields of ``settings`` (``dtype``, ...) are
    the solver's; its ``pentol`` None is replaced by :func:`pentol_or_default`'s default.
    """
    from .._support.progress import progress_bar

    stiffness, fd_step, dtype = check.stiffness, check.fd_step, settings.dtype
    pentol, pentol_note = pentol_or_default(surface.heights, settings.pentol)
    solver = contact_solver(
        surface.heights,
        (surface.dx, surface.dy),
        material.contact_modulus,
        settings=settings.replace(pentol=pentol),
        device=device,
        devices=devices,
    )
    where = "+".join(getattr(solver, "device_names", [])) or str(solver.device)
    m = d.size
    out, conv, nit, edge = _run_columns(m)
    solves: list[dict[str, Any]] = []
    per_row = 3 if stiffness == "central" else 1
    bar = progress_bar(total=per_row * m, desc="BEM solves", unit="solve", enabled=progress)

    def solve(delta: float) -> ContactState:
        info = solver.solve(delta)
        bar.update()
        solves.append(
            {
                "depth_m": float(delta),
                "success": bool(info.converged),
                "n_iterations": int(info.n_iterations),
                "n_convolutions": float(info.n_convolutions),
                "load_N": float(info.load),
                "residual_m": float(info.residual),
                "message": "converged" if info.converged else f"reached maxiter = {solver.maxiter}",
            }
        )
        return info

    for i, delta in enumerate(d):
        t0 = time.perf_counter()
        lo = solve(delta * (1 - fd_step)) if stiffness == "central" else None
        mid = solve(delta)
        # sync point; the contact of the solve at δ (over several devices: booleans only)
        contact = solver.contact_map() if hasattr(solver, "contact_map") else solver.maps()[0] > 0
        if lo is not None:
            hi = solve(delta * (1 + fd_step))
            out["k"][i] = (hi.load - lo.load) / (2 * fd_step * delta)
            conv[i] = lo.converged and mid.converged and hi.converged
        else:
            k, k_it, k_ok = solver.punch_stiffness()
            solves[-1]["punch_iterations"] = k_it
            out["k"][i] = k
            conv[i] = mid.converged and k_ok
        out["t"][i] = time.perf_counter() - t0
        out["F"][i] = mid.load
        out["A"][i] = np.count_nonzero(contact) * surface.pixel_area
        nit[i] = mid.n_iterations
        edge[i] = edge_contact(contact)
    bar.close()
    extra = {
        "solver": "warptrunc",
        "solver_description": "warptrunc.contact constrained conjugate gradients "
        f"(Polonsky & Keer 1999) on {where}, {dtype}",
        "stiffness_method": "central difference of F over δ(1 ± fd_step)"
        if stiffness == "central"
        else "Barber: flat punch of the contact set (linear CG)",
        "pentol_m": pentol,
        "pentol_source": pentol_note,
        "device": where,
        "dtype": dtype,
    }
    return out, conv, nit, edge, solves, extra
