# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The result store: a directory holding a sweep's grid, cases table and per-case curves.

Layout::

    OUT/sweep.json              format tag, grid, options (what made the store)
    OUT/cases.parquet           one row per case × fit range (see CASE_COLUMNS)
    OUT/curves/<case_id>.parquet  the case's curve (depth_m, n_contact_pixels, ...); its
                                Parquet metadata also holds the case's rows, so the cases
                                table can be rebuilt from the curve files alone

Every file is written to a temporary name in the same folder, made durable and renamed
(atomic on POSIX), so a crash leaves either the old file or the new one. ``sweep.json`` and
``cases.parquet`` are fsynced one by one; curve files come in batches (:func:`write_curves`:
all temporaries written, one ``syncfs`` of the filesystem, the renames, one fsync of the
folder), which keeps the same guarantee at one sync per batch instead of one per case. A
curve file is never replaced: the first attempt of a case wins. A case counts as finished
once its curve file exists (and parses); ``cases.parquet`` is rewritten at most every
``flush_interval`` seconds and on close, and rows missing from it after a hard kill are
recovered from the curve files on the next open. The sweep's client is the only writer of
``cases.parquet``; curve files are written by the client or, with worker writes, by the Dask
workers (on a filesystem they share with the client).

Why a store apart from ``warptrunc.reproduce.store``: this one holds many small cases as
Parquet rows, written concurrently by workers and resumed case by case; the reproduce store holds
one JSON document per stage of a fixed study. Both write through
:func:`warptrunc._results.write_atomic` and convert values with :func:`warptrunc._results.jsonable`.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import numpy as np

from .._atomic import jsonable_strict, read_json, strict_json
from .._results import jsonable, write_atomic
from .curves import CURVE_COLUMNS, curve_rows, parquet_bytes, write_curves
from .grid import FORMAT, SweepGrid, SweepOptions

__all__ = [
    "CASE_COLUMNS", "CURVE_COLUMNS", "RUN_COLUMNS", "Store", "conflict", "load", "load_curves",
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
``fractal_seconds`` (s) are NaN/null unless the sweep ran with ``fractal_methods``."""

RUN_COLUMNS = ("seconds", "fractal_seconds", "device", "device_name", "host", "finished_utc", "git_commit")
"""Columns that describe how and where a case ran rather than its result."""


_INT = ("case_index", "seed", "nx", "ny", "M", "increments", "min_pixels")
_NULLABLE_INT = ("n_points", "final_contact_pixels")
_STR = ("case_id", "cutoff", "fractal_options", "fit_error", "error", "device", "device_name", "host",
        "finished_utc", "warptrunc_version", "git_commit")  # fmt: skip


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


def rows_frame(rows: list[dict[str, Any]]):
    """The rows as a DataFrame with the columns and dtypes of ``cases.parquet``."""
    import pandas as pd

    rows = [{_RENAMED.get(k, k): v for k, v in r.items()} for r in rows]
    df = pd.DataFrame.from_records(rows, columns=list(CASE_COLUMNS))
    for c in _INT:
        df[c] = df[c].astype("int64")
    for c in _NULLABLE_INT:
        df[c] = df[c].astype("Int64")
    for c in _STR:
        df[c] = df[c].astype("string")
    for c in set(CASE_COLUMNS) - set(_INT) - set(_NULLABLE_INT) - set(_STR):
        df[c] = df[c].astype("float64")
    return df


def _sorted(df):
    if "min_pixels_fraction" not in df:  # a store written before that column existed
        df = df.assign(min_pixels_fraction=np.nan)
    keys = ["case_index", "min_pixels_fraction", "min_pixels"]
    return df.sort_values(keys, kind="stable", na_position="first").reset_index(drop=True)


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
        Forget cases recorded with an error so that they run again.
    flush_interval : float
        Rewrite ``cases.parquet`` at most this often while cases stream in (s); see
        :meth:`flush`.
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
    ) -> None:
        require_extra()
        self.path = None if path is None else Path(path)
        self.grid, self.options = grid, options
        self.flush_interval = flush_interval
        self.rows: dict[str, list[dict[str, Any]]] = {}
        self.duplicates = 0
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
            _check_same(self.path, read_json(meta), spec)
        elif (self.path / "cases.parquet").exists() or self.curves.exists():
            raise ValueError(
                f"{self.path} holds sweep results but no sweep.json; use --overwrite or a new --out"
            )
        self.curves.mkdir(parents=True, exist_ok=True)
        for tmp in [*self.path.glob(".*.tmp-*"), *self.curves.glob(".*.tmp-*")]:
            tmp.unlink()  # left by a crash mid-write
        if not meta.exists():
            write_atomic(meta, strict_json(spec).encode())  # E_flat: null = rigid (inf)
        self._read_existing()
        if retry_failed:
            for cid in [c for c, r in self.rows.items() if r[0]["error"] is not None]:
                del self.rows[cid]
                (self.curves / f"{cid}.parquet").unlink(missing_ok=True)
                self._dirty = True
        self.flush()

    def spec(self) -> dict[str, Any]:
        """The content of ``sweep.json``.

        Returns
        -------
        dict
            ``format`` (the store format version), ``grid`` (:meth:`SweepGrid.to_dict`),
            ``options`` (:meth:`SweepOptions.to_dict`) and ``n_cases``.
        """
        return {
            "format": FORMAT,
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
        table = self.path / "cases.parquet"
        if table.exists():
            for r in load(self.path, _raw=True).to_dict("records"):
                r = {k: (None if _isna(v) else jsonable(v, nonfinite="keep")) for k, v in r.items()}
                self.rows.setdefault(r["case_id"], []).append(r)
        for f in self.curves.glob("*.parquet"):
            cid = f.stem
            if cid in self.rows or cid not in wanted:
                continue
            rows = curve_rows(f)
            if rows is not None:  # finished after the last cases.parquet flush
                self.rows[cid] = rows
                self._dirty = True
            else:  # does not parse: not finished, computed again
                f.unlink()
        for cid in set(self.rows) - wanted:
            raise ValueError(f"{self.path}: case {cid} in cases.parquet is not in the grid")

    @property
    def done(self) -> set[str]:
        """Ids of the finished cases (including recorded failures)."""
        return set(self.rows)

    def add(self, rows: list[dict[str, Any]], curve: dict[str, np.ndarray] | None) -> bool:
        """Record one finished case; returns False (and writes nothing) for a duplicate.

        ``add_many([(rows, curve)])[0]``: see :meth:`add_many`.

        Parameters
        ----------
        rows : list of dict
            The case's result rows; the first holds its ``case_id``.
        curve : dict of str to ndarray or None
            Its curve, the :data:`CURVE_COLUMNS` arrays (SI units in the names), or None for
            a failed case.

        Returns
        -------
        bool
            True when the case was recorded, False for a duplicate.
        """
        return self.add_many([(rows, curve)])[0]

    def add_many(
        self, results: list[tuple[list[dict[str, Any]], dict[str, np.ndarray] | None]]
    ) -> list[bool]:
        """Record finished cases, writing their curve files as one batch (:func:`write_curves`).

        Returns, per case, False for a duplicate (nothing written, nothing recorded).
        A store without a folder records the rows only. ``cases.parquet`` is rewritten when
        the flush interval has passed.

        Parameters
        ----------
        results : list of (list of dict, dict or None)
            One ``(rows, curve)`` per case, as for :meth:`add`.

        Returns
        -------
        list of bool
            Per case, in order: True when recorded, False for a duplicate (a case already in
            the store or earlier in ``results``); duplicates are counted in ``duplicates``.
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
        if self.path is not None and fresh:
            kept = write_curves(self.curves, fresh)
        else:
            kept = [[{k: jsonable(v, nonfinite="keep") for k, v in r.items()} for r in rows] for rows, _ in fresh]
        for rows in kept:
            self._record(rows)
        return new

    def record(self, rows: list[dict[str, Any]]) -> bool:
        """Record a case whose curve file a worker already wrote; False for a duplicate.

        Parameters
        ----------
        rows : list of dict
            The case's result rows (as returned by :func:`write_curves`); the first holds its
            ``case_id``.

        Returns
        -------
        bool
            True when recorded, False for a duplicate (counted in ``duplicates``).
        """
        if rows[0]["case_id"] in self.rows:
            self.duplicates += 1
            return False
        self._record([{k: jsonable(v, nonfinite="keep") for k, v in r.items()} for r in rows])
        return True

    def _record(self, rows: list[dict[str, Any]]) -> None:
        self.rows[rows[0]["case_id"]] = rows
        self._dirty = True
        if time.monotonic() - self._last_flush >= self._interval:
            self.flush()

    def frame(self):
        """The cases table (DataFrame) in grid order.

        Returns
        -------
        pandas.DataFrame
            One row per recorded result row, the columns and dtypes of ``cases.parquet``
            (:data:`CASE_COLUMNS`, SI units in the names).
        """
        rows = [r for rs in self.rows.values() for r in rs]
        return _sorted(rows_frame(rows))

    def flush(self) -> None:
        """Rewrite ``cases.parquet`` (atomically) if rows were added since the last flush.

        While streaming, the interval grows to 10× the time a flush takes, so that rewriting
        a large table never dominates (the curve files hold every row meanwhile).
        """
        t0 = time.monotonic()
        self._last_flush = t0
        if self.path is None or not self._dirty:
            return
        write_atomic(self.path / "cases.parquet", parquet_bytes(self.frame()))
        self._dirty = False
        self._interval = max(self.flush_interval, 10 * (time.monotonic() - t0))


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
    if old.get("format") != new["format"]:
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

    None also when ``path`` holds no ``sweep.json`` yet (a new store).

    Parameters
    ----------
    path : str or Path
        The store folder.
    grid : SweepGrid
        The grid of the sweep to resume.
    options : SweepOptions
        Its options.

    Returns
    -------
    str or None
        The message of the conflict (another format, or the grid or options entries that
        differ from the stored ``sweep.json``), or None when the store can be resumed.
    """
    meta = Path(path) / "sweep.json"
    if not meta.exists():
        return None
    new = {"format": FORMAT, "grid": grid.to_dict(), "options": options.to_dict()}
    try:
        _check_same(Path(path), read_json(meta), new)
    except ValueError as exc:
        return str(exc)
    return None


def load(path: str | Path, *, _raw: bool = False):
    """The cases table of the store at ``path`` as a pandas DataFrame, in grid order.

    Rows of cases finished after the last flush of ``cases.parquet`` (a killed sweep) are
    read from their curve files, so nothing that finished is missing.

    Parameters
    ----------
    path : str or Path
        The store folder (holding ``sweep.json``).
    _raw : bool
        Internal (used by :class:`Store` when it reopens a store); not for users. True returns
        ``cases.parquet`` as stored: no rows from curve files, no sorting.

    Returns
    -------
    pandas.DataFrame
        One row per result row, the columns of ``cases.parquet`` (:data:`CASE_COLUMNS`, SI
        units in the names), sorted by ``case_index``, then ``min_pixels_fraction``, then
        ``min_pixels``.

    Raises
    ------
    ImportError
        pandas or pyarrow is missing (the ``sweep`` extra).
    FileNotFoundError
        ``path`` holds no ``sweep.json``.
    """
    require_extra()
    import pyarrow.parquet as pq

    path = Path(path)
    if not (path / "sweep.json").exists():
        raise FileNotFoundError(f"{path} is not a sweep store (no sweep.json)")
    f = path / "cases.parquet"
    df = pq.read_table(f).to_pandas().rename(columns=_RENAMED) if f.exists() else rows_frame([])
    if _raw:
        return df
    have = set(df["case_id"])
    extra = []
    for c in sorted((path / "curves").glob("*.parquet")):
        if c.stem not in have:
            extra += curve_rows(c) or []
    if extra:
        import pandas as pd

        df = pd.concat([df, rows_frame(extra)], ignore_index=True)
    return _sorted(df)


def load_curves(path: str | Path, case_id: str | None = None):
    """Curves of the store at ``path``: one case's, or all (long format with ``case_id``).

    Columns: ``case_id`` and CURVE_COLUMNS (SI units in the names). Failed cases have no rows.

    Parameters
    ----------
    path : str or Path
        The store folder (holding ``sweep.json``).
    case_id : str, optional
        One case's id; None for every curve file.

    Returns
    -------
    pandas.DataFrame
        ``case_id`` followed by :data:`CURVE_COLUMNS`: ``depth_m`` (m),
        ``n_contact_pixels``, ``contact_area_m2`` (m²), ``stiffness_N_per_m`` (N/m),
        ``load_N`` (N), ``Ec_over_E`` and ``F_over_EA`` (dimensionless); the files'
        rows concatenated in ``case_id`` order. Empty (with these columns) when there are no
        curve files.

    Raises
    ------
    ImportError
        pandas or pyarrow is missing (the ``sweep`` extra).
    FileNotFoundError
        ``path`` holds no ``sweep.json``.
    ValueError
        ``case_id`` has no curve file.
    """

    require_extra()
    import pandas as pd
    import pyarrow.parquet as pq

    path = Path(path)
    curves = path / "curves"
    if not (path / "sweep.json").exists():
        raise FileNotFoundError(f"{path} is not a sweep store (no sweep.json)")
    if case_id is not None:
        f = curves / f"{case_id}.parquet"
        if not f.exists():
            raise ValueError(f"case_id {case_id!r} has no curve in {path}")
        files = [f]
    else:
        files = sorted(curves.glob("*.parquet"))
    parts = []
    for f in files:
        df = pq.read_table(f).to_pandas()
        df.insert(0, "case_id", f.stem)
        parts.append(df)
    if not parts:
        return pd.DataFrame(columns=["case_id", *CURVE_COLUMNS])
    return pd.concat(parts, ignore_index=True)
