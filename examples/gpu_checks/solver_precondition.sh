#!/usr/bin/env bash
# GPU check of issue 29's iterations: BCCG with its preconditioner from 2 % of the map
# (precondition_above 0.02) against always (0), on the scaling benchmark's maps (W_c = 2 px) and
# on a fixed-content family (W_c = 8 px at the first N), then one 32768² solve. Needs warp-lang
# under /tmp/site (../shared/device/README.md); results under $OUT.
#   bash examples/gpu_checks/solver_precondition.sh [sizes] [dtypes] [thresholds]
set -uo pipefail
export PYTHONPATH=/tmp/site MPLBACKEND=Agg
sizes=${1:-2048 4096 8192 10240 16384}
dtypes=${2:-float32}
pcs=${3:-0.02 0}
b=examples/benchmarks/benchmark_solver_scaling.py
python3 $b --device cuda:0 --n $sizes --dtype $dtypes --precondition-above $pcs --budget 200 \
  --out $OUT/pixel 2>&1 | grep -E "^N=|stopped|device"
python3 $b --device cuda:0 --n $sizes --dtype float32 --precondition-above $pcs --budget 150 \
  --wc-pixels 8 --out $OUT/content 2>&1 | grep -E "^N=|stopped"
