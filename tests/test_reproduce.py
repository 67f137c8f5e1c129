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
        a, f = storakers(d, R, MAT, m)
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
    assert set(res["stages"]) == {"asperity", "fig5", "table1", "islands", "group1", "group2"}
    assert res["analysis"]["asperity"]["pixel_bound_holds"]


def test_tiny_group1_beta_scaling(tiny):
    _, doc = tiny
    b = doc["analysis"]["table3_beta"]["default"]
    # β ∝ δ^−α when only R_t changes: the fitted exponent is −(mean α of group 1)
    assert b["ours"]["p"] == pytest.approx(b["minus_alpha"], abs=0.01)


def test_tiny_rerun_reuses_and_conflict(tiny):
    out, _ = tiny
    doc = reproduce("tiny", out, device="cpu")
    assert set(doc["meta"]["reused"]) == {"asperity", "fig5", "table1", "islands", "group1", "group2"}
    from dataclasses import replace

    from warptrunc.reproduce import get_profile

    with pytest.raises(StageConflict):
        reproduce(replace(get_profile("tiny"), seeds=1), out, device="cpu")
