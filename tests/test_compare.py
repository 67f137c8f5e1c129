# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""warptrunc.compare: Eq. 2, island-resolved truncation and elastic BEM on one map, the study
store (resume, conflicts, tables from the store) and ``warptrunc compare``."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from warptrunc.compare import (
    CASE_COLUMNS,
    MapStudy,
    StudyDesign,
    compare_models,
    compare_study,
    load_comparison,
    study_cases,
    summarize,
)
from warptrunc.compare.models import _k_vs_F
from warptrunc.stiffness import Material

pd = pytest.importorskip("pandas")
FR = (0.05, 0.1, 0.2, 0.4)


def test_k_vs_F_recovers_a_power_law():
    F = np.geomspace(1e-3, 1.0, 7)
    f = _k_vs_F(F, 3.0 * F**0.62)
    assert f["alpha"] == pytest.approx(0.62, rel=1e-12) and f["prefactor"] == pytest.approx(3.0)
    assert f["r2"] == pytest.approx(1.0) and f["n_points"] == 7
    assert math.isnan(_k_vs_F([0, 1, 2], [1, 2, 3])["alpha"])  # two usable points


def test_deprecated_names_are_gone():
    import warptrunc.compare as c

    for name in ("DEFAULT_FRACTIONS", "MODELS", "fit_k_vs_F"):
        assert not hasattr(c, name)


def test_compare_models_against_independent_formulas(device):
    """Eq. 2 and the island sum at each approach from the float32 threshold mask and
    ``scipy.ndimage.label``; the elastic columns are those of ``solve_contact``."""
    import scipy.ndimage as ndi

    from warptrunc.contact import solve_contact
    from warptrunc.wm import wm_surface

    s = wm_surface(2.5, 100e-6, L=300e-6, n=48, Rt=1e-6, seed=2, device=device)
    m = Material()
    c = compare_models(s, FR, material=m, device=device)
    z, top = s.heights, np.float32(s.heights.max())
    pref = 2 / math.sqrt(math.pi) * m.contact_modulus
    for i, f in enumerate(FR):
        mask = z >= np.float32(top - np.float32(f * s.Rt))
        lab, n = ndi.label(mask)
        a = np.bincount(lab.ravel())[1:] * s.pixel_area
        assert c.n_islands[i] == n
        assert c.trunc_area[i] == pytest.approx(mask.sum() * s.pixel_area, rel=1e-12)
        assert c.eq2_stiffness[i] == pytest.approx(pref * math.sqrt(a.sum()), rel=1e-12)
        assert c.islands_stiffness[i] == pytest.approx(pref * np.sqrt(a).sum(), rel=1e-9)
    assert np.all(c.islands_stiffness >= c.eq2_stiffness * (1 - 1e-9))
    assert np.all(c.islands_load >= c.eq2_load * (1 - 1e-9)) and np.all(np.diff(c.eq2_load) > 0)
    cc = solve_contact(s, np.asarray(FR) * s.Rt, material=m, device=device)
    np.testing.assert_allclose(c.bem_load, cc.load, rtol=1e-12)
    np.testing.assert_allclose(c.bem_stiffness, cc.stiffness, rtol=1e-12)
    assert c.converged.all()
    np.testing.assert_allclose(c.ratio("eq2"), c.eq2_stiffness / c.bem_stiffness)
    d = c.to_dict()
    assert set(d) <= set(CASE_COLUMNS) and all(len(v) == len(FR) for v in d.values())
    assert set(c.fits()) == {"eq2", "islands", "bem"}


def test_study_cases_grids():
    cases = study_cases(
        StudyDesign(D=(2.5,), size_ratios=(1, 3), pixels_per_Wr=16, refine_ratio=3, seeds="0-1")
    )
    grids = sorted({(c["size_ratio"], c["n"]) for c in cases})
    assert grids == [(1, 16), (3, 48), (3, 96)] and len(cases) == 6
    fine = [c for c in cases if c["n"] == 96]
    assert all(c["Wc_m"] == pytest.approx(2 * 100e-6 / 16) for c in cases)  # same surface
    assert all(c["dx_m"] == pytest.approx(100e-6 / 32) for c in fine)
    with pytest.raises(ValueError, match="whole number"):
        study_cases(StudyDesign(size_ratios=(1.5,), pixels_per_Wr=3, refine_ratio=None))


def test_study_resumes_refuses_and_reloads(tmp_path, monkeypatch):
    import warptrunc.compare as cmp
    import warptrunc.compare.study as cmp_study

    design = StudyDesign(
        D=(2.2, 2.8), size_ratios=(1,), pixels_per_Wr=24, refine_ratio=None, seeds=0, fractions=FR
    )
    cases = study_cases(design)
    out = tmp_path / "study"
    rows = compare_study(out, design, device="cpu", progress=False)
    assert list(rows.columns) == list(CASE_COLUMNS) and len(rows) == 2 * len(FR)
    meta = json.loads((out / "study.json").read_text())  # strict JSON
    assert meta["format"] == cmp.FORMAT and meta["settings"]["fractions"] == list(FR)
    # resume: one case file lost, only that case is computed again
    lost = out / "cases" / f"{cases[1]['case_id']}.parquet"
    lost.unlink()
    calls = []
    real = cmp.compare_models
    monkeypatch.setattr(
        cmp_study, "compare_models", lambda *a, **k: calls.append(1) or real(*a, **k)
    )
    again = compare_study(out, design, device="cpu", progress=False)
    assert len(calls) == 1 and lost.exists()
    times = ["case_seconds", "solve_time_s"]  # the recomputed case: same numbers, new times
    pd.testing.assert_frame_equal(again.drop(columns=times), rows.drop(columns=times))
    # other settings: refused, store untouched
    with pytest.raises(ValueError, match="differing: fractions"):
        compare_study(out, design.replace(fractions=(0.1, 0.2, 0.3)), device="cpu", progress=False)
    # the tables are reproducible from the store
    s1, s2 = summarize(rows), summarize(load_comparison(out))
    for k in ("ratios", "alpha"):
        pd.testing.assert_frame_equal(s1[k], s2[k])
    r = s1["ratios"]
    assert len(r) == 2 * len(FR) and (r["seeds"] == 1).all()
    # the rows load with plain pandas too
    assert len(pd.read_parquet(out / "cases")) == len(rows)


def test_cli_compare_on_a_map(tmp_path):
    from warptrunc.io import write_height_map
    from warptrunc.wm import wm_surface

    s = wm_surface(2.5, 100e-6, L=200e-6, n=32, Rt=1e-6, seed=1, device="cpu")
    write_height_map(s, tmp_path / "s.npz")
    out = tmp_path / "out"
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "warptrunc",
            "compare",
            "--input",
            str(tmp_path / "s.npz"),
            "--fractions",
            *map(str, FR),
            "--device",
            "cpu",
            "--out",
            str(out),
            "--no-progress",
        ],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert r.returncode == 0, r.stderr
    rows = load_comparison(out)
    assert list(rows["case_id"].unique()) == ["input"] and len(rows) == len(FR)
    assert rows["n"].iloc[0] == 32 and rows["D_in"].iloc[0] == 2.5
    summ = json.loads((out / "summary.json").read_text())
    assert summ["stage"]["n_cases"] == 1
    assert len(pd.read_parquet(out / "ratios.parquet")) == len(FR)
    assert "α" in r.stdout and "wrote" in r.stdout


def test_map_study_stores_the_map_at_its_approaches(tmp_path):
    """A study of one map is that map's ``compare_models`` at its fractions, stored as the
    case ``input``; fractions that do not increase are refused, naming them."""
    from warptrunc.wm import wm_surface

    s = wm_surface(2.5, 100e-6, L=200e-6, n=32, Rt=1e-6, seed=1, device="cpu")
    rows = compare_study(tmp_path / "m", MapStudy(s, fractions=FR), device="cpu", progress=False)
    c = compare_models(s, FR, device="cpu")
    assert list(rows["case_id"].unique()) == ["input"]
    np.testing.assert_array_equal(rows["bem_load_N"], c.bem_load)
    np.testing.assert_array_equal(rows["eq2_stiffness_N_per_m"], c.eq2_stiffness)
    with pytest.raises(ValueError, match=r"fractions must increase strictly .* got 0\.2 0\.1"):
        MapStudy(s, fractions=(0.2, 0.1))
