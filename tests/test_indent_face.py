# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The punch as the experiment had it (issue 38, item 5): a tilted flat and a rough face.

References independent of the code under test: Sneddon's flat punch K = 2E*a and the
rotated flat punch's pressure E*(δ + 2θx)/(π√(a² − r²)), which is positive over the whole
disk iff F = 2E*aδ ≥ 4E*a²θ (full contact); the untilted solve on the same grid (the same
contact set is the same linear problem); the approach of a translated tilted flat,
δ_tilt − δ_flat = tan θ·x_top; the power spectrum of the generated field by numpy's FFT and a
least-squares fit of log C against log q; rms and planes by numpy; the face between its
reference samples by numpy's zero-padded FFT interpolation and by a direct Fourier sum; a read
face by scipy's bilinear interpolation. Small windows on the CPU.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from cli_helpers import assert_refused_in_one_line

import warptrunc
from warptrunc.cli import main
from warptrunc.indent import (
    IndentProtocol,
    PunchFaceSpec,
    indent,
    make_face,
    punch_window,
    run_cycles,
)
from warptrunc.indent.face import self_affine_field
from warptrunc.indent.refine import WindowSource
from warptrunc.material import Material

MAT = Material.against_diamond()  # E* = 73.5 GPa
ES = MAT.contact_modulus


# --- the tilted flat ----------------------------------------------------------------------------


def test_tilt_softens_below_full_contact_and_is_sneddon_once_the_face_touches():
    """A flat tilted by θ = 10⁻³ rad (0.0573°) on a flat half-space, held against rotation.

    Full contact needs F ≥ 4E*a²θ (the rotated punch's edge pressure vanishes there). Below,
    K is lower than the aligned punch's and rises with the load; at 2× and 4× that load every
    disk pixel touches and K equals the aligned solve on the same grid to the solver's
    tolerance (the same contact set is the same linear problem: rtol 10⁻⁸), which is Sneddon's
    2E*a within 1 % (a = 50 pixels: the pixel disk's area and the dx/a discretisation error
    of tests/test_indent.py, < 0.5 % at 50 pixels). The approach from first touch of the
    translated tilted flat exceeds the aligned one by tan θ·x_top (x_top the outermost pixel
    centre in the tilt's direction), to the load tolerance."""
    dx, a_px = 1e-6, 50
    a = a_px * dx
    theta = 1e-3
    z = np.zeros((2 * a_px + 4, 2 * a_px + 4))
    face = make_face(2 * a, PunchFaceSpec(tilt_deg=math.degrees(math.atan(theta))))
    f_full = 4 * ES * a * a * theta
    loads = np.array([0.05, 0.2, 0.5, 2.0, 4.0]) * f_full
    flat = punch_window(z, dx, 2 * a)
    tilted = punch_window(z, dx, 2 * a, face=face)
    r0 = run_cycles(flat, IndentProtocol(peak_loads=loads), MAT, device="cpu")
    rt = run_cycles(tilted, IndentProtocol(peak_loads=loads), MAT, device="cpu")
    assert r0["converged"].all() and rt["converged"].all()
    k0, kt = r0["unloading_stiffness"], rt["unloading_stiffness"]
    partial, full = loads < f_full, loads >= 2 * f_full
    assert np.all(rt["n_contact"][partial] < tilted.n_pixels)
    assert np.all(kt[partial] < 0.9 * k0[partial]) and np.all(np.diff(kt[partial]) > 0)
    np.testing.assert_array_equal(rt["n_contact"][full], tilted.n_pixels)
    np.testing.assert_allclose(kt[full], k0[full], rtol=1e-8)
    np.testing.assert_allclose(k0, 2 * ES * a, rtol=0.01)
    x_top = (a_px - 0.5) * dx  # the pixel centre nearest the +x edge, inside the disk
    np.testing.assert_allclose(
        rt["displacement"][full] - r0["displacement"][full], theta * x_top, rtol=1e-4
    )
    # the face rises toward +x (azimuth 0): first touch on the +x edge
    _, ix = np.unravel_index(
        np.argmax(np.where(tilted.mask, tilted.heights, -np.inf)), tilted.mask.shape
    )
    assert (ix + tilted.origin[1] + 0.5) * dx - tilted.centre[0] == pytest.approx(x_top)


def test_tilt_azimuth_turns_the_face_and_keeps_the_stiffness():
    """The azimuth turns the face about the punch axis: at 90° the face is the 0° one
    transposed (x ↔ y), and on the pixel disk (symmetric under x ↔ y) K is the same."""
    dx, a_px = 1e-6, 30
    z = np.zeros((2 * a_px + 2, 2 * a_px + 2))
    d = 2 * a_px * dx
    w0 = punch_window(z, dx, d, face=make_face(d, PunchFaceSpec(tilt_deg=0.05)))
    w90 = punch_window(
        z, dx, d, face=make_face(d, PunchFaceSpec(tilt_deg=0.05, tilt_azimuth_deg=90.0))
    )
    np.testing.assert_allclose(w90.face_heights, w0.face_heights.T, rtol=0, atol=1e-18)
    tan = math.tan(math.radians(0.05))
    x = (np.arange(w0.mask.shape[1]) + w0.origin[1] + 0.5) * dx - w0.centre[0]
    np.testing.assert_allclose(
        w0.face_heights[w0.mask], np.broadcast_to(tan * x, w0.mask.shape)[w0.mask], rtol=1e-12
    )
    loads = [2e-3]
    at = IndentProtocol(peak_loads=loads)
    k = [run_cycles(w, at, MAT, device="cpu")["unloading_stiffness"][0] for w in (w0, w90)]
    assert k[1] == pytest.approx(k[0], rel=1e-6)


# --- the rough face -----------------------------------------------------------------------------


def _psd_slope(field, period, lam_s, lam_l):
    n = field.shape[0]
    c = np.abs(np.fft.fft2(field)) ** 2
    k = np.fft.fftfreq(n, d=period / n) * 2 * math.pi
    q = np.hypot(k[:, None], k[None, :])
    band = (q >= 2 * math.pi / lam_l) & (q <= 2 * math.pi / lam_s)
    slope = np.polyfit(np.log(q[band]), np.log(c[band]), 1)[0]
    return slope, float(c[~band].max() / c[band].max())


@pytest.mark.parametrize("hurst", [0.8, 0.5])
def test_generated_field_is_self_affine_between_its_cut_offs(hurst):
    """C(q) = |FFT|² of the field, fitted mode by mode (log C against log q, least squares):
    slope −2 − 2H within 0.05 over four seeds (one seed: within 0.12, about 3 standard
    errors of the fit over the 12 808 modes of the band), and no power outside the band."""
    n, period = 256, 1e-3
    lam_s, lam_l = 4 * period / n, period / 4
    slopes = []
    for seed in range(4):
        field, _ = self_affine_field(n, period, hurst, lam_s, lam_l, seed)
        s, outside = _psd_slope(field, period, lam_s, lam_l)
        assert abs(s + 2 + 2 * hurst) < 0.12
        assert outside < 1e-20
        slopes.append(s)
    assert abs(np.mean(slopes) + 2 + 2 * hurst) < 0.05


def _reference(face):
    """The face's reference grid, offsets from the punch centre, and the raw field (numpy)."""
    r = face.info["roughness"]
    n, period = r["reference_grid"], r["period_m"]
    raw, _ = self_affine_field(
        n, period, r["hurst"], r["cutoff_short_m"], r["cutoff_long_m"], tuple(r["seed"])
    )
    u = (np.arange(n) - n // 2) * (period / n)
    return u, raw, n, period


def test_rough_face_has_the_requested_rms_levelled_over_the_disk():
    """Over the disk's points of its reference grid the face has rms R_q exactly and no mean
    plane (numpy lstsq); it is the raw field less its plane, scaled (numpy); sampled at the
    map's pixel under a punch its rms is R_q within 10 % (other points of the same face)."""
    d, rq, px = 500e-6, 0.05e-6, 5e-6
    face = make_face(d, PunchFaceSpec(roughness=rq, seed=3), pixel=px)
    r = face.info["roughness"]
    assert r["hurst"] == 0.8 and r["cutoff_short_m"] == 2 * px and r["cutoff_long_m"] == d
    u, raw, _, _ = _reference(face)
    f = face.heights(u, u)
    x, y = np.meshgrid(u, u)
    disk = x * x + y * y <= (d / 2) ** 2
    assert math.sqrt(np.mean(f[disk] ** 2)) == pytest.approx(rq, rel=1e-12)
    a = np.column_stack([np.ones(disk.sum()), x[disk], y[disk]])
    np.testing.assert_allclose(np.linalg.lstsq(a, f[disk], rcond=None)[0], 0, atol=1e-12 * rq / d)
    plane = np.linalg.lstsq(a, raw[disk], rcond=None)[0]
    lev = raw[disk] - a @ plane
    np.testing.assert_allclose(
        f[disk], lev * rq / math.sqrt(np.mean(lev**2)), rtol=0, atol=1e-9 * rq
    )
    w = punch_window(np.zeros((120, 120)), px, d, face=face)
    rough = w.face_heights[w.mask]
    assert np.sqrt(np.mean(rough**2)) == pytest.approx(rq, rel=0.1)


def test_rough_face_between_its_samples_is_the_band_limited_field():
    """Between its reference samples the face is the field's trigonometric interpolant: at
    half the spacing it equals numpy's zero-padded FFT upsampling, and at arbitrary points a
    direct Fourier sum over every mode (both less the same plane and scale, recovered from the
    face at the reference samples)."""
    d = 200e-6
    face = make_face(d, PunchFaceSpec(roughness=1e-7, seed=1), pixel=5e-6)
    u, raw, n, period = _reference(face)
    f = face.heights(u, u)
    x, y = np.meshgrid(u, u)
    a = np.column_stack([np.ones(n * n), x.ravel(), y.ravel()])
    coef = np.linalg.lstsq(np.column_stack([a, raw.ravel()]), f.ravel(), rcond=None)[0]
    scale, plane = coef[3], coef[:3]  # f = scale·raw + plane, exactly
    np.testing.assert_allclose(f.ravel(), a @ plane + scale * raw.ravel(), rtol=0, atol=1e-9 * 1e-7)
    spec = np.fft.fft2(raw)
    up = np.zeros((2 * n, 2 * n), complex)  # zero-padded spectrum: the interpolant at h/2
    h = n // 2
    for sy in (slice(0, h), slice(-h, None)):
        for sx in (slice(0, h), slice(-h, None)):
            up[sy, sx] = spec[sy, sx]
    fine = np.fft.ifft2(up).real * 4
    u2 = (np.arange(2 * n) - n) * (period / (2 * n))
    x2, y2 = np.meshgrid(u2, u2)
    want = scale * fine + plane[0] + plane[1] * x2 + plane[2] * y2
    np.testing.assert_allclose(face.heights(u2, u2), want, rtol=0, atol=1e-9 * 1e-7)
    rng = np.random.default_rng(0)
    px, py = rng.uniform(-d / 2, d / 2, 7), rng.uniform(-d / 2, d / 2, 5)
    k = np.fft.fftfreq(n, d=1.0 / n)
    X, Y = px + period / 2, py + period / 2
    ex = np.exp(2j * math.pi * np.outer(X, k) / period)
    ey = np.exp(2j * math.pi * np.outer(Y, k) / period)
    direct = (ey @ spec @ ex.T).real / n**2
    want = scale * direct + plane[0] + plane[1] * px[None, :] + plane[2] * py[:, None]
    np.testing.assert_allclose(face.heights(px, py), want, rtol=0, atol=1e-9 * 1e-7)


def test_same_seed_same_face_another_seed_another():
    u = np.linspace(-40e-6, 40e-6, 9)

    def face(seed, index=0):
        return make_face(100e-6, PunchFaceSpec(roughness=5e-8, seed=seed), index=index, pixel=4e-6)

    f0 = face(0).heights(u, u)
    np.testing.assert_array_equal(face(0).heights(u, u), f0)
    assert not np.allclose(face(1).heights(u, u), f0)
    assert not np.allclose(face(0, index=1).heights(u, u), f0)  # the next punch's face


# --- refinement, the run, the record ----------------------------------------------------------


def _wm(n=64, L=0.5e-3, Rt=0.3e-6, seed=1):
    return warptrunc.wm_surface(2.5, 100e-6, L=L, n=n, Rt=Rt, seed=seed, device="cpu")


def test_finer_window_holds_the_same_face_and_the_same_sample():
    """A WM map's punch window at pixel/2 with a tilted rough face: the composite less the
    face is the window without a face (the sample's heights, as generated again), and the
    face at its pixel centres is the face's own definition there: the plane tan θ·x plus the
    rough part, whose coarse and fine samples are points of one function (checked against a
    direct evaluation at the fine centres)."""
    s = _wm()
    d, c = 300e-6, (0.25e-3, 0.24e-3)
    face = make_face(d, PunchFaceSpec(tilt_deg=0.02, roughness=3e-8), pixel=s.dx)
    src = WindowSource(s.heights, (s.dx, s.dy), s.params, device="cpu")
    assert src.refinable
    for k in (1, 2):
        w = src.window(d, c, k, face=face)
        bare = src.window(d, c, k)
        np.testing.assert_array_equal(w.mask, bare.mask)
        np.testing.assert_allclose(w.surface_disk_heights, bare.disk_heights, rtol=0, atol=1e-18)
        p = s.dx / k
        x = (np.arange(w.origin[1], w.origin[1] + w.mask.shape[1]) + 0.5) * p - c[0]
        y = (np.arange(w.origin[0], w.origin[0] + w.mask.shape[0]) + 0.5) * p - c[1]
        xx, _ = np.meshgrid(x, y)
        tilt = math.tan(math.radians(0.02)) * xx
        rough = face.rough.heights(x, y)
        np.testing.assert_allclose(
            w.face_heights[w.mask], (tilt + rough)[w.mask], rtol=0, atol=1e-18
        )
        # the untilted heights (the solver's tolerance) take the plane out exactly
        np.testing.assert_allclose(
            w.untilted_disk_heights, (bare.heights + rough)[w.mask], rtol=0, atol=1e-18
        )


AT = IndentProtocol(punch_diameters=300e-6, peak_loads=(2e-3, 8e-3, 32e-3), placements=1,
                    placement_seed=2, refine_max=2, min_contact_pixels=1)  # fmt: skip
KW = {"device": "cpu", "material": MAT}


def test_indent_records_the_face_and_keeps_truncation_the_samples():
    """With a tilt and a rough face: the CSV has the same columns; truncation (the paper's
    model of the sample) is unchanged where the cells share a pixel; the contact is another
    one; settings record the face, with the defaults it took; the same run twice gives the
    same numbers (the face from its seed on the host)."""
    s = _wm()
    base = indent(s, protocol=AT, **KW)
    face = AT.replace(face=PunchFaceSpec(tilt_deg=0.05, roughness=3e-8, seed=7))
    res = indent(s, protocol=face, **KW)
    a, b = base.to_dict(), res.to_dict()
    assert list(a) == list(b)
    for k in ("truncation_depth_m", "truncation_stiffness_N_per_m"):
        np.testing.assert_array_equal(
            a[k][a["pixel_size_m"] == b["pixel_size_m"]],
            b[k][a["pixel_size_m"] == b["pixel_size_m"]],
        )
    assert not np.array_equal(a["displacement_m"], b["displacement_m"])
    rec = res.settings["punch_face"]
    assert len(rec) == 1 and rec[0]["diameter_m"] == 300e-6 and rec[0]["tilt_deg"] == 0.05
    r = rec[0]["roughness"]
    assert r["rms_m"] == 3e-8 and r["hurst"] == 0.8 and r["seed"] == [7, 0]
    assert r["cutoff_short"].startswith("default") and r["cutoff_short_m"] == pytest.approx(
        2 * s.dx
    )
    assert r["cutoff_long_m"] == 300e-6
    pun = res.settings["punches"][0]
    assert pun["face_Rt_m"] > 300e-6 * math.tan(math.radians(0.05))
    assert base.settings["punch_face"] is None
    assert res.protocol.face.tilt_deg == 0.05
    again = indent(s, protocol=face, **KW).to_dict()
    np.testing.assert_array_equal(
        again["unloading_stiffness_N_per_m"], b["unloading_stiffness_N_per_m"]
    )


def test_a_read_face_is_levelled_and_resampled_bilinearly(tmp_path):
    """A face file: a plane alone is levelled away (the run equals the smooth one); a curved
    face is scipy's bilinear interpolant of its pixel-centre values, less its least-squares
    plane over the disk (numpy), at the window's pixel centres."""
    from scipy.interpolate import RegularGridInterpolator

    from warptrunc.io import read_height_map, write_height_map

    d, c = 100e-6, (0.25e-3, 0.25e-3)
    fx, fy, h = 61, 53, 2.1e-6
    x = (np.arange(fx) - (fx - 1) / 2) * h
    y = (np.arange(fy) - (fy - 1) / 2) * h
    xx, yy = np.meshgrid(x, y)
    plane_file = tmp_path / "plane.npz"
    write_height_map(warptrunc.from_heights(1e-7 + 2e-4 * xx - 1e-4 * yy, h, h), plane_file)
    s = _wm()
    at = AT.replace(punch_diameters=d, refine_max=1)
    smooth = indent(s, protocol=at, **KW).to_dict()
    flat = indent(s, protocol=at.replace(face=PunchFaceSpec(file=plane_file)), **KW).to_dict()
    np.testing.assert_allclose(
        flat["unloading_stiffness_N_per_m"], smooth["unloading_stiffness_N_per_m"], rtol=1e-6
    )
    z = 1e-7 * np.cos(xx / 7e-6) * np.sin(yy / 9e-6 + 0.3) + 3e-9 * xx / h
    curved = tmp_path / "curved.npz"
    write_height_map(warptrunc.from_heights(z, h, h), curved)
    z = np.asarray(read_height_map(curved).heights, np.float64)  # as stored
    from warptrunc.indent.face import punch_faces

    face = punch_faces(PunchFaceSpec(file=str(curved)), (d,), s.dx)[0]
    w = punch_window(s.heights, s.dx, d, c, face=face)
    px = (np.arange(w.origin[1], w.origin[1] + w.mask.shape[1]) + 0.5) * s.dx - c[0]
    py = (np.arange(w.origin[0], w.origin[0] + w.mask.shape[0]) + 0.5) * s.dy - c[1]
    pyy, pxx = np.meshgrid(py, px, indexing="ij")
    inside = w.mask
    interp = RegularGridInterpolator((y, x), z, method="linear")
    vals = interp(np.column_stack([pyy[inside], pxx[inside]]))
    disk = xx * xx + yy * yy <= (d / 2) ** 2
    a = np.column_stack([np.ones(disk.sum()), xx[disk], yy[disk]])
    p = np.linalg.lstsq(a, z[disk], rcond=None)[0]
    want = vals - (p[0] + p[1] * pxx[inside] + p[2] * pyy[inside])
    np.testing.assert_allclose(w.face_heights[inside], want, rtol=0, atol=1e-15)
    small = tmp_path / "small.npz"
    write_height_map(warptrunc.from_heights(z[:20, :20], h, h), small)
    with pytest.raises(ValueError, match=r"face.file must cover the punch disk"):
        indent(s, protocol=at.replace(face=PunchFaceSpec(file=small)), **KW)


@pytest.mark.parametrize(
    ("kw", "match"),
    [
        ({"tilt_deg": 6.0}, r"tilt_deg must be in \[0, 5\]"),
        ({"tilt_deg": -0.1}, r"tilt_deg must be in \[0, 5\]"),
        ({"tilt_azimuth_deg": 360.0}, r"tilt_azimuth_deg must be in \[0, 360\)"),
        ({"roughness": -1e-9}, r"roughness must be in \[0, inf\) m"),
        ({"hurst": 0.0}, r"hurst must be in \(0, 1\]"),
        ({"cutoff_short": 0.0}, r"cutoff_short must be in \(0, inf\) m"),
        ({"roughness": 1e-8, "file": "f.npz"}, r"both give the punch face"),
        ({"file": ""}, r"file must be a path"),
    ],
)
def test_face_refuses_bad_values(kw, match):
    with pytest.raises(ValueError, match=match):
        PunchFaceSpec(**kw)
    with pytest.raises(ValueError, match=r"face must be a warptrunc\.indent\.PunchFaceSpec"):
        IndentProtocol(face=kw)


def test_face_needs_a_band_a_finite_punch_and_the_same_face_to_reuse():
    s = _wm()

    def run(**face):
        return indent(s, protocol=AT.replace(face=PunchFaceSpec(**face)), **KW)

    with pytest.raises(ValueError, match=r"face.cutoff_long .* must exceed face.cutoff_short"):
        run(roughness=1e-8, cutoff_long=5e-6)
    with pytest.raises(ValueError, match=r"needs a finite punch_diameters"):
        indent(
            s, protocol=AT.replace(punch_diameters=None, face=PunchFaceSpec(tilt_deg=0.01)), **KW
        )
    with pytest.raises(ValueError, match=r"face.cutoff_short must be at least"):
        run(roughness=1e-8, cutoff_short=1e-9)
    at = AT.replace(refine_max=1)
    elastic = indent(s, protocol=at, **KW)
    with pytest.raises(ValueError, match=r"reuse was run with face.tilt_deg = 0.0"):
        indent(
            s,
            protocol=at.replace(face=PunchFaceSpec(tilt_deg=0.01)),
            reuse=elastic,
            **{**KW, "material": Material.against_diamond(hardness=1e9)},
        )


# --- the command line ---------------------------------------------------------------------------

CLI = [
    "indent",
    "--n",
    "64",
    "--L",
    "0.4e-3",
    "--Rt",
    "0.3e-6",
    "--punch-diameters",
    "1.5e-4",
    "--peak-loads",
    "1e-3",
    "4e-3",
    "--placements",
    "1",
    "--no-progress",
    "--refine-max",
    "1",
    "--hardness",
    "inf",
    "--no-plot",
    "--accept-unconverged",
]


def test_cli_face_options_reach_the_json(tmp_path, capsys):
    out = tmp_path / "ind"
    assert (
        main(
            [
                *CLI,
                "--face-tilt-deg",
                "0.05",
                "--face-tilt-azimuth-deg",
                "30",
                "--face-roughness",
                "2e-8",
                "--face-hurst",
                "0.6",
                "--out",
                str(out),
            ]
        )
        == 0
    )
    doc = json.loads((out / "indent.json").read_text())
    assert doc["protocol"]["face"]["tilt_deg"] == 0.05 and doc["protocol"]["face"]["hurst"] == 0.6
    face = doc["settings"]["punch_face"][0]
    assert face["tilt_azimuth_deg"] == 30 and face["roughness"]["hurst"] == 0.6
    assert "tilt 0.05°" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("extra", "needles"),
    [
        (["--face-tilt-deg", "9"], ["--face-tilt-deg", "[0, 5]", "'9'"]),
        (["--face-hurst", "1.5"], ["--face-hurst", "(0, 1]", "'1.5'"]),
        (
            ["--face-roughness", "1e-8", "--face-cutoff-long", "1e-6"],
            ["--face-cutoff-long", "--face-cutoff-short", "must exceed"],
        ),
        (
            ["--face-roughness", "1e-8", "--face-file", "x.npz"],
            ["--face-roughness", "file ('x.npz')", "give one"],
        ),
        (["--face-file", "no_such_face.npz"], ["--face-file", "no_such_face.npz"]),
    ],
)
def test_cli_bad_face_input_exits_2_with_the_option_named(tmp_path, capsys, extra, needles):
    assert_refused_in_one_line([*CLI, *extra], tmp_path / "ind", capsys, needles)


# --- a tilt relative to the surface under the punch -------------------------------------------


def _plane_slopes(w, heights):
    """Least-squares slopes (∂z/∂x, ∂z/∂y) of ``heights`` over the window's disk, numpy."""
    iy, ix = np.nonzero(w.mask)
    x = (ix + w.origin[1] + 0.5) * w.pixel_size[0] - w.centre[0]
    y = (iy + w.origin[0] + 0.5) * w.pixel_size[1] - w.centre[1]
    a = np.column_stack([np.ones_like(x), x, y])
    return np.linalg.lstsq(a, heights, rcond=None)[0][1:]


def test_a_local_tilt_is_relative_to_the_sample_plane_under_each_placement():
    """tilt_reference = "local": at every placement the composite (sample + face) has, over the
    disk, the least-squares plane of the tilt θ toward its azimuth; the azimuth turns by
    360°/n from one placement to the next (tilt_azimuths); 0° local aligns the face with the
    surface (its composite plane is flat) while 0° against the map is no face at all; the
    sample's heights, and so truncation, are unchanged; a finer window keeps the same face."""
    s = warptrunc.wm_surface(2.2, 0.5e-3, L=1e-3, n=128, Rt=2e-6, seed=2, device="cpu")
    theta = 0.05
    spec = PunchFaceSpec(tilt_deg=theta, tilt_reference="local", tilt_azimuths=3,
                         tilt_azimuth_deg=10.0)  # fmt: skip
    at = IndentProtocol(punch_diameters=(0.2e-3,), peak_loads=(1e-3,), placements=3,
                        refine_max=1, min_contact_pixels=1, elastic=False, face=spec)  # fmt: skip
    r = indent(s, protocol=at, material=MAT, device="cpu")
    flat = indent(s, protocol=at.replace(face=PunchFaceSpec()), material=MAT, device="cpu")
    src = WindowSource(np.asarray(s.heights), (s.dx, s.dy), s.params, device="cpu")
    t = math.tan(math.radians(theta))
    for j, rec in enumerate(r.settings["punches"]):
        phi = math.radians(10.0 + 120.0 * j)
        assert rec["face_tilt_azimuth_deg"] == pytest.approx(math.degrees(phi))
        w0 = src.window(0.2e-3, tuple(rec["centre_m"]))  # the sample alone
        b, c = _plane_slopes(w0, w0.disk_heights)
        assert rec["local_plane_tilt_deg"] == pytest.approx(
            math.degrees(math.atan(math.hypot(b, c))), rel=1e-6
        )
        from warptrunc.indent.face import make_face, placement_face

        face = placement_face(make_face(0.2e-3, spec), spec, j, w0)
        w = src.window(0.2e-3, tuple(rec["centre_m"]), face=face)
        np.testing.assert_allclose(
            _plane_slopes(w, w.disk_heights), [t * math.cos(phi), t * math.sin(phi)], atol=1e-9
        )
        np.testing.assert_allclose(w.surface_disk_heights, w0.disk_heights, atol=1e-15)
        w2 = src.window(0.2e-3, tuple(rec["centre_m"]), 2, face=w.face)  # the same face finer
        np.testing.assert_allclose(
            _plane_slopes(w2, w2.disk_heights - w2.surface_disk_heights),
            np.array([t * math.cos(phi), t * math.sin(phi)]) - [b, c],
            atol=1e-12,
        )
        level = placement_face(make_face(0.2e-3, spec.replace(tilt_deg=0.0)), spec, j, w0)
        wl = src.window(0.2e-3, tuple(rec["centre_m"]), face=level)
        np.testing.assert_allclose(_plane_slopes(wl, wl.disk_heights), [0, 0], atol=1e-12)
    np.testing.assert_array_equal(r.truncation_stiffness, flat.truncation_stiffness)
    assert make_face(0.2e-3, PunchFaceSpec()) is None
    assert not PunchFaceSpec(tilt_reference="local").is_flat
