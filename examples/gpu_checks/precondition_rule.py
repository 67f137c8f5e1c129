# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Experiment behind BCCG's default preconditioner rule: one placement of the paper's
three punches at 10240² over 1 mm (H = ∞, float32, `warptrunc indent`), with BCCG's
preconditioner rule given as RULE: "none" = from 2 % of the window (the default under a punch),
"always" = precondition_above 0; prints the time and the iterations and convolutions per punch
window (benchmarks/records/solver_precondition_h100_2026-11-26.json, ``indentation_one_placement_10240``).

Run (GPU machine): python examples/gpu_checks/precondition_rule.py PRESET RULE
"""

import collections
import json
import sys
import tempfile
import time

from warptrunc.cli import main
from warptrunc.contact import solver as S

preset, rule = sys.argv[1], sys.argv[2]
extra = ["--precondition-above", {"always": "0", "none": "0.02"}[rule]]
tally = collections.defaultdict(lambda: [0, 0, 0.0])
solve = S.ContactSolver.solve


def counted(self, *a, **k):
    st = solve(self, *a, **k)
    t = tally[self.shape[0]]
    t[0] += 1
    t[1] += st.n_iterations
    t[2] += st.n_convolutions
    return st


S.ContactSolver.solve = counted
out = tempfile.mkdtemp()
t0 = time.perf_counter()
main(["indent", "--preset", preset, "--n", "10240", "--L", "1e-3", "--hardness", "inf",
      "--placements", "1", "--dtype", "float32", "--device", "cuda:0", "--no-plot",
      "--no-progress", "--out", out, *extra])
d = json.load(open(f"{out}/indent.json"))
print(f"{preset} rule={rule}: {d['settings']['seconds']['elastic_plastic_s']:.2f} s "
      f"(wall {time.perf_counter() - t0:.1f}), converged {d['all_converged']}; "
      + "; ".join(f"{k}²: {v[0]} solves {v[1]} it {v[2]:.0f} conv"
                  for k, v in sorted(tally.items())),
      flush=True)
