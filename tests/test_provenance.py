# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Issue 30: every output cites itself (version, commit, command line, device, time), and every
command that reads a map takes ``--input``."""

from __future__ import annotations

import json
import shlex
from pathlib import Path

import numpy as np
import pytest
from cli_helpers import CALIBRATE_CLI, QUICK_CALIBRATION, RENDER_CLI, SMALL, sweep_cli

from warptrunc import __version__, resolve_device
from warptrunc._support.provenance import provenance
from warptrunc.cli import main

KEYS = {
    "warptrunc_version",
    "git_commit",
    "command",
    "device",
    "device_name",
    "host",
    "created_utc",
    "python_version",
    "warp_version",
}


def check(p: dict, argv: list[str] | None = None) -> None:
    assert set(p) == KEYS
    assert p["warptrunc_version"] == __version__
    assert p["created_utc"] == "2001-09-09T01:46:40Z"  # $SOURCE_DATE_EPOCH = 1e9
    assert p["git_commit"] == "0123abc"
    if argv is not None:
        assert p["command"] == shlex.join(["warptrunc", *map(str, argv)])
        # the device the command ran on: the default one (cpu in CI, cuda:0 where there is a
        # GPU), or the host for commands whose work is host-side there
        assert p["device"] in {"cpu", str(resolve_device(None))}


@pytest.fixture(autouse=True)
def fixed(monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1000000000")
    monkeypatch.setenv("WARPTRUNC_GIT_COMMIT", "0123abc")


def test_provenance_of_a_library_call_names_the_script():
    import sys

    p = provenance(argv=["my_script.py", "--x", "a b"])
    check(p)
    assert p["command"] == "my_script.py --x 'a b'"
    assert provenance()["command"] == shlex.join(sys.argv)


def run(*argv) -> list[str]:
    argv = [str(a) for a in argv]
    assert main(argv) in (0, 3)
    return argv


def test_every_command_output_carries_provenance(tmp_path, capsys):
    z = tmp_path / "z.npy"
    np.save(z, np.random.default_rng(0).normal(size=(32, 32)) * 1e-6)
    a = run(
        "analyze",
        *SMALL,
        "--min-pixels",
        1,
        "--no-plot",
        "--device",
        "cpu",
        "--out",
        tmp_path / "a",
    )
    check(json.loads((tmp_path / "a" / "fit.json").read_text())["provenance"], a)
    i = run(
        "islands",
        *SMALL,
        "--increments",
        20,
        "--no-plot",
        "--device",
        "cpu",
        "--out",
        tmp_path / "i",
    )
    check(json.loads((tmp_path / "i" / "indicators.json").read_text())["provenance"], i)
    d = run(
        "describe",
        "-i",
        z,
        "--dx",
        1e-6,
        "--methods",
        "box",
        "--device",
        "cpu",
        "--json",
        tmp_path / "d.json",
    )
    check(json.loads((tmp_path / "d.json").read_text())["provenance"], d)
    b = run(
        "bem-check",
        "--n",
        32,
        "--maxiter",
        200,
        "--accept-unconverged",
        "--no-plot",
        "--no-progress",
        "--device",
        "cpu",
        "--out",
        tmp_path / "b",
    )
    check(json.loads((tmp_path / "b" / "bem.json").read_text())["provenance"], b)
    c = run(
        *CALIBRATE_CLI,
        *QUICK_CALIBRATION,
        "--no-surface",
        "--device",
        "cpu",
        "--out",
        tmp_path / "c",
    )
    check(json.loads((tmp_path / "c" / "calibration.json").read_text())["provenance"], c)
    g = run("generate", "--n", 32, "--device", "cpu", "-o", tmp_path / "s.npz")
    with np.load(tmp_path / "s.npz") as f:
        check(json.loads(str(f["metadata"]))["provenance"], g)
    capsys.readouterr()


def test_sweep_store_carries_the_provenance_of_the_run_that_made_it(tmp_path, capsys):
    pytest.importorskip("pyarrow")
    argv = run(
        *sweep_cli("2.3", n="32"),
        "--device",
        "cpu",
        "--out",
        tmp_path / "s",
    )
    check(json.loads((tmp_path / "s" / "sweep.json").read_text())["provenance"], argv)
    run(*argv)  # resumes: provenance does not enter the grid/options comparison
    capsys.readouterr()


def test_render_json_carries_provenance(tmp_path, capsys):
    pytest.importorskip("pyvista")
    argv = run(
        *RENDER_CLI,
        "--size",
        120,
        100,
        "--device",
        "cpu",
        "--out",
        tmp_path / "r",
    )
    check(json.loads((tmp_path / "r" / "render.json").read_text())["provenance"], argv)
    capsys.readouterr()


def test_fit_and_curve_to_json_carry_provenance(tmp_path):
    from warptrunc import Material, fit_power_law, from_heights, stiffness_curve, truncate

    z = np.random.default_rng(1).normal(size=(64, 64)) * 1e-6
    sc = stiffness_curve(truncate(from_heights(z, 1e-6), 100, device="cpu"), Material())
    fit = fit_power_law(sc, min_pixels=1)
    check(json.loads(fit.to_json(tmp_path / "fit.json").read_text())["provenance"])
    check(json.loads(sc.to_json(tmp_path / "curve.json").read_text())["provenance"])


# --- --input on every command that reads a map ------------------------------------------------


@pytest.mark.parametrize("form", ["positional", "--input", "-i"])
def test_describe_and_calibrate_take_input(form, tmp_path, capsys):
    z = tmp_path / "z.npy"
    np.save(z, np.random.default_rng(0).normal(size=(32, 32)) * 1e-6)
    where = [str(z)] if form == "positional" else [form, str(z)]
    assert main(["describe", *where, "--dx", "1e-6", "--methods", "box", "--json", "-"]) == 0
    assert json.loads(capsys.readouterr().out)["file"] == str(z)
    assert (
        main(
            [
                "calibrate",
                *where,
                "--dx",
                "1e-6",
                "--method",
                "box",
                *QUICK_CALIBRATION,
                "--no-surface",
                "--n",
                "32",
                "--out",
                str(tmp_path / "c"),
            ]
        )
        == 0
    )
    cal = json.loads((tmp_path / "c" / "calibration.json").read_text())
    assert str(z) in json.dumps(cal)
    capsys.readouterr()


def test_input_given_twice_is_one_line(tmp_path, capsys):
    a, b = tmp_path / "a.npy", tmp_path / "b.npy"
    for f in (a, b):
        np.save(f, np.zeros((4, 4)))
    assert main(["describe", str(a), "--input", str(b)]) == 2
    assert "give the height map once, as FILE or --input FILE" in capsys.readouterr().err


def test_describe_without_a_file_describes_the_generated_surface(capsys):
    assert main(["describe", "--n", "64", "--device", "cpu"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("WM surface, D = 2.5: 64×64 pixels")
    assert "h′_rms" in out and "h″_rms" in out


@pytest.mark.parametrize(
    "cmd", ["analyze", "bem-check", "calibrate", "compare", "describe", "islands", "render"]
)
def test_every_command_that_reads_a_map_lists_input(cmd, capsys):
    with pytest.raises(SystemExit):
        main([cmd, "--help"])
    assert "--input" in capsys.readouterr().out


def test_readme_promise_holds_for_the_help_of_generate_too(capsys):
    """generate makes a map; it refuses --input with a reason (one line)."""
    assert main(["generate", "--input", str(Path(__file__))]) == 2
    assert "generate makes a new surface" in capsys.readouterr().err
