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
is one file (``pd.read_parquet("OUT/cases.parquet")``). :func:`load` and
:func:`load_curves` read both, dropping any duplicate.

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
converted by :func:`migrate` (``warptrunc sweep --migrate OUT``); :func:`run_sweep` converts
them on open, :func:`load` refuses them with that command.

Why a store apart from ``warptrunc.reproduce.store``: this one holds many small cases as
Parquet rows, written concurrently by workers and resumed case by case; the reproduce store holds
one JSON document per stage of a fixed study. Both write through
:func:`warptrunc._results.write_atomic` and convert values with :func:`warptrunc._results.jsonable`.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from .._atomic import jsonable_strict, read_json, strict_json
from .._results import jsonable, write_atomic
from .curves import (
    CURVE_COLUMNS,
    clean_rows,
    parquet_bytes,
    part_files,
    part_rows,
    read_part_curves,
    write_part,
)  # fmt: skip
from .grid import FORMAT, STORE_FORMAT, SweepGrid, SweepOptions

__all__ = [
    "BEM_QUANTITIES", "CASE_COLUMNS", "CURVE_COLUMNS", "RUN_COLUMNS", "Store", "bem_long",
    "conflict", "load", "load_curves", "migrate",
]  # fmt: skip

CASE_COLUMNS = (
    "case_id", "case_index", "D_in", "delta", "seed", "Rt_m", "Wr_m", "Lx_m", "Ly_m", "nx",
    "ny", "M", "gamma", "Wc_m", "cutoff", "increments", "max_depth_fraction", "max_depth_m",
    "E_Pa", "nu", "E_flat_Pa", "nu_flat", "beta_prime", "min_pixels", "min_pixels_fraction",
    "depth_window_lo_m", "depth_window_hi_m", "alpha", "beta", "r2", "n_points",
    "fit_depth_min_m", "fit_depth_max_m", "final_contact_pixels", "final_area_fraction",
    "Rt_measured_m", "D_tri", "D_tri_r2", "D_box", "D_box_r2", "D_vs", "D_vs_r2", "D_sp",
    "D_sp_r2", "fractal_options", "fractal_seconds", "fit_error", "error", "seconds", "device", "device_name", "host", "finished_utc",
    "warptrunc_version", "git_commit",
)  # fmt: skip
"""Columns of ``cases.parquet``, in order; units in the names (SI).

``min_pixels_fraction`` is NaN for a ``min_pixels`` fit range and f for a
``min_pixels_fraction`` one (``min_pixels`` then holds the count it resolved to, 0 when the
case failed). ``D_<method>``, ``D_<method>_r2``, ``fractal_options`` (JSON) and
``fractal_seconds`` (s) are NaN/null unless the sweep ran with ``fractal_methods``. With
``bem_fractions`` the columns of ``bem_columns`` follow."""

RUN_COLUMNS = ("seconds", "fractal_seconds", "device", "device_name", "host", "finished_utc", "git_commit")
"""Columns that describe how and where a case ran rather than its result."""

BEM_QUANTITIES = (
    "bem_depth_m", "F_bem_N", "A_bem_m2", "k_bem_N_per_m", "F_trunc_N", "A_trunc_m2",
    "k_trunc_N_per_m", "F_ratio", "A_ratio", "k_ratio", "bem_converged", "bem_iterations",
)  # fmt: skip
"""Elastic columns per approach fraction f, named ``<quantity>_<f>`` (``F_bem_N_0.1``).

δ = f·R_t (m, measured R_t) is the approach; ``*_bem_*`` are the elastic solver's load (N), real
contact area (m²) and stiffness (N/m, Barber's punch of the contact set), ``*_trunc_*`` Eq. 2's
truncation values at the same depth, ``*_ratio`` = elastic / truncation (dimensionless);
``bem_converged`` (boolean) is False for a solve that hit its iteration limit (kept, not
dropped), ``bem_iterations`` its CG iterations. Per case: ``bem_seconds`` (s) and ``bem_error``
(the solver raised; the truncation results are kept)."""


def bem_columns(fractions) -> tuple[str, ...]:
    """The elastic columns of a sweep with these ``bem_fractions`` (empty for none)."""
    out = tuple(f"{q}_{f:g}" for f in fractions for q in BEM_QUANTITIES)
    return (*out, "bem_seconds", "bem_error") if out else ()


_INT = ("case_index", "seed", "nx", "ny", "M", "increments", "min_pixels")
_NULLABLE_INT = ("n_points", "final_contact_pixels")
_STR = ("case_id", "cutoff", "fractal_options", "fit_error", "error", "device", "device_name", "host",
        "finished_utc", "warptrunc_version", "git_commit", "bem_error")  # fmt: skip
_MANIFEST_KEY = b"warptrunc.parts"
_CHECK = True  # test hook: the per-part rows are checked against the grid


def require_extra() -> None:
    """Import pandas and pyarrow, or raise ImportError naming the extra to install."""
    try:
        import pandas  # noqa: F401
        import pyarrow  # noqa: F401
    except ImportError as exc:
        raise ImportError(
            f"sweeps need pandas and pyarrow ({exc.name} is missing): "
            'pip install "warptrunc[sweep]"'
        ) from None


_RENAMED = {"rt_measured_m": "Rt_measured_m"}
"""Columns of stores written before R_t was spelled ``Rt`` everywhere, read under the new name."""


def rows_frame(rows: list[dict[str, Any]], columns: tuple[str, ...] | None = None):
    """The rows as a DataFrame with the columns and dtypes of ``cases.parquet``.

    ``columns`` defaults to CASE_COLUMNS and the elastic columns the rows hold.
    """
    import pandas as pd

    if rows and any(k in rows[0] for k in _RENAMED):
        rows = [{_RENAMED.get(k, k): v for k, v in r.items()} for r in rows]
    if columns is None:
        extra = [k for k in (rows[0] if rows else {}) if k not in CASE_COLUMNS]
        columns = (*CASE_COLUMNS, *extra)
    data = {}
    for c in columns:
        values = [r.get(c) for r in rows]
        if c in _INT:
            data[c] = pd.array(values, dtype="int64")
        elif c in _NULLABLE_INT or c.startswith("bem_iterations_"):
            data[c] = pd.array(values, dtype="Int64")
        elif c in _STR:
            data[c] = pd.array(values, dtype="string")
        elif c.startswith("bem_converged_"):
            data[c] = pd.array(values, dtype="boolean")
        else:
            data[c] = np.array([np.nan if v is None else v for v in values], dtype=np.float64)
    return pd.DataFrame(data, columns=list(columns))


def _sorted(df):
    if "min_pixels_fraction" not in df:  # a store written before that column existed
        df = df.assign(min_pixels_fraction=np.nan)
    keys = ["case_index", "min_pixels_fraction", "min_pixels"]
    return df.sort_values(keys, kind="stable", na_position="first").reset_index(drop=True)


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
            old = read_json(meta)
            _check_same(self.path, old, spec)
            migrate(self.path, notify=notify)  # the previous layout, or its leftovers
        elif (self.path / "cases.parquet").exists() or self.curves.exists():
            raise ValueError(
                f"{self.path} holds sweep results but no sweep.json; use --overwrite or a new --out"
            )
        self.curves.mkdir(parents=True, exist_ok=True)
        for tmp in [*self.path.glob(".*.tmp-*"), *self.curves.glob(".*.tmp-*")]:
            tmp.unlink()  # left by a crash mid-write: never a readable part
        if not meta.exists():
            write_atomic(meta, strict_json(spec).encode())  # E_flat: null = rigid (inf)
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
            ``format``, ``grid``, ``options`` and ``n_cases``.
        """
        return {
            "format": STORE_FORMAT,
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
        if (self.path / "cases.parquet").exists() and _manifest(self.path) != set(
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
            self._frame = _sorted(rows_frame(rows, self.columns))
        return self._frame.copy()

    def flush(self) -> None:
        """Rewrite ``cases.parquet`` (atomically) if cases were recorded since the last flush.

        While streaming, the interval grows to 10× the time a flush takes, so that rewriting
        a large table never dominates (the parts hold every row meanwhile).
        """
        t0 = time.monotonic()
        self._last_flush = t0
        if self.path is None or not self._dirty:
            return
        manifest = json.dumps(sorted(set(self.part_of.values()))).encode()
        data = parquet_bytes(self.frame(), {_MANIFEST_KEY: manifest})
        write_atomic(self.path / "cases.parquet", data)
        self._dirty = False
        self._interval = max(self.flush_interval, 10 * (time.monotonic() - t0))


def _manifest(path: Path) -> set[str] | None:
    import pyarrow.parquet as pq

    try:
        meta = pq.read_schema(path / "cases.parquet").metadata or {}
    except (OSError, ValueError):
        return None
    return set(json.loads(meta[_MANIFEST_KEY])) if _MANIFEST_KEY in meta else None


def _isna(v: Any) -> bool:
    import pandas as pd

    return v is None or v is pd.NA


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


def _open_spec(path: Path) -> dict[str, Any]:
    meta = path / "sweep.json"
    if not meta.exists():
        raise FileNotFoundError(f"{path} is not a sweep store (no sweep.json)")
    spec = read_json(meta)
    if spec.get("format") == FORMAT:
        raise ValueError(
            f"{path} is a sweep store of the previous layout (one curve file per case); "
            f"convert it with: warptrunc sweep --migrate {path}"
        )
    return spec


def _unique_parts(path: Path) -> list[tuple[Path, list[list[dict[str, Any]]]]]:
    """(part, its cases' rows) in name order, each case kept in its first part only."""
    seen: set[str] = set()
    out = []
    for f in part_files(path / "curves"):
        held = part_rows(f)
        if held is None:
            continue
        held = [rs for rs in held if rs[0]["case_id"] not in seen]
        seen.update(rs[0]["case_id"] for rs in held)
        if held:
            out.append((f, held))
    return out


def load(path: str | Path):
    """The cases table of the store at ``path``, in grid order.

    Parameters
    ----------
    path : path
        The store folder.

    Returns
    -------
    pandas.DataFrame
        ``cases.parquet`` when it holds every part present; otherwise (a sweep killed before
        its last flush, or still running) the table rebuilt from the parts, so nothing that
        finished is missing and no case appears twice.

    Raises
    ------
    FileNotFoundError
        If ``path`` holds no ``sweep.json``.
    ValueError
        If the store has the previous layout (the message gives the command converting it).
    """
    require_extra()
    import pyarrow.parquet as pq

    path = Path(path)
    spec = _open_spec(path)
    columns = (*CASE_COLUMNS, *bem_columns(spec.get("options", {}).get("bem_fractions", ())))
    parts = _unique_parts(path)
    f = path / "cases.parquet"
    if f.exists() and _manifest(path) == {p.name for p, _ in parts}:
        return _sorted(pq.read_table(f).to_pandas().rename(columns=_RENAMED))
    rows = [r for _, held in parts for rs in held for r in rs]
    return _sorted(rows_frame(rows, columns))


def load_curves(path: str | Path, case_id: str | None = None):
    """Curves of the store at ``path``: one case's, or all (long format with ``case_id``).

    Parameters
    ----------
    path : path
        The store folder.
    case_id : str, optional
        One case (ValueError if no part holds its curve).

    Returns
    -------
    pandas.DataFrame
        ``case_id`` and CURVE_COLUMNS (SI units in the names), rows in part order (grid
        order), each case from its first part only. Failed cases have no rows.
    """
    require_extra()
    import pandas as pd

    path = Path(path)
    _open_spec(path)
    frames = []
    for f, held in _unique_parts(path):
        ids = [rs[0]["case_id"] for rs in held]
        if case_id is not None:
            if case_id not in ids:
                continue
            ids = [case_id]
        frames.append(read_part_curves(f, ids))
    if case_id is not None and not frames:
        raise ValueError(f"case_id {case_id!r} has no curve in {path}")
    if not frames:
        return pd.DataFrame({"case_id": pd.Series(dtype=object),
                             **{k: pd.Series(dtype=float) for k in CURVE_COLUMNS}})  # fmt: skip
    return pd.concat(frames, ignore_index=True)


def bem_long(df):
    """The elastic columns of a cases table in long format: one row per case × fit range × f.

    Parameters
    ----------
    df : pandas.DataFrame
        A cases table (:func:`load`) of a sweep with ``bem_fractions``.

    Returns
    -------
    pandas.DataFrame
        ``case_id``, ``min_pixels``, ``min_pixels_fraction``, ``D_in``, ``delta``, ``seed``,
        ``alpha``, ``bem_fraction`` (f, dimensionless) and one column per quantity of
        :data:`BEM_QUANTITIES` without the suffix (``F_bem_N``, ``k_ratio``, ...).
    """
    import pandas as pd

    keys = ["case_id", "min_pixels", "min_pixels_fraction", "D_in", "delta", "seed", "alpha"]
    fracs = sorted({c[len("F_bem_N_"):] for c in df.columns if c.startswith("F_bem_N_")},
                   key=float)  # fmt: skip
    parts = []
    for f in fracs:
        part = df[keys].copy()
        part["bem_fraction"] = float(f)
        for q in BEM_QUANTITIES:
            part[q] = df[f"{q}_{f}"]
        parts.append(part)
    if not parts:
        return pd.DataFrame(columns=[*keys, "bem_fraction", *BEM_QUANTITIES])
    return pd.concat(parts, ignore_index=True)


def migrate(path: str | Path, *, notify: Callable[[str], Any] | None = None) -> int:
    """Convert a store of format ``warptrunc-sweep/1`` (one curve file per case) in place.

    Parameters
    ----------
    path : path
        The store folder. The caller holds its lock (``warptrunc sweep --migrate`` does).
    notify : callable, optional
        Called with a one-line message when the store was converted.

    Returns
    -------
    int
        Cases converted (count); 0 when the store has the current layout already.

    Notes
    -----
    The rows (``cases.parquet``, completed by the rows kept in each curve file) and curves go
    into parts of at most 1000 cases; then ``sweep.json`` gets the new format tag, and only then
    are the old curve files and ``cases.parquet`` removed. A migration interrupted before the
    tag changed starts over (its parts are removed first); one interrupted after it only
    leaves old files, which the next open removes. Case ids do not change.
    """
    require_extra()
    import pyarrow.parquet as pq

    path = Path(path)
    meta = path / "sweep.json"
    spec = read_json(meta)
    curves = path / "curves"
    if spec.get("format") != FORMAT:
        for f in curves.glob("*.parquet") if curves.is_dir() else []:
            if not f.name.startswith("part-"):
                f.unlink()  # left by a migration interrupted after its last step's first half
        return 0
    for f in part_files(curves):
        f.unlink()  # an interrupted migration
    rows: dict[str, list[dict[str, Any]]] = {}
    table = path / "cases.parquet"
    if table.exists():
        df = pq.read_table(table).to_pandas().rename(columns=_RENAMED)
        for r in df.to_dict("records"):
            r = {k: (None if _isna(v) else jsonable(v, nonfinite="keep")) for k, v in r.items()}
            rows.setdefault(r["case_id"], []).append(r)
    files = {f.stem: f for f in curves.glob("*.parquet")} if curves.is_dir() else {}
    for cid, f in files.items():
        if cid not in rows:
            try:
                m = pq.read_schema(f).metadata or {}
            except (OSError, ValueError):
                continue
            if b"warptrunc.rows" in m:
                rows[cid] = json.loads(m[b"warptrunc.rows"])
    order = sorted(rows, key=lambda c: rows[c][0]["case_index"])
    for i in range(0, len(order), 1000):
        results = []
        for cid in order[i : i + 1000]:
            curve = None
            if cid in files and rows[cid][0].get("error") is None:
                t = pq.read_table(files[cid]).to_pandas()
                curve = {k: t[k].to_numpy() for k in CURVE_COLUMNS}
            results.append((rows[cid], curve))
        write_part(curves, results)
    write_atomic(meta, strict_json({**spec, "format": STORE_FORMAT}).encode())
    for f in files.values():
        f.unlink()
    table.unlink(missing_ok=True)
    if notify is not None:
        notify(f"{path}: converted {len(order)} cases of the previous store layout (one curve "
               f"file per case) into {-(-len(order) // 1000)} part(s) in {curves}")  # fmt: skip
    return len(order)
