# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The shared CSV column writer: float64 values read back bit for bit, integers stay integers."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from warptrunc._support.outputs import write_columns_csv


def test_columns_round_trip(tmp_path):
    x = np.array([0.1, 1.0 / 3.0, np.nan, np.inf, -2.5e-300])
    n = np.arange(5, dtype=np.int64)
    ok = np.array([True, False, True, True, False])
    p = write_columns_csv(tmp_path / "t.csv", {"x": x, "n": n, "ok": ok})
    with p.open(newline="") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["x", "n", "ok"]
    got = np.array([float(r[0]) for r in rows[1:]])
    np.testing.assert_array_equal(got, x)  # NaN positions equal, finite values exact
    assert [r[1] for r in rows[1:]] == ["0", "1", "2", "3", "4"]
    assert [r[2] for r in rows[1:]] == ["1", "0", "1", "1", "0"]


def test_unequal_columns_raise(tmp_path):
    with pytest.raises(ValueError):
        write_columns_csv(tmp_path / "t.csv", {"a": np.zeros(2), "b": np.zeros(3)})
