# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The automatic rule's tilt, its deeper ranges and its refusal (``warptrunc.robust``), on
synthetic maps checked with NumPy: a WM surface on a tilted plane; a map whose default range
holds more than 50 contact pixels and still no fit worth reading; a map on which no range of
the rule gives one, refused with the settings that do (each then run as the user would);
and, when ``WARPTRUNC_ST_EXAMPLES`` names SurfaceTopography's example files, every map among
them."""

from __future__ import annotations

import json
import os
import re
import shlex
from pathlib import Path

import numpy as np
import pytest

import warptrunc as wt
from warptrunc.cli import main
from warptrunc.robust import tilt_rule
from warptrunc.wm import wm_surface

pytestmark = pytest.mark.usefixtures("quiet_surfacetopography")


def _analyze(path: Path, out: Path, *extra) -> tuple[int, dict | None]:
    argv = ["analyze", "-i", str(path), "--no-plot", "--device", "cpu", "--out", str(out)]
    status = main([*argv, *map(str, extra)])
    return status, json.loads((out / "fit.json").read_text()) if status == 0 else None


def _plane(z: np.ndarray) -> np.ndarray:
    """The least-squares plane a + b·ix + c·iy of ``z``, by NumPy's lstsq."""
    ny, nx = z.shape
    iy, ix = np.mgrid[0:ny, 0:nx]
    a = np.stack([np.ones(z.size), ix.ravel(), iy.ravel()], axis=1)
    coef, *_ = np.linalg.lstsq(a, z.ravel(), rcond=None)
    return (a @ coef).reshape(z.shape)


def _robust_range(z: np.ndarray) -> float:
    lo, hi = np.percentile(z, [0.1, 99.9])
    return float(hi - lo)


# --- tilt ----------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def tilted(tmp_path_factory):
    """A WM surface on a plane that spans 3·R_robust, and the surface itself."""
    d = tmp_path_factory.mktemp("tilted")
    clean = wm_surface(2.3, 100e-6, L=1e-3, n=128, Rt=1e-6, seed=2, device="cpu")
    z = np.asarray(clean.heights, dtype=np.float64)
    ix = np.arange(128)[None, :]
    plane = 3.0 * _robust_range(z - _plane(z)) * ix / 127.0
    wt.write_height_map(wt.from_heights(z + plane, clean.dx), d / "tilted.npz")
    wt.write_height_map(clean, d / "clean.npz")
    return d


def test_a_tilted_map_is_levelled_and_gives_the_levelled_maps_fit(tilted, tmp_path, capsys):
    status, fit = _analyze(tilted / "tilted.npz", tmp_path / "t")
    err = capsys.readouterr().err
    assert status == 0, err
    rec = fit["fit_range"]["levelled"]
    z = np.asarray(wt.read_height_map(tilted / "tilted.npz").heights, dtype=np.float64)
    flat = z - _plane(z)
    assert rec["plane_range_m"] == pytest.approx(float(np.ptp(_plane(z))), rel=1e-6)
    assert rec["roughness_range_m"] == pytest.approx(_robust_range(flat), rel=1e-6)
    assert rec["plane_range_m"] > rec["roughness_range_m"]  # the rule's condition
    assert fit["surface"]["Rt_m"] == pytest.approx(float(np.ptp(flat)), rel=1e-5)
    (line,) = [ln for ln in err.splitlines() if ln.startswith("warning: auto_levelled: ")]
    assert "as --level" in line
    # the same map read with --level: not levelled again, the same range and the same fit
    capsys.readouterr()
    status, ref = _analyze(tilted / "tilted.npz", tmp_path / "r", "--level")
    assert status == 0 and ref["fit_range"]["levelled"] is None and ref["fit_error"] is None
    assert fit["fit_error"] is None
    assert fit["depth_max"] == pytest.approx(ref["depth_max"], rel=1e-5)
    assert fit["alpha"] == pytest.approx(ref["alpha"], abs=1e-4)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_wm_map_one_wavelength_wide_is_not_levelled(seed):
    """Its longest wavelength spans the map (W_r = L): a plane well under R_robust."""
    s = wm_surface(2.2, 100e-6, L=100e-6, n=128, Rt=1e-6, seed=seed, device="cpu")
    z = np.asarray(s.heights, dtype=np.float64)
    assert np.ptp(_plane(z)) < 0.6 * _robust_range(z - _plane(z))
    out, rec, warnings = tilt_rule(s)
    assert out is s and rec is None and warnings == []


def test_a_map_read_levelled_is_not_levelled_again(tilted):
    s = wt.read_height_map(tilted / "tilted.npz", level=True)
    out, rec, _ = tilt_rule(s)
    assert out is s and rec is None


# --- a default range with more than 50 contact pixels, and no fit worth reading -----------------


def _shoulder(seed: int, slow: float) -> np.ndarray:
    """A WM surface whose 10 highest pixels spread over ``slow``·R_t below the top and the next
    50 over the rest of 0.1·R_t: the default range holds 60 contact pixels."""
    s = wm_surface(2.3, 100e-6, L=1e-3, n=128, Rt=1e-6, seed=seed, device="cpu")
    z = np.array(s.heights, dtype=np.float64)
    rt, top = float(np.ptp(z)), float(z.max())
    order = np.argsort(z.ravel())[::-1]
    flat = z.ravel()
    flat[order[:10]] = top - np.linspace(0.0, slow * rt, 10)
    flat[order[10:60]] = top - np.linspace((slow + 1e-3) * rt, 0.099 * rt, 50)
    return wt.from_heights(flat.reshape(z.shape), s.dx)


def test_the_contact_pixels_double_from_a_range_that_holds_more_than_50(tmp_path, capsys):
    wt.write_height_map(_shoulder(2, 0.06), tmp_path / "m.npz")
    z = np.asarray(wt.read_height_map(tmp_path / "m.npz").heights, dtype=np.float32)
    rt = float(np.float64(z.max()) - z.min())
    held = int(np.count_nonzero(z >= np.float32(np.float64(z.max()) - 0.1 * rt)))
    assert held == 60  # ≥ 50: nothing for the extension to 50 to do
    status, legacy = _analyze(tmp_path / "m.npz", tmp_path / "l", "--fit-range", "legacy")
    assert status == 0 and legacy["fit_error"] is not None  # the default fit is flagged
    capsys.readouterr()
    status, fit = _analyze(tmp_path / "m.npz", tmp_path / "a")
    err = capsys.readouterr().err
    assert status == 0, err
    ext = fit["fit_range"]["depth_extended"]
    assert ext["contact_pixels_before"] == held
    assert ext["target_contact_pixels"] in (2 * held, 4 * held, 8 * held)
    zs = np.sort(z.astype(np.float64).ravel())[::-1]
    target = ext["target_contact_pixels"]
    assert zs[0] - zs[target - 1] <= fit["depth_max"] < zs[0] - zs[target]
    assert fit["fit_error"] is None and fit["r2"] >= 0.9 and 0 < fit["alpha"] <= 1
    (line,) = [ln for ln in err.splitlines() if ln.startswith("warning: auto_depth_extended: ")]
    assert f", {held} contact pixels)" in line and f", {target} contact pixels)" in line
    assert "the count doubled until it was" in line


# --- no range of the rule gives a fit worth reading: refused, with settings that do ------------


def test_no_fit_worth_reading_is_refused_with_settings_checked_on_the_map(tmp_path, capsys):
    wt.write_height_map(_shoulder(1, 0.08), tmp_path / "m.npz")
    out = tmp_path / "a"
    status = main(["analyze", "-i", str(tmp_path / "m.npz"), "--no-plot", "--device", "cpu",
                   "--out", str(out)])  # fmt: skip
    err = capsys.readouterr().err.strip()
    assert status == 2 and not out.exists()
    assert len(err.splitlines()) == 1, err
    assert "no fit worth reading (automatic rule: " in err
    assert "--fit-range legacy" in err
    advice = re.search(r"on this map these give one: (.+); or --fit-range legacy", err)
    assert advice, err
    settings = [re.sub(r" \(α [^)]*\)$", "", a) for a in advice.group(1).split("; ")]
    assert 1 <= len(settings) <= 2
    for i, setting in enumerate(settings):  # each, as the user would run it
        status, fit = _analyze(tmp_path / "m.npz", tmp_path / f"s{i}", *shlex.split(setting))
        assert status == 0, capsys.readouterr().err
        assert fit["fit_error"] is None, setting
        alpha = float(re.search(r"α (\S+), r² (\S+)\)", advice.group(1).split("; ")[i])[1])
        assert fit["alpha"] == pytest.approx(alpha, abs=0.006), setting


# --- SurfaceTopography's example files, when given -----------------------------------------------


def test_every_example_map_gives_a_fit_or_says_what_to_change(tmp_path, capsys):
    """``WARPTRUNC_ST_EXAMPLES``: SurfaceTopography's ``test/file_format_examples`` (not part of
    this repository). Every file read into a map of 32 pixels a side or more gives, on
    ``--missing fill`` and the defaults, a fit worth reading or a refusal that names settings
    checked on the map or what on the map keeps every range from one."""
    folder = os.environ.get("WARPTRUNC_ST_EXAMPLES")
    if not folder or not Path(folder).is_dir():
        pytest.skip("WARPTRUNC_ST_EXAMPLES does not name SurfaceTopography's example files")
    maps = 0
    for f in sorted(Path(folder).iterdir()):
        try:
            s = wt.read_height_map(f, missing="fill")
        except Exception:  # no map, or no spacing: the readers' own tests
            continue
        if min(s.nx, s.ny) < 32:
            continue
        maps += 1
        status, fit = _analyze(f, tmp_path / f.name, "--missing", "fill")
        err = capsys.readouterr().err
        if status == 0:
            assert fit["fit_error"] is None, (f.name, fit["fit_error"])
        else:
            line = err.strip().splitlines()[-1]
            assert status == 2 and "no fit worth reading" in line, (f.name, line)
            assert "these give one: " in line or "no --rt-percentile or --max-depth" in line
    assert maps >= 20
