# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Fits over loads, one punch at a time, and intervals over independent surfaces
(``warptrunc.indent.fits``).

References independent of the code under test: synthetic power laws with a known exponent per
punch and a known spread between realisations and between placements; the least-squares line
by ``numpy.polyfit``; the intervals' widths compared between the hierarchical and the flat
bootstrap on the same cells.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from warptrunc.indent.fits import (
    MIN_LOADS,
    agree_within_intervals,
    bootstrap_power_law,
    fit_model,
)
from warptrunc.material import Material

MAT = Material.against_diamond()
LOADS = 0.5 / 2 ** np.arange(6)[::-1]  # N


def _cells(punches=(54.1e-6, 108.7e-6), alpha=(0.45, 0.45), loads=LOADS, n_real=3, n_place=4,
           real_sd=0.0, place_sd=0.03, seed=0):  # fmt: skip
    """Cells E_c/E = β·x^α_d per punch d, x = F/(E·A): α of each indent drawn around α_d with a
    realisation effect (sd ``real_sd``, shared by the punches of one realisation) and a
    placement effect (sd ``place_sd``), 1 % noise per cell."""
    rng = np.random.default_rng(seed)
    out = {k: [] for k in ("x", "y", "depth", "load", "punch", "realisation", "placement")}
    for r in range(n_real):
        a_r = real_sd * rng.standard_normal()
        for d, a_d in zip(punches, alpha, strict=True):
            area = math.pi * d * d / 4
            for p in range(n_place):
                a = a_d + a_r + place_sd * rng.standard_normal()
                for f in loads:
                    x = f / (MAT.E * area)
                    out["x"].append(x)
                    out["y"].append(2.0 * x**a * math.exp(0.01 * rng.standard_normal()))
                    out["depth"].append(1e-6)
                    out["load"].append(f)
                    out["punch"].append(d)
                    out["realisation"].append(r)
                    out["placement"].append(p)
    return {k: np.asarray(v) for k, v in out.items()}


def test_a_fit_over_two_loads_is_refused_with_the_reason():
    c = _cells(punches=(54.1e-6,), alpha=(0.45,), loads=LOADS[-2:])
    mf = fit_model(c, MAT)
    (d,) = mf.per_punch
    assert mf.per_punch[d] is None and mf.n_loads[d] == 2 < MIN_LOADS
    why = mf.reasons[f"{d:.6g}"]
    assert "2 distinct peak load(s)" in why and "at least 3" in why and "250, 500 mN" in why
    doc = mf.to_dict()
    assert doc["per_punch"][0] == {
        "made": False, "punch_diameter_m": d, "n_loads": 2, "reason": why,
    }  # fmt: skip
    assert doc["pooled"]["made"] is False
    # three loads of the same punch: made
    assert (
        fit_model(_cells(punches=(54.1e-6,), alpha=(0.45,), loads=LOADS[-3:]), MAT).per_punch[d]
        is not None
    )


def test_one_load_over_several_punches_is_refused_with_the_reason():
    """The paper profile's grit-blasted 'fits': one (or two) loads on each of several punches.
    No per-punch fit; the pooled one is refused because a slope across punch sizes at one load
    measures K against the punch, not the load."""
    c = _cells(punches=(54.1e-6, 108.7e-6, 502.6e-6), alpha=(0.45,) * 3, loads=LOADS[-1:])
    mf = fit_model(c, MAT)
    assert all(f is None for f in mf.per_punch.values())
    assert all(n == 1 for n in mf.n_loads.values())
    assert mf.pooled is None
    assert "one peak load" in mf.reasons["pooled"] and "punch" in mf.reasons["pooled"]
    for d in mf.per_punch:
        assert "1 distinct peak load(s)" in mf.reasons[f"{d:.6g}"]


def test_per_punch_fits_are_the_least_squares_lines_of_their_own_cells():
    c = _cells(alpha=(0.40, 0.50), place_sd=0.0)
    mf = fit_model(c, MAT)
    for d, a_d in zip((54.1e-6, 108.7e-6), (0.40, 0.50), strict=True):
        f = mf.per_punch[d]
        on = c["punch"] == d
        alpha, logb = np.polyfit(np.log(c["x"][on]), np.log(c["y"][on]), 1)
        assert f.alpha == pytest.approx(alpha, rel=1e-9) and abs(f.alpha - a_d) < 0.01
        assert f.beta == pytest.approx(math.exp(logb), rel=1e-9)
        assert f.n_loads == mf.n_loads[d] == len(LOADS) and f.n_points == on.sum()
        assert f.n_indents == 3 * 4 and f.n_realisations == 3 and f.punch_diameter == d
    # the two punches' exponents differ far beyond their intervals: no pooled fit
    assert mf.agreement["agree"] is False and mf.pooled is None
    assert "no value in common" in mf.reasons["pooled"]


def test_the_pooled_fit_is_given_beside_per_punch_fits_that_agree():
    c = _cells(alpha=(0.45, 0.45))
    mf = fit_model(c, MAT)
    ivs = [tuple(f.alpha_ci95) for f in mf.per_punch.values()]
    assert agree_within_intervals(ivs) and mf.agreement["agree"] is True
    p = mf.pooled
    assert p is not None and p.punch_diameter is None
    assert p.punch_diameters == (54.1e-6, 108.7e-6) and p.n_points == c["x"].size
    alpha, _ = np.polyfit(np.log(c["x"]), np.log(c["y"]), 1)
    assert p.alpha == pytest.approx(alpha, rel=1e-9)
    doc = mf.to_dict()
    assert [r["n_loads"] for r in doc["per_punch"]] == [6, 6]
    assert doc["pooled"]["made"] and doc["agreement"]["test"].startswith("the per-punch 95 %")


def test_agreement_is_a_common_value_of_the_intervals():
    assert agree_within_intervals([(0.40, 0.46), (0.45, 0.50), (0.44, 0.47)])
    assert not agree_within_intervals([(0.40, 0.44), (0.45, 0.50)])
    assert not agree_within_intervals([(0.40, math.nan), (0.41, 0.50)])  # no interval: no test
    assert agree_within_intervals([(0.40, 0.45), (0.45, 0.50)])  # touching ends share 0.45


def test_hierarchical_interval_is_wider_with_a_realisation_effect_and_equal_without():
    """Placements on one realisation share its long waves (here: its exponent shift). With a
    realisation effect (sd 0.05 against 0.02 between placements) the hierarchical interval is
    much wider than the flat one over indents; without one it has the flat one's width within
    the Monte-Carlo spread of 2000 replicates and the shrinkage's sampling (20 %); on one
    realisation it is the flat bootstrap itself."""
    kw = dict(punches=(54.1e-6,), alpha=(0.45,), n_real=8, n_place=6, place_sd=0.02)

    def widths(c):
        one = np.zeros(c["x"].size)
        ind = np.stack([c["realisation"], c["placement"]], 1)
        h = bootstrap_power_law(c["x"], c["y"], ind, one, c["realisation"], seed=3)
        f = bootstrap_power_law(c["x"], c["y"], ind, one, seed=3)
        return np.diff(h["alpha_ci95"])[0], np.diff(f["alpha_ci95"])[0], h

    wh, wf, h = widths(_cells(real_sd=0.05, seed=1, **kw))
    assert h["hierarchical"] and h["n_realisations"] == 8
    assert wh > 1.5 * wf
    for seed in (1, 2):
        wh, wf, h = widths(_cells(real_sd=0.0, seed=seed, **kw))
        assert 0.8 < wh / wf < 1.2, (seed, wh / wf, h["shrink"])
    c = _cells(real_sd=0.05, seed=1, **{**kw, "n_real": 1})
    ind = np.stack([c["realisation"], c["placement"]], 1)
    one = np.zeros(c["x"].size)
    a = bootstrap_power_law(c["x"], c["y"], ind, one, c["realisation"], seed=3)
    b = bootstrap_power_law(c["x"], c["y"], ind, one, seed=3)
    assert not a["hierarchical"] and a["alpha_ci95"] == b["alpha_ci95"]


def test_the_realisation_level_is_shrunk_to_its_variance_component():
    """Identical realisations (the same placements on each): no realisation effect at all, the
    shrinkage factor c is 0; a realisation effect much larger than the placements' gives c
    near √(n/(n − 1)) (the bias correction of a between-group variance)."""
    c = _cells(punches=(54.1e-6,), alpha=(0.45,), n_real=1, n_place=6, seed=4)
    copies = {k: np.tile(v, 4) for k, v in c.items()}
    copies["realisation"] = np.repeat(np.arange(4), c["x"].size)
    ind = np.stack([copies["realisation"], copies["placement"]], 1)
    one = np.zeros(copies["x"].size)
    b = bootstrap_power_law(copies["x"], copies["y"], ind, one, copies["realisation"])
    assert b["shrink"] == {0.0: 0.0}
    big = _cells(punches=(54.1e-6,), alpha=(0.45,), n_real=6, n_place=4, real_sd=0.2,
                 place_sd=0.002, seed=5)  # fmt: skip
    ind = np.stack([big["realisation"], big["placement"]], 1)
    b = bootstrap_power_law(big["x"], big["y"], ind, np.zeros(big["x"].size), big["realisation"])
    assert b["shrink"][0.0] == pytest.approx(math.sqrt(6 / 5), rel=0.01)


def test_the_interval_spans_both_cell_rules():
    """A second rule that drops the light loads of one punch (their contact area unconverged)
    moves α: the reported interval holds both rules' intervals and estimates."""
    c = _cells(punches=(54.1e-6,), alpha=(0.45,), place_sd=0.01)
    bend = c["load"] >= LOADS[2]
    c["y"] = np.where(bend, c["y"] * (c["load"] / LOADS[2]) ** 0.05, c["y"])  # α steeper there
    c["rules"] = {"stiffness": np.ones(c["x"].size, bool), "stiffness_and_area": bend}
    f = fit_model(c, MAT).per_punch[54.1e-6]
    k, ka = f.rules["stiffness"], f.rules["stiffness_and_area"]
    assert k["made"] and ka["made"] and ka["n_loads"] == 4
    assert f.rule_shift == pytest.approx(abs(k["alpha"] - ka["alpha"])) and f.rule_shift > 0.01
    lo, hi = f.alpha_ci95
    for r in (k, ka):
        assert lo <= r["alpha_ci95"][0] and r["alpha_ci95"][1] <= hi
        assert lo <= r["alpha"] <= hi
    assert list(f.alpha_ci95) != k["alpha_ci95"]  # wider than the one rule's own
    # a second rule with two loads left: its systematic is not assessed, said so
    c["rules"]["stiffness_and_area"] = c["load"] >= LOADS[-2]
    f = fit_model(c, MAT).per_punch[54.1e-6]
    assert not f.rules["stiffness_and_area"]["made"]
    assert "not assessed" in f.rules["stiffness_and_area"]["reason"]
    assert list(f.alpha_ci95) == f.rules["stiffness"]["alpha_ci95"]


def test_every_punch_of_the_run_is_listed():
    c = _cells(punches=(54.1e-6,), alpha=(0.45,))
    mf = fit_model(c, MAT, punches=(54.1e-6, 502.6e-6))
    assert mf.n_loads == {54.1e-6: 6, 502.6e-6: 0}
    assert mf.per_punch[502.6e-6] is None and "0 distinct" in mf.reasons["0.0005026"]
