# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Contact islands against independent references: scipy.ndimage.label, scipy.sparse.csgraph
(periodic maps), NumPy edge counting, NumPy least squares, and analytic cases."""

import math
import os

import numpy as np
import pytest
import scipy.ndimage as ndi
import warp as wp
from islands_helpers import (
    edge_counts,
    graph_labels,
    hand_masks,
    islands_minus_holes,
    scipy_labels,
    smooth_surface,
    spiral,
    thresholds,
)

import warptrunc
from warptrunc.islands import (
    ISLANDS_TRUNCATION,
    MIN_ISLANDS,
    IslandSettings,
    island_curve,
    islands_at_depths,
    label_islands,
)
from warptrunc.islands import unionfind as _unionfind


def island_depths(increments, **kw):
    """The depths of an island curve: ``increments`` to 0.5·R_t unless ``kw`` says otherwise."""
    return ISLANDS_TRUNCATION.replace(increments=increments, **kw)


# --- labelling of one mask ----------------------------------------------------------------------

METHODS = ["dispatch", "parallel", "parallel-pixel", "sequential"]


def labels_of(mask, connectivity, device, method, periodic=False):
    """(labels, n) from ``label_islands`` (which picks the path for the device), or from the
    parallel (GPU) or sequential (CPU) union-find forced on ``device``, so that both paths are
    tested on every machine."""
    if method == "dispatch":
        isl = label_islands(mask, connectivity=connectivity, periodic=periodic, device=device)
        return isl.labels, isl.n_islands
    m = wp.array(np.ascontiguousarray(mask, np.uint8), dtype=wp.uint8, device=device)
    if method == "sequential":
        lab, n = _unionfind._label_sequential(m, connectivity, periodic)
    else:  # "parallel": 4 pixels per thread where rows allow it; "parallel-pixel": 1 per thread
        lab, n = _unionfind._label_parallel(
            m, connectivity, periodic, quads=None if method == "parallel" else False
        )
    return lab.numpy(), n


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize("density", [0.05, 0.2, 0.4, 0.5, 0.593, 0.7, 0.95])
def test_labels_equal_scipy_random(device, connectivity, density, method):
    rng = np.random.default_rng(int(density * 1000) + connectivity)
    mask = rng.random((64, 72)) < density
    labels, n_islands = labels_of(mask, connectivity, device, method)
    ref, n = scipy_labels(mask, connectivity)
    assert n_islands == n
    np.testing.assert_array_equal(labels, ref)  # both number in raster order
    assert labels.dtype == np.int32


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize("name", list(hand_masks()))
def test_labels_equal_scipy_hand_drawn(device, connectivity, name, method):
    mask = hand_masks()[name]
    labels, n_islands = labels_of(mask, connectivity, device, method)
    ref, n = scipy_labels(mask, connectivity)
    assert n_islands == n
    np.testing.assert_array_equal(labels, ref)


def test_known_counts():
    m = hand_masks()
    assert label_islands(m["spiral"], device="cpu").n_islands == 1
    assert label_islands(m["checkerboard"], device="cpu").n_islands == 16 * 20 // 2
    assert label_islands(m["checkerboard"], connectivity=8, device="cpu").n_islands == 1
    assert label_islands(m["diagonals"], device="cpu").n_islands == 8
    assert label_islands(m["diagonals"], connectivity=8, device="cpu").n_islands == 3
    assert label_islands(m["empty"], device="cpu").n_islands == 0
    full = label_islands(m["full"], 2e-6, 3e-6, device="cpu")
    assert full.n_islands == 1
    # the border counts as non-contact: a full 9×13 map is closed by its border
    assert full.perimeter[0] == pytest.approx(2 * 13 * 2e-6 + 2 * 9 * 3e-6)
    assert full.area[0] == pytest.approx(9 * 13 * 6e-12)


@pytest.mark.parametrize("method", ["parallel", "sequential"])
@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("density", [0.1, 0.45, 0.6, 0.9])
def test_labels_equal_graph_reference(connectivity, periodic, density, method):
    rng = np.random.default_rng(7 + int(density * 100))
    mask = rng.random((33, 40)) < density
    labels, n_islands = labels_of(mask, connectivity, "cpu", method, periodic)
    ref, n = graph_labels(mask, connectivity, periodic)
    assert n_islands == n
    np.testing.assert_array_equal(labels, ref)


@pytest.mark.parametrize("method", ["parallel", "sequential"])
@pytest.mark.parametrize("periodic", [False, True])
def test_periodic_seams(periodic, method):
    mask = np.zeros((8, 10), bool)
    mask[:, 0] = mask[:, -1] = True  # joined across the x seam
    mask[0, 4] = mask[-1, 4] = True  # joined across the y seam
    mask[0, 6] = mask[-1, 7] = True  # diagonal across the y seam
    n4 = labels_of(mask, 4, "cpu", method, periodic)[1]
    n8 = labels_of(mask, 8, "cpu", method, periodic)[1]
    assert (n4, n8) == ((4, 3) if periodic else (6, 6))


@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize(
    "name", ["random", "rings", "spiral", "rectangles", "full", "checkerboard"]
)
def test_areas_and_perimeters_equal_numpy(device, connectivity, periodic, name):
    if name == "random":
        mask = np.random.default_rng(3).random((40, 52)) < 0.55
    else:
        mask = hand_masks()[name]
    dx, dy = 2e-6, 3e-6
    isl = label_islands(mask, dx, dy, connectivity=connectivity, periodic=periodic, device=device)
    ref, n = graph_labels(mask, connectivity, periodic)
    area, ex, ey = edge_counts(ref, n, periodic)
    np.testing.assert_array_equal(isl.area_pixels, area)
    np.testing.assert_array_equal(isl.edges_x, ex)
    np.testing.assert_array_equal(isl.edges_y, ey)
    np.testing.assert_allclose(isl.area, area * dx * dy, rtol=1e-15)
    np.testing.assert_allclose(isl.perimeter, ex * dy + ey * dx, rtol=1e-15)
    cols = isl.to_dict()
    assert {len(v) for v in cols.values()} == {n}


def test_labels_transpose_invariant():
    mask = np.random.default_rng(5).random((31, 47)) < 0.5
    a = label_islands(mask, device="cpu")
    b = label_islands(mask.T, device="cpu")
    assert a.n_islands == b.n_islands
    assert sorted(a.area_pixels) == sorted(b.area_pixels)
    assert sorted(a.perimeter) == sorted(b.perimeter)


# --- carried forest across depths ---------------------------------------------------------------


@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize("kind", ["smooth", "noise", "quantised"])
def test_carried_forest_equals_labelling_each_depth(device, connectivity, kind):
    if kind == "smooth":
        s = smooth_surface(48, 56, seed=1)
    else:
        z = np.random.default_rng(2).random((40, 44))
        if kind == "quantised":  # many equal heights: pixels that touch at the same depth
            z = np.floor(z * 6)
        s = warptrunc.from_heights((z * 1e-6).astype(np.float32), 1e-6)
    depths = np.array([0.45, 0.0, 0.1, 0.25, 0.25, 0.6, 0.95, 1.0]) * s.Rt
    got = islands_at_depths(s, depths, connectivity=connectivity, device=device)
    thr = thresholds(s, depths)
    for d, t, isl in zip(depths, thr, got, strict=True):
        mask = s.heights >= t
        scratch = label_islands(mask, s.dx, connectivity=connectivity, device=device)
        ref, _ = scipy_labels(mask, connectivity)
        np.testing.assert_array_equal(isl.labels, ref)
        np.testing.assert_array_equal(isl.labels, scratch.labels)
        np.testing.assert_array_equal(isl.perimeter, scratch.perimeter)
        assert isl.depth == d
    (one,) = islands_at_depths(s, [depths[0]], connectivity=connectivity, device=device)
    np.testing.assert_array_equal(one.labels, got[0].labels)


def test_long_merge_chain_along_spiral(device):
    """Pixels of a spiral touch one by one along the path: a merge chain as long as the map."""
    mask, path = spiral(33)
    z = np.full(mask.shape, -1.0)
    for step, (y, x) in enumerate(path):
        z[y, x] = -step / len(path) * 0.5  # the path's start is the top
    s = warptrunc.from_heights(z.astype(np.float32), 1.0)
    c = island_curve(s, truncation=island_depths(40, max_depth_fraction=0.6), device=device)
    thr = thresholds(s, c.depth)
    ref = [scipy_labels(s.heights >= t, 4)[1] for t in thr]
    np.testing.assert_array_equal(c.n_islands, ref)
    # reversed: the path's end touches first, so every new pixel has the smaller index
    z_rev = np.full(mask.shape, -1.0)
    for step, (y, x) in enumerate(path):
        z_rev[y, x] = -(len(path) - step) / len(path) * 0.5
    r = warptrunc.from_heights(z_rev.astype(np.float32), 1.0)
    c2 = island_curve(
        r, truncation=island_depths(40, max_depth_fraction=1.0, connectivity=8), device=device
    )
    thr2 = thresholds(r, c2.depth)
    np.testing.assert_array_equal(c2.n_islands, [scipy_labels(r.heights >= t, 8)[1] for t in thr2])


@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize("periodic", [False, True])
def test_island_curve_against_references(device, connectivity, periodic):
    s = smooth_surface(64, 72, seed=3)
    min_pixels = 4
    snaps = [0.2 * s.Rt, 0.35 * s.Rt]
    c = island_curve(
        s,
        truncation=island_depths(30, max_depth_fraction=0.9, connectivity=connectivity),
        settings=IslandSettings(periodic=periodic, min_pixels=min_pixels, snapshots=(0.2, 0.35)),
        device=device,
    )
    thr = thresholds(s, c.depth)
    nbins = c.area_histogram.shape[1]
    snap_k = sorted({int(np.argmin(np.abs(c.depth - v))) for v in snaps})
    sizes = iter(c.sizes)
    for k, t in enumerate(thr):
        mask = s.heights >= t
        ref, n = graph_labels(mask, connectivity, periodic)
        assert c.n_islands[k] == n
        assert c.n_contact_pixels[k] == np.count_nonzero(mask)
        area, ex, ey = edge_counts(ref, n, periodic)
        tot = ex.sum() * s.dy + ey.sum() * s.dx
        assert c.total_perimeter[k] == pytest.approx(tot, rel=1e-12)
        if not periodic:
            assert c.euler_characteristic[k] == islands_minus_holes(mask, connectivity)
        # area histogram in log2 bins of pixels
        hist = np.bincount(np.floor(np.log2(area)).astype(int), minlength=nbins) if n else 0
        np.testing.assert_array_equal(c.area_histogram[k], hist)
        # slit-island fit by NumPy least squares over islands ≥ min_pixels
        big = area >= min_pixels
        assert c.slit_n_islands[k] == big.sum()
        if big.sum() >= MIN_ISLANDS:
            x = np.log10(area[big] * s.pixel_area)
            y = np.log10(ex[big] * s.dy + ey[big] * s.dx)
            slope, _ = np.polyfit(x, y, 1)
            r2 = np.corrcoef(x, y)[0, 1] ** 2
            assert c.slit_exponent[k] == pytest.approx(slope, rel=1e-9, abs=1e-12)
            assert c.slit_r2[k] == pytest.approx(r2, rel=1e-9, abs=1e-12)
        else:
            assert math.isnan(c.slit_exponent[k])
        if k in snap_k:
            sz = next(sizes)
            assert sz.depth == c.depth[k]
            np.testing.assert_array_equal(sz.area_pixels, area)
            np.testing.assert_allclose(sz.perimeter, ex * s.dy + ey * s.dx, rtol=1e-15)
    assert len(c.sizes) == len(snap_k)


def test_counts_only_equal_statistics_run(device):
    s = smooth_surface(48, seed=4)
    a = island_curve(s, truncation=island_depths(25), device=device)
    b = island_curve(
        s, truncation=island_depths(25), settings=IslandSettings(statistics=False), device=device
    )
    np.testing.assert_array_equal(a.n_islands, b.n_islands)
    np.testing.assert_array_equal(a.euler_characteristic, b.euler_characteristic)
    assert np.isnan(b.slit_exponent).all()
    assert not b.area_histogram.any()


def test_curve_invariants():
    s = smooth_surface(40, 52, seed=6)
    a = island_curve(s, truncation=island_depths(20), device="cpu")
    t = warptrunc.from_heights(s.heights.T.copy(), s.dx)
    b = island_curve(t, truncation=island_depths(20), device="cpu")
    np.testing.assert_array_equal(a.n_islands, b.n_islands)
    np.testing.assert_array_equal(a.euler_characteristic, b.euler_characteristic)
    assert np.diff(a.n_contact_pixels).min() >= 0
    big = warptrunc.from_heights(s.heights, 3 * s.dx)
    d = island_curve(big, truncation=island_depths(20), device="cpu")
    np.testing.assert_allclose(d.contact_area, 9 * a.contact_area, rtol=1e-12)
    np.testing.assert_allclose(d.total_perimeter, 3 * a.total_perimeter, rtol=1e-12)
    np.testing.assert_allclose(d.slit_exponent, a.slit_exponent, rtol=1e-9)
    cols = a.to_dict()
    assert list(cols)[:8] == [
        "depth_m",
        "depth_fraction_of_Rt",
        "n_islands",
        "euler_characteristic",
        "total_perimeter_m",
        "contact_area_m2",
        "slit_exponent",
        "slit_r2",
    ]
    assert {len(v) for v in cols.values()} == {21}


# --- bad input ------------------------------------------------------------------------------------


def test_bad_input_raises_clear_errors():
    with pytest.raises(ValueError, match=r"mask must be 2-D.*\(2, 3, 4\)"):
        label_islands(np.zeros((2, 3, 4), bool))
    with pytest.raises(ValueError, match=r"mask must be boolean or integer.*float64"):
        label_islands(np.zeros((3, 4)))
    with pytest.raises(ValueError, match=r"mask must be boolean or integer.*float32"):
        label_islands(np.full((3, 4), np.nan, np.float32))
    with pytest.raises(ValueError, match="connectivity must be 4 or 8, got 6"):
        label_islands(np.zeros((3, 4), bool), connectivity=6)
    with pytest.raises(ValueError, match="dx must be"):
        label_islands(np.zeros((3, 4), bool), dx=-1.0)
    z = np.zeros((4, 4), np.float32)
    z[1, 2] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        warptrunc.from_heights(z, 1e-6)
    with pytest.raises(TypeError, match=r"warptrunc\.Surface"):
        island_curve(np.zeros((4, 4), np.float32))
    s = smooth_surface(16)
    with pytest.raises(ValueError, match=r"min_pixels must be an integer in \[1, inf\), got 0"):
        IslandSettings(min_pixels=0)
    with pytest.raises(ValueError, match=r"connectivity must be one of \{4, 8\}, got 'four'"):
        island_depths(5, connectivity="four")
    with pytest.raises(ValueError, match="depths must be finite"):
        islands_at_depths(s, [0.1e-6, np.nan], device="cpu")
    with pytest.raises(ValueError, match="depths must be finite and ≥ 0"):
        islands_at_depths(s, [-1.0], device="cpu")


@pytest.mark.parametrize("connectivity", [4, 8])
def test_island_counts_device_equal_scipy(device, connectivity):
    s = smooth_surface(50, 61, seed=8)
    depth = warptrunc.depth_grid(s.Rt, 30, max_depth_fraction=1.0)
    idx = warptrunc.truncation.contact_index_device(s, depth, warptrunc.resolve_device(device))
    from warptrunc.islands import island_counts_device

    got = island_counts_device(idx, depth.size, connectivity)
    ref = [scipy_labels(s.heights >= t, connectivity)[1] for t in thresholds(s, depth)]
    np.testing.assert_array_equal(got, ref)
    with pytest.raises(ValueError, match="index must be a 2-D warp array of int32"):
        island_counts_device(idx.numpy(), depth.size)


def _cuda_or_skip():
    want = os.environ.get("WARPTRUNC_TEST_DEVICES")
    if wp.get_cuda_device_count() == 0 or (want and "cuda:0" not in want):
        pytest.skip("needs a CUDA device")


@pytest.mark.gpu
@pytest.mark.parametrize("connectivity", [4, 8])
def test_gpu_labels_deterministic_and_equal_scipy(connectivity):
    _cuda_or_skip()
    rng = np.random.default_rng(12)
    for density in (0.3, 0.5, 0.593, 0.7):
        mask = rng.random((512, 640)) < density
        ref, n = scipy_labels(mask, connectivity)
        for _ in range(3):  # thread scheduling differs from run to run, labels must not
            isl = label_islands(mask, connectivity=connectivity, device="cuda:0")
            assert isl.n_islands == n
            np.testing.assert_array_equal(isl.labels, ref)


@pytest.mark.gpu
@pytest.mark.parametrize("connectivity", [4, 8])
def test_gpu_island_curve_equals_cpu(connectivity):
    _cuda_or_skip()
    s = smooth_surface(256, 200, sigma=3.0, seed=13)
    kw = dict(
        truncation=island_depths(60, connectivity=connectivity),
        settings=IslandSettings(min_pixels=4, snapshots=(0.3,)),
    )
    a = island_curve(s, device="cpu", **kw)
    b = island_curve(s, device="cuda:0", **kw)
    for key, col in a.to_dict().items():
        if key.startswith("slit_") and col.dtype.kind == "f":
            # float64 sums accumulated on the device in a thread-dependent order (and log10 of
            # the device's libm): equal to ~1e-15, not bit for bit
            np.testing.assert_allclose(col, b.to_dict()[key], rtol=1e-12, equal_nan=True)
        else:
            np.testing.assert_array_equal(col, b.to_dict()[key], err_msg=key)
    np.testing.assert_array_equal(a.area_histogram, b.area_histogram)
    np.testing.assert_array_equal(a.sizes[0].perimeter, b.sizes[0].perimeter)


# --- Σ√A_i of the island-resolved stiffness ---------------------------------------------------


@pytest.mark.parametrize("connectivity", [4, 8])
def test_sqrt_area_sum_matches_scipy_label(device, connectivity):
    """Σ_i √A_i at every depth equals the sum over ``scipy.ndimage.label``'s islands of the
    same float32 threshold mask; rel. 1e-9: each √a is rounded to 2^-31 pixel^½ on the device."""

    from warptrunc.islands import island_curve
    from warptrunc.wm import wm_surface

    s = wm_surface(2.5, 100e-6, L=1e-3, n=96, seed=3, device=device)
    ic = island_curve(
        s, truncation=island_depths(40, max_depth_fraction=0.4, connectivity=connectivity), device=device
    )
    z = s.heights
    top = np.float32(z.max())
    structure = np.ones((3, 3)) if connectivity == 8 else None
    ref = []
    for d in ic.depth:
        lab, _ = ndi.label(z >= np.float32(top - np.float32(d)), structure=structure)
        ref.append(np.sqrt(np.bincount(lab.ravel())[1:].astype(np.float64)).sum() * s.dx)
    np.testing.assert_allclose(ic.sqrt_area_sum, ref, rtol=1e-9, atol=0)
    assert ic.apparent_area == pytest.approx(s.apparent_area)
    # deterministic: a second run gives the same bits
    again = island_curve(
        s, truncation=island_depths(40, max_depth_fraction=0.4, connectivity=connectivity), device=device
    )
    np.testing.assert_array_equal(again.sqrt_area_sum, ic.sqrt_area_sum)


def test_sqrt_area_sum_absent_without_statistics():
    from warptrunc.islands import island_curve
    from warptrunc.stiffness import island_stiffness_curve
    from warptrunc.wm import wm_surface

    s = wm_surface(2.5, 100e-6, L=1e-3, n=32, seed=0, device="cpu")
    ic = island_curve(
        s, truncation=island_depths(10), settings=IslandSettings(statistics=False), device="cpu"
    )
    assert ic.sqrt_area_sum is None
    with pytest.raises(ValueError, match="statistics=True"):
        island_stiffness_curve(ic)


def test_island_curve_csv_reads_back(tmp_path):
    """islands.csv: the to_dict columns, floats to the last bit, counts as integers."""
    import csv

    z = np.random.default_rng(4).normal(size=(48, 40))
    c = island_curve(warptrunc.from_heights(z, 1e-6), truncation=island_depths(30), device="cpu")
    with open(c.to_csv(tmp_path / "i.csv"), newline="") as fh:
        rows = list(csv.reader(fh))
    cols = c.to_dict()
    assert rows[0] == list(cols)
    assert len(rows) == c.depth.size + 1
    for j, (name, v) in enumerate(cols.items()):
        got = [r[j] for r in rows[1:]]
        if v.dtype.kind == "i":
            assert got == [str(int(x)) for x in v], name
        else:
            np.testing.assert_array_equal(np.array(got, dtype=np.float64), v, err_msg=name)
