# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Calibration loop (Fig. 4): recovers known WM inputs, copes with noise, refuses the
unreachable."""

from __future__ import annotations

import json

import numpy as np
import pytest

import warptrunc
from warptrunc.calibrate import (
    CalibrationError,
    CalibrationSettings,
    CalibrationTarget,
    calibrate,
    calibrated_surface,
    target_from_surface,
)
from warptrunc.calibrate._root_find import find_root, isotonic
from warptrunc.fractal import fractal_dimension
from warptrunc.wm import wm_surface

L = 1e-3
WR = L / 8
TARGET = ["--Rrms", "2e-6", "--Rt", "15e-6", "--Wr", str(WR), "--L", str(L)]
"""R_rms, R_t, W_r and L of the command-line calibrations."""


def _scan(D=2.45, seed=42, n=128, Rt=300e-6):
    return wm_surface(D, WR, L=L, n=n, Rt=Rt, seed=seed, device="cpu")


@pytest.mark.parametrize("method", ["tri", "box", "vs", "sp"])
def test_calibration_matches_targets(method):
    """A 'scan' that is itself a WM surface (other seed): targets are met within tolerance."""
    scan = _scan()
    settings = CalibrationSettings(method=method, seeds=(0, 1, 2), rtol=0.005)
    target = target_from_surface(scan, settings, Wr=WR)
    cal = calibrate(target, settings=settings, progress=False, device="cpu")
    assert cal.converged
    assert abs(cal.D_out - target.D) <= 0.005 * target.D
    # R_rms ∝ R_t for fixed D_in and seeds: the rescaling is exact up to float32 heights
    assert cal.Rrms == pytest.approx(target.Rrms, rel=1e-5)
    # independent check: regenerate the seeds at (D_in, R_t') and measure again
    ds = [
        fractal_dimension(
            wm_surface(cal.D_in, WR, L=L, n=128, Rt=cal.Rt, seed=s, device="cpu"), method
        ).D
        for s in (0, 1, 2)
    ]
    assert np.mean(ds) == pytest.approx(cal.D_out, abs=1e-9)
    # the scan's own D_in is recovered up to the seed scatter of D_out (slope ~1 … 3)
    assert cal.D_in == pytest.approx(2.45, abs=0.12)
    d = cal.to_dict()
    json.dumps({k: v.tolist() if isinstance(v, np.ndarray) else v for k, v in d.items()})
    assert len(d["history_D_in"]) == cal.iterations == len(d["history_D_out"])


def test_given_targets_and_high_resolution_surface():
    target = CalibrationTarget(
        D=2.4, method="vs", Rrms=2e-6, Rt=15e-6, Wr=WR, L=(L, L), n=(64, 64), source="given"
    )
    cal = calibrate(
        target, settings=CalibrationSettings(seeds=(0, 1)), progress=False, device="cpu"
    )
    s = calibrated_surface(cal, n=128, seed=3, device="cpu")
    assert s.heights.shape == (128, 128)
    assert s.Rt == pytest.approx(cal.Rt, rel=1e-5)  # heights are scaled to R_t'
    assert s.params["calibration"]["D_in"] == cal.D_in
    json.dumps(s.params)


@pytest.mark.parametrize(("D", "side", "D_in"), [(2.70, "upper", 2.4), (2.45, "lower", 2.3)])
def test_calibration_ending_on_a_bound_says_so(D, side, D_in):
    """D_vs of these 64² surfaces is 2.55 at D_in = 2.3 and 2.58 at 2.4 (measured): the target
    is met within 5 % only at one end of [2.3, 2.4], and the result says which."""
    target = CalibrationTarget(D=D, method="vs", Rrms=2e-6, Rt=15e-6, Wr=WR, L=L, n=64)
    settings = CalibrationSettings(seeds=(0, 1), D_bounds=(2.3, 2.4), D_start=D_in)
    cal = calibrate(target, settings=settings, progress=False, device="cpu")
    assert cal.D_in == D_in and cal.bound == side
    assert abs(cal.D_out - D) <= 0.05 * D  # within tolerance, yet only on the bound
    d = cal.to_dict()
    assert d["bound"] == side and d["D_bounds"] == [2.3, 2.4]


def test_unreachable_target():
    """D_tri in metres ("si") of a surface whose heights are tiny against the pixel size
    stays near 2."""
    target = CalibrationTarget(
        D=2.6,
        method="tri",
        Rrms=0.2e-6,
        Rt=1e-6,
        Wr=WR,
        L=L,
        n=64,
        source="given",
        method_options={"height_scaling": "si"},
    )
    with pytest.raises(
        CalibrationError,
        match=r"2\.6000 cannot be reached with D_in in \[2\.02, 2\.98\]: the upper bound",
    ):
        calibrate(target, settings=CalibrationSettings(seeds=(0,)), progress=False, device="cpu")


def test_target_validation():
    with pytest.raises(ValueError, match=r"D must be in \(2, 3\), got 3\.1"):
        CalibrationTarget(D=3.1, method="sp", Rrms=1e-6, Rt=5e-6, Wr=WR, L=L, n=64)
    with pytest.raises(ValueError, match="method must be one of"):
        CalibrationTarget(D=2.5, method="fft", Rrms=1e-6, Rt=5e-6, Wr=WR, L=L, n=64)
    with pytest.raises(ValueError, match="Rrms must be below Rt"):
        CalibrationTarget(D=2.5, method="sp", Rrms=6e-6, Rt=5e-6, Wr=WR, L=L, n=64)
    with pytest.raises(ValueError, match=r"n must be an integer in \[8, 1048576\], got 4"):
        CalibrationTarget(D=2.5, method="sp", Rrms=1e-6, Rt=5e-6, Wr=WR, L=L, n=4)
    assert CalibrationTarget(D=2.5, method="sp", Rrms=1e-6, Rt=5e-6, Wr=WR, L=L, n=64).L == (L, L)
    with pytest.raises(ValueError, match=r"D_bounds\[0\] must be in \(2, 3\), got 1\.9"):
        CalibrationSettings(D_bounds=(1.9, 2.9))
    with pytest.raises(ValueError, match="D_bounds needs LO < HI"):
        CalibrationSettings(D_bounds=(2.9, 2.1))


def test_target_from_unresolved_scan_needs_wr():
    scan = wm_surface(2.5, 3 * L, L=L, n=64, Rt=1e-6, seed=0, device="cpu")
    with pytest.raises(ValueError, match=r"does not resolve its roll-off wavelength.*give Wr"):
        target_from_surface(scan, CalibrationSettings(method="sp"))


# --- the root search on its own ------------------------------------------------------------------


def test_isotonic_against_brute_force():
    y = np.array([1.0, 3.0, 2.0, 2.5, 0.5, 4.0])
    got = isotonic(y)
    assert np.all(np.diff(got) >= 0)
    # pooled blocks: [1], [3, 2, 2.5, 0.5] → 2.0, [4]
    np.testing.assert_allclose(got, [1.0, 2.0, 2.0, 2.0, 2.0, 4.0])


def test_root_search_noisy_non_monotone():
    """f rises on average but wiggles and is noisy: the search still lands within atol."""
    rng = np.random.default_rng(0)
    calls = []

    def f(x):
        calls.append(x)
        return 0.7 * x + 0.8 + 0.02 * np.sin(60 * x) + rng.normal(0, 0.005)

    target = 0.7 * 2.63 + 0.8
    x = find_root(f, target, 0.01, (2.02, 2.98), 2.2, 15)
    assert abs(0.7 * x + 0.8 - target) < 0.01 + 0.02 + 0.015  # atol + wiggle + 3σ noise
    assert len(calls) <= 15


def test_root_search_out_of_evaluations():
    with pytest.raises(CalibrationError, match=r"did not reach 2\.5000 ± 0\.0001 in 3 evaluations"):
        find_root(lambda x: x + 0.01 * np.sin(1e4 * x), 2.5, 1e-4, (2.02, 2.98), 2.2, 3)


def test_root_search_unreachable_above():
    with pytest.raises(CalibrationError, match="cannot be reached"):
        find_root(lambda x: 2.0 + 0.1 * (x - 2.0), 2.9, 0.01, (2.02, 2.98), 2.5, 10)


# --- CLI and figure ------------------------------------------------------------------------------


def test_cli_calibrate_typed_targets(tmp_path, capsys):
    from warptrunc import read_height_map
    from warptrunc.cli import main

    out = tmp_path / "cal"
    rc = main(
        [
            "calibrate",
            "--method",
            "sp",
            "--D",
            "2.4",
            *TARGET,
            "--n",
            "128",
            "--seeds",
            "0",
            "1",
            "--n-out",
            "96",
            "--no-progress",
            "--out",
            str(out),
            "--device",
            "cpu",
        ]
    )
    assert rc == 0
    info = json.loads((out / "calibration.json").read_text())
    assert abs(info["D_out"] - 2.4) <= 0.05 * 2.4
    assert info["target_source"] == "given"
    s = read_height_map(out / "surface.npz")
    assert s.heights.shape == (96, 96)
    assert s.Rt == pytest.approx(info["Rt_m"], rel=1e-5)


def test_cli_calibrate_from_file_and_errors(tmp_path, capsys):
    from warptrunc.cli import main

    p = warptrunc.write_height_map(_scan(n=64), tmp_path / "scan.npz")
    rc = main(
        [
            "calibrate",
            str(p),
            "--method",
            "vs",
            "--Wr",
            str(WR),
            "--seeds",
            "0",
            "--no-progress",
            "--no-surface",
            "--out",
            str(tmp_path / "o"),
        ]
    )
    assert rc == 0
    info = json.loads((tmp_path / "o" / "calibration.json").read_text())
    assert info["target_nx"] == 64 and info["target_source"].endswith("scan.npz")
    assert not (tmp_path / "o" / "surface.npz").exists()
    assert main(["calibrate", "--D", "2.4", "--no-progress"]) == 2
    assert "missing --Rrms, --Rt, --Wr, --L, --n" in capsys.readouterr().err


def test_cli_calibrate_d_bounds(tmp_path, capsys):
    """--D-bounds is the search interval; a result on a bound is said and recorded (the case
    of test_calibration_ending_on_a_bound_says_so)."""
    from warptrunc.cli import main

    args = [
        "calibrate",
        "--method",
        "vs",
        "--D",
        "2.70",
        *TARGET,
        "--n",
        "64",
        "--seeds",
        "0",
        "1",
        "--no-progress",
        "--no-surface",
        "--device",
        "cpu",
        "--out",
        str(tmp_path / "o"),
    ]
    assert main([*args, "--D-bounds", "2.3", "2.4"]) == 0
    info = json.loads((tmp_path / "o" / "calibration.json").read_text())
    assert info["bound"] == "upper" and info["D_bounds"] == [2.3, 2.4] and info["D_in"] == 2.4
    assert "note: D_in' is the upper bound of --D-bounds (2.3, 2.4)" in capsys.readouterr().out
    assert main([*args, "--D-bounds", "2.4", "2.3"]) == 2
    assert "--D-bounds needs LO < HI, got 2.4 2.3" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main([*args, "--D-bounds", "2.4", "3"])
    assert "argument --D-bounds: must be in (2, 3), got '3'" in capsys.readouterr().err


def test_calibration_history_figure(tmp_path):
    from warptrunc import plot

    target = CalibrationTarget(D=2.45, method="vs", Rrms=2e-6, Rt=15e-6, Wr=WR, L=L, n=128)
    settings = CalibrationSettings(seeds=(0,), rtol=0.005)
    cal = calibrate(target, settings=settings, progress=False, device="cpu")
    fig = plot.calibration_history(cal, path=tmp_path / "h.png")
    assert len(fig.axes) == 1 and (tmp_path / "h.png").stat().st_size > 0
