# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The result store: a directory holding a sweep's grid, its parts and the cases table.

Layout (format ``warptrunc-sweep/2``)::

    OUT/sweep.json                  format tag, grid, options (what made the store)
    OUT/curves/part-<i>-<h>.parquet one part per shard of cases: the shard's curves in long
                                    format (case_id, depth_m, n_contact_pixels, ...) and, in its
                                    Parquet metadata, the shard's rows of the cases table
    OUT/cases.parquet               one row per case × fit range (see CASE_COLUMNS), rebuilt by
                                    the client from the parts; its metadata names the parts it
                                    holds

``OUT/curves`` is a Parquet dataset that pandas, pyarrow and Dask read directly
(``pd.read_parquet("OUT/curves")``, ``dd.read_parquet("OUT/curves")``); ``cases.parquet``
is one file (``pd.read_parquet("OUT/cases.parquet")``). :func:`~warptrunc.sweep.read.load` and
:func:`~warptrunc.sweep.read.load_curves` read both, dropping any duplicate.

A part is written by whoever computed its shard (a Dask worker, or the in-process engine's
writer thread) to a temporary dot name, fsynced, and hard-linked to its final name, which
never replaces a file (:func:`~warptrunc.sweep.curves.write_part`): a crash leaves no part or a
complete one, and the first attempt of a shard wins. The set of parts present *is* the
progress of the sweep: a case is finished once a part holds it, and resuming skips exactly
those cases. A case held by two parts (a shard that the client thought lost, computed again
in a different shard) keeps the part first in name order; the client deletes a later part
all of whose cases are held elsewhere, and rewrites one that overlaps only in part.
``cases.parquet`` is rewritten at most every ``flush_interval`` seconds and on close; rows
missing from it after a hard kill are read from the parts on the next open.

A store of the layout before (format ``warptrunc-sweep/1``, one ``curves/<case_id>.parquet``
per case) was written only by development versions, for two days before 0.1 and never in a
release; it is refused, with the reason, by :class:`Store` and :func:`~warptrunc.sweep.read.load`
alike. The case ids did not change with the layout (:data:`~warptrunc.sweep.grid.CASE_ID_FORMAT`).

One sweep writes a store at a time: :func:`store_lock` creates ``OUT/.lock`` exclusively
(``O_CREAT | O_EXCL``) with the holder's pid, host and start time (JSON). A second sweep on the
same store is refused at once with :class:`StoreLocked`, naming the holder. A lock whose holder
is gone — same host, and no process of that pid — is stale: it is taken over, and the takeover
is reported through the ``notify`` callback. A lock held from another host cannot be checked and
is never taken over; the message says which file to remove once that sweep is known to be dead.

Why a store apart from ``warptrunc.reproduce.store``: this one holds many small cases as
Parquet rows, written concurrently by workers and resumed case by case; the reproduce store holds
one JSON document per stage of a fixed study. Both write through
:func:`warptrunc._support.outputs.write_atomic` and convert values with :func:`warptrunc._support.outputs.jsonable`.
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

import numpy as np

from .._support.outputs import jsonable, read_json, strict_json, write_atomic
from .._support.provenance import provenance
from .curves import (
    CURVE_COLUMNS,
    clean_rows,
    parquet_bytes,
    part_files,
    part_rows,
    read_part_curves,
    write_part,
)
from .grid import STORE_FORMAT, SweepGrid, stored_options
from .normalisation import NORMALISATION
from .options import SweepOptions
from .read import (
    CASE_COLUMNS,
    MANIFEST_KEY,
    bem_columns,
    format_refusal,
    manifest_parts,
    require_extra,
    rows_frame,
    sort_cases,
)

__all__ = ["LOCK_NAME", "Store", "StoreLocked", "conflict", "read_lock", "store_lock"]

_clean = clean_rows


class Store:
    """A sweep's result directory (or, with ``path=None``, rows kept in memory only).

    Parameters
    ----------
    path : path or None
        The store folder; created if missing.
    grid, options
        What the sweep computes; compared with ``sweep.json`` of an existing store.
    overwrite : bool
        Delete an existing store's files (sweep.json, cases.parquet, curves/) first.
    retry_failed : bool
        Forget cases recorded with an error so that they run again (their parts are
        rewritten without them).
    flush_interval : float
        Rewrite ``cases.parquet`` at most this often while cases stream in (s); see
        :meth:`flush`.
    device : str, optional
        The Warp device of the run, recorded in the provenance of a new ``sweep.json``
        (default: the one Warp resolves by default).
    """

    def __init__(
        self,
        path: str | Path | None,
        grid: SweepGrid,
        options: SweepOptions,
        *,
        overwrite: bool = False,
        retry_failed: bool = False,
        flush_interval: float = 2.0,
        device: Any = None,
    ) -> None:
        require_extra()
        self.path = None if path is None else Path(path)
        self.grid, self.options = grid, options
        self.columns = (*CASE_COLUMNS, *bem_columns(options.bem_fractions or ()))
        self.flush_interval = flush_interval
        self.rows: dict[str, list[dict[str, Any]]] = {}
        self.part_of: dict[str, str] = {}
        self.duplicates = 0
        self._frame = None
        self._dirty = False
        self._last_flush = time.monotonic()
        self._interval = flush_interval
        if self.path is None:
            return
        self.curves = self.path / "curves"
        spec = self.spec()
        meta = self.path / "sweep.json"
        if overwrite:
            self._remove()
        elif meta.exists():
            try:
                old = read_json(meta)
            except ValueError as exc:
                raise ValueError(
                    f"{exc}; its results cannot be matched to this grid: use --overwrite (removes "
                    "them) or a new --out"
                ) from None
            _check_same(self.path, old, spec)
        elif (self.path / "cases.parquet").exists() or self.curves.exists():
            raise ValueError(
                f"{self.path} holds sweep results but no sweep.json; use --overwrite or a new --out"
            )
        self.curves.mkdir(parents=True, exist_ok=True)
        self.remove_temporaries()
        if not meta.exists():
            import warp  # noqa: F401  (the provenance names Warp's version: the cases run on it)

            doc = {**spec, "provenance": provenance(device)}  # of the run that made the store
            write_atomic(meta, strict_json(doc).encode())  # E_flat: null = rigid (inf)
        self._read_existing()
        if retry_failed:
            failed = {c for c, r in self.rows.items() if r[0]["error"] is not None}
            for name in sorted({self.part_of[c] for c in failed}):
                held = [c for c, p in self.part_of.items() if p == name]
                kept = self._rewrite(name, [c for c in held if c not in failed])
                for rows in kept[1] if kept is not None else []:
                    self.part_of[rows[0]["case_id"]] = kept[0]
            for c in failed:
                del self.rows[c], self.part_of[c]
            self._frame = None
            self._dirty = self._dirty or bool(failed)
        self.flush()

    def spec(self) -> dict[str, Any]:
        """The content of ``sweep.json``.

        Returns
        -------
        dict of str to Any
            ``format``, ``normalisation`` (:data:`~warptrunc.sweep.normalisation.NORMALISATION`,
            the meaning of ``beta``), ``grid``, ``options`` (in the store's spelling,
            :func:`~warptrunc.sweep.grid.stored_options`) and ``n_cases``.
        """
        return {
            "format": STORE_FORMAT,
            "normalisation": NORMALISATION,
            "grid": self.grid.to_dict(),
            "options": stored_options(self.options),
            "n_cases": len(self.grid),
        }

    def _remove(self) -> None:
        for f in ("sweep.json", "cases.parquet"):
            (self.path / f).unlink(missing_ok=True)
        if self.curves.exists():
            for f in self.curves.iterdir():
                if f.suffix == ".parquet" or ".tmp-" in f.name:
                    f.unlink(missing_ok=True)

    def _read_existing(self) -> None:
        wanted = {c.case_id for c in self.grid.cases(self.options)}
        for f in part_files(self.curves):
            held = part_rows(f)
            if held is None:  # does not parse (power loss after the rename): computed again
                f.unlink()
                continue
            for rows in held:
                if rows[0]["case_id"] not in wanted:
                    raise ValueError(
                        f"{self.path}: case {rows[0]['case_id']} in {f.name} is not in the grid"
                    )
            self.record_part(f.name, held)
        if (self.path / "cases.parquet").exists() and manifest_parts(self.path) != set(
            self.part_of.values()
        ):
            self._dirty = True

    @property
    def done(self) -> set[str]:
        """Ids of the finished cases (including recorded failures)."""
        return set(self.rows)

    def add_many(
        self, results: list[tuple[list[dict[str, Any]], dict[str, np.ndarray] | None]]
    ) -> list[bool]:
        """Record finished cases, writing them as one part (:func:`write_part`) from here.

        Parameters
        ----------
        results : list of (list of dict, dict or None)
            Per case, its rows and curve (:func:`~warptrunc.sweep.engines.compute_case`).

        Returns
        -------
        list of bool
            Per case, False for a duplicate (nothing written, nothing recorded).
        """
        fresh, seen, new = [], set(), []
        for rows, curve in results:
            cid = rows[0]["case_id"]
            ok = cid not in self.rows and cid not in seen
            new.append(ok)
            if ok:
                seen.add(cid)
                fresh.append((rows, curve))
            else:
                self.duplicates += 1
        if not fresh:
            return new
        if self.path is None:
            for rows, _ in fresh:
                self._record(_clean(rows), None)
            return new
        name, held = write_part(self.curves, fresh)
        self.record_part(name, held)
        return new

    def add(self, rows: list[dict[str, Any]], curve: dict[str, np.ndarray] | None) -> bool:
        """Record one finished case (a part of its own).

        Parameters
        ----------
        rows : list of dict
            The case's fit-range rows.
        curve : dict of str to ndarray or None
            Its curve (None for a failed case).

        Returns
        -------
        bool
            False for a duplicate.
        """
        return self.add_many([(rows, curve)])[0]

    def record_part(self, name: str, held: list[list[dict[str, Any]]]) -> list[bool]:
        """Record a part that exists in ``curves/`` (written by a worker or by :meth:`add_many`).

        Parameters
        ----------
        name : str
            The part's file name.
        held : list of list of dict
            Its rows, one list per case (:func:`~warptrunc.sweep.curves.part_rows`).

        Returns
        -------
        list of bool
            Per case, False when another part held the case already.

        Notes
        -----
        A part all of whose cases are held elsewhere is deleted; one that overlaps in part is
        rewritten without the cases held elsewhere. Recording the same part twice changes
        nothing.
        """
        ids = [rows[0]["case_id"] for rows in held]
        new = [c not in self.rows for c in ids]
        if all(new):
            for rows in held:
                self._record(_clean(rows), name)
            return new
        self.duplicates += sum(
            1 for c, n in zip(ids, new, strict=True) if not n and self.part_of.get(c) != name
        )
        if self.path is not None and not all(
            self.part_of.get(c) == name for c in ids if c in self.rows
        ):
            keep = [c for c, n in zip(ids, new, strict=True) if n]
            kept = self._rewrite(name, keep)
            if kept is not None:
                name, held = kept
                for rows in held:
                    self._record(_clean(rows), name)
        return new

    def _rewrite(self, name: str, keep: list[str]):
        """Replace part ``name`` by one holding only ``keep`` (or by nothing); returns the new
        part's (name, rows) or None."""
        f = self.curves / name
        out = None
        if keep:
            held = {rs[0]["case_id"]: rs for rs in part_rows(f) or []}
            curves = read_part_curves(f, keep)
            results = []
            for cid in keep:
                c = curves[curves["case_id"] == cid]
                curve = {k: c[k].to_numpy() for k in CURVE_COLUMNS} if len(c) else None
                results.append((held[cid], curve))
            out = write_part(self.curves, results)
        if out is None or out[0] != name:
            f.unlink(missing_ok=True)
        return out

    def _record(self, rows: list[dict[str, Any]], part: str | None) -> None:
        cid = rows[0]["case_id"]
        self.rows[cid] = rows
        self._frame = None
        if part is not None:
            self.part_of[cid] = part
        self._dirty = True
        if time.monotonic() - self._last_flush >= self._interval:
            self.flush()

    def frame(self):
        """The cases table in grid order.

        Returns
        -------
        pandas.DataFrame
            One row per case × fit range (the columns of ``cases.parquet``).
        """
        if self._frame is None:
            rows = [r for rs in self.rows.values() for r in rs]
            self._frame = sort_cases(rows_frame(rows, self.columns))
        return self._frame.copy()

    def remove_temporaries(self) -> int:
        """Delete the temporary files of writes that never finished (a crash, or a worker killed
        mid-write): never a readable part. Called when the store opens and when a run has
        collected every case (no writer of this run is left then).

        Returns
        -------
        int
            Files removed (dimensionless count).
        """
        if self.path is None:
            return 0
        n = 0
        for tmp in [*self.path.glob(".*.tmp-*"), *self.curves.glob(".*.tmp-*")]:
            tmp.unlink(missing_ok=True)
            n += 1
        return n

    def flush(self) -> None:
        """Rewrite ``cases.parquet`` (atomically) if cases were recorded since the last flush.

        While streaming, the interval grows to 10× the time a flush takes, so that rewriting
        a large table never dominates (the parts hold every row meanwhile).
        """
        t0 = time.monotonic()
        self._last_flush = t0
        if self.path is None or not self._dirty:
            return
        names = json.dumps(sorted(set(self.part_of.values()))).encode()
        data = parquet_bytes(self.frame(), {MANIFEST_KEY: names})
        write_atomic(self.path / "cases.parquet", data)
        self._dirty = False
        self._interval = max(self.flush_interval, 10 * (time.monotonic() - t0))


def _diff(a: Any, b: Any, prefix: str = "") -> list[str]:
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for k in sorted(set(a) | set(b)):
            out += _diff(a.get(k), b.get(k), f"{prefix}{k}.")
        return out
    return [] if a == b else [f"{prefix[:-1]}: {a!r} → {b!r}"]


def _check_same(path: Path, old: dict[str, Any], new: dict[str, Any]) -> None:
    if old.get("format") != STORE_FORMAT:
        raise ValueError(format_refusal(path, old.get("format")))
    diff = _diff(
        jsonable({"grid": old.get("grid"), "options": old.get("options")}),
        jsonable({"grid": new["grid"], "options": new["options"]}),
    )
    if diff:
        shown = "; ".join(diff[:4]) + (f"; and {len(diff) - 4} more" if len(diff) > 4 else "")
        raise ValueError(
            f"{path} holds a sweep with another grid or options ({shown}); "
            "use --overwrite to replace it, or a new --out"
        )


def conflict(path: str | Path, grid: SweepGrid, options: SweepOptions) -> str | None:
    """Why the store at ``path`` cannot be resumed with ``grid`` and ``options``, or None.

    Parameters
    ----------
    path : path
        The store folder.
    grid : SweepGrid
        The grid to resume with.
    options : SweepOptions
        The options to resume with.

    Returns
    -------
    str or None
        The refusal message; None when ``path`` holds no ``sweep.json`` yet (a new store).
    """
    meta = Path(path) / "sweep.json"
    if not meta.exists():
        return None
    new = {"format": STORE_FORMAT, "grid": grid.to_dict(), "options": stored_options(options)}
    try:
        _check_same(Path(path), read_json(meta), new)
    except ValueError as exc:
        return str(exc)
    return None


# --- one writer per store: OUT/.lock ----------------------------------------------------------

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
        return {"pid": None, "host": None, "started_utc": None, "unreadable": "no pid recorded"}
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
