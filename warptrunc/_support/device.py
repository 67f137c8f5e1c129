# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Device resolution and memory checks shared by every driver.

``device=None`` means: the value of the environment variable ``WARPTRUNC_DEVICE`` if set,
else ``"cuda:0"`` when a CUDA device is present, else ``"cpu"``.
"""

from __future__ import annotations

import ctypes
import os
import sys
import tempfile

import warp as wp

_initialised = False
_mempool_kept: set = set()

#: Lines that Warp's native library prints while it initialises on a machine without a CUDA
#: driver. They are not errors for warptrunc (the CPU is a supported device), so they are
#: shown only when verbose (``set_verbose(True)``, ``warptrunc --verbose``, or the environment
#: variable ``WARPTRUNC_VERBOSE=1``).
CPU_ONLY_NOTICES = (
    "Could not find or load the NVIDIA CUDA driver",
    "Unable to determine CUDA driver version",
)
_verbose: bool | None = None


def set_verbose(flag: bool) -> None:
    """Show (True) or hide (False) the notices of Warp and VTK on CPU-only machines."""
    global _verbose
    _verbose = bool(flag)


def is_verbose() -> bool:
    """True when :func:`set_verbose` asked for it, else when ``$WARPTRUNC_VERBOSE`` is set."""
    if _verbose is not None:
        return _verbose
    return os.environ.get("WARPTRUNC_VERBOSE", "").strip().lower() not in ("", "0", "false", "no")


def _run_filtering_native_output(fn, drop: tuple[str, ...]):
    """Call ``fn()`` with the process's stdout/stderr file descriptors captured.

    Native libraries write with C stdio, below Python's ``sys.stderr``, so the capture works on
    file descriptors 1 and 2; C buffers are flushed before they are restored. Captured lines
    that contain none of ``drop`` are written back to the same stream afterwards.
    """

    try:
        libc = ctypes.CDLL(None)
        flush_c = lambda: libc.fflush(None)  # noqa: E731
        saved = {fd: os.dup(fd) for fd in (1, 2)}
    except (OSError, AttributeError):  # no fd-level control (e.g. an embedded interpreter)
        return fn()
    tmp = {fd: tempfile.TemporaryFile() for fd in (1, 2)}
    for stream in (sys.stdout, sys.stderr):
        if stream is not None:
            stream.flush()
    try:
        for fd, f in tmp.items():
            os.dup2(f.fileno(), fd)
        return fn()
    finally:
        flush_c()
        for fd, old in saved.items():
            os.dup2(old, fd)
            os.close(old)
        for fd, f in tmp.items():
            f.seek(0)
            text = f.read().decode(errors="replace")
            f.close()
            keep = [ln for ln in text.splitlines(keepends=True) if not any(d in ln for d in drop)]
            if keep:
                os.write(fd, "".join(keep).encode())


def _init() -> None:
    global _initialised
    if not _initialised:
        wp.config.log_level = wp.LOG_WARNING
        if is_verbose():
            wp.init()
        else:
            _run_filtering_native_output(wp.init, CPU_ONLY_NOTICES)
        _initialised = True


def cuda_device_count() -> int:
    """Number of CUDA devices Warp sees (0 on a machine without a GPU)."""
    _init()
    return wp.get_cuda_device_count()


def as_device(device: wp.DeviceLike = None) -> wp.context.Device:
    """``device`` itself when it is already a resolved Warp device (as internal helpers get it
    from the public call that resolved it), else :func:`resolve_device` of it."""
    return device if isinstance(device, wp.Device) else resolve_device(device)


def resolve_device(device: wp.DeviceLike = None) -> wp.context.Device:
    """Return the Warp device to run on.

    Parameters
    ----------
    device : str or warp Device, optional
        ``"cpu"``, ``"cuda:0"``, ... ``None`` picks ``$WARPTRUNC_DEVICE``, else CUDA when
        present, else the CPU.

    Returns
    -------
    warp.context.Device
        The resolved device. On the first use of a CUDA device with a memory pool whose
        release threshold is 0, the threshold is set to a quarter of its memory.

    Raises
    ------
    ValueError
        Warp does not know ``device``; the message lists the available devices.
    """

    _init()
    if device is None:
        device = os.environ.get("WARPTRUNC_DEVICE") or None
    if device is None:
        device = "cuda:0" if wp.get_cuda_device_count() > 0 else "cpu"
    try:
        dev = wp.get_device(device)
    except Exception as exc:  # warp raises RuntimeError/ValueError depending on the case
        names = [str(d) for d in wp.get_devices()]
        raise ValueError(f"device must be one of {names}, got {device!r}") from exc
    if dev.is_cuda and dev.is_mempool_supported and str(dev) not in _mempool_kept:
        # CUDA's default pool gives memory back at every synchronisation, so each new
        # height map (hundreds of MB) is mapped afresh: measured 1–2.5 ms per 10240² array on
        # an H200. Keep up to a quarter of the device's memory pooled, unless the user set it.
        if wp.get_mempool_release_threshold(dev) == 0:
            wp.set_mempool_release_threshold(dev, 0.25)
        _mempool_kept.add(str(dev))
    return dev


def free_memory_bytes(device: wp.context.Device) -> int:
    """Free memory on ``device`` in bytes (host: MemAvailable from /proc/meminfo)."""
    if device.is_cuda:
        return int(device.free_memory)
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return int(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))


def release_cached_memory(device: wp.context.Device) -> int:
    """Give the memory that Warp's (and CuPy's) pools keep cached back to the device and
    return the free bytes then: the pooled blocks are free for our next allocation but not
    counted as free by the driver, so a size check would refuse work that fits."""
    if device.is_mempool_supported:
        keep = wp.get_mempool_release_threshold(device)
        wp.set_mempool_release_threshold(device, 0)
        wp.synchronize_device(device)  # the pool trims to the threshold here
        wp.set_mempool_release_threshold(device, keep)
    cupy = sys.modules.get("cupy")
    if cupy is not None:
        with cupy.cuda.Device(device.ordinal):
            cupy.get_default_memory_pool().free_all_blocks()
    return free_memory_bytes(device)


def release_kept_pools() -> None:
    """Give back what Warp's pools keep cached (up to a quarter of each GPU, see
    ``resolve_device``) on every CUDA device warptrunc has used: before another allocator,
    JAX's for a solve over several devices, takes the same GPUs."""
    for name in sorted(_mempool_kept):
        release_cached_memory(wp.get_device(name))


def check_memory(nbytes: int, device: wp.context.Device, what: str) -> None:
    """Raise ``MemoryError`` before allocating when ``nbytes`` exceed the free memory."""
    free = free_memory_bytes(device)
    if nbytes > free and device.is_cuda:
        free = release_cached_memory(device)
    if nbytes > free:
        raise MemoryError(
            f"{what} needs {nbytes / 2**30:.2f} GiB on {device} but only "
            f"{free / 2**30:.2f} GiB is free; use a smaller grid or another device"
        )
