# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Plausibility warnings: the spike rule (against scipy's median filter), no false positives on
WM surfaces and clean real scans, D outside (2, 3), fits not worth reading, the fit range past
§ 4.3's depth, and the CLI: warnings in the JSON outputs and on stderr, ``--fit-range``."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from cli_helpers import run_cli

import warptrunc as wt
from warptrunc import plausibility as pl
from warptrunc.islands.results import Indicators
from warptrunc.stiffness import fit_power_law, stiffness_curve
from warptrunc.wm import wm_surface

ROOT = Path(__file__).resolve().parents[1]
SCANS = ROOT.parent.parent / "shared" / "data" / "scans"  # /work/shared/data/scans beside wt/NAME
if not SCANS.is_dir():
    SCANS = ROOT.parent / "shared" / "data" / "scans"
CLEAN_SCANS = ("x3p-2.x3p", "top-1.top", "matrix-4.txt")


def _neighbours(z):
    """(ny, nx, 8) heights of the 8 neighbours of every pixel (mirrored edges), from sliding
    windows."""
    z = np.asarray(z, dtype=np.float64)
    w = np.lib.stride_tricks.sliding_window_view(np.pad(z, 1, mode="reflect"), (3, 3))
    return np.delete(w.reshape(*z.shape, 9), 4, axis=-1)


def _neighbour_median(z):
    return np.median(_neighbours(z), axis=-1)


def _reference_spikes(z, k=pl.SPIKE_K, share=pl.SPIKE_SHARE):
    """The spike rule written independently, on sliding windows of the whole map."""
    z = np.asarray(z, dtype=np.float64)
    nb = _neighbours(z)
    d = z - np.median(nb, axis=-1)
    sigma = 1.4826 * np.median(np.abs(d - np.median(d)))
    p_lo, p_hi = np.percentile(z, [0.1, 99.9])
    close = np.count_nonzero(np.abs(nb - z[..., None]) < np.abs(d)[..., None] / 2, axis=-1)
    flag = (np.abs(d) > k * sigma) & (np.abs(d) > share * (p_hi - p_lo)) & (close < 4)
    return [(int(y), int(x)) for y, x in zip(*np.nonzero(flag), strict=True)]


@pytest.mark.parametrize("n", [256, 512])
@pytest.mark.parametrize("D", [2.1, 2.3, 2.5, 2.7, 2.9])
def test_no_spikes_on_wm_surfaces(D, n):
    for seed in (1, 2, 3):
        s = wm_surface(D, 100e-6, L=1e-3, n=n, Rt=1e-6, seed=seed, device="cpu")
        assert pl.check_spikes(s) == []


@pytest.mark.parametrize("name", CLEAN_SCANS)
def test_no_spikes_on_clean_real_scans(name):
    pytest.importorskip("SurfaceTopography")
    if not (SCANS / name).exists():
        pytest.skip(f"{SCANS} is absent (real scans are not shipped)")
    s = wt.read_height_map(SCANS / name)
    assert pl.check_spikes(s) == []
    assert _reference_spikes(s.heights) == []


def test_dropouts_of_the_sur_scan_are_flagged():
    """sur-2.sur has pits next to its missing points, up to 15 robust height ranges deep."""
    pytest.importorskip("SurfaceTopography")
    if not (SCANS / "sur-2.sur").exists():
        pytest.skip(f"{SCANS} is absent (real scans are not shipped)")
    s = wt.read_height_map(SCANS / "sur-2.sur", missing="fill")
    iy, ix, _ = pl.find_spikes(s.heights)
    assert list(zip(iy.tolist(), ix.tolist(), strict=True)) == _reference_spikes(s.heights)
    assert iy.size > 0


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_a_byte_flipped_pixel_is_flagged_at_its_place(sign):
    s = wm_surface(2.5, 100e-6, L=1e-3, n=256, Rt=10e-6, seed=4, device="cpu")
    z = np.array(s.heights, dtype=np.float64)
    z[77, 150] += sign * 10.0 * s.Rt  # one spike moves R_t tenfold
    spiky = wt.from_heights(z, s.dx)
    (w,) = pl.check_spikes(spiky)
    assert w.code == "spikes" and w.details["count"] == 1
    loc = w.details["locations"][0]
    assert (loc["iy"], loc["ix"]) == (77, 150)
    assert loc["x_m"] == pytest.approx(150 * s.dx) and loc["y_m"] == pytest.approx(77 * s.dx)
    assert _reference_spikes(z) == [(77, 150)]
    masked, (mw,) = pl.mask_spikes(spiky)
    assert mw.details["action"] == "mask"
    med = _neighbour_median(z.astype(np.float32))
    assert masked.heights[77, 150] == np.float32(med[77, 150])
    zc = z.astype(np.float32)
    zc[77, 150] = med[77, 150]
    assert masked.Rt == pytest.approx(float(zc.max()) - float(zc.min()), rel=1e-6)
    assert masked.params["n_spikes_masked"] == 1


def _reference_passes(z, passes):
    """The spike rule repeated on the map masked by the passes before, with NumPy: (set of
    pixels flagged, masked heights)."""
    z = np.asarray(z, dtype=np.float32).copy()
    hit: set = set()
    for _ in range(passes):
        flags = _reference_spikes(z)
        if not flags:
            break
        med = _neighbour_median(z)
        for y, x in flags:
            z[y, x] = np.float32(med[y, x])
        hit |= set(flags)
    return hit, z


def test_repeated_passes_find_a_spike_population_one_pass_misses():
    s = wm_surface(2.3, 100e-6, L=1e-3, n=128, Rt=10e-6, seed=5, device="cpu")
    z = np.array(s.heights, dtype=np.float64)
    rng = np.random.default_rng(8)
    cells = np.array([(y, x) for y in range(2, 126, 2) for x in range(2, 126, 2)])
    iy, ix = cells[rng.choice(len(cells), 60, replace=False)].T  # 0.37 % of the pixels
    z[iy, ix] += rng.uniform(10, 60, 60) * z.std()
    spiky = wt.from_heights(z, s.dx)
    planted = set(zip(iy.tolist(), ix.tolist(), strict=True))
    assert 0 < len(_reference_spikes(z)) < 60  # P99.9 lies among the spikes: one pass is short
    masked, (w,) = pl.mask_spikes(spiky, passes=10)
    hit, zref = _reference_passes(z, 10)
    assert hit == planted and w.details["count"] == 60 and w.details["passes"] >= 2
    np.testing.assert_array_equal(masked.heights, zref)
    assert masked.params["n_spikes_masked"] == 60
    _, (w1,) = pl.mask_spikes(spiky)  # the default: one pass, as before
    assert w1.details["count"] == len(_reference_spikes(z)) and w1.details["passes"] == 1
    with pytest.raises(ValueError, match="passes must be an integer ≥ 1"):
        pl.mask_spikes(spiky, passes=0)


def test_spikes_report_counts_one_pass(spiky_map, tmp_path):
    """``analyze --spikes report``: the spikes reported as one pass finds them, the map kept."""
    r = _analyze(spiky_map / "spiky.npz", tmp_path / "r", "--spikes", "report", cwd=tmp_path)
    assert r.returncode == 2  # the spike alone is in contact at 0.1·R_t: nothing to fit
    assert "warning: spikes: 1 spike pixel(s) (first at iy=40, ix=200)" in r.stderr
    assert "reported, not masked" in r.stderr and "auto_spikes_masked" not in r.stderr


def test_spike_options_are_checked():
    with pytest.raises(ValueError, match="k must be"):
        pl.find_spikes(np.zeros((4, 4)), k=0)
    with pytest.raises(ValueError, match="share must be"):
        pl.find_spikes(np.zeros((4, 4)), share=math.nan)
    iy, _, _ = pl.find_spikes(np.zeros((4, 4)))  # flat: nothing to find
    assert iy.size == 0


def test_dimensions_outside_2_3():
    ws = pl.check_dimensions({"sp": 3.27, "tri": 2.4, "box": None, "vs": math.nan, "x": 2.0})
    assert [(w.code, w.details["method"]) for w in ws] == [
        ("dimension_range", "sp"),
        ("dimension_range", "x"),
    ]


def _curve(D, n, seed=1, delta=0.01):
    s = wm_surface(D, 100e-6, L=1e-3, n=n, Rt=delta * 100e-6, seed=seed, device="cpu")
    return stiffness_curve(wt.truncate(s, 200, max_depth_fraction=0.1, device="cpu"))


def test_the_sweep_fit_of_issue_30_is_flagged():
    """256², D = 2.7, δ = 0.01, seed 1: 10 contact pixels at every fitted increment, so E_c/E
    is constant: α = 0 and r² undefined (NaN), both flagged."""
    sc = _curve(2.7, 256)
    fit = fit_power_law(sc)
    assert fit.alpha == 0.0 and math.isnan(fit.r2)
    codes = {w.code for w in pl.check_fit(fit, sc)}
    assert {"fit_contact_pixels", "fit_r2", "fit_alpha", "fit_load_decades"} <= codes
    assert pl.fit_error_text(pl.check_fit(fit, sc)).startswith("not worth reading")


def test_a_good_fit_is_not_flagged():
    sc = _curve(2.3, 1024, seed=0)
    fit = fit_power_law(sc)
    # independent reading of the same fit range: the numbers the rules look at
    sel = (sc.load > 0) & (sc.n_contact_pixels >= 10)
    assert sc.n_contact_pixels[sel].max() >= pl.FIT_MIN_CONTACT_PIXELS
    assert math.log10(sc.F_over_EA[sel].max() / sc.F_over_EA[sel].min()) >= 0.5
    assert pl.check_fit(fit, sc) == []
    assert pl.fit_error_text([]) is None


def test_alpha_outside_0_1_is_flagged():
    sc = _curve(2.3, 1024, seed=0)
    fit = fit_power_law(sc)
    from dataclasses import replace

    for a in (0.0, -0.1, 1.2):
        codes = [w.code for w in pl.check_fit(replace(fit, alpha=a), sc)]
        assert codes == ["fit_alpha"]


def _indicators(growth, fractal, censored, Rt=1e-6):
    return Indicators(
        max_growth_depth=growth,
        fractal_depth=fractal,
        peak_depth=growth,
        plateau_exponent=0.6,
        fractal_depth_censored=censored,
        Rt=Rt,
        exponent_tolerance=0.05,
        min_islands=50,
        persist=0.02,
        plateau_range=(0.0, 0.1),
        smooth=5,
    )


def test_fit_past_the_applicable_depth():
    sc = _curve(2.5, 512)
    fit = fit_power_law(sc)  # to 0.1·R_t
    Rt = sc.Rt
    assert pl.check_fit_depth(fit, _indicators(0.3 * Rt, math.nan, False, Rt)) == []
    (w,) = pl.check_fit_depth(fit, _indicators(0.05 * Rt, math.nan, False, Rt))
    assert w.code == "fit_past_validity" and w.details["max_growth_rate_depth_m"] == 0.05 * Rt
    # a censored fractality depth is a lower bound: no warning from it
    assert pl.check_fit_depth(fit, _indicators(0.3 * Rt, 0.05 * Rt, True, Rt)) == []
    (w,) = pl.check_fit_depth(fit, _indicators(0.3 * Rt, 0.05 * Rt, False, Rt))
    assert "fractality depth" in w.message


def test_report_prints_one_line_each(capsys):
    ws = pl.check_dimensions({"sp": 3.5, "tri": 1.9})
    out = pl.report(ws)
    err = capsys.readouterr().err.splitlines()
    assert err == [str(w) for w in ws] and all(
        e.startswith("warning: dimension_range: ") for e in err
    )
    assert out == [w.to_dict() for w in ws] and json.dumps(out)


# --- the command line ----------------------------------------------------------------------


def _cli(*args, cwd):
    return run_cli(*args, cwd=cwd)


def _analyze(height_map, out, *extra, cwd):
    """``warptrunc analyze --input MAP --no-plot --out OUT --device cpu EXTRA`` in ``cwd``."""
    return _cli(
        "analyze",
        "--input",
        height_map,
        "--no-plot",
        "--out",
        out,
        "--device",
        "cpu",
        *extra,
        cwd=cwd,
    )


@pytest.fixture(scope="module")
def spiky_map(tmp_path_factory):
    d = tmp_path_factory.mktemp("spiky")
    s = wm_surface(2.3, 100e-6, L=1e-3, n=512, Rt=10e-6, seed=2, device="cpu")
    wt.write_height_map(s, d / "clean.npz")
    z = np.array(s.heights, dtype=np.float64)
    z[40, 200] += 10 * s.Rt
    wt.write_height_map(wt.from_heights(z, s.dx), d / "spiky.npz")
    return d


def test_analyze_flags_and_fits_a_spiky_map(spiky_map, tmp_path):
    r = _analyze(spiky_map / "spiky.npz", tmp_path / "a", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "warning: auto_spikes_masked: 1 spike pixel(s) (first at iy=40, ix=200;" in r.stderr
    info = json.loads((tmp_path / "a" / "fit.json").read_text())
    assert info["warnings"][0]["code"] == "auto_spikes_masked"
    rule = info["fit_range"]
    assert rule["rule"] == "auto" and rule["spikes_masked"]["count"] == 1
    assert rule["reason"].startswith("the default fit is empty")
    assert info["fit_error"] is None and info["r2"] >= 0.9
    assert 0 < info["alpha"] <= 1
    # the spike masked, the map is the clean one but for one pixel: the clean map's legacy fit
    s = wt.read_height_map(spiky_map / "clean.npz")
    fit = fit_power_law(stiffness_curve(wt.truncate(s, 200, max_depth_fraction=0.1)))
    assert abs(info["alpha"] - fit.alpha) < 1e-3
    # the legacy range on the same map: ω_max = 0.1·R_t of the spike touches the spike alone
    r = _analyze(spiky_map / "spiky.npz", tmp_path / "b", "--fit-range", "legacy", cwd=tmp_path)
    assert r.returncode == 2 and "only 0 increments in the fit range" in r.stderr
    assert "warning: spikes: 1 spike pixel(s) (first at iy=40, ix=200)" in r.stderr


def test_analyze_on_a_clean_map_keeps_the_legacy_range(spiky_map, tmp_path):
    r = _analyze(spiky_map / "clean.npz", tmp_path / "a", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert not [ln for ln in r.stderr.splitlines() if ln.startswith("warning:")], r.stderr
    info = json.loads((tmp_path / "a" / "fit.json").read_text())
    assert info["warnings"] == []
    # the rule auto chose, and why (issue 41, item 5)
    assert info["fit_range"] == {
        "asked": "auto",
        "rule": "legacy",
        "levelled": None,
        "spikes_masked": None,
        "depth_extended": None,
        "depth_cut": None,
        "reason": "the default fit is worth reading, no spike sets R_t and no tilt spans more "
        "than the roughness",
    }
    s = wt.read_height_map(spiky_map / "clean.npz")
    fit = fit_power_law(stiffness_curve(wt.truncate(s, 200, max_depth_fraction=0.1)))
    assert info["alpha"] == fit.alpha  # the legacy numbers, unchanged
    assert info["applicable_depth"]["max_growth_rate_depth_m"] > info["depth_max"]


def test_describe_warns_about_d_outside_2_3(tmp_path):
    # white noise: D_sp of a flat spectrum is above 3
    rng = np.random.default_rng(5)
    wt.write_height_map(
        wt.from_heights(rng.normal(size=(128, 128)) * 1e-6, 1e-6), tmp_path / "noise.npz"
    )
    r = _cli("describe", tmp_path / "noise.npz", "--json", "-", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    bad = {
        m
        for m in ("tri", "box", "vs", "sp")
        if out[f"D_{m}"] is not None and not 2 < out[f"D_{m}"] < 3
    }
    assert bad  # the case is one the check must catch
    assert {w["details"]["method"] for w in out["warnings"]} == bad
    assert r.stderr.count("warning: dimension_range:") == len(bad)


def test_sweep_flags_the_fit_of_issue_30(tmp_path):
    pytest.importorskip("pandas")
    r = _cli(
        "sweep",
        "--D",
        "2.1",
        "2.7",
        "--delta",
        "0.01",
        "--seeds",
        "1",
        "--n",
        "256",
        "--out",
        tmp_path / "s",
        "--no-progress",
        "--device",
        "cpu",
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    df = wt.sweep.load(tmp_path / "s")
    bad = df[df["D_in"] == 2.7].iloc[0]
    assert bad["fit_error"].startswith("not worth reading")
    assert {w["code"] for w in json.loads(bad["warnings"])} >= {"fit_r2", "fit_contact_pixels"}
    assert np.isfinite(bad["alpha"])  # kept beside the error
    good = df[df["D_in"] == 2.1].iloc[0]
    assert good["fit_error"] is None or str(good["fit_error"]) == "<NA>"
    assert "1 fits not worth reading" in r.stderr
    # one D left: no trend line α = a·D + b from a flagged fit, and the summary says why
    assert "·D" not in r.stdout and "no line α(D)" in r.stdout
