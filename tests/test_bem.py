# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic BEM cross-check (warptrunc.contact.check): Hertz, the truncation closed form, a WM
surface, with warptrunc's solver (default) and ContactMechanics' (the ``bem`` extra).

The ContactMechanics cases skip cleanly without the extra, except the test of the message that
names it. The solver itself is tested in test_contact.py.
"""

from __future__ import annotations

import builtins
import json
import math

import numpy as np
import pytest

from warptrunc.contact import BemCheckSettings, SolverSettings
from warptrunc.contact import check as bem
from warptrunc.stiffness import Material
from warptrunc.surface import from_heights
from warptrunc.wm import wm_surface

MATERIAL = Material(E=70e9, nu=0.33)


def _needs_bem():
    pytest.importorskip("ContactMechanics")
    pytest.importorskip("SurfaceTopography")


def _sphere(n: int, L: float, R: float):
    """Spherical cap z = √(R² − r²) − R on an n² grid of side L (m), apex at the centre."""
    dx = L / n
    x = (np.arange(n) + 0.5) * dx - L / 2
    X, Y = np.meshgrid(x, x)
    return from_heights(np.sqrt(R**2 - X**2 - Y**2) - R, dx)


@pytest.fixture(scope="module", params=["warptrunc", "contactmechanics"])
def hertz(request):
    """One sphere (R = 50 mm) on 128² pixels of 7.8 µm; approaches give a = 20–35 pixels."""
    if request.param == "contactmechanics":
        _needs_bem()
    n, L, R = 128, 1e-3, 0.05
    s = _sphere(n, L, R)
    # a = √(Rδ) = √f · L/2 for δ = f·(L/2)²/R: contact radius 20, 29 and 35 pixels
    depths = np.array([0.1, 0.2, 0.3]) * (L / 2) ** 2 / R
    check = BemCheckSettings(depths=depths, solver=request.param)
    res = bem.bem_check(s, check=check, material=MATERIAL, progress=False, device="cpu")
    return s, R, res


def test_hertz_load_area_stiffness(hertz):
    """BEM against Hertz: F = (4/3)E*R^½δ^{3/2}, a = √(Rδ), k = 2E*a.

    Tolerances: pressure is piecewise constant on pixels and the contact edge is resolved to a
    pixel, so the contact-pixel area is off by at most a band of half a pixel around the rim,
    a relative error ≲ dx/a = 5 % at a = 20 dx (allowed: 5 %). The load and its derivative
    integrate the pressure, whose √-profile at the rim makes the error of order (dx/a)^{3/2}
    ≈ 1 % (allowed: 2 %). A sphere with a/R ≤ 0.006 differs from Hertz's paraboloid by
    O((a/R)²), negligible here.
    """
    _, R, res = hertz
    e = MATERIAL.contact_modulus
    d = res.depth
    assert res.all_converged
    assert not res.edge_contact.any()
    np.testing.assert_allclose(res.bem_load, 4 / 3 * e * math.sqrt(R) * d**1.5, rtol=0.02)
    np.testing.assert_allclose(res.bem_stiffness, 2 * e * np.sqrt(R * d), rtol=0.02)
    np.testing.assert_allclose(res.bem_area, math.pi * R * d, rtol=0.05)


def test_truncation_closed_form_and_ratio_two(hertz):
    """Truncation: a' = π(2Rδ − δ²) (pixel count, same 5 % rim bound); a'/a_E ≈ 2 (§2.1).

    Truncation formulas give k' = (2/√π)E*√a' = 2√2·E*√(Rδ) = √2·k_Hertz and hence, integrated,
    F' = √2·F_Hertz: the truncation side must show that ratio against the BEM.
    """
    _, R, res = hertz
    d = res.depth
    np.testing.assert_allclose(res.trunc_area, math.pi * (2 * R * d - d**2), rtol=0.05)
    np.testing.assert_allclose(res.area_ratio, 2.0, rtol=0.08)  # two 5 % pixel-rim errors
    e = MATERIAL.contact_modulus
    np.testing.assert_allclose(
        res.trunc_stiffness, 2 / math.sqrt(math.pi) * e * np.sqrt(res.trunc_area), rtol=1e-12
    )
    np.testing.assert_allclose(res.stiffness_ratio, math.sqrt(2), rtol=0.05)


@pytest.fixture(scope="module", params=["warptrunc", "contactmechanics"])
def wm_small(request):
    if request.param == "contactmechanics":
        _needs_bem()
    s = wm_surface(2.5, 100e-6, L=0.25e-3, n=64, Rt=2e-6, seed=3, device="cpu")
    check = BemCheckSettings(fractions=[0.05, 0.1, 0.2, 0.3, 0.4], solver=request.param)
    res = bem.bem_check(s, check=check, material=MATERIAL, progress=False, device="cpu")
    return s, res


def test_wm_monotone_and_converged(wm_small):
    s, res = wm_small
    assert res.all_converged, res.settings["solves"]
    assert np.all(np.diff(res.bem_load) > 0)
    assert np.all(np.diff(res.bem_area) >= 0)
    assert np.all(res.bem_stiffness > 0)
    # the real (elastic) area never exceeds the truncated one on a rough surface (§2.1)
    assert np.all(res.area_ratio >= 1.0)
    # the truncation side is the `analyze` formula: k' = (2/√π)·E*·√A'
    e = MATERIAL.contact_modulus
    np.testing.assert_allclose(
        res.trunc_stiffness, 2 / math.sqrt(math.pi) * e * np.sqrt(res.trunc_area)
    )
    z = s.heights
    n_ref = [np.count_nonzero(z >= np.float32(z.max() - v)) for v in res.depth]
    np.testing.assert_array_equal(res.trunc_area, np.array(n_ref) * s.pixel_area)


def test_outputs(wm_small, tmp_path):
    _, res = wm_small
    res.to_csv(tmp_path / "bem.csv")
    res.to_json(tmp_path / "bem.json")
    head = (tmp_path / "bem.csv").read_text().splitlines()[0].split(",")
    assert {"depth_m", "bem_load_N", "bem_area_m2", "bem_stiffness_N_per_m", "trunc_load_N"} <= set(
        head
    )
    d = json.loads((tmp_path / "bem.json").read_text())
    if d["settings"]["solver"] == "contactmechanics":
        assert d["settings"]["half_space"] == "FreeFFTElasticHalfSpace"
    assert d["settings"]["contact_modulus_Pa"] == pytest.approx(MATERIAL.contact_modulus)
    assert len(d["settings"]["solves"]) == 3 * res.depth.size
    assert d["summary"]["all_converged"] is True


@pytest.mark.parametrize("solver", ["warptrunc", "contactmechanics"])
def test_cli_writes_files(tmp_path, solver):
    if solver == "contactmechanics":
        _needs_bem()
    from warptrunc.cli import main

    out = tmp_path / "b"
    rc = main(
        [
            "bem-check",
            "--n",
            "48",
            "--L",
            "2e-4",
            "--Rt",
            "1e-6",
            "--fractions",
            "0.1",
            "0.3",
            "--device",
            "cpu",
            "--no-progress",
            "--solver",
            solver,
            "--out",
            str(out),
        ]
    )
    assert rc == 0
    assert {p.name for p in out.iterdir()} == {"bem.csv", "bem.json", "bem.png"}
    assert json.loads((out / "bem.json").read_text())["settings"]["solver"] == solver


def test_cli_exit_code_when_not_converged(tmp_path, capsys):
    """--maxiter 1 cannot converge: the files are written, the exit status is 3, and 0 with
    --accept-unconverged."""
    from warptrunc.cli import main

    args = [
        "bem-check",
        "--n",
        "32",
        "--L",
        "2e-4",
        "--Rt",
        "1e-6",
        "--fractions",
        "0.3",
        "--device",
        "cpu",
        "--no-progress",
        "--no-plot",
        "--maxiter",
        "1",
    ]
    assert main([*args, "--out", str(tmp_path / "a")]) == 3
    assert "not every solve converged" in capsys.readouterr().err
    d = json.loads((tmp_path / "a" / "bem.json").read_text())
    assert d["summary"]["all_converged"] is False
    assert main([*args, "--accept-unconverged", "--out", str(tmp_path / "b")]) == 0


@pytest.mark.parametrize("solver", ["warptrunc", "contactmechanics"])
def test_not_converged_is_flagged(solver):
    """maxiter = 1 cannot converge on a WM surface: every row must say so."""
    if solver == "contactmechanics":
        _needs_bem()
    s = wm_surface(2.5, 100e-6, L=0.25e-3, n=32, Rt=2e-6, seed=1, device="cpu")
    res = bem.bem_check(
        s,
        check=BemCheckSettings(fractions=[0.3], solver=solver),
        settings=SolverSettings(maxiter=1),
        progress=False,
        device="cpu",
    )
    assert not res.converged.any()
    assert res.summary()["n_not_converged"] == 1
    assert not any(x["success"] for x in res.settings["solves"])


def test_bad_input():
    s = wm_surface(2.5, 100e-6, L=0.25e-3, n=32, Rt=2e-6, seed=1, device="cpu")
    with pytest.raises(ValueError, match=r"fractions\[0\] must be in \(0, 1\)"):
        BemCheckSettings(fractions=[1.5])
    with pytest.raises(ValueError, match="increase strictly"):
        BemCheckSettings(fractions=[0.3, 0.2])
    with pytest.raises(ValueError, match="give one"):
        BemCheckSettings(fractions=[0.1], depths=[1e-7])
    with pytest.raises(ValueError, match="substrate must be"):
        SolverSettings(substrate="rigid")
    with pytest.raises(ValueError, match="solver must be one of"):
        BemCheckSettings(solver="fenics")
    with pytest.raises(ValueError, match="barber needs solver warptrunc"):
        BemCheckSettings(stiffness="barber", solver="contactmechanics")
    with pytest.raises(ValueError, match=r"depths must be in \(0, R_t\)"):
        bem.bem_check(s, check=BemCheckSettings(depths=[1e-6, 3e-6]), progress=False, device="cpu")


def test_missing_extra_names_it(monkeypatch, capsys):
    real_import = builtins.__import__

    def fake(name, *a, **k):
        if name.startswith("ContactMechanics"):
            raise ImportError(f"No module named {name!r}")
        return real_import(name, *a, **k)

    monkeypatch.setattr(builtins, "__import__", fake)
    with pytest.raises(ImportError, match=r'pip install "warptrunc\[bem\]"'):
        bem.require_bem()
    from warptrunc.cli import main

    assert main(["bem-check", "--n", "16", "--solver", "contactmechanics", "--out", "unused"]) == 2
    assert "warptrunc[bem]" in capsys.readouterr().err


@pytest.mark.parametrize("solver", ["warptrunc", "contactmechanics"])
def test_periodic_westergaard(solver):
    """Periodic substrate on a y-constant cosine z = h₀cos(2πx/λ): Westergaard's partial contact.

    Mean pressure against contact width 2a (Johnson 1985, §13.2): p̄ = (πE*h₀/λ)·sin²(πa/λ).
    This relation does not involve δ (the periodic half-space's q = 0 mode is a convention).
    The width is known to a pixel, so p̄ is allowed the error of a ± dx/2 shift of a,
    (π·dx/λ)·cot(πa/λ), plus 1 %.
    """
    if solver == "contactmechanics":
        _needs_bem()
    n, lam, h0 = 128, 1e-4, 1e-7
    dx = lam / n
    x = (np.arange(n) + 0.5) * dx
    s = from_heights(np.tile(h0 * np.cos(2 * np.pi * x / lam), (4, 1)), dx)
    res = bem.bem_check(
        s,
        check=BemCheckSettings(fractions=[0.2, 0.4], solver=solver),
        material=MATERIAL,
        settings=SolverSettings(substrate="periodic"),
        progress=False,
        device="cpu",
    )
    if solver == "contactmechanics":
        assert res.settings["half_space"] == "PeriodicFFTElasticHalfSpace"
    assert res.all_converged
    a = res.bem_area / s.apparent_area * lam / 2
    p_mean = res.bem_load / s.apparent_area
    p_ref = math.pi * MATERIAL.contact_modulus * h0 / lam * np.sin(np.pi * a / lam) ** 2
    tol = math.pi * dx / lam / np.tan(np.pi * a / lam) + 0.01
    assert np.all(np.abs(p_mean / p_ref - 1) <= tol), (p_mean / p_ref, tol)
