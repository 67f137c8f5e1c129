#!/usr/bin/env bash
# The paper profile of `warptrunc reproduce` on cuda:0, timed.
# Writes $OUT/paper/{report.md,results.json,*.png,stages/}; copy report.md + PNGs to
# docs/reproduction/ to publish them. Also runs the reproduce tests on the GPU device.
set -euo pipefail
OUT=${OUT:-out}
mkdir -p "$OUT"
python -c "import warp as wp; wp.init(); print(wp.get_cuda_devices())"
WARPTRUNC_DEVICE=cuda:0 python -m pytest -q tests/test_reproduce.py
time warptrunc reproduce --profile paper --out "$OUT/paper" --device cuda:0
# second run: every stage must be reused (seconds)
time warptrunc reproduce --profile paper --out "$OUT/paper" --device cuda:0
grep -E "wall time|reused" "$OUT/paper/report.md" | head -3
