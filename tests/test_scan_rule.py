# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The automatic rule for maps read from files (issue 41, item 1; ``warptrunc.robust``): one
map of each class that failed on the defaults — spikes that set R_t (planted on a WM surface),
a map whose contact at 0.1·R_t is a few dozen pixels, a map whose R_t a wide pit sets, a
patch of a few pixels a side — checked against numbers computed here with NumPy on the
heights (the spikes planted, contact pixels counted, neighbour medians), and the real scans
of ``../shared/data/scans`` when present."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import warptrunc as wt
from warptrunc.cli import main
from warptrunc.plausibility import FIT_MIN_CONTACT_PIXELS
from warptrunc.wm import wm_surface

pytestmark = pytest.mark.usefixtures("quiet_surfacetopography")


def _analyze(path: Path, out: Path, *extra) -> tuple[int, dict | None]:
    status = main(
        [
            "analyze",
            "-i",
            str(path),
            "--no-plot",
            "--device",
            "cpu",
            "--out",
            str(out),
            *map(str, extra),
        ]
    )
    fit = out / "fit.json"
    return status, json.loads(fit.read_text()) if status == 0 else None


def _warning_lines(err: str, code: str) -> list[str]:
    return [ln for ln in err.splitlines() if ln.startswith(f"warning: {code}: ")]


def _contact(z, depth: float) -> int:
    """Pixels with z ≥ z_top − ω, on float32 heights and a float32 threshold (the definition
    of contact in the truncation)."""
    z = np.asarray(z, dtype=np.float32)
    return int(np.count_nonzero(z >= np.float32(np.float64(z.max()) - depth)))


def _neighbour_median(z, iy: int, ix: int) -> float:
    """Median of the 8 neighbours of an interior pixel."""
    w = np.asarray(z, dtype=np.float64)[iy - 1 : iy + 2, ix - 1 : ix + 2].ravel()
    return float(np.median(np.delete(w, 4)))


# --- class (a): spikes that set R_t ------------------------------------------------------------

N_SPIKES = 200  # 0.3 % of a 256² map: P99.9 lies among them, so one pass finds only some


@pytest.fixture(scope="module")
def spiky(tmp_path_factory):
    d = tmp_path_factory.mktemp("spiky")
    clean = wm_surface(2.3, 100e-6, L=1e-3, n=256, Rt=10e-6, seed=2, device="cpu")
    z = np.array(clean.heights, dtype=np.float64)
    rng = np.random.default_rng(4)
    # on even rows and columns, off the edges: no two spikes are neighbours
    cells = np.array([(y, x) for y in range(2, 254, 2) for x in range(2, 254, 2)])
    iy, ix = cells[rng.choice(len(cells), N_SPIKES, replace=False)].T
    z[iy, ix] += rng.uniform(10, 60, N_SPIKES) * z.std()
    wt.write_height_map(wt.from_heights(z, clean.dx), d / "spiky.npz")
    wt.write_height_map(clean, d / "clean.npz")
    return d, clean, set(zip(iy.tolist(), ix.tolist(), strict=True))


def test_spikes_that_set_rt_are_masked_with_their_count(spiky, tmp_path, capsys):
    d, clean, planted = spiky
    status, fit = _analyze(d / "spiky.npz", tmp_path / "a")
    err = capsys.readouterr().err
    assert status == 0, err
    rule = fit["fit_range"]
    assert rule["asked"] == "auto" and rule["rule"] == "auto"
    masked = rule["spikes_masked"]
    assert masked["count"] == N_SPIKES  # every spike planted, nothing else
    assert masked["passes"] >= 2 and masked["sets"] == ["top"]
    zc = np.asarray(clean.heights, dtype=np.float64)
    raw = wt.read_height_map(d / "spiky.npz").heights
    assert masked["Rt_before_m"] == pytest.approx(float(raw.max() - raw.min()), rel=1e-6)
    assert masked["Rt_after_m"] == pytest.approx(float(zc.max() - zc.min()), rel=1e-3)
    assert fit["surface"]["Rt_m"] == pytest.approx(float(zc.max() - zc.min()), rel=1e-3)
    (line,) = _warning_lines(err, "auto_spikes_masked")
    assert f"{N_SPIKES} spike pixel(s)" in line and "--spikes report keeps them" in line
    (w,) = [w for w in fit["warnings"] if w["code"] == "auto_spikes_masked"]
    assert {(p["iy"], p["ix"]) for p in w["details"]["locations"]} <= planted
    # the fit is worth reading and reads the surface, not the spikes: the clean map's numbers
    assert fit["fit_error"] is None and fit["r2"] >= 0.9 and 0 < fit["alpha"] <= 1
    status, ref = _analyze(d / "clean.npz", tmp_path / "c")
    assert status == 0 and ref["fit_range"]["spikes_masked"] is None
    assert abs(fit["alpha"] - ref["alpha"]) < 0.02
    assert fit["depth_max"] == pytest.approx(ref["depth_max"], rel=0.01)


def test_spikes_report_keeps_the_map_as_read(spiky, tmp_path, capsys):
    """``--spikes report``: reported (one pass, as before), never masked; R_t and the depths
    are those of the map as read."""
    d, _, _ = spiky
    status, fit = _analyze(d / "spiky.npz", tmp_path / "r", "--spikes", "report")
    err = capsys.readouterr().err
    assert status == 0, err
    raw = wt.read_height_map(d / "spiky.npz").heights
    rt = float(np.float64(raw.max()) - raw.min())
    assert fit["surface"]["Rt_m"] == pytest.approx(rt, rel=1e-6)
    assert fit["fit_range"]["spikes_masked"] is None
    assert not _warning_lines(err, "auto_spikes_masked")
    (line,) = _warning_lines(err, "spikes")
    assert "reported, not masked" in line
    ext = fit["fit_range"]["depth_extended"]
    if ext is None:
        assert fit["depth_max"] == pytest.approx(0.1 * rt, rel=1e-6)
    else:  # extended on the map as read: from 0.1·R_t of the spikes
        assert ext["from_m"] == pytest.approx(0.1 * rt, rel=1e-6)
        assert _contact(raw, fit["depth_max"]) == ext["contact_pixels"]


# --- class (b): a few dozen contact pixels at 0.1·R_t --------------------------------------------


@pytest.fixture(scope="module")
def sparse(tmp_path_factory):
    d = tmp_path_factory.mktemp("sparse")
    s = wm_surface(2.3, 100e-6, L=1.25e-4, n=64, Rt=1e-6, seed=1, device="cpu")
    wt.write_height_map(s, d / "sparse.npz")
    return d / "sparse.npz", np.asarray(s.heights)


def test_depth_extends_to_50_contact_pixels(sparse, tmp_path, capsys):
    path, z = sparse
    rt = float(np.float64(z.max()) - z.min())
    before = _contact(z, 0.1 * rt)
    assert 10 <= before < FIT_MIN_CONTACT_PIXELS  # the class: fitted on the legacy range, flagged
    status, legacy = _analyze(path, tmp_path / "l", "--fit-range", "legacy")
    assert status == 0 and legacy["fit_error"].startswith("not worth reading")
    assert legacy["fit_range"] == {
        "asked": "legacy",
        "rule": "legacy",
        "levelled": None,
        "reason": "--fit-range legacy asked",
        "spikes_masked": None,
        "depth_extended": None,
        "depth_cut": None,
    }
    capsys.readouterr()
    status, fit = _analyze(path, tmp_path / "a")
    err = capsys.readouterr().err
    assert status == 0, err
    ext = fit["fit_range"]["depth_extended"]
    assert fit["fit_range"]["rule"] == "auto" and fit["fit_range"]["depth_cut"] is None
    assert ext["contact_pixels_before"] == before
    # the deepest fitted increment: ≥ 50 contact pixels, and no deeper than the pixel after
    after = _contact(z, fit["depth_max"])
    assert after >= FIT_MIN_CONTACT_PIXELS and after == ext["contact_pixels"]
    zs = np.sort(z.astype(np.float64).ravel())[::-1]
    target = ext["target_contact_pixels"]
    assert target in (50, 100, 200) and after == target
    assert zs[0] - zs[target - 1] <= fit["depth_max"] < zs[0] - zs[target]
    assert fit["depth_max"] == pytest.approx(ext["to_m"], rel=1e-12)
    assert fit["fit_error"] is None and fit["r2"] >= 0.9 and 0 < fit["alpha"] <= 1
    assert math.log10(fit["F_over_EA_max"] / fit["F_over_EA_min"]) >= 0.5
    (line,) = _warning_lines(err, "auto_depth_extended")
    assert f"{before} contact pixels" in line and f"{after} contact pixels" in line
    assert "not worth reading (fit: only" in fit["fit_range"]["reason"]


# --- R_t set by a wide pit (not a spike): the depth range is cut to 5 % of A ---------------------


def test_depth_is_cut_to_five_percent_when_a_pit_sets_rt(tmp_path, capsys):
    s = wm_surface(2.3, 100e-6, L=5e-4, n=128, Rt=1e-6, seed=3, device="cpu")
    z = np.array(s.heights, dtype=np.float64)
    y, x = np.mgrid[0:128, 0:128]
    z -= 5e-6 * np.exp(-((x - 40.0) ** 2 + (y - 90.0) ** 2) / (2 * 12.0**2))  # a wide pit
    top = np.unravel_index(np.argmax(z), z.shape)
    z[top] += 10e-6  # a spike on the highest pixel: the default range is empty
    wt.write_height_map(wt.from_heights(z, s.dx), tmp_path / "pit.npz")
    status, fit = _analyze(tmp_path / "pit.npz", tmp_path / "a")
    err = capsys.readouterr().err
    assert status == 0, err
    rule = fit["fit_range"]
    assert rule["spikes_masked"]["count"] == 1 and rule["spikes_masked"]["sets"] == ["top"]
    zm = z.astype(np.float32)
    zm[top] = _neighbour_median(zm, *top)  # the masked map, by hand
    rt = float(np.float64(zm.max()) - zm.min())
    assert _contact(zm, 0.1 * rt) > 0.05 * z.size  # the pit sets R_t: 0.1·R_t is deep
    cut = rule["depth_cut"]
    assert cut is not None and rule["depth_extended"] is None
    n_cut = _contact(zm, fit["depth_max"])
    assert FIT_MIN_CONTACT_PIXELS <= n_cut <= math.floor(0.05 * z.size) == cut["contact_pixels"]
    assert len(_warning_lines(err, "auto_depth_cut")) == 1
    assert fit["fit_error"] is None


# --- class (c): a patch of a few pixels a side -----------------------------------------------


@pytest.mark.parametrize("shape", [(5, 10), (7, 4), (31, 200)])
def test_tiny_map_is_refused_in_one_line(shape, tmp_path, capsys):
    np.save(tmp_path / "m.npy", np.random.default_rng(1).normal(size=shape))
    out = tmp_path / "x"
    status = main(["analyze", "-i", str(tmp_path / "m.npy"), "--dx", "1e-6", "--out", str(out)])
    err = capsys.readouterr().err.strip()
    assert status == 2 and not out.exists()
    assert len(err.splitlines()) == 1
    ny, nx = shape
    assert f"{nx}×{ny} pixels" in err and "at least 32 pixels a side" in err


def test_compare_refuses_a_tiny_map_and_masks_spikes_as_it_reads(spiky, tmp_path, capsys):
    import argparse

    from warptrunc.cli import _common
    from warptrunc.cli import compare as cmd

    p = argparse.ArgumentParser()
    cmd.add_arguments(p)
    d, clean, _ = spiky
    args = p.parse_args(["--input", str(d / "spiky.npz")])
    s = _common.read_input(d / "spiky.npz", args)
    zc = np.asarray(clean.heights)
    assert s.Rt == pytest.approx(float(zc.max() - zc.min()), rel=1e-3)
    assert [w.code for w in args._warnings] == ["auto_spikes_masked"]
    assert args._warnings[0].details["count"] == N_SPIKES
    np.save(tmp_path / "m.npy", np.zeros((5, 10)))
    args = p.parse_args(["--input", str(tmp_path / "m.npy"), "--dx", "1e-6"])
    with pytest.raises(ValueError, match=r"10×5 pixels .* at least 32 pixels a side"):
        _common.read_input(tmp_path / "m.npy", args)


# --- what the rule leaves alone ----------------------------------------------------------------


def test_generated_surface_keeps_the_default_fit(tmp_path, capsys):
    out = tmp_path / "g"
    assert (
        main(
            [
                "analyze",
                "--n",
                "64",
                "--min-pixels",
                "1",
                "--no-plot",
                "--device",
                "cpu",
                "--out",
                str(out),
            ]
        )
        == 0
    )
    assert "warning: auto_" not in capsys.readouterr().err
    fit = json.loads((out / "fit.json").read_text())
    rule = fit["fit_range"]
    assert rule["asked"] == "auto" and rule["rule"] == "legacy"
    assert rule["reason"].startswith("a generated surface")
    assert fit["depth_max"] == pytest.approx(0.1 * fit["surface"]["Rt_m"], rel=1e-6)


def test_a_range_of_ones_own_is_kept(sparse, tmp_path, capsys):
    path, _ = sparse
    status, fit = _analyze(path, tmp_path / "w", "--max-depth", 1e-7)
    assert status == 0
    assert fit["fit_range"]["rule"] == "legacy"
    assert fit["fit_range"]["reason"] == "a range of the caller's own (--max-depth)"
    assert fit["depth_max"] == pytest.approx(1e-7, rel=1e-9)


# --- the real scans ----------------------------------------------------------------------------


def test_real_scans_give_a_fit_worth_reading_on_defaults(scans_dir, tmp_path, capsys):
    pytest.importorskip("SurfaceTopography")  # the instrument files need the 'scans' extra
    files = [f for f in sorted(scans_dir.iterdir()) if f.suffix != ".md"]
    for f in files:
        status, fit = _analyze(f, tmp_path / f.name, "--missing", "fill")
        err = capsys.readouterr().err
        assert status == 0, (f.name, err)
        assert fit["fit_error"] is None and fit["r2"] >= 0.9 and 0 < fit["alpha"] <= 1, f.name
        assert math.log10(fit["F_over_EA_max"] / fit["F_over_EA_min"]) >= 0.5, f.name
        rule = fit["fit_range"]
        assert rule["asked"] == "auto" and rule["reason"], f.name
        # every automatic decision is one warning line and one key
        for key, code in (
            ("levelled", "auto_levelled"),
            ("spikes_masked", "auto_spikes_masked"),
            ("depth_extended", "auto_depth_extended"),
            ("depth_cut", "auto_depth_cut"),
        ):
            assert len(_warning_lines(err, code)) == (rule[key] is not None), (f.name, code)
