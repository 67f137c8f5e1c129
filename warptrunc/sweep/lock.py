# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One writer per result store: ``OUT/.lock``.

:func:`store_lock` creates ``OUT/.lock`` exclusively (``O_CREAT | O_EXCL``) with the holder's
pid, host and start time (JSON). A second sweep on the same store is refused at once with
:class:`StoreLocked`, naming the holder. A lock whose holder is gone — same host, and no
process of that pid — is stale: it is taken over, and the takeover is reported through the
``notify`` callback. A lock held from another host cannot be checked and is never taken over;
the message says which file to remove once that sweep is known to be dead.
"""

from __future__ import annotations

import json
import os
import socket
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

__all__ = ["LOCK_NAME", "StoreLocked", "read_lock", "store_lock"]

LOCK_NAME = ".lock"
"""File name of the lock inside the store folder."""


class StoreLocked(ValueError):
    """Another process holds the store's lock; the message names its pid and host."""


def read_lock(path: str | Path) -> dict[str, Any] | None:
    """The holder recorded in ``path/.lock`` (pid, host, started_utc), or None if unlocked.

    Parameters
    ----------
    path : str or Path
        The store folder.

    Returns
    -------
    dict or None
        The lock file's JSON object (``pid``, ``host``, ``started_utc``); None when there is
        no lock file. A lock file that cannot be read or parsed (half-written, damaged, a
        folder) gives ``{"pid": None, "host": None, "started_utc": None, "unreadable": why}``.
    """

    f = Path(path) / LOCK_NAME
    try:
        info = json.loads(f.read_text(encoding="utf-8"))
    except FileNotFoundError:
        return None
    except (OSError, ValueError) as exc:  # half-written or damaged: the holder is unknown
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else "not JSON"
        return {"pid": None, "host": None, "started_utc": None, "unreadable": why}
    if not isinstance(info, dict) or not isinstance(info.get("pid"), int):
        return {"pid": None, "host": None, "started_utc": None,
                "unreadable": "no pid recorded"}  # fmt: skip
    return info


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # exists, owned by someone else
        return True
    return True


def _try_create(f: Path, info: dict[str, Any]) -> bool:
    try:
        fd = os.open(f, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
    except FileExistsError:
        return False
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(json.dumps(info) + "\n")
    except BaseException:  # e.g. a full disk: never leave a half-written lock behind
        f.unlink(missing_ok=True)
        raise
    return True


@contextmanager
def store_lock(
    path: str | Path, *, notify: Callable[[str], None] | None = None
) -> Iterator[dict[str, Any]]:
    """Hold ``path/.lock`` for the duration of the block.

    Parameters
    ----------
    path : path
        The store folder (created if missing).
    notify : callable, optional
        Called with a one-line message when a stale lock is taken over.

    Yields
    ------
    dict
        This holder's record (pid, host, started_utc).

    Raises
    ------
    StoreLocked
        A live process (or one on another host) holds the lock.
    """
    path = Path(path)
    path.mkdir(parents=True, exist_ok=True)
    f = path / LOCK_NAME
    host = socket.gethostname()
    me = {
        "pid": os.getpid(),
        "host": host,
        "started_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    }
    for _ in range(3):
        if _try_create(f, me):
            break
        held = read_lock(path)
        if held is None:
            continue  # released meanwhile
        pid, h = held.get("pid"), held.get("host")
        stale = h == host and isinstance(pid, int) and pid != os.getpid() and not _alive(pid)
        if held.get("unreadable"):
            raise StoreLocked(
                f"{path} is locked, but its lock file {f} cannot be read ({held['unreadable']}; "
                "half-written or damaged), so its holder is unknown; if no sweep is running on "
                f"this store, remove {f}"
            )
        if not stale:
            raise StoreLocked(
                f"{path} is in use by another sweep (pid {pid} on host {h}, since "
                f"{held.get('started_utc')}); wait for it to finish, or use another --out. If "
                f"that process is gone, remove {f}"
            )
        f.unlink(missing_ok=True)
        if notify is not None:
            notify(
                f"{path}: took over a stale lock of pid {pid} on {h} (started "
                f"{held.get('started_utc')}; that process no longer exists)"
            )
    else:
        raise StoreLocked(f"{path}: could not take the lock {f} (contended); try again")
    try:
        yield me
    finally:
        if read_lock(path) == me:
            f.unlink(missing_ok=True)
