# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""All-or-nothing outputs and strict JSON.

Strict JSON
    :func:`strict_json` writes standard JSON (RFC 8259): no ``NaN``/``Infinity`` tokens. A
    non-finite float becomes ``null``; the key's documentation says what ``null`` means
    (``E_i``/``E_flat_Pa`` = null: a rigid flat, E = ∞; a fit value = null: no fit).
    :func:`read_json` reads such a file back and maps ``null`` to ``inf`` for the keys of
    :data:`INF_KEYS` (the moduli of a rigid flat).

All-or-nothing output folders
    :func:`staged_output` yields a hidden staging folder inside ``--out``; the command writes
    every file there, and only when the block ends without an exception are the files renamed
    into ``--out`` (each rename atomic on POSIX). On an exception the staging folder is removed,
    and so is ``--out`` itself (and the parents) if the command created it: a failed command
    leaves nothing new behind, and files of an earlier run in ``--out`` are untouched.
    :func:`atomic_write` does the same for a single file.

Writable paths
    :func:`probe_writable` creates and removes a temporary folder in the nearest existing
    ancestor of a path, which answers "can I write there" on every filesystem (``os.access`` is
    wrong for root and for pseudo-filesystems such as /proc).
"""

from __future__ import annotations

import json
import math
import os
import shutil
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "INF_KEYS",
    "atomic_write",
    "jsonable_strict",
    "probe_writable",
    "read_json",
    "staged_output",
    "strict_json",
]

INF_KEYS = frozenset({"E_i", "E_flat", "E_flat_Pa"})
"""Keys whose ``null`` means ``inf`` (the modulus of a rigid flat)."""

STAGING_PREFIX = ".warptrunc-partial-"
"""Name prefix of the staging folders inside an output folder (removed on failure)."""


def jsonable_strict(v: Any) -> Any:
    """Nested dicts/lists/tuples/NumPy values → JSON types; NaN and ±inf → None."""
    if isinstance(v, dict):
        return {str(k): jsonable_strict(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [jsonable_strict(x) for x in v]
    if isinstance(v, np.ndarray):
        return jsonable_strict(v.tolist())
    if isinstance(v, np.generic):
        return jsonable_strict(v.item())
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, Path):
        return str(v)
    return v


def strict_json(obj: Any, *, indent: int | None = 2) -> str:
    """``obj`` as strict JSON text (non-finite floats as null), ending in a newline."""
    return json.dumps(jsonable_strict(obj), indent=indent, allow_nan=False, default=str) + "\n"


def _null_to_inf(v: Any) -> Any:
    if isinstance(v, dict):
        return {
            k: (math.inf if (k in INF_KEYS and x is None) else _null_to_inf(x))
            for k, x in v.items()
        }
    if isinstance(v, list):
        return [_null_to_inf(x) for x in v]
    return v


def read_json(path: str | Path) -> Any:
    """Read a JSON file written by warptrunc; ``null`` under :data:`INF_KEYS` becomes inf.

    Older files with ``Infinity`` tokens are read as well.
    """
    return _null_to_inf(json.loads(Path(path).read_text()))


def _nearest_existing(p: Path) -> Path:
    q = p.absolute()
    while not q.exists() and q != q.parent:
        q = q.parent
    return q


def probe_writable(path: str | Path) -> str | None:
    """Why files cannot be created at ``path`` (a folder to be, or a file's folder), or None.

    Creates and removes a temporary folder in the nearest existing ancestor of ``path``.
    """
    anc = _nearest_existing(Path(path))
    if not anc.is_dir():
        return f"{str(anc)!r} is not a folder"
    try:
        tmp = tempfile.mkdtemp(prefix=".warptrunc-probe-", dir=anc)
    except OSError as exc:
        return f"cannot write under {str(anc)!r} ({exc.strerror or exc})"
    os.rmdir(tmp)
    return None


def _created_parents(out: Path) -> list[Path]:
    """The folders that ``out.mkdir(parents=True)`` would create, outermost last."""
    made = []
    q = out.absolute()
    while not q.exists() and q != q.parent:
        made.append(q)
        q = q.parent
    return made


@contextmanager
def staged_output(out: str | Path) -> Iterator[Path]:
    """A staging folder whose files are moved into ``out`` only if the block succeeds.

    Parameters
    ----------
    out : path
        The output folder (created if missing).

    Yields
    ------
    Path
        A hidden folder inside ``out``; write every output file there (sub-folders allowed).

    Notes
    -----
    On success every file is renamed into ``out`` (replacing files of the same name) and the
    staging folder is removed. On any exception (including KeyboardInterrupt) the staging
    folder is removed, ``out`` and its parents are removed again if this call created them,
    and the exception propagates.
    """
    out = Path(out)
    created = _created_parents(out)
    out.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=STAGING_PREFIX, dir=out))
    try:
        yield stage
        files = sorted(p for p in stage.rglob("*") if not p.is_dir())
        for f in files:
            dest = out / f.relative_to(stage)
            if dest.is_dir():
                raise IsADirectoryError(f"cannot write {dest}: a folder of that name exists")
        for f in files:
            dest = out / f.relative_to(stage)
            dest.parent.mkdir(parents=True, exist_ok=True)
            os.replace(f, dest)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        for d in created:  # innermost first
            try:
                d.rmdir()
            except OSError:
                break
        raise
    shutil.rmtree(stage, ignore_errors=True)


@contextmanager
def atomic_write(path: str | Path) -> Iterator[Path]:
    """A temporary path next to ``path``, renamed onto ``path`` only if the block succeeds."""
    path = Path(path)
    created = _created_parents(path.parent)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}.partial-", suffix=path.suffix)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        for d in created:
            try:
                d.rmdir()
            except OSError:
                break
        raise
