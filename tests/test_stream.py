# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Streamed WM truncation against the in-memory path and NumPy counts; bit-identical bands."""

import itertools
import json

import numpy as np
import pytest
from reference import wm_numpy

from warptrunc import resolve_device, truncate
from warptrunc.cli import main
from warptrunc.truncation.stream import (
    as_wm_spec,
    banded_truncation,
    fits_in_memory,
    in_memory_bytes,
    wm_bands,
)
from warptrunc.wm import wm_spec, wm_surface

# (nx, ny): square, ny not a multiple of the bands, wide, tall
GRIDS = [(64, 64), (96, 100), (256, 200), (160, 512)]


def numpy_counts(z, thresholds):
    return np.array([np.count_nonzero(z >= t) for t in thresholds])


@pytest.mark.parametrize("nx,ny", GRIDS, ids=[f"{a}x{b}" for a, b in GRIDS])
@pytest.mark.parametrize("band_rows", [8, 24, 40, None], ids=str)
def test_streamed_counts_equal_in_memory_and_numpy(device, nx, ny, band_rows):
    kw = dict(D=2.4, Wr=100e-6, n=(nx, ny), seed=7)
    s = wm_surface(**kw, device=device)
    ref = truncate(s, 60, max_depth_fraction=0.4, device=device)
    st = banded_truncation(
        as_wm_spec(s.params),
        60,
        max_depth=None,
        max_depth_fraction=0.4,
        band_rows=band_rows,
        device=resolve_device(device),
        progress=False,
    )
    c = st.curve
    public = truncate(
        s.params, 60, max_depth_fraction=0.4, stream=True, band_rows=band_rows, device=device
    )
    np.testing.assert_array_equal(public.n_contact_pixels, c.n_contact_pixels)
    # independent: NumPy counts on the in-memory heights at the streamed thresholds
    np.testing.assert_array_equal(c.n_contact_pixels, numpy_counts(s.heights, c.threshold))
    np.testing.assert_array_equal(c.n_contact_pixels, ref.n_contact_pixels)
    np.testing.assert_array_equal(c.threshold, ref.threshold)
    np.testing.assert_array_equal(c.depth, ref.depth)
    np.testing.assert_array_equal(c.contact_area, ref.contact_area)
    assert (c.z_top, c.Rt, c.n_pixels) == (ref.z_top, ref.Rt, ref.n_pixels)
    assert (c.apparent_area, c.pixel_area) == (ref.apparent_area, ref.pixel_area)
    assert c.z_top == float(s.heights.max())
    assert st.surface == s.to_dict()
    assert st.n_bands == -(-ny // st.band_rows)
    if band_rows is not None:
        align = 128 if device.startswith("cuda") else 8
        assert st.band_rows == max(align, -(-band_rows // align) * align)


@pytest.mark.parametrize("nx,ny", [(120, 90), (64, 300)], ids=["120x90", "64x300"])
@pytest.mark.parametrize("band_rows", [8, 16, 56, 88])
def test_bands_match_float64_numpy(device, nx, ny, band_rows):
    """Each band against the independent float64 NumPy sum of Eq. (4) (``tests/reference.py``)
    on the same rows; with G given (Rt=None) the scale does not depend on the other bands."""
    # 64×300: several bands on CUDA too (bands are rounded up to 128 rows there)
    D, Wr, L, G, seed = 2.6, 80e-6, (1.2e-3, 0.9e-3), 1e-9, 11
    Wc = 2 * max(L[0] / nx, L[1] / ny)
    ref, _ = wm_numpy(D, Wr, L[0], L[1], nx, ny, G=G, Wc=Wc, seed=seed)
    kw = dict(D=D, Wr=Wr, L=L, n=(nx, ny), Rt=None, G=G, seed=seed)
    parts = list(wm_bands(kw, band_rows=band_rows, device=device))
    assert [r0 for r0, _, _ in parts] == sorted({r0 for r0, _, _ in parts})
    assert parts[0][0] == 0 and parts[-1][1] == ny
    assert all(a[1] == b[0] for a, b in itertools.pairwise(parts))  # no gap, no overlap
    for r0, r1, z in parts:
        assert z.dtype == np.float32 and z.shape == (r1 - r0, nx)
        # float32 heights of a float64 sum: 1e-5 of the height range, as tests/test_wm.py
        err = np.abs(z.astype(np.float64) - ref[r0:r1]).max() / np.ptp(ref)
        assert err <= 1e-5, (r0, r1, err)


def test_topothesy_scaling_and_max_depth(device):
    """Rt=None (G given): the scale does not depend on the extremes; z_top and R_t still do."""
    kw = dict(D=2.3, Wr=100e-6, n=(80, 72), Rt=None, G=1e-9, seed=2)
    s = wm_surface(**kw, device=device)
    ref = truncate(s, 40, max_depth=0.25 * s.Rt, device=device)
    c = truncate(kw, 40, max_depth=0.25 * s.Rt, stream=True, band_rows=16, device=device)
    np.testing.assert_array_equal(c.n_contact_pixels, ref.n_contact_pixels)
    np.testing.assert_array_equal(c.n_contact_pixels, numpy_counts(s.heights, c.threshold))
    assert c.Rt == s.Rt


def test_accepts_a_spec_and_a_params_mapping():
    spec = wm_spec(2.5, 100e-6, n=64, seed=5)
    a = truncate(spec, 20, stream=True, band_rows=16, device="cpu")
    b = truncate({"D": 2.5, "Wr": 100e-6, "n": 64, "seed": 5}, 20, stream=True, device="cpu")
    np.testing.assert_array_equal(a.n_contact_pixels, b.n_contact_pixels)
    c = truncate(spec, 20, stream=False, device="cpu")  # generated whole
    d = truncate(spec, 20, device="cpu")  # "auto": a 64² map fits
    np.testing.assert_array_equal(c.n_contact_pixels, a.n_contact_pixels)
    np.testing.assert_array_equal(d.n_contact_pixels, a.n_contact_pixels)


def test_bad_input_is_refused_with_the_parameter():
    spec = wm_spec(2.5, 100e-6, n=64)
    with pytest.raises(ValueError, match="band_rows"):
        truncate(spec, 10, stream=True, band_rows=0, device="cpu")
    with pytest.raises(ValueError, match="band_rows"):
        truncate(spec, 10, stream=True, band_rows=65, device="cpu")
    with pytest.raises(ValueError, match="method='tile'"):
        truncate(wm_spec(2.5, 100e-6, n=64, method="direct"), 10, stream=True, device="cpu")
    with pytest.raises(TypeError, match="spec_or_params"):
        truncate([2.5], 10, device="cpu")
    with pytest.raises(ValueError, match="stream=True"):
        truncate(wm_surface(2.5, 100e-6, n=32, device="cpu"), 10, stream=True)
    with pytest.raises(ValueError, match="stream must be"):
        truncate(spec, 10, stream="yes", device="cpu")


def test_memory_estimate():
    spec = wm_spec(2.5, 100e-6, n=(160, 96))
    dev, host = in_memory_bytes(spec, "cpu")
    assert dev >= 4 * 160 * 96 and host >= 4 * 160 * 96
    assert fits_in_memory(spec, "cpu")
    # 2**20 × 2**20 pixels: 4 TiB of float32, more than any device or host here
    assert not fits_in_memory(wm_spec(2.5, 100e-6, n=2**20, L=1e-2), "cpu")


def _analyze(out, *extra):
    args = [
        "analyze",
        "--n",
        "128",
        "120",
        "--max-depth-fraction",
        "0.3",
        "--increments",
        "50",
        "--no-plot",
        "--device",
        "cpu",
        "--out",
        str(out),
        *extra,
    ]
    assert main(args) == 0


def test_cli_stream_equals_in_memory(tmp_path, capsys):
    _analyze(tmp_path / "mem", "--no-islands")  # a streamed map has no island pass
    _analyze(tmp_path / "str", "--stream", "--band-rows", "24")
    out = capsys.readouterr().out
    assert "streamed: 5 bands of 24 rows" in out
    a = (tmp_path / "mem" / "curve.csv").read_text()
    b = (tmp_path / "str" / "curve.csv").read_text()
    assert a == b
    fa = json.loads((tmp_path / "mem" / "fit.json").read_text())
    fb = json.loads((tmp_path / "str" / "fit.json").read_text())
    assert fa.pop("path") == "in-memory" and fb.pop("path") == "streamed"
    assert fb.pop("streaming") == {"band_rows": 24, "n_bands": 5, "reason": "--stream given"}
    assert fa.pop("provenance")["command"] != fb.pop("provenance")["command"]  # the runs differ
    # a streamed map is never held whole: its slope is the spectrum's, the in-memory map's the
    # finite differences' at the pixel, beside the same spectrum
    sa, sb = fa["surface"].pop("slope"), fb["surface"].pop("slope")
    assert sa["method"] == "finite differences" and sb["method"] == "spectrum"
    assert sb["finite_differences"] is None and sa["spectrum"] == sb["spectrum"]
    assert sb["slope_rms"] == sb["spectrum"]["slope_rms"]
    assert fa == fb


def test_cli_streams_when_the_map_does_not_fit(tmp_path, monkeypatch):
    import warptrunc.truncation.stream

    monkeypatch.setattr(warptrunc.truncation.stream, "fits", lambda spec, device: False)
    _analyze(tmp_path)
    info = json.loads((tmp_path / "fit.json").read_text())
    assert info["path"] == "streamed"
    assert info["streaming"]["reason"] == "the map needs more than half of the free memory"


def test_cli_stream_refuses_an_input_file(tmp_path, capsys):
    z = np.random.default_rng(0).normal(size=(32, 32)).astype(np.float32)
    np.save(tmp_path / "z.npy", z)
    rc = main(
        [
            "analyze",
            "-i",
            str(tmp_path / "z.npy"),
            "--dx",
            "1e-6",
            "--stream",
            "--no-plot",
            "--out",
            str(tmp_path / "o"),
        ]
    )
    assert rc == 2
    assert "--stream applies to generated surfaces" in capsys.readouterr().err


def test_cli_stream_refuses_islands(tmp_path, capsys):
    """The island-resolved model needs the map in memory: --islands with --stream is an error."""
    args = [
        "analyze",
        "--n",
        "64",
        "--stream",
        "--islands",
        "--no-plot",
        "--device",
        "cpu",
        "--out",
        str(tmp_path / "o"),
    ]
    assert main(args) == 2
    assert "--islands needs the map in memory" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()
