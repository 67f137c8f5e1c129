# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Cells that converge in the pixel size and fits with intervals (issue 38, items 1 and 2).

References independent of the code under test: the WM sum of Eq. 4 written again in NumPy
float64 from the seed (phases by ``default_rng(seed)`` in (m, n) order), with the height scale
taken from the coarse map's own pixels; punch windows built from those heights by
:func:`punch_window` and solved on their own; pixel counts and flags recomputed from the
columns; synthetic power laws with a known spread between indents for the bootstrap.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import warptrunc
from warptrunc.indent import IndentProtocol, indent, punch_window, run_cycles
from warptrunc.indent.fits import MIN_FIT_POINTS, bootstrap_power_law
from warptrunc.indent.refine import WindowSource
from warptrunc.material import Material
from warptrunc.wm import wm_window

D, WR, M, GAMMA = 2.5, 100e-6, 10, 1.5


def _wm(n=64, L=0.5e-3, Rt=2e-6, seed=1, **kw):
    return warptrunc.wm_surface(D, WR, L=L, n=n, Rt=Rt, seed=seed, device="cpu", **kw)


def _eq4(x, y, s):
    """The raw WM sum S(x, y) of Eq. 4 (without its prefactor), NumPy float64, from the seed
    and the map's cut-off: S = Σ_mn γ^((D−3)n)·[cos α_mn − cos(2πγⁿ(x cos θ_m + y sin θ_m)/W_r
    + α_mn)], θ_m = πm/M."""
    n_f = math.floor(math.log(WR / s.params["Wc"]) / math.log(GAMMA) + 1e-9) + 1
    alpha = np.random.default_rng(s.params["seed"]).uniform(0.0, 2 * math.pi, size=(M, n_f))
    out = np.zeros(np.broadcast(x, y).shape)
    for m in range(1, M + 1):
        th = math.pi * m / M
        for n in range(n_f):
            k, a = 2 * math.pi * GAMMA**n / WR, alpha[m - 1, n]
            out += GAMMA ** ((D - 3) * n) * (
                math.cos(a) - np.cos(k * (x * math.cos(th) + y * math.sin(th)) + a)
            )
    return out


def _scale(s):
    """Metres per unit of S, from the coarse map's own pixels (sample (i, j) at (j·dx, i·dy))."""
    z = np.asarray(s.heights, np.float64)
    yy, xx = np.mgrid[0 : s.ny, 0 : s.nx]
    raw = _eq4(xx * s.dx, yy * s.dy, s)
    scale = float(np.ptp(z) / np.ptp(raw))
    np.testing.assert_allclose(z, scale * raw, rtol=0, atol=2e-6 * np.ptp(z))  # the map is Eq. 4
    return scale


# --- item 1: the same surface at a finer pixel --------------------------------------------------


@pytest.mark.parametrize("factor", [2, 4])
def test_wm_window_at_a_finer_pixel_is_the_same_surface(factor):
    """A window generated again at p/2 (p/4) equals the coarse map wherever the samples
    coincide (every factor-th one, float32 round-off), and everywhere else Eq. 4 at the finer
    points times the coarse map's height scale: same content, scale frozen, not R_t again."""
    s = _wm()
    z = np.asarray(s.heights, np.float64)
    scale = _scale(s)
    (iy, ix), (wy, wx) = (10, 5), (20, 30)
    fine = wm_window(
        s.params, (factor * iy, factor * ix), (factor * wy, factor * wx), factor, device="cpu"
    ).astype(np.float64)
    tol = 2e-6 * np.ptp(z)  # float32 heights and float32 products of float32 tables
    np.testing.assert_allclose(
        fine[::factor, ::factor], z[iy : iy + wy, ix : ix + wx], rtol=0, atol=tol
    )
    fy, fx = np.mgrid[0 : factor * wy, 0 : factor * wx]
    ref = scale * _eq4((factor * ix + fx) * s.dx / factor, (factor * iy + fy) * s.dy / factor, s)
    np.testing.assert_allclose(fine, ref, rtol=0, atol=tol)
    off = np.ones(fine.shape, bool)
    off[::factor, ::factor] = False
    assert np.abs(fine[off] - fine[off].mean()).max() > 100 * tol  # new samples, not copies


def test_only_a_wm_map_of_its_parameters_is_refined():
    s = _wm()
    z = np.asarray(s.heights)
    assert WindowSource(z, (s.dx, s.dy), s.params).refinable
    assert WindowSource(z, (s.dx, s.dy), None).why_not == "read-map"
    assert WindowSource(z + 1e-7, (s.dx, s.dy), s.params).why_not == "read-map"  # edited
    assert WindowSource(z, (2 * s.dx, s.dy), s.params).why_not == "read-map"  # another pixel
    aliased = _wm(cutoff="pixel")  # W_c = one pixel: the coarse map aliases its finest terms
    assert WindowSource(aliased.heights, (s.dx, s.dy), aliased.params).why_not == "aliased"


def _independent_cell(s, scale, centre, d, load, pixel, material):
    """The cell solved on its own at ``pixel``: heights from Eq. 4 in NumPy on a local map of
    the punch's neighbourhood (samples at multiples of the pixel, as the refined map's), the
    window by punch_window, the cycle by run_cycles."""
    cx, cy = centre
    i0x, i0y = (max(0, math.floor((c - d / 2) / pixel) - 2) for c in (cx, cy))
    n = math.ceil(d / pixel) + 6
    jy, jx = np.mgrid[0:n, 0:n]
    z = scale * _eq4((i0x + jx) * pixel, (i0y + jy) * pixel, s)
    w = punch_window(z.astype(np.float32), pixel, d, (cx - i0x * pixel, cy - i0y * pixel))
    r = run_cycles(w, IndentProtocol(peak_loads=[load]), material, device="cpu")
    assert r["converged"][0]
    return r["unloading_stiffness"][0], r["contact_area"][0], w.n_pixels


def _richardson_by_hand(k0, k1, k2):
    """The documented rule written again: r = d2/d1; monotone (0 < r < 1): r' = max(r, 1/4),
    K∞ = k2 + d2·r'/(1 − r'); else K∞ = k2 and the error max(|d1|, |d2|)."""
    d1, d2 = k1 - k0, k2 - k1
    r = d2 / d1 if d1 else math.inf
    if 0 < r < 1:
        rr = max(r, 0.25)
        return k2 + d2 * rr / (1 - rr), abs(d2 * rr / (1 - rr))
    return k2, max(abs(d1), abs(d2))


def test_a_resolved_cell_is_converged_in_K_over_two_halvings():
    """Cells flagged resolved at pixel p: solved independently at 4p, 2p and p, K at p is the
    one reported, Richardson's error estimate from those three K is the one reported and within
    the tolerance of the extrapolated K, and one more halving (p/2, solved independently) lands
    within the tolerance of the extrapolation. The contact area is reported with its error,
    not judged by it."""
    s = _wm()
    mat = Material.against_diamond(hardness=0.05e9)  # soft: large plastic contacts
    tol = 0.02
    at = IndentProtocol(
        punch_diameters=(0.15e-3,),
        peak_loads=(16e-3, 64e-3),
        placements=2,
        refine_max=8,
        min_contact_pixels=50,
        resolution_tol=tol,
        elastic=False,
    )
    r = indent(s, protocol=at, material=mat, device="cpu")
    d = r.to_dict()
    done = np.flatnonzero(d["resolved"])
    assert done.size >= 1
    scale = _scale(s)
    for i in done:
        p = d["pixel_size_m"][i]
        assert p <= s.dx / 4 and d["resolution_note"][i] == "resolved"  # two halvings at least
        c, load = (d["centre_x_m"][i], d["centre_y_m"][i]), d["peak_load_N"][i]
        k, a, n_disk = _independent_cell(s, scale, c, 0.15e-3, load, p, mat)
        assert n_disk == d["n_punch_pixels"][i]
        np.testing.assert_allclose(d["unloading_stiffness_N_per_m"][i], k, rtol=1e-4)
        np.testing.assert_allclose(d["contact_area_m2"][i], a, rtol=1e-3)
        k2, a2, _ = _independent_cell(s, scale, c, 0.15e-3, load, 2 * p, mat)
        k4, a4, _ = _independent_cell(s, scale, c, 0.15e-3, load, 4 * p, mat)
        ext, err = _richardson_by_hand(k4, k2, k)
        np.testing.assert_allclose(d["stiffness_extrapolated_N_per_m"][i], ext, rtol=1e-3)
        np.testing.assert_allclose(d["stiffness_error_N_per_m"][i], err, rtol=0.05, atol=1e-4 * k)
        assert err <= tol * abs(ext) and d["n_contact_pixels"][i] >= 50
        a_ext, a_err = _richardson_by_hand(a4, a2, a)
        np.testing.assert_allclose(d["contact_area_error_m2"][i], a_err, rtol=0.05, atol=1e-3 * a)
        assert d["area_resolved"][i] == (a_err <= tol * abs(a_ext))
        kh, _ah, _ = _independent_cell(s, scale, c, 0.15e-3, load, p / 2, mat)
        assert abs(kh / ext - 1) < tol
    # every other cell ran to the finest pixel allowed, unresolved
    rest = np.setdiff1d(np.arange(d["peak_load_N"].size), done)
    assert np.all(d["pixel_size_m"][rest] == s.dx / 8)
    assert set(d["resolution_note"][rest]) <= {"refine-max"}


def test_one_halving_resolves_nothing():
    """refine_max = 2 gives one halving: K's convergence is not judged on one change, so no
    refined cell is resolved, whatever K did; the change and its estimate are reported."""
    s = _wm()
    at = IndentProtocol(punch_diameters=(0.15e-3,), peak_loads=(16e-3, 64e-3), placements=None,
                        refine_max=2, min_contact_pixels=1, elastic=False)  # fmt: skip
    d = indent(s, protocol=at, material=Material.against_diamond(hardness=0.05e9),
               device="cpu").to_dict()  # fmt: skip
    assert not d["resolved"].any() and set(d["resolution_note"]) == {"refine-max"}
    assert np.all(np.isfinite(d["resolution_change"])) and np.all(d["pixel_size_m"] == s.dx / 2)


def test_saturated_cells_are_never_in_fit():
    """Complete contact (every disk pixel touches) is flagged saturated and left out of the fits,
    resolved or not: a flat read map under a punch, and a nearly flat WM map refined."""
    flat = np.zeros((64, 64))
    at = IndentProtocol(
        punch_diameters=(60e-6,), peak_loads=(1e-3, 2e-3), placements=None, min_contact_pixels=1
    )
    r = indent(
        flat, protocol=at, pixel_size=2e-6, material=Material.against_diamond(), device="cpu"
    )
    d = r.to_dict()
    assert np.all(d["n_contact_pixels"] == d["n_punch_pixels"]) and d["saturated"].all()
    assert d["resolved"].all() and not d["in_fit"].any()  # resolved by the pixel rule alone
    assert set(d["resolution_note"]) == {"read-map"} and np.isnan(d["resolution_change"]).all()
    assert np.all(d["pixel_size_m"] == 2e-6)
    s = _wm(n=64, L=0.2e-3, Rt=1e-9)  # 24 pixels of radius: K within 1 % at p/2 and p/4
    at = IndentProtocol(
        punch_diameters=(0.15e-3,),
        peak_loads=(0.5, 1.0),
        placements=None,
        refine_max=4,
        min_contact_pixels=10,
    )
    r = indent(s, protocol=at, material=Material.against_diamond(), device="cpu")
    d = r.to_dict()
    np.testing.assert_array_equal(d["saturated"], d["n_contact_pixels"] >= d["n_punch_pixels"])
    assert d["saturated"].all() and d["resolved"].any()
    assert not d["in_fit"].any() and not d["elastic_in_fit"].any()
    assert all(not f["per_punch"][0]["made"] for f in r.fit_summary().values())


def test_cells_at_the_complete_contact_plateau_are_saturated():
    """A cell whose K is within resolution_tol of Sneddon's complete-contact stiffness 2E*a of
    the face is saturated (and out of the fits) even with a few face pixels free: a shallow
    dome under a flat punch approaches the plateau as the load rises."""
    n, dx, d = 64, 2e-6, 100e-6
    y, x = (np.mgrid[0:n, 0:n] - (n - 1) / 2) * dx
    dome = -(x**2 + y**2) / (2 * 0.5)  # R = 0.5 m: a rim 1.25 nm below the top at r = 50 µm
    mat = Material.against_diamond()
    at = IndentProtocol(
        punch_diameters=(d,),
        peak_loads=(1e-4, 2e-2, 2.4e-2, 1.0),
        placements=None,
        min_contact_pixels=1,
    )
    r = indent(dome, protocol=at, pixel_size=dx, material=mat, device="cpu")
    c = r.to_dict()
    k = c["unloading_stiffness_N_per_m"]
    plateau = mat.contact_modulus * d  # 2E*·a
    expected = (c["n_contact_pixels"] >= c["n_punch_pixels"]) | (k >= 0.98 * plateau)
    np.testing.assert_array_equal(c["saturated"], expected)
    assert not c["saturated"][0] and k[0] < 0.9 * plateau  # the first touch: far below it
    # 24 mN: 1968 of 1976 face pixels touch, K = 0.996·2E*a: saturated by the plateau rule
    by_plateau = c["saturated"] & (c["n_contact_pixels"] < c["n_punch_pixels"])
    assert by_plateau[2] and not c["saturated"][1], (c["n_contact_pixels"], k / plateau)
    assert not (c["in_fit"] & c["saturated"]).any()


# --- item 2: fits over the cells in_fit, with intervals over indents ----------------------------


@pytest.fixture(scope="module")
def two_surfaces():
    """Two realisations, three placements of two punches, four loads; judged by the pixel
    rule (refine_max = 1) with min_contact_pixels = 1, so every converged, unsaturated cell."""
    maps = [_wm(n=96, L=1.2e-3, Rt=4e-6, seed=k) for k in (3, 4)]
    at = IndentProtocol(punch_diameters=(0.1e-3, 0.2e-3), peak_loads=(2e-3, 8e-3, 32e-3, 128e-3),
                        placements=3, placement_seed=1, refine_max=1, min_contact_pixels=1,
                        elastic=False)  # fmt: skip
    return indent(maps, protocol=at, device="cpu")


def test_rows_of_several_realisations(two_surfaces):
    d = two_surfaces.to_dict()
    assert d["peak_load_N"].size == 2 * 2 * 3 * 4
    np.testing.assert_array_equal(d["realisation"], np.repeat([0, 1], 24))
    # the same punches and placements on each realisation, on other heights
    for k in ("punch_diameter_m", "placement", "centre_x_m", "centre_y_m", "peak_load_N"):
        np.testing.assert_array_equal(d[k][:24], d[k][24:], err_msg=k)
    assert not np.array_equal(d["E_c_over_E"][:24], d["E_c_over_E"][24:])
    with pytest.raises(ValueError, match="one size and pixel"):
        indent([_wm(n=64), _wm(n=96)], device="cpu")


def test_fits_per_punch_use_the_cells_in_fit_over_their_loads(two_surfaces):
    """Each punch's fit is the least-squares line through its cells in_fit only; n_points,
    n_loads and n_indents count them, their loads and their (realisation, placement); its 95 %
    intervals hold the fit; with fewer than three loads in_fit there is no fit, and the summary
    says why."""
    r = two_surfaces
    d = r.to_dict()
    use = d["in_fit"]
    np.testing.assert_array_equal(
        use,
        d["converged"]
        & (d["n_contact_pixels"] >= 1)
        & (d["n_contact_pixels"] < d["n_punch_pixels"]),
    )
    for name, col in (("elastic_plastic", "E_c_over_E"), ("truncation", "truncation_E_c_over_E")):
        doc = r.fit_summary()[name]
        for d0, fit in r.punch_fits()[name].items():
            on = use & (d["punch_diameter_m"] == d0)
            alpha, logb = np.polyfit(np.log(d["F_over_EA"][on]), np.log(d[col][on]), 1)
            assert fit.alpha == pytest.approx(alpha, rel=1e-9)
            assert fit.beta == pytest.approx(math.exp(logb), rel=1e-9)
            assert fit.n_points == on.sum() and fit.n_loads == 4
            assert fit.n_indents == 6 and fit.n_realisations == 2
            lo, hi = fit.alpha_ci95
            assert lo < fit.alpha < hi and hi - lo < 0.5
            lo, hi = fit.beta_ci95
            assert lo < fit.beta < hi
            (row,) = [x for x in doc["per_punch"] if x["punch_diameter_m"] == d0]
            assert row["made"] and row["alpha_ci95"] == list(fit.alpha_ci95)
            assert row["n_loads"] == 4 and row["n_indents"] == 6
    assert r.punch_fits()["elastic"][0.1e-3] is None  # not run (elastic=False): no cell in_fit
    # cells in_fit at two loads only: not made, and the summary says why
    few = dict(r.__dict__)
    few.pop("_model_fits", None)
    few["in_fit"] = use & (d["peak_load_N"] >= 32e-3)
    thin = type(r)(**few)
    assert thin.punch_fits()["elastic_plastic"][0.1e-3] is None
    row = thin.fit_summary()["elastic_plastic"]["per_punch"][0]
    assert not row["made"] and row["n_loads"] == 2 and "at least 3" in row["reason"]


def _indents(rng, n_ind, x):
    """Synthetic indents, each a power law of its own: α_i ~ N(0.5, 0.05), ln β_i ~ N(0, 0.1)
    between indents, 1 % noise within; cells (x, y) and their indent labels."""
    xs, ys, ind = [], [], []
    for i in range(n_ind):
        a_i, lb_i = 0.5 + 0.05 * rng.standard_normal(), 0.1 * rng.standard_normal()
        xs.append(x)
        ys.append(np.exp(lb_i + a_i * np.log(x) + 0.01 * rng.standard_normal(x.size)))
        ind.append(np.full(x.size, i))
    return np.concatenate(xs), np.concatenate(ys), np.concatenate(ind)


def test_intervals_narrow_with_more_indents():
    """The 95 % interval of α from resampling indents narrows about as 1/√n with the number of
    indents, and holds the α of the population in about 95 % of repeated experiments."""
    rng = np.random.default_rng(7)
    x = np.geomspace(1e-5, 1e-2, 6)
    widths = {}
    for n_ind in (4, 16, 64):  # the mean width over 20 experiments
        w = []
        for k in range(20):
            xx, yy, ii = _indents(rng, n_ind, x)
            b = bootstrap_power_law(xx, yy, ii, np.zeros(xx.size), n_boot=1000, seed=k)
            assert b["n_indents"] == n_ind and b["n_bootstrap"] == 1000
            w.append(b["alpha_ci95"][1] - b["alpha_ci95"][0])
        widths[n_ind] = np.mean(w)
    assert widths[4] > widths[16] > widths[64]
    assert 1.6 < widths[16] / widths[64] < 2.5  # ≈ 2 = √(64/16)
    # coverage over 200 experiments of 16 indents (a percentile bootstrap of 16 clusters
    # undercovers a little: ≈ 0.91 here)
    hits = 0
    for k in range(200):
        xx, yy, ii = _indents(rng, 16, x)
        lo, hi = bootstrap_power_law(xx, yy, ii, np.zeros(xx.size), n_boot=500, seed=k)[
            "alpha_ci95"
        ]
        hits += lo < 0.5 < hi
    assert 0.85 <= hits / 200 <= 0.99
    # one indent: nothing to resample, no interval (its loads are not independent)
    xx, yy, ii = _indents(rng, 1, x)
    assert np.isnan(bootstrap_power_law(xx, yy, ii, ii)["alpha_ci95"]).all()


def test_intervals_resample_within_each_punch():
    """Indents are drawn within their punch diameter: every replicate keeps each punch's number
    of indents. Two punches of three indents, one load each (one F/(E·A) per punch): a
    replicate of one punch's indents alone could not fit a line (drawn over all six indents,
    2·(1/2)⁶ ≈ 3 % of replicates would be), yet every replicate fits."""
    rng = np.random.default_rng(3)
    xa, ya, ia = _indents(rng, 3, np.array([1e-5]))
    xb, yb, ib = _indents(rng, 3, np.array([1e-3]))
    x, y = np.concatenate([xa, xb]), np.concatenate([ya, yb])
    ind, punch = np.concatenate([ia, ib + 3]), np.repeat([1.0, 2.0], 3)
    b = bootstrap_power_law(x, y, ind, punch, n_boot=1000, seed=0)
    assert b["n_bootstrap"] == 1000 and b["n_indents"] == 6


# --- the command line ---------------------------------------------------------------------------

NEW_COLUMNS = [
    "pixel_size_m",
    "n_contact_pixels",
    "resolution_change",
    "resolved",
    "saturated",
    "in_fit",
]


def test_cli_writes_the_resolution_columns_and_the_intervals(tmp_path, capsys):
    """Two realisations (--seeds), the cells judged by the pixel rule: indent.csv has the new
    columns, indent.json the fits with their intervals and counts, the figure is written."""
    import csv
    import json

    from warptrunc.cli import main

    out = tmp_path / "ind"
    argv = [
        "indent",
        "--n",
        "96",
        "--L",
        "1.2e-3",
        "--Rt",
        "4e-6",
        "--seeds",
        "3",
        "4",
        "--punch-diameters",
        "1e-4",
        "2e-4",
        "--peak-loads",
        "2e-3",
        "8e-3",
        "32e-3",
        "128e-3",
        "--placements",
        "3",
        "--placement-seed",
        "1",
        "--refine-max",
        "1",
        "--min-contact-pixels",
        "1",
        "--no-elastic",
        "--no-progress",
        "--out",
        str(out),
    ]
    assert main(argv) == 0
    with (out / "indent.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 48 and set(NEW_COLUMNS) <= set(rows[0])
    for r in rows:
        assert float(r["pixel_size_m"]) == pytest.approx(1.2e-3 / 96)
        assert r["in_fit"] == str(
            int(r["resolved"] == "1" and r["saturated"] == "0" and r["converged"] == "1")
        )
        assert r["resolution_change"] == "nan" and r["resolution_note"] == "not-refined"
    doc = json.loads((out / "indent.json").read_text())
    for fit in doc["fits"]["elastic_plastic"]["per_punch"]:
        assert fit["made"] and fit["n_indents"] == 6 and fit["n_loads"] == 4
        assert fit["n_realisations"] == 2 and fit["n_points"] >= MIN_FIT_POINTS
        assert fit["alpha_ci95"][0] < fit["alpha"] < fit["alpha_ci95"][1]
        assert fit["beta_ci95"][0] < fit["beta"] < fit["beta_ci95"][1]
    assert [f["n_loads"] for f in doc["fits"]["elastic"]["per_punch"]] == [0, 0]
    assert doc["resolution"]["n_cells"] == 48
    text = capsys.readouterr().out
    assert "(2 realisations)" in text and "α 95 % [" in text and "4 loads, 6 indents" in text
    assert (out / "indent.png").stat().st_size > 10_000


def test_default_map_holds_the_default_placements_apart(tmp_path, capsys):
    """A generated map is 1 mm per side at the preset's (or the defaults') pixel: the paper's
    three punches at the default two placements each never overlap, and the command does not
    warn."""
    from warptrunc.cli import build_parser, main
    from warptrunc.cli.indent import map_specs
    from warptrunc.indent import PAPER_PUNCH_DIAMETERS, IndentMaps, IndentProtocol, place_punches
    from warptrunc.presets import TABLE1

    parse = build_parser(["indent"]).parse_args
    (spec,) = map_specs(parse(["indent", "--preset", "GB300s"]))
    assert spec.L == 1e-3 and spec.n == 10240  # the preset's 97.7 nm pixel
    assert IndentMaps().specs(TABLE1["GB300s"]) == [spec]  # the library's default
    assert map_specs(parse(["indent"]))[0].n == 1024  # the defaults' 0.977 µm pixel
    (spec,) = map_specs(parse(["indent", "--preset", "GB300s", "--n", "512"]))
    assert spec.L == 1e-3 and spec.n == 512
    assert map_specs(parse(["indent", "--L", "1e-3"]))[0].L == 1e-3
    assert map_specs(parse(["indent", "--map-side", "2e-3", "--n", "64"]))[0].L == 2e-3
    specs = map_specs(parse(["indent", "--seeds", "0-2", "--n", "64"]))
    assert [s.seed for s in specs] == [0, 1, 2] and {s.n for s in specs} == {64}
    with pytest.raises(ValueError, match=r"--L and --map-side 0\.002 both"):
        map_specs(parse(["indent", "--L", "1e-3", "--map-side", "2e-3"]))
    p = IndentProtocol()
    for i, d in enumerate(PAPER_PUNCH_DIAMETERS):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            c, frac = place_punches((1e-3, 1e-3), d, p.placements, seed=(p.placement_seed, i))
        sep = np.hypot(*(c[:, None] - c[None]).transpose(2, 0, 1))[np.triu_indices(len(c), 1)]
        assert np.all(frac == 0) and sep.min() >= d
    out = tmp_path / "ind"
    assert (
        main(
            [
                "indent",
                "--n",
                "256",
                "--peak-loads",
                "0.5",
                "--refine-max",
                "1",
                "--no-elastic",
                "--no-plot",
                "--no-progress",
                "--out",
                str(out),
            ]
        )
        == 0
    )
    assert "warning" not in capsys.readouterr().err


# --- sub-windows: the contact and its interaction range ---------------------------------------


def _smooth_wm():
    """A WM map smooth at the punch's scale (D = 2.2, W_r = L): the light loads touch near
    one summit, so the pixels within the gap margin of contact fill a fraction of the disk."""
    return warptrunc.wm_surface(2.2, 0.5e-3, L=0.5e-3, n=128, Rt=2e-6, seed=1, device="cpu")


def test_a_refined_sub_window_gives_the_whole_refined_windows_K():
    """The same cells refined to p/4 on whole windows and, with max_window_pixels below the
    finer windows, on sub-windows that hold the contact: the same final pixels and K (on the
    free half-space the disk's pixels outside the contact carry no pressure, so the two
    problems have one solution: agreement to the solver's tolerance, far inside
    resolution_tol), the whole disk counted for saturation, truncation read on the finest whole
    window."""
    s = _smooth_wm()
    mat = Material.against_diamond(hardness=1e9)
    at = IndentProtocol(punch_diameters=(0.3e-3,), peak_loads=(1e-3, 4e-3, 16e-3),
                        placements=None, refine_max=4, min_contact_pixels=1)  # fmt: skip
    whole = indent(s, protocol=at, material=mat, device="cpu").to_dict()
    sub = indent(s, protocol=at.replace(max_window_pixels=30_000), material=mat,
                 device="cpu").to_dict()  # fmt: skip
    assert not whole["sub_window"].any() and sub["sub_window"].all()
    np.testing.assert_array_equal(sub["pixel_size_m"], whole["pixel_size_m"])
    assert np.all(whole["pixel_size_m"] == s.dx / 4)
    for col in ("unloading_stiffness_N_per_m", "elastic_unloading_stiffness_N_per_m",
                "contact_area_m2"):  # fmt: skip
        np.testing.assert_allclose(sub[col], whole[col], rtol=1e-6, err_msg=col)
    # the approach to the solves' tolerance (the default penetration tolerance scales with the
    # window's side)
    np.testing.assert_allclose(sub["displacement_m"], whole["displacement_m"], rtol=1e-4)
    np.testing.assert_array_equal(sub["n_punch_pixels"], whole["n_punch_pixels"])
    np.testing.assert_array_equal(sub["resolved"], whole["resolved"])
    # ×4 windows are 320² (> 30 000 pixels) but ×2 fit: truncation reads ×2 in the sub run
    np.testing.assert_allclose(sub["truncation_pixel_size_m"], s.dx / 2)
    np.testing.assert_allclose(whole["truncation_pixel_size_m"], s.dx / 4)


def test_a_sub_window_that_cuts_the_contact_is_grown():
    """A solve whose contact reaches within the guard of a sub-window's cut edge is not taken:
    the sub-window is grown (three times its size, clipped to the disk) and the cell solved
    again, until the contact lies inside; a contact that no sub-window within
    max_window_pixels holds gives up. The contact here is a fixed rectangle of the finer map,
    cut to each window (a stand-in for the solver)."""
    from warptrunc.indent.refine import SUB_WINDOW_GUARD, WindowSource, _Grow, _solve_checked

    s = _smooth_wm()
    src = WindowSource(np.asarray(s.heights), (s.dx, s.dy), s.params, device="cpu")
    d, c = 0.3e-3, (0.25e-3, 0.25e-3)
    w = src.window(d, c)
    bounds = src.disk_bounds(d, c, 2)
    contact = (bounds[0] + 60, bounds[1] + 60, bounds[0] + 80, bounds[1] + 90)  # fine pixels
    seen = []

    def solve(win, idx, factor, approach):
        oy, ox = win.origin
        ys, xs = np.nonzero(win.mask)
        y0, x0 = max(contact[0], oy + ys.min()), max(contact[1], ox + xs.min())
        y1, x1 = min(contact[2], oy + ys.max()), min(contact[3], ox + xs.max())
        seen.append(win.mask.shape)
        box = [[y0 - oy, x0 - ox, y1 - oy, x1 - ox]] * idx.size
        return {"displacement": np.zeros(idx.size), "contact_box": np.asarray(box)}

    start = src.window(d, c, 2, region=(contact[0] + 5, contact[1] + 5, contact[2] - 5,
                                        contact[3] - 5))  # fmt: skip
    cur = {"displacement": np.zeros(1)}
    top = np.full(1, w.top)
    new, got = _solve_checked(src, solve, start, np.arange(1), 2, top, cur, bounds, 10**6, w)
    assert len(seen) >= 2 and got.is_sub_window
    y0, x0, y1, x1 = (int(v) for v in new["contact_box"][0])
    oy, ox = got.origin
    assert (oy + y0, ox + x0, oy + y1, ox + x1) == contact  # the whole contact inside at last
    ys, xs = np.nonzero(got.mask)
    g = SUB_WINDOW_GUARD
    assert oy + ys.min() <= contact[0] - g and ox + xs.max() >= contact[3] + g
    with pytest.raises(_Grow):  # no sub-window within 1000 pixels holds it
        _solve_checked(src, solve, start, np.arange(1), 2, top, cur, bounds, 1000, w)
