# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Shared by every result type and both result stores: JSON-ready values, dataclass fields as a
dict of columns, and atomic file writes.

- :func:`jsonable`: nested dicts, lists, NumPy arrays and scalars → plain JSON types.
- :func:`fields_to_dict`: a result dataclass's fields as ``{column: value}``, in field order,
  with the column names (unit suffixes such as ``depth_m``) given once per type.
- :func:`write_atomic`: a temporary file in the same folder, fsynced, then renamed, so a crash
  leaves either the old file or the new one (the sweep store and the reproduce store).
"""

from __future__ import annotations

import dataclasses
import math
import os
import tempfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any, Literal

import numpy as np

__all__ = ["fields_to_dict", "jsonable", "write_atomic"]

WRITE_DOCS = {
    "{path}": "Parameters\n----------\npath : str or Path\n    File to write (overwritten).",
    "{returns_path}": "Returns\n-------\nPath",
}
"""Docstring text of the results' writers (``to_csv``, ``to_json``), written once
(:func:`warptrunc._support.docs.fill_doc`)."""


def all_converged_property() -> property:
    """The ``all_converged`` property of a result with a ``converged`` column (assign it in the
    class body, where the API reference documents it with the class's own members)."""

    def all_converged(self: Any) -> bool:
        """True when every entry of ``converged`` is true (every solve converged)."""
        return bool(np.all(self.converged))

    return property(all_converged)


def jsonable(v: Any, *, nonfinite: Literal["null", "text", "keep"] = "null") -> Any:
    """Nested dicts/lists/tuples, NumPy arrays and NumPy scalars → JSON types.

    ``nonfinite`` says what becomes of NaN and ±inf floats: ``"null"`` → ``None`` (strict JSON,
    the reproduce store), ``"text"`` → ``"nan"``/``"inf"``/``"-inf"`` (read back by ``float()``:
    surface metadata, calibration targets), ``"keep"`` → the float itself (Parquet rows of the
    sweep store, where NaN is a missing value).
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
    return v


def fields_to_dict(
    obj: Any, columns: Mapping[str, str] | None = None, *, skip: Iterable[str] = ()
) -> dict[str, Any]:
    """The dataclass ``obj``'s fields as ``{column: value}`` in field order.

    ``columns`` maps a field name to its column name (``{"depth": "depth_m"}``); fields not in
    it keep their name; fields in ``skip`` are left out. Values are not copied or converted.
    """
    columns = columns or {}
    skip = set(skip)
    return {
        columns.get(f.name, f.name): getattr(obj, f.name)
        for f in dataclasses.fields(obj)
        if f.name not in skip
    }


def write_atomic(path: str | Path, data: str | bytes) -> Path:
    """Write ``data`` to ``path`` through a fsynced temporary file in the same folder and a rename.

    The temporary file is named ``.<name>.tmp-<pid>-<random>``, so a store can find and delete
    those a crash left behind (``.*.tmp-*``).
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
