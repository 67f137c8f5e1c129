# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Height maps: the :class:`Surface` result object and :func:`from_heights`.

One way in and out: :func:`from_heights` wraps an array, :func:`warptrunc.read_height_map`
reads a file and :func:`warptrunc.write_height_map` writes one (``warptrunc.io``);
:func:`warptrunc.wm_surface` synthesises a Weierstrass–Mandelbrot surface (``warptrunc.wm``).
The :class:`Surface` constructor is the low-level one those functions use. Everything here is
validation (on the host, or one device reduction for a device map) and bookkeeping.
"""

from __future__ import annotations

import math
import sys
from typing import Any

import numpy as np
import warp as wp

from ._support.device import check_memory, resolve_device
from ._support.outputs import jsonable
from ._support.validate import check_height_map, check_range
from .kernels import reduce as _kr

__all__ = ["Surface", "from_heights"]


class Surface:
    """A height map on a regular grid, kept where it was made.

    Heights are ``z[iy, ix]`` at ``x = ix·dx``, ``y = iy·dy`` (pixel corner at the origin).

    ``heights`` may be a NumPy array (a user's map: validated on the host, uploaded once per
    device on demand by :meth:`device_heights`) or a 2-D float32 Warp array (as made by
    :func:`warptrunc.wm_surface`: it stays on its device, validated by one device reduction, and
    a host copy is made only when a host consumer reads :attr:`heights`).

    Parameters
    ----------
    heights : (ny, nx) ndarray or warp array
        Heights z (m). NumPy input is converted to C-contiguous float32; a Warp array must be a
        contiguous 2-D float32 array and is not copied (the surface then owns it: do not write
        to it afterwards).
    dx, dy : float
        Pixel spacings along x and y (m).
    params : dict, optional
        Generation or provenance parameters (SI units; JSON-serialisable).
    """

    def __init__(
        self,
        heights: Any,
        dx: float,
        dy: float,
        params: dict[str, Any] | None = None,
    ) -> None:
        set_ = object.__setattr__
        set_(self, "_dev", {})
        set_(self, "_extremes", None)
        if _is_warp_array(heights):
            z = _check_device_map(heights)
            set_(self, "_host", None)
            set_(self, "_home", str(z.device))
            self._dev[str(z.device)] = z
            set_(self, "_extremes", _validate_on_device(z))
        else:
            z = check_height_map(heights)
            z.setflags(write=False)
            set_(self, "_host", z)
            set_(self, "_home", None)
        set_(self, "dx", check_range("dx", dx, 0.0, unit="m"))
        set_(self, "dy", check_range("dy", dy, 0.0, unit="m"))
        set_(self, "params", dict(params or {}))

    @classmethod
    def _on_device(
        cls,
        z: Any,
        dx: float,
        dy: float,
        params: dict[str, Any],
        extremes: tuple[float, float],
    ) -> Surface:
        """A device surface whose exact (min z, max z) are already known (the WM generator
        records them): no validation reduction when both are finite, since every height lies
        between them; otherwise the usual validation."""
        lo, hi = (float(v) for v in extremes)
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            return cls(z, dx, dy, params)
        self = cls.__new__(cls)
        set_ = object.__setattr__
        z = _check_device_map(z)
        set_(self, "_dev", {str(z.device): z})
        set_(self, "_host", None)
        set_(self, "_home", str(z.device))
        set_(self, "_extremes", (lo, hi))
        set_(self, "dx", check_range("dx", dx, 0.0, unit="m"))
        set_(self, "dy", check_range("dy", dy, 0.0, unit="m"))
        set_(self, "params", dict(params or {}))
        return self

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"Surface is immutable; cannot set {name!r}")

    def __repr__(self) -> str:
        where = self._home or "host"
        return f"Surface({self.ny}×{self.nx}, dx={self.dx!r} m, dy={self.dy!r} m, on {where})"

    # --- where the heights live --------------------------------------------------------------

    @property
    def heights(self) -> np.ndarray:
        """(ny, nx) float32 heights z (m) as a read-only NumPy array.

        For a device-resident surface the host copy is made on first access (one device →
        host transfer, a sync point) and kept; prefer :meth:`device_heights` in device code.
        """
        if self._host is None:
            src = self._dev[self._home]
            # a CPU-device array's .numpy() is a view of the device memory: copy it
            z = np.array(src.numpy(), copy=True) if src.device.is_cpu else src.numpy()
            z.setflags(write=False)
            object.__setattr__(self, "_host", z)
        return self._host

    @property
    def device(self) -> str | None:
        """The Warp device holding the original heights (``"cpu"``, ``"cuda:0"``, ...), or
        None when they are a host NumPy array."""
        return self._home

    @property
    def has_host_copy(self) -> bool:
        """True once the NumPy heights exist (always for a surface made from NumPy)."""
        return self._host is not None

    def device_heights(self, device: Any = None) -> Any:
        """The heights as a (ny, nx) float32 Warp array on ``device`` (m), read-only by contract.

        ``None`` means the surface's own device when it is device-resident, else
        :func:`warptrunc.resolve_device`'s default. A copy on another device is made once
        (host → device upload, or device → device copy) and cached on the surface.

        Parameters
        ----------
        device : str or warp.context.Device, optional
            Target Warp device; None for the default above.

        Returns
        -------
        warp.array2d of float32
            (ny, nx) heights z (m). On a CPU device made from a host map it shares the host
            buffer (no copy); do not write to it.

        Raises
        ------
        MemoryError
            The copy would not fit the device's free memory (checked before allocating).
        """


        dev = device if isinstance(device, wp.Device) else None  # resolved by the caller
        if dev is None:
            dev = resolve_device(self._home if device is None else device)
        key = str(dev)
        z = self._dev.get(key)
        if z is None:
            check_memory(4 * self.nx * self.ny, dev, "the height map")
            if self._home is not None and self._host is None:
                src = self._dev[self._home]
                z = wp.empty(src.shape, dtype=wp.float32, device=dev)
                wp.copy(z, src)
            elif dev.is_cpu:  # share the read-only host buffer (kernels never write heights)
                z = wp.array(self.heights, dtype=wp.float32, device=dev, copy=False)
            else:
                z = wp.array(self.heights, dtype=wp.float32, device=dev)
            self._dev[key] = z
        return z

    def release_device_copies(self) -> Surface:
        """Keep the heights on the host only: make the host copy (one device → host transfer)
        and drop every device copy, so that Warp can give their memory back (before another
        allocator, JAX's for a solve over several devices, takes the same GPUs).

        Returns
        -------
        Surface
            This surface, now host-resident (:attr:`device` is None); the heights are the same
            values, and a later :meth:`device_heights` uploads them again.
        """
        self.heights  # noqa: B018 - makes the host copy
        self._dev.clear()
        object.__setattr__(self, "_home", None)
        return self

    def extremes(self) -> tuple[float, float]:
        """(min z, max z) (m), float32 values as Python floats; from the validation reduction
        for a device surface, else one NumPy pass (cached).

        Returns
        -------
        tuple of (float, float)
            Lowest and highest height (m).
        """
        if self._extremes is None:
            z = self._host
            object.__setattr__(self, "_extremes", (float(z.min()), float(z.max())))
        return self._extremes

    def _cached_extremes(self) -> tuple[float, float] | None:
        return self._extremes

    def _cache_extremes(self, lo: float, hi: float) -> None:
        object.__setattr__(self, "_extremes", (float(lo), float(hi)))

    @property
    def shape(self) -> tuple[int, int]:
        """(ny, nx)."""
        if self._host is not None:
            return (int(self._host.shape[0]), int(self._host.shape[1]))
        s = self._dev[self._home].shape
        return (int(s[0]), int(s[1]))

    @property
    def ny(self) -> int:
        """Number of pixels along y."""
        return self.shape[0]

    @property
    def nx(self) -> int:
        """Number of pixels along x."""
        return self.shape[1]

    @property
    def lx(self) -> float:
        """Side length along x, nx·dx (m)."""
        return self.nx * self.dx

    @property
    def ly(self) -> float:
        """Side length along y, ny·dy (m)."""
        return self.ny * self.dy

    @property
    def pixel_area(self) -> float:
        """Area of one pixel, dx·dy (m²)."""
        return self.dx * self.dy

    @property
    def apparent_area(self) -> float:
        """Apparent (projected) area A = Lx·Ly (m²)."""
        return self.lx * self.ly

    @property
    def Rt(self) -> float:
        """Peak-to-valley height R_t = max z − min z (m), in float64."""
        lo, hi = self.extremes()
        return float(np.float64(hi) - np.float64(lo))

    def to_dict(self) -> dict[str, Any]:
        """Scalar metadata (grid and parameters), JSON-serialisable.

        Returns
        -------
        dict
            ``nx``, ``ny`` (pixels), ``dx_m``, ``dy_m``, ``lx_m``, ``ly_m``, ``Rt_m`` (m), then
            every entry of ``params`` (non-finite floats written as text).
        """
        return {
            "nx": self.nx,
            "ny": self.ny,
            "dx_m": self.dx,
            "dy_m": self.dy,
            "lx_m": self.lx,
            "ly_m": self.ly,
            "Rt_m": self.Rt,
            **{k: jsonable(v, nonfinite="text") for k, v in self.params.items()},
        }


def from_heights(z: np.ndarray, dx: float, dy: float | None = None, **params: Any) -> Surface:
    """Wrap a user height map ``z[iy, ix]`` (m) with pixel spacing ``dx`` (and ``dy``) (m).

    Parameters
    ----------
    z : (ny, nx) ndarray or warp array
        Heights (m); see :class:`Surface` for what is accepted (NumPy input becomes
        C-contiguous float32).
    dx : float
        Pixel spacing along x (m), > 0.
    dy : float, optional
        Pixel spacing along y (m), > 0; defaults to ``dx``.
    **params
        Provenance parameters stored in ``Surface.params`` (SI units; JSON-serialisable).

    Returns
    -------
    Surface
        The map, kept where ``z`` lives (host or Warp device).

    Raises
    ------
    ValueError
        ``z`` is not a non-empty finite 2-D map (or not a contiguous float32 Warp array), or
        a spacing is not a positive finite number.

    Examples
    --------
    >>> import numpy as np
    >>> import warptrunc
    >>> s = warptrunc.from_heights(np.zeros((64, 64)), 1e-6)
    >>> s.lx
    6.4e-05
    """

    return Surface(z, dx, dx if dy is None else dy, params)


def _is_warp_array(a: Any) -> bool:
    wp = sys.modules.get("warp")
    return wp is not None and isinstance(a, wp.array)


def _check_device_map(z: Any, name: str = "heights") -> Any:
    if z.ndim != 2:
        raise ValueError(f"{name} must be 2-D (ny, nx), got shape {z.shape}")
    if z.shape[0] < 1 or z.shape[1] < 1:
        raise ValueError(f"{name} must not be empty, got shape {z.shape}")
    if z.dtype != wp.float32:
        raise ValueError(
            f"a device {name} array must be float32, got {wp.types.type_repr(z.dtype)}"
        )
    if not z.is_contiguous:
        raise ValueError(f"a device {name} array must be contiguous")
    return z


def _validate_on_device(z: Any, name: str = "heights") -> tuple[float, float]:
    """Finite check and (min, max) of a device map: one launch, one 32-byte read-back."""


    dev = z.device
    n = z.shape[0] * z.shape[1]
    flat = z.reshape((n,))
    out = wp.array(np.array([np.inf, -np.inf], dtype=np.float32), device=dev)
    bad = wp.array(np.array([0, n], dtype=np.int64), device=dev)
    lanes = min(_VALIDATE_LANES, n)
    chunk = 0 if dev.is_cuda else -(-n // lanes)
    wp.launch(
        _kr.validate_kernel, dim=lanes, inputs=[flat, lanes, chunk], outputs=[out, bad], device=dev
    )
    lo, hi = (float(v) for v in out.numpy())  # sync point
    nbad, first = (int(v) for v in bad.numpy())
    if nbad:
        iy, ix = divmod(first, z.shape[1])
        raise ValueError(
            f"{name} contains {nbad} NaN/inf values (first at iy={iy}, ix={ix}); "
            "fill or mask them first"
        )
    return lo, hi


_VALIDATE_LANES = 65536
