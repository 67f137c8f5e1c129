# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Curve files of the sweep store (``OUT/curves/<case_id>.parquet``): Parquet bytes, batched
durable writes (one ``syncfs`` per batch), and reading a curve file's rows back. Moved verbatim
from :mod:`warptrunc.sweep.store` (the durability rules are described there).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import json
import os
import sys
import threading
from pathlib import Path
from typing import Any

import numpy as np

from .._results import jsonable

__all__ = ["CURVE_COLUMNS", "curve_rows", "parquet_bytes", "table_bytes", "write_curves"]

CURVE_COLUMNS = (
    "depth_m", "n_contact_pixels", "contact_area_m2", "stiffness_N_per_m", "load_N",
    "Ec_over_E", "F_over_EA",
)  # fmt: skip
"""Columns of a curve file (as ``warptrunc analyze``'s curve.csv)."""


_META_KEY = b"warptrunc.rows"


def parquet_bytes(df) -> bytes:
    """A pandas DataFrame as the bytes of a Parquet file (index left out).

    Parameters
    ----------
    df : pandas.DataFrame
        The table to serialise.

    Returns
    -------
    bytes
        The Parquet file's content, as :func:`table_bytes` writes it.
    """
    import pyarrow as pa

    return table_bytes(pa.Table.from_pandas(df, preserve_index=False))


def table_bytes(table) -> bytes:
    """A pyarrow Table as the bytes of a Parquet file (``pyarrow.parquet.write_table``).

    Parameters
    ----------
    table : pyarrow.Table
        The table to serialise, schema metadata included.

    Returns
    -------
    bytes
        The Parquet file's content, for an atomic write.
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    sink = pa.BufferOutputStream()
    pq.write_table(table, sink)
    return sink.getvalue().to_pybytes()


def _sync_folder(folder: Path) -> None:
    """Make the data of every file written so far under ``folder``'s filesystem durable.

    One ``syncfs(2)`` on Linux (one call for a whole batch of files, instead of an fsync per
    file); ``os.sync()`` elsewhere.
    """
    fd = os.open(folder, os.O_RDONLY)
    try:
        if _syncfs is not None and _syncfs(fd) == 0:
            return
        os.sync()
    finally:
        os.close(fd)


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


def _load_syncfs():
    if not sys.platform.startswith("linux"):
        return None
    try:
        f = ctypes.CDLL(ctypes.util.find_library("c") or None, use_errno=True).syncfs
    except (OSError, AttributeError):  # pragma: no cover
        return None
    f.argtypes = [ctypes.c_int]
    return f


_syncfs = _load_syncfs()


def curve_rows(path: Path) -> list[dict[str, Any]] | None:
    """The rows stored in a curve file's metadata; None when it has none or does not parse.

    Parameters
    ----------
    path : Path
        A curve file ``curves/<case_id>.parquet``.

    Returns
    -------
    list of dict or None
        The case's result rows (the JSON under the schema metadata key ``warptrunc.rows``);
        None for a file without that key, or one that cannot be read (missing, truncated,
        empty).
    """

    import pyarrow.parquet as pq

    try:
        meta = pq.read_schema(path).metadata or {}
    except (OSError, ValueError):  # truncated or empty (e.g. renamed, then power loss)
        return None
    return json.loads(meta[_META_KEY]) if _META_KEY in meta else None


def write_curves(
    curves: str | Path, results: list[tuple[list[dict[str, Any]], dict[str, np.ndarray] | None]]
) -> list[list[dict[str, Any]]]:
    """Write the curve files of a batch of finished cases atomically; returns their rows.

    Each case's curve (with its rows in the Parquet metadata) goes to a temporary name; then
    one filesystem sync makes all of them durable, each is renamed to
    ``<case_id>.parquet`` and the folder is fsynced once. So a visible curve file is always
    complete (as with an fsync per file, at one sync per batch). A case whose file already
    exists (written by an earlier attempt of the same case: first writer wins, through
    ``os.link`` that never replaces) keeps that file, and its rows are returned instead.
    Used by the client (the store) and, with worker writes, by the Dask workers.

    Parameters
    ----------
    curves : str or Path
        The store's ``curves`` folder (must exist).
    results : list of (list of dict, dict or None)
        One ``(rows, curve)`` per case: its result rows (the first has ``case_id``; values
        made JSON-able with non-finite floats kept) and its curve, a dict of the
        :data:`CURVE_COLUMNS` arrays (``depth_m`` (m), ``contact_area_m2`` (m²), ``load_N``
        (N), ``stiffness_N_per_m`` (N/m), ...), or None for a failed case (an empty curve).

    Returns
    -------
    list of list of dict
        Per case, in the order of ``results``: the rows now stored for it (those given, or
        the earlier attempt's when its file already existed).
    """

    import pyarrow as pa

    curves = Path(curves)
    out: list[list[dict[str, Any]] | None] = []
    tmps: list[tuple[int, Path, Path]] = []
    for i, (rows, curve) in enumerate(results):
        rows = [{k: jsonable(v, nonfinite="keep") for k, v in r.items()} for r in rows]
        out.append(rows)
        final = curves / f"{rows[0]['case_id']}.parquet"
        old = curve_rows(final) if final.exists() else None
        if old is not None:
            out[i] = old
            continue
        cols = {k: np.asarray(curve[k]) if curve else np.zeros(0) for k in CURVE_COLUMNS}
        cols["n_contact_pixels"] = cols["n_contact_pixels"].astype(np.int64)
        table = pa.table(cols).replace_schema_metadata(
            {_META_KEY: json.dumps(rows, allow_nan=True).encode()}
        )
        tmp = final.with_name(f".{final.name}.tmp-{os.getpid()}-{threading.get_ident()}")
        tmp.write_bytes(table_bytes(table))
        tmps.append((i, tmp, final))
    if not tmps:
        return out
    _sync_folder(curves)
    for i, tmp, final in tmps:
        try:
            os.link(tmp, final)  # fails if another attempt of this case got there first
        except FileExistsError:
            old = curve_rows(final)
            if old is not None:
                out[i] = old
            else:  # an unreadable leftover: replace it
                os.replace(tmp, final)
                continue
        except OSError:  # a filesystem without hard links
            os.replace(tmp, final)
            continue
        tmp.unlink()
    _fsync_dir(curves)
    return out
