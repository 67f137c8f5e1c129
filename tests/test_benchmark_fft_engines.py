# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""examples/benchmarks/benchmark_fft_engines.py (issue 42, item 1) on 2 host CPU devices at 32²:
the JAX engine's padded transform pair against numpy float64, its JSON lines, the solver's pruned
convolution beside it, and the report."""

import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

# not imported here: JAX must start with the two host devices tests/conftest.py asks for
pytestmark = pytest.mark.skipif(importlib.util.find_spec("jax") is None, reason="needs JAX")

SCRIPT = (
    Path(__file__).resolve().parents[1] / "examples" / "benchmarks" / "benchmark_fft_engines.py"
)
FIELDS = {
    "engine",
    "n",
    "padded_shape",
    "ndev",
    "dtype",
    "devices",
    "versions",
    "commit",
    "floor_ms",
    "repeats_ms",
    "max_rel_error",
    "check_n",
    "elements_per_fft_call",
}


def run(*args, timeout=60):
    env = {
        **os.environ,
        "JAX_PLATFORMS": "cpu",
        "XLA_FLAGS": "--xla_force_host_platform_device_count=2",
    }
    r = subprocess.run(
        [sys.executable, str(SCRIPT), *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=timeout,
    )
    assert r.returncode == 0, (r.stdout + r.stderr)[-4000:]
    return r.stdout


@pytest.mark.timeout(120)
def test_jax_engine_two_cpu_devices_matches_numpy_and_records(tmp_path):
    out = tmp_path / "fe.jsonl"
    run(
        "jax",
        "--n",
        "32",
        "--ndev",
        "2",
        "--dtype",
        "float64",
        "float32",
        "--repeats",
        "2",
        "--check-n",
        "32",
        "--jsonl",
        str(out),
    )
    lines = [json.loads(x) for x in out.read_text().splitlines()]
    assert lines[0]["record"] == "diagnostics" and "jax" in lines[0]["versions"]
    recs = {r["dtype"]: r for r in lines if r.get("engine") == "jax"}
    assert set(recs) == {"float64", "float32"}
    for dtype, r in recs.items():
        assert "error" not in r, r.get("traceback")
        assert FIELDS <= set(r), FIELDS - set(r)
        assert r["engine"] == "jax" and r["n"] == 32 and r["ndev"] == 2 and r["check_n"] == 32
        assert r["padded_shape"] == [64, 64] and len(r["devices"]) == 2
        assert r["floor_ms"] > 0 and len(r["repeats_ms"]) == 2
        assert 0 < r["elements_per_fft_call"] < 2**31
        assert r["max_rel_error"] < (1e-10 if dtype == "float64" else 1e-5)
    pruned = {r["dtype"]: r for r in lines if r.get("engine") == "jax-pruned"}
    assert set(pruned) == {"float64", "float32"}, [r.get("error") for r in pruned.values()]
    assert "error" not in pruned["float64"], pruned["float64"].get("traceback")
    assert pruned["float64"]["unit_force_check"] < 1e-8 and pruned["float64"]["floor_ms"] > 0
    table = run("report", "--jsonl", str(out))
    assert "jax" in table and "float64" in table and "ERROR" not in table
