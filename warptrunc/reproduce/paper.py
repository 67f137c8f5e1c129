# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The paper's printed values that the reproduction is compared with (µm where noted)."""

from __future__ import annotations

__all__ = ["TABLE1", "TABLE2", "TABLE3"]

#: Table 1, simulated rows: R_t' (µm), R_rms (µm), W_r (µm; None = "≫ 1024"), D_tri, D_box,
#: D_vs, D_sp (means; the ± are in the paper).
TABLE1 = {
    "Ps": (0.263, 0.053, None, 2.091, 2.025, 2.103, 2.315),
    "SMATs": (16.210, 2.762, 120.0, 2.225, 2.161, 2.417, 2.421),
    "GB300s": (36.865, 4.102, 60.0, 2.555, 2.417, 2.813, 2.282),
    "GB50s": (26.239, 2.935, 25.0, 2.625, 2.351, 2.825, 2.284),
}

#: Table 2 (% R_t ranges): maximum applicable depth, depth of the maximum growth rate of the
#: island number, maximum depth of fractality.
TABLE2 = {
    "Ps": ((10.0, 15.0), (33.0, 33.5), (25.0, 30.0)),
    "SMATs": ((30.0, 35.0), (36.0, 36.5), (32.5, 37.5)),
    "GB300s": ((32.5, 37.5), (31.0, 31.5), (30.0, 35.0)),
    "GB50s": ((25.0, 30.0), (34.0, 34.5), (27.5, 32.5)),
}

#: Table 3: α = slope·D + intercept (r) per D; β = b·δ^p (r).
TABLE3 = {
    "alpha": {
        "in": (0.209, 0.090, 0.940),
        "tri": (0.313, -0.186, 0.948),
        "box": (0.394, -0.347, 0.966),
        "vs": (0.328, -0.258, 0.980),
        "sp": (0.229, 0.071, 0.741),
    },
    "beta": (0.0386, -1.122, 0.992),
}
