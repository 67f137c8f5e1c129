# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The CPUs near a GPU, and binding a process to them (as dask-cuda's ``CPUAffinity`` does).

On a host of several CPU sockets each GPU hangs off one socket's PCIe root. A process driving
the GPU from the other socket pays for every kernel launch, copy and read-back across the socket
link, and the contact solver's loop on a GPU launches a kernel every ≈ 150 µs and waits for the
scalars it reads back (about 46 000 Warp launches in the two indentation parts profiled by
``examples/benchmarks/benchmark_worker_overhead.py``), so where its thread runs shows in its time.
Linux places a process anywhere it is allowed to run, so an unbound process may land on either
socket, and move.
(A reading, not a measurement: the one 4-GPU host whose topology was recorded, 4 × H100 at
``1b64d9c``, is a single NUMA node whose GPUs all list CPUs 0–63, so binding changed nothing
there; the workers' extra cost on that host was Dask's profiler, see
:func:`warptrunc.sweep.cluster.worker_environment`.)

The GPU's PCI bus id comes from the CUDA driver (``cuDeviceGetPCIBusId``; the ordinal as this
process counts devices, after ``CUDA_VISIBLE_DEVICES``; no context is created), and its CPUs
from ``/sys/bus/pci/devices/<bus id>/local_cpulist``; both need Linux and a CUDA driver, and
without either nothing is bound. :func:`bind_near` binds every thread of this process to
those CPUs that it may already use; the workers of a local cluster that
:class:`~warptrunc.sweep.cluster.PinDevice` pins call it (``WARPTRUNC_CPU_AFFINITY=0`` turns
it off). ``python -m warptrunc.sweep._affinity 0`` prints device 0's CPUs (for ``taskset
-c``), or nothing.
"""

from __future__ import annotations

import ctypes
import os
import sys
from collections.abc import Iterable
from pathlib import Path

from .._support.docs import fill_doc

__all__ = [
    "AFFINITY_ENV",
    "bind_near",
    "format_cpulist",
    "gpu_local_cpus",
    "parse_cpulist",
    "pci_bus_id",
    "sysfs_name",
]

AFFINITY_ENV = "WARPTRUNC_CPU_AFFINITY"
"""Set to ``0`` to leave the CPU affinity of a local cluster's pinned workers alone."""

SYSFS_PCI = "/sys/bus/pci/devices"

_DOCS = {
    "{ordinals}": (
        "ordinals : iterable of int\n    CUDA device ordinals, as this process counts them.\n"
        "sysfs : str\n    Folder of the PCI devices (tests give another)."
    )
}
"""Parameter text :func:`gpu_local_cpus` and :func:`bind_near` share
(:func:`~warptrunc._support.docs.fill_doc`)."""


def parse_cpulist(text: str) -> set[int]:
    """The CPUs of a Linux CPU list (``"0-31,64-95"``; ``"3"``; ``""`` is none).

    Parameters
    ----------
    text : str
        The list, as in ``local_cpulist`` or ``taskset -c``.

    Returns
    -------
    set of int
        The CPU numbers.

    Raises
    ------
    ValueError
        A part is not ``N`` or ``N-M`` with N ≤ M.
    """
    cpus: set[int] = set()
    for part in text.strip().split(","):
        part = part.strip()
        if not part:
            continue
        lo, _, hi = part.partition("-")
        try:
            a, b = int(lo), int(hi or lo)
        except ValueError:
            raise ValueError(f"not a CPU list: {text!r}") from None
        if a < 0 or b < a:
            raise ValueError(f"not a CPU list: {text!r}")
        cpus.update(range(a, b + 1))
    return cpus


def format_cpulist(cpus: Iterable[int]) -> str:
    """A Linux CPU list of ``cpus`` in ranges (``{0, 1, 2, 3, 8}`` → ``"0-3,8"``; none → ``""``),
    the inverse of :func:`parse_cpulist`."""
    runs: list[list[int]] = []  # [first, last] of each run of consecutive CPUs
    for c in sorted({int(c) for c in cpus}):
        if runs and c == runs[-1][1] + 1:
            runs[-1][1] = c
        else:
            runs.append([c, c])
    return ",".join(str(a) if a == b else f"{a}-{b}" for a, b in runs)


def pci_bus_id(ordinal: int) -> str | None:
    """PCI bus id (``"0000:1b:00.0"``, lower case as sysfs names it) of CUDA device ``ordinal``
    as this process counts them; None without a CUDA driver or such a device."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        lib = ctypes.CDLL("libcuda.so.1")
        dev = ctypes.c_int(0)
        buf = ctypes.create_string_buffer(64)
        if lib.cuInit(0) != 0 or lib.cuDeviceGet(ctypes.byref(dev), int(ordinal)) != 0:
            return None
        if lib.cuDeviceGetPCIBusId(buf, 64, dev) != 0:
            return None
    except (OSError, AttributeError):
        return None
    return sysfs_name(buf.value.decode())


def sysfs_name(bus_id: str) -> str | None:
    """The sysfs folder name of a PCI bus id: ``"00000000:1B:00.0"`` or ``"0000:1B:00.0"`` →
    ``"0000:1b:00.0"`` (a 4-digit domain, lower case); None when it is not such an id."""
    try:
        dom, bus, rest = bus_id.strip().split(":")
        dev, fn = rest.split(".")
        return f"{int(dom, 16):04x}:{int(bus, 16):02x}:{int(dev, 16):02x}.{int(fn, 16):x}"
    except ValueError:
        return None


@fill_doc(_DOCS)
def gpu_local_cpus(ordinals: Iterable[int], sysfs: str = SYSFS_PCI) -> set[int] | None:
    """The CPUs local to the CUDA devices ``ordinals`` (the union), or None when unknown.

    Parameters
    ----------
    {ordinals}

    Returns
    -------
    set of int or None
        None when a device's bus id or its ``local_cpulist`` cannot be read (no Linux, no
        CUDA driver, a virtual machine that does not say).
    """
    cpus: set[int] = set()
    for o in ordinals:
        bus = pci_bus_id(o)
        if bus is None:
            return None
        try:
            cpus |= parse_cpulist((Path(sysfs) / bus / "local_cpulist").read_text())
        except (OSError, ValueError):
            return None
    return cpus or None


def _set_all_threads(cpus: set[int]) -> None:
    """``sched_setaffinity`` for every thread of this process (Linux applies it per thread;
    threads started later inherit the caller's)."""
    try:
        tids = [int(t) for t in os.listdir("/proc/self/task")]
    except OSError:
        tids = [0]
    for tid in tids:
        try:
            os.sched_setaffinity(tid, cpus)
        except OSError:  # a thread that ended meanwhile
            pass
    os.sched_setaffinity(0, cpus)


@fill_doc(_DOCS)
def bind_near(ordinals: Iterable[int], sysfs: str = SYSFS_PCI) -> set[int] | None:
    """Bind this process to the CPUs near the CUDA devices ``ordinals`` that it may use now.

    Parameters
    ----------
    {ordinals}

    Returns
    -------
    set of int or None
        The CPUs bound to; None when nothing changed: ``$WARPTRUNC_CPU_AFFINITY`` is ``0``, the
        CPUs are unknown (:func:`gpu_local_cpus`), none of them is allowed now, or the process
        is already limited to them.
    """
    if os.environ.get(AFFINITY_ENV, "").strip().lower() in ("0", "false", "no", "off"):
        return None
    if not hasattr(os, "sched_setaffinity"):
        return None
    near = gpu_local_cpus(list(ordinals), sysfs)
    if near is None:
        return None
    allowed = os.sched_getaffinity(0)
    keep = near & allowed
    if not keep or keep == allowed:
        return None
    _set_all_threads(keep)
    return keep


def _main(argv: list[str]) -> int:
    """Print the CPU list of the devices named (``taskset -c`` form), or nothing."""
    cpus = gpu_local_cpus(int(a) for a in argv)
    if cpus:
        print(format_cpulist(cpus))
    return 0


if __name__ == "__main__":
    raise SystemExit(_main(sys.argv[1:]))
