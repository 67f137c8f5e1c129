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

Stores of format ``warptrunc-sweep/1`` (one ``curves/<case_id>.parquet`` per case) are
converted by :func:`~warptrunc.sweep.migration.migrate` (``warptrunc sweep --migrate OUT``); :func:`run_sweep` converts
them on open, :func:`~warptrunc.sweep.read.load` refuses them with that command.

Why a store apart from ``warptrunc.reproduce.store``: this one holds many small cases as
Parquet rows, written concurrently by workers and resumed case by case; the reproduce store holds
one JSON document per stage of a fixed study. Both write through
:func:`warptrunc._support.results.write_atomic` and convert values with :func:`warptrunc._support.results.jsonable`.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from .._support.atomic import jsonable_strict, read_json, strict_json
from .._support.provenance import provenance
from .._support.results import write_atomic
from .curves import (
    CURVE_COLUMNS,
    clean_rows,
    parquet_bytes,
    part_files,
    part_rows,
    read_part_curves,
    write_part,
)  # fmt: skip
from .grid import FORMAT, STORE_FORMAT, SweepGrid
from .migration import migrate
from .normalisation import NORMALISATION
from .options import SweepOptions
from .read import (
    CASE_COLUMNS,
    MANIFEST_KEY,
    bem_columns,
    manifest_parts,
    require_extra,
    rows_frame,
    sort_cases,
)  # fmt: skip

__all__ = ["Store", "conflict"]

_CHECK = True  # test hook: the per-part rows are checked against the grid

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
    notify : callable, optional
        Called with a message when a store of the previous layout is converted.
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
        notify: Callable[[str], Any] | None = None,
    ) -> None:
        require_extra()
        self.path = None if path is None else Path(path)
        self.grid, self.options = grid, options
        self.columns = (*CASE_COLUMNS, *bem_columns(options.bem_fractions))
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
            migrate(self.path, notify=notify)  # the previous layout, or its leftovers
        elif (self.path / "cases.parquet").exists() or self.curves.exists():
            raise ValueError(
                f"{self.path} holds sweep results but no sweep.json; use --overwrite or a new --out"
            )
        self.curves.mkdir(parents=True, exist_ok=True)
        self.remove_temporaries()
        if not meta.exists():
            doc = {**spec, "provenance": provenance()}  # of the run that made the store
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
            the meaning of ``beta``), ``grid``, ``options`` and ``n_cases``.
        """
        return {
            "format": STORE_FORMAT,
            "normalisation": NORMALISATION,
            "grid": self.grid.to_dict(),
            "options": self.options.to_dict(),
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
        self.duplicates += sum(1 for c, n in zip(ids, new, strict=True)
                               if not n and self.part_of.get(c) != name)  # fmt: skip
        if self.path is not None and not all(self.part_of.get(c) == name for c in ids if c in self.rows):
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
    if old.get("format") not in (FORMAT, STORE_FORMAT):
        raise ValueError(
            f"{path} is a store of format {old.get('format')!r}, not {new['format']!r}; "
            "use --overwrite or a new --out"
        )
    diff = _diff(jsonable_strict({"grid": old.get("grid"), "options": old.get("options")}),
                 jsonable_strict({"grid": new["grid"], "options": new["options"]}))  # fmt: skip
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
        The refusal message; None also when ``path`` holds no ``sweep.json`` yet (a new
        store), and for a store of the previous layout with the same grid and options
        (resuming converts it).
    """
    meta = Path(path) / "sweep.json"
    if not meta.exists():
        return None
    new = {"format": STORE_FORMAT, "grid": grid.to_dict(), "options": options.to_dict()}
    try:
        _check_same(Path(path), read_json(meta), new)
    except ValueError as exc:
        return str(exc)
    return None
