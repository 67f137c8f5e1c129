# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic–perfectly-plastic contact (``ContactSolver(hardness=H)``): the limit H = inf, the
complementarity conditions of the capped problem, the plastic volume against an independent
NumPy convolution, path dependence (reloading, unloading, load/unload histories) and
ContactMechanics' ``PlasticNonSmoothContactSystem`` on the same map (``bem`` extra)."""

import math
import warnings

import numpy as np
import pytest

from warptrunc import Material, SolverSettings, wm_surface
from warptrunc.contact import ContactSolver, CurveSettings, influence_spectrum, solve_contact

E_STAR = 70e9 / (1 - 0.33**2)  # aluminium on a rigid flat (Pa)
H_AL = 1.0e9  # a hardness with some 10–80 % of the contact at the cap on these maps (Pa)


def _surface(n=64, seed=4):
    return wm_surface(2.5, L=1e-3, n=n, seed=seed, device="cpu")


def _displacement(q, dx, substrate="free"):
    """u = K·q by a float64 NumPy FFT convolution with the (independently tested) spectrum."""
    ny, nx = q.shape
    w = influence_spectrum((ny, nx), (dx, dx), E_STAR, substrate)
    grid = (2 * ny, 2 * nx) if substrate == "free" else (ny, nx)
    pad = np.zeros(grid)
    pad[:ny, :nx] = q
    return np.fft.irfft2(np.fft.rfft2(pad) * w, s=grid)[:ny, :nx]


@pytest.mark.parametrize("dtype", ["float64", "float32"])
def test_huge_hardness_equals_elastic(device, dtype):
    """H = inf takes the elastic path (bit for bit); a hardness no pixel reaches (1e6·E*) runs the
    capped path and equals the elastic solver to round-off: same contact pixels, F within 1e-9
    (float64) or 1e-5 (float32), no plastic pixel."""
    s = _surface()
    el = ContactSolver(s.heights, s.dx, E_STAR, device=device, settings=SolverSettings(dtype=dtype))
    inf = ContactSolver(
        s.heights,
        s.dx,
        E_STAR,
        hardness=math.inf,
        device=device,
        settings=SolverSettings(dtype=dtype),
    )
    big = ContactSolver(
        s.heights,
        s.dx,
        E_STAR,
        hardness=1e6 * E_STAR,
        device=device,
        settings=SolverSettings(dtype=dtype),
    )
    rtol = 1e-9 if dtype == "float64" else 1e-5
    for f in (0.1, 0.2, 0.3):
        a, b, c = (x.solve(f * s.Rt) for x in (el, inf, big))
        assert a == b
        assert a.converged and c.converged
        assert c.n_plastic == 0 and c.plastic_volume == 0.0
        assert c.n_contact == a.n_contact
        assert math.isclose(c.load, a.load, rel_tol=rtol)
        np.testing.assert_array_equal(el.maps()[0] > 0, big.maps()[0] > 0)
    assert not np.any(big.plastic_displacement())


@pytest.mark.parametrize("algorithm", ["pk", "bccg"])
@pytest.mark.parametrize("substrate", ["free", "periodic"])
@pytest.mark.parametrize("dtype", ["float64", "float32"])
def test_complementarity(device, substrate, dtype, algorithm):
    """At convergence of every loading solve: gap ≥ −pentol, 0 ≤ p ≤ H, |gap| ≤ pentol where
    p > 0 (p·gap ≈ 0), and the plastic displacement grows only where p = H."""
    s = _surface()
    sol = ContactSolver(
        s.heights,
        s.dx,
        E_STAR,
        hardness=H_AL,
        device=device,
        settings=SolverSettings(substrate=substrate, dtype=dtype, algorithm=algorithm),
    )
    tol = sol.pentol * (1 + 1e-3) + (1e-12 if dtype == "float64" else 1e-6 * s.Rt)
    w_old = sol.plastic_displacement()
    for f in (0.15, 0.3, 0.45):
        st = sol.solve(f * s.Rt)
        assert st.converged
        p, gap = sol.maps()
        w = sol.plastic_displacement()
        at_cap = p >= H_AL * (1 - 1e-6)
        assert st.n_plastic == np.count_nonzero(at_cap) > 0
        assert st.n_contact == np.count_nonzero(p > 0)
        assert p.min() >= 0 and p.max() <= H_AL * (1 + 1e-6)
        assert gap.min() >= -tol
        assert np.abs(gap[p > 0]).max() <= tol
        assert np.all(w >= 0)
        grew = w > w_old
        assert np.all(at_cap[grew])
        w_old = w


def test_plastic_volume_is_the_interference_removed(device):
    """One loading solve from the undeformed map: the plastic displacement at each pixel at the
    cap is the interference of the original heights with the elastically displaced surface,
    h + offset − u (u = K·q by an independent NumPy convolution of the solver's forces), and
    Σ w·dx·dy equals the reported plastic volume."""
    s = _surface()
    sol = ContactSolver(s.heights, s.dx, E_STAR, hardness=H_AL, device=device)
    st = sol.solve(0.4 * s.Rt)
    p, _ = sol.maps()
    q = p * s.dx * s.dx
    u = _displacement(q, s.dx)
    interference = np.where(p >= H_AL * (1 - 1e-9), s.heights + st.depth - s.heights.max() - u, 0)
    w = sol.plastic_displacement()
    scale = float(w.max())
    np.testing.assert_allclose(w, np.maximum(interference, 0), atol=1e-6 * scale + 2 * sol.pentol)
    assert math.isclose(w.sum() * s.dx * s.dx, st.plastic_volume, rel_tol=1e-9)
    assert math.isclose(
        np.maximum(interference, 0).sum() * s.dx**2, st.plastic_volume, rel_tol=1e-3
    )


@pytest.mark.parametrize("dtype", ["float64", "float32"])
def test_reloading_and_unloading(device, dtype):
    """Unloading from a peak is elastic (no pixel reaches H again, no plastic volume, with the
    cap active or frozen) and reloading to the peak returns the peak's load and contact and adds
    no plastic volume beyond the solver's tolerance (each pixel at the cap may flow by at most
    ``pentol`` more: the peak's penetration was converged to within it)."""
    s = _surface()
    sol = ContactSolver(
        s.heights, s.dx, E_STAR, hardness=H_AL, device=device, settings=SolverSettings(dtype=dtype)
    )
    peak = sol.solve(0.4 * s.Rt)
    w_peak = sol.plastic_displacement()
    for f in (0.38, 0.3, 0.2):
        un = sol.solve(f * s.Rt, plastic=False)  # frozen: elastic, no cap
        assert un.converged and un.n_plastic == 0
        assert sol.maps()[0].max() < H_AL
        un = sol.solve(f * s.Rt)  # the cap active: nothing flows either
        assert un.n_plastic == 0 and un.plastic_volume == peak.plastic_volume
    sol.freeze_plastic()
    assert sol.solve(load=0.9 * peak.load).n_plastic == 0
    sol.freeze_plastic(False)
    again = sol.solve(0.4 * s.Rt)
    rtol = 1e-6 if dtype == "float64" else 1e-4
    assert math.isclose(again.load, peak.load, rel_tol=rtol)
    assert again.n_contact == peak.n_contact
    added = again.plastic_volume - peak.plastic_volume
    assert 0 <= added <= peak.n_plastic * sol.pentol * s.dx * s.dx
    np.testing.assert_allclose(sol.plastic_displacement(), w_peak, atol=sol.pentol)


def test_fully_plastic_carries_hardness_times_area(device):
    """With a tiny hardness (H = 1e-5·E*: the elastic deflection is 1e-5 of the approach) every
    contact pixel is at the cap: F = H·A_c."""
    s = _surface()
    h = 1e-5 * E_STAR
    sol = ContactSolver(s.heights, s.dx, E_STAR, hardness=h, device=device)
    for f in (0.1, 0.3):
        st = sol.solve(f * s.Rt)
        assert st.converged
        assert st.n_plastic == st.n_contact > 0
        assert math.isclose(st.load, h * st.contact_area, rel_tol=1e-9)


def test_monotonic_equals_load_unload_history(device):
    """Monotonic loading through the peaks F1 < F2 < F3 gives at each peak the state of the
    experiment's history (each peak followed by a 10 % partial unloading, then reloading):
    the same contact and plastic pixels, plastic maps and loads within the tolerances."""
    s = _surface()
    a = ContactSolver(s.heights, s.dx, E_STAR, hardness=H_AL, device=device)
    b = ContactSolver(s.heights, s.dx, E_STAR, hardness=H_AL, device=device)
    for load in (2.0, 8.0, 30.0):
        sa = a.solve(load=load)
        sb = b.solve(load=load)
        assert sa.converged and sb.converged
        assert sa.n_contact == sb.n_contact and sa.n_plastic == sb.n_plastic
        assert math.isclose(sa.load, sb.load, rel_tol=1e-5)
        assert math.isclose(sa.plastic_volume, sb.plastic_volume, rel_tol=1e-5)
        wa = a.plastic_displacement()
        np.testing.assert_allclose(b.plastic_displacement(), wa, atol=1e-5 * wa.max())
        un = b.solve(load=0.9 * load)  # the partial unloading, then reload at the next peak
        assert un.converged and un.n_plastic == 0


def test_punch_stiffness_on_the_deformed_surface(device):
    """Barber's stiffness of the contact set at a plastic peak is the initial unloading slope:
    the secant of a 0.1 % elastic unloading lies within 2 % of it."""
    s = _surface()
    sol = ContactSolver(s.heights, s.dx, E_STAR, hardness=H_AL, device=device)
    peak = sol.solve(0.4 * s.Rt)
    k, _, ok = sol.punch_stiffness()
    assert ok and peak.n_plastic > 0
    un = sol.solve(0.999 * peak.depth, plastic=False)
    secant = (peak.load - un.load) / (peak.depth - un.depth)
    assert math.isclose(secant, k, rel_tol=0.02)


def test_reset_forgets_the_plastic_state(device):
    s = _surface()
    sol = ContactSolver(s.heights, s.dx, E_STAR, hardness=H_AL, device=device)
    first = sol.solve(0.3 * s.Rt)
    sol.reset()
    assert not np.any(sol.plastic_displacement())
    again = sol.solve(0.3 * s.Rt)
    assert again.n_plastic == first.n_plastic
    assert math.isclose(again.plastic_volume, first.plastic_volume, rel_tol=1e-6)


def test_solve_contact_material_and_plastic_columns(device):
    """``solve_contact`` reads E* and H from a Material: its rows are those of a
    ``ContactSolver`` with that E* and H; the curve has the plastic columns (zero when
    elastic); the central difference is refused with H < inf."""
    s = _surface()
    m = Material(hardness=H_AL)
    d = np.array([0.1, 0.3]) * s.Rt
    c = solve_contact(s, d, material=m, device=device)
    cols = c.to_dict()
    assert cols["plastic_area_m2"][-1] > 0 and cols["plastic_volume_m3"][-1] > 0
    assert np.all(np.diff(cols["plastic_volume_m3"]) >= 0)
    e = solve_contact(s, d, material=m.replace(hardness=math.inf), device=device)
    assert not np.any(e.to_dict()["plastic_area_m2"])
    solver = ContactSolver(s.heights, s.dx, m.contact_modulus, hardness=H_AL, device=device)
    np.testing.assert_array_equal([solver.solve(v).n_plastic for v in d], c.n_plastic)
    with pytest.raises(ValueError, match="central"):
        solve_contact(s, d, material=m, device=device, curve=CurveSettings(stiffness="central"))


def test_settings_are_one_object(device):
    """The solver's settings come in one object; bad values name the field; the settings'
    fields are no keywords of the solver; a solve's result is read by attribute."""
    s = _surface(32)
    a = ContactSolver(
        s.heights, s.dx, E_STAR, settings=SolverSettings(dtype="float32", maxiter=50), device=device
    )
    assert (a.dtype, a.maxiter) == ("float32", 50)
    with pytest.raises(ValueError, match="maxiter"):
        SolverSettings(maxiter=0)
    with pytest.raises(ValueError, match="hardness"):
        ContactSolver(s.heights, s.dx, E_STAR, hardness=-1.0, device=device)
    for kw in ({"tolerance": 1.0}, {"dtype": "float32"}):
        with pytest.raises(TypeError, match=next(iter(kw))):
            ContactSolver(s.heights, s.dx, E_STAR, device=device, **kw)
    st = a.solve(0.2 * s.Rt)
    with pytest.raises(TypeError):
        st["load"]
    assert set(st.to_dict()) >= {"depth_m", "load_N", "plastic_area_m2", "plastic_volume_m3"}


# --- ContactMechanics ------------------------------------------------------------------------


@pytest.mark.parametrize("algorithm", ["pk", "bccg"])
def test_equals_contactmechanics_plastic_system(device, algorithm):
    """Loading to three approaches and a 10 % partial unloading equal ContactMechanics'
    ``PlasticNonSmoothContactSystem`` (``PlasticTopography``) on the same 64² map: contact and
    plastic areas and the plastic displacement within 1 %, the unloading stiffness within 2 %."""
    pytest.importorskip("ContactMechanics")
    pytest.importorskip("SurfaceTopography")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        from ContactMechanics import FreeFFTElasticHalfSpace
        from ContactMechanics.PlasticSystemSpecialisations import PlasticNonSmoothContactSystem
        from SurfaceTopography import PlasticTopography, Topography
    s = _surface()
    h = np.asarray(s.heights, dtype=np.float64)
    hT = np.ascontiguousarray(h.T)  # ContactMechanics: x first
    sizes = (s.lx, s.ly)
    topo = PlasticTopography(Topography(hT, physical_sizes=sizes, periodic=False), H_AL)
    system = PlasticNonSmoothContactSystem(FreeFFTElasticHalfSpace(hT.shape, E_STAR, sizes), topo)
    sol = ContactSolver(
        h, s.dx, E_STAR, hardness=H_AL, device=device, settings=SolverSettings(algorithm=algorithm)
    )
    kw = {"pentol": sol.pentol, "forcetol": sol.forcetol, "maxiter": 100000}
    cap = H_AL * s.dx * s.dx
    u0 = None
    for f in (0.1, 0.25, 0.4):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = system.minimize_proxy(offset=f * s.Rt - h.max(), initial_displacements=u0, **kw)
        assert r.success
        u0 = r.x
        f_cm = np.asarray(r.jac).T
        st = sol.solve(f * s.Rt)
        assert st.converged
        assert math.isclose(st.load, f_cm.sum(), rel_tol=0.01)
        assert math.isclose(st.n_contact, np.count_nonzero(f_cm > 0), rel_tol=0.01)
        assert math.isclose(st.n_plastic, np.count_nonzero(f_cm >= cap * (1 - 1e-9)), rel_tol=0.01)
        w_cm = -np.asarray(topo.plastic_displ).T
        w = sol.plastic_displacement()
        assert math.isclose(w.sum(), w_cm.sum(), rel_tol=0.01)
        np.testing.assert_allclose(w, w_cm, atol=0.01 * w_cm.max())
    peak = st
    un = sol.solve(load=0.9 * peak.load, plastic=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = system.minimize_proxy(offset=un.depth - h.max(), initial_displacements=u0, **kw)
    k_cm = (np.asarray(r.jac).sum() - f_cm.sum()) / (un.depth - peak.depth)
    k = (un.load - peak.load) / (un.depth - peak.depth)
    assert math.isclose(k, k_cm, rel_tol=0.02)


# PK (not the default algorithm) takes 11–13 s per precision here: in the slow set
@pytest.mark.parametrize("algorithm", [pytest.param("pk", marks=pytest.mark.slow), "bccg"])
@pytest.mark.parametrize("dtype", ["float64", "float32"])
def test_load_control_under_complete_contact_converges(device, dtype, algorithm):
    """A gently tilted plane (8 nm across 32 pixels of 1 µm) under loads that bring every pixel
    into contact, below H·A: F(δ) becomes linear once the whole map touches, and each
    load-controlled solve must converge to the load with every pixel in contact and none at
    the cap (the mean pressure F/A stays well below H)."""
    n, dx = 32, 1e-6
    y, x = np.mgrid[0:n, 0:n]
    z = -8e-9 * (x + y) / (2 * n)  # m
    area = (n * dx) ** 2
    sol = ContactSolver(
        z,
        dx,
        E_STAR,
        hardness=H_AL,
        device=device,
        settings=SolverSettings(dtype=dtype, algorithm=algorithm),
    )
    for p_mean in (2e7, 5e7, 1e8):  # Pa, 2–10 % of H
        st = sol.solve(load=p_mean * area)
        assert st.converged, (dtype, p_mean)
        assert st.n_contact == n * n and st.n_plastic == 0
        assert math.isclose(st.load, p_mean * area, rel_tol=1e-4)
