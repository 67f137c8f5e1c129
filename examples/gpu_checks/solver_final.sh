#!/usr/bin/env bash
# GPU check of the contact solver as it lands (issue 29): its tests on cuda:0, the scaling
# benchmark on the default settings (both precisions), and the pruned plan in float64 (memory).
# Needs warp-lang under /tmp/site (../shared/device/README.md); results under $OUT.
set -uo pipefail
export PYTHONPATH=/tmp/site MPLBACKEND=Agg
(cd tests && WARPTRUNC_TEST_DEVICES=cuda:0 timeout 240 python3 -m pytest -q -p no:cacheprovider \
  test_bccg.py test_fft_plan.py test_contact.py test_transforms.py test_lanes.py test_plastic.py \
  test_indent.py 2>&1 | tail -4)
b=examples/benchmarks/benchmark_solver_scaling.py
python3 $b --device cuda:0 --n ${1:-2048 4096 8192 10240 16384} --dtype float32 float64 --budget 200 \
  --out $OUT/default 2>&1 | grep -E "^N=|stopped|device"
python3 $b --device cuda:0 --n 4096 8192 --dtype float64 --fft-plan pruned --budget 60 \
  --out $OUT/pruned64 2>&1 | grep -E "^N=|stopped"
