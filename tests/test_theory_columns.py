# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The theory columns beside elastic solves (warptrunc.theory.columns) and in the tables of
``bem-check`` and ``compare``: present, finite, at the solve's nominal pressure F/A₀, and equal
to the theories called on their own at that pressure (Persson's and GW's functions, which
tests/test_theory.py checks against quadrature); κ against its definition."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from warptrunc import Material, wm_surface
from warptrunc.selfaffine import SelfAffineSpec, self_affine_surface
from warptrunc.theory import IsotropicPSD, greenwood_williamson, persson_contact
from warptrunc.theory.columns import (
    KAPPA_MAX_AREA_FRACTION,
    THEORY_COLUMNS,
    kappa_record,
    surface_spectrum,
    theory_columns,
)

MAT = Material(E=25e6, nu=0.0)


def test_surface_spectrum_by_kind(device):
    wm = wm_surface(2.5, 100e-6, L=0.25e-3, n=64, Rt=2e-6, seed=3, device=device)
    assert surface_spectrum(wm).source == "weierstrass-mandelbrot"
    sa = self_affine_surface(
        SelfAffineSpec(hurst=0.8, L=100e-6, n=64, rolloff=20e-6, rms_slope=0.2), device=device
    )
    psd = surface_spectrum(sa)
    assert psd.source == "self-affine"
    # the map's own C₀, integrated continuously: its discrete sums give 0.2 exactly, the
    # integral over the band differs by the sampling of the modes (6e-5 at 64²)
    assert psd.slope_rms == pytest.approx(0.2, rel=1e-3)
    from warptrunc import from_heights

    m = from_heights(np.asarray(sa.heights), sa.dx)
    est = surface_spectrum(m, window="none")
    assert est.source == "height map"
    assert est.wavevector[-1] <= est.noise_wavevector * (1 + 1e-12)  # cut at its noise floor
    assert math.isfinite(est.noise_wavevector)


def test_columns_are_the_theories_at_F_over_A0():
    psd = IsotropicPSD.from_self_affine(
        SelfAffineSpec(hurst=0.8, L=100e-6, n=256, rolloff=20e-6, rms_slope=0.3)
    )
    a0 = 1e-8
    load = np.array([0.0, 1e-4, 1e-3, 1e-2]) * MAT.contact_modulus * a0
    area = np.array([0.0, 2e-4, 2e-3, 2e-2]) * a0 * 0.3  # κ = 2·0.3/0.3… by construction
    cols = theory_columns(psd, load, a0, material=MAT, area=area)
    assert set(cols) == set(THEORY_COLUMNS)
    assert all(len(v) == 4 for v in cols.values())
    assert np.isnan(cols["persson_area_m2"][0])  # no load, no pressure
    p = load[1:] / a0
    pc = persson_contact(psd, p, material=MAT)
    gw = greenwood_williamson(psd, p, material=MAT)
    np.testing.assert_allclose(cols["nominal_pressure_Pa"][1:], p, rtol=1e-15)
    np.testing.assert_allclose(cols["persson_area_m2"][1:], pc.area_fraction * a0, rtol=1e-12)
    np.testing.assert_allclose(cols["persson_mean_gap_m"][1:], pc.mean_separation, rtol=1e-12)
    np.testing.assert_allclose(cols["persson_stiffness_N_per_m"][1:], pc.stiffness * a0, rtol=1e-12)
    np.testing.assert_allclose(cols["gw_area_m2"][1:], gw.area_fraction * a0, rtol=1e-12)
    np.testing.assert_allclose(cols["gw_stiffness_N_per_m"][1:], gw.stiffness * a0, rtol=1e-12)
    # κ = (A/A₀) E* h′_rms / p by its definition
    kappa = (area[1:] / a0) * MAT.contact_modulus * psd.slope_rms / p
    np.testing.assert_allclose(cols["bem_kappa"][1:], kappa, rtol=1e-12)
    rec = kappa_record(cols, area, a0)
    small = (area / a0 > 0) & (area / a0 <= KAPPA_MAX_AREA_FRACTION)
    assert rec["n_solves"] == int(small.sum())
    assert rec["bem"] == pytest.approx(float(np.mean(cols["bem_kappa"][small])))
    # Persson's κ at the same p: its small-load limit √(8/π) at these small A/A₀
    assert rec["persson"] == pytest.approx(math.sqrt(8 / math.pi), rel=1e-3)
    assert rec["bgt_limit"] == pytest.approx(math.sqrt(2 * math.pi))


def test_bem_check_carries_the_theory_columns(tmp_path):
    from warptrunc.contact import BemCheckSettings
    from warptrunc.contact.check import bem_check

    s = self_affine_surface(
        SelfAffineSpec(hurst=0.8, L=100e-6, n=64, rolloff=20e-6, rms_slope=0.3), device="cpu"
    )
    from warptrunc.contact import SolverSettings

    res = bem_check(
        s,
        check=BemCheckSettings(fractions=(0.05, 0.1, 0.2), stiffness="barber"),
        material=MAT,
        settings=SolverSettings(substrate="periodic"),
        progress=False,
        device="cpu",
    )
    cols = res.to_dict()
    for k in THEORY_COLUMNS:
        assert k in cols
    for k in ("persson_area_m2", "persson_mean_gap_m", "gw_area_m2", "bem_kappa"):
        assert np.all(np.isfinite(cols[k])), k
    a0 = s.lx * s.ly
    np.testing.assert_allclose(cols["nominal_pressure_Pa"], res.bem_load / a0, rtol=1e-15)
    res.to_csv(tmp_path / "bem.csv")
    res.to_json(tmp_path / "bem.json")
    head = (tmp_path / "bem.csv").read_text().splitlines()[0].split(",")
    assert set(THEORY_COLUMNS) <= set(head)
    d = json.loads((tmp_path / "bem.json").read_text())
    assert d["summary"]["kappa"]["persson_limit"] == pytest.approx(math.sqrt(8 / math.pi))
    assert d["settings"]["theory"]["spectrum"]["source"] == "self-affine"


def test_compare_rows_carry_the_theory_columns(tmp_path):
    pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    from warptrunc.compare import MapStudy, compare_study

    s = wm_surface(2.5, 50e-6, L=0.2e-3, n=64, Rt=2e-6, seed=1, device="cpu")
    rows = compare_study(
        tmp_path / "c",
        MapStudy(s, fractions=(0.1, 0.2)),
        material=MAT,
        progress=False,
        device="cpu",
    )
    for k in (*THEORY_COLUMNS, "bem_mean_gap_m"):
        assert k in rows.columns, k
    for k in ("persson_area_m2", "persson_mean_gap_m", "gw_area_m2", "bem_mean_gap_m"):
        assert np.all(np.isfinite(rows[k].to_numpy(dtype=float))), k
    np.testing.assert_allclose(
        rows["nominal_pressure_Pa"], rows["bem_load_N"] / (s.lx * s.ly), rtol=1e-12
    )
    assert set(rows["spectrum_source"]) == {"weierstrass-mandelbrot"}
