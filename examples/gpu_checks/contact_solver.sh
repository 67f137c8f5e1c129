#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
# The elastic contact solver on the GPU machine: the contact tests on cpu and
# cuda:0 (closed forms, ContactMechanics on the same maps, float32), bem-check with the warptrunc
# solver on cuda:0 against --solver contactmechanics, and the benchmark at 2048²–10240².
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT=${OUT:-gpu_out}
mkdir -p "$OUT"
pip install -q -e ".[test,gpu]"
python -m pytest -q -s tests/test_contact.py tests/test_bem.py | tee "$OUT/contact_tests.txt"
for solver in warptrunc contactmechanics; do
  warptrunc bem-check --n 256 --device cuda:0 --solver "$solver" --no-progress --no-plot \
    --out "$OUT/bem_$solver"
done
python - "$OUT" <<'PY'
import csv, sys
a, b = (list(csv.DictReader(open(f"{sys.argv[1]}/bem_{s}/bem.csv")))
        for s in ("warptrunc", "contactmechanics"))
for ra, rb in zip(a, b, strict=True):
    for k in ("bem_load_N", "bem_area_m2", "bem_stiffness_N_per_m"):
        rel = abs(float(ra[k]) / float(rb[k]) - 1)
        assert rel < 1e-3, (k, ra[k], rb[k])
print("bem-check: warptrunc on cuda:0 and ContactMechanics agree within 1e-3")
PY
python examples/benchmarks/benchmark_contact.py --device cuda:0 --n 2048 4096 8192 10240 \
  --json "$OUT/contact.json" | tee "$OUT/contact_bench.txt"
