# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The contact-mechanics challenge's problem and its study (warptrunc.compare.challenge).

References, each independent of the code under test: the self-affine generator's own
normalisation (its Warp mode sums) for the NumPy C₀ of :func:`challenge_c0`; the generator's
exact discrete sums for the spectral h′_rms; h5py for the HDF5 file; scipy quadrature of the GW
distributions against the GW closed forms; the load balance ∫σP(σ)dσ = p of the BEM's pressure
map; κ p/(E* h′_rms) at small loads between Persson's and BGT's limits; −Δp/Δū from two more
solves for K.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from warptrunc.compare.challenge import (
    ChallengeSettings,
    challenge_c0,
    challenge_patch_spec,
    challenge_spec,
    challenge_study,
    gw_patch_area_density,
    gw_pressure_density,
    read_challenge_surface,
    spectral_slope_rms,
)
from warptrunc.presets import CHALLENGE, CHALLENGE_MATERIAL
from warptrunc.selfaffine import self_affine_surface


def test_the_preset_is_the_challenges_problem():
    g = CHALLENGE.grid()
    assert (CHALLENGE.hurst, CHALLENGE.L, CHALLENGE.n) == (0.8, 100e-6, 32768)
    assert (CHALLENGE.rolloff, CHALLENGE.short_cutoff, CHALLENGE.rms_slope) == (20e-6, 0.1e-6, 1.0)
    assert math.isclose(g["dx"], 100e-6 / 32768)
    assert math.isclose(CHALLENGE.short_cutoff / g["dx"], 32.768)
    assert CHALLENGE_MATERIAL.contact_modulus == 25e6


def test_c0_is_the_generators_own(device):
    # a 2048² grid holds every mode of the band (|m| ≤ 1000): the generator's Warp sums
    s = self_affine_surface(challenge_spec(2048), device=device)
    assert s.params["slope_rms"] == pytest.approx(1.0, rel=1e-12)
    assert challenge_c0() == pytest.approx(s.params["C0_m4"], rel=1e-12)


def test_coarser_grids_keep_the_spectrum_and_lose_slope(device):
    ref = self_affine_surface(challenge_spec(2048), device=device)
    s = self_affine_surface(challenge_spec(256), device=device)
    spec = challenge_spec(256)
    assert spec.short_cutoff == pytest.approx(2 * 100e-6 / 256, rel=2e-6)
    assert s.params["C0_m4"] == pytest.approx(ref.params["C0_m4"], rel=1e-10)
    # h′² ∝ q_s^(2−2H) between the two cut-offs, about; h_rms set by the roll-off
    expect = (0.1e-6 / spec.short_cutoff) ** (1 - 0.8)
    assert s.params["slope_rms"] == pytest.approx(expect, rel=0.1)
    assert s.params["h_rms_m"] == pytest.approx(ref.params["h_rms_m"], rel=0.01)


def test_the_same_content_on_a_grid_twice_as_fine_is_the_same_surface(device):
    spec = challenge_spec(64)
    a = self_affine_surface(spec, device=device)
    b = self_affine_surface(spec.replace(n=128), device=device)
    assert a.params["C0_m4"] == b.params["C0_m4"]
    np.testing.assert_allclose(b.heights[::2, ::2], a.heights, rtol=0, atol=1e-6 * a.heights.std())


def test_a_patch_at_the_challenges_pixel_has_the_challenges_spectrum(device):
    # the patch's periodogram, mode by mode, against the challenge's C(q) = C₀ (q/q_r)^−2(1+H)
    # (float64 NumPy; the generator draws each mode at its spectrum's amplitude)
    n = 128
    s = self_affine_surface(challenge_patch_spec(n), device=device)
    side = n * CHALLENGE.L / CHALLENGE.n
    assert s.dx == pytest.approx(CHALLENGE.L / CHALLENGE.n, rel=1e-12)
    h = np.asarray(s.heights, dtype=np.float64)
    power = np.abs(np.fft.fft2(h)) ** 2 / n**4  # mean square height per mode (m²)
    m = np.fft.fftfreq(n, 1.0 / n)
    q = 2 * math.pi / side * np.hypot(m[:, None], m[None, :])
    band = (q > 0) & (q <= 2 * math.pi / CHALLENGE.short_cutoff * (1 - 1e-9))
    band &= (np.abs(m)[:, None] < n // 2) & (np.abs(m)[None, :] < n // 2)
    q_r = 2 * math.pi / CHALLENGE.rolloff
    c = challenge_c0() * (np.where(q > 0, q, q_r) / q_r) ** (-2 * (1 + CHALLENGE.hurst))
    expect = c * (2 * math.pi / side) ** 2  # C(q) times the area of one mode in q-space
    assert np.allclose(power[band], expect[band], rtol=1e-4)
    assert power[~band & (q > 0)].max() < 1e-8 * expect[band].min()
    with pytest.raises(ValueError, match="at least 64"):
        challenge_patch_spec(32)


@pytest.mark.parametrize("n", [512, 8192])  # λ_r = 20 µm beyond the patch, and inside it
def test_a_patch_holds_the_challenges_mean_square_height_of_its_modes(n):
    # Σ C(q_m)(2π/L_p)² over the patch's modes (C₀, plateau below q_r, power law above, zero
    # past λ_s; NumPy float64) is the rms height the spec gives the generator
    side = n * CHALLENGE.L / CHALLENGE.n
    k = int(side / CHALLENGE.short_cutoff) + 1
    m = np.arange(-k, k + 1, dtype=np.float64)
    q = 2 * math.pi / side * np.hypot(m[:, None], m[None, :])
    q_r, q_s = 2 * math.pi / CHALLENGE.rolloff, 2 * math.pi / CHALLENGE.short_cutoff
    with np.errstate(divide="ignore"):
        c = challenge_c0() * np.where(q < q_r, 1.0, (q / q_r) ** (-2 * (1 + CHALLENGE.hurst)))
    inside = (q > 0) & (q <= q_s * (1 + 1e-9))
    expect = math.sqrt(float((c[inside] * (2 * math.pi / side) ** 2).sum()))
    assert challenge_patch_spec(n).rms_height == pytest.approx(expect, rel=1e-9)


def test_spec_refuses_content_the_grid_cannot_hold():
    with pytest.raises(ValueError, match="at least the challenge"):
        challenge_spec(4096, short_cutoff=0.05e-6)
    with pytest.raises(ValueError, match="below 2 pixels"):
        challenge_spec(256, short_cutoff=0.2e-6)
    with pytest.raises(ValueError, match="p_min"):
        ChallengeSettings(p_min=0.1, p_max=0.01)


def test_settings_pressures():
    p = ChallengeSettings().pressures(25e6)
    assert p.size == 13
    np.testing.assert_allclose(p / 25e6, np.geomspace(1e-4, 1e-1, 13), rtol=1e-12)


def test_spectral_slope_is_the_generators(device):
    s = self_affine_surface(challenge_spec(128), device=device)
    z = np.asarray(s.heights, dtype=np.float64)
    # float32 heights: round-off of 1e-7 relative
    assert spectral_slope_rms(z, s.dx) == pytest.approx(s.params["slope_rms"], rel=1e-6)


def test_read_challenge_surface_from_hdf5(tmp_path, device):
    h5py = pytest.importorskip("h5py")
    pytest.importorskip("SurfaceTopography")
    s = self_affine_surface(challenge_spec(64), device=device)
    z = np.asarray(s.heights, dtype=np.float64) / s.params["slope_rms"]  # h′_rms = 1
    path = tmp_path / "challenge.h5"
    with h5py.File(path, "w") as f:
        f["surface"] = 37.0 * z.T  # arbitrary units, x first as the challenge's file
    r = read_challenge_surface(path)
    assert (r.nx, r.ny) == (64, 64)
    assert r.dx == pytest.approx(100e-6 / 64)
    assert r.params["periodic"] is True
    assert r.params["height_unit_m"] == pytest.approx(1 / 37.0, rel=1e-6)
    np.testing.assert_allclose(r.heights, z, rtol=0, atol=1e-6 * z.std())
    r2 = read_challenge_surface(path, height_unit=1e-9)
    np.testing.assert_allclose(r2.heights, 37e-9 * z, rtol=0, atol=1e-6 * 37e-9 * z.std())


def test_gw_distributions_integrate_to_gw_closed_forms():
    from scipy.integrate import quad

    from warptrunc.theory import IsotropicPSD, greenwood_williamson, nayak_summits

    psd = IsotropicPSD.from_self_affine(challenge_spec(512))
    e = CHALLENGE_MATERIAL.contact_modulus
    p = 0.01 * e
    gw = greenwood_williamson(psd, p, material=CHALLENGE_MATERIAL)
    sm = nayak_summits(psd)
    d = float(gw.separation[0])
    top = 50 * e  # far past the largest Hertz pressure of any summit that matters
    area = quad(lambda s: gw_pressure_density(sm, d, s, modulus=e), 0, top, limit=400)[0]
    load = quad(lambda s: s * gw_pressure_density(sm, d, s, modulus=e), 0, top, limit=400)[0]
    assert area == pytest.approx(float(gw.area_fraction[0]), rel=1e-6)
    assert load == pytest.approx(p, rel=1e-6)
    a_top = 40 * math.pi * sm.radius * sm.height_std
    count = quad(lambda a: gw_patch_area_density(sm, d, a), 0, a_top, limit=400)[0]
    covered = quad(lambda a: a * gw_patch_area_density(sm, d, a), 0, a_top, limit=400)[0]
    assert count == pytest.approx(float(gw.contact_density[0]), rel=1e-6)
    assert covered == pytest.approx(float(gw.area_fraction[0]), rel=1e-6)


@pytest.fixture(scope="module")
def study():
    # 32² → 64² pixels of the challenge's spectrum cut at 2 pixels of 32², 7 loads
    s = ChallengeSettings(n=32, per_decade=2, p_min=1e-3, p_max=1e-1, reference_pressure=0.03)
    return challenge_study(study=s, device="cpu")


def test_study_columns_present_and_finite(study):
    cols = study.to_dict()
    m = study.pressure.size
    assert all(np.asarray(v).shape == (m,) for v in cols.values())
    for k in (
        "bem_area_fraction",
        "bem_mean_gap_m",
        "bem_stiffness_Pa_per_m",
        "coarse_area_fraction",
        "persson_area_fraction",
        "persson_mean_gap_m",
        "persson_stiffness_Pa_per_m",
        "gw_area_fraction",
        "gw_stiffness_Pa_per_m",
        "bgt_area_fraction",
        "bgt_stiffness_Pa_per_m",
    ):
        assert np.all(np.isfinite(cols[k])), k
    ok = study.truncation_resolved
    assert ok.any()
    assert np.all(np.isfinite(study.truncation_area_fraction[ok]))
    assert study.converged.all()


def test_grid_study_maps_are_the_same_surface(study):
    g = study.grid_study
    assert g["n"] == [32, 64]
    assert g["same_surface_max_difference_over_h_rms"] < 1e-6
    assert g["pixel_m"][1] == pytest.approx(g["pixel_m"][0] / 2)


def test_small_load_area_between_persson_and_twice_bgt(study):
    # A/A₀ = κ p/(E* h′_rms) at small load: κ of numerical contact mechanics is about 2 when
    # resolved (Hyun et al. 2004), above it on coarse grids (patches of a few pixels); it lies
    # above Persson's √(8/π), which underestimates the area, and below 1.5 √(2π) on a grid that
    # resolves λ_s with 4 pixels
    x = study.pressure / (study.contact_modulus * study.slope_rms)
    small = study.area_fraction <= 0.05
    kappa = study.area_fraction[small] / x[small]
    assert np.all(kappa > math.sqrt(8 / math.pi))
    assert np.all(kappa < 1.5 * math.sqrt(2 * math.pi))


def test_stiffness_is_minus_dp_dugap(study, device):
    from warptrunc.contact import CurveSettings, SolverSettings, solve_contact

    i = 3  # a middle load
    p = study.pressure[i]
    fine = self_affine_surface(challenge_spec(32).replace(n=64), device=device)
    a0 = fine.lx * fine.ly
    cc = solve_contact(
        fine,
        loads=[p * 0.97 * a0, p * 1.03 * a0],
        material=CHALLENGE_MATERIAL,
        settings=SolverSettings(substrate="periodic", pentol=1e-12 * fine.heights.std()),
        curve=CurveSettings(stiffness="none"),
        device=device,
    )
    k = -(0.06 * p) / (cc.mean_gap[1] - cc.mean_gap[0])
    # the study's K differentiates over loads a factor 10^(1/2) apart: its second-order
    # difference in ln p is good to about 10 % where ū is near-linear in ln p
    assert study.stiffness[i] == pytest.approx(k, rel=0.1)


def test_distributions_normalised(study):
    d = study.distributions
    pr, ga, pa = d["pressure"], d["gap"], d["patch_area"]
    e = np.asarray(pr["bin_edges_Pa"])
    dens = np.asarray(pr["bem_density_per_Pa"])
    assert (dens * np.diff(e)).sum() == pytest.approx(pr["bem_area_fraction"], rel=1e-12)
    # load balance: the pressure map carries the nominal pressure (bin midpoints: 1/100 width)
    mid = np.asarray(pr["stress_Pa"])
    assert (mid * dens * np.diff(e)).sum() == pytest.approx(d["reference_pressure_Pa"], rel=0.02)
    ue = np.asarray(ga["bin_edges_m"])
    gd = np.asarray(ga["bem_density_per_m"])
    assert (gd * np.diff(ue)).sum() + ga["bem_contact_fraction"] == pytest.approx(1.0, rel=1e-12)
    assert (np.asarray(ga["gap_m"]) * gd * np.diff(ue)).sum() == pytest.approx(
        ga["bem_mean_gap_m"], rel=0.02
    )
    ae = np.asarray(pa["bin_edges_m2"])
    assert (np.asarray(pa["bem_density_per_m4"]) * np.diff(ae)).sum() * study.apparent_area == (
        pytest.approx(pa["bem_count"], rel=1e-12)
    )


def test_record_is_strict_json(study, tmp_path):
    path = study.to_json(tmp_path / "c.json")

    def refuse(v):
        raise AssertionError(f"non-strict JSON constant {v}")

    doc = json.loads(path.read_text(), parse_constant=refuse)
    assert doc["kappa"]["persson_limit"] == pytest.approx(math.sqrt(8 / math.pi))
    assert doc["kappa"]["bgt_limit"] == pytest.approx(math.sqrt(2 * math.pi))
    assert doc["problem"]["source"].startswith("Müser")
    assert set(doc["stiffness_slope"]) >= {"bem", "persson", "gw", "bgt", "truncation"}


def test_challenge_command_writes_its_outputs(tmp_path):
    from warptrunc.cli import main

    out = tmp_path / "c"
    code = main(
        [
            "challenge",
            "--n",
            "16",
            "--per-decade",
            "1",
            "--p-min",
            "1e-2",
            "--no-refine",
            "--no-plot",
            "--no-progress",
            "--device",
            "cpu",
            "--out",
            str(out),
        ]
    )
    assert code == 0
    assert {p.name for p in out.iterdir()} == {"challenge.json", "challenge.csv"}
    doc = json.loads((out / "challenge.json").read_text())
    assert doc["grid_study"] == {}
    assert doc["surface"]["grid"] == [16, 16]
