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
    k = lambda s: (  # noqa: E731
        2 / math.sqrt(math.pi) * MAT.contact_modulus * math.sqrt(math.pi * (2 * R * s - s * s))
    )
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
    d_star = R * (3 * math.pi * MAT.H / (2 * math.sqrt(2) * MAT.contact_modulus)) ** 2
    deep = sphere.d[sel] > 1.05 * d_star
    assert deep.any() and np.all(below_plastic[deep] < 1.0)
    assert np.all(below_plastic[sphere.d[sel] < 0.95 * d_star] > 1.0)


def test_stage_store_reuses_and_refuses(tmp_path):
    st = StageStore(tmp_path)
    calls = []
    st.run("s", {"a": 1}, lambda: calls.append(1) or {"x": 1.5})
    assert StageStore(tmp_path).run("s", {"a": 1}, lambda: calls.append(2) or {"x": 9}) == {
        "x": 1.5
    }
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
    assert res["meta"]["provenance"]["device"] == "cpu" and res["meta"]["wall_s"] > 0
    stages = {"asperity", "fig5", "table1", "islands", "group1", "group2", "elastic", "indentation"}
    assert set(res["stages"]) == stages
    assert res["analysis"]["asperity"]["pixel_bound_holds"]


def test_tiny_group1_beta_scaling(tiny):
    out, doc = tiny
    # β ∝ δ^−α when only R_t changes: the exponent of β(δ) over every fit of group 1 (those
    # flagged not worth reading at this size too, a property of the method) is −(mean α)
    rows = json.loads((out / "results.json").read_text())["stages"]["group1"]["rows"]
    f = [(r["delta"], r["fits"]["default"]) for r in rows if r["fits"]["default"].get("beta")]
    p = np.polyfit(np.log([d for d, _ in f]), np.log([x["beta"] for _, x in f]), 1)[0]
    assert p == pytest.approx(-np.mean([x["alpha"] for _, x in f]), abs=0.01)
    b = doc["analysis"]["table3_beta"]["default"]
    if b["ours"] is not None:  # the fits worth reading, when there are some: the same law
        assert b["ours"]["p"] == pytest.approx(b["minus_alpha"], abs=0.01)


def test_tiny_rerun_reuses_and_conflict(tiny):
    out, _ = tiny
    doc = reproduce("tiny", out, device="cpu")
    stored = {"asperity", "fig5", "table1", "islands", "group1", "group2", "elastic", "indentation"}
    assert set(doc["meta"]["reused"]) == stored
    from dataclasses import replace

    from warptrunc.reproduce import get_profile

    with pytest.raises(StageConflict):
        reproduce(replace(get_profile("tiny"), seeds=1), out, device="cpu")


def _drop_case(store, case_id):
    """Rewrite the part holding ``case_id`` without it (as if killed before that case's part)."""
    from warptrunc.sweep.curves import part_files, part_rows, read_part_curves, write_part

    for f in part_files(store / "curves"):
        held = part_rows(f)
        if case_id not in {rs[0]["case_id"] for rs in held}:
            continue
        keep = [rs for rs in held if rs[0]["case_id"] != case_id]
        curves = read_part_curves(f)
        f.unlink()
        if keep:
            write_part(
                store / "curves",
                [
                    (
                        rs,
                        {
                            k: v.to_numpy()
                            for k, v in curves[curves.case_id == rs[0]["case_id"]]
                            .drop(columns="case_id")
                            .items()
                        },
                    )
                    for rs in keep
                ],
            )


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
    # stage files lost and group 1 interrupted (cases.parquet and one case's curve gone): the rerun
    # rebuilds both stages from the stores and computes only the missing surface
    for g in stores:
        (out / "stages" / f"{g}.json").unlink()
    lost = before["group1"].case_id.iloc[-1]
    (stores["group1"] / "cases.parquet").unlink()
    _drop_case(stores["group1"], lost)
    again = reproduce("tiny", out, device="cpu")
    assert set(again["meta"]["computed"]) == {"group1", "group2"}
    pd.testing.assert_frame_equal(load(stores["group2"]), before["group2"])  # same stamps
    g1 = load(stores["group1"])
    kept = g1.case_id != lost
    pd.testing.assert_frame_equal(g1[kept], before["group1"][kept])
    assert (g1[~kept].finished_utc > before["group1"][~kept].finished_utc.max()).all()
    from warptrunc.sweep import RUN_COLUMNS

    pd.testing.assert_frame_equal(
        g1.drop(columns=list(RUN_COLUMNS)), before["group1"].drop(columns=list(RUN_COLUMNS))
    )
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
        assert m["cells"] == len(p.elastic_D) * len(p.elastic_size_ratios) * len(
            p.elastic_fractions
        )
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
    np.testing.assert_allclose(
        rows["eq2_k_ratio"], rows["eq2_stiffness_N_per_m"] / rows["bem_stiffness_N_per_m"]
    )
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


# --- paper scale, fit-range map, slit band, Fig. 2 models, commit -----------------------------


def test_paper_profile_at_paper_scale():
    from warptrunc.reproduce import get_profile

    p = get_profile("paper")
    assert (p.islands_n, p.islands_L, p.fig5_seeds) == (30720, 3e-3, 10)
    assert p.islands_seeds >= 2 and (p.table1_n, p.n, p.seeds) == (1024, 10240, 5)
    assert p.islands_n**2 < 2**30  # the in-memory labelling limit (warptrunc._support.limits)
    assert p.islands_n**2 * 52 < 70 * 2**30  # island_curve's statistics fit an 80 GB GPU


def test_fit_range_map_equals_direct_refit(tiny):
    """One range of the map, re-fitted by hand from the stored curves, and the stored fit."""
    from warptrunc.reproduce.fitrange import refit_store
    from warptrunc.stiffness import fit_power_law
    from warptrunc.sweep import load, load_curves

    out, doc = tiny
    fm = doc["analysis"]["fit_range_map"]
    g2 = out / doc["stages"]["group2"]["store"]
    cases, alphas, D = load(g2), [], []
    for cid, part in cases[cases["error"].isna()].groupby("case_id", sort=False):
        c = load_curves(g2, cid)
        sc = __import__("types").SimpleNamespace(
            depth=c["depth_m"].to_numpy(),
            n_contact_pixels=c["n_contact_pixels"].to_numpy(),
            load=c["load_N"].to_numpy(),
            Ec_over_E=c["Ec_over_E"].to_numpy(),
            F_over_EA=c["F_over_EA"].to_numpy(),
        )
        stored = part[part["min_pixels_fraction"].isna() & (part["min_pixels"] == 10)].iloc[0]
        if not np.isfinite(stored["alpha"]):  # too few increments: left out, as in the map
            with pytest.raises(ValueError):
                fit_power_law(sc, min_pixels=10)
            continue
        a = fit_power_law(sc, min_pixels=10).alpha
        assert a == pytest.approx(float(stored["alpha"]), rel=1e-9)  # the sweep's own fit
        alphas.append(a)
        D.append(float(part["D_in"].iloc[0]))
    slope, icpt = np.polyfit(D, alphas, 1)  # independent: numpy's least-squares line
    ref = {"slope": slope, "intercept": icpt}
    got = fm["alpha"]["min_pixels=10"]["in"]
    assert got["slope"] == pytest.approx(ref["slope"], rel=1e-12)
    assert got["intercept"] == pytest.approx(ref["intercept"], rel=1e-12)
    assert got["alpha_2_5"] == pytest.approx(2.5 * ref["slope"] + ref["intercept"])
    # the map's rows cover both kinds of range and β is −α of group 1 in each
    rows = refit_store(g2)
    assert {r["kind"] for r in rows} == {"min_pixels", "fraction"}
    for b in fm["beta"].values():
        if b is not None:
            assert b["p"] == pytest.approx(b["minus_alpha"], abs=0.01)


def test_slit_bootstrap_band_contains_estimate_and_is_deterministic():
    from warptrunc.islands import (
        ISLANDS_TRUNCATION,
        IslandSettings,
        island_curve,
        slit_bootstrap,
        slit_island_fit,
    )
    from warptrunc.wm import wm_surface

    s = wm_surface(2.5, 60e-6, L=1e-3, n=256, Rt=30e-6, seed=0, device="cpu")
    t = ISLANDS_TRUNCATION.replace(increments=50)
    c = island_curve(s, truncation=t, settings=IslandSettings(snapshots=(0.3,)), device="cpu")
    (sz,) = c.sizes
    e, lo, hi = slit_bootstrap(sz, min_islands=5)
    assert e == pytest.approx(slit_island_fit(sz, min_islands=5).exponent)
    assert lo < e < hi
    assert slit_bootstrap(sz, min_islands=5) == (e, lo, hi)  # same seed, same band
    assert slit_bootstrap(sz, min_islands=5, seed=1) != (e, lo, hi)
    # blocks of islands: the same estimate, a band of similar width
    eb, lob, hib = slit_bootstrap(sz, min_islands=5, blocks=8)
    assert eb == e and lob < e < hib


def test_tiny_report_new_sections(tiny):
    out, doc = tiny
    text = (out / "report.md").read_text()
    assert "| item | the paper | this run | same? |" in text
    assert "## Fit-range map of Table 3" in text and "](fit_range_map.png)" in text
    assert "Slit-island exponent with an error bar" in text
    for model in ("Storåkers–Biwa–Larsson", "Hertz", "fully plastic", "truncation model"):
        assert model in text
    sb = doc["analysis"]["slit_band"]
    assert sb and all(len(v["lo"]) == len(v["percent_Rt"]) for v in sb.values())
    band = doc["stages"]["islands"]["surfaces"]
    for s in band.values():
        b = s["seeds"][0]["slit_band"]
        for e, lo, hi in zip(b["exponent"], b["lo"], b["hi"], strict=True):
            if e is not None and lo is not None:
                assert lo <= e <= hi


def test_report_commit_fallback(tiny, monkeypatch):
    from warptrunc._support.provenance import git_commit
    from warptrunc.reproduce import get_profile
    from warptrunc.reproduce.report import departure_lines, markdown

    rows = "\n".join(departure_lines(get_profile("paper").to_dict()))
    assert "| Islands (Figs. 7–8, Table 2) | 30720² over 3 mm | 30720² over 3 mm," in rows
    assert "| Fig. 5 seeds per resolution | 10 | 10 | yes |" in rows
    out, _ = tiny
    doc = json.loads((out / "results.json").read_text())
    # made where neither the variable nor git says
    meta = {**doc["meta"], "provenance": {**doc["meta"]["provenance"], "git_commit": None}}
    text = markdown(meta, doc["stages"], doc["analysis"], doc["meta"]["figures"])
    assert "commit unknown (set `WARPTRUNC_GIT_COMMIT` or pass `--commit SHA`)" in text
    assert "commit `None`" not in text
    monkeypatch.setenv("WARPTRUNC_GIT_COMMIT", "abc123")
    assert git_commit() == "abc123"


# --- the indentation stage (Fig. 6 in silico) -------------------------------------------------


def test_tiny_indentation_stage(tiny):
    """Rows of every surface × design × model × realisation × punch × placement × load, F/(E·A)
    from the definition, truncation independent of H at the same pixel, the section, its figures
    and the resolution check; the sweep's elastic–plastic pieces take the unyielded cycles of
    the unrefined punches from the sweep's elastic piece."""
    from warptrunc.reproduce import get_profile

    out, doc = tiny
    p = get_profile("tiny")
    st, ana = doc["stages"]["indentation"], doc["analysis"]["indentation"]
    r = st["rows"]
    pr = p.indentation.protocol
    n_punch = len(pr.punch_diameters) * len(pr.peak_loads)
    expect = 0
    for t in st["timings"]:
        if t["design"] != "face":  # the face pieces are kept apart (st["faces"])
            expect += (
                len(t["seeds"]) * t["placements"] * n_punch * (2 if t["model"] == "elastic" else 1)
            )
    assert (
        len(r["surface"]) == expect
    )  # + truncation once per surface and design (its elastic piece)
    assert {
        "truncation",
        "elastic",
        "elastic_plastic_0.5GPa",
        "elastic_plastic_2GPa",
        "elastic_plastic_8GPa",
    } == set(r["model"])
    d, f = np.array(r["punch_diameter_m"]), np.array(r["peak_load_N"])
    np.testing.assert_allclose(r["F_over_EA"], f / (70e9 * np.pi * d**2 / 4), rtol=1e-12)
    model, design = np.array(r["model"]), np.array(r["design"])
    trunc = np.array(r["truncation_E_c_over_E"], dtype=float)
    px = np.array(r["pixel_size_m"], dtype=float)
    for s in p.indentation.surfaces:
        el = (model == "elastic") & (design == "sweep") & (np.array(r["surface"]) == s)
        ep = (model == "elastic_plastic_2GPa") & (design == "sweep") & (np.array(r["surface"]) == s)
        same = px[el] == px[ep]  # truncation does not depend on H at one pixel
        assert same.any() and np.array_equal(trunc[el][same], trunc[ep][same])
    assert np.all(np.array(r["plastic_area_m2"], dtype=float)[model == "elastic"] == 0)
    assert np.any(
        np.array(r["plastic_area_m2"], dtype=float)[model == "elastic_plastic_0.5GPa"] > 0
    )
    assert ana["mean_pressure"]["p_mean_Pa"] == pytest.approx(0.5 / (np.pi * 27.05e-6**2))
    assert round(ana["mean_pressure"]["p_mean_Pa"] / 1e6) == 218
    assert ana["smooth_Ec_over_E"] == pytest.approx(73.52e9 / 70e9, rel=1e-3)
    res = ana["resolution"]
    assert res["n_fine"] == 2 * res["n_coarse"] and res["dx_fine_m"] == pytest.approx(
        res["dx_coarse_m"] / 2
    )
    text = (out / "report.md").read_text()
    assert "## Indentation in silico (Fig. 6)" in text and "Which model truncation tracks" in text
    assert "](indentation_fig6.png)" in text and "](indentation_depth_vs_H.png)" in text
    assert "Resolution check" in text and "| Indentation punches | 54.1, 108.7, 502.6 µm |" in text
    assert "| Hardness H of the alloy | not stated | swept: ∞, 0.5, 2, 8 GPa | n/a |" in text
    pieces = sorted((out / "indentation").glob("*.json"))
    assert len(pieces) == len(st["timings"]) + 1  # + resolution
    assert "cycles taken from the elastic piece" in text
    recs = {f.stem: json.loads(f.read_text()) for f in pieces if f.stem != "resolution"}
    m = len(pr.peak_loads)
    for name, rec in recs.items():
        if "__sweep__elastic_plastic_" not in name:
            continue
        hard = float(name.split("_")[-1].removesuffix("GPa")) * 1e9
        el = recs[name.split("__")[0] + "__sweep__elastic"]["rows"]
        expect = 0
        for b in range(0, len(el["peak_load_N"]), m):
            if el["punch_diameter_m"][b] in p.indentation.refine_punches:
                continue  # refined punches solve every cycle (reuse needs refine_max = 1)
            k = 0
            while k < m and el["max_pressure_Pa"][b + k] < hard and el["converged"][b + k]:
                assert (
                    rec["rows"]["unloading_stiffness_N_per_m"][b + k]
                    == el["unloading_stiffness_N_per_m"][b + k]
                )
                k += 1
            expect += k
        assert rec["reused_elastic_cycles"] == expect
        assert all(v <= hard * (1 + 1e-6) for v in rec["rows"]["max_pressure_Pa"])


def test_tracking_rule_on_hand_made_ratios():
    from warptrunc.reproduce.indentation.analysis import tracking

    d1, d2 = 5e-5, 1e-4
    ratios = {
        # elastic: in the band at the two smallest loads of d1 and the middle one of d2
        "elastic": {
            (d1, 1.0): 1.1,
            (d1, 2.0): 0.85,
            (d1, 4.0): 1.5,
            (d2, 1.0): 2.0,
            (d2, 2.0): 1.19,
            (d2, 4.0): 0.7,
        },
        # plastic: in the band at one cell only, nearer to 1 there than elastic
        "plastic": {
            (d1, 1.0): 0.3,
            (d1, 2.0): 0.5,
            (d1, 4.0): 1.01,
            (d2, 1.0): 0.1,
            (d2, 2.0): 0.2,
            (d2, 4.0): None,
        },
    }
    t = tracking(ratios, good=0.2)
    e, p = t["per_model"]["elastic"], t["per_model"]["plastic"]
    assert (e["n_cells"], e["n_good"], p["n_cells"], p["n_good"]) == (6, 3, 5, 1)
    assert e["runs"] == [[d1, 1.0, 2.0, 2], [d2, 2.0, 2.0, 1]]
    assert p["runs"] == [[d1, 4.0, 4.0, 1]]
    assert t["tracked"] == "elastic"  # 3/6 > 1/5
    # nearest model per cell: |ln r| smallest; (d1, 4.0) → plastic, (d2, 4.0) → elastic only
    assert t["closest"] == {"elastic": 5, "plastic": 1}
    assert e["median_ratio"] == pytest.approx(np.median([1.1, 0.85, 1.5, 2.0, 1.19, 0.7]))
    # the band's edge is inside; nothing in the band → None
    assert tracking({"m": {(d1, 1.0): 1.2}}, good=0.2)["per_model"]["m"]["n_good"] == 1
    assert tracking({"m": {(d1, 1.0): 1.3}}, good=0.2)["tracked"] is None


def _small_stage():
    from warptrunc.reproduce import get_profile

    st = get_profile("tiny").indentation
    return st.replace(
        surfaces=("GB300s", "GB50s"),
        hardness=(math.inf, 1e9),
        stats=("elastic",),
        refine=False,
        face_surface=None,
        protocol=st.protocol.replace(punch_diameters=(108.7e-6,), peak_loads=(0.125, 0.25)),
    )


def _small_profile():
    from dataclasses import replace

    from warptrunc.reproduce import get_profile

    return replace(get_profile("tiny"), name="indent-test", indentation=_small_stage())


def test_indentation_stage_resumes_after_interruption(tmp_path):
    """A time budget stops the stage between pieces; the rerun computes only what is missing and
    gives the stage an uninterrupted run gives."""
    from warptrunc.reproduce.indentation import StageIncomplete, stage_indentation

    p = _small_stage()
    full = stage_indentation(p, tmp_path / "a", "cpu", progress=False)
    with pytest.raises(StageIncomplete, match="0 of 6 planned pieces"):
        stage_indentation(p, tmp_path / "b", "cpu", deadline=0.0, progress=False)
    # interrupted after two pieces: keep two of the uninterrupted run's pieces, drop the others
    (tmp_path / "b" / "indentation").mkdir(parents=True, exist_ok=True)
    files = sorted((tmp_path / "a" / "indentation").glob("*.json"))
    kept = [f for f in files if f.name.startswith("GB300s")]
    for f in kept:
        (tmp_path / "b" / "indentation" / f.name).write_text(f.read_text())
    before = {f.name: (tmp_path / "b" / "indentation" / f.name).stat().st_mtime_ns for f in kept}
    again = stage_indentation(p, tmp_path / "b", "cpu", progress=False)
    for name, t in before.items():  # reused, not rewritten
        assert (tmp_path / "b" / "indentation" / name).stat().st_mtime_ns == t
    assert len(list((tmp_path / "b" / "indentation").glob("*.json"))) == 6
    assert _nan_eq(again["rows"], full["rows"])
    # a piece stored with other parameters is refused, or replaced with overwrite
    q = p.replace(protocol=p.protocol.replace(peak_loads=(0.125, 0.3)))
    with pytest.raises(StageConflict, match="other parameters"):
        stage_indentation(q, tmp_path / "b", "cpu", progress=False)


def test_reproduce_stages_and_time_budget(tmp_path):
    """--stages runs one stage; a time budget leaves it incomplete (reported, not stored) and a
    rerun finishes it."""
    p = _small_profile()
    doc = reproduce(p, tmp_path, device="cpu", stages="indentation", time_budget=1e-9)
    assert "indentation" in doc["meta"]["incomplete"] and "indentation" not in doc["stages"]
    assert doc["meta"]["stages_selected"] == ["indentation"]
    assert "asperity" in doc["meta"]["stages_skipped"]
    assert "## Stage `indentation`: incomplete" in (tmp_path / "report.md").read_text()
    assert not (tmp_path / "stages" / "indentation.json").exists()
    doc = reproduce(p, tmp_path, device="cpu", stages=["indentation"])
    assert doc["meta"]["computed"] == ["indentation"] and "incomplete" not in doc["meta"]
    assert set(doc["stages"]) == {"indentation"}
    assert "## Indentation in silico (Fig. 6)" in (tmp_path / "report.md").read_text()
    with pytest.raises(ValueError, match="stages must be names among"):
        reproduce(p, tmp_path, device="cpu", stages="fig6")
    from warptrunc.reproduce.study import select_stages

    assert select_stages("islands") == ("table1", "islands")


def test_fig6_model_colours_are_distinct():
    """Truncation and every contact model get their own colour (the elastic–plastic ones once
    took truncation's red)."""
    from warptrunc.reproduce.indentation.report import model_colours

    models = [
        "truncation",
        "elastic",
        "elastic_plastic_0.5GPa",
        "elastic_plastic_1GPa",
        "elastic_plastic_2GPa",
        "elastic_plastic_4GPa",
        "elastic_plastic_8GPa",
    ]
    c = model_colours(models)
    assert set(c) == set(models) and len(set(c.values())) == len(models)
    assert c["truncation"] == "C3" and c["elastic"] == "C0"
