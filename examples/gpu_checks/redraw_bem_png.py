# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Redraw a bem-check's bem.png from its bem.csv and bem.json (the numbers the device computed),
with warptrunc.plot.bem.plot_bem_check, where the PNG did not come back from the device (a call
returns at most 8 files). Used for benchmarks/records/bem_check_65536_h200x4_34cbf1b/bem.png:
    python examples/gpu_checks/redraw_bem_png.py benchmarks/records/bem_check_65536_h200x4_34cbf1b
Prints True when the ratios recomputed from the columns equal the stored ones."""

import csv
import json
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from warptrunc.contact.check import BemCheck
from warptrunc.plot.bem import plot_bem_check

folder = sys.argv[1]
rows = list(csv.DictReader(open(f"{folder}/bem.csv")))


def col(k, t=float):
    return np.array([t(float(r[k])) for r in rows])


doc = json.load(open(f"{folder}/bem.json"))
res = BemCheck(
    depth=col("depth_m"),
    depth_fraction=col("depth_fraction_of_Rt"),
    bem_load=col("bem_load_N"),
    bem_area=col("bem_area_m2"),
    bem_stiffness=col("bem_stiffness_N_per_m"),
    trunc_area=col("trunc_area_m2"),
    trunc_load=col("trunc_load_N"),
    trunc_stiffness=col("trunc_stiffness_N_per_m"),
    converged=col("converged", bool),
    n_iterations=col("n_iterations", int),
    solve_time=col("solve_time_s"),
    edge_contact=col("edge_contact", bool),
    settings=doc["settings"],
)
s = doc["settings"]
fig = plot_bem_check(
    res,
    f"{folder}/bem.png",
    title=f"65536×65536, R$_t$ = {s['Rt_m'] * 1e6:.3g} µm, E* = {s['contact_modulus_Pa'] / 1e9:.4g} GPa, "
    f"{s['substrate']} half-space (warptrunc, 4 × H200, float32)",
)
plt.close(fig)
print(np.allclose(res.stiffness_ratio, col("stiffness_ratio"), rtol=1e-12))
