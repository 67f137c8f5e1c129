# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Provenance of results: what made an output, and when; the package version.

:func:`provenance` is the one record every output carries (``"provenance"`` in ``fit.json``,
``fit.to_json()``, ``render.json``, ``bem.json``, ``indicators.json``, ``calibration.json``,
``describe --json``, a sweep store's ``sweep.json``, a comparison study, reports): warptrunc's
version, the git commit where known, the command line, the device, the time (UTC), and the
versions of Python and Warp. The command line is the ``warptrunc`` command while one runs
(:func:`set_command`, called by :func:`warptrunc.cli.main`), else ``sys.argv``.
``$SOURCE_DATE_EPOCH``, when set, fixes the time (reproducible outputs).

:data:`__version__` is warptrunc's version (``warptrunc.__version__`` re-exports it). This
module imports only the standard library, and git, :mod:`platform` and :mod:`shlex` only
when a record is made, so ``import warptrunc`` reads the version at no cost.
"""

from __future__ import annotations

import functools
import os
import sys
import time
from pathlib import Path
from typing import Any

__all__ = ["__version__", "git_commit", "provenance", "set_command"]

__version__ = "0.1.0"
"""warptrunc's version, the first field of every provenance record."""

_command: list[str] | None = None


def set_command(argv: list[str] | None) -> None:
    """Record the command line of the running ``warptrunc`` command (None: forget it).

    Parameters
    ----------
    argv : list of str or None
        The full command line, program name first (``["warptrunc", "analyze", ...]``).
    """
    global _command
    _command = None if argv is None else [str(a) for a in argv]


@functools.lru_cache(maxsize=8)
def _git_head(root: str) -> str | None:
    import subprocess

    try:
        out = subprocess.run(
            ["git", "-C", root, "rev-parse", "HEAD"], capture_output=True, text=True, timeout=10
        )
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() if out.returncode == 0 and out.stdout.strip() else None


def git_commit(root: str | Path | None = None) -> str | None:
    """The commit of the checkout at ``root`` (default: this package's), or None.

    ``$WARPTRUNC_GIT_COMMIT``, when set, is returned as it is. The answer of git is kept for
    the life of the process.

    Parameters
    ----------
    root : str or Path, optional
        A folder inside a git checkout.

    Returns
    -------
    str or None
        The full commit hash; None outside a checkout or without git.
    """
    env = os.environ.get("WARPTRUNC_GIT_COMMIT")
    if env:  # a copy without .git (e.g. a tree shipped to a GPU machine) can say its commit
        return env.strip()
    root = Path(root) if root is not None else Path(__file__).resolve().parents[2]
    return _git_head(str(root))


def _utc_now() -> str:
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    t = time.gmtime(int(epoch)) if epoch and epoch.strip().isdigit() else time.gmtime()
    return time.strftime("%Y-%m-%dT%H:%M:%SZ", t)


def _device(device: Any) -> tuple[str | None, str | None]:
    """(device alias, device name) as resolved by Warp, when Warp is loaded already."""
    if "warp" not in sys.modules:  # nothing ran on a device; do not load Warp for this
        return (None if device is None else str(device)), None
    try:
        from .device import resolve_device

        d = resolve_device(device)
        return str(d.alias), str(getattr(d, "name", "") or "") or None
    except Exception:  # an unknown device name: the command reports it elsewhere
        return (None if device is None else str(device)), None


def input_file(path: str | Path) -> dict[str, Any]:
    """The record of a file an output was computed from: ``path`` as given, ``resolved`` (the
    absolute path), ``bytes`` and ``sha256`` (hex) of its content.

    Parameters
    ----------
    path : str or Path
        The file read.

    Returns
    -------
    dict
        JSON-ready.
    """
    import hashlib

    p = Path(path)
    h = hashlib.sha256()
    with p.open("rb") as f:
        for block in iter(lambda: f.read(1 << 22), b""):
            h.update(block)
    return {
        "path": str(path),
        "resolved": str(p.resolve()),
        "bytes": p.stat().st_size,
        "sha256": h.hexdigest(),
    }


def provenance(
    device: Any = None,
    argv: list[str] | None = None,
    *,
    input_path: str | Path | None = None,
    commit: str | None = None,
) -> dict[str, Any]:
    """What made an output and when, as a JSON-ready dict.

    Parameters
    ----------
    device : str or warp.Device, optional
        The device the work ran on (default: the one Warp resolves by default, when Warp is
        loaded; else None).
    argv : list of str, optional
        The command line, program name first (default: the running ``warptrunc`` command,
        else ``sys.argv``).
    input_path : str or Path, optional
        The height-map file the output was computed from: recorded as ``"input"``
        (:func:`input_file`).
    commit : str, optional
        The commit to record (``warptrunc reproduce --commit``); default :func:`git_commit`.

    Returns
    -------
    dict
        ``warptrunc_version``, ``git_commit`` (None where unknown), ``command`` (one string,
        shell-quoted), ``device`` (e.g. ``"cuda:0"``), ``device_name``, ``host`` (the
        machine's network name), ``created_utc`` (ISO 8601, ``$SOURCE_DATE_EPOCH`` when set),
        ``python_version`` and ``warp_version`` (None when Warp is not loaded); with ``input_path``, ``input`` (the
        file's path, absolute path, size and SHA-256).

    Examples
    --------
    >>> sorted(provenance())[:3]
    ['command', 'created_utc', 'device']
    """
    import platform
    import shlex

    if argv is None:
        argv = _command if _command is not None else list(sys.argv)
    dev, name = _device(device)
    warp = sys.modules.get("warp")
    out = {
        "warptrunc_version": __version__,
        "git_commit": commit or git_commit(),
        "command": shlex.join(str(a) for a in argv),
        "device": dev,
        "device_name": name,
        "host": platform.node(),
        "created_utc": _utc_now(),
        "python_version": platform.python_version(),
        "warp_version": None
        if warp is None
        else getattr(getattr(warp, "config", None), "version", None),
    }
    if input_path is not None:
        out["input"] = input_file(input_path)
    return out
