# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Parts of the sweep store (``OUT/curves/part-*.parquet``): one Parquet file per shard of
cases, written durably under a temporary name and renamed into place (first writer wins);
reading a part's rows back. The store's rules are described in :mod:`warptrunc.sweep.store`.

A part's table is the curves of its cases in long format (``case_id`` then CURVE_COLUMNS,
one row per depth increment; a failed case has no curve rows) and its key-value metadata
``warptrunc.rows`` holds the cases' rows (JSON, one list of fit-range rows per case), so the
cases table is rebuilt from the parts alone.
"""

from __future__ import annotations

import hashlib
import json
import os
import threading
from pathlib import Path
from typing import Any

import numpy as np

from .._support.outputs import jsonable
from .normalisation import upgrade_curves, upgrade_rows

__all__ = [
    "CURVE_COLUMNS",
    "PART_GLOB",
    "parquet_bytes",
    "part_files",
    "part_name",
    "part_rows",
    "read_part_curves",
    "table_bytes",
    "write_part",
]

CURVE_COLUMNS = (
    "depth_m",
    "n_contact_pixels",
    "contact_area_m2",
    "stiffness_N_per_m",
    "load_N",
    "Ec_over_E",
    "F_over_EA",
    "Ec_over_Estar",
)
"""Curve columns of a part, after ``case_id`` (as ``warptrunc analyze``'s curve.csv): E_c/E (E
the Young's modulus) is ``Ec_over_E``, E_c/E* ``Ec_over_Estar``. Parts written before the one
normalisation lack ``Ec_over_Estar`` and are read with their meaning
(:mod:`warptrunc.sweep.normalisation`)."""

PART_GLOB = "part-*.parquet"
"""Names of the parts in ``OUT/curves``; temporaries start with a dot (readers skip them)."""

_META_KEY = b"warptrunc.rows"

Result = tuple[list[dict[str, Any]], "dict[str, np.ndarray] | None"]


def parquet_bytes(df, metadata: dict[bytes, bytes] | None = None) -> bytes:
    """A DataFrame as Parquet bytes (no index), with extra key-value metadata.

    Parameters
    ----------
    df : pandas.DataFrame
        The table.
    metadata : dict of bytes to bytes, optional
        Extra schema metadata (besides pandas').

    Returns
    -------
    bytes
        The Parquet file.
    """
    import pyarrow as pa

    table = pa.Table.from_pandas(df, preserve_index=False)
    if metadata:
        table = table.replace_schema_metadata({**(table.schema.metadata or {}), **metadata})
    return table_bytes(table)


def table_bytes(table) -> bytes:
    """A pyarrow Table as Parquet bytes.

    Parameters
    ----------
    table : pyarrow.Table
        The table.

    Returns
    -------
    bytes
        The Parquet file.
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    sink = pa.BufferOutputStream()
    pq.write_table(table, sink)
    return sink.getvalue().to_pybytes()


def _fsync_dir(folder: Path) -> None:
    """fsync a directory, so that renames into it survive a power loss (POSIX only)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:  # pragma: no cover - e.g. Windows
        return
    try:
        os.fsync(fd)
    except OSError:  # pragma: no cover - filesystems that refuse directory fsync
        pass
    finally:
        os.close(fd)


def part_name(case_ids: list[str], first_index: int) -> str:
    """``part-<first case index, 8 digits>-<12 hex of SHA-256 over the sorted case ids>.parquet``.

    Parameters
    ----------
    case_ids : list of str
        Ids of the shard's cases (any order).
    first_index : int
        Grid index of the shard's first case.

    Returns
    -------
    str
        The part's file name: a function of the shard's cases only, so a retried shard writes
        the same name (and loses to the first attempt), and parts list in grid order.
    """
    h = hashlib.sha256(",".join(sorted(case_ids)).encode()).hexdigest()[:12]
    return f"part-{first_index:08d}-{h}.parquet"


def part_files(folder: str | Path) -> list[Path]:
    """The parts in ``folder``, sorted by name (grid order of their first case).

    Parameters
    ----------
    folder : path
        The store's ``curves/`` folder (missing: no parts).

    Returns
    -------
    list of Path
        The ``part-*.parquet`` files; temporaries (dot names) are not among them.
    """
    folder = Path(folder)
    return sorted(folder.glob(PART_GLOB)) if folder.is_dir() else []


def part_rows(path: str | Path) -> list[list[dict[str, Any]]] | None:
    """The rows held by a part, one list per case; None when it does not parse.

    Parameters
    ----------
    path : path
        A part file.

    Returns
    -------
    list of list of dict, or None
        Per case, its fit-range rows (the cases table's columns; rows written before the one
        normalisation are converted, :func:`~warptrunc.sweep.normalisation.upgrade_rows`);
        None for a file that is truncated, empty or not a part.
    """
    import pyarrow.parquet as pq

    try:
        meta = pq.read_schema(path).metadata or {}
    except (OSError, ValueError):  # truncated or empty (e.g. renamed, then power loss)
        return None
    if _META_KEY not in meta:
        return None
    return [upgrade_rows(rs) for rs in json.loads(meta[_META_KEY])]


def read_part_curves(path: str | Path, case_ids=None):
    """The curves of a part as a DataFrame.

    Parameters
    ----------
    path : path
        A part file.
    case_ids : iterable of str, optional
        Only these cases (default all).

    Returns
    -------
    pandas.DataFrame
        ``case_id`` and CURVE_COLUMNS (SI units), one row per depth increment (a part written
        before the one normalisation converted, :func:`~warptrunc.sweep.normalisation.upgrade_curves`).
    """
    import pyarrow.parquet as pq

    filters = None if case_ids is None else [("case_id", "in", list(case_ids))]
    df = pq.read_table(path, filters=filters).to_pandas()
    if "Ec_over_Estar" not in df.columns:
        df = upgrade_curves(df, part_rows(path))
    return df


def _part_table(results: list[Result]):
    import pyarrow as pa

    lengths = [0 if curve is None else len(curve["depth_m"]) for _, curve in results]
    ids = np.repeat(np.array([rows[0]["case_id"] for rows, _ in results], dtype=object), lengths)
    data = {"case_id": pa.array(ids, type=pa.string())}
    for k in CURVE_COLUMNS:
        parts = [np.asarray(curve[k]) for (_, curve), m in zip(results, lengths, strict=True) if m]
        v = np.concatenate(parts) if parts else np.zeros(0)
        data[k] = pa.array(v.astype(np.int64 if k == "n_contact_pixels" else np.float64))
    return pa.table(data)


_PLAIN = (float, int, str, bool, type(None))


def clean_rows(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Rows with JSON-ready values (NaN kept): plain Python values pass as they are, others
    through :func:`warptrunc._support.outputs.jsonable`."""
    return [
        {k: v if type(v) in _PLAIN else jsonable(v, nonfinite="keep") for k, v in r.items()}
        for r in rows
    ]


def write_part(
    folder: str | Path, results: list[Result], *, first_index: int | None = None
) -> tuple[str, list[list[dict[str, Any]]]]:
    """Write one part holding ``results`` (a shard's cases); returns its name and rows.

    Parameters
    ----------
    folder : path
        The store's ``curves/`` folder.
    results : list of (rows, curve)
        Per case, its fit-range rows and its curve (None for a failed case).
    first_index : int, optional
        ``case_index`` for the name; default the smallest of ``results``.

    Returns
    -------
    name : str
        The part's file name (:func:`part_name`).
    rows : list of list of dict
        The rows now in that part, one list per case: those of ``results``, or, when a part
        of the same name existed (an earlier attempt of the same shard), that part's rows.

    Notes
    -----
    The part is written to ``.<name>.tmp-<pid>-<thread>`` (a dot name: pandas, pyarrow and
    Dask skip it), its data made durable (``fsync``), then hard-linked to ``<name>``, which
    never replaces an existing file: the first attempt of a shard wins, and a process killed
    at any point leaves either no part or a complete one. The folder is fsynced last.
    """
    folder = Path(folder)
    rows = [clean_rows(rs) for rs, _ in results]
    ids = [rs[0]["case_id"] for rs in rows]
    if first_index is None:
        first_index = min(rs[0]["case_index"] for rs in rows)
    name = part_name(ids, first_index)
    final = folder / name
    if final.exists():
        old = part_rows(final)
        if old is not None:
            return name, old
    table = _part_table(results).replace_schema_metadata(
        {_META_KEY: json.dumps(rows, allow_nan=True).encode()}
    )
    tmp = folder / f".{name}.tmp-{os.getpid()}-{threading.get_ident()}"
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    try:
        try:
            data = table_bytes(table)
            view = memoryview(data)
            while view:
                view = view[os.write(fd, view) :]
            os.fsync(fd)
        finally:
            os.close(fd)
    except BaseException as exc:  # a full disk, a file-size limit: no half-written .tmp left
        tmp.unlink(missing_ok=True)
        if isinstance(exc, OSError) and exc.filename is None and exc.errno is not None:
            raise OSError(exc.errno, exc.strerror, str(final)) from exc  # names the part
        raise
    try:
        os.link(tmp, final)  # fails if another attempt of this shard got there first
    except FileExistsError:
        old = part_rows(final)
        if old is None:  # an unreadable leftover (power loss after the rename): replace it
            os.replace(tmp, final)
            _fsync_dir(folder)
            return name, rows
        tmp.unlink()
        return name, old
    except OSError:  # a filesystem without hard links
        os.replace(tmp, final)
        _fsync_dir(folder)
        return name, rows
    tmp.unlink()
    _fsync_dir(folder)
    return name, rows
