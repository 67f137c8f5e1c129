# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""warptrunc.reproduce: single asperity (Fig. 2), stage store, and the tiny profile end to end."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from warptrunc.reproduce import StageConflict, StageStore, reproduce
from warptrunc.reproduce.asperity import (
    AsperityMaterial,
    closed_form_truncation,
    fully_plastic,
    hertz,
    pixel_area_bounds,
    run_asperity,
    storakers,
)

MAT = AsperityMaterial()
R = 1e-3


def _slope(x, y):
    return float(np.polyfit(np.log(x), np.log(y), 1)[0])


def test_storakers_limits():
    d = np.geomspace(1e-8, 1e-5, 20)
    for m in (0.0, 0.3, 1.0):
        _a, f = storakers(d, R, MAT, m)
        assert _slope(d, f) == pytest.approx(1 + m / 2, abs=1e-9)
    a0, f0 = storakers(d, R, MAT, 0.0)
    assert _slope(d, a0) == pytest.approx(1.0)  # a ∝ d
    np.testing.assert_allclose(f0 / a0, 3 * MAT.sigma_y)  # constant mean pressure 3σ_y
    # m = 1 against incompressible Hertz (ν = ½, σ₀ = E): within the curve fits' 15 %
    inc = AsperityMaterial(nu=0.5)
    a1, f1 = storakers(d, R, inc, 1.0)
    ah, fh = hertz(d, R, inc)
    np.testing.assert_allclose(a1 / ah, 1.0, rtol=0.1)
    np.testing.assert_allclose(f1 / fh, 1.0, rtol=0.15)


def test_closed_form_truncation_load_matches_quadrature():
    from scipy.integrate import quad

    d = np.array([1e-7, 3e-6, 2e-5, 4e-4])
    _, f = closed_form_truncation(d, R, MAT)
    k = lambda s: 2 / math.sqrt(math.pi) * MAT.E_r * math.sqrt(math.pi * (2 * R * s - s * s))  # noqa: E731
    ref = [quad(k, 0, x, epsabs=0, epsrel=1e-10)[0] for x in d]
    np.testing.assert_allclose(f, ref, rtol=1e-7)


@pytest.fixture(scope="module")
def sphere():
    return run_asperity(n=256, n_increments=200, device="cpu")


def test_sphere_truncated_area_within_pixel_bound(sphere):
    a, _ = sphere.curves["truncation"]
    lo, hi = pixel_area_bounds(sphere.d, sphere.R, sphere.dx)
    assert np.all(a >= lo) and np.all(a <= hi)
    exact = math.pi * (2 * sphere.R * sphere.d - sphere.d**2)
    assert abs(a[-1] - exact[-1]) / exact[-1] < 0.01


def test_sphere_truncation_between_hertz_and_plastic(sphere):
    a, f = sphere.curves["truncation"]
    sel = f > 0
    ah, fh = hertz(sphere.d, sphere.R, MAT)
    ap, fp = fully_plastic(sphere.d, sphere.R, MAT)
    above_hertz = a[sel] / np.interp(f[sel], fh, ah)
    below_plastic = a[sel] / np.interp(f[sel], fp, ap)
    assert np.all(above_hertz > 1.0)
    d_star = R * (3 * math.pi * MAT.H / (2 * math.sqrt(2) * MAT.E_r)) ** 2
    deep = sphere.d[sel] > 1.05 * d_star
    assert deep.any() and np.all(below_plastic[deep] < 1.0)
    assert np.all(below_plastic[sphere.d[sel] < 0.95 * d_star] > 1.0)


def test_stage_store_reuses_and_refuses(tmp_path):
    st = StageStore(tmp_path)
    calls = []
    st.run("s", {"a": 1}, lambda: calls.append(1) or {"x": 1.5})
    assert StageStore(tmp_path).run("s", {"a": 1}, lambda: calls.append(2) or {"x": 9}) == {"x": 1.5}
    assert calls == [1]
    with pytest.raises(StageConflict, match="differing: a"):
        StageStore(tmp_path).run("s", {"a": 2}, lambda: {"x": 3})
    assert json.loads(st.path("s").read_text())["result"] == {"x": 1.5}  # not destroyed
    assert StageStore(tmp_path, overwrite=True).run("s", {"a": 2}, lambda: {"x": 3}) == {"x": 3}


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    out = tmp_path_factory.mktemp("repro")
    return out, reproduce("tiny", out, device="cpu")


def test_tiny_report_structure(tiny):
    out, doc = tiny
    text = (out / "report.md").read_text()
    for head in ("Fig. 2", "Fig. 5", "Table 1", "Table 2", "Table 3", "Fig. 10"):
        assert head in text
    for name in doc["meta"]["figures"]:
        assert f"]({name})" in text
        img = __import__("matplotlib.image", fromlist=["imread"]).imread(out / name)
        assert img[..., :3].std() > 0.01  # not blank
    res = json.loads((out / "results.json").read_text())
    assert res["meta"]["device"].startswith("cpu") and res["meta"]["wall_s"] > 0
    stages = {"asperity", "fig5", "table1", "islands", "group1", "group2", "elastic"}
    assert set(res["stages"]) == stages
    assert res["analysis"]["asperity"]["pixel_bound_holds"]


def test_tiny_group1_beta_scaling(tiny):
    _, doc = tiny
    b = doc["analysis"]["table3_beta"]["default"]
    # β ∝ δ^−α when only R_t changes: the fitted exponent is −(mean α of group 1)
    assert b["ours"]["p"] == pytest.approx(b["minus_alpha"], abs=0.01)


def test_tiny_rerun_reuses_and_conflict(tiny):
    out, _ = tiny
    doc = reproduce("tiny", out, device="cpu")
    stored = {"asperity", "fig5", "table1", "islands", "group1", "group2", "elastic"}
    assert set(doc["meta"]["reused"]) == stored
    from dataclasses import replace

    from warptrunc.reproduce import get_profile

    with pytest.raises(StageConflict):
        reproduce(replace(get_profile("tiny"), seeds=1), out, device="cpu")


def test_tiny_group_stores_loadable_and_reused(tiny):
    pd = pytest.importorskip("pandas")
    from warptrunc.sweep import load

    out, doc = tiny
    stores = {g: out / "sweeps" / g for g in ("group1", "group2")}
    g2 = load(stores["group2"])
    rows = doc["stages"]["group2"]["rows"]
    # one row per surface × fit range (the package default and the late range), no failures,
    # the four D measured on every group-2 surface (group 1 has none: fractal_on_group1 False)
    assert len(g2) == 2 * len(rows) == 2 * 3 * 2 and g2["error"].isna().all()
    assert g2[["D_tri", "D_box", "D_vs", "D_sp"]].notna().all().all()
    assert load(stores["group1"])[["D_tri", "D_vs"]].isna().all().all()
    for r in rows:  # the report's rows are the store's
        part = g2[g2.case_id == r["case_id"]]
        late = part[part.min_pixels_fraction == doc["stages"]["group2"]["fit_ranges"]["late"]]
        for fit, sel in (("default", part[part.min_pixels_fraction.isna()]), ("late", late)):
            a = sel.alpha.item()  # None in the stage where the range had < 3 points (NaN here)
            assert r["fits"][fit]["alpha"] == a if np.isfinite(a) else "error" in r["fits"][fit]
        assert r["fits"]["late"]["min_pixels"] == late.min_pixels.item()
        assert r["D"]["vs"]["D"] == part.D_vs.iloc[0] and r["D"]["tri"]["D"] == part.D_tri.iloc[0]
    assert np.isfinite(g2.alpha).sum() >= len(rows)  # the comparisons above are not all skipped
    before = {g: load(p) for g, p in stores.items()}
    # stage files lost and group 1 interrupted (cases.parquet and one curve gone): the rerun
    # rebuilds both stages from the stores and computes only the missing surface
    for g in stores:
        (out / "stages" / f"{g}.json").unlink()
    lost = before["group1"].case_id.iloc[-1]
    (stores["group1"] / "cases.parquet").unlink()
    (stores["group1"] / "curves" / f"{lost}.parquet").unlink()
    again = reproduce("tiny", out, device="cpu")
    assert set(again["meta"]["computed"]) == {"group1", "group2"}
    pd.testing.assert_frame_equal(load(stores["group2"]), before["group2"])  # same stamps
    g1 = load(stores["group1"])
    kept = g1.case_id != lost
    pd.testing.assert_frame_equal(g1[kept], before["group1"][kept])
    assert (g1[~kept].finished_utc > before["group1"][~kept].finished_utc.max()).all()
    from warptrunc.sweep import RUN_COLUMNS

    pd.testing.assert_frame_equal(g1.drop(columns=list(RUN_COLUMNS)),
                                  before["group1"].drop(columns=list(RUN_COLUMNS)))  # fmt: skip
    assert again["stages"]["group2"] == doc["stages"]["group2"]
    assert again["analysis"]["table3_beta"] == doc["analysis"]["table3_beta"]
    assert "sweeps/group2" in (out / "report.md").read_text()


def test_tiny_elastic_section(tiny):
    """The elastic stage of the tiny profile: every cell in the tables, finite positive ratios,
    the section and its two figures in the report."""
    out, doc = tiny
    text = (out / "report.md").read_text()
    assert "## How far is truncation from elastic contact?" in text
    stage, ana = doc["stages"]["elastic"], doc["analysis"]["elastic"]
    from warptrunc.reproduce import get_profile

    p = get_profile("tiny")
    n_grids = len(p.elastic_size_ratios) + 1
    assert stage["n_cases"] == len(p.elastic_D) * p.elastic_seeds * n_grids
    assert stage["n_rows"] == stage["n_cases"] * len(p.elastic_fractions)
    assert len(stage["ratios"]) == len(p.elastic_D) * n_grids * len(p.elastic_fractions)
    for r in stage["ratios"]:
        for k in ("eq2_k_ratio_mean", "islands_k_ratio_mean", "eq2_F_ratio_mean"):
            assert np.isfinite(r[k]) and r[k] > 0, (k, r)
        # one punch per island is never softer than one punch of the total area
        assert r["islands_k_ratio_mean"] >= r["eq2_k_ratio_mean"] * (1 - 1e-9)  # √a to 2^-31
    for key in ("eq2_k_ratio", "islands_k_ratio"):
        m = ana["models"][key]
        assert m["cells"] == len(p.elastic_D) * len(p.elastic_size_ratios) * len(p.elastic_fractions)
    assert "within ±20 %" in text and "Reading the paper in this light" in text
    for name in ("elastic_ratio_vs_size.png", "elastic_alpha_vs_D.png"):
        assert name in doc["meta"]["figures"] and f"]({name})" in text
    assert (out / "stages" / "elastic.json").exists()


def test_tiny_elastic_tables_from_store(tiny):
    """The stage's tables are recomputed exactly from the Parquet case store."""
    pytest.importorskip("pandas")
    from warptrunc.compare import load_comparison
    from warptrunc.reproduce.elastic import summary_from_rows

    out, doc = tiny
    rows = load_comparison(out / "elastic")
    again = json.loads(json.dumps(summary_from_rows(rows), default=float))
    stage = doc["stages"]["elastic"]
    for k in ("ratios", "alpha", "grid", "n_cases", "n_rows"):
        assert _nan_eq(again[k], stage[k]), k
    # the ratio columns are the quotients of the stored columns
    np.testing.assert_allclose(rows["eq2_k_ratio"],
                               rows["eq2_stiffness_N_per_m"] / rows["bem_stiffness_N_per_m"])  # fmt: skip
    np.testing.assert_allclose(rows["islands_F_ratio"], rows["islands_load_N"] / rows["bem_load_N"])


def _nan_eq(a, b) -> bool:
    """Equality of JSON-like values with NaN (stage JSON: null) equal to NaN/None."""
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(_nan_eq(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(_nan_eq(x, y) for x, y in zip(a, b, strict=True))
    na = a is None or (isinstance(a, float) and math.isnan(a))
    nb = b is None or (isinstance(b, float) and math.isnan(b))
    if na or nb:
        return na and nb
    if isinstance(a, float) or isinstance(b, float):
        return a == pytest.approx(b, rel=1e-12)
    return a == b
