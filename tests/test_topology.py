# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Total perimeter and Euler characteristic of the contact set (``warptrunc.islands.topology``):
χ against islands − holes from scipy labelling, periodic against bounded, and the block-private
GPU kernels against the global-atomic ones."""

import numpy as np
import pytest
from test_islands import hand_masks, islands_minus_holes, smooth_surface

import warptrunc
from warptrunc.islands import topology_curve


@pytest.mark.parametrize("connectivity", [4, 8])
def test_euler_periodic_equals_bounded_away_from_the_border(connectivity):
    s = smooth_surface(56, seed=5)
    z = np.full((64, 64), s.heights.min() - 1e-6, np.float32)
    z[4:60, 4:60] = s.heights
    s = warptrunc.from_heights(z, 1e-6)
    a = topology_curve(s, 20, max_depth_fraction=0.6, connectivity=connectivity, device="cpu")
    b = topology_curve(
        s, 20, max_depth_fraction=0.6, connectivity=connectivity, periodic=True, device="cpu"
    )
    np.testing.assert_array_equal(a.euler_characteristic, b.euler_characteristic)
    np.testing.assert_array_equal(a.total_perimeter, b.total_perimeter)
    # a full torus: χ = 0; the full bounded square: χ = 1
    full = warptrunc.from_heights(np.r_[np.zeros((1, 8)), np.ones((7, 8))].astype(np.float32), 1.0)
    t = topology_curve(
        full, 2, max_depth_fraction=1.0, connectivity=connectivity, periodic=True, device="cpu"
    )
    assert t.euler_characteristic[-1] == 0
    t = topology_curve(full, 2, max_depth_fraction=1.0, connectivity=connectivity, device="cpu")
    assert t.euler_characteristic[-1] == 1


@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize("name", ["rings", "checkerboard", "spiral", "diagonals", "rectangles"])
def test_euler_of_hand_drawn_masks(connectivity, name):
    mask = hand_masks()[name]
    z = np.where(mask, 1.0, 0.0).astype(np.float32)
    s = warptrunc.from_heights(z, 1.0)
    t = topology_curve(s, 1, max_depth_fraction=0.5, connectivity=connectivity, device="cpu")
    assert t.euler_characteristic[-1] == islands_minus_holes(mask, connectivity)


@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize("periodic", [False, True])
def test_block_topology_histograms_equal_atomic(device, monkeypatch, connectivity, periodic):
    """The block-private (shared-memory) topology kernels give the same integer histograms as
    the global-atomic ones, on a rectangle whose pixel count is not a multiple of the block."""
    import warptrunc.islands.topology as dep

    s = smooth_surface(37, 53, seed=8)
    out = {}
    for mode in ("atomic", "block"):
        monkeypatch.setattr(dep, "TOPOLOGY_KERNEL", mode)
        out[mode] = topology_curve(
            s,
            40,
            max_depth_fraction=0.9,
            connectivity=connectivity,
            periodic=periodic,
            device=device,
        )
    for name in ("n_contact_pixels", "total_perimeter", "euler_characteristic"):
        np.testing.assert_array_equal(getattr(out["block"], name), getattr(out["atomic"], name))
    assert out["atomic"].n_contact_pixels[-1] > 0
