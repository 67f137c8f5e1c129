# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The ``indentation`` stage of ``warptrunc reproduce`` against the paper's text: the H range consistent with the ≈ 5 µm depth, how deep truncation stays within
±20 % of each model, the statistics pieces and the report's tables — the rules on hand-made
tables against numpy, the stage on the ``tiny`` profile (CPU)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from warptrunc.reproduce import get_profile, reproduce
from warptrunc.reproduce.indentation.rules import (
    agreement_depth,
    depth_at_load,
    depth_match,
    hardness_range,
)

H = np.array([0.5, 1, 2, 4, 8]) * 1e9
DEPTH = (
    np.array([9.0, 6.5, 4.8, 3.1, 2.0]) * 1e-6
)  # decreasing with H, as a softer alloy sinks more
BAND = (4e-6, 6e-6)


def _interp_H(depth_at: float, h=H, d=DEPTH) -> float:
    """H where the log–log line through (H, depth) reaches ``depth_at`` (numpy, depths increasing)."""
    return float(np.exp(np.interp(np.log(depth_at), np.log(d)[::-1], np.log(h)[::-1])))


def test_hardness_range_against_numpy_interpolation():
    r = hardness_range(H, DEPTH, BAND)
    assert r["contiguous"] and len(r["intervals"]) == 1
    assert r["low"] == pytest.approx(_interp_H(6e-6), rel=1e-12)  # softer end: the deeper edge
    assert r["high"] == pytest.approx(_interp_H(4e-6), rel=1e-12)
    assert not r["open_below"] and not r["open_above"] and r["n_points"] == 5
    # the order of the points, inf and missing depths do not matter
    perm = [3, 0, 4, 1, 2]
    r2 = hardness_range([*H[perm], math.inf], [*DEPTH[perm], 1e-7], BAND)
    np.testing.assert_allclose(r2["intervals"], r["intervals"], rtol=1e-12)
    m = depth_match(H, DEPTH, 5e-6, BAND)
    assert m["H_target"] == pytest.approx(_interp_H(5e-6), rel=1e-12)
    # nearest sweep H in log H to the interpolated one (1.81 GPa here → 2 GPa)
    assert m["H_match"] == H[np.argmin(np.abs(np.log(H / m["H_target"])))] == 2e9


def test_hardness_range_at_the_sweep_end_and_nowhere():
    deep = DEPTH * 0.8  # 7.2, 5.2, 3.84, …: the band starts before the softest H
    r = hardness_range(H, deep, BAND)
    assert r["open_below"] is False and r["low"] == pytest.approx(_interp_H(6e-6, d=deep))
    shallow = np.array([5.5, 5.0, 4.6, 4.3, 4.1]) * 1e-6  # every point in the band
    r = hardness_range(H, shallow, BAND)
    assert r["open_below"] and r["open_above"]
    np.testing.assert_allclose(r["intervals"], [[H[0], H[-1]]], rtol=1e-12)
    m = depth_match(H, np.array([5.5, 5.4, 5.3, 5.2, 5.1]) * 1e-6, 5e-6, BAND)
    assert m["H_target"] is None and m["H_match"] == H[-1]  # not bracketed: nearest depth in band
    none = hardness_range(H, DEPTH * 1e-2, BAND)
    assert none["low"] is None and none["intervals"] == []
    assert depth_match(H, DEPTH * 1e-2, 5e-6, BAND)["H_match"] is None
    # a depth that does not fall monotonically: two intervals
    r = hardness_range(H, np.array([7.0, 5.0, 7.0, 5.0, 3.0]) * 1e-6, BAND)
    assert len(r["intervals"]) == 2 and not r["contiguous"]
    with pytest.raises(ValueError, match="band must be"):
        hardness_range(H, DEPTH, (6e-6, 4e-6))


def test_agreement_depth_on_a_hand_made_series():
    # ω (% R_t′) and E_c,trunc/E_c,model; walked by ω: 1 (1.05 in), 2 (0.90 in), 3 (1.15 in),
    # 4 (1.25 out) → agreement to 3 %, leaves at 4 %; the cells deeper than 4 do not count
    omega = [5.0, 1.0, 3.0, 2.0, 4.0, 6.0, 7.0]
    ratio = [0.7, 1.05, 1.15, 0.9, 1.25, 1.0, None]
    a = agreement_depth(omega, ratio, 0.2)
    assert (a["depth"], a["leaves_at"], a["n_in"], a["n_cells"]) == (3.0, 4.0, 3, 6)
    assert (a["shallowest"], a["deepest"]) == (1.0, 6.0)
    assert agreement_depth([1, 2], [1.3, 1.0])["depth"] is None  # the shallowest is outside
    every = agreement_depth([1, 2, 3], [1.2, 0.8, 1.0])  # the band's edges are inside
    assert every["depth"] == 3 and every["leaves_at"] is None


def test_face_verdict_rule():
    """A face explains the paper's divergence (10–15 % R_t′) when truncation leaves the band
    there with it and stays within beyond it with the aligned flat."""
    from warptrunc.reproduce.indentation.analysis import _verdict

    def walk(depth, leaves, n=5):
        return {"depth": depth, "leaves_at": leaves, "n_cells": n}

    aligned = walk(30.0, None)
    assert _verdict(walk(12.0, 14.0), aligned, 10, 15) == "explains"
    assert _verdict(walk(8.0, 11.0), aligned, 10, 15) == "explains"  # the bracket meets 10–15
    assert _verdict(walk(4.0, 6.0), aligned, 10, 15) == "too-early"
    assert _verdict(walk(25.0, 28.0), aligned, 10, 15) == "does-not-explain"
    assert _verdict(walk(12.0, 14.0), walk(11.0, 13.0), 10, 15) == "aligned-leaves"
    assert _verdict(walk(9.0, None), walk(9.0, None), 10, 15) == "undecided"
    assert _verdict(walk(None, None, 0), aligned, 10, 15) == "no-cells"


def test_depth_at_load_takes_the_deepest_punch():
    punch = [1e-4, 1e-4, 1e-4, 5e-5, 5e-5, 5e-5]
    load = [0.5, 0.5, 0.25, 0.5, 0.5, 0.5]
    depth = [2e-6, 4e-6, 9e-6, 5e-6, 7e-6, 99e-6]
    ok = [True, True, True, True, True, False]
    d = depth_at_load(punch, load, depth, ok, 0.5)
    assert d["per_punch"][1e-4] == {"median": 3e-6, "min": 2e-6, "max": 4e-6, "n": 2}
    assert d["deepest"] == {"punch_m": 5e-5, "median": 6e-6, "min": 5e-6, "max": 7e-6, "n": 2}


def test_paper_profile_design():
    """Every punch refined to the paper's pixel over at least two halvings, placements that
    never overlap (two per punch on 1 mm, refused otherwise) traded for six realisations, the H
    sweep from 0.2 GPa, tilts relative to the surface under each placement."""
    from warptrunc.indent import place_punches
    from warptrunc.reproduce.indentation.design import face_variants

    st = get_profile("paper").indentation
    assert {0.2e9, 0.5e9, 1e9, 2e9, 4e9, 8e9, math.inf} <= set(st.hardness)
    assert min(st.hardness) == 0.2e9
    assert (len(st.seeds), st.stats_placements, st.protocol.placements) == (6, 2, 2)
    assert st.stats == ("elastic", "depth-match")
    assert st.refine_punches is None and st.protocol.refine_max == 8
    assert st.pixel_size / st.protocol.refine_max == pytest.approx(1e-3 / 10240)  # 97.7 nm
    assert st.protocol.overlap == "error"
    for k, d in enumerate(st.protocol.punch_diameters):  # the placements of each punch apart
        _c, frac = place_punches((st.L, st.L), d, st.stats_placements, seed=(k, 0),
                                 overlap="error")  # fmt: skip
        assert np.all(frac == 0)
    labels = [f[0] for f in face_variants(st)]
    assert labels == ["tilt 0° local", "tilt 0.02° local", "tilt 0.05° local",
                      "tilt 0.1° local", "rough 0.05 µm rms"]  # fmt: skip
    assert st.depth_target == 5e-6 and st.depth_band == (4e-6, 6e-6)
    assert st.protocol.punch_diameters == (54.1e-6, 108.7e-6, 502.6e-6)
    assert st.protocol.peak_loads[-1] == 0.5 and len(st.protocol.peak_loads) == 10
    assert st.solver.dtype == "float32" and st.solver.maxiter == 1000


def test_bad_stage_fields_are_named():
    st = get_profile("tiny").indentation
    for kw, word in (
        ({"stats": ("plastic",)}, "stats must name"),
        ({"depth_band": (6e-6, 7e-6)}, "depth_band must bracket depth_target"),
        ({"depth_band": (6e-6, 4e-6)}, "depth_band needs LO < HI"),
        ({"hardness": (0.0,)}, r"hardness\[0\] must be in \(0, inf\] Pa"),
        ({"face_hardness": 3e9}, "face_hardness must be one of hardness"),
        ({"surfaces": ("SMATs",)}, "face_surface must be one of surfaces"),
        ({"surfaces": ("Nope",)}, r"surfaces\[0\] must be one of"),
        ({"protocol": st.protocol.replace(placements=None)}, "protocol needs"),
        ({"stats_placements": 0}, "stats_placements must be"),
    ):
        with pytest.raises(ValueError, match=word) as e:
            st.replace(**kw)
        assert "\n" not in str(e.value)


@pytest.fixture(scope="module")
def tiny_indent(tmp_path_factory):
    out = tmp_path_factory.mktemp("indent")
    return out, reproduce("tiny", out, device="cpu", stages="indentation")


def test_tiny_report_has_each_table(tiny_indent):
    out, doc = tiny_indent
    text = (out / "report.md").read_text()
    st = doc["stages"]["indentation"]
    for head in (
        "**Hardness as a question**",
        "| surface | punch | H = 0.5 GPa |",
        "H with the deepest placement in 4–6 µm",
        "| **every surface (largest)** |",
        "| surface | design | model | punch | α [95 %] | β [95 %] | loads | cells | indents |",
        "a power law in the load needs at least 3 loads of one punch",
        "**How deep truncation stays within ±20 % of each model**",
        "the paper (vs experiment)",
        "**Which model truncation tracks, on resolved cells.**",
        "**Resolution of the cells per load.**",
        "Largest refinement reached: ×1",  # 256² over 1 mm: W_c under 2 pixels, not refined
        "**The material is assumed, not the paper's**",
        "**Ps with a tilted or rough punch face**",
        "| tilt 0° local |",
        "| tilt 0.1° local |",
        "| rough 0.05 µm rms |",
        "| aligned smooth flat (the sweep) |",
    ):
        assert head in text, head
    for s in st["surfaces"]:  # the resolution table has every load of every surface
        for f in st["loads_N"]:
            assert f"| {s} | {f * 1e3:.4g} |" in text
    assert "the paper's aluminium alloy" not in text and "2–4×" not in text
    faces = doc["analysis"]["indentation"]["faces"]
    assert [f["label"] for f in faces] == ["tilt 0° local", "tilt 0.1° local", "rough 0.05 µm rms"]
    assert all(f["surface"] == "Ps" and f["model"] == "elastic_plastic_2GPa" for f in faces)
    assert [f["reference"] for f in faces] == ["the sweep's aligned flat", *["tilt 0° local"] * 2]


def _depth_table(st, s=None):
    """H → the largest threshold depth at the largest load over the placements of every punch
    (of surface ``s``, or of every surface), from the sweep's rows (numpy)."""
    r = {k: np.array(v, dtype=object) for k, v in st["rows"].items()}
    at = max(st["loads_N"])
    out = {}
    for m, h in st["hardness_Pa"].items():
        sel = (
            (r["design"] == "sweep")
            & (r["model"] == m)
            & (r["peak_load_N"] == at)
            & r["converged"].astype(bool)
        )
        if s is not None:
            sel &= r["surface"] == s
        if sel.any():
            out[math.inf if h is None else h] = float(
                r["threshold_depth_m"][sel].astype(float).max()
            )
    return out


def test_tiny_H_range_and_statistics_come_from_the_threshold_depths(tiny_indent):
    """The paper's ≈ 5 µm is its maximum over all tests: per H the largest threshold depth over
    every surface, punch and placement; its H range and the one H of the statistics of every
    surface come from those depths; per surface the deepest placement's."""
    _out, doc = tiny_indent
    st, ana = doc["stages"]["indentation"], doc["analysis"]["indentation"]
    band = tuple(st["depth_band_m"])
    everything = _depth_table(st)
    hs = sorted(h for h in everything if math.isfinite(h))
    dd = np.array([everything[h] for h in hs])
    allh = ana["hardness_all"]
    assert allh["hardness_Pa"] == hs and allh["max_depth_m"] == pytest.approx(list(dd), rel=1e-12)
    mono = np.all(np.diff(dd) < 0)
    if mono and dd[0] >= band[1] >= dd[-1]:
        assert allh["range"]["low"] == pytest.approx(_interp_H(band[1], np.array(hs), dd), rel=1e-9)
    h_match = allh["match"]["H_match"]
    want = {"elastic"} | (set() if h_match is None else {f"elastic_plastic_{h_match / 1e9:g}GPa"})
    for s in st["surfaces"]:
        stats = {t["model"] for t in st["timings"] if t["surface"] == s and t["design"] == "stats"}
        assert stats == want  # one H for every surface
        tab = _depth_table(st, s)
        v = ana["hardness"][s]
        assert max(x for x in v["depth_max_m"] if x is not None) <= max(tab[h] for h in hs) * (
            1 + 1e-12
        )
        assert v["elastic_depth_range_m"][1] <= tab[math.inf] * (1 + 1e-12)
        assert all(a <= b for a, b in zip(v["depth_min_m"], v["depth_max_m"], strict=True))
    r = st["rows"]
    for t, z in zip(r["threshold_depth_m"], r["displacement_m"], strict=True):
        if t is not None and z is not None and math.isfinite(t):  # never deeper than δ
            assert t <= z


def test_tiny_agreement_depth_by_hand(tiny_indent):
    """The agreement depth of every surface × design × model recomputed from the rows: ratios per
    indent, geometric mean per (punch, load) over resolved indents, walked by ω in % R_t′."""
    _out, doc = tiny_indent
    st, ana = doc["stages"]["indentation"], doc["analysis"]["indentation"]
    r = st["rows"]
    n = len(r["surface"])
    for a in ana["agreement"]:
        cells: dict = {}
        for i in range(n):
            if (r["surface"][i], r["design"][i], r["model"][i]) != (
                a["surface"],
                a["design"],
                a["model"],
            ):
                continue
            t, e = r["truncation_E_c_over_E"][i], r["E_c_over_E"][i]
            if r["in_fit"][i] and r["converged"][i] and t and e and t > 0 and e > 0:
                c = cells.setdefault((r["punch_diameter_m"][i], r["peak_load_N"][i]), ([], []))
                c[0].append(math.log(t / e))
                c[1].append(r["truncation_depth_m"][i] / st["Rt_m"][a["surface"]] * 100)
        walk = sorted((float(np.median(w)), math.exp(np.mean(lr))) for lr, w in cells.values())
        depth = leaves = None
        for w, q in walk:
            if abs(q - 1) <= 0.2:
                depth = w
                continue
            leaves = w
            break
        assert a["n_cells"] == len(walk)
        assert (a["depth"] is None) == (depth is None) and (a["leaves_at"] is None) == (
            leaves is None
        )
        if depth is not None:
            assert a["depth"] == pytest.approx(depth, rel=1e-9)
        if leaves is not None:
            assert a["leaves_at"] == pytest.approx(leaves, rel=1e-9)


def test_tiny_fits_are_per_punch_over_loads(tiny_indent):
    """Every fit is one punch's over at least three of its loads; the statistics' fits of a punch
    with two realisations have intervals from the hierarchical bootstrap; the sweep's (one
    indent per punch) none, and no pooled fit (agreement cannot be tested)."""
    _out, doc = tiny_indent
    ana = doc["analysis"]["indentation"]
    made = [(f, g) for f in ana["fits"] for g in f["per_punch"] if g["made"]]
    assert made and all(g["n_loads"] >= 3 for _f, g in made)
    not_made = [g for f in ana["fits"] for g in f["per_punch"] if not g["made"]]
    assert all("at least 3 loads" in g["reason"] for g in not_made)
    stats = [g for f, g in made if f["design"] == "stats"]
    assert stats and all(g["n_realisations"] == 2 and g["n_indents"] == 2 for g in stats)
    assert all(g["alpha_ci95"][0] <= g["alpha"] <= g["alpha_ci95"][1] for g in stats)
    sweep = [(f, g) for f, g in made if f["design"] == "sweep"]
    assert sweep and all(g["alpha_ci95"][0] is None for _f, g in sweep)  # NaN in JSON
    assert all(not f["pooled"]["made"] for f, _g in sweep)


def test_statistics_piece_resumes(tmp_path):
    """A stats piece lost is computed again alone; the others are reused, not rewritten."""
    from warptrunc.reproduce.indentation import stage_indentation

    p = get_profile("tiny").indentation.replace(
        surfaces=("GB300s",), refine=False, face_surface=None
    )
    a = stage_indentation(p, tmp_path, "cpu", progress=False)
    files = sorted((tmp_path / "indentation").glob("*.json"))
    lost = next(f for f in files if "__stats__elastic_plastic" in f.name)
    before = {f.name: f.stat().st_mtime_ns for f in files if f != lost}
    lost.unlink()
    b = stage_indentation(p, tmp_path, "cpu", progress=False)
    assert lost.exists()
    for f in files:
        if f != lost:
            assert f.stat().st_mtime_ns == before[f.name]
    assert json.dumps(a["rows"]) == json.dumps(b["rows"])


def test_loads_the_cap_cannot_carry_are_flagged_rows_not_solved():
    """A part at soft H: the loads at or above 0.99·H·A of its punch are rows flagged
    bulk_yield, not converged, not in_fit, with their load and F/(E·A) and no measured value,
    in load order within each placement."""
    from warptrunc.reproduce.indentation.pieces import COLUMNS, bulk_yield_rows

    rows = {c: [None] * 4 for c in COLUMNS}
    rows.update(
        punch_diameter_m=[5e-5] * 4, placement=[0, 0, 1, 1], realisation=[0] * 4,
        peak_load_N=[0.1, 0.2, 0.1, 0.2], F_over_EA=[1.0, 2.0, 1.0, 2.0],
        mean_pressure_Pa=[1e7, 2e7, 1e7, 2e7], converged=[True] * 4, bulk_yield=[False] * 4,
        in_fit=[True] * 4, displacement_m=[1e-6, 2e-6, 1.5e-6, 2.5e-6],
    )  # fmt: skip
    out = bulk_yield_rows(rows, (0.1, 0.2, 0.4), (0.1, 0.2))
    assert out["peak_load_N"] == [0.1, 0.2, 0.4, 0.1, 0.2, 0.4]
    assert out["placement"] == [0, 0, 0, 1, 1, 1]
    assert out["bulk_yield"] == [False, False, True, False, False, True]
    assert out["converged"] == [True, True, False, True, True, False]
    assert out["in_fit"] == [True, True, False, True, True, False]
    assert out["displacement_m"] == [1e-6, 2e-6, None, 1.5e-6, 2.5e-6, None]
    assert out["F_over_EA"][2] == pytest.approx(4.0) and out["mean_pressure_Pa"][5] == 4e7
