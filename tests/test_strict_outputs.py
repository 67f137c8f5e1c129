# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Issue 17: strict JSON from every command, all-or-nothing outputs, options checked before
computing, fit-range advice that works, describe per method, the store lock, clear messages."""

from __future__ import annotations

import json
import math
import os
import socket
from pathlib import Path

import numpy as np
import pytest
from cli_helpers import CALIBRATE_CLI, QUICK_CALIBRATION, RENDER_CLI, SMALL, sweep_cli

from warptrunc._support.outputs import read_json, staged_output, strict_json
from warptrunc.cli import main


def strict_load(path: Path):
    """json.loads that fails the test on NaN/Infinity tokens."""
    return json.loads(
        Path(path).read_text(),
        parse_constant=lambda c: pytest.fail(f"{path}: non-standard JSON token {c}"),
    )


def run(*argv) -> int:
    return main([str(a) for a in argv])


def leftovers(root: Path) -> list[Path]:
    """Staging folders and temporary files left anywhere under ``root``."""
    return [p for p in root.rglob("*") if "partial" in p.name or ".tmp" in p.name]


pytestmark = pytest.mark.usefixtures("quiet_surfacetopography")


# --- 1. strict JSON ---------------------------------------------------------------------------


@pytest.fixture(scope="module")
def every_command(tmp_path_factory):
    """Run every command that writes JSON once, on small inputs; the folder holding it all."""
    root = tmp_path_factory.mktemp("every")
    z = np.random.default_rng(0).normal(size=(64, 64)) * 1e-6
    np.save(root / "noise.npy", z)
    assert run("analyze", *SMALL, "--min-pixels", 1, "--no-plot", "--out", root / "analyze") == 0
    assert run("describe", root / "noise.npy", "--dx", 1e-6, "--json", root / "describe.json") == 0
    assert run("islands", *SMALL, "--increments", 20, "--no-plot", "--out", root / "islands") == 0
    assert (
        run(
            *sweep_cli("2.3"),
            "--out",
            root / "sweep",
        )
        == 0
    )
    assert (
        run(
            *CALIBRATE_CLI,
            *QUICK_CALIBRATION,
            "--out",
            root / "calibrate",
        )
        == 0
    )
    try:
        import pyvista  # noqa: F401

        assert (
            run(
                *RENDER_CLI,
                "--size",
                120,
                100,
                "--out",
                root / "render",
            )
            == 0
        )
    except ImportError:
        pass
    from warptrunc.reproduce import reproduce

    reproduce("tiny", root / "reproduce", device="cpu")
    return root


@pytest.mark.slow  # runs every command once (about 20 s on 2 cores)
def test_every_json_written_by_every_command_is_strict(every_command):
    files = sorted(every_command.rglob("*.json"))
    names = {p.relative_to(every_command).parts[0] for p in files}
    assert {"analyze", "describe.json", "islands", "sweep", "calibrate", "reproduce"} <= names
    for f in files:
        strict_load(f)
    fit = strict_load(every_command / "analyze" / "fit.json")
    assert fit["material"]["E_i"] is None  # null = rigid flat
    assert read_json(every_command / "analyze" / "fit.json")["material"]["E_i"] == math.inf
    sweep = strict_load(every_command / "sweep" / "sweep.json")
    assert sweep["options"]["E_flat"] is None
    groups = list((every_command / "reproduce").rglob("sweep.json"))
    assert all(strict_load(g)["options"]["E_flat"] is None for g in groups)


def test_sweep_resumes_a_store_with_null_e_flat(every_command, capsys):
    # null in sweep.json means inf: the same command resumes instead of reporting a conflict
    assert (
        run(
            *sweep_cli("2.3"),
            "--out",
            every_command / "sweep",
        )
        == 0
    )


def test_strict_json_maps_non_finite_to_null():
    text = strict_json({"a": math.inf, "b": [np.float32("nan"), 1.5], "E_i": -math.inf})
    assert json.loads(text, parse_constant=lambda c: pytest.fail(c)) == {
        "a": None,
        "b": [None, 1.5],
        "E_i": None,
    }


# --- 2. all or nothing -----------------------------------------------------------------------


@pytest.mark.parametrize(
    "extra",
    [[], ["--depth-window", "1", "2"]],
    ids=["default-fit-range", "depth-window"],
)
def test_analyze_that_cannot_fit_leaves_nothing(tmp_path, capsys, extra):
    out = tmp_path / "x"
    assert run("analyze", "--n", 64, *extra, "--out", out) == 2
    err = capsys.readouterr().err
    assert "increments in the fit range" in err
    assert not out.exists() and not leftovers(tmp_path)


def test_analyze_on_a_4x7_map_leaves_nothing(tmp_path, capsys):
    np.save(tmp_path / "m.npy", np.random.default_rng(1).normal(size=(4, 7)))
    out = tmp_path / "x"
    assert run("analyze", "-i", tmp_path / "m.npy", "--dx", 1e-6, "--out", out) == 2
    assert not out.exists() and not leftovers(tmp_path)


def test_failure_keeps_an_earlier_result_untouched(tmp_path, capsys):
    out = tmp_path / "x"
    assert run("analyze", "--n", 64, "--min-pixels", 1, "--no-plot", "--out", out) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert run("analyze", "--n", 64, "--no-plot", "--out", out) == 2
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


def test_write_failing_half_way_leaves_no_partial_result_and_a_rerun_completes(
    tmp_path, monkeypatch, capsys
):
    """Fault injection: the second file's writer raises OSError after curve.csv is written."""
    from warptrunc import stiffness

    calls = []
    real = stiffness.StiffnessCurve.to_csv

    def first_then_fail(self, path, **kw):
        calls.append(path)
        real(self, path, **kw)
        raise OSError(28, "No space left on device (injected)")

    out = tmp_path / "x"
    monkeypatch.setattr(stiffness.StiffnessCurve, "to_csv", first_then_fail)
    assert run("analyze", "--n", 64, "--min-pixels", 1, "--out", out) == 2
    assert calls and Path(calls[0]).exists() is False  # written, then rolled back
    assert "No space left" in capsys.readouterr().err
    assert not out.exists() and not leftovers(tmp_path)

    import warptrunc.plot as plot

    monkeypatch.undo()
    real_plot = plot.stiffness_load
    monkeypatch.setattr(
        plot, "stiffness_load", lambda *a, **k: (_ for _ in ()).throw(OSError("disk"))
    )
    assert run("analyze", "--n", 64, "--min-pixels", 1, "--out", out) == 2
    assert not out.exists() and not leftovers(tmp_path)
    monkeypatch.setattr(plot, "stiffness_load", real_plot)
    assert run("analyze", "--n", 64, "--min-pixels", 1, "--out", out) == 0
    assert sorted(p.name for p in out.iterdir()) == [
        "area_fraction.png",
        "curve.csv",
        "fit.json",
        "stiffness.png",
    ]
    strict_load(out / "fit.json")
    assert not leftovers(tmp_path)


def test_staged_output_removes_folders_it_created(tmp_path):
    out = tmp_path / "a" / "b"
    with pytest.raises(RuntimeError), staged_output(out) as st:
        (st / "f.txt").write_text("x")
        raise RuntimeError
    assert not (tmp_path / "a").exists()
    with staged_output(out) as st:
        (st / "sub").mkdir()
        (st / "sub" / "f.txt").write_text("x")
    assert (out / "sub" / "f.txt").read_text() == "x" and not leftovers(tmp_path)


def test_render_checks_the_animation_extension_before_rendering(tmp_path, capsys):
    out = tmp_path / "out"
    with pytest.raises(SystemExit) as e:
        run("render", "--n", 64, "--animate", "out.avi", "--out", out)
    assert e.value.code == 2
    assert "--animate: must end in .gif or .mp4" in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.parametrize(
    "argv, option",
    [
        (["analyze", "--n", "64", "--out", "/proc/x"], "--out"),
        (["describe", "{npy}", "--dx", "1e-6", "--json", "/proc/x.json"], "--json"),
        (["islands", "--n", "64", "--out", "/proc/x"], "--out"),
    ],
    ids=["analyze-out", "describe-json", "islands-out"],
)
def test_unwritable_path_names_the_option_before_computing(tmp_path, capsys, argv, option):
    if not Path("/proc/self").exists():
        pytest.skip("no /proc")
    np.save(tmp_path / "z.npy", np.ones((8, 8)))
    argv = [a.format(npy=tmp_path / "z.npy") for a in argv]
    with pytest.raises(SystemExit) as e:
        run(*argv)
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert f"argument {option}: cannot write under '/proc'" in err and "Errno" not in err


# --- 3. measured scans: advice that works -----------------------------------------------------


def test_fit_range_advice_names_options_that_work(tmp_path, capsys):
    out = tmp_path / "x"
    assert run("analyze", "--n", 64, "--no-plot", "--out", out) == 2
    err = capsys.readouterr().err
    assert "for this map any one of these works" in err
    advice = err.split("works: ")[1].strip().split("; ")
    assert any(a.startswith("--max-depth-fraction") for a in advice)
    for a in advice:
        words = a.split(" (")[0].split()
        assert run("analyze", "--n", 64, "--no-plot", *words, "--out", out) == 0, a


def test_rt_percentile_clips_spikes_and_is_recorded(tmp_path, capsys):
    z = np.random.default_rng(2).normal(size=(128, 128)) * 1e-7
    z[5, 5] = 1e-4  # one spike sets R_t
    np.save(tmp_path / "spike.npy", z)
    args = ["analyze", "-i", tmp_path / "spike.npy", "--dx", 1e-6, "--no-plot"]
    assert run(*args, "--fit-range", "legacy", "--out", tmp_path / "a") == 2
    assert "--rt-percentile 0.1 99.9" in capsys.readouterr().err
    # the automatic fit range (the default) masks the spike and fits without help
    assert run(*args, "--out", tmp_path / "c") == 0
    auto = strict_load(tmp_path / "c" / "fit.json")
    assert auto["fit_range"]["rule"] == "auto" and auto["fit_range"]["spikes_masked"]["count"] == 1
    assert auto["warnings"][0]["details"]["locations"][0]["iy"] == 5
    assert run(*args, "--rt-percentile", 0.1, 99.9, "--out", tmp_path / "b") == 0
    fit = strict_load(tmp_path / "b" / "fit.json")
    assert fit["surface"]["rt_percentile"] == [0.1, 99.9]
    assert fit["surface"]["Rt_raw_m"] > 10 * fit["surface"]["Rt_m"]
    assert fit["surface"]["n_clipped_above"] >= 1


def test_measured_scans_analyse_on_defaults_or_name_a_working_fix(scans_dir, tmp_path, capsys):
    pytest.importorskip("SurfaceTopography")  # the instrument files need the 'scans' extra
    for f in sorted(scans_dir.iterdir()):
        if f.suffix == ".md":
            continue
        args = ["analyze", "-i", f, "--missing", "fill", "--level", "--no-plot"]
        if f.suffix == ".txt":
            args += ["--dx", "1e-6"] if "pixel size" not in f.read_text()[:500] else []
        status = run(*args, "--out", tmp_path / f.name)
        err = capsys.readouterr().err
        if status == 0:
            continue
        assert "any one of these works: " in err, err
        first = err.split("works: ")[1].split(";")[0].split(" (")[0].split()
        assert run(*args, *first, "--out", tmp_path / f.name) == 0, (f.name, first)
        assert not leftovers(tmp_path)


# --- 6. describe per method ------------------------------------------------------------------


def test_describe_reports_each_method_and_calls_flat_maps_flat(tmp_path, capsys):
    np.save(tmp_path / "zeros.npy", np.zeros((32, 32)))
    assert run("describe", tmp_path / "zeros.npy", "--dx", 1e-6, "--json", tmp_path / "z.json") == 0
    d = strict_load(tmp_path / "z.json")
    assert d["flat"] is True and d["Rt_m"] == 0
    assert all(
        d[f"D_{m}"] is None and "flat" in d[f"error_{m}"] for m in ("tri", "box", "vs", "sp")
    )
    assert "every height is the same" in capsys.readouterr().out

    np.save(tmp_path / "tiny.npy", np.random.default_rng(3).normal(size=(4, 4)))
    assert run("describe", tmp_path / "tiny.npy", "--dx", 1e-6) == 0
    text = capsys.readouterr().out
    assert "D_tri     — (cannot fit on this 4×4 map" in text
    assert "box_sizes" not in text and "fit_range" not in text
    assert "D_box" in text


# --- 8. the store lock -----------------------------------------------------------------------


def test_second_sweep_on_a_locked_store_is_refused_at_once(tmp_path, capsys):
    from warptrunc.sweep.store import store_lock

    out = tmp_path / "s"
    argv = ["sweep", "--D", 2.3, "--delta", 0.01, "--n", 32, "--min-pixels", 1, "--no-progress"]
    with store_lock(out):
        assert run(*argv, "--out", out) == 2
    err = capsys.readouterr().err
    assert f"pid {os.getpid()} on host {socket.gethostname()}" in err
    assert not (out / "sweep.json").exists()
    # a lock left by a dead process on this host is taken over, and said so
    (out / ".lock").write_text(
        json.dumps(
            {
                "pid": 2**22 + 12345,
                "host": socket.gethostname(),
                "started_utc": "2026-01-01T00:00:00Z",
            }
        )
    )
    assert run(*argv, "--out", out) == 0
    assert "took over a stale lock of pid" in capsys.readouterr().err
    assert not (out / ".lock").exists()


# --- 7. messages -----------------------------------------------------------------------------


def test_no_plot_help_names_both_pictures(capsys):
    with pytest.raises(SystemExit):
        run("analyze", "--help")
    assert "skip stiffness.png and area_fraction.png" in capsys.readouterr().out


def test_gitignore_covers_the_readme_python_block():
    text = (Path(__file__).resolve().parents[1] / ".gitignore").read_text().split()
    assert {"/curve.csv", "/fit.json", "/results/"} <= set(text)
