# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The command-line interface, run as a user would (subprocesses)."""

import json

import numpy as np
import pytest
from cli_helpers import run_cli

from warptrunc import read_height_map


def cli(*args, cwd=None):
    return run_cli(*args, cwd=cwd)


def test_generate_then_analyze(tmp_path):
    r = cli(
        "generate",
        "--n",
        128,
        96,
        "--L",
        1e-3,
        0.75e-3,
        "--D",
        2.4,
        "--Rt",
        2e-6,
        "--seed",
        3,
        "--device",
        "cpu",
        "-o",
        tmp_path / "s.npz",
    )
    assert r.returncode == 0, r.stderr
    s = read_height_map(tmp_path / "s.npz")
    assert s.heights.shape == (96, 128) and s.Rt == pytest.approx(2e-6, rel=1e-6)
    assert s.params["D"] == 2.4 and s.params["seed"] == 3
    out = tmp_path / "out"
    r = cli(
        "analyze",
        "--input",
        tmp_path / "s.npz",
        "--device",
        "cpu",
        "--out",
        out,
        "--increments",
        50,
        "--max-depth-fraction",
        0.3,
        "--min-pixels",
        3,
    )
    assert r.returncode == 0, r.stderr
    data = np.genfromtxt(out / "curve.csv", delimiter=",", names=True)
    assert data.dtype.names == (
        "depth_m",
        "n_contact_pixels",
        "contact_area_m2",
        "stiffness_N_per_m",
        "load_N",
        "Ec_over_E",
        "F_over_EA",
        "Ec_over_Estar",
        "stiffness_islands_N_per_m",
        "load_islands_N",
        "Ec_over_E_islands",
        "Ec_over_Estar_islands",
    )
    assert len(data) == 51
    # one punch per island is at least one punch of the total area (Σ√A_i ≥ √ΣA_i)
    assert np.all(data["stiffness_islands_N_per_m"] >= data["stiffness_N_per_m"] * (1 - 1e-9))
    z = s.heights
    thr = (np.float64(z.max()) - data["depth_m"]).astype(np.float32)
    np.testing.assert_array_equal(data["n_contact_pixels"], [np.count_nonzero(z >= t) for t in thr])
    fit = json.loads((out / "fit.json").read_text())
    assert {"alpha", "beta", "r2", "n_points", "depth_min", "depth_max", "min_pixels"} <= set(fit)
    assert fit["min_pixels"] == 3
    assert fit["islands"]["min_pixels"] == 3 and fit["islands"]["connectivity"] == 4
    png = (out / "stiffness.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000


def test_analyze_generates_from_parameters_same_as_python(tmp_path):
    from warptrunc.wm import wm_surface

    r = cli(
        "analyze",
        "--n",
        64,
        "--seed",
        9,
        "--device",
        "cpu",
        "--out",
        tmp_path,
        "--no-plot",
        "--min-pixels",
        1,
    )
    assert r.returncode == 0, r.stderr
    data = np.genfromtxt(tmp_path / "curve.csv", delimiter=",", names=True)
    z = wm_surface(2.5, 100e-6, n=64, seed=9, device="cpu").heights
    thr = (np.float64(z.max()) - data["depth_m"]).astype(np.float32)
    np.testing.assert_array_equal(data["n_contact_pixels"], [np.count_nonzero(z >= t) for t in thr])


@pytest.mark.parametrize(
    "args, match",
    [
        (["generate", "--D", "3.5", "-o", "x.npz"], "argument --D: must be in (2, 3), got '3.5'"),
        (["generate", "--gamma", "1", "-o", "x.npz"], "argument --gamma: must be in (1, inf)"),
        (["analyze", "--n", "64", "--increments", "0"], "--increments: must be an integer in"),
        (["analyze", "--input", "missing.npz"], "missing.npz"),
    ],
)
def test_bad_input_exits_2_with_message(tmp_path, args, match):
    r = cli(*args, "--device", "cpu", cwd=tmp_path)
    assert r.returncode == 2
    assert match in r.stderr


def test_help_states_units():
    r = cli("analyze", "--help")
    assert r.returncode == 0
    for unit in ("(m)", "(Pa)", "(dimensionless)"):
        assert unit in r.stdout
