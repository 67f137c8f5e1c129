# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Adhesive contact (``warptrunc.contact.adhesion``, ``warptrunc.contact.iteration.adhesive``):
the laws against their closed forms; w = 0 against the non-adhesive solver, bit for bit; a
paraboloid on a flat against JKR (1.5πwR), DMT (2πwR) and Maugis' closed-form transition
(Maugis 1992, computed here with SciPy); the force–approach cycle's branches and jumps; a
rough periodic surface against tamaas' adhesive solver on the same surface and law.

The sphere's lengths are Maugis': ℓ = (πwR²/K)^(1/3) for radii, (π²w²R/K²)^(1/3) for
approaches, πwR for loads (K = 4E*/3). A pixel of the Maugis–Dugdale law resolves the
cohesive zone when σ₀·dx/E* ≪ h₀, i.e. (dx/ℓ)·πλ²/3 ≪ 1: the tests' grids keep it below 0.3
(λ ≤ 1); the JKR limit takes the exponential law (smooth, no pixel is bistable while
(dx/ℓ)·πλ²/3 < 1).
"""

import math
import os

import numpy as np
import pytest
import warp as wp
from scipy.integrate import quad
from scipy.optimize import brentq

from warptrunc.contact import ContactSolver, CurveSettings, SolverSettings, solve_contact
from warptrunc.contact.adhesion import Adhesion
from warptrunc.contact.hysteresis import force_approach
from warptrunc.contact.memory import memory_bytes, memory_terms
from warptrunc.material import Material

R, E_STAR, WORK = 1e-3, 1e6, 0.05  # sphere radius (m), E* (Pa), work of adhesion (J/m²)
K = 4 * E_STAR / 3
ELL = (math.pi * WORK * R**2 / K) ** (1 / 3)  # Maugis' radius unit (m)
DELTA = (math.pi**2 * WORK**2 * R / K**2) ** (1 / 3)  # Maugis' approach unit (m)
P_UNIT = math.pi * WORK * R  # Maugis' load unit (N)


# --- the reference: Maugis' closed form (Maugis 1992, Johnson & Greenwood 1997's notation) ---


def maugis_state(lam: float, a_bar: float) -> tuple[float, float]:
    """(P̄, Δ̄) of the Maugis–Dugdale sphere at contact radius Ā and transition parameter λ: m
    = c/a from Maugis' equation (1), then P̄ and Δ̄ (his equations (2), (3))."""

    def eq1(m: float) -> float:
        s, t = math.sqrt(m * m - 1), math.atan(math.sqrt(m * m - 1))
        return (
            lam * a_bar**2 / 2 * (s + (m * m - 2) * t)
            + 4 * lam**2 * a_bar / 3 * (s * t - m + 1)
            - 1
        )

    hi = 2.0
    while eq1(hi) < 0:
        hi *= 2
    m = brentq(eq1, 1.0, hi, xtol=1e-14)
    s, t = math.sqrt(m * m - 1), math.atan(math.sqrt(m * m - 1))
    p = a_bar**3 - lam * a_bar**2 * (s + m * m * t)
    d = a_bar**2 - 4 / 3 * lam * a_bar * s
    return p, d


def maugis_pull_off(lam: float) -> float:
    """Maugis' pull-off force P̄ (load control: the minimum of P̄ over the contact radii)."""
    a = np.linspace(0.02, 2.5, 1200)
    p = np.array([maugis_state(lam, x)[0] for x in a])
    return float(p.min())


def maugis_jump_out(lam: float) -> float:
    """The approach Δ̄ where displacement control loses the contact: the minimum of Δ̄."""
    a = np.linspace(0.01, 2.5, 1200)
    return float(min(maugis_state(lam, x)[1] for x in a))


def test_maugis_reference_has_the_jkr_and_dmt_limits():
    # the reference itself, against the two closed forms it joins (1.5πwR, 2πwR)
    assert maugis_pull_off(20.0) == pytest.approx(-1.5, rel=3e-3)
    assert maugis_pull_off(0.01) == pytest.approx(-2.0, rel=3e-3)


# --- the sphere ----------------------------------------------------------------------------


def sphere(n: int, width: float, lam: float, law: str):
    """A paraboloid z = −r²/(2R) on an n² free map ``width``·ℓ wide, and the law of Maugis'
    parameter λ (range h₀ = w/σ₀; for the exponential law ρ with σ_max = w/ρ = σ₀)."""
    sigma0 = lam / 2 * (math.pi * WORK * K**2 / R) ** (1 / 3)
    dx = width * ELL / n
    x = (np.arange(n) - n / 2 + 0.5) * dx
    xx, yy = np.meshgrid(x, x)
    return -(xx**2 + yy**2) / (2 * R), dx, Adhesion(law, work=WORK, range=WORK / sigma0)


def retract(n, width, lam, law, top, step, bottom=-1.3, dtype="float64"):
    """Approach from far to ``top`` (Δ̄), retract by ``step`` until the contact breaks; the
    retraction's rows (Δ̄, P̄, contact pixels) and the solver."""
    h, dx, adh = sphere(n, width, lam, law)
    s = ContactSolver(
        h, dx, E_STAR, settings=SolverSettings(dtype=dtype, adhesion=adh), device="cpu"
    )
    assert adh.maugis_parameter(R, E_STAR) == pytest.approx(lam, rel=1e-12)
    for d in (-0.6, top):
        assert s.solve(d * DELTA).converged
    rows = []
    d = top
    while d > bottom:
        d -= step
        st = s.solve(d * DELTA)
        assert st.converged
        rows.append((d, st.load / P_UNIT, st.n_contact))
        if st.n_contact == 0:
            break
    return np.array(rows), s


# --- the law ---------------------------------------------------------------------------------


@pytest.mark.parametrize("law", ["maugis", "exponential"])
def test_law_energy_is_minus_the_integral_of_its_stress(law):
    a = Adhesion(law, work=0.05, range=2e-9)
    assert a.active and a.peak_stress == pytest.approx(0.05 / 2e-9, rel=1e-15)
    assert float(a.energy(0.0)) == pytest.approx(-0.05, rel=1e-15)  # w = −φ(0)
    for g in (0.0, 0.5e-9, 1.5e-9, 3e-9, 8e-9):
        # φ(g) = ∫_g^∞ (−σ): the stress of the law is the traction it exerts (tensile)
        tail, _ = quad(lambda x: float(a.stress(x)), g, 60e-9, points=[2e-9], limit=200)
        assert float(a.energy(g)) == pytest.approx(tail, rel=1e-9, abs=1e-15)
    assert float(a.stress(-1e-9)) == float(a.stress(0.0))  # a closed gap is 0


def test_law_parameters_against_their_definitions():
    a = Adhesion("maugis", work=0.05, range=2e-9)
    sigma0, k = 0.05 / 2e-9, 4 * 25e6 / 3
    lam = 2 * sigma0 * (1e-5 / (math.pi * 0.05 * k**2)) ** (1 / 3)
    assert a.maugis_parameter(1e-5, 25e6) == pytest.approx(lam, rel=1e-14)
    mu = (1e-5 * 0.05**2 / (25e6**2 * 2e-9**3)) ** (1 / 3)
    assert a.tabor_parameter(1e-5, 25e6) == pytest.approx(mu, rel=1e-14)
    assert not Adhesion().active and Adhesion().peak_stress == 0.0
    with pytest.raises(ValueError, match="work"):
        Adhesion("maugis", work=-1.0)
    with pytest.raises(ValueError, match="law"):
        Adhesion("lennard-jones", work=0.05)
    with pytest.raises(ValueError, match="range"):
        Adhesion("exponential", work=0.05, range=0.0)


# --- w → 0 is the non-adhesive solver --------------------------------------------------------


def _wm_map(n=96):
    from warptrunc.wm import wm_surface

    s = wm_surface(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6, seed=1, device="cpu")
    return np.asarray(s.heights), s.dx


@pytest.mark.parametrize("substrate", ["free", "periodic"])
@pytest.mark.parametrize("dtype", ["float64", "float32"])
@pytest.mark.parametrize("law", ["maugis", "exponential"])
def test_zero_work_is_the_non_adhesive_solver_bit_for_bit(substrate, dtype, law):
    h, dx = _wm_map()
    st = SolverSettings(substrate=substrate, dtype=dtype)
    plain = ContactSolver(h, dx, 70e9, settings=st, device="cpu")
    zero = ContactSolver(
        h,
        dx,
        70e9,
        settings=st.replace(adhesion=Adhesion(law, work=0.0, range=1e-9)),
        device="cpu",
    )
    for kw in ({"depth": 1e-6}, {"depth": 2e-6}, {"load": 5.0}, {"depth": 1e-6}):
        a, b = plain.solve(**kw), zero.solve(**kw)
        da, db = a.to_dict(), b.to_dict()
        assert b.n_adhesion_updates == 1 and b.adhesive_force == 0.0 and b.n_attractive == 0
        for key in da:
            if key != "n_adhesion_updates":
                assert da[key] == db[key], (kw, key)
        for ma, mb in zip(plain.maps(), zero.maps(), strict=True):
            np.testing.assert_array_equal(ma, mb)
        assert plain.punch_stiffness() == zero.punch_stiffness()


def test_adhesion_refusals_name_the_reason():
    h, dx = _wm_map(32)
    law = SolverSettings(adhesion=Adhesion("maugis", work=0.05, range=2e-9))
    with pytest.raises(ValueError, match="hardness"):
        ContactSolver(h, dx, 70e9, hardness=1e9, settings=law, device="cpu")
    with pytest.raises(ValueError, match="secant"):
        ContactSolver(h, dx, 70e9, settings=law.replace(load_control="secant"), device="cpu")
    with pytest.raises(ValueError, match="central difference"):
        solve_contact(
            h, [1e-6], pixel_size=dx, settings=law, curve=CurveSettings(stiffness="central"),
            device="cpu",
        )  # fmt: skip
    with pytest.raises(ValueError, match="one device"):
        memory_bytes((64, 64), adhesion=True, devices=2)
    with pytest.raises(ValueError, match="Adhesion"):
        SolverSettings(adhesion="maugis")
    # a dict of the law's fields (as SolverSettings.to_dict writes it) is the law
    assert SolverSettings(**law.to_dict()) == law
    assert "adhesion" not in SolverSettings().to_dict()


@pytest.mark.parametrize("dtype", ["float64", "float32"])
def test_memory_counts_the_law_and_the_original_heights(dtype):
    item = np.dtype(dtype).itemsize
    for substrate in ("free", "periodic"):
        plain = memory_terms((300, 200), substrate, dtype)
        adh = memory_terms((300, 200), substrate, dtype, adhesion=True)
        assert adh.pop("adhesion") == 2 * 300 * 200 * item
        assert adh == plain
        gap = memory_bytes((300, 200), substrate, dtype, adhesion=True) - memory_bytes(
            (300, 200), substrate, dtype
        )
        assert gap == 2 * 300 * 200 * item


# --- the sphere's pull-off: DMT, Maugis, JKR -------------------------------------------------


def test_pull_off_at_small_lambda_is_dmt():
    # λ = 0.05 (Maugis: −1.981, DMT −2): 128² over 12ℓ (the cohesive zone reaches 5ℓ)
    rows, _ = retract(128, 12.0, 0.05, "maugis", top=0.3, step=0.1)
    p_min = rows[:, 1].min()
    assert p_min == pytest.approx(-2.0, rel=0.02)  # DMT, 2πwR
    assert p_min == pytest.approx(maugis_pull_off(0.05), rel=0.01)


def test_pull_off_and_unloading_at_intermediate_lambda_follow_maugis():
    # λ = 0.5: 128² over 4.5ℓ, (dx/ℓ)·πλ²/3 = 0.009; Maugis' pull-off −1.718
    rows, _ = retract(128, 4.5, 0.5, "maugis", top=0.3, step=0.05)
    assert rows[:, 1].min() == pytest.approx(maugis_pull_off(0.5), rel=0.02)
    # the unloading branch against the closed form at the approaches solved (contact radii
    # from the contact pixels; the load at each Δ̄ from Maugis' curve through those radii)
    a = np.linspace(0.2, 2.0, 600)
    ref = np.array([maugis_state(0.5, x) for x in a])
    stable = a >= a[np.argmin(ref[:, 1])]  # the branch that displacement control follows
    for d, p, n_c in rows:
        if n_c > 200:
            assert p == pytest.approx(np.interp(d, ref[stable, 1], ref[stable, 0]), rel=0.03)


@pytest.mark.slow
def test_pull_off_at_large_tabor_parameter_is_jkr():
    # the exponential law at λ = 5 (Tabor's μ = 4.4): 128² over 4ℓ; JKR 1.5πwR
    adh = sphere(128, 4.0, 5.0, "exponential")[2]
    assert adh.tabor_parameter(R, E_STAR) > 4
    rows, _ = retract(128, 4.0, 5.0, "exponential", top=0.1, step=0.1, bottom=-0.8)
    assert rows[:, 1].min() == pytest.approx(-1.5, rel=0.03)


# --- the force–approach cycle ----------------------------------------------------------------


@pytest.mark.slow
def test_force_approach_cycle_jumps_in_and_out():
    # the exponential law at λ = 3 (μ = 2.7), 64² over 4ℓ: a JKR-like cycle
    h, dx, adh = sphere(64, 4.0, 3.0, "exponential")
    up = np.arange(-1.2, 0.31, 0.15)
    down = np.arange(0.25, -1.21, -0.05)
    c = solve_contact(
        h,
        np.concatenate([up, down]) * DELTA,
        pixel_size=dx,
        material=Material(E=E_STAR, nu=0.0),
        settings=SolverSettings(adhesion=adh),
        curve=CurveSettings(stiffness="none"),
        device="cpu",
    )
    assert c.all_converged
    assert c.settings["adhesion"] == adh.to_dict()
    assert {"adhesive_force_N", "n_attractive", "attractive_area_m2"} <= set(c.to_dict())
    cyc = force_approach(c)
    # jump-in on loading: the surfaces snap together (the load drops) before geometric touch
    assert cyc.jump_in and -1.0 < cyc.jump_in_depth / DELTA < 0.0
    assert cyc.jump_in_load_change / P_UNIT < -1.0
    # jump-out on unloading past Maugis' displacement-controlled limit (−0.92 at λ = 3)
    assert cyc.jump_out and cyc.jump_out_load_change / P_UNIT > 0.5
    assert cyc.jump_out_depth / DELTA == pytest.approx(maugis_jump_out(3.0), abs=0.12)
    # the pull-off force is the cycle's minimum, near JKR; the loop dissipates work
    assert cyc.pull_off_force / P_UNIT == pytest.approx(-1.5, rel=0.05)
    assert cyc.dissipated_work > 0.2 * P_UNIT * DELTA
    # in contact the curve is reversible: loading and unloading rows at the same approach
    n_up = up.size
    for i, d in enumerate(up):
        j = n_up + int(np.argmin(np.abs(down - d)))
        if c.n_contact[i] > 0 and abs(down[j - n_up] - d) < 1e-9:
            assert c.load[i] == pytest.approx(c.load[j], rel=2e-3)
    # attraction outside the repulsive contact: the law's forces there
    assert np.all(c.adhesive_force[c.n_contact > 0] < 0)
    assert np.all(c.attractive_area == c.n_attractive * dx * dx)


def test_load_control_follows_the_displacement_controlled_state():
    # the state reached at an approach, solved again at its load from the same history
    h, dx, adh = sphere(64, 4.0, 0.5, "maugis")
    a = ContactSolver(h, dx, E_STAR, settings=SolverSettings(adhesion=adh), device="cpu")
    b = ContactSolver(h, dx, E_STAR, settings=SolverSettings(adhesion=adh), device="cpu")
    for d in (-0.6, 0.3):
        a.solve(d * DELTA)
        b.solve(d * DELTA)
    ref = a.solve(-0.2 * DELTA)
    st = b.solve(load=ref.load)  # tensile
    assert ref.load < 0 and st.converged
    assert st.load == pytest.approx(ref.load, rel=1e-9)
    assert st.depth == pytest.approx(ref.depth, rel=2e-3)
    assert abs(st.n_contact - ref.n_contact) <= 0.01 * ref.n_contact
    # below what the branch holds there is no equilibrium in contact: not converged
    assert not b.solve(load=3 * ref.load).converged


# --- a rough periodic surface against tamaas -------------------------------------------------


@pytest.mark.parametrize(("work", "tamaas_tol"), [(2e-8, 1e-10), (1e-7, 1e-12)])
def test_rough_periodic_surface_against_tamaas(work, tamaas_tol):
    # tamaas' PolonskyKeerRey in the gap formulation (Rey, Anciaux & Molinari 2017) with its
    # ExponentialAdhesionFunctional, at a mean gap; warptrunc at tamaas' mean pressure. A
    # 256² self-affine map (tamaas' generator, H = 0.8, rms slope 0.01 over L = 1, E* = 1),
    # ρ = 1e-4: w/ρ² = 2 (a convex energy) and 10 (not convex)
    tm = pytest.importorskip("tamaas")
    n = 256
    sp = tm.Isopowerlaw2D()
    sp.q0, sp.q1, sp.q2, sp.hurst = 4, 4, n // 4, 0.8
    gen = tm.SurfaceGeneratorFilter2D([n, n])
    gen.spectrum, gen.random_seed = sp, 1
    h = np.array(gen.buildSurface(), dtype=np.float64)
    h *= 1e-2 / tm.Statistics2D.computeSpectralRMSSlope(h)
    rho = 1e-4
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
    model.E, model.nu = 1.0, 0.0
    peer = tm.PolonskyKeerRey(model, h, tamaas_tol, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
    law = tm.ExponentialAdhesionFunctional(h)
    law.parameters = {"rho": rho, "surface_energy": work}
    peer.addFunctionalTerm(law)
    peer.max_iter = 20000
    peer.dump_freq = 10**9
    peer.solve(1.5e-4)  # the mean gap (m)
    p_ref = np.array(model.traction)
    gap_ref = np.array(model.displacement) - h
    load_ref = float(p_ref.mean())  # N over the unit square
    area_ref = float(np.count_nonzero(gap_ref <= 0.0)) / n**2  # the gap closed: repulsive
    s = ContactSolver(
        h,
        1.0 / n,
        1.0,
        settings=SolverSettings(
            substrate="periodic", adhesion=Adhesion("exponential", work=work, range=rho)
        ),
        device="cpu",
    )
    st = s.solve(load=load_ref)
    assert st.converged and st.n_adhesion_updates > 1
    assert st.contact_area == pytest.approx(area_ref, rel=1e-3)
    assert st.mean_gap == pytest.approx(float(gap_ref.mean()), rel=1e-3)
    assert st.load == pytest.approx(load_ref, rel=1e-3)
    # the adhesion matters at this tolerance: without it the area is more than 1 % off
    plain = ContactSolver(h, 1.0 / n, 1.0, settings=SolverSettings(substrate="periodic"))
    assert abs(plain.solve(load=load_ref).contact_area / area_ref - 1) > 1e-2


# --- CPU against GPU -------------------------------------------------------------------------


@pytest.mark.gpu
@pytest.mark.parametrize("dtype", ["float64", "float32"])
def test_adhesive_solve_on_cuda_equals_the_cpu(dtype):
    want = os.environ.get("WARPTRUNC_TEST_DEVICES")
    if wp.get_cuda_device_count() == 0 or (want and "cuda:0" not in want):
        pytest.skip("needs a CUDA device")
    pytest.importorskip("cupy")
    h, dx, adh = sphere(128, 4.5, 0.5, "maugis")
    out = []
    for dev in ("cpu", "cuda:0"):
        st = SolverSettings(dtype=dtype, adhesion=adh)
        s = ContactSolver(h, dx, E_STAR, settings=st, device=dev)
        states = [s.solve(d * DELTA) for d in (-0.6, 0.3, -0.3)]
        out.append((states, s.maps()))
    (a, (pa, ga)), (b, (pb, gb)) = out
    scale = np.abs(pa).max()
    np.testing.assert_allclose(pb, pa, atol=(1e-9 if dtype == "float64" else 1e-4) * scale)
    tol = 1e-9 if dtype == "float64" else 1e-4
    for x, y in zip(a, b, strict=True):
        assert x.converged and y.converged
        assert y.load == pytest.approx(x.load, rel=tol)
        assert abs(y.n_contact - x.n_contact) <= 2
    np.testing.assert_allclose(gb, ga, atol=tol * np.abs(ga).max())
