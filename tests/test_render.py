# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""3-D pictures (pyvista, off-screen), block down-sampling of contact masks, and VTK export.

References are independent of the code under test: contact masks from
``numpy: z >= float32(z_top − ω)``, block pooling by padding and reshaping, first-contact
indices by counting thresholds, and the pixels of the top view predicted from the geometry of
an orthographic camera. Tests that draw need pyvista and skip cleanly without it.
"""

import json
import subprocess
import sys

import numpy as np
import pytest

from warptrunc import from_heights, truncate
from warptrunc.io.vtk import export_vtk
from warptrunc.render import (
    AnimationSettings,
    RenderSettings,
    auto_exaggeration,
    contact_masks,
    pool_blocks,
)
from warptrunc.wm import wm_surface


def _ref_pool(a, f, how):
    """Pooling by padding to a multiple of f and reshaping (the padding never wins)."""
    ny, nx = a.shape
    my, mx = -(-ny // f), -(-nx // f)
    if how == "mean":
        p = np.full((my * f, mx * f), np.nan)
        p[:ny, :nx] = a
        return np.nanmean(p.reshape(my, f, mx, f), axis=(1, 3))
    fill = {"max": np.iinfo(np.int64).min, "min": np.iinfo(np.int64).max}[how]
    p = np.full((my * f, mx * f), fill, dtype=np.int64)
    p[:ny, :nx] = a
    r = p.reshape(my, f, mx, f)
    return r.max(axis=(1, 3)) if how == "max" else r.min(axis=(1, 3))


def _ref_mask(z, depth):
    return z >= np.float32(np.float64(z.max()) - depth)


@pytest.fixture(scope="module")
def surf128():
    return wm_surface(2.5, 100e-6, n=128, L=1e-3, Rt=10e-6, seed=1, device="cpu")


# --- down-sampling (no pyvista needed) ----------------------------------------------------------


@pytest.mark.parametrize("shape, f", [((67, 45), 4), ((64, 64), 8), ((50, 31), 7), ((9, 5), 1)])
def test_pool_blocks_matches_padded_reshape(shape, f):
    rng = np.random.default_rng(3)
    mask = rng.random(shape) < 0.03
    idx = rng.integers(0, 50, shape).astype(np.int32)
    z = rng.standard_normal(shape).astype(np.float32)
    pooled = pool_blocks(mask, f, "max")
    np.testing.assert_array_equal(pooled, _ref_pool(mask.astype(np.int64), f, "max").astype(bool))
    np.testing.assert_array_equal(pool_blocks(idx, f, "min"), _ref_pool(idx, f, "min"))
    np.testing.assert_allclose(pool_blocks(z, f, "mean"), _ref_pool(z, f, "mean"), rtol=1e-12)


def test_downsampled_mask_keeps_every_contact_pixel():
    rng = np.random.default_rng(5)
    mask = rng.random((203, 157)) < 0.002  # sparse single pixels: the case averaging would lose
    f = 10
    pooled = pool_blocks(mask, f, "max")
    iy, ix = np.nonzero(mask)
    assert iy.size > 0
    assert pooled[iy // f, ix // f].all()  # every contact pixel's block is red
    # and no block is red without a contact pixel in it
    by, bx = np.nonzero(pooled)
    assert all(
        mask[y * f : (y + 1) * f, x * f : (x + 1) * f].any() for y, x in zip(by, bx, strict=True)
    )


def test_contact_masks_match_numpy_at_full_and_block_resolution(device):
    s = wm_surface(2.3, 100e-6, n=(80, 96), L=(1e-3, 1.2e-3), Rt=5e-6, seed=2, device="cpu")
    depths = np.array([0.3, 0.05, 0.2]) * s.Rt  # any order
    for f in (1, 3):
        got = contact_masks(s, depths, downsample=f, device=device)
        for k, d in enumerate(depths):
            ref = _ref_mask(s.heights, d)
            np.testing.assert_array_equal(got[k], _ref_pool(ref.astype(np.int64), f, "max") > 0)


def test_auto_exaggeration_is_1_2_5_and_draws_rt_near_a_tenth_of_the_side():
    for Rt in (1e-6, 3e-6, 10e-6, 10e-6 * (1 + 1e-7), 40e-6):
        z = np.zeros((8, 8), np.float32)
        z[0, 0] = Rt
        s = from_heights(z, 1e-3 / 8)
        ve = auto_exaggeration(s)
        mant = ve / 10 ** np.floor(np.log10(ve))
        assert np.isclose(mant, [1, 2, 5]).any()
        assert ve * Rt <= 0.1 * 1e-3 * (1 + 1e-6)  # never more than a tenth of the side
        assert 2.5 * ve * Rt > 0.1 * 1e-3  # and within one 1-2-5 step of it
    assert auto_exaggeration(from_heights(np.eye(4, dtype=np.float32), 1e-6)) == 1.0  # rough


# --- VTK export (read back independently) -------------------------------------------------------


def _ref_index(z, depth):
    t = (np.float64(z.max()) - depth).astype(np.float32)
    # thresholds are non-increasing: the first k with z >= t[k] is the number of t[k] > z
    return (t[None, :] > z.ravel()[:, None]).sum(axis=1)


def _read_vti_raw(path):
    """Parse our raw-appended .vti with NumPy alone (header: UInt64 byte counts)."""
    data = path.read_bytes()
    head, _, rest = data.partition(b'<AppendedData encoding="raw">')
    start = rest.index(b"_") + 1
    names = [n.split(b'"')[0].decode() for n in head.split(b'Name="')[1:]]
    types = [t.split(b'"')[0].decode() for t in head.split(b'DataArray type="')[1:]]
    dt = {"Float32": "<f4", "Float64": "<f8", "Int32": "<i4"}
    out, pos = {}, start
    for name, ty in zip(names, types, strict=True):
        nbytes = int(np.frombuffer(rest[pos : pos + 8], "<u8")[0])
        out[name] = np.frombuffer(rest[pos + 8 : pos + 8 + nbytes], dt[ty])
        pos += 8 + nbytes
    return head.decode(), out


def test_vti_export_parsed_with_numpy(tmp_path, device):
    s = wm_surface(2.5, 100e-6, n=(48, 32), L=(1e-3, 0.75e-3), Rt=10e-6, seed=1, device="cpu")
    p = export_vtk(s, tmp_path / "s.vti", n_increments=20, max_depth_fraction=0.5, device=device)
    head, arr = _read_vti_raw(p)
    assert 'WholeExtent="0 47 0 31 0 0"' in head
    assert f'Spacing="{s.dx!r} {s.dy!r}' in head
    z = s.heights
    np.testing.assert_array_equal(arr["height"], z.ravel())  # C-order ravel: x fastest
    depth = np.arange(21) * (0.5 * s.Rt / 20)
    ref = _ref_index(z, depth)
    np.testing.assert_array_equal(arr["contact_index"], ref)
    ref_depth = np.where(ref <= 20, depth[np.minimum(ref, 20)], np.nan)
    np.testing.assert_array_equal(arr["first_contact_depth"], ref_depth)
    assert np.isnan(arr["first_contact_depth"]).any()  # pixels deeper than 0.5 R_t never touch


@pytest.mark.parametrize("ext", ["vti", "vtk"])
def test_vtk_export_read_by_pyvista_point_order(tmp_path, ext):
    pv = pytest.importorskip("pyvista")
    s = wm_surface(2.5, 100e-6, n=(24, 16), L=(1e-3, 0.5e-3), Rt=10e-6, seed=4, device="cpu")
    g = pv.read(export_vtk(s, tmp_path / f"s.{ext}", n_increments=10, device="cpu"))
    assert isinstance(g, pv.ImageData)
    assert tuple(g.dimensions) == (24, 16, 1)
    z = s.heights
    for iy, ix in [(0, 0), (0, 23), (15, 0), (7, 11)]:
        i = ix + 24 * iy  # ImageData point id, x fastest
        np.testing.assert_allclose(g.points[i][:2], [ix * s.dx, iy * s.dy], rtol=1e-12)
        assert g.point_data["height"][i] == z[iy, ix]
    np.testing.assert_array_equal(g.point_data["height"], z.ravel())
    # up to ω = R_t every point touches; the lowest at the last increment
    fcd = np.asarray(g.point_data["first_contact_depth"])
    assert np.isfinite(fcd).all() and fcd.max() == pytest.approx(s.Rt, rel=1e-12)
    np.testing.assert_array_equal(
        g.point_data["contact_index"], _ref_index(z, np.arange(11) * (s.Rt / 10))
    )


def test_vtk_export_rejects_unknown_suffix(tmp_path, surf128):
    with pytest.raises(ValueError, match=r"\.vti or \.vtk"):
        export_vtk(surf128, tmp_path / "s.vtu")


# --- pictures (pyvista, off-screen) -------------------------------------------------------------


def _red(img):
    img = img.astype(int)
    return (img[..., 0] - img[..., 1] > 100) & (img[..., 0] - img[..., 2] > 100)


def test_missing_pyvista_gives_clear_message(monkeypatch, surf128):
    from warptrunc import render

    monkeypatch.setitem(sys.modules, "pyvista", None)  # import pyvista → ImportError
    with pytest.raises(ImportError, match="pip install pyvista"):
        render.render_truncation(
            surf128, settings=RenderSettings(depth_fractions=(0.1,)), device="cpu"
        )


def test_top_view_red_pixels_equal_area_fraction_at_integer_scale(surf128):
    """At 2 screen pixels per map pixel, every pixel centre lies inside one cell: exact.

    The top view is orthographic with flat colours and no anti-aliasing, and without
    annotations the map fills each 256² panel, so each of the 128² cells covers exactly 2×2
    pixels. The red fraction must equal A_c/A of ``truncate`` exactly.
    """
    pytest.importorskip("pyvista")
    curve = truncate(surf128, 5, max_depth_fraction=0.5, device="cpu")
    r = render_truncation_top(surf128, curve.depth[1:], 256)
    assert r.downsample == 1 and r.image.shape == (256, 5 * 256, 3)
    for k in range(5):
        panel = r.image[:, k * 256 : (k + 1) * 256]
        assert _red(panel).sum() == 4 * curve.n_contact_pixels[k + 1]
    np.testing.assert_array_equal(r.area_fraction, curve.area_fraction[1:])


def render_truncation_top(s, depths, px, window_size_override=None, **kw):
    from warptrunc.render import render_truncation

    settings = RenderSettings(
        depths=tuple(depths),
        top_view=True,
        annotate=False,
        ncols=len(depths),
        window_size=window_size_override or (px * len(depths), px),
        **kw,
    )
    return render_truncation(s, settings=settings, device="cpu")


def test_top_view_pixels_match_mask_at_non_integer_scale(surf128):
    """At 300 px for 128 cells (2.34 px per cell), pixel centres sample the mask.

    Pixel (row, col) has its centre at x = (col + ½)·L/300, y = L − (row + ½)·L/300 (x to
    the right, y up). Every pixel whose centre is more than 2 % of a cell from a cell edge
    must show its cell's colour; only the others (where rasterisation may round either way)
    may differ, which bounds the error of the red fraction. Checks orientation too.
    """
    pytest.importorskip("pyvista")
    d = 0.4 * surf128.Rt
    r = render_truncation_top(surf128, [d], 300)
    mask = _ref_mask(surf128.heights, d)
    u = (np.arange(300) + 0.5) * 128 / 300  # pixel centres in cell units
    col, row = u.astype(int), (128 - u).astype(int)  # image row 0 is the top (y = L)
    ref = mask[row[:, None], col[None, :]]
    safe_1d = np.abs(u - np.rint(u)) > 0.02
    safe = safe_1d[:, None] & safe_1d[None, :]
    red = _red(r.image)
    np.testing.assert_array_equal(red[safe], ref[safe])
    frac_err = abs(red.mean() - mask.mean())
    # sampling error of ref plus the undecided pixels
    assert frac_err <= abs(ref.mean() - mask.mean()) + (~safe).mean()


def test_top_view_of_a_rectangular_map_keeps_x_and_y_apart():
    """96×64 pixels over 1.5×1 mm in a 192×128 window: 2×2 screen pixels per map pixel."""
    pytest.importorskip("pyvista")
    s = wm_surface(2.4, 100e-6, n=(96, 64), L=(1.5e-3, 1e-3), Rt=5e-6, seed=6, device="cpu")
    d = 0.35 * s.Rt
    r = render_truncation_top(s, [d], 0, window_size_override=(192, 128))
    mask = _ref_mask(s.heights, d)
    expected = np.kron(mask[::-1], np.ones((2, 2), bool))  # image row 0 is y = Ly
    np.testing.assert_array_equal(_red(r.image), expected)


def test_top_view_orientation_on_a_tilted_plane():
    """z = ix − iy: the highest corner is x = L, y = 0, drawn at the bottom right."""
    pytest.importorskip("pyvista")
    iy, ix = np.mgrid[0:64, 0:64]
    s = from_heights((ix - iy).astype(np.float32) * 1e-8, 1e-3 / 64)
    r = render_truncation_top(s, [0.25 * s.Rt], 128)
    red = _red(r.image)
    rows, cols = np.nonzero(red)
    assert rows.min() >= 64 and cols.min() >= 64  # only the bottom-right quadrant
    assert red[-1, -1] and not red[0, 0]


def test_downsampled_rendering_never_loses_contact_and_says_so(tmp_path):
    """A 512² map at a block factor of 4 drawn 2 px per block: red = pooled mask exactly."""
    pytest.importorskip("pyvista")
    from PIL import Image

    s = wm_surface(2.5, 100e-6, n=512, Rt=10e-6, seed=7, device="cpu")
    d = np.array([0.08, 0.25]) * s.Rt
    r = render_truncation_top(s, d, 256, downsample=4, pooling="any")
    assert r.downsample == 4 and r.mesh_shape == (128, 128) and r.pooling == "any"
    assert "down-sampled ×4" in r.caption and "max-pooling" in r.caption
    assert "any of its pixels" in r.caption
    for k in range(2):
        pooled = _ref_pool(_ref_mask(s.heights, d[k]).astype(np.int64), 4, "max") > 0
        panel = r.image[:, k * 256 : (k + 1) * 256]
        assert _red(panel).sum() == 4 * pooled.sum()
        assert _red(panel).mean() >= r.area_fraction[k]  # max-pooling only adds red
    # automatic factor: every block gets at least one screen pixel
    r = render_truncation_top(s, d[:1], 256, pooling="any")  # 256 px: 2 pixels per block
    assert r.downsample == 2
    pooled = _ref_pool(_ref_mask(s.heights, d[0]).astype(np.int64), 2, "max") > 0
    assert _red(r.image).sum() == pooled.sum()  # one screen pixel per block: none lost
    from warptrunc.render import render_truncation

    p = tmp_path / "big.png"
    settings = RenderSettings(depth_fractions=(0.2,), window_size=(200, 160), pooling="any")
    r2 = render_truncation(s, p, settings=settings, device="cpu")
    # the panel's shorter side: 160 px less the caption strip below it (at most a third)
    assert r2.downsample == 5  # ceil(512 / (160 - 53))
    meta = Image.open(p).text
    assert "down-sampled ×5" in meta["Description"]
    assert json.loads(meta["warptrunc"])["downsample"] == 5


def _redness(img):
    """Share of red per pixel: (R − G)/(R − G of pure contact red); 0 on grey (R = G = B).

    A cell coloured grey + φ·(red − grey) has redness φ whatever its grey level.
    """
    img = img.astype(float)
    return np.clip((img[..., 0] - img[..., 1]) / (214 - 39), 0.0, 1.0)


@pytest.mark.parametrize("window", [200, 256, 333])
def test_default_top_view_red_measures_contact_area_when_downsampled(window):
    """512² WM (D 2.5) in blocks of f = 2 or 3: the red of the default picture is A_c/A.

    Reference: A_c/A by NumPy at full resolution. The default (``pooling="area"``) must be
    within 10 % of it; max-pooling (``"any"``) must overstate it, as its caption says.
    """
    pytest.importorskip("pyvista")
    s = wm_surface(2.5, 100e-6, n=512, Rt=10e-6, seed=5, device="cpu")
    d = np.array([0.2, 0.3]) * s.Rt
    ref = [_ref_mask(s.heights, x).mean() for x in d]
    r = render_truncation_top(s, d, window)
    assert r.downsample > 1 and r.pooling == "area" and "fraction of its pixels" in r.caption
    a = render_truncation_top(s, d, window, pooling="any")
    for k in range(2):
        panel = r.image[:, k * window : (k + 1) * window]
        assert _redness(panel).mean() == pytest.approx(ref[k], rel=0.10)
        assert _red(a.image[:, k * window : (k + 1) * window]).mean() > 1.3 * ref[k]


def test_annotated_top_view_red_fraction_and_caption_clear_of_the_axis_title():
    """The picture a user gets: annotated top view, default panel, a 512² map (f = 2).

    The red share inside the map's footprint is within 10 % of A_c/A; the caption's rows (grey
    text at the left edge) do not share rows with the black axis labels below the map.
    """
    pytest.importorskip("pyvista")
    from warptrunc.render import render_truncation

    s = wm_surface(2.5, 100e-6, n=512, Rt=10e-6, seed=2, device="cpu")
    r = render_truncation(
        s, settings=RenderSettings(depth_fractions=(0.3,), top_view=True), device="cpu"
    )
    assert r.downsample > 1
    img = r.image.astype(int)
    grey = (np.abs(img[..., 1] - img[..., 2]) < 2) & (img.min(-1) > 60) & (img.max(-1) < 240)
    surf = grey | (img[..., 0] - img[..., 1] > 5)
    cols = np.nonzero(surf.mean(0) > 0.5)[0]
    rows = np.nonzero(surf[:, cols.min() : cols.max() + 1].mean(1) > 0.9)[0]
    box = img[rows.min() + 1 : rows.max(), cols.min() + 1 : cols.max()]
    assert min(box.shape[:2]) > 200  # found the map
    ref = _ref_mask(s.heights, 0.3 * s.Rt).mean()
    assert _redness(box).mean() == pytest.approx(ref, rel=0.10)
    below = img[rows.max() + 2 :]
    w = img.shape[1]
    black_rows = set(np.nonzero((below.max(-1) < 60).any(1))[0])
    caption_rows = set(np.nonzero((below[:, : int(0.15 * w)].max(-1) < 200).any(1))[0])
    assert black_rows and caption_rows  # axis labels and the caption are both there
    assert not black_rows & caption_rows


def test_panel_picture_has_requested_size_and_is_not_blank(tmp_path, surf128):
    pytest.importorskip("pyvista")
    from PIL import Image

    from warptrunc.render import render_truncation

    p = tmp_path / "panel.png"
    # 5 panels, 2×3
    r = render_truncation(surf128, p, settings=RenderSettings(window_size=(700, 330)), device="cpu")
    assert r.image.shape == (330, 700, 3)
    with Image.open(p) as im:
        assert im.size == (700, 330)
        np.testing.assert_array_equal(np.asarray(im.convert("RGB")), r.image)
    img = r.image.astype(int)
    assert img.std() > 20  # not blank
    grey = (np.abs(img[..., 0] - img[..., 1]) < 4) & (img.max(-1) < 235) & (img.min(-1) > 60)
    assert _red(img).sum() > 1000 and grey.sum() > 10_000  # contact over a grey surface
    # deeper panels show more red (panels 1..5, row-major, 233×165 px each)
    reds = [
        _red(img[(k // 3) * 165 : (k // 3 + 1) * 165, (k % 3) * 233 : (k % 3 + 1) * 233]).sum()
        for k in range(5)
    ]
    assert reds == sorted(reds) and reds[0] < reds[-1]
    d = r.to_dict()
    assert d["image_width"] == 700 and d["downsample"] == 1 and d["vertical_exaggeration"] == 10
    np.testing.assert_allclose(d["depth_fraction_of_Rt"], [0.1, 0.2, 0.3, 0.4, 0.5])


def test_animation_gif(tmp_path):
    pytest.importorskip("pyvista")
    from PIL import Image

    from warptrunc.render import animate_truncation

    s = wm_surface(2.5, 100e-6, n=64, Rt=10e-6, seed=3, device="cpu")
    frames = AnimationSettings(frames=3, frame_size=(160, 120))
    a = animate_truncation(s, tmp_path / "a.gif", animation=frames, device="cpu")
    assert a.depth_fraction.tolist() == [0.0, 0.25, 0.5]
    with Image.open(a.path) as im:
        assert im.n_frames == 3 and im.size == (160, 120)
        frames = []
        for k in range(3):
            im.seek(k)
            frames.append(_red(np.asarray(im.convert("RGB"))).sum())
    assert frames[0] < frames[-1]
    with pytest.raises(ValueError, match=r"\.gif or \.mp4"):
        animate_truncation(s, tmp_path / "a.avi", animation=AnimationSettings(frames=2))


def test_mp4_without_imageio_names_the_packages(tmp_path, monkeypatch):
    pytest.importorskip("pyvista")
    from warptrunc.render import animate_truncation

    monkeypatch.setitem(sys.modules, "imageio", None)
    monkeypatch.setitem(sys.modules, "imageio.v2", None)
    s = wm_surface(2.5, 100e-6, n=32, Rt=10e-6, seed=3, device="cpu")
    with pytest.raises(ImportError, match="pip install imageio imageio-ffmpeg"):
        animate_truncation(s, tmp_path / "a.mp4", animation=AnimationSettings(frames=2))


def test_cli_render_writes_picture_animation_vtk_and_json(tmp_path):
    pytest.importorskip("pyvista")
    out = tmp_path / "out"
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "warptrunc",
            "render",
            "--n",
            "64",
            "--seed",
            "2",
            "--device",
            "cpu",
            "--out",
            str(out),
            "--size",
            "600",
            "300",
            "--depth-fractions",
            "0.2",
            "0.4",
            "--animate",
            "--frames",
            "3",
            "--vtk",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode == 0, r.stderr
    for f in ("truncation.png", "truncation.gif", "surface.vti", "render.json"):
        assert (out / f).stat().st_size > 0
    info = json.loads((out / "render.json").read_text())
    z = wm_surface(2.5, 100e-6, n=64, seed=2, device="cpu").heights
    ref = [_ref_mask(z, f * (np.float64(z.max()) - np.float64(z.min()))).mean() for f in (0.2, 0.4)]
    np.testing.assert_allclose(info["picture"]["area_fraction"], ref, rtol=0, atol=0)
    assert info["picture"]["image_width"] == 600 and len(info["animation"]["depth_m"]) == 3
