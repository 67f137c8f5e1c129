# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Every file warptrunc writes: strict JSON, full-precision CSV, and all-or-nothing writes.

The one module of JSON values and file writes; the commands, the result types and the stores
(sweep, compare, reproduce) all write through it.

JSON values
    :func:`jsonable` turns nested dicts, lists, NumPy arrays and scalars into plain JSON types
    (``nonfinite`` says what becomes of NaN and ±inf). :func:`strict_json` writes standard JSON
    (RFC 8259): no ``NaN``/``Infinity`` tokens. A non-finite float becomes ``null``; the key's
    documentation says what ``null`` means (``E_i``/``E_flat_Pa`` = null: a rigid flat,
    E = ∞; a fit value = null: no fit). :func:`read_json` reads such a file back and maps
    ``null`` to ``inf`` for the keys of :data:`INF_KEYS` (the moduli of a rigid flat).

CSV
    :func:`write_columns_csv` writes equal-length columns (``to_dict`` of the result classes)
    at full float64 precision (:func:`csv_cell`).

All-or-nothing outputs
    :func:`staged_outputs` is the one mechanism of every command: it hands out staging folders
    (for an output folder) and temporary sibling files (for an output file) and renames them
    all into place when the block succeeds, or removes them all when it fails.
    :func:`staged_output` yields a hidden staging folder inside ``--out``; the command writes
    every file there, and only when the block ends without an exception are the files renamed
    into ``--out`` (each rename atomic on POSIX). On an exception the staging folder is removed,
    and so is ``--out`` itself (and the parents) if the command created it: a failed command
    leaves nothing new behind, and files of an earlier run in ``--out`` are untouched.

Records of a store
    :func:`write_atomic` writes one file of a resumable store (sweep, compare, reproduce)
    through a fsynced temporary file in the same folder and a rename, so a crash leaves either
    the old file or the new one; :func:`store_rollback` removes what a failed run that
    finished nothing created.

Writable paths
    :func:`probe_writable` creates and removes a temporary folder in the nearest existing
    ancestor of a path, which answers "can I write there" on every filesystem (``os.access`` is
    wrong for root and for pseudo-filesystems such as /proc).
"""

from __future__ import annotations

import csv
import json
import math
import os
import shutil
import tempfile
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Literal

import numpy as np

__all__ = [
    "INF_KEYS",
    "Staging",
    "csv_cell",
    "jsonable",
    "kept_stores",
    "probe_writable",
    "read_json",
    "staged_output",
    "staged_outputs",
    "store_rollback",
    "strict_json",
    "write_atomic",
    "write_columns_csv",
]

INF_KEYS = frozenset({"E_i", "E_flat", "E_flat_Pa"})
"""Keys whose ``null`` means ``inf`` (the modulus of a rigid flat)."""

STAGING_PREFIX = ".warptrunc-partial-"
"""Name prefix of the staging folders inside an output folder (removed on failure)."""


def jsonable(v: Any, *, nonfinite: Literal["null", "text", "keep"] = "null") -> Any:
    """Nested mappings/lists/tuples, NumPy arrays and NumPy scalars → JSON types; a path → str.

    ``nonfinite`` says what becomes of NaN and ±inf floats: ``"null"`` → ``None`` (strict JSON:
    every JSON file, the reproduce store), ``"text"`` → ``"nan"``/``"inf"``/``"-inf"`` (read
    back by ``float()``: surface metadata, calibration targets), ``"keep"`` → the float itself
    (Parquet rows of the sweep store, where NaN is a missing value).
    """
    if isinstance(v, Mapping):
        return {str(k): jsonable(x, nonfinite=nonfinite) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [jsonable(x, nonfinite=nonfinite) for x in v]
    if isinstance(v, np.ndarray):
        return jsonable(v.tolist(), nonfinite=nonfinite)
    if isinstance(v, np.generic):
        return jsonable(v.item(), nonfinite=nonfinite)
    if isinstance(v, float) and not math.isfinite(v):
        return None if nonfinite == "null" else str(v) if nonfinite == "text" else v
    if isinstance(v, Path):
        return str(v)
    return v


def strict_json(obj: Any, *, indent: int | None = 2) -> str:
    """``obj`` as strict JSON text (non-finite floats as null), ending in a newline."""
    return json.dumps(jsonable(obj), indent=indent, allow_nan=False, default=str) + "\n"


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

    Older files with ``Infinity`` tokens are read as well. A file that is not JSON (cut short
    by a full disk or a crash, or not text) raises ValueError naming the file.
    """
    path = Path(path)
    try:
        return _null_to_inf(json.loads(path.read_text(encoding="utf-8")))
    except ValueError as exc:  # JSONDecodeError, UnicodeDecodeError
        from .messages import one_line

        raise ValueError(
            f"{path}: not valid JSON, the file is damaged (cut short?): {one_line(exc, 120)}"
        ) from None


def csv_cell(v: Any) -> Any:
    """One CSV cell: booleans and integers as integers, text as it is, everything else as
    ``repr(float(v))`` (the shortest text that reads back to the same float64; ``nan``/``inf``
    as such)."""
    if isinstance(v, (bool, np.bool_, np.integer)):
        return int(v)
    if isinstance(v, str):  # np.str_ too
        return str(v)
    return repr(float(v))


def write_columns_csv(path: str | Path, columns: dict[str, Any]) -> Path:
    """Write equal-length columns as CSV: a header row of the keys, then one row per index.

    Raises ValueError (from ``zip(strict=True)``) when the columns differ in length.
    """
    path = Path(path)
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(columns)
        for row in zip(*columns.values(), strict=True):
            w.writerow([csv_cell(v) for v in row])
    return path


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
    from .messages import show

    if not anc.is_dir():
        return f"{show(anc)} is not a folder"
    try:
        tmp = tempfile.mkdtemp(prefix=".warptrunc-probe-", dir=anc)
    except OSError as exc:
        return f"cannot write under {show(anc)} ({exc.strerror or type(exc).__name__})"
    os.rmdir(tmp)
    return None


def _created_parents(out: Path) -> list[Path]:
    """The folders that ``out.mkdir(parents=True)`` would create, innermost first."""
    made = []
    q = out.absolute()
    while not q.exists() and q != q.parent:
        made.append(q)
        q = q.parent
    return made


class Staging:
    """One all-or-nothing set of outputs: folders and single files, committed together.

    Made by :func:`staged_outputs`; do not build it directly. :meth:`folder` gives a staging
    folder for an output folder, :meth:`file` a temporary sibling for an output file. The
    destinations are touched only by :meth:`commit` (renames within each file system); until
    then a failure removes every staged file and every folder that this set created.
    """

    def __init__(self) -> None:
        self._created: list[Path] = []  # folders made for the outputs, innermost first
        self._folders: list[tuple[Path, Path]] = []  # (staging folder, destination folder)
        self._files: list[tuple[Path, Path]] = []  # (temporary file, destination file)
        self.targets: list[Path] = []
        """The output folders and files asked for, in order."""

    def _make_parents(self, folder: Path) -> None:
        made = _created_parents(folder)
        try:
            folder.mkdir(parents=True, exist_ok=True)
        finally:
            self._created = [d for d in made if d.is_dir()] + self._created

    def folder(self, out: str | Path) -> Path:
        """A hidden staging folder whose files go into ``out`` on commit.

        Parameters
        ----------
        out : path
            The output folder (created if missing; removed again on failure).

        Returns
        -------
        Path
            The staging folder inside ``out``; write every output file there (sub-folders
            allowed).
        """
        out = Path(out)
        self.targets.append(out)
        self._make_parents(out)
        stage = Path(tempfile.mkdtemp(prefix=STAGING_PREFIX, dir=out))
        self._folders.append((stage, out))
        return stage

    def file(self, path: str | Path) -> Path:
        """A temporary sibling of ``path`` that replaces ``path`` on commit.

        Parameters
        ----------
        path : path
            The output file (its folder is created if missing; removed again on failure).

        Returns
        -------
        Path
            An empty temporary file in the same folder (``.<stem>.partial-*<suffix>``).
        """
        path = Path(path)
        self.targets.append(path)
        self._make_parents(path.parent)
        fd, tmp = tempfile.mkstemp(
            dir=path.parent, prefix=f".{path.stem}.partial-", suffix=path.suffix
        )
        os.close(fd)
        self._files.append((Path(tmp), path))
        return Path(tmp)

    def _moves(self) -> list[tuple[Path, Path]]:
        moves = list(self._files)
        for stage, out in self._folders:
            for f in sorted(p for p in stage.rglob("*") if not p.is_dir()):
                moves.append((f, out / f.relative_to(stage)))
        for _, dest in moves:
            if dest.is_dir():
                raise IsADirectoryError(f"cannot write {dest}: a folder of that name exists")
        return moves

    def commit(self) -> None:
        """Move every staged file onto its destination and remove the staging folders."""
        temporary = {tmp for tmp, _ in self._files}
        for src, dest in self._moves():
            dest.parent.mkdir(parents=True, exist_ok=True)
            if src in temporary:
                os.chmod(src, 0o644)  # mkstemp made it 0600
            os.replace(src, dest)
        for stage, _ in self._folders:
            shutil.rmtree(stage, ignore_errors=True)
        self._folders, self._files, self._created = [], [], []

    def failed_output(self) -> Path | None:
        """The output that a write without a file name in its error was most likely writing:
        the destination of the staged file modified last (the write that failed leaves its
        file the newest), else the first output asked for; None when none was asked for."""
        staged = [(tmp, dest) for tmp, dest in self._files if tmp.exists()]
        for stage, out in self._folders:
            staged += [(f, out / f.relative_to(stage)) for f in stage.rglob("*") if f.is_file()]
        if staged:
            return max(staged, key=lambda s: (s[0].stat().st_mtime_ns, s[0].stat().st_size))[1]
        return self.targets[0] if self.targets else None

    def rollback(self) -> None:
        """Remove every staged file, staging folder and folder this set created."""
        for stage, _ in self._folders:
            shutil.rmtree(stage, ignore_errors=True)
        for tmp, _ in self._files:
            tmp.unlink(missing_ok=True)
        for d in self._created:  # innermost first; stops at a folder that is not empty
            try:
                d.rmdir()
            except OSError:
                break
        self._folders, self._files, self._created = [], [], []


@contextmanager
def staged_outputs() -> Iterator[Staging]:
    """All-or-nothing outputs of one command, in several folders and files.

    Yields
    ------
    Staging
        Ask it for staging folders (:meth:`Staging.folder`) and temporary files
        (:meth:`Staging.file`) and write there.

    Notes
    -----
    When the block ends without an exception every staged file is renamed onto its destination
    (each rename atomic on POSIX; destinations are checked first, so that a rename fails only
    in exceptional cases). On any exception (KeyboardInterrupt included) the staged files are
    removed, and so are the output folders (and their parents) this call created, and the
    exception propagates: a failed command leaves nothing new behind, and files of an earlier
    run are untouched.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> root = pathlib.Path(tempfile.mkdtemp())
    >>> with staged_outputs() as st:
    ...     _ = (st.folder(root / "out") / "a.txt").write_text("a")
    ...     _ = st.file(root / "b.json").write_text("{}")
    >>> sorted(p.name for p in root.rglob("*"))
    ['a.txt', 'b.json', 'out']
    """
    st = Staging()
    try:
        yield st
        st.commit()
    except OSError as exc:  # a full disk, a file-size limit: say which output could not be made
        where = st.failed_output() if exc.filename is None and exc.errno is not None else None
        st.rollback()
        if where is not None:
            raise OSError(exc.errno, exc.strerror or str(exc), str(where)) from exc
        raise
    except BaseException:
        st.rollback()
        raise


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
    :func:`staged_outputs` with one folder: on success every file is renamed into ``out``
    (replacing files of the same name) and the staging folder is removed. On any exception
    (including KeyboardInterrupt) the staging folder is removed, ``out`` and its parents are
    removed again if this call created them, and the exception propagates.
    """
    with staged_outputs() as st:
        yield st.folder(out)


def write_atomic(path: str | Path, data: str | bytes) -> Path:
    """Write ``data`` to ``path`` through a fsynced temporary file in the same folder and a rename.

    One record of a store, durable on its own (the commands' outputs are staged together by
    :func:`staged_outputs` instead). The temporary file is named
    ``.<name>.tmp-<pid>-<random>``, so a store can find and delete those a crash left behind
    (``.*.tmp-*``).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.tmp-{os.getpid()}-")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data.encode() if isinstance(data, str) else data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


_kept: list[Path] = []


def kept_stores() -> list[Path]:
    """The stores that :func:`store_rollback` kept after a failure in this process (oldest
    first): a resumable store of finished cases, left for the same command to resume."""
    return list(_kept)


def _tree(out: Path) -> set[Path]:
    if not out.is_dir():
        return set()
    return {out, *out.rglob("*")}


@contextmanager
def store_rollback(out: str | Path, keep: Callable[[], bool]) -> Iterator[None]:
    """For a resumable store (sweep, compare): a failed run that finished nothing leaves
    nothing new.

    Parameters
    ----------
    out : path
        The store folder (it may exist, hold an earlier run, or not exist yet).
    keep : callable
        Called after a failure: True when the run stored results worth resuming (then every
        file stays, as the store promises); False to remove what the run created.

    Notes
    -----
    On an exception with ``keep()`` False, every file and folder under ``out`` that did not
    exist when the block started is removed (files first, deepest folders first), and so are
    ``out`` and its parents if the block created them; files of an earlier run are untouched.
    With ``keep()`` True, ``out`` is recorded in :func:`kept_stores` (what the command's
    one-line message after Ctrl-C names). The exception propagates.
    """
    out = Path(out)
    created = _created_parents(out)
    before = _tree(out)
    try:
        yield
    except BaseException:
        if keep():
            _kept.append(out)
        else:
            new = sorted(_tree(out) - before, key=lambda p: len(p.parts), reverse=True)
            for p in new:
                try:
                    if p.is_dir() and not p.is_symlink():
                        p.rmdir()
                    else:
                        p.unlink()
                except OSError:
                    pass
            for d in created:  # innermost first; out itself may be gone already
                try:
                    d.rmdir()
                except FileNotFoundError:
                    continue
                except OSError:
                    break
        raise
