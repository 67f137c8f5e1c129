#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
# bem-check on the GPU machine: the BEM itself runs on the host (ContactMechanics,
# NumPy/muGrid FFT); only generation and truncation use the Warp device. Checks that the
# truncation columns are identical with --device cuda:0 and --device cpu (same seed, same map).
set -euo pipefail
cd "$(dirname "$0")/../.."
pip install -q -e ".[test]"
python -m pytest -q tests/test_bem.py
out=$(mktemp -d)
for dev in cpu cuda:0; do
  warptrunc bem-check --n 256 --device "$dev" --solver contactmechanics --no-progress \
    --out "$out/${dev/:/}"
done
python - "$out" <<'PY'
import csv, sys
a, b = (list(csv.DictReader(open(f"{sys.argv[1]}/{d}/bem.csv"))) for d in ("cpu", "cuda0"))
for ra, rb in zip(a, b, strict=True):
    for k in ("depth_m", "trunc_area_m2", "trunc_load_N", "bem_load_N"):
        assert ra[k] == rb[k], (k, ra[k], rb[k])
print("bem-check: cpu and cuda:0 give identical truncation and BEM columns")
PY
