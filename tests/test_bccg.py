# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The preconditioned bound-constrained CG (``SolverSettings(algorithm="bccg")``): the same
solutions as the default Polonsky–Keer CG (itself equal to ContactMechanics, tests/test_contact.py),
u = K·q against an independent float64 NumPy convolution, complementarity, Barber's punch, and
iterations that stop growing with the grid under a punch close to complete contact."""

import math

import numpy as np
import pytest
from test_plastic import _displacement

from warptrunc import SolverSettings, wm_surface
from warptrunc.contact import ContactSolver

E_STAR = 70e9 / (1 - 0.33**2)  # aluminium on a rigid flat (Pa)


def _solvers(h, dx, device, **kw):
    return [
        ContactSolver(h, dx, E_STAR, settings=SolverSettings(algorithm=a, **kw), device=device)
        for a in ("pk", "bccg")
    ]


@pytest.mark.parametrize("substrate", ["free", "periodic"])
@pytest.mark.parametrize("dtype", ["float64", "float32"])
def test_same_solution_as_pk(device, substrate, dtype):
    """Displacement- and load-controlled solves (warm-started, loading and unloading) give the
    default solver's load, approach and contact pixels to within the shared tolerances, and the
    gap is that of u = K·q by an independent float64 convolution."""
    s = wm_surface(2.5, L=1e-3, n=128, seed=3, device="cpu")
    h = np.asarray(s.heights, dtype=np.float64)
    pk, bc = _solvers(h, s.dx, device, substrate=substrate, dtype=dtype)
    rtol = 2e-4 if dtype == "float64" else 1e-3
    for kw in (
        {"depth": 0.2 * s.Rt},
        {"depth": 0.5 * s.Rt},
        {"load": 40.0},
        {"load": 8.0},
        {"depth": 0.05 * s.Rt},
    ):
        a, b = pk.solve(**kw), bc.solve(**kw)
        assert a.converged and b.converged, kw
        assert math.isclose(a.load, b.load, rel_tol=rtol), (kw, a.load, b.load)
        assert math.isclose(a.depth, b.depth, rel_tol=rtol), kw
        assert abs(a.n_contact - b.n_contact) <= max(2, 0.01 * a.n_contact), kw
        assert b.n_iterations >= 1 and b.n_convolutions >= b.n_iterations
    p, gap = bc.maps()
    q = p * s.dx * s.dx
    ref_gap = _displacement(q, s.dx, substrate) - h - (b.depth - h.max())
    scale = 1e-9 if dtype == "float64" else 1e-5
    np.testing.assert_allclose(gap, ref_gap, atol=scale * s.Rt + 2 * bc.pentol)
    assert p.min() >= 0
    assert gap.min() >= -1.01 * bc.pentol - scale * s.Rt
    assert np.abs(gap[p > 0]).max() <= 1.01 * bc.pentol + scale * s.Rt


def test_capped_same_as_pk(device):
    """With a hardness the capped solves (displacement control, then a load by the secant) give
    the default solver's load, contact and plastic pixels and plastic volume."""
    s = wm_surface(2.5, L=1e-3, n=96, seed=4, device="cpu")
    h = np.asarray(s.heights, dtype=np.float64)
    sols = [
        ContactSolver(
            h, s.dx, E_STAR, hardness=1e9, device=device, settings=SolverSettings(algorithm=a)
        )
        for a in ("pk", "bccg")
    ]
    load = None
    for kw in ({"depth": 0.2 * s.Rt}, {"depth": 0.4 * s.Rt}, "load"):
        if kw == "load":
            kw = {"load": 1.3 * load}  # further loading, by the secant
        a, b = (x.solve(**kw) for x in sols)
        load = a.load
        assert a.converged and b.converged, kw
        assert b.n_plastic > 0
        assert math.isclose(a.load, b.load, rel_tol=1e-3), kw
        assert abs(a.n_contact - b.n_contact) <= max(2, 0.01 * a.n_contact)
        assert abs(a.n_plastic - b.n_plastic) <= max(2, 0.01 * a.n_plastic)
        assert math.isclose(a.plastic_volume, b.plastic_volume, rel_tol=0.01)
    p, _ = sols[1].maps()
    assert p.max() <= 1e9 * (1 + 1e-9)


def test_punch_pcg_equals_cg(device):
    """Barber's stiffness by the preconditioned CG equals the plain CG's, in fewer iterations."""
    s = wm_surface(2.5, L=1e-3, n=128, seed=5, device="cpu")
    out = []
    for sol in _solvers(s.heights, s.dx, device):
        sol.solve(0.6 * s.Rt)
        out.append(sol.punch_stiffness())
    (k_cg, it_cg, ok_cg), (k_pcg, it_pcg, ok_pcg) = out
    assert ok_cg and ok_pcg
    assert math.isclose(k_cg, k_pcg, rel_tol=1e-8)
    assert it_pcg < it_cg


def _punch_case(n):
    """A fixed-content surface (modes down to 1/16 of the side only) under a rigid flat disk of
    0.9 of the side, pushed to about 80 % contact."""
    s = wm_surface(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6, Wc=1e-3 / 16, seed=0, device="cpu")
    h = np.asarray(s.heights, dtype=np.float64)
    y, x = np.mgrid[0:n, 0:n]
    outside = (x - n / 2 + 0.5) ** 2 + (y - n / 2 + 0.5) ** 2 >= (0.45 * n) ** 2
    h[outside] = h.min() - 1e-3  # never touches
    return h, s.dx, 10 * s.Rt


def test_iterations_stop_growing_under_a_punch(device):
    """Cold-start iterations at a fixed relative tolerance (pentol = 1e-4·rms) under a punch
    near complete contact: from 64² to 256² the preconditioned BCCG's grow ≤ 1.5×, the default
    solver's ≥ 2× (the O(√N) growth this algorithm removes)."""
    its = {"pk": [], "bccg": []}
    for n in (64, 256):
        h, dx, depth = _punch_case(n)
        inside = h > h.min()
        pentol = 1e-4 * float(np.std(h[inside]))
        for a in its:
            sol = ContactSolver(
                h, dx, E_STAR, device=device, settings=SolverSettings(algorithm=a, pentol=pentol)
            )
            st = sol.solve(depth)
            assert st.converged
            assert st.n_contact > 0.6 * np.count_nonzero(inside)
            its[a].append(st.n_iterations)
    assert its["bccg"][1] <= 1.5 * its["bccg"][0], its
    assert its["pk"][1] >= 2 * its["pk"][0], its


def test_precondition_above_is_checked():
    """The preconditioner threshold is a fraction in [0, 1]; "auto" is None (the default rule)."""
    assert SolverSettings(precondition_above="auto").precondition_above is None
    assert SolverSettings(precondition_above=0).precondition_above == 0
    for bad in (-0.1, 1.5):
        with pytest.raises(ValueError, match=r"precondition_above must be in \[0, 1\]"):
            SolverSettings(precondition_above=bad)


def test_preconditioner_always_stops_the_growth_on_a_whole_map(device):
    """A fixed-content map (W_c = L/32 sampled finer) at 0.2·R_t, cold, pentol = 1e-4·rms: from
    128² to 512² the iterations of BCCG preconditioned always (precondition_above=0) stay within
    1.35× of each other, the plain CG's (1 = never) grow ≥ 1.5×, and all give the same load."""
    its = {0.0: [], 1.0: []}
    for n in (128, 256, 512):
        s = wm_surface(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6, seed=0, device="cpu", Wc=1e-3 / 32)
        h = np.asarray(s.heights, dtype=np.float64)
        loads = []
        for pa in its:
            sol = ContactSolver(
                h,
                s.dx,
                E_STAR,
                device=device,
                settings=SolverSettings(pentol=1e-4 * float(np.std(h)), precondition_above=pa),
            )
            st = sol.solve(0.2 * float(np.ptp(h)))
            assert st.converged
            its[pa].append(st.n_iterations)
            loads.append(st.load)
        assert math.isclose(loads[0], loads[1], rel_tol=1e-5), (n, loads)
    assert max(its[0.0]) <= 1.35 * min(its[0.0]), its
    assert its[1.0][-1] >= 1.5 * its[1.0][0], its


def test_default_rule_preconditions_large_maps(device, monkeypatch):
    """The default rule (precondition_above=None) preconditions always on a map of at least
    PRECONDITION_LARGE pixels (here lowered to 96²) and from 2 % of a smaller one: its
    iterations and convolutions are those of precondition_above = 0 and 0.02 respectively; a
    punch window's solver takes 2 % at every size."""
    import warptrunc.contact.iteration.bccg as bccg
    from warptrunc.indent import default_material, make_solver, punch_window

    monkeypatch.setattr(bccg, "PRECONDITION_LARGE", 96 * 96)
    s = wm_surface(2.5, 100e-6, L=1e-3, n=128, Rt=10e-6, seed=0, device="cpu", Wc=1e-3 / 32)
    h = np.asarray(s.heights, dtype=np.float64)
    depth = 0.2 * float(np.ptp(h))

    def counts(z, pa):
        sol = ContactSolver(
            z, s.dx, E_STAR, device=device, settings=SolverSettings(precondition_above=pa)
        )
        st = sol.solve(depth - (h.max() - z.max()))
        assert st.converged
        return st.n_iterations, st.n_convolutions

    big, small = counts(h, None), counts(h[:64, :64], None)
    assert big == counts(h, 0.0) and big != counts(h, 0.02), big
    assert small == counts(h[:64, :64], 0.02) and small != counts(h[:64, :64], 0.0), small
    win = punch_window(h, s.dx, 0.6e-3, (0.5e-3, 0.5e-3))
    for given, taken in ((None, 0.02), (0.0, 0.0)):
        sol = make_solver(
            win,
            default_material(hardness=math.inf),
            device=device,
            solver=SolverSettings(precondition_above=given),
        )
        assert sol.settings.precondition_above == taken, (given, sol.settings)
