# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The paper's printed values that the reproduction is compared with (µm where noted)."""

from __future__ import annotations

__all__ = ["TABLE1", "TABLE1_SD", "TABLE2", "TABLE3"]

#: Table 1, simulated rows: R_t' (µm), R_rms (µm), W_r (µm; None = "≫ 1024"), D_tri, D_box,
#: D_vs, D_sp (means; the ± are in the paper).
TABLE1 = {
    "Ps": (0.263, 0.053, None, 2.091, 2.025, 2.103, 2.315),
    "SMATs": (16.210, 2.762, 120.0, 2.225, 2.161, 2.417, 2.421),
    "GB300s": (36.865, 4.102, 60.0, 2.555, 2.417, 2.813, 2.282),
    "GB50s": (26.239, 2.935, 25.0, 2.625, 2.351, 2.825, 2.284),
}

#: Table 1, simulated rows: the ± of R_t' and R_rms (µm) and of the four D, as printed.
TABLE1_SD = {
    "Ps": {"Rt": 0.032, "Rrms": 0.004, "tri": 0.0344, "box": 0.0313, "vs": 0.0562, "sp": 0.1196},
    "SMATs": {"Rt": 1.569, "Rrms": 0.053, "tri": 0.0232, "box": 0.0297, "vs": 0.0487, "sp": 0.1222},
    "GB300s": {"Rt": 1.731, "Rrms": 0.034, "tri": 0.0425, "box": 0.0316, "vs": 0.0521, "sp": 0.0876},
    "GB50s": {"Rt": 1.157, "Rrms": 0.031, "tri": 0.0328, "box": 0.0395, "vs": 0.0876, "sp": 0.0933},
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
