# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Height-map readers: round trips, malformed files, missing points, measured scans."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import warptrunc
from warptrunc import from_heights
from warptrunc.io import (
    MissingExtraError,
    fill_missing,
    level_plane,
    read_height_map,
    read_scan,
    write_height_map,
)

DATA = Path(__file__).parent / "data"


def _surface(ny=6, nx=9, dx=1e-6, dy=2.5e-6, seed=0):
    z = np.random.default_rng(seed).normal(size=(ny, nx)).astype(np.float32) * 1e-6
    return from_heights(z, dx, dy, D=2.5, note="test")


# --- round trips through the built-in formats --------------------------------------------------


@pytest.mark.parametrize("ext", ["npz", "npy", "csv", "txt", "tsv"])
def test_round_trip_exact(tmp_path, ext):
    s = _surface()
    p = write_height_map(s, tmp_path / f"map.{ext}")
    r = read_height_map(p)
    # float32 written with 9 significant digits reads back bit for bit
    np.testing.assert_array_equal(r.heights, s.heights)
    assert (r.dx, r.dy) == (s.dx, s.dy)
    assert r.heights.shape == (6, 9)  # (ny, nx): non-square map keeps its orientation
    assert r.params["n_missing"] == 0
    if ext in ("npz", "npy"):
        assert r.params["D"] == 2.5 and r.params["note"] == "test"


def test_plain_npy_needs_spacing(tmp_path):
    z = np.arange(12.0).reshape(3, 4)
    np.save(tmp_path / "z.npy", z)
    with pytest.raises(ValueError, match=r"z\.npy.*no pixel spacing.*dx="):
        read_height_map(tmp_path / "z.npy")
    s = read_height_map(tmp_path / "z.npy", dx=2e-6, height_unit=1e-6)
    np.testing.assert_allclose(s.heights, (z * 1e-6).astype(np.float32))
    assert s.dx == s.dy == 2e-6


def test_plain_npz_single_and_named(tmp_path):
    z = np.arange(12.0).reshape(3, 4)
    np.savez(tmp_path / "one.npz", z)  # numpy's arr_0
    np.savez(tmp_path / "named.npz", heights=z, other=np.zeros(3))
    np.savez(tmp_path / "many.npz", a=z, b=z)
    np.savez(tmp_path / "other.npz", whatever=z)  # issue 17: any key was taken as heights
    for name in ("one", "named"):
        s = read_height_map(tmp_path / f"{name}.npz", dx=1.0, dy=3.0)
        np.testing.assert_array_equal(s.heights, z.astype(np.float32))
        assert (s.dx, s.dy) == (1.0, 3.0)
    for name in ("many", "other"):
        with pytest.raises(ValueError, match=rf"{name}\.npz: no height array under a known key"):
            read_height_map(tmp_path / f"{name}.npz", dx=1.0)


def test_text_with_plain_matrix_and_units(tmp_path):
    z = np.arange(20.0).reshape(4, 5)
    np.savetxt(tmp_path / "m.txt", z)
    np.savetxt(tmp_path / "m.csv", z, delimiter=",")
    for f in ("m.txt", "m.csv"):
        s = read_height_map(tmp_path / f, dx=1e-6, dy=2e-6, height_unit=1e-9)
        np.testing.assert_allclose(s.heights, (z * 1e-9).astype(np.float32))
        assert (s.dx, s.dy) == (1e-6, 2e-6)
    with pytest.raises(ValueError, match=r"m\.csv: a text matrix without a 'dx='"):
        read_height_map(tmp_path / "m.csv")


def test_text_header_units(tmp_path):
    p = tmp_path / "h.txt"
    p.write_text("h=2 w=3\npixel size=0.5 um\nheight conversion factor (-> m)=1e-9\n1 2 3\n4 5 6\n")
    s = read_height_map(p)
    np.testing.assert_allclose(s.heights, np.array([[1, 2, 3], [4, 5, 6]], np.float32) * 1e-9)
    assert s.dx == pytest.approx(0.5e-6) and s.dy == pytest.approx(0.5e-6)
    with pytest.raises(ValueError, match="declares its height unit"):
        read_height_map(p, height_unit=1e-6)
    # an explicit spacing overrides the header
    assert read_height_map(p, dx=3e-6).dx == 3e-6


def test_golden_csv():
    """tests/data/golden_4x3.csv: hand-written, see tests/data/README.md."""
    s = read_height_map(DATA / "golden_4x3.csv")
    want = np.array([[0, 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11]], dtype=np.float64) * 1e-6
    np.testing.assert_allclose(s.heights, want.astype(np.float32))
    assert s.dx == pytest.approx(2e-6) and s.dy == pytest.approx(3e-6)
    assert s.lx == pytest.approx(6e-6) and s.ly == pytest.approx(12e-6)


# --- malformed files ----------------------------------------------------------------------------


def test_truncated_text(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("# dx=1e-6 m\n1,2,3\n4,5,6\n7,8\n")
    with pytest.raises(ValueError, match=r"t\.csv: line 4 has 2 values, expected 3"):
        read_height_map(p)


def test_header_shape_mismatch(tmp_path):
    p = tmp_path / "t.txt"
    p.write_text("h=3 w=2\npixel size=1 m\n1 2\n3 4\n")
    with pytest.raises(ValueError, match=r"t\.txt: header says h=3 but the file has 2 rows"):
        read_height_map(p)


def test_text_among_numbers(tmp_path):
    p = tmp_path / "bad.txt"
    p.write_text("1 2 3\n4 five 6\n7 8 9\n")
    with pytest.raises(ValueError, match=r"bad\.txt: line 2, column 2: 'five' is not a number"):
        read_height_map(p, dx=1.0)


def test_no_numbers(tmp_path):
    p = tmp_path / "words.txt"
    p.write_text("hello\nworld\n")
    with pytest.raises(ValueError, match=r"words\.txt: no numeric rows"):
        read_height_map(p, dx=1.0)


def test_binary_as_text(tmp_path):
    p = tmp_path / "bin.txt"
    p.write_bytes(bytes(range(256)))
    with pytest.raises(ValueError, match=r"bin\.txt: not a text file"):
        read_height_map(p, dx=1.0)


@pytest.mark.parametrize("shape", [(7,), (1, 7), (7, 1)])
def test_profile_where_map_needed(tmp_path, shape):
    np.save(tmp_path / "p.npy", np.arange(7.0).reshape(shape))
    with pytest.raises(ValueError, match=r"p\.npy: holds a 1-D profile of 7 points"):
        read_height_map(tmp_path / "p.npy", dx=1.0)
    p = tmp_path / "p.txt"
    np.savetxt(p, np.arange(7.0).reshape(shape))
    with pytest.raises(ValueError, match=r"p\.txt: holds a 1-D profile of 7 points"):
        read_height_map(p, dx=1.0)


def test_wrong_dimensionality(tmp_path):
    np.save(tmp_path / "c.npy", np.zeros((2, 3, 4)))
    with pytest.raises(ValueError, match=r"c\.npy: heights must be a 2-D array.*\(2, 3, 4\)"):
        read_height_map(tmp_path / "c.npy", dx=1.0)


def test_truncated_npz_and_npy(tmp_path):
    s = _surface(32, 32)
    good = warptrunc.write_height_map(s, tmp_path / "s.npz")
    (tmp_path / "cut.npz").write_bytes(good.read_bytes()[:200])
    with pytest.raises(ValueError, match=r"cut\.npz"):
        read_height_map(tmp_path / "cut.npz")
    np.save(tmp_path / "a.npy", np.zeros((32, 32)))
    (tmp_path / "cut.npy").write_bytes((tmp_path / "a.npy").read_bytes()[:300])
    with pytest.raises(ValueError, match=r"cut\.npy: not a readable \.npy"):
        read_height_map(tmp_path / "cut.npy", dx=1.0)


def test_corrupt_sidecar(tmp_path):
    s = _surface()
    p = warptrunc.write_height_map(s, tmp_path / "s.npy")
    p.with_suffix(".json").write_text("{not json")
    with pytest.raises(ValueError, match=r"s\.npy: corrupt warptrunc metadata"):
        read_height_map(p)


def test_missing_file_and_bad_options(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"nope\.csv"):
        read_height_map(tmp_path / "nope.csv", dx=1.0)
    p = write_height_map(_surface(), tmp_path / "s.csv")
    with pytest.raises(ValueError, match="missing must be 'error' or 'fill', got 'ignore'"):
        read_height_map(p, missing="ignore")
    with pytest.raises(ValueError, match="fill must be one of"):
        read_height_map(p, fill="cubic")
    with pytest.raises(ValueError, match=r"dx must be in \(0, inf\) m, got -1"):
        read_height_map(p, dx=-1)
    with pytest.raises(ValueError, match="engine must be one of"):
        read_height_map(p, engine="magic")
    with pytest.raises(ValueError, match="can write"):
        write_height_map(_surface(), tmp_path / "s.xyz")


def test_instrument_format_without_extra(tmp_path, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)  # import now fails
    p = tmp_path / "scan.sur"
    p.write_bytes(b"\0" * 64)
    with pytest.raises(MissingExtraError, match=r"scan\.sur.*pip install SurfaceTopography"):
        read_height_map(p)


# --- missing points and levelling ---------------------------------------------------------------


def test_missing_points_reported_and_filled(tmp_path):
    z = np.arange(30.0).reshape(5, 6)
    z[1, 2] = np.nan
    z[3, 4] = np.nan
    np.save(tmp_path / "m.npy", z)
    with pytest.raises(ValueError, match=r"2 of 30 points are missing.*iy=1, ix=2.*missing='fill'"):
        read_height_map(tmp_path / "m.npy", dx=1.0)
    scan = read_scan(tmp_path / "m.npy", dx=1.0)
    assert scan.n_missing == 2
    np.testing.assert_array_equal(np.argwhere(~scan.valid), [[1, 2], [3, 4]])
    # on a plane z = 6 iy + ix, the harmonic fill (discrete Laplace) is exact
    s = read_height_map(tmp_path / "m.npy", dx=1.0, missing="fill", fill="harmonic")
    np.testing.assert_allclose(s.heights, np.arange(30.0).reshape(5, 6), atol=1e-5)
    assert s.params["n_missing"] == 2 and s.params["missing"] == "fill:harmonic"
    s = read_height_map(tmp_path / "m.npy", dx=1.0, missing="fill", fill="mean")
    assert s.heights[1, 2] == pytest.approx(np.nanmean(z))


def test_fill_nearest_and_isolated_harmonic():
    z = np.zeros((4, 5))
    z[:, 0] = 7.0
    valid = np.zeros_like(z, bool)
    valid[:, 0] = True
    out = fill_missing(z, valid, method="nearest")
    np.testing.assert_array_equal(out, np.full_like(z, 7.0))
    out = fill_missing(np.where(valid, z, np.nan), valid, method="harmonic")
    np.testing.assert_allclose(out, 7.0)  # Laplace with constant boundary data: constant
    with pytest.raises(ValueError, match="every point is missing"):
        fill_missing(z, np.zeros_like(valid))


def test_level_plane():
    ny, nx, dx, dy = 7, 9, 2e-6, 3e-6
    yy, xx = np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")
    rough = np.random.default_rng(1).normal(size=(ny, nx)) * 1e-7
    z = 5e-6 + 0.01 * xx - 0.02 * yy + rough
    out = level_plane(z, dx, dy)
    # least squares: the residual is orthogonal to 1, x and y (normal equations)
    for basis in (np.ones_like(z), xx, yy):
        assert abs(np.sum(out * basis)) < 1e-9 * np.sum(np.abs(z * basis))
    # what was removed is a plane: its second differences vanish
    removed = z - out
    np.testing.assert_allclose(np.diff(removed, 2, axis=1), 0.0, atol=1e-18)
    np.testing.assert_allclose(np.diff(removed, 2, axis=0), 0.0, atol=1e-18)
    # a pure plane levels to zero (float64 round-off relative to 5 µm)
    np.testing.assert_allclose(level_plane(z - rough, dx, dy), 0.0, atol=1e-12 * 5e-6)


# --- measured scans (../shared/data/scans) ------------------------------------------------------


def test_matrix_scan_builtin(scans_dir):
    """The header-carrying matrix is read by the built-in reader with the declared units."""
    p = scans_dir / "matrix-4.txt"
    s = read_height_map(p)
    assert s.heights.shape == (305, 75)  # 305 lines of 75 numbers: ny = 305, nx = 75
    assert s.dx == pytest.approx(3.69862e-7) and s.dy == pytest.approx(3.69862e-7)
    raw = np.loadtxt(p, skiprows=4)
    np.testing.assert_allclose(s.heights, (raw * 2.91818e-8).astype(np.float32), rtol=1e-6)


@pytest.mark.parametrize(
    ("name", "shape", "size", "n_missing"),
    [
        ("x3p-2.x3p", (650, 650), (83e-6, 204e-6), 0),
        ("sur-2.sur", (484, 563), (1.96e-3, 1.69e-3), 117),
        ("top-1.top", (256, 256), (600e-9, 600e-9), 0),
        ("matrix-4.txt", (305, 75), (27.7e-6, 112.8e-6), 0),
    ],
)
def test_instrument_scans(scans_dir, name, shape, size, n_missing):
    """Sizes and missing counts from the scans' README (read independently)."""
    pytest.importorskip("SurfaceTopography")
    engine = "surfacetopography" if name.endswith(".txt") else "auto"
    scan = read_scan(scans_dir / name, engine=engine)
    assert scan.shape == shape
    lx, ly = scan.shape[1] * scan.dx, scan.shape[0] * scan.dy
    np.testing.assert_allclose((lx, ly), size, rtol=6e-3)  # README rounds to 3 digits
    assert scan.n_missing == n_missing
    json.dumps(scan.to_dict())
    if n_missing:
        with pytest.raises(ValueError, match=rf"{name}: {n_missing} of .* missing"):
            scan.to_surface()
        s = scan.to_surface(missing="fill", level=True)
        assert s.params["n_missing"] == n_missing
    else:
        s = scan.to_surface(level=True)
    assert np.isfinite(s.heights).all()
    # heights of real scans are far below a millimetre: units were converted to metres
    assert 0 < s.Rt < 1e-4


def test_matrix_scan_transposition_matches_surfacetopography(scans_dir):
    pytest.importorskip("SurfaceTopography")
    p = scans_dir / "matrix-4.txt"
    a = read_scan(p)
    b = read_scan(p, engine="surfacetopography")
    np.testing.assert_allclose(a.heights, b.heights, rtol=1e-12)
    assert (a.dx, a.dy) == pytest.approx((b.dx, b.dy))


def test_malformed_instrument_file(tmp_path):
    pytest.importorskip("SurfaceTopography")
    p = tmp_path / "broken.sur"
    p.write_bytes(b"not a sur file at all" * 10)
    with pytest.raises(ValueError, match=r"broken\.sur: cannot read"):
        read_height_map(p)
