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

import numpy as np
import pytest

import warptrunc
from warptrunc.indent import indent, punch_window, run_cycles
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
            out += GAMMA ** ((D - 3) * n) * (math.cos(a) - np.cos(k * (x * math.cos(th) + y * math.sin(th)) + a))
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
    fine = wm_window(s.params, (factor * iy, factor * ix), (factor * wy, factor * wx), factor,
                     device="cpu").astype(np.float64)  # fmt: skip
    tol = 2e-6 * np.ptp(z)  # float32 heights and float32 products of float32 tables
    np.testing.assert_allclose(fine[::factor, ::factor], z[iy : iy + wy, ix : ix + wx], rtol=0, atol=tol)
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
    r = run_cycles(w, [load], 0.1, material, hardness=material.hardness, device="cpu")
    assert r["converged"][0]
    return r["unloading_stiffness"][0], r["contact_area"][0], w.n_pixels


def test_a_resolved_cell_agrees_with_the_cell_solved_on_its_own_at_half_its_pixel():
    """Cells flagged resolved at pixel p: solved independently at 2p, p and p/2, K and A at p
    are reproduced, the change from 2p is the one reported and below the tolerance, and the
    cell at p/2 agrees with the one reported within the tolerance."""
    s = _wm()
    mat = Material.against_diamond(hardness=0.05e9)  # soft: large plastic contacts
    tol = 0.02
    r = indent(s, punch_diameter=(0.15e-3,), peak_loads=(16e-3, 64e-3), placements=2,
               material=mat, refine_max=4, min_contact_pixels=50, resolution_tol=tol,
               elastic=False, device="cpu")  # fmt: skip
    d = r.to_dict()
    done = np.flatnonzero(d["resolved"])
    assert done.size >= 1 and not d["resolved"].all()
    scale = _scale(s)
    for i in done:
        p = d["pixel_size_m"][i]
        assert p < s.dx and d["resolution_note"][i] == "resolved"
        c, load = (d["centre_x_m"][i], d["centre_y_m"][i]), d["peak_load_N"][i]
        k, a, n_disk = _independent_cell(s, scale, c, 0.15e-3, load, p, mat)
        assert n_disk == d["n_punch_pixels"][i]
        np.testing.assert_allclose(d["unloading_stiffness_N_per_m"][i], k, rtol=1e-4)
        np.testing.assert_allclose(d["contact_area_m2"][i], a, rtol=1e-3)
        k2, a2, _ = _independent_cell(s, scale, c, 0.15e-3, load, 2 * p, mat)
        np.testing.assert_allclose(d["resolution_change"][i], abs(k / k2 - 1), atol=1e-4)
        assert abs(k / k2 - 1) < tol and abs(a / a2 - 1) < tol
        assert d["n_contact_pixels"][i] >= 50
        kh, ah, _ = _independent_cell(s, scale, c, 0.15e-3, load, p / 2, mat)
        assert abs(d["unloading_stiffness_N_per_m"][i] / kh - 1) < tol
        assert abs(d["contact_area_m2"][i] / ah - 1) < tol
    # every other cell ran to the finest pixel allowed, unresolved
    rest = np.setdiff1d(np.arange(d["peak_load_N"].size), done)
    assert np.all(d["pixel_size_m"][rest] == s.dx / 4)
    assert set(d["resolution_note"][rest]) == {"refine-max"}


def test_saturated_cells_are_never_in_fit():
    """Complete contact (every disk pixel touches) is flagged saturated and left out of the fits,
    resolved or not: a flat read map under a punch, and a nearly flat WM map refined."""
    flat = np.zeros((64, 64))
    r = indent(flat, pixel_size=2e-6, punch_diameter=(60e-6,), peak_loads=(1e-3, 2e-3),
               placements=None, material=Material.against_diamond(), device="cpu",
               min_contact_pixels=1)  # fmt: skip
    d = r.to_dict()
    assert np.all(d["n_contact_pixels"] == d["n_punch_pixels"]) and d["saturated"].all()
    assert d["resolved"].all() and not d["in_fit"].any()  # resolved by the pixel rule alone
    assert set(d["resolution_note"]) == {"read-map"} and np.isnan(d["resolution_change"]).all()
    assert np.all(d["pixel_size_m"] == 2e-6)
    s = _wm(n=64, L=0.2e-3, Rt=1e-9)  # 24 pixels of radius: K and A within 1 % at p/2
    r = indent(s, punch_diameter=(0.15e-3,), peak_loads=(0.5, 1.0), placements=None,
               material=Material.against_diamond(), refine_max=2, min_contact_pixels=10,
               device="cpu")  # fmt: skip
    d = r.to_dict()
    np.testing.assert_array_equal(d["saturated"], d["n_contact_pixels"] >= d["n_punch_pixels"])
    assert d["saturated"].all() and d["resolved"].any()
    assert not d["in_fit"].any() and not d["elastic_in_fit"].any()
    assert all(not f["made"] for f in r.fit_summary().values())
