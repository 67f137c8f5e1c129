# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""examples/benchmarks/benchmark_indentation_workers.py ``compare``: values
files of runs made by separate benchmark processes (e.g. at the same time on different GPUs of
one host) are compared bit for bit; a change of one unit in the last place is found."""

import gzip
import json
import math
import subprocess
import sys
from pathlib import Path

SCRIPT = (
    Path(__file__).resolve().parents[1]
    / "examples"
    / "benchmarks"
    / "benchmark_indentation_workers.py"
)


def _write(path: Path, values: dict) -> Path:
    with gzip.open(path, "wt", encoding="utf-8") as f:
        json.dump(values, f)
    return path


def _values(k: float) -> dict:
    return {
        "indentation/piece_0.json": {"K_N_per_m": [1.0e5, k, 0.1 + 0.2], "seconds_s": 3.0},
        "results.json:analysis": {"alpha": 0.5, "n": 7, "note": "x"},
    }


def _compare(*paths: Path, out: Path) -> tuple[int, dict, str]:
    r = subprocess.run(
        [sys.executable, str(SCRIPT), "compare", *map(str, paths), "--json", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    return r.returncode, json.loads(out.read_text()), r.stdout + r.stderr


def test_compare_identical_and_one_ulp_apart(tmp_path):
    k = 2.345678901234e6
    ref = _write(tmp_path / "values_inproc.json.gz", _values(k))
    same = _write(tmp_path / "values_workers_2.json.gz", _values(k))
    # the seconds differ in any run: left out of the comparison, as the benchmark does
    timed = _values(k)
    timed["indentation/piece_0.json"]["seconds_s"] = 99.0
    timed = _write(tmp_path / "values_workers_1.json.gz", timed)
    off = _write(tmp_path / "values_workers_4.json.gz", _values(math.nextafter(k, math.inf)))

    rc, doc, text = _compare(ref, same, timed, out=tmp_path / "a.json")
    assert rc == 0, text
    checks = doc["checks"]
    assert all(c["identical"] for c in checks.values())
    # 3 K values, alpha, n, note (the seconds left out)
    assert {c["values_compared"] for c in checks.values()} == {6}

    rc, doc, text = _compare(ref, same, off, out=tmp_path / "b.json")
    assert rc == 1, text
    bad = doc["checks"][str(off)]
    assert not bad["identical"] and bad["n_fields"] == 1
    ((field, e),) = bad["fields"].items()
    assert field.startswith("indentation/piece_0.json") and e["count"] == 1
    assert e["max_abs"] == math.ulp(k)
    assert "DIFFERENT" in text
