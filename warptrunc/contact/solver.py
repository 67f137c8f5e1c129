# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The contact solver object, :class:`ContactSolver`: a rough map on an elastic half-space.

This module holds the solver's settings, its state (the device maps, allocated in
``ContactSolver.__init__``, cleared by ``reset``) and its public methods (``solve``: displacement
or load control, elastic or capped; the plastic state; Barber's stiffness; the read-backs
``maps`` and ``max_pressure``). The iterations it runs are :mod:`warptrunc.contact.iteration`:
the preconditioned bound-constrained CG (``SolverSettings.algorithm="bccg"``, the default,
:mod:`~warptrunc.contact.iteration.bccg`) or Polonsky & Keer's constrained CG
(``algorithm="pk"``, described below, :mod:`~warptrunc.contact.iteration.pk`); its memory model
and the check against the free memory are :mod:`warptrunc.contact.memory`.

The iteration is that of ContactMechanics' ``constrained_conjugate_gradients`` (same gap sign,
warm start, offset handling in load control and stopping criterion), so that both give the same
answers on the same discretisation (:mod:`warptrunc.contact.halfspace`); its kernels are in
``warptrunc.kernels.contact.cg`` and ``warptrunc.kernels.contact.spectral``.

Work per iteration, in transforms (a convolution = one forward and one inverse transform, each
pruned to the map: :mod:`warptrunc.contact.halfspace`). PK needs t·K·t (for the step τ) and
u = K·q (the gaps). t·K·t comes from the spectrum T̂ of the direction by Parseval, in the same
pass that multiplies T̂ by the kernel; one inverse transform then gives K·t, and after the step
q ← q − τ·t the new displacement is u − τ·K·t by linearity (times the load scale in load
control). The projection then changes a few forces by Δp (tensile forces set to zero, penetrating
pixels given force): when they are at most ``direct_max`` pixels, K·Δp is summed directly over
the real-space influence table (``advance_kernel``: one pass over the map per changed pixel, in
the same kernel as the update and the convergence sums; the changed pixels are listed in a fixed
order by a scan, so the result is deterministic); otherwise, on the first iteration and every
``refresh`` iterations (against round-off drift), q is transformed afresh and u = K·q. So an
iteration costs one convolution (forward t, inverse) while the projection changes at most
``direct_max`` pixels, 1.5 when it changes more; u is exact in every iteration (to round-off)
and the iterates are those of ContactMechanics' algorithm. ``n_convolutions`` reports
transforms / 2. Measured on D = 2.5 WM maps, warm-started solve at 0.2·R_t: 256², 13 iterations,
16 convolutions; 512², 16 iterations, 19.5; 2048², 26 iterations, 31 with
``direct_max`` = 24.

Host synchronisation: two small read-backs per iteration. τ is formed on the device
(``step_length_kernel``) and read back with the force update's counts (how many forces the
projection changed decides between direct summation and a transform); the advance's sums (gaps,
convergence) are the second.

The max abs(Δu) of the stopping criterion is taken over the map (ContactMechanics takes it over the
padded grid; outside the map Δu is the far field of the map's Δq and smaller).

Stopping (ContactMechanics' criterion): rms and max penetration over the CG set and the largest
change of u in the iteration below ``pentol`` (m); the largest tensile pixel force before the
projection below ``forcetol`` (N); the relative change of the total force below ``thermotol``
(displacement control) or the total force within ``thermotol`` of the target and the flat's
position steady (load control).

Elastic–perfectly-plastic contact (``hardness`` H < inf): :mod:`warptrunc.contact.iteration.plastic`.
Adhesive contact (an :class:`~warptrunc.contact.adhesion.Adhesion` law):
:mod:`warptrunc.contact.iteration.adhesive`, a fixed point on the law's forces whose every step
is the non-adhesive solve above on the effective heights.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import warp as wp

from .._support.device import resolve_device
from .._support.docs import SHARED_DOCS, fill_doc
from .._support.validate import check_height_map, check_range, pair
from ..kernels.contact import cg as _k
from ..material import Material
from ..params import check_value
from .halfspace import DTYPES, ElasticHalfSpace
from .iteration.adhesive import AdhesiveSolves
from .iteration.bccg import BCCGSolves
from .iteration.bccg_device import DeviceLoopSolves
from .iteration.loop import SolveLoop
from .iteration.pk import PKSolves
from .iteration.plastic import CappedSolves
from .iteration.punch import PunchStiffness
from .memory import fft_plan_that_fits, memory_bytes, memory_terms
from .results import ContactState
from .settings import SolverSettings

__all__ = ["ContactSolver", "default_pentol"]


def default_pentol(heights: np.ndarray) -> float:
    """ContactMechanics' default penetration tolerance: rms height / (10·mean(nx, ny)).

    Parameters
    ----------
    heights : (ny, nx) array_like
        Heights (m).

    Returns
    -------
    float
        Tolerance on penetration (m).
    """
    h = np.asarray(heights, dtype=np.float64)
    return float(np.std(h)) / (10 * np.mean(h.shape))


@fill_doc(SHARED_DOCS)
class ContactSolver(
    SolveLoop,
    CappedSolves,
    BCCGSolves,
    DeviceLoopSolves,
    PKSolves,
    PunchStiffness,
    AdhesiveSolves,
):
    """A rough map (the rigid indenter) on an elastic half-space; solves keep a warm start.

    With a finite ``hardness`` the local pressure is capped at H and the map flows plastically
    (elastic–perfectly-plastic contact, see the module docstring): the plastic height change is
    state of the solver, so a sequence of solves is a loading history.

    The iterations are base classes of the solver, each in its module of
    :mod:`warptrunc.contact.iteration` (``SolveLoop``: what the loops share; ``PKSolves``,
    ``BCCGSolves``, ``DeviceLoopSolves``, ``CappedSolves``: the loops; ``PunchStiffness``:
    Barber's punch; ``AdhesiveSolves``: the adhesive solve over them), rather than objects the solver holds, because every one of them reads and
    writes the solver's device maps (forces, displacements, direction, mask, lane reductions)
    in every iteration, and because :class:`~warptrunc.contact.sharded.ShardedContactSolver`
    replaces some of them (the BCCG iteration, its sums and warm start, the plastic flow, the
    punch) with their versions over several devices while inheriting everything above them.

    Parameters
    ----------
    heights : (ny, nx) array_like
        Heights z (m) of the rough surface; a finite 2-D map.
    pixel_size : float or (float, float)
        Pixel sides (dx, dy) (m).
    contact_modulus : float
        Contact modulus E* (Pa).
    settings : SolverSettings, optional
        Precision, substrate, interaction law, tolerances and iteration limits
        (:class:`~warptrunc.contact.SolverSettings`; default ``SolverSettings()``). An adhesive
        ``settings.adhesion`` (:class:`~warptrunc.contact.adhesion.Adhesion`) keeps its forces
        between solves, so a sequence of solves is an approach–retract history
        (:mod:`warptrunc.contact.iteration.adhesive`); it needs H = inf, one device and
        ``load_control="offset"``. Measured
        float32 against float64 on D = 2.5 WM maps of 128²–512²: F within 5e-7, the same contact
        pixels, k within 3e-5 (relative); about 0.6× the time on the CPU.
    hardness : float
        Hardness H (Pa), the local pressure cap, in (0, inf]; ``inf`` (default): elastic.
    {warp_device_obj}
    devices : list, int or "auto", optional
        One device given as a list of one or a count of 1, or ``"auto"`` where the solver fits
        this device (:func:`~warptrunc.contact.sharded.devices.choose_devices`). A map spread
        over several devices is a :class:`~warptrunc.contact.sharded.ShardedContactSolver`,
        made by :func:`~warptrunc.contact.factory.contact_solver` (which picks this class or
        that one); here such ``devices`` are refused. None (default): ``device``.

    Raises
    ------
    ValueError
        Non-finite or non-2-D heights, parameters out of range; ``devices`` that name several
        devices; an adhesion law with a finite hardness or with ``load_control="secant"``.
    MemoryError
        When the estimated memory (:meth:`memory_bytes`) exceeds the device's free memory,
        before anything is allocated.
    """

    def __init__(
        self,
        heights: Any,
        pixel_size: Any,
        contact_modulus: float,
        *,
        settings: SolverSettings | None = None,
        hardness: float = math.inf,
        device: wp.DeviceLike = None,
        devices: Any = None,
    ) -> None:
        if settings is None:
            settings = SolverSettings()
        elif not isinstance(settings, SolverSettings):
            raise ValueError(f"settings must be a SolverSettings, got {type(settings).__name__}")
        self.settings = settings
        self.adhesion = adhesion = settings.adhesion
        """The interaction law (``settings.adhesion``, an
        :class:`~warptrunc.contact.adhesion.Adhesion`)."""
        self.hardness = float(check_value(Material, "hardness", hardness))
        if adhesion.active and math.isfinite(self.hardness):
            raise ValueError(
                f"adhesion ({adhesion.law}) with a finite hardness ({self.hardness:g} Pa) is not "
                "solved: the pressure cap bounds the wall's reaction, and the plastic flow "
                "changes the heights the adhesive solve pulls on; give hardness = inf"
            )
        if adhesion.active and settings.load_control == "secant":
            raise ValueError(
                f"adhesion ({adhesion.law}) finds the approach of a load inside each "
                "non-adhesive solve (load_control='offset'): the secant assumes a load that "
                "grows with the approach, which an adhesive curve does not"
            )
        check_height_map(heights)
        h = np.asarray(heights, dtype=np.float64)
        dx, dy = pair("pixel_size", pixel_size)
        check_range("pixel_size", dx, 0.0, unit="m")
        check_range("pixel_size", dy, 0.0, unit="m")
        self.contact_modulus = check_range("contact_modulus", contact_modulus, 0.0, unit="Pa")
        substrate, dtype = settings.substrate, settings.dtype
        self.pressure_tol = settings.pressure_tol
        self.pentol = default_pentol(h) if settings.pentol is None else settings.pentol
        if self.pentol == 0.0:
            self.pentol = 1e-3 * max(float(np.ptp(h)), dx)  # a flat map: a fraction of its scale
        self.thermotol = settings.thermotol
        self.load_control = settings.load_control
        self.maxiter = settings.maxiter
        self.refresh = settings.refresh
        if devices is not None:  # one device (several: contact_solver, ShardedContactSolver)
            from .sharded.devices import choose_devices, single_device

            if type(self) is ContactSolver and choose_devices(
                devices, np.shape(heights), settings, device
            ):
                raise ValueError(
                    f"devices={devices!r} spreads the map over several devices: make the solver "
                    "with warptrunc.contact.contact_solver(..., devices=...), which returns a "
                    "ShardedContactSolver for several devices and this class for one"
                )
            device = single_device(devices, device)
        self.device = resolve_device(device)
        direct_max = settings.direct_max
        if direct_max is None:
            direct_max = 24 if self.device.is_cuda else 4
        self.direct_max = int(direct_max)
        self.shape = h.shape
        self.pixel_size = (dx, dy)
        self.substrate = substrate
        self.dtype = dtype
        self.forcetol = self.pressure_tol * self.contact_modulus * dx * dy
        plan = self._fft_plan_that_fits(h.shape, settings)  # or MemoryError, before allocating
        self._allocate(h, plan)
        self.offset = 0.0
        self.plastic_frozen = False
        self.plastic_volume = 0.0  # Σ plastic displacement·dx·dy (m³)
        self._depth: float | None = None  # approach of the last solve (m)
        # (δ (m), F (N), also on the capped curve) of the last converged solve
        self._point: tuple[float, float, bool] | None = None
        self._slope: float | None = None  # dF/dδ at or near the last solution (N/m)
        self._trial_failed = False  # an elastic trial of a capped load solve exceeded H
        self._approach_hint: float | None = None  # where the first load solve starts (m)

    def _allocate(self, h: np.ndarray, plan: str) -> None:
        """The half-space and the device maps of the map ``h`` (m), with the cuFFT ``plan``
        (:class:`~warptrunc.contact.sharded.ShardedContactSolver` allocates its own)."""
        dx, dy = self.pixel_size
        substrate, dtype = self.substrate, self.dtype
        self.fft_plan = plan
        """The cuFFT plans in use (``warptrunc.contact.halfspace.FFT_PLANS``; 'pruned' off
        CUDA and on the periodic substrate)."""
        self.hs = ElasticHalfSpace(
            h.shape,
            (dx, dy),
            self.contact_modulus,
            substrate=substrate,
            dtype=dtype,
            device=self.device,
            fft_plan=plan,
        )
        sc, _, npd = DTYPES[dtype]
        dev = self.device
        self.h_max = float(h.max())
        h_dev = h.astype(npd)
        self.h = wp.array(h_dev, dtype=sc, device=dev)
        # the original map as stored on the device (host copy): plastic displacement = h0 − h
        self._h0 = h_dev if math.isfinite(self.hardness) else None
        self.q_buf, self.q = self.hs.map_buffer()  # forces (N) on the map (no pad stored)
        self.t_buf, self.t = self.hs.map_buffer()  # CG direction (m)
        self.u = wp.zeros(h.shape, dtype=sc, device=dev)
        self.mask = wp.zeros(h.shape, dtype=wp.uint8, device=dev)
        self.lin = wp.zeros(
            h.shape, dtype=sc, device=dev
        )  # q before the projection, where it acted
        if self.adhesion.active:
            self._allocate_adhesion(h_dev)
        lanes = self.hs.reduction.lanes
        self.lane_count = wp.zeros(lanes, dtype=wp.int32, device=dev)
        self.lane_offset = wp.zeros(lanes, dtype=wp.int32, device=dev)
        self.change_index = wp.zeros(max(1, self.direct_max), dtype=wp.int32, device=dev)
        self.change_value = wp.zeros(max(1, self.direct_max), dtype=wp.float64, device=dev)
        self.tau = wp.zeros(1, dtype=wp.float64, device=dev)

    # the memory model (:mod:`warptrunc.contact.memory`), named here so that the API reference
    # lists it with the solver (autodoc shows a class's own members only)
    memory_terms = staticmethod(memory_terms)
    memory_bytes = staticmethod(memory_bytes)

    def _fft_plan_that_fits(self, shape: tuple[int, int], settings: SolverSettings) -> str:
        """The cuFFT plans of a map of ``shape`` on this device, or MemoryError before anything
        is allocated (:func:`~warptrunc.contact.memory.fft_plan_that_fits`; the solver over
        several devices checks each device's share instead)."""
        return fft_plan_that_fits(self.device, shape, settings)

    # --- one solve ---------------------------------------------------------------------------

    def solve(
        self, depth: float | None = None, *, load: float | None = None, plastic: bool | None = None
    ) -> ContactState:
        """Solve at approach ``depth`` δ (m) or total ``load`` F (N), warm-started.

        With a finite hardness the pressure is capped at H and, once converged, the heights
        flow where p = H (the plastic state grows; see the module docstring). Unloading (a solve
        at a smaller δ or F) is elastic from the deformed surface.

        Parameters
        ----------
        depth : float, optional
            Approach δ of the flat from first touch at the highest pixel of the original map (m).
        load : float, optional
            Total normal load (N), instead of ``depth``. How the approach is found is
            ``settings.load_control``: ``"offset"`` moves the rigid offset inside the CG
            (ContactMechanics'; with the cap, an elastic trial kept when no pixel exceeds H,
            else the secant from it); ``"secant"`` runs a secant on the approach over
            displacement-controlled solves (from the last converged solution, with the slope
            of the last secant or of :meth:`punch_stiffness`).
        plastic : bool, optional
            False: an elastic solve of the current (deformed) surface with the plastic state
            frozen and no pressure cap (for unloading); True: capped and flowing. Default: not
            ``plastic_frozen`` (see :meth:`freeze_plastic`). Irrelevant when H = inf.

        Returns
        -------
        ContactState
            Load, contact and plastic areas, plastic volume and the solve's convergence record.

        Raises
        ------
        ValueError
            Neither or both of depth and load, or a load ≤ 0.
        FloatingPointError
            When the residual becomes NaN/inf.
        """
        if (depth is None) == (load is None):
            raise ValueError("give exactly one of depth (m) and load (N)")
        if self.adhesion.active:  # any finite approach or load, tensile ones too
            if depth is None:
                return self._solve_adhesive(None, check_range("load", load, unit="N"))
            return self._solve_adhesive(check_range("depth", depth, unit="m"), None)
        if load is not None:
            load = check_range("load", load, 0.0, unit="N")
        else:
            depth = float(depth)
        if plastic is None:
            plastic = not self.plastic_frozen
        secant = load is not None and self.load_control == "secant"
        if math.isinf(self.hardness):
            info = (
                self._solve_load_secant(load, capped=False)
                if secant
                else (self._solve_elastic(depth, load))
            )
            self._point = self._point_of(info, capped=True)
            return self._state(info, None)
        if not plastic:
            info = (
                self._solve_load_secant(load, capped=False)
                if secant
                else (self._solve_elastic(depth, load))
            )
            flow = self._flow(apply=False)
            # below the cap everywhere, the elastic solution is the capped one at that approach
            self._point = self._point_of(info, capped=flow[1] == 0)
            return self._state(info, flow)
        if load is None:
            info = self._solve_capped(depth - self.h_max)
        elif secant:
            info = self._solve_load_secant(load, capped=True)
        else:
            info = self._solve_load_trial(load)
        state = self._state(info, self._flow(apply=info["converged"]))
        # a converged loading state is a solution of the capped problem on the flowed surface
        self._point = self._point_of(info, capped=True)
        return state

    # --- elastic–perfectly-plastic solves -------------------------------------------------------

    def freeze_plastic(self, frozen: bool = True) -> None:
        """Freeze (or release) the plastic state: while frozen, :meth:`solve` is elastic on the
        deformed surface without the pressure cap (an unloading).

        Parameters
        ----------
        frozen : bool
            True freezes, False lets the surface flow again at p = H.
        """
        self.plastic_frozen = bool(frozen)

    def plastic_displacement(self) -> np.ndarray:
        """The plastic height change so far, copied to the host (a synchronisation point).

        Returns
        -------
        (ny, nx) ndarray of float64
            Height removed by plastic flow, w = h_original − h_deformed ≥ 0 (m); zeros when
            H = inf.
        """
        if self._h0 is None:
            return np.zeros(self.shape)
        return self._h0.astype(np.float64) - self.h.numpy().astype(np.float64)

    def reset(self) -> None:
        """Forget the solution, the plastic state and the adhesive forces: original heights,
        zero forces."""
        if self._h0 is not None:
            self.h.assign(self._h0)
        for a in (self.q_buf, self.t_buf, self.u, self.mask, self.lin):
            a.zero_()
        if self.adhesion.active:
            self._reset_adhesion()
        self.offset = 0.0
        self.plastic_volume = 0.0
        self._depth = None
        self._point = None
        self._slope = None
        self._trial_failed = False
        self._approach_hint = None

    def hint_approach(self, depth: float | None) -> None:
        """Start the first load-controlled solve near the approach ``depth``.

        A solution of the same contact known elsewhere — on a coarser grid of the same surface
        (:mod:`warptrunc.indent.refine`) — starts the offset iteration (and, with a hardness,
        the elastic trial and the secant) there instead of at first touch. It only moves the
        start: the solve's answer is the same. Unused once the solver has a solution of its own.

        Parameters
        ----------
        depth : float or None
            Approach δ from first touch at the highest pixel of the map (m); None forgets it.
        """
        self._approach_hint = None if depth is None else float(depth)

    # --- after a solve -----------------------------------------------------------------------

    def punch_stiffness(self, rtol: float | None = None) -> tuple[float, int, bool]:
        """Barber's incremental stiffness of the current contact: a rigid flat punch shaped like
        the contact set, K·x = 1 m on the set, solved by linear CG (preconditioned with c·K⁻¹·c
        under ``algorithm="bccg"`` when the set covers more than ``settings.precondition_above``
        of the map (by default 2 %); :mod:`warptrunc.contact.iteration.punch`); k = Σx (N/m).

        Parameters
        ----------
        rtol : float, optional
            Relative rms residual to stop at (dimensionless); default 1e-10 (float64) or 1e-5
            (float32).

        Returns
        -------
        (float, int, bool)
            Stiffness k (N/m), CG iterations, converged. A converged k is also the slope with
            which the next secant load control (:meth:`solve` with ``load``) takes its first
            step: it is dF/dδ of unloading from the current solution.
        """
        return self._punch_solve(rtol)

    def max_pressure(self) -> float:
        """The largest contact pressure of the current solution, reduced on the device.

        Returns
        -------
        float
            max(q)/(dx·dy) (Pa), 0 without contact; a synchronisation point (one number is
            read back). Below the hardness H no pixel is capped: that solution is also the
            elastic–perfectly-plastic one. With adhesion the largest whole traction (the
            wall's reaction plus the law's), not below 0.
        """
        if self.adhesion.active:
            return max(0.0, float(self.maps()[0].max()))
        red = self.hs.reduction
        red.launch(_k.max_force_kernel, self.shape[0] * self.shape[1], [self.q], [])
        dx, dy = self.pixel_size
        return float(red.read((True,))[0]) / (dx * dy)

    def contact_map(self) -> np.ndarray:
        """The contact set of the current solution, copied to the host as booleans.

        Returns
        -------
        (ny, nx) ndarray of bool
            Pixels with a positive force (with adhesion: a positive reaction of the wall, the
            repulsive contact); a synchronisation point.
        """
        return self.q.numpy() > 0

    def maps(self) -> tuple[np.ndarray, np.ndarray]:
        """Copy the pressure and gap maps of the current solution to the host.

        Reads the device back (a synchronisation point).

        Returns
        -------
        pressure : (ny, nx) ndarray of float64
            Pressure (Pa): the pixel forces (N) divided by the pixel area dx·dy (m²); with
            adhesion the whole traction, the wall's reaction plus the law's (tensile
            negative).
        gap : (ny, nx) ndarray of float64
            Gap (m): displacement u minus heights h minus the rigid offset of the last solve,
            u − h − offset (ContactMechanics' sign; with adhesion u and h are the wall's
            displacement and the effective heights, whose difference is the gap of the whole
            traction).
        """
        sc = DTYPES[self.dtype][0]
        out = []
        for src in (self.q, self.u):
            dst = wp.empty(self.shape, dtype=sc, device=self.device)
            wp.launch(
                _k.copy_map_kernel, dim=self.shape, inputs=[src], outputs=[dst], device=self.device
            )
            out.append(dst.numpy().astype(np.float64))  # sync point
        q, u = out
        if self.adhesion.active:
            q = self._adhesive_pressure(q)
        h = self.h.numpy().astype(np.float64)
        dx, dy = self.pixel_size
        return q / (dx * dy), u - h - self.offset

