# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Depth as the instrument reads it, and the bulk-yield flag (``warptrunc.indent.depth``).

References independent of the code under test: a load solve at the detection force on the
same window by the contact solver itself; the smooth flat punch's elastic sink F/(2E*a)
(Sneddon); a spike of known height on a flat; the mean pressure F/A and Shield's and Tabor's
numbers written again.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import warptrunc
from warptrunc.indent import IndentProtocol, indent, punch_window
from warptrunc.indent.cycles import make_solver
from warptrunc.indent.depth import BULK_YIELD_FRACTION, DETECTION_LOAD, bulk_yield
from warptrunc.material import Material

MAT = Material.against_diamond(hardness=1e9)


def _wm():
    return warptrunc.wm_surface(2.5, 100e-6, L=0.5e-3, n=64, Rt=2e-6, seed=1, device="cpu")


def test_threshold_depth_is_the_depth_from_surface_detection():
    """threshold depth = δ(F) − δ(F_s) with δ(F_s) a load solve at F_s on the same window, and
    never more than the depth from the highest point."""
    s = _wm()
    at = IndentProtocol(punch_diameters=(0.2e-3,), peak_loads=(1e-3, 4e-3, 16e-3),
                        placements=2, refine_max=1, min_contact_pixels=1)  # fmt: skip
    assert at.detection_load == DETECTION_LOAD == 10e-6
    r = indent(s, protocol=at, material=MAT, device="cpu")
    d = r.to_dict()
    assert np.all(d["threshold_depth_m"] <= d["displacement_m"])
    assert np.all(d["threshold_depth_m"] > 0) and np.all(d["detection_displacement_m"] > 0)
    np.testing.assert_allclose(
        d["threshold_depth_m"], d["displacement_m"] - d["detection_displacement_m"], rtol=1e-12
    )
    np.testing.assert_array_less(d["elastic_threshold_depth_m"], d["elastic_displacement_m"])
    for j in (0, 1):
        row = np.flatnonzero(d["placement"] == j)[0]
        c = (d["centre_x_m"][row], d["centre_y_m"][row])
        w = punch_window(np.asarray(s.heights), s.dx, 0.2e-3, c)
        state = make_solver(w, MAT, device="cpu").solve(load=DETECTION_LOAD)
        assert state.converged
        np.testing.assert_allclose(d["detection_displacement_m"][row], state.depth, rtol=1e-3)
    doc = r.depth_summary()
    assert doc["detection_load_N"] == 10e-6 and "detection" in doc
    (per,) = doc["at_largest_load"]["per_punch"]
    top = d["threshold_depth_m"][d["peak_load_N"] == 16e-3]
    assert per["threshold_depth_m"] == {
        "median": pytest.approx(np.median(top)), "min": top.min(), "max": top.max(),
    }  # fmt: skip
    none = indent(s, protocol=at.replace(detection_load=None), material=MAT, device="cpu")
    assert np.isnan(none.threshold_depth).all()
    with pytest.raises(ValueError, match="detection_load must be below the first peak load"):
        IndentProtocol(peak_loads=(1e-3,), detection_load=1e-3)


def test_threshold_depth_leaves_out_a_lone_spike():
    """A flat with one spike pixel 0.2 µm high, on pixels small enough that the spike yields
    under the detection force (H·dx² < F_s): the depth from the highest point counts the
    spike's height, the threshold depth only the flat punch's elastic sink F/(2E*a)."""
    n, dx, d = 128, 50e-9, 5e-6
    z = np.zeros((n, n))
    z[n // 2, n // 2] = 0.2e-6
    assert MAT.hardness * dx * dx < DETECTION_LOAD
    f = 2e-3
    at = IndentProtocol(punch_diameters=(d,), peak_loads=(f,), placements=None,
                        min_contact_pixels=1, elastic=False)  # fmt: skip
    r = indent(z, protocol=at, pixel_size=dx, material=MAT, device="cpu")
    sink = f / (2 * MAT.contact_modulus * d / 2)  # Sneddon
    assert r.displacement[0] > 0.2e-6  # the spike's height and more
    assert r.threshold_depth[0] == pytest.approx(sink, rel=0.1)


def test_a_cell_above_the_bulk_yield_criterion_is_flagged():
    """F/A ≥ (2.84/3)·H (Shield's flat-punch collapse pressure 2.84·σ_y, Tabor's H = 3·σ_y):
    flagged bulk_yield and out of the fits; lighter cells not."""
    assert BULK_YIELD_FRACTION == pytest.approx(5.69 / 2 / 3, rel=2e-3)
    s = _wm()
    d = 0.3e-3
    area = math.pi * d * d / 4
    h = 16e-3 / area / 0.97  # the heaviest cell at 0.97·H, above 0.947·H
    mat = Material.against_diamond(hardness=h)
    at = IndentProtocol(punch_diameters=(d,), peak_loads=(1e-3, 4e-3, 16e-3), placements=None,
                        refine_max=1, min_contact_pixels=1)  # fmt: skip
    r = indent(s, protocol=at, material=mat, device="cpu")
    c = r.to_dict()
    np.testing.assert_allclose(c["mean_pressure_Pa"], c["peak_load_N"] / area, rtol=1e-12)
    np.testing.assert_array_equal(c["bulk_yield"], [False, False, True])
    assert not c["in_fit"][2] and not (c["in_fit"] & c["bulk_yield"]).any()
    doc = r.depth_summary()["bulk_yield"]
    assert doc["n_cells"] == 1 and doc["pressure_Pa"] == pytest.approx(0.947 * h, rel=1e-3)
    assert "Shield" in doc["criterion"] and "Tabor" in doc["criterion"]
    assert not bulk_yield([1.0], [1e-12], math.inf).any()  # elastic: never
