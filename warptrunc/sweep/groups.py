# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Device groups of Dask workers: each worker takes G devices, over which its elastic solves
are spread (``run_sweep(..., execution=SweepExecution(workers=N, devices=G))``,
``warptrunc sweep --workers N --devices G --bem-fractions ...``).

Worker ``i`` of a local cluster (named 0..N-1) gets devices ``i·G … i·G + G − 1`` (modulo the
devices present): its Warp device is the first (``WARPTRUNC_DEVICE``, CUDA only) and the group
is written to ``WARPTRUNC_DEVICE_GROUP`` (``"cuda:2,cuda:3"``) in the worker process
(:class:`~warptrunc.sweep.cluster.PinDevice`). A solve given ``devices=G`` in a process whose
group names G devices is spread over that group
(:func:`~warptrunc.contact.sharded.devices.choose_devices`), not over the first G devices of
the host. On an existing cluster (``scheduler``) give each worker its group yourself: start it
with ``CUDA_VISIBLE_DEVICES`` naming its G GPUs (its first G JAX devices are then its own), or
with ``WARPTRUNC_DEVICE_GROUP``.
"""

from __future__ import annotations

from typing import Any

__all__ = ["GROUP_ENV", "group_layout", "group_size", "worker_group"]

GROUP_ENV = "WARPTRUNC_DEVICE_GROUP"
"""Environment variable naming this process's device group, comma-separated JAX device names
(``"cuda:0,cuda:1"``; ``"cpu:0,cpu:1"`` for host devices)."""


def group_size(devices: Any) -> int:
    """Devices per worker for a ``devices`` argument of the sweep (count).

    Parameters
    ----------
    devices : None, int or "auto"
        The sweep's ``devices``.

    Returns
    -------
    int
        ``devices`` when it is a count ≥ 2; else 1 (one device per worker).

    Raises
    ------
    ValueError
        ``"auto"`` or a list with workers: a worker's group is a fixed count.
    """
    if devices is None or isinstance(devices, bool):
        return 1
    if isinstance(devices, int):
        return max(1, devices)
    raise ValueError(
        f"devices={devices!r} with workers: give a count (each worker takes that "
        "many devices), not 'auto' or a list"
    )


def worker_group(worker_name: Any, n_devices: int, group: int, platform: str = "cuda") -> list[str]:
    """The device names of a worker's group.

    Parameters
    ----------
    worker_name : Any
        The Dask worker's name (its index: :func:`~warptrunc.sweep.engines.worker_index`).
    n_devices : int
        Devices present (count ≥ 1).
    group : int
        Devices per worker (count ≥ 1).
    platform : {"cuda", "cpu"}, optional
        JAX platform of the names.

    Returns
    -------
    list of str
        ``group`` names, ``"<platform>:<k>"`` for k = i·group … i·group + group − 1 modulo
        ``n_devices``.

    Raises
    ------
    ValueError
        ``group`` exceeds ``n_devices``.
    """
    from .engines import worker_index

    if group > n_devices:
        raise ValueError(
            f"devices per worker must be at most the {n_devices} devices present, got {group}"
        )
    first = worker_index(worker_name) * group
    return [f"{platform}:{(first + k) % n_devices}" for k in range(group)]


def group_layout(workers: Any, n: int | None, group: int, n_gpus: int) -> tuple[int, int, str]:
    """Workers, devices and platform of a local cluster whose workers take ``group`` devices.

    Parameters
    ----------
    workers : int, "auto" or None
        The ``workers`` argument as given.
    n : int or None
        Its count (:func:`~warptrunc.sweep.cluster.resolve_workers`); None or ``"auto"``: as
        many workers as whole groups fit.
    group : int
        Devices per worker (count ≥ 2).
    n_gpus : int
        CUDA devices visible (count); 0: JAX's host devices are the devices.

    Returns
    -------
    (int, int, str)
        Workers, devices present, and their platform (``"cuda"`` or ``"cpu"``).

    Raises
    ------
    ValueError
        More workers × devices than devices present; the message gives the largest count.
    """
    if n_gpus > 0:
        have, platform = n_gpus, "cuda"
    else:
        from ..contact.sharded.grid import import_jax

        have, platform = len(import_jax().devices("cpu")), "cpu"
    if isinstance(workers, str) or n is None:
        n = max(1, have // group)
    if n * group > have:
        raise ValueError(
            f"workers × devices = {n} × {group} = {n * group} devices, but "
            f"{have} {platform} devices are present; use at most "
            f"--workers {max(1, have // group)} (or 'auto')"
        )
    return n, have, platform
