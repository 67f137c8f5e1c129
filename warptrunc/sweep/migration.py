# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Converting a store of the previous layout (``warptrunc-sweep/1``, one curve file per case).

:func:`migrate` writes the parts of the current layout (:mod:`warptrunc.sweep.store`).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

from .._support.atomic import read_json, strict_json
from .._support.results import jsonable, write_atomic
from .curves import CURVE_COLUMNS, part_files, write_part
from .grid import FORMAT, STORE_FORMAT
from .read import RENAMED_COLUMNS, require_extra

__all__ = ["migrate"]


def _isna(v: Any) -> bool:
    import pandas as pd

    return v is None or v is pd.NA


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
        df = pq.read_table(table).to_pandas().rename(columns=RENAMED_COLUMNS)
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
