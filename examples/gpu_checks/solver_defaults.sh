#!/usr/bin/env bash
# The contact solver on its default settings, on cuda:0: the solver's tests, the scaling
# benchmark at 2048²–16384² in both precisions (or the sizes given as $1), and the pruned FFT
# plan in float64 at 4096² and 8192² (its memory). Results under $OUT ($OUT/default,
# $OUT/pruned64: scaling.json each, the record benchmarks/records/solver_scaling_*.json).
# PYTHONPATH: when unset, $STAGE (default /tmp/site), the folder the GPU machine's packages are
# installed into with `pip install --target`.
#   OUT=gpu_out bash examples/gpu_checks/solver_defaults.sh ["2048 4096"]
set -uo pipefail
: "${OUT:?set OUT to a folder for the results}"
export PYTHONPATH=${PYTHONPATH:-${STAGE-/tmp/site}} MPLBACKEND=Agg
(cd tests && WARPTRUNC_TEST_DEVICES=cuda:0 timeout 240 python3 -m pytest -q -p no:cacheprovider \
  test_bccg.py test_fft_plan.py test_contact.py test_transforms.py test_lanes.py test_plastic.py \
  test_indent.py 2>&1 | tail -4)
b=examples/benchmarks/benchmark_solver_scaling.py
# shellcheck disable=SC2086  # the sizes: several words
python3 $b --device cuda:0 --n ${1:-2048 4096 8192 10240 16384} --dtype float32 float64 --budget 200 \
  --out "$OUT/default" 2>&1 | grep -E "^N=|stopped|device"
python3 $b --device cuda:0 --n 4096 8192 --dtype float64 --fft-plan pruned --budget 60 \
  --out "$OUT/pruned64" 2>&1 | grep -E "^N=|stopped"
