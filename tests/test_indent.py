# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Flat-punch indentation in silico (``warptrunc.indent``, ``warptrunc indent``).

References independent of the code under test: the flat punch's K = 2E*a (Sneddon/Boussinesq);
disk membership, lens areas and truncated counts recomputed in NumPy; E_c = √π·K/(2√A)
recomputed from the columns; the paraboloid's truncated area 2πRδ; the elastic solver
(H = ∞) for H → ∞; and the truncated set {h ≥ h_max − δ} with F = H·A′ for H → 0. Small maps
(64²–256²) on the CPU.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from cli_helpers import INDENT_CLI, assert_refused_in_one_line

import warptrunc
from warptrunc.cli import main
from warptrunc.contact import ContactSolver
from warptrunc.indent import (
    IndentProtocol,
    PlacementOverlapWarning,
    disk_mask,
    disk_truncation,
    indent,
    lens_fraction,
    place_punches,
    punch_window,
    run_cycles,
    truncation_at_loads,
)
from warptrunc.material import Material
from warptrunc.params import add_options, from_args

MAT = Material.against_diamond()  # E* = 73.5 GPa


def _wm(n=64, L=0.5e-3, Rt=2e-6, seed=1):
    return warptrunc.wm_surface(2.5, 100e-6, L=L, n=n, Rt=Rt, seed=seed, device="cpu")


# --- the punch --------------------------------------------------------------------------------


@pytest.mark.parametrize("a_px", [25, 50, 100])
def test_flat_punch_stiffness_is_2_Estar_a(a_px):
    """A smooth face under the punch: K = 2E*a (both ways), within 1 % for a ≥ 100 pixels."""
    dx = 1e-6
    z = np.zeros((2 * a_px + 4, 2 * a_px + 4))
    w = punch_window(z, dx, 2 * a_px * dx)
    r = run_cycles(w, IndentProtocol(peak_loads=[1.0]), MAT, device="cpu")
    assert r["converged"].all()
    k_ref = 2 * MAT.contact_modulus * a_px * dx
    k = r["unloading_stiffness"][0]
    # elastic and linear: the secant of the partial unloading is the same stiffness
    np.testing.assert_allclose(r["partial_unloading_stiffness"][0], k, rtol=1e-4)
    if a_px >= 100:
        assert abs(k / k_ref - 1) < 0.01


def test_flat_punch_error_falls_as_dx_over_a():
    """Against the punch of the pixel disk's area, a_eff = √(N·dx²/π), the error is ~ c·dx/a:
    halving dx/a halves it (within 25 %), and it is below 0.2 % at a = 100 pixels."""
    dx = 1e-6
    err = {}
    for a_px in (25, 50, 100):
        z = np.zeros((2 * a_px + 2, 2 * a_px + 2))
        w = punch_window(z, dx, 2 * a_px * dx)
        k = run_cycles(w, IndentProtocol(peak_loads=[1.0]), MAT, device="cpu")
        k = k["unloading_stiffness"][0]
        a_eff = math.sqrt(w.n_pixels * dx * dx / math.pi)
        err[a_px] = abs(k / (2 * MAT.contact_modulus * a_eff) - 1)
    assert err[25] > err[50] > err[100]
    for a_px in (50, 100):
        np.testing.assert_allclose(err[a_px] / err[a_px // 2], 0.5, rtol=0.25)
    assert err[100] < 2e-3


def test_window_holds_exactly_the_disk_pixels():
    """The window's mask equals the disk test on every pixel centre of the whole map; pixels
    outside it sit at ``floor``, below the disk by the drop; the window is the disk's bounding
    box, grown at its far ends to the next 7-smooth sides (FFT lengths at full speed)."""
    rng = np.random.default_rng(3)
    z = rng.normal(size=(80, 70)) * 1e-6
    dx, dy = 1e-6, 1.3e-6
    centre, d = (33.3e-6, 41.7e-6), 47.5e-6
    w = punch_window(z, (dx, dy), d, centre)
    yy, xx = np.mgrid[0:80, 0:70]
    full = ((xx + 0.5) * dx - centre[0]) ** 2 + ((yy + 0.5) * dy - centre[1]) ** 2 <= (d / 2) ** 2
    iy0, ix0 = w.origin
    rows, cols = np.nonzero(full)
    by, bx = rows.max() + 1 - iy0, cols.max() + 1 - ix0  # the disk's bounding box
    assert (rows.min(), cols.min()) == (iy0, ix0)
    assert full.sum() == w.n_pixels
    np.testing.assert_array_equal(full[iy0 : iy0 + by, ix0 : ix0 + bx], w.mask[:by, :bx])
    assert not w.mask[by:, :].any() and not w.mask[:, bx:].any()

    def smooth(m):  # prime factors 2, 3, 5, 7 only, by trial division
        return all(m % p for p in range(11, m + 1) if all(p % q for q in range(2, p))) or m == 1

    for side, box in zip(w.mask.shape, (by, bx), strict=True):  # the next 7-smooth length
        assert side >= box and smooth(side) and not any(smooth(m) for m in range(box, side))
    np.testing.assert_array_equal(w.disk_heights, z[full])
    assert np.all(w.heights[~w.mask] == w.floor) and w.floor < z[full].min()
    np.testing.assert_array_equal(disk_mask(z.shape, (dx, dy), centre, d), full)
    assert w.area == pytest.approx(math.pi * d * d / 4)


def test_punch_larger_than_the_map_is_refused():
    with pytest.raises(ValueError, match=r"punch_diameters must be at most .*min\(Lx, Ly\)"):
        punch_window(np.zeros((16, 16)), 1e-6, 17e-6)
    with pytest.raises(ValueError, match="punch_diameter"):
        place_punches((16e-6, 32e-6), 17e-6, 1)


@pytest.mark.parametrize("seed", [0, 1, 7])
def test_placements_inside_the_map_and_apart(seed):
    L, d, n = 1e-3, 200e-6, 5
    c, frac = place_punches((L, 0.8 * L), d, n, seed=seed)
    assert c.shape == (n, 2)
    assert np.all(c[:, 0] >= d / 2) and np.all(c[:, 0] <= L - d / 2)
    assert np.all(c[:, 1] >= d / 2) and np.all(c[:, 1] <= 0.8 * L - d / 2)
    sep = np.hypot(*(c[:, None] - c[None]).transpose(2, 0, 1))[np.triu_indices(n, 1)]
    assert sep.min() >= d
    assert np.all(frac == 0)
    np.testing.assert_array_equal(place_punches((L, 0.8 * L), d, n, seed=seed)[0], c)
    c0, _ = place_punches((L, L), d, None)
    np.testing.assert_array_equal(c0, [[L / 2, L / 2]])


def test_placements_that_cannot_be_apart_warn_or_raise():
    """Three 0.6·L punches cannot be apart on an L × L map: the overlap is reported (the lens
    fraction of the nearest pair), and 'error' names the map size that holds them apart."""
    L, d = 1e-3, 0.6e-3
    with pytest.warns(PlacementOverlapWarning, match=r"overlap by up to .* per side"):
        c, frac = place_punches((L, L), d, 3, seed=0)
    sep = np.hypot(*(c[:, None] - c[None]).transpose(2, 0, 1))
    np.fill_diagonal(sep, np.inf)
    np.testing.assert_allclose(frac, lens_fraction(sep.min(axis=1), d))
    assert np.all(frac > 0)
    with pytest.raises(ValueError, match=r"placements: .* at least 0.0012 m per side"):
        place_punches((L, L), d, 3, seed=0, overlap="error")


def test_lens_fraction_against_a_pixel_count():
    d = 1.0
    g = (np.arange(2000) + 0.5) / 2000 * 3 - 1.5  # 1.5 µ-pixels over [-1.5, 1.5]
    x, y = np.meshgrid(g, g)
    for s in (0.0, 0.3, 0.5, 0.9, 1.0, 1.5):
        a = (x**2 + y**2 <= 0.25) & ((x - s) ** 2 + y**2 <= 0.25)
        b = x**2 + y**2 <= 0.25
        np.testing.assert_allclose(lens_fraction(s, d), a.sum() / b.sum(), atol=2e-3)


# --- truncation on the punch disk -----------------------------------------------------------


def test_disk_truncation_counts_equal_numpy():
    s = _wm(n=128)
    w = punch_window(s.heights, s.dx, 300e-6, (0.22e-3, 0.27e-3))
    tc = disk_truncation(w, 57, device="cpu")
    z32 = np.asarray(s.heights, dtype=np.float32)[disk_mask(s.shape, s.dx, w.centre, 300e-6)]
    thr = (np.float64(z32.max()) - tc.depth).astype(np.float32)
    np.testing.assert_array_equal(tc.threshold, thr)
    ref = [np.count_nonzero(z32 >= t) for t in thr]
    np.testing.assert_array_equal(tc.n_contact_pixels, ref)
    assert tc.n_contact_pixels[-1] == z32.size == tc.n_pixels
    assert tc.apparent_area == pytest.approx(math.pi * (150e-6) ** 2)


def test_truncation_at_loads_flat_and_paraboloid():
    """Flat disk: k = (2/√π)E*√A_disk at every load and ω = F/k. Paraboloid z = −r²/2R:
    A_c = 2πRω, so F = (2/√π)E*√(2πR)·(2/3)ω^{3/2}; ω(F) within 2 % (pixel areas)."""
    es = MAT.contact_modulus
    c = 2 / math.sqrt(math.pi) * es
    w = punch_window(np.zeros((64, 64)), 1e-6, 60e-6)
    loads = np.array([1e-3, 1e-2, 0.1])
    r = truncation_at_loads(w, loads, es, device="cpu")
    k = c * math.sqrt(w.n_pixels * 1e-12)
    np.testing.assert_allclose(r["stiffness"], k, rtol=1e-12)
    np.testing.assert_allclose(r["depth"], loads / k, rtol=1e-9)
    n, dx, R = 256, 1e-6, 5e-3
    y, x = (np.mgrid[0:n, 0:n] + 0.5 - n / 2) * dx
    w = punch_window(-(x * x + y * y) / (2 * R), dx, n * dx)
    loads = np.array([0.05, 0.2, 1.0])
    r = truncation_at_loads(w, loads, es, n_increments=2000, device="cpu")
    omega = (loads / (c * math.sqrt(2 * math.pi * R) * 2 / 3)) ** (2 / 3)
    np.testing.assert_allclose(r["depth"], omega, rtol=0.02)
    np.testing.assert_allclose(r["contact_area"], 2 * math.pi * R * r["depth"], rtol=0.03)


# --- the protocol and its result ---------------------------------------------------------------

HEADER = [
    "punch_diameter_m",
    "placement",
    "peak_load_N",
    "displacement_m",
    "contact_area_m2",
    "plastic_area_m2",
    "unloading_stiffness_N_per_m",
    "partial_unloading_stiffness_N_per_m",
    "E_c_Pa",
    "E_c_over_E",
    "F_over_EA",
    "converged",
]


@pytest.fixture(scope="module")
def result():
    s = _wm(n=96, L=0.6e-3)
    m = Material.against_diamond(hardness=1e9)
    with pytest.warns(PlacementOverlapWarning):  # 0.4 mm twice on 0.6 mm: they overlap
        return indent(
            s,
            protocol=IndentProtocol(
                punch_diameters=(0.1e-3, 0.4e-3),
                peak_loads=(2e-3, 8e-3, 32e-3),
                placements=2,
                placement_seed=4,
                refine_max=1,
                min_contact_pixels=1,
            ),
            material=m,
            device="cpu",
        )


def test_result_columns_and_units(result):
    d = result.to_dict()
    assert list(d)[: len(HEADER)] == HEADER
    assert {v.shape for v in d.values()} == {(2 * 2 * 3,)}
    assert d["converged"].all() and d["elastic_converged"].all()
    np.testing.assert_array_equal(d["punch_diameter_m"], np.repeat([0.1e-3, 0.4e-3], 6))
    np.testing.assert_array_equal(d["placement"], np.tile(np.repeat([0, 1], 3), 2))
    np.testing.assert_array_equal(d["peak_load_N"], np.tile([2e-3, 8e-3, 32e-3], 4))
    area = math.pi * d["punch_diameter_m"] ** 2 / 4
    E = 70e9
    for k, ec, over in (
        ("unloading_stiffness_N_per_m", "E_c_Pa", "E_c_over_E"),
        ("partial_unloading_stiffness_N_per_m", "E_c_partial_Pa", "E_c_partial_over_E"),
    ):
        np.testing.assert_allclose(d[ec], math.sqrt(math.pi) * d[k] / (2 * np.sqrt(area)))
        np.testing.assert_allclose(d[over], d[ec] / E)
    np.testing.assert_allclose(d["F_over_EA"], d["peak_load_N"] / (E * area))
    np.testing.assert_allclose(
        d["truncation_E_c_over_E"],
        2
        / math.sqrt(math.pi)
        * MAT.contact_modulus
        * np.sqrt(d["truncation_contact_area_m2"])
        * math.sqrt(math.pi)
        / (2 * np.sqrt(area))
        / E,
    )
    # every contact pixel carries at most H: F ≤ H·A_c; plastic area within the contact area
    assert np.all(d["peak_load_N"] <= 1e9 * d["contact_area_m2"] * (1 + 1e-9))
    assert np.all(d["plastic_area_m2"] <= d["contact_area_m2"])
    assert np.all(np.diff(d["plastic_volume_m3"].reshape(4, 3), axis=1) >= 0)
    assert np.all(d["overlap_fraction"][:6] == 0) and np.all(d["overlap_fraction"][6:] > 0)
    # the unloading starts steeper than the secant: Barber's slope ≥ the partial-unloading
    # secant, which is accurate to 2·thermotol·F/(0.1·F) = 2e-5 (each load within 1e-6)
    assert np.all(
        d["unloading_stiffness_N_per_m"] >= d["partial_unloading_stiffness_N_per_m"] * (1 - 2e-5)
    )
    cx, cy, dd = d["centre_x_m"], d["centre_y_m"], d["punch_diameter_m"]
    assert np.all(cx - dd / 2 >= 0) and np.all(cx + dd / 2 <= 0.6e-3)
    assert np.all(cy - dd / 2 >= 0) and np.all(cy + dd / 2 <= 0.6e-3)


def test_fits_are_the_least_squares_line_in_log_log(result):
    d = result.to_dict()
    use = d["in_fit"]  # min_contact_pixels = 1, not refined: every converged, unsaturated cell
    np.testing.assert_array_equal(
        use,
        d["converged"]
        & (d["n_contact_pixels"] >= 1)
        & (d["n_contact_pixels"] < d["n_punch_pixels"]),
    )
    assert use.sum() >= 6
    for name, col in (("elastic_plastic", "E_c_over_E"), ("truncation", "truncation_E_c_over_E")):
        fits = result.punch_fits()[name]  # one fit per punch, over its loads
        assert sorted(fits) == [0.1e-3, 0.4e-3]
        for d0, fit in fits.items():
            on = use & (d["punch_diameter_m"] == d0)
            assert fit.n_points == on.sum() and fit.n_loads == 3
            alpha, logb = np.polyfit(np.log(d["F_over_EA"][on]), np.log(d[col][on]), 1)
            assert fit.alpha == pytest.approx(alpha, rel=1e-9)
            assert fit.beta == pytest.approx(math.exp(logb), rel=1e-9)


def test_monotonic_loading_needs_no_replay_of_the_partial_unloads():
    """The state at a peak after load / 10 % unload / reload cycles equals that of loading
    straight to it (elastic unloading and reloading below the previous peak): same contact and
    plastic pixels, approach and both stiffnesses to the solver's tolerance."""
    s = _wm(n=128, L=0.25e-3, Rt=1e-6)
    at = IndentProtocol(punch_diameters=0.2e-3, placements=None, elastic=False, refine_max=1)
    kw = {"device": "cpu", "material": Material.against_diamond(hardness=0.3e9)}
    cycles = indent(s, protocol=at.replace(peak_loads=(0.02, 0.04, 0.08, 0.16)), **kw).to_dict()
    straight = indent(s, protocol=at.replace(peak_loads=(0.16,)), **kw).to_dict()
    assert cycles["plastic_area_m2"][-1] > 50 * s.dx**2  # plasticity is there
    for k in ("contact_area_m2", "plastic_area_m2", "n_contact_pixels"):
        assert cycles[k][-1] == straight[k][0], k
    for k in ("displacement_m", "plastic_volume_m3", "unloading_stiffness_N_per_m"):
        np.testing.assert_allclose(cycles[k][-1], straight[k][0], rtol=1e-5, err_msg=k)
    # the secant ΔF/Δδ over a 10 % step: each load within thermotol = 1e-6 of F, so ΔF within
    # 2·1e-6·F = 2e-5·ΔF (the approach's share comes on top)
    k = "partial_unloading_stiffness_N_per_m"
    np.testing.assert_allclose(cycles[k][-1], straight[k][0], rtol=5e-5, err_msg=k)


def test_elastic_hardness_copies_the_elastic_columns():
    s = _wm()
    r = indent(
        s,
        protocol=IndentProtocol(punch_diameters=None, peak_loads=(1e-3, 4e-3)),
        material=MAT,
        device="cpu",
    )
    d = r.to_dict()
    assert d["n_punch_pixels"][0] == 64 * 64
    assert np.isnan(d["punch_diameter_m"]).all()
    np.testing.assert_allclose(d["punch_area_m2"], s.lx * s.ly)
    np.testing.assert_array_equal(
        d["elastic_unloading_stiffness_N_per_m"], d["unloading_stiffness_N_per_m"]
    )
    assert np.all(d["plastic_area_m2"] == 0)


def test_unyielded_cycles_taken_from_the_elastic_run_equal_solving_them():
    """With a finite H the elastic cycles run first, and each punch's leading cycles whose
    elastic peak pressure stays below H are copied, not solved: the result equals the one that
    solves every cycle (elastic=False), to round-off, and at least one cycle is copied and at
    least one solved (plasticity sets in within the loads)."""
    s = _wm(n=128, L=0.5e-3, Rt=1e-6)
    at = IndentProtocol(punch_diameters=(0.1e-3, 0.25e-3), peak_loads=(1e-3, 4e-3, 16e-3, 64e-3),
                        placements=2, placement_seed=3, refine_max=1)  # fmt: skip
    kw = {"device": "cpu", "material": Material.against_diamond(hardness=1e9)}
    both = indent(s, protocol=at, **kw)
    alone = indent(s, protocol=at.replace(elastic=False), **kw)
    n = both.settings["reused_elastic_cycles"]
    assert 0 < n < 16 and alone.settings["reused_elastic_cycles"] == 0
    a, b = both.to_dict(), alone.to_dict()
    assert np.any(a["plastic_area_m2"] > 0)
    for k in ("n_contact_pixels", "contact_area_m2", "plastic_area_m2", "converged"):
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)
    # the first solved cycle starts from zero forces instead of the previous peak's: equal to
    # the solver's tolerances (loads within thermotol = 1e-6)
    for k in (
        "displacement_m",
        "max_pressure_Pa",
        "unloading_stiffness_N_per_m",
        "partial_unloading_stiffness_N_per_m",
    ):
        np.testing.assert_allclose(a[k], b[k], rtol=1e-6, atol=0, err_msg=k)
    # a few plastic pixels' interference is small next to δ, so δ's change weighs more there
    np.testing.assert_allclose(a["plastic_volume_m3"], b["plastic_volume_m3"], rtol=1e-4, atol=0)
    # the copied cycles are the elastic ones: below H, no plastic area; the others reach H
    el = a["elastic_contact_area_m2"] == a["contact_area_m2"]
    assert np.all(a["max_pressure_Pa"] <= 1e9 * (1 + 1e-12))
    assert np.all(a["plastic_area_m2"][a["max_pressure_Pa"] < 1e9] == 0)
    assert el.sum() >= n
    # an elastic run given as ``reuse`` (also as its columns) does the same without solving it
    elastic = indent(s, protocol=at, **{**kw, "material": Material.against_diamond()})
    for given in (elastic, elastic.to_dict()):
        c = indent(s, protocol=at, reuse=given, **kw)
        assert c.settings["reused_elastic_cycles"] == n
        np.testing.assert_allclose(
            c.to_dict()["unloading_stiffness_N_per_m"], b["unloading_stiffness_N_per_m"], rtol=1e-6
        )
        np.testing.assert_array_equal(
            c.to_dict()["elastic_contact_area_m2"], a["elastic_contact_area_m2"]
        )


def test_reuse_of_another_run_is_refused():
    s = _wm(n=64)
    at = IndentProtocol(punch_diameters=0.1e-3, peak_loads=(1e-3, 4e-3), placements=1, refine_max=1)
    elastic = indent(s, protocol=at, material=Material.against_diamond(), device="cpu")
    plastic = indent(s, protocol=at, material=Material.against_diamond(hardness=1e9), device="cpu")
    m = Material.against_diamond(hardness=1e9)
    with pytest.raises(ValueError, match="not the punch"):  # another placement
        indent(s, protocol=at.replace(placement_seed=5), material=m, reuse=elastic, device="cpu")
    with pytest.raises(ValueError, match=r"reuse must be an elastic run"):
        indent(s, protocol=at, material=m, reuse=plastic, device="cpu")
    cols = elastic.to_dict()
    del cols["max_pressure_Pa"]
    with pytest.raises(ValueError, match="max_pressure_Pa"):
        indent(s, protocol=at, material=m, reuse=cols, device="cpu")


def test_max_pressure_is_the_largest_pixel_pressure():
    """ContactSolver.max_pressure (a device reduction) equals the maximum of the pressure map
    copied to the host."""
    z = _wm(n=64).heights
    solver = ContactSolver(z, 0.5e-3 / 64, MAT.contact_modulus, device="cpu")
    assert solver.max_pressure() == 0.0
    solver.solve(load=1e-2)
    p, _ = solver.maps()
    assert solver.max_pressure() == pytest.approx(p.max(), rel=1e-12)


def test_loads_above_what_the_punch_carries_are_refused():
    s = _wm()
    m = Material.against_diamond(hardness=1e9)
    with pytest.raises(ValueError, match=r"peak_loads must stay below .* H × A"):
        indent(
            s,
            protocol=IndentProtocol(
                punch_diameters=50e-6, peak_loads=(1e-3, 10.0), placements=None
            ),
            material=m,
        )


@pytest.mark.parametrize(
    ("kw", "match"),
    [
        ({"peak_loads": (0.2, 0.1)}, r"peak_loads must be strictly increasing"),
        ({"peak_loads": ()}, r"peak_loads needs at least one value"),
        ({"peak_loads": (0.1, -1.0)}, r"peak_loads\[1\] must be in \(0, inf\) N"),
        ({"unload_fraction": 1.0}, r"unload_fraction must be in \(0, 1\)"),
        ({"unload_fraction": 0.0}, r"unload_fraction must be in \(0, 1\)"),
        ({"placements": 0}, r"placements must be an integer in \[1, 10000\]"),
        ({"punch_diameters": (1e-4, 0.0)}, r"punch_diameters\[1\] must be in \(0, inf\) m"),
    ],
)
def test_protocol_refuses_bad_values(kw, match):
    with pytest.raises(ValueError, match=match):
        IndentProtocol(**kw)


def test_protocol_options_round_trip():
    import argparse

    p = argparse.ArgumentParser()
    add_options(p, IndentProtocol)
    args = p.parse_args(
        [
            "--punch-diameters",
            "1e-4",
            "2e-4",
            "--peak-loads",
            "0.01",
            "--placements",
            "none",
            "--no-elastic",
        ]
    )
    pr = from_args(IndentProtocol, args)
    assert pr.punch_diameters == (1e-4, 2e-4) and pr.peak_loads == (0.01,)
    assert pr.placements is None and pr.unload_fraction == 0.1 and pr.elastic is False
    assert (
        from_args(IndentProtocol, p.parse_args(["--punch-diameters", "none"])).punch_diameters
        is None
    )
    assert IndentProtocol(peak_loads=0.5).peak_loads == (0.5,)


def test_top_level_export():
    assert warptrunc.indent is indent
    assert {"indent", "IndentationResult", "IndentProtocol"} <= set(warptrunc.__all__)


# --- truncation as the limit H → 0, the elastic solution as H → ∞ ------------------------------

ES = MAT.contact_modulus


def _capped(z, dx, delta, ratio):
    sol = ContactSolver(z, dx, ES, hardness=ratio * ES, device="cpu")
    st = sol.solve(depth=delta)
    p, _ = sol.maps()
    assert st.converged
    return st, p > 0


def _paraboloid(n=128, dx=1e-6, R=200e-6):
    y, x = (np.mgrid[0:n, 0:n] + 0.5 - n / 2) * dx
    return -(x * x + y * y) / (2 * R), dx, R


@pytest.mark.parametrize("surface", ["paraboloid", "wm"])
def test_small_hardness_tends_to_the_truncated_set(surface):
    """At a fixed approach δ from first touch, as H/E* → 0 (10⁻², 10⁻³, 10⁻⁴) the contact set
    tends to the truncated set {h ≥ h_max − δ}: the pixel-set difference falls monotonically and
    is ≤ 1 % of A′ at the smallest; F → H·A′ (every contact pixel at H)."""
    if surface == "paraboloid":
        z, dx, _ = _paraboloid()
        delta = 2e-6
    else:
        s = _wm(n=128, L=128e-6, Rt=10e-6)
        z, dx, delta = s.heights.astype(np.float64), s.dx, 2e-6
    trunc = z >= z.max() - delta
    a1 = int(trunc.sum())
    assert a1 > 100
    diffs = []
    for ratio in (1e-2, 1e-3, 1e-4):
        st, contact = _capped(z, dx, delta, ratio)
        diffs.append(np.count_nonzero(contact ^ trunc))
        load_ratio = st.load / (ratio * ES * a1 * dx * dx)
    assert diffs[0] > diffs[1] > diffs[2] or (diffs[2] == 0 and diffs[0] >= diffs[1] >= diffs[2])
    assert diffs[-1] <= 0.01 * a1
    assert abs(load_ratio - 1) <= 0.01


def test_paraboloid_truncated_area_is_2_pi_R_delta():
    """z = −r²/2R truncated at δ: A′ = 2πRδ within one pixel ring of the perimeter 2π√(2Rδ);
    the H/E* = 10⁻⁴ contact area too."""
    z, dx, R = _paraboloid()
    delta = 2e-6
    exact = 2 * math.pi * R * delta
    ring = 2 * math.pi * math.sqrt(2 * R * delta) * dx
    assert abs(np.count_nonzero(z >= z.max() - delta) * dx * dx - exact) <= ring
    st, _ = _capped(z, dx, delta, 1e-4)
    assert abs(st.contact_area - exact) <= ring


def test_large_hardness_is_the_elastic_solution():
    s = _wm(n=64, L=64e-6)
    z, delta = s.heights.astype(np.float64), 0.3e-6
    el = ContactSolver(z, s.dx, ES, device="cpu")
    e = el.solve(depth=delta)
    p_el, _ = el.maps()
    st, contact = _capped(z, s.dx, delta, 1e6)
    assert st.n_plastic == 0
    np.testing.assert_array_equal(contact, p_el > 0)
    np.testing.assert_allclose(st.load, e.load, rtol=1e-6)


# --- the command line ---------------------------------------------------------------------------

CLI = INDENT_CLI


def test_cli_writes_csv_json_and_figure(tmp_path, capsys):
    out = tmp_path / "ind"
    assert main([*CLI, "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["indent.csv", "indent.json", "indent.png"]
    header = (out / "indent.csv").read_text().splitlines()[0].split(",")
    assert header[: len(HEADER)] == HEADER
    rows = (out / "indent.csv").read_text().splitlines()[1:]
    assert len(rows) == 2 * 3

    def no_constants(name):
        raise AssertionError(f"non-standard JSON constant {name}")

    doc = json.loads((out / "indent.json").read_text(), parse_constant=no_constants)
    assert set(doc["fits"]) == {
        "elastic_plastic",
        "elastic_plastic_partial",
        "elastic",
        "elastic_partial",
        "truncation",
    }
    assert doc["material"]["hardness"] == 1e9 and doc["material"]["E_i"] == 1141e9
    assert doc["protocol"]["peak_loads"] == [1e-3, 4e-3, 1.6e-2]
    assert "git_commit" in doc["provenance"]
    assert (out / "indent.png").stat().st_size > 10_000
    text = capsys.readouterr().out
    assert "cells: " in text and "resolved" in text and "in_fit" in text
    # 64² over 0.4 mm: no cell has 100 contact pixels, so no fit is made, per punch or pooled
    assert "no fit: 0 distinct peak load(s) of the 150 µm punch with cells in_fit" in text
    for f in doc["fits"].values():
        assert [r["n_loads"] for r in f["per_punch"]] == [0]
        assert not f["per_punch"][0]["made"] and not f["pooled"]["made"]


@pytest.mark.parametrize(
    ("extra", "needles"),
    [
        (["--punch-diameters", "5e-4"], ["--punch-diameters", "min(Lx, Ly)", "0.0005"]),
        (["--hardness", "0"], ["--hardness", "(0, inf] Pa", "'0'"]),
        (["--hardness", "-1e9"], ["--hardness", "(0, inf] Pa", "-1e9"]),
        (["--peak-loads", "1e-3", "100"], ["--peak-loads", "H × A", "100"]),
        (["--peak-loads", "2e-3", "1e-3"], ["--peak-loads", "increasing"]),
        (["--unload-fraction", "1"], ["--unload-fraction", "(0, 1)", "'1'"]),
        (["--unload-fraction", "0"], ["--unload-fraction", "(0, 1)", "'0'"]),
        (["--unload-fraction", "nan"], ["--unload-fraction", "(0, 1)", "nan"]),
        (["--placements", "0"], ["--placements", "[1, 10000]", "'0'"]),
        (
            ["--placements", "3", "--punch-diameters", "3e-4", "--overlap", "error"],
            ["--placements", "per side"],
        ),
    ],
)
def test_cli_bad_input_exits_2_with_the_option_named(tmp_path, capsys, extra, needles):
    assert_refused_in_one_line([*CLI, *extra], tmp_path / "ind", capsys, needles)
