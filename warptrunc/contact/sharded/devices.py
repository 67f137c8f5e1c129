# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Which devices a contact solve runs on: the ``devices`` argument of
:class:`~warptrunc.contact.ContactSolver` (checked here, with messages that name the value and
what is allowed), ``devices="auto"`` (one device when the solver fits it, else the fewest that
fit: spreading is slower per iteration on one host, since the transposes cost more than the
transforms) and the per-device memory check. JAX is imported only when several devices are
asked for (or ``"auto"`` finds that one does not suffice)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..._support.docs import fill_doc
from .grid import SHARDED_DOCS, devices_needed, import_jax, sharded_memory_bytes

__all__ = [
    "check_fits",
    "choose_devices",
    "out_of_memory",
    "single_device",
    "spread_in_use",
]

XLA_ERRORS = ("XlaRuntimeError", "JaxRuntimeError")
"""Names of the XLA runtime's error types (jaxlib's, by version)."""

_SPREAD = {"used": False}  # set once a solve was spread (ShardedHalfSpace): see spread_in_use


def mark_spread() -> None:
    """Record that this process spread a solve over several devices (:func:`spread_in_use`)."""
    _SPREAD["used"] = True


def spread_in_use() -> bool:
    """Whether this process spread a contact solve over several devices.

    Returns
    -------
    bool
        True once a :class:`~warptrunc.contact.sharded.ShardedContactSolver` was made. After an
        error in such a solve the other devices may still wait in a collective (an all-to-all
        whose partner failed), and the JAX runtime then waits for them at interpreter exit; the
        command line therefore ends the process at once after reporting the error
        (``os._exit``, ``warptrunc.cli.main``).
    """
    return _SPREAD["used"]


def out_of_memory(exc: BaseException) -> MemoryError | None:
    """XLA's out-of-memory error as a :class:`MemoryError`, or None for any other error.

    Parameters
    ----------
    exc : BaseException
        An error raised by a JAX programme (an ``XLA_ERRORS`` type with XLA's
        ``RESOURCE_EXHAUSTED`` status: a device allocation refused).

    Returns
    -------
    MemoryError or None
        One line naming the failed allocation where XLA gave it, and what to do.
    """
    text = str(exc)
    if "RESOURCE_EXHAUSTED" not in text or type(exc).__name__ not in XLA_ERRORS:
        return None
    import re

    first = " ".join(text.split("=== Source Location Trace")[0].split())[:300]
    asked = re.search(r"allocat\w* ([\d.]+\s*[KMGT]i?B)", text)
    what = f" (XLA asked for {asked.group(1)})" if asked else ""
    return MemoryError(
        f"a device ran out of memory in a solve spread over several devices{what}: {first}; "
        "use more devices (--devices), float32, or a smaller map, and see "
        "ContactSolver.memory_bytes(..., devices=n)"
    )


_PLATFORMS = {"cuda": "gpu", "gpu": "gpu", "cpu": "cpu", "tpu": "tpu"}


def _settings(settings: Any):
    from ..settings import SolverSettings

    return settings if settings is not None else SolverSettings()


def _jax_device(name: Any, jax: Any):
    """A JAX device from a device object or a name ``"cuda:1"``, ``"gpu:1"``, ``"cpu:0"``."""
    if not isinstance(name, str):
        return name
    platform, _, index = name.partition(":")
    backend = _PLATFORMS.get(platform.lower())
    if backend is None or (index and not index.isdigit()):
        raise ValueError(
            f"devices: unknown device name {name!r}; allowed: 'cuda:N', 'gpu:N', "
            "'cpu:N' or JAX device objects"
        )
    try:
        found = jax.devices(backend)
    except RuntimeError as exc:
        raise ValueError(f"devices: no JAX {backend} devices for {name!r} ({exc})") from None
    i = int(index or 0)
    if i >= len(found):
        raise ValueError(
            f"devices: {name!r} is out of range; JAX has {len(found)} {backend} "
            f"device(s), 0 … {len(found) - 1}"
        )
    return found[i]


def _free_bytes(device: Any) -> int | None:
    """Free memory of a JAX device (B), or None where JAX does not report it (the CPU)."""
    import jax

    if getattr(device, "process_index", 0) != jax.process_index():
        return None  # another process's (host's) device: that process checks it
    stats = device.memory_stats() if hasattr(device, "memory_stats") else None
    if not stats or "bytes_limit" not in stats:
        return None
    return int(stats["bytes_limit"]) - int(stats.get("bytes_in_use", 0))


@fill_doc(SHARDED_DOCS)
def check_fits(shape: tuple[int, int], substrate: str, dtype: str, devices: list[Any]) -> int:
    """Check that each device's share fits its free memory.

    Parameters
    ----------
    {shape}
    {substrate}
    {dtype}
    devices : list of jax Device
        The devices.

    Returns
    -------
    int
        Bytes each device needs (the model,
        :func:`~warptrunc.contact.sharded.grid.sharded_memory_bytes`).

    Raises
    ------
    MemoryError
        A device has less free memory than its share; the message says how many would do.
    """
    need = sharded_memory_bytes(shape, substrate, dtype, len(devices))
    for dev in devices:
        free = _free_bytes(dev)
        if free is not None and need > free:
            more = devices_needed(shape, substrate, dtype, free)
            hint = f"devices={more}" if more else "float32 or a smaller map"
            raise MemoryError(
                f"the contact solver for a {shape[0]}×{shape[1]} map ({substrate}, {dtype}) over "
                f"{len(devices)} devices needs {need / 1e9:.2f} GB per device, {free / 1e9:.2f} "
                f"GB free on {dev}; use {hint}"
            )
    return need


def _process_group() -> list[str] | None:
    """The device names of ``$WARPTRUNC_DEVICE_GROUP`` (a Dask worker's group), or None."""
    import os

    text = os.environ.get("WARPTRUNC_DEVICE_GROUP", "").strip()
    return [t.strip() for t in text.split(",") if t.strip()] or None


def _count_error(n: int, ny: int, avail: int) -> ValueError:
    ok = [k for k in range(1, avail + 1) if ny % k == 0]
    return ValueError(
        f"devices: the map's ny = {ny} rows are split in equal slabs, so the device count must "
        f"divide ny; got {n} (counts up to {avail} that do: {ok})"
    )


def choose_devices(
    devices: Any, shape: tuple[int, ...], settings: Any = None, device: Any = None
) -> list[Any] | None:
    """The JAX devices a solve is spread over, or None for the one-device solver.

    Parameters
    ----------
    devices : None, int, "auto" or list
        The solver's ``devices`` argument: None (one device); a count N ≥ 1 (the first N JAX
        devices of the default backend; in a process whose ``$WARPTRUNC_DEVICE_GROUP`` names
        N devices, those: a Dask worker's group, :mod:`warptrunc.sweep.groups`); ``"auto"``; a list of JAX devices or names
        (``"cuda:0"``, ``"gpu:1"``, ``"cpu:0"``).
    shape : tuple of int
        Shape of the height map (ny, nx).
    settings : SolverSettings, optional
        The solver's settings (substrate, dtype, algorithm).
    device : str or warp Device, optional
        The one-device solver's Warp device (``"auto"`` checks it first, against
        :func:`~warptrunc.contact.memory.memory_bytes`).

    Returns
    -------
    list of jax Device or None
        Two or more devices, or None: one device.

    Raises
    ------
    ValueError
        A bad value (the message names it and what is allowed), or a count that does not
        divide ny.
    MemoryError
        ``"auto"``: no count of the available devices holds the solve.
    """
    if devices is None:
        return None
    ny = int(shape[0]) if len(shape) else 0
    if isinstance(devices, str) and devices == "auto":
        s = _settings(settings)
        from ..._support.device import free_memory_bytes, resolve_device
        from ..memory import memory_bytes

        dev = resolve_device(device)
        one = memory_bytes(
            tuple(shape), s.substrate, s.dtype, cuda=dev.is_cuda, algorithm=s.algorithm
        )
        if one <= free_memory_bytes(dev):
            return None
        jax = import_jax()
        avail = jax.devices()
        for n in range(2, len(avail) + 1):
            if ny % n == 0:
                try:
                    check_fits(tuple(shape), s.substrate, s.dtype, avail[:n])
                except MemoryError:
                    continue
                return list(avail[:n])
        raise MemoryError(
            f"devices='auto': the contact solver for a {shape[0]}×{shape[1]} map "
            f"({s.substrate}, {s.dtype}) fits neither {dev} ({one / 1e9:.2f} GB needed) nor any "
            f"count of the {len(avail)} JAX devices that divides ny = {ny}"
        )
    if isinstance(devices, bool) or isinstance(devices, str | float):
        raise ValueError(
            f"devices must be None, 'auto', a count ≥ 1 or a list of devices, got {devices!r}"
        )
    if isinstance(devices, int | np.integer):
        n = int(devices)
        if n < 1:
            raise ValueError(f"devices must be a count ≥ 1, got {n}")
        if n == 1:
            return None
        group = _process_group()
        if group is not None:  # a Dask worker's own devices (warptrunc.sweep.groups)
            if len(group) != n:
                raise ValueError(
                    f"devices={n}, but this process's device group "
                    f"(WARPTRUNC_DEVICE_GROUP) names {len(group)}: {group}"
                )
            return choose_devices(group, shape, settings, device)
        jax = import_jax()
        avail = jax.devices()
        if n > len(avail):
            raise ValueError(
                f"devices must be in [1, {len(avail)}] (the JAX devices of backend "
                f"{jax.default_backend()!r}), got {n}"
            )
        if ny % n:
            raise _count_error(n, ny, len(avail))
        return list(avail[:n])
    try:
        items = list(devices)
    except TypeError:
        raise ValueError(
            f"devices must be None, 'auto', a count ≥ 1 or a list of devices, got {devices!r}"
        ) from None
    if not items:
        raise ValueError("devices must name at least one device, got an empty list")
    if len(items) == 1:
        return None
    jax = import_jax()
    found = [_jax_device(d, jax) for d in items]
    if len({id(d) for d in found}) != len(found):
        raise ValueError(f"devices must not repeat a device, got {items!r}")
    if ny % len(found):
        raise _count_error(len(found), ny, len(found))
    return found


def single_device(devices: Any, device: Any) -> Any:
    """The Warp device of a one-device solve asked for through ``devices``.

    Parameters
    ----------
    devices : int, "auto" or list
        The solver's ``devices`` (1, ``"auto"`` or one device).
    device : str or warp Device or None
        The solver's ``device`` (kept for 1 and ``"auto"``).

    Returns
    -------
    str or warp Device or None
        ``device``, or the Warp name of the one device listed (``"cuda:N"``, ``"cpu"``).
    """
    if isinstance(devices, str) or not hasattr(devices, "__len__") or len(devices) != 1:
        return device
    d = next(iter(devices))
    if isinstance(d, str):
        platform, _, index = d.partition(":")
        if platform.lower() in ("cuda", "gpu"):
            return f"cuda:{index or 0}"
        return "cpu" if platform.lower() == "cpu" else d
    if getattr(d, "platform", "") == "gpu":
        return f"cuda:{getattr(d, 'local_hardware_id', None) or d.id}"
    return "cpu"
