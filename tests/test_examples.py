# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Every user example in ``examples/`` runs on the CPU as a user would, at a small size.

Each script runs in its own process (``WARPTRUNC_DEVICE=cpu``, ``MPLBACKEND=Agg``) with
``--quick --no-show --out <tmp>``; the test checks the exit status, the files the script says it
writes and, where cheap, one property of them. A new ``examples/*.py`` without a row in
:data:`EXAMPLES` fails :func:`test_every_example_is_listed`. The scripts in
``examples/benchmarks/`` are only checked to import (``--help``); their timings are reported, never
asserted. The whole file takes about 30 s on 2 cores (kernel cache warm).
"""

from __future__ import annotations

import csv
import importlib.util
import json
import os
import re
import subprocess
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES_DIR = ROOT / "examples"
BENCHMARKS_DIR = EXAMPLES_DIR / "benchmarks"

pytestmark = pytest.mark.timeout(180)  # hang guard; each example takes seconds


def _csv_header(path: Path) -> list[str]:
    with open(path, newline="") as fh:
        return next(csv.reader(fh))


def _json(path: Path) -> dict:
    return json.loads(path.read_text())


@dataclass(frozen=True)
class Example:
    """How to run one example and what it must leave in ``--out``."""

    args: tuple[str, ...] = ("--quick",)
    outputs: tuple[str, ...] = ()
    needs: tuple[str, ...] = ()  # optional modules: the test skips without them
    check: Callable[[Path], None] | None = field(default=None, compare=False)


def _check_quickstart(out: Path) -> None:
    assert _csv_header(out / "curve.csv")[:2] == ["depth_m", "n_contact_pixels"]
    assert 0 < _json(out / "fit.json")["alpha"] < 5


def _check_calibrate(out: Path) -> None:
    assert 2 < _json(out / "calibration.json")["D_in"] < 3


def _check_islands(out: Path) -> None:
    assert "n_islands" in _csv_header(out / "islands_seed0.csv")
    summary = _json(out / "summary.json")
    assert summary["seeds"]
    assert len(summary["seeds"]) == 2
    assert (out / "island_number.png").exists() and (out / "slit_islands.png").exists()


def _check_figures(out: Path) -> None:
    for f in ("height_map.png", "area_fraction.png", "stiffness_load.png", "alpha_vs_D.png"):
        assert (out / f).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def _check_render(out: Path) -> None:
    assert (out / "truncation.png").exists() and (out / "surface.vti").exists()


def _check_fractal(out: Path) -> None:
    assert {"known_D", "wm_D_out"} <= set(_json(out / "fractal_dimension.json"))


def _check_sweep(out: Path) -> None:
    assert _json(out / "summary.json")["fit_ranges"]


def _check_indentation(out: Path) -> None:
    assert _csv_header(out / "indent.csv")[:3] == ["punch_diameter_m", "placement", "peak_load_N"]
    fits = _json(out / "indent.json")["fits"]["truncation"]  # per punch, over its loads
    assert all("n_loads" in f for f in fits["per_punch"])
    assert any(f["made"] and f["alpha"] > 0 for f in fits["per_punch"])


def _check_challenge(out: Path) -> None:
    doc = _json(out / "challenge.json")
    assert doc["grid_study"]["n"] == [128, 256]
    assert doc["kappa"]["bem"] > doc["kappa"]["persson_limit"]


def _check_stream(out: Path) -> None:
    assert _json(out / "stream_islands.json")["equal_to_in_memory"] is True


def _check_adhesion(out: Path) -> None:
    d = _json(out / "adhesion.json")
    assert d["all_converged"] and d["adhesion"]["law"] == "exponential"
    assert 0.5 < d["range_over_pixel"] < 1.0  # the law resolved: the challenge's own pixel
    assert d["pull_off_pressure_over_E_star"] < 0  # the flat pulls before it lets go
    with open(out / "adhesion.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    for r in rows:  # attraction only lowers the load at an approach (same surface, same δ)
        assert float(r["p_over_E_star"]) <= float(r["p_over_E_star_non_adhesive"]) + 1e-12
    assert {r["branch"] for r in rows} == {"loading", "unloading"}


EXAMPLES: dict[str, Example] = {
    "quickstart": Example(
        ("--n", "128"), ("curve.csv", "fit.json", "stiffness.png"), check=_check_quickstart
    ),
    "calibrate_to_scan": Example(
        outputs=(
            "calibrated_surface.npz",
            "calibration.json",
            "calibration_history.png",
            "psd.png",
        ),
        check=_check_calibrate,
    ),
    "adhesive_challenge": Example(
        outputs=("adhesion.csv", "adhesion.json", "adhesion.png"), check=_check_adhesion
    ),
    "contact_challenge": Example(
        outputs=("challenge.json", "challenge.png"), check=_check_challenge
    ),
    "contact_islands": Example(
        args=("--quick", "--seeds", "2"),
        outputs=("islands_seed0.csv", "summary.json", "island_number.png", "slit_islands.png"),
        check=_check_islands,
    ),
    "figures": Example(
        outputs=(
            "height_map.png",
            "area_fraction.png",
            "stiffness_load.png",
            "alpha_vs_D.png",
            "psd.png",
        ),
        check=_check_figures,
    ),
    "indentation": Example(
        outputs=("indent.csv", "indent.json", "indent.png"), check=_check_indentation
    ),
    "fractal_dimension": Example(
        outputs=("fractal_dimension.json", "fractal_fits.png", "d_out_vs_d_in.png"),
        check=_check_fractal,
    ),
    "parametric_sweep": Example(
        outputs=("summary.json", "alpha_vs_D.png", "sweep.json", "cases.parquet"),
        needs=("pandas", "pyarrow"),
        check=_check_sweep,
    ),
    "render_truncated_section": Example(
        outputs=("truncation.png", "truncation_top.png", "surface.vti", "render.json"),
        needs=("pyvista",),
        check=_check_render,
    ),
    "stream_islands": Example(
        outputs=("stream_islands.json", "island_sizes.png"), check=_check_stream
    ),
    "scan_survey": Example(outputs=("scan_survey.md", "scan_survey.json", "survey.png")),
}


def _env() -> dict[str, str]:
    env = dict(os.environ, WARPTRUNC_DEVICE="cpu", MPLBACKEND="Agg")
    env.pop("DISPLAY", None)
    return env


def _run(script: Path, *args: str, timeout: float = 150) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, str(script), *args],
        cwd=ROOT,
        env=_env(),
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def test_every_example_is_listed():
    found = {p.stem for p in EXAMPLES_DIR.glob("*.py")}
    assert found - EXAMPLES.keys() == set(), "add these examples to EXAMPLES in this file"
    assert EXAMPLES.keys() - found == set(), "EXAMPLES lists scripts that are gone"


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_example_runs(name, tmp_path):
    ex = EXAMPLES[name]
    for module in ex.needs:
        pytest.importorskip(module)
    out = tmp_path / "out"
    r = _run(EXAMPLES_DIR / f"{name}.py", *ex.args, "--no-show", "--out", str(out))
    assert r.returncode == 0, f"{name} failed:\n{r.stdout[-2000:]}\n{r.stderr[-4000:]}"
    missing = [f for f in ex.outputs if not (out / f).is_file() or (out / f).stat().st_size == 0]
    assert not missing, f"{name} did not write {missing}; wrote {sorted(os.listdir(out))}"
    if ex.check is not None:
        ex.check(out)


def test_examples_have_a_docstring_with_a_run_command():
    for name in EXAMPLES:
        text = (EXAMPLES_DIR / f"{name}.py").read_text()
        doc = text.split('"""')[1]
        assert f"python examples/{name}.py" in doc, f"{name}: the docstring shows no command"


BENCHMARKS = sorted(p.name for p in BENCHMARKS_DIR.glob("*.py") if not p.name.startswith("_"))


def test_benchmarks_exist():
    assert "benchmark_pipeline.py" in BENCHMARKS


@pytest.mark.parametrize("script", BENCHMARKS)
def test_benchmark_help(script):
    r = _run(BENCHMARKS_DIR / script, "--help", timeout=60)
    assert r.returncode == 0, r.stderr[-4000:]
    assert "usage:" in r.stdout


def test_solver_scaling_benchmark_runs_quick(tmp_path):
    """The contact solver's scaling benchmark runs on the CPU with --quick and writes its JSON
    (sizes, iterations, convolutions, peak memory against the model)."""
    script = BENCHMARKS_DIR / "benchmark_solver_scaling.py"
    r = _run(script, "--quick", "--device", "cpu", "--out", str(tmp_path), timeout=300)
    assert r.returncode == 0, r.stderr[-4000:]
    doc = json.loads((tmp_path / "scaling.json").read_text())
    assert [row["n"] for row in doc["rows"]] == [128, 256]
    for row in doc["rows"]:
        assert row["converged"] and row["cold_iterations"] > 0
        # Warp's allocation tracker against the model, on the CPU (no cuFFT work area)
        assert abs(row["peak_bytes"] / row["memory_model_bytes"] - 1) < 0.1


@pytest.mark.slow
def test_adhesion_benchmark_runs_on_the_cpu(tmp_path):
    """The adhesion benchmark at 64² on the CPU: both laws solved, converged, their rows and the
    ratio of warm times written; attraction adds tensile load at the same approach."""
    script = BENCHMARKS_DIR / "benchmark_adhesion.py"
    r = _run(script, "--device", "cpu", "--n", "64", "--out", str(tmp_path), timeout=300)
    assert r.returncode == 0, r.stderr[-4000:]
    (path,) = tmp_path.glob("adhesion_*.json")
    rows = _json(path)["rows"]
    assert [(row["n"], row["law"]) for row in rows] == [(64, "non-adhesive"), (64, "exponential")]
    plain, adh = rows
    assert plain["converged"] and adh["converged"]
    assert adh["pressure_over_E_star"] < plain["pressure_over_E_star"]
    assert adh["attractive_area_fraction"] > 0 == plain["attractive_area_fraction"]
    assert adh["warm_ratio_adhesive_over_non_adhesive"] > 0
    assert adh["memory_bytes"] > plain["memory_bytes"]


@pytest.fixture
def common():
    spec = importlib.util.spec_from_file_location("_bench_common", BENCHMARKS_DIR / "_common.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_timeit_returns_the_median_after_a_warm_up(common, monkeypatch):
    # a fake clock: the three timed runs take 3, 1 and 2 s, so the median is 2 s
    ticks = iter([0.0, 3.0, 10.0, 11.0, 20.0, 22.0])
    monkeypatch.setattr(common.time, "perf_counter", lambda: next(ticks))
    calls = {"fn": 0, "sync": 0}

    def fn():
        calls["fn"] += 1

    def sync():
        calls["sync"] += 1

    assert common.timeit(fn, 3, sync) == 2.0
    assert calls == {"fn": 4, "sync": 4}  # one untimed warm-up run


def test_git_commit_reads_the_environment_first(common, monkeypatch):
    monkeypatch.setenv("WARPTRUNC_GIT_COMMIT", " abc123\n")
    assert common.git_commit() == "abc123"


@pytest.mark.parametrize("stem", ["parametric_sweep", "figures"])
def test_alpha_vs_D_below_8192_carries_the_resolution_caveat(stem):
    # the gallery draws α against D at 128², where α falls with D beside the paper's rising
    # line: the title must say that this is below the resolution α(D) needs (§ 3.3: ≥ 8192²)
    spec = importlib.util.spec_from_file_location(f"_ex_{stem}", EXAMPLES_DIR / f"{stem}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    text = mod.resolution_caveat(128)
    assert "128²" in text and "8192²" in text and "10240²" in text
    assert mod.resolution_caveat(8192) == "" and mod.resolution_caveat(10240) == ""
    assert "alpha-vs-d-10240" in mod.__doc__  # the docstring links the 10240² figure


@pytest.mark.parametrize("path", sorted(EXAMPLES_DIR.glob("*.py")), ids=lambda p: p.stem)
def test_example_does_not_exit_on_success(path):
    # sphinx-gallery runs each example as __main__ in the docs build process: a SystemExit on
    # success (``raise SystemExit(main())``, ``sys.exit(0)``) ends the whole build, with status 0
    import ast

    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.Raise) and isinstance(node.exc, ast.Call):
            f, args = node.exc.func, node.exc.args
            if getattr(f, "id", None) == "SystemExit" and args and isinstance(args[0], ast.Call):
                assert getattr(args[0].func, "id", None) != "main", f"{path.name}:{node.lineno}"
        if isinstance(node, ast.Call) and getattr(node.func, "attr", None) == "exit":
            args = node.args
            assert not (
                args
                and isinstance(args[0], ast.Call)
                and getattr(args[0].func, "id", None) == "main"
            ), path.name


def test_indentation_profiler_runs_small():
    """The indentation profiler runs one small case on the CPU and reports every phase (loading,
    Barber's stiffness, partial unloading) with converged cycles."""
    script = BENCHMARKS_DIR / "profile_indentation.py"
    r = _run(
        script,
        "--n",
        "256",
        "--surfaces",
        "GB300s",
        "--hardness-factors",
        "1",
        "--punches-um",
        "108.7",
        "--device",
        "cpu",
        timeout=300,
    )
    assert r.returncode == 0, r.stderr[-4000:]
    assert "converged True" in r.stdout
    for phase in ("/load ", "/barber ", "/load/frozen "):
        assert re.search(rf"GB300s/1H/109um/\d+px{phase}", r.stdout), phase


def test_iterations_vs_grid_runs_small(tmp_path):
    """The iterations-against-the-grid benchmark runs two small sizes on the CPU, both
    algorithms, every case converged, and writes its rows as JSON; under the punch near complete
    contact the preconditioned BCCG needs fewer iterations than PK at the larger size."""
    out = tmp_path / "iters.json"
    script = BENCHMARKS_DIR / "iterations_vs_grid.py"
    r = _run(script, "--n", "64", "128", "--json", str(out), timeout=300)
    assert r.returncode == 0, r.stderr[-4000:]
    rows = json.loads(out.read_text())["rows"]
    assert {row["algorithm"] for row in rows} == {"pk", "bccg"}
    assert all(row["converged"] for row in rows)
    punch = {
        row["algorithm"]: row["iterations"]
        for row in rows
        if row["n"] == 128 and row["case"].startswith("punch")
    }
    assert punch["bccg"] < punch["pk"], punch
