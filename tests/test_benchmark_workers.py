# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""examples/benchmarks/benchmark_workers.py (issue 39) on the CPU at 64²: whole commands in
process and on 2 local workers, its JSON, and its check that 2 workers store the same rows and
curves as in process, bit for bit (as an in-process run repeats itself)."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("distributed")
pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

SCRIPT = Path(__file__).resolve().parents[1] / "examples" / "benchmarks" / "benchmark_workers.py"


@pytest.mark.slow
@pytest.mark.timeout(300)
def test_benchmark_workers_cpu_two_workers_rows_equal_in_process(tmp_path):
    r = subprocess.run(
        [
            sys.executable,
            str(SCRIPT),
            "--device",
            "cpu",
            "--workers",
            "2",
            "--runs",
            "light",
            "check",
            "--light-args",
            "--n 64 --D 2.4 --delta 0.01 --seeds 0-5",
            "--out",
            str(tmp_path),
        ],
        capture_output=True,
        text=True,
        timeout=280,
    )
    assert r.returncode == 0, (r.stdout + r.stderr)[-4000:]
    doc = json.loads((tmp_path / "benchmark_workers.json").read_text())
    assert doc["commit"] and doc["device"] == "cpu" and doc["workers"] == [2]
    runs = {x["run"]: x for x in doc["runs"]}
    assert set(runs) == {"inproc", "workers_2"}
    for x in runs.values():
        assert x["rc"] == 0 and x["cases"] == 6 and x["failed"] == 0, x
        assert x["wall_s"] > 0 and "--out <out>/store_light" in x["command"]
    assert "--workers 2" in runs["workers_2"]["command"]
    assert runs["workers_2"]["cluster"] == "LocalCluster"
    assert runs["workers_2"]["worker_devices"] == ["cpu", "cpu"]
    assert runs["inproc"]["speedup"] == 1.0 and runs["workers_2"]["start_s"] > 0
    for kind in ("light", "elastic"):
        c = doc["check"][kind]
        assert c["devices"]["workers_2"] == ["cpu"]
        for name in ("inproc_b", "workers_2"):  # bit for bit, rows and curves
            assert c[name]["identical"], (kind, name, c[name])
    assert "workers_2 vs inproc_a: identical" in r.stdout  # the table, printed last
    assert not list(tmp_path.glob("store_*")) and not list(tmp_path.glob("check_*"))


def test_bitwise_diff_names_the_columns_that_differ():
    import importlib.util

    import numpy as np
    import pandas as pd

    spec = importlib.util.spec_from_file_location("benchmark_workers", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    a = pd.DataFrame({"x": [1.0, np.nan, 0.0], "s": ["a", None, "c"], "t": [1.0, 2.0, 3.0]})
    b = a.copy()
    assert mod.bitwise_diff(a, b) == {}
    b.loc[2, "x"] = -0.0  # equal as numbers, not bit for bit
    b.loc[0, "s"] = "z"
    b.loc[1, "t"] = 2.0 + 1e-15
    d = mod.bitwise_diff(a, b, skip=("t",))
    assert set(d) == {"x", "s"} and d["x"]["rows"] == 1 and d["s"]["rows"] == 1
    assert mod.bitwise_diff(a, b)["t"]["max_abs"] > 0
    assert mod.default_workers(0) == [1, 2] and mod.default_workers(4) == [1, 2, 4]
    assert mod.default_workers(6) == [1, 2, 4, 6]
