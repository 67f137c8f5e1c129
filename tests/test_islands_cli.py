# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""``warptrunc islands``, the islands figures and examples/contact_islands.py, run as a user
would (subprocesses), checked against scipy.ndimage.label."""

import json

import numpy as np
import pytest
import scipy.ndimage as ndi
from cli_helpers import run_cli

import warptrunc
from warptrunc import plot
from warptrunc.islands import (
    ISLANDS_TRUNCATION,
    IndicatorSettings,
    IslandSettings,
    applicable_depth,
    island_curve,
)

PNG = b"\x89PNG\r\n\x1a\n"
COLUMNS = (
    "depth_m",
    "depth_fraction_of_Rt",
    "n_islands",
    "euler_characteristic",
    "total_perimeter_m",
    "contact_area_m2",
    "slit_exponent",
    "slit_r2",
    "slit_n_islands",
    "n_contact_pixels",
    "normalised_island_number",
    "island_growth_rate",
)


def cli(*args):
    return run_cli("islands", *args)


def test_islands_cli_on_a_height_map(tmp_path):
    rng = np.random.default_rng(11)
    z = ndi.gaussian_filter(rng.standard_normal((72, 64)), 2.0).astype(np.float32)
    np.save(tmp_path / "z.npy", z)
    out = tmp_path / "out"
    r = cli(
        "--input",
        tmp_path / "z.npy",
        "--dx",
        2e-6,
        "--height-unit",
        1e-6,
        "--increments",
        40,
        "--max-depth-fraction",
        0.8,
        "--min-pixels",
        4,
        "--min-islands",
        5,
        "--snapshots",
        0.2,
        0.4,
        "--device",
        "cpu",
        "--out",
        out,
    )
    assert r.returncode == 0, r.stderr
    assert "max. growth rate" in r.stdout
    data = np.genfromtxt(out / "islands.csv", delimiter=",", names=True)
    assert data.dtype.names == COLUMNS
    assert len(data) == 41
    zm = (z.astype(np.float64) * 1e-6).astype(np.float32)
    thr = (np.float64(zm.max()) - data["depth_m"]).astype(np.float32)
    cross = ndi.generate_binary_structure(2, 1)
    np.testing.assert_array_equal(data["n_islands"], [ndi.label(zm >= t, cross)[1] for t in thr])
    np.testing.assert_allclose(data["contact_area_m2"], data["n_contact_pixels"] * 4e-12)
    ind = json.loads((out / "indicators.json").read_text())
    for key in (
        "max_growth_rate_depth_percent_Rt",
        "fractality_depth_percent_Rt",
        "island_peak_depth_percent_Rt",
    ):
        assert key in ind
    k = int(np.argmax(data["n_islands"]))
    assert ind["island_peak_depth_percent_Rt"] == pytest.approx(
        100 * data["depth_fraction_of_Rt"][k]
    )
    assert ind["connectivity"] == 4 and ind["surface"]["nx"] == 64
    for name in ("island_number.png", "slit_islands.png"):
        png = (out / name).read_bytes()
        assert png[:8] == PNG and len(png) > 10_000


def test_islands_cli_generates_counts_without_statistics(tmp_path):
    r = cli(
        "--n",
        64,
        "--seed",
        3,
        "--no-statistics",
        "--connectivity",
        8,
        "--increments",
        20,
        "--device",
        "cpu",
        "--out",
        tmp_path,
        "--no-plot",
    )
    assert r.returncode == 0, r.stderr
    data = np.genfromtxt(tmp_path / "islands.csv", delimiter=",", names=True)
    from warptrunc.wm import wm_surface

    z = wm_surface(2.5, 100e-6, n=64, seed=3, device="cpu").heights
    thr = (np.float64(z.max()) - data["depth_m"]).astype(np.float32)
    block = np.ones((3, 3), bool)
    np.testing.assert_array_equal(data["n_islands"], [ndi.label(z >= t, block)[1] for t in thr])
    assert np.isnan(data["slit_exponent"]).all()
    assert not (tmp_path / "island_number.png").exists()


def test_islands_cli_bad_connectivity(tmp_path):
    r = cli("--n", 32, "--connectivity", 6, "--device", "cpu", "--out", tmp_path)
    assert r.returncode == 2
    assert "--connectivity: must be one of 4, 8, got '6'" in r.stderr


def test_figures_from_python(tmp_path):
    rng = np.random.default_rng(2)
    z = ndi.gaussian_filter(rng.standard_normal((64, 64)), 2.0).astype(np.float32)
    s = warptrunc.from_heights(z * 1e-6, 1e-6)
    c = island_curve(
        s,
        truncation=ISLANDS_TRUNCATION.replace(increments=30, max_depth_fraction=0.8),
        settings=IslandSettings(min_pixels=3, snapshots=(0.2, 0.5)),
        device="cpu",
    )
    ind = applicable_depth(c, IndicatorSettings(min_islands=5))
    fig = plot.island_number([c, c], [ind, None], labels=["a", "b"], path=tmp_path / "a.png")
    assert len(fig.axes[0].lines) >= 4
    fig = plot.slit_islands(c, path=tmp_path / "b.png")
    assert (tmp_path / "b.png").read_bytes()[:8] == PNG
