# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One contact problem over several devices: :class:`ShardedContactSolver`.

``contact_solver(..., devices=[...])`` (or ``devices=N``, ``devices="auto"``) returns one when the
map is spread over two or more devices, so every entry point that takes a
:class:`~warptrunc.contact.ContactSolver` takes it (it *is* one: a subclass). A subclass rather
than a branch inside the one-device solver because the state lives elsewhere (JAX arrays in row
slabs, not Warp arrays on one device) while everything above the iteration is shared: ``solve``
(displacement and load control, the offset and secant load controls, the elastic trial and the
secant of the capped solves), the stopping tests (``SolveLoop._steady``), the records of a
solve, the warm start's choice of approach and the preconditioner's rule are the one-device
solver's own methods, inherited. What is re-written here is the BCCG iteration
(:mod:`warptrunc.contact.iteration.bccg`, the default ``algorithm``) and its per-pixel steps, line for line,
plus Barber's punch, the plastic flow and the read-backs.

Engine and layout: :mod:`warptrunc.contact.sharded.fft` (JAX/XLA, row slabs, two all-to-alls per
convolution). The per-pixel work is ``jax.numpy`` on the slabs (``jax.jit``; XLA fuses each step
into a few kernels per device), not Warp kernels: handing JAX's buffers to Warp (DLPack) inside
one step would split every step into separate programmes and host calls; and the sums (loads,
dot products, counts) are ``jnp`` sums over the sharded maps, which XLA turns into all-reduces.
Sums and maxima are float64, as on one device; the order of the additions differs, so results
agree to round-off, not bit for bit.

The one difference of the iteration: the projection's force changes are never summed directly
over the real-space influence table (``direct_max`` is 0: the table would have to be whole on
every device); u = K·q is transformed afresh instead whenever the projection changed a force.
The one-device solver with ``direct_max=0`` runs the same iteration (``tests/test_sharded.py``
compares them); with its default ``direct_max`` the two agree within the solver's tolerances.
Only ``algorithm="bccg"`` (the default) is spread.
"""

from __future__ import annotations

import inspect
import math
from typing import Any

import numpy as np

from ..._support.docs import fill_doc
from ..iteration.bccg import _HUGE
from ..solver import ContactSolver
from .fft import ShardedHalfSpace
from .grid import SHARDED_DOCS, host_array, sharded_memory_terms

__all__ = ["ShardedContactSolver"]


def _is_free(jnp, q, g, hf):
    """The BCCG free set (``warptrunc.kernels.contact.bccg.is_free``), float64 arguments."""
    return ((q > 0) & (q < hf)) | ((q <= 0) & (g < 0)) | ((q >= hf) & (g > 0))


class ShardedContactSolver(ContactSolver):
    """A :class:`~warptrunc.contact.ContactSolver` whose map is split in row slabs over several
    JAX devices (module docstring); made by ``contact_solver(..., devices=...)``.

    Parameters
    ----------
    heights : (ny, nx) array_like
        Heights z (m); ny a multiple of the number of devices.
    pixel_size : float or (float, float)
        Pixel sides (dx, dy) (m).
    contact_modulus : float
        Contact modulus E* (Pa).
    settings : SolverSettings, optional
        As for :class:`~warptrunc.contact.ContactSolver`; ``algorithm`` must be ``"bccg"`` and
        ``adhesion`` non-adhesive (the adhesive solve runs on one device); ``direct_max`` and
        ``fft_plan`` are not used (module docstring).
    hardness : float
        Hardness H (Pa), in (0, inf].
    device : str or warp Device, optional
        Unused (the Warp device of the one-device solver); kept for the shared signature.
    devices : list, int or "auto"
        The JAX devices (``jax.Device`` objects, or names ``"cuda:0"``, ``"gpu:1"``,
        ``"cpu:0"``), a count (the first N of JAX's default backend) or ``"auto"``
        (:func:`~warptrunc.contact.sharded.devices.choose_devices`).

    Raises
    ------
    ValueError
        A bad ``devices`` (the message names the value and what is allowed), ny not a multiple
        of the device count, ``algorithm="pk"``, an adhesion law.
    ImportError
        Without JAX.
    MemoryError
        When one device's share exceeds its free memory, before anything is allocated.
    """

    def __init__(
        self,
        heights: Any,
        pixel_size: Any,
        contact_modulus: float,
        *,
        settings: Any = None,
        hardness: float = math.inf,
        device: Any = None,
        devices: Any = 2,
    ) -> None:
        from .devices import choose_devices, mark_spread

        law = getattr(settings, "adhesion", None)
        if law is not None and law.active:
            raise ValueError(f"adhesion ({law.law}) runs on one device: give one device")

        shape = np.shape(heights)
        self._jax_devices = choose_devices(devices, shape, settings, device)
        if self._jax_devices is None or len(self._jax_devices) < 2:
            raise ValueError(
                f"devices: a ShardedContactSolver needs two or more devices, got {devices!r}; "
                "use ContactSolver for one"
            )
        mark_spread()  # an XLA runtime error ends the command at once (warptrunc.cli)
        super().__init__(
            heights,
            pixel_size,
            contact_modulus,
            settings=settings,
            hardness=hardness,
            device=device,
        )
        self.direct_max = 0  # the projection's changes: transformed afresh (module docstring)

    # --- construction hooks of ContactSolver.__init__ -------------------------------------

    def _fft_plan_that_fits(self, shape: tuple[int, int], settings: Any) -> str:
        """Check each device's share against its free memory (MemoryError before allocating),
        after Warp's pools gave back what they keep cached on the GPUs (JAX allocates next)."""
        from ..._support.device import release_kept_pools
        from .devices import check_fits

        release_kept_pools()
        check_fits(shape, settings.substrate, settings.dtype, self._jax_devices)
        return "pruned"

    def _allocate(self, h: np.ndarray, plan: str) -> None:
        """The half-space and the maps, in row slabs over the devices."""
        if self.settings.algorithm != "bccg":
            raise ValueError(
                f"settings.algorithm must be 'bccg' for a solve over several devices, got "
                f"{self.settings.algorithm!r}"
            )
        self.fft_plan = plan
        self.hs = ShardedHalfSpace(
            h.shape,
            self.pixel_size,
            self.contact_modulus,
            substrate=self.substrate,
            dtype=self.dtype,
            devices=self._jax_devices,
        )
        self.jax, self.jnp = self.hs.jax, self.hs.jnp
        self.h_max = float(h.max())
        h_dev = h.astype(self.hs.np_dtype)
        self.h = self.hs.put(h_dev)
        self._h0 = h_dev if math.isfinite(self.hardness) else None
        self.q, self.u, self.t, self.r, self.z_old = (self.hs.zeros() for _ in range(5))
        self.mask = self.hs.zeros(np.bool_)

    # --- jitted steps -----------------------------------------------------------------------

    def _fn(self, name: str):
        """The jitted step ``name`` (made once per solver)."""
        steps = self.hs.layout.steps
        fn = steps.get(name)
        if fn is None:
            from .steps import make_step

            fn = steps[name] = make_step(self.hs.layout, name)
        return fn

    def _read(self, values: Any) -> list[float]:
        """Read device scalars back to the host (a synchronisation point)."""
        parts = values if isinstance(values, list | tuple) else [values]
        return [float(x) for v in parts for x in host_array(v).reshape(-1)]

    # --- the shared loop's primitives (SolveLoop, BCCGSolves) ------------------------------

    def _sums(self, offset: float) -> np.ndarray:
        return np.array(self._read(self._fn("sums")(self.q, self.u, self.h, offset)))

    def _warm_start(self, offset: float) -> None:
        self.q, self.u = self._fn("warm_start")(self.q, self.u, self.h, offset, self.hs.spectrum)

    def _scale_to_load(self, load: float, total: float) -> bool:
        n_map = self.shape[0] * self.shape[1]
        if total > 0.0:
            self.q, self.u = self._fn("scale")(self.q, self.u, load / total)
            return True
        self.mask = self.hs.full(True, np.bool_)
        self.q = self._fn("fill")(self.q, load / n_map)
        return False

    def _exact_u(self) -> float:
        self.u, du = self._fn("exact_u")(self.q, self.u, self.hs.spectrum)
        return self._read([du])[0]

    def _solve_bccg(self, offset: float, load: float | None, cap: float | None) -> dict[str, Any]:
        """``BCCGSolves._solve_bccg`` (:mod:`warptrunc.contact.iteration.bccg`), step for step, on the
        slabs (``direct_max`` 0)."""
        n_map = self.shape[0] * self.shape[1]
        hf = _HUGE if cap is None else float(cap)
        load_control = load is not None
        pc_above = self._precondition_above()
        w = self.hs.spectrum
        self._warm_start(offset)
        self.q = self._fn("clamp")(self.q, hf)
        total = float(self._sums(offset)[3])
        if load_control:
            self._scale_to_load(load, total)
            total = float(load)
        self._exact_u()
        n_transforms = 4
        self.t, self.z_old = self.hs.zeros(), self.hs.zeros()
        rz_old = None
        last_pc = None
        du = None
        viol = 0.0
        last: dict[str, float] = {}  # the previous iteration's total and height
        info: dict[str, Any] = {"converged": False}
        for it in range(1, self.maxiter + 1):
            set_offset = offset
            if load_control:
                n_f, s_g = self._read(self._fn("free_sums")(self.q, self.u, self.h, offset, hf))
                if n_f > 0:
                    offset = offset + s_g / n_f
            self.r, self.mask, sums = self._fn("residual")(
                self.q, self.u, self.h, set_offset, offset, hf
            )
            sums = self._read(sums)
            n_f, s_r = float(sums[0]), float(sums[1])
            info, stop = self._bccg_stop(
                sums, offset, total, load, du, viol, it, n_transforms, last
            )
            if stop:
                break
            use_pc = n_f > pc_above * n_map
            if use_pc != last_pc:
                rz_old = None
            last_pc = use_pc
            z, dots = self._fn("precondition" if use_pc else "dots")(
                self.r, self.z_old, self.mask, w
            )
            if use_pc:
                n_transforms += 2
            s_z, rz, rzo = self._read(dots)
            mean = s_z / n_f if load_control else 0.0
            rz -= mean * s_r
            beta = 0.0
            if rz_old is not None and rz_old > 0.0:
                beta = max(0.0, (rz - rzo) / rz_old)
            rz_old = rz
            self.t, self.z_old, self.q, self.u, sums = self._fn("step")(
                z, mean, beta, self.mask, self.r, self.t, self.q, self.u, n_f, hf, w
            )
            del z
            n_transforms += 2
            n_proj, viol, total, du = self._read(sums)
            exact = it % self.refresh == 0 or n_proj > self.direct_max
            if load_control:
                if not self._scale_to_load(load, total):
                    exact = True
                total = float(load)
            if exact:
                du = max(du, self._exact_u())
                n_transforms += 2
        self.offset = offset
        return info

    # --- plastic flow, Barber's punch, read-backs --------------------------------------------

    def _flow(self, apply: bool) -> tuple[int, int]:
        self.h, sums = self._fn("flow")(self.q, self.u, self.h, self.offset, self._cap, apply)
        n_c, n_p, s_dw = self._read(sums)
        dx, dy = self.pixel_size
        self.plastic_volume += s_dw * dx * dy
        return int(n_c), int(n_p)

    def _punch_solve(self, rtol: float | None = None) -> tuple[float, int, bool]:
        """:meth:`~warptrunc.contact.ContactSolver.punch_stiffness` on the slabs: Barber's
        punch by CG, preconditioned with c·K⁻¹·c on a contact set above
        ``_precondition_above(barber=True)`` of the map (:mod:`warptrunc.contact.iteration.punch`)."""
        if rtol is None:
            rtol = 1e-10 if self.dtype == "float64" else 1e-5
        w = self.hs.spectrum
        self.t = self.r = self.z_old = None  # free between solves: d, res and x take them
        self.mask, x, res, n_set = self._fn("punch_start")(self.q)
        n_set = self._read([n_set])[0]
        k, it, ok = 0.0, 0, n_set == 0
        n_map = self.shape[0] * self.shape[1]
        pc = n_set > self._precondition_above(barber=True) * n_map
        step, pc_fn, cg_fn = self._fn("punch_step"), self._fn("punch_pc"), self._fn("punch_cg")
        if pc:  # d = c·K⁻¹·res, rz = res·z on the set
            d, rz = pc_fn(res, res, self.mask, 0.0, w)
            rz = self._read([rz])[0]
        else:
            d, rz = res + 0, n_set
        for it in range(1, self.maxiter + 1 if n_set > 0 else 1):  # noqa: B007
            x, res, sums = step(x, res, d, self.mask, rz, w)
            d_k_d, rr_new, k = self._read(sums)
            if not d_k_d > 0.0:
                break
            if math.sqrt(rr_new / n_set) < rtol:
                ok = True
                break
            if pc:
                d, rz_new = pc_fn(res, d, self.mask, rz, w)
                rz_new = self._read([rz_new])[0]
            else:
                d, rz_new = cg_fn(res, d, self.mask, rr_new / rz, w), rr_new
            rz = rz_new
        if n_set == 0:
            it = 0
        del d, res
        self.r = self.hs.zeros()
        self.z_old = x  # q_lin's map is scratch between solves (as on one device)
        self.t = self.hs.zeros()
        if ok and k > 0:
            self._slope = float(k)
        return float(k), it, ok

    @property
    def device_names(self) -> list[str]:
        """The devices the map is spread over, by name (``"cuda:0"``, ``"cpu:1"``, ...)."""
        return [f"{'cuda' if d.platform == 'gpu' else d.platform}:{d.id}" for d in self.hs.devices]

    def max_pressure(self) -> float:
        """The largest contact pressure of the current solution.

        Returns
        -------
        float
            max(q)/(dx·dy) (Pa), 0 without contact; a synchronisation point.
        """
        qm = self._read([self._fn("max_force")(self.q)])[0]
        dx, dy = self.pixel_size
        return qm / (dx * dy)

    def maps(self) -> tuple[np.ndarray, np.ndarray]:
        """Copy the pressure and gap maps of the current solution to the host (gathers the
        slabs: the whole map in host memory).

        Returns
        -------
        pressure : (ny, nx) ndarray of float64
            Pressure (Pa): pixel forces (N) over the pixel area dx·dy (m²).
        gap : (ny, nx) ndarray of float64
            Gap u − h − offset (m).
        """
        q, u, h = (host_array(a).astype(np.float64) for a in (self.q, self.u, self.h))
        dx, dy = self.pixel_size
        return q / (dx * dy), u - h - self.offset

    def contact_map(self) -> np.ndarray:
        """The contact set of the current solution, gathered to the host as booleans (1 B/px,
        where :meth:`maps` gathers pressure and gap in float64, 16 B/px).

        Returns
        -------
        (ny, nx) ndarray of bool
            Pixels with a positive force.
        """
        return host_array(self.q > 0)

    def plastic_displacement(self) -> np.ndarray:
        """The plastic height change so far, copied to the host.

        Returns
        -------
        (ny, nx) ndarray of float64
            h_original − h_deformed ≥ 0 (m); zeros when H = inf.
        """
        if self._h0 is None:
            return np.zeros(self.shape)
        return self._h0.astype(np.float64) - host_array(self.h).astype(np.float64)

    def reset(self) -> None:
        """Forget the solution and the plastic state: original heights, zero forces."""
        if self._h0 is not None:
            self.h = self.hs.put(self._h0)
        self.q, self.u, self.t, self.r, self.z_old = (self.hs.zeros() for _ in range(5))
        self.mask = self.hs.zeros(np.bool_)
        self.offset = 0.0
        self.plastic_volume = 0.0
        self._depth = None
        self._point = None
        self._slope = None
        self._trial_failed = False
        self._approach_hint = None

    @staticmethod
    @fill_doc(SHARDED_DOCS)
    def memory_terms_per_device(
        shape: tuple[int, int], substrate: str = "free", dtype: str = "float64", n_devices: int = 2
    ) -> dict[str, int]:
        """Bytes one device holds, term by term
        (:func:`~warptrunc.contact.sharded.grid.sharded_memory_terms`).

        Parameters
        ----------
        {shape}
        {substrate}
        {dtype}
        {n_devices}

        Returns
        -------
        dict of str to int
            The terms (B).
        """
        return sharded_memory_terms(shape, substrate, dtype, n_devices)


# the constructor's signature is its own __init__'s (ContactSolver's __new__ only picks a class)
ShardedContactSolver.__signature__ = inspect.signature(ShardedContactSolver.__init__).replace(
    parameters=list(inspect.signature(ShardedContactSolver.__init__).parameters.values())[1:]
)
