# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The self-affine generator (warptrunc.selfaffine): its discrete power spectrum is the one
asked for, its rms height and rms slope are the spectrum's discrete sums (numpy FFT of the map),
the same seed gives the same map on every device, a finer grid of the same content samples the
same surface, and its statistics agree with SurfaceTopography's ``fourier_synthesis``."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from warptrunc.selfaffine import SelfAffineSpec, self_affine_surface

L, N = 1e-4, 256
SPEC = SelfAffineSpec(
    hurst=0.8, L=L, n=N, short_cutoff=4 * L / N, rolloff=L / 4, rms_slope=1.0, seed=3
)


def _spectrum(s):
    """Periodogram |ĥ(q)|²/N⁴·A/(2π)² (m⁴, the PSD of each mode) and |q| (rad/m), float64."""
    z = s.heights.astype(np.float64)
    ny, nx = z.shape
    c = np.abs(np.fft.fft2(z)) ** 2 / (nx * ny) ** 2 * (s.lx * s.ly) / (2 * np.pi) ** 2
    qx = 2 * np.pi * np.fft.fftfreq(nx, s.dx)
    qy = 2 * np.pi * np.fft.fftfreq(ny, s.dy)
    return c, np.hypot(qx[None, :], qy[:, None])


def test_discrete_psd_is_the_requested_one():
    s = self_affine_surface(SPEC, device="cpu")
    c, q = _spectrum(s)
    want = SPEC.psd(q, s.params["C0_m4"])
    on = want > 0
    # float32 heights: the periodogram carries their rounding, ~1e-7·h per pixel
    np.testing.assert_allclose(c[on], want[on], rtol=2e-5)
    assert c[~on].max() < 1e-9 * want[on].max()
    # the shape: flat below the roll-off, q^(−2(1+H)) above, nothing past the short cut-off
    g = SPEC.grid()
    assert np.all(want[(q > 0) & (q < g["q_roll"])] == s.params["C0_m4"])
    assert np.all(want[q > g["q_short"] * (1 + 1e-9)] == 0)


def test_rms_height_and_slope_are_the_spectrum_sums():
    s = self_affine_surface(SPEC, device="cpu")
    c, q = _spectrum(s)
    dq2 = (2 * np.pi) ** 2 / (s.lx * s.ly)
    assert s.params["slope_rms"] == pytest.approx(1.0, rel=1e-12)  # the normalisation asked for
    z = s.heights.astype(np.float64)
    assert math.sqrt(np.mean((z - z.mean()) ** 2)) == pytest.approx(s.params["h_rms_m"], rel=1e-6)
    assert math.sqrt((c * dq2).sum()) == pytest.approx(s.params["h_rms_m"], rel=1e-6)
    assert math.sqrt((q**2 * c * dq2).sum()) == pytest.approx(1.0, rel=1e-6)
    assert abs(z.mean()) < 1e-6 * s.params["h_rms_m"]


def test_rms_height_normalisation():
    s = self_affine_surface(SPEC.replace(rms_slope=None, rms_height=2e-7), device="cpu")
    z = s.heights.astype(np.float64)
    assert z.std() == pytest.approx(2e-7, rel=1e-6)


def test_same_seed_same_surface_on_every_device(device):
    ref = self_affine_surface(SPEC, device="cpu").heights
    z = self_affine_surface(SPEC, device=device).heights
    # one float64 spectrum, inverse FFTs of different libraries: equal to their round-off
    np.testing.assert_allclose(z, ref, rtol=0, atol=1e-6 * np.abs(ref).max())
    other = self_affine_surface(SPEC.replace(seed=4), device="cpu").heights
    assert not np.allclose(other, ref)


def test_a_finer_grid_samples_the_same_content():
    coarse = self_affine_surface(SPEC, device="cpu").heights
    fine = self_affine_surface(SPEC.replace(n=2 * N), device="cpu").heights
    np.testing.assert_allclose(fine[::2, ::2], coarse, rtol=0, atol=1e-6 * np.abs(coarse).max())


def test_bad_parameters_are_refused_with_their_values():
    with pytest.raises(ValueError, match="not both"):
        SelfAffineSpec(rms_height=1e-6, rms_slope=1.0)
    with pytest.raises(ValueError, match="below 2 pixels"):
        SelfAffineSpec(L=L, n=N, short_cutoff=L / N)
    with pytest.raises(ValueError, match="rolloff"):
        SelfAffineSpec(L=L, n=N, rolloff=2 * L)
    with pytest.raises(ValueError, match="hurst"):
        SelfAffineSpec(hurst=1.2)


@pytest.mark.usefixtures("quiet_surfacetopography")
def test_statistics_agree_with_surfacetopography():
    gen = pytest.importorskip("SurfaceTopography.Generation")
    # SurfaceTopography's long_cutoff is the wavelength below which its PSD is flat (our roll-off)
    st = [
        gen.fourier_synthesis(
            (N, N),
            (L, L),
            hurst=0.8,
            rms_slope=1.0,
            short_cutoff=4 * L / N,
            long_cutoff=L / 4,
            rng=np.random.default_rng(k),
        )
        for k in range(8)
    ]
    with warnings.catch_warnings():  # its statistics call deprecated names of its own
        warnings.simplefilter("ignore", DeprecationWarning)
        st_h = np.mean([t.rms_height_from_area() for t in st])
        st_g = np.mean([t.rms_gradient() for t in st])
    from warptrunc.slope import slope_statistics

    ours = [
        slope_statistics(self_affine_surface(SPEC.replace(seed=k), device="cpu"), per_decade=False)
        for k in range(8)
    ]
    # SurfaceTopography draws Rayleigh amplitudes (its PSD is C(q) on average) and sets C₀ from
    # the continuous integral; ours are exact: the means agree to their scatter over 8 maps
    assert np.mean([o.h_rms for o in ours]) == pytest.approx(st_h, rel=0.08)
    assert np.mean([o.slope_rms for o in ours]) == pytest.approx(st_g, rel=0.04)


def test_curvature_is_the_spectrum_sum():
    s = self_affine_surface(SPEC, device="cpu")
    c, q = _spectrum(s)
    dq2 = (2 * np.pi) ** 2 / (s.lx * s.ly)
    got = math.sqrt((q**4 * c * dq2).sum())
    assert got == pytest.approx(s.params["curvature_rms_per_m"], rel=1e-5)
