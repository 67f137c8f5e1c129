#!/usr/bin/env bash
# BCCG's preconditioner rule on cuda:0: the default rule (auto: always on maps of at least 1024²
# pixels) against the 2 % rule (0.02), at a fixed relative tolerance (pentol = 1e-4·rms) on the
# scaling benchmark's maps (W_c = 2 px) and on a fixed-content family (W_c = 8 px at the first
# N); one 32768² solve; one paper-scale indentation placement with both rules (the record
# benchmarks/records/solver_precondition_*.json). Results under $OUT. PYTHONPATH: when unset,
# $STAGE (default /tmp/site), the folder the GPU machine's packages are installed into with
# `pip install --target`.
#   bash examples/gpu_checks/solver_precondition.sh [what] [sizes] [thresholds]
#   what: iterations | 32768 | indent | all (default)
set -uo pipefail
export PYTHONPATH=${PYTHONPATH:-${STAGE-/tmp/site}} MPLBACKEND=Agg
: "${OUT:?set OUT to a folder for the results}"
what=${1:-all}
sizes=${2:-2048 4096 8192 10240 16384}
pcs=${3:-auto 0.02}
b=examples/benchmarks/benchmark_solver_scaling.py
if [ $what = iterations ] || [ $what = all ]; then
  python3 $b --device cuda:0 --n $sizes --dtype float32 --precondition-above $pcs --budget 150 \
    --pentol-rms 1e-4 --out $OUT/pixel 2>&1 | grep -E "^N=|stopped|device"
  python3 $b --device cuda:0 --n $sizes --dtype float32 --precondition-above $pcs --budget 150 \
    --pentol-rms 1e-4 --wc-pixels 8 --out $OUT/content 2>&1 | grep -E "^N=|stopped"
fi
if [ $what = 32768 ] || [ $what = all ]; then
  python3 examples/gpu_checks/solve_32768.py 32768 bccg 400 auto free auto 2>&1 | grep -v "^Warp\|Module"
fi
if [ $what = indent ] || [ $what = all ]; then
  for pa in 0.02 auto; do
    /usr/bin/time -f "indent precondition_above $pa: %e s wall" python3 -m warptrunc indent \
      --preset GB300s --n 10240 --L 1e-3 --hardness inf --placements 1 --dtype float32 \
      --device cuda:0 --no-plot --no-progress --precondition-above $pa --out $OUT/indent_$pa \
      2>&1 | grep -v "^Warp\|Module" | tail -3
    python3 -c "import json,sys; d=json.load(open('$OUT/indent_$pa/indent.json')); print('$pa', d['settings']['seconds'], d['all_converged'])"
  done
fi
