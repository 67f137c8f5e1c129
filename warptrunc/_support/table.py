# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Column tables (``to_dict`` of the result classes) written as CSV at full float64 precision."""

from __future__ import annotations

import csv
from pathlib import Path
from typing import Any

import numpy as np


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
