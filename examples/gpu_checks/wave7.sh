#!/usr/bin/env bash
# GPU checks of the seventh wave (issues 39, 40, 42) on a 4-GPU host, one mode per device call:
#   bash examples/gpu_checks/wave7.sh sharded_ab   # issue 42 (a) + (b): sharded_x4.sh PARTS="a b"
#   bash examples/gpu_checks/wave7.sh sharded_c    # issue 42 (c): bem-check --n 65536 --devices 4
#   bash examples/gpu_checks/wave7.sh loop         # issue 40: tests on cuda:0, solver_loop.sh
#   bash examples/gpu_checks/wave7.sh workers      # issue 39: workers_bench.sh on every GPU
#   bash examples/gpu_checks/wave7.sh indent2 S    # issue 39: the paper's indentation stage on
#                                                  # GPUs 0,1 for S seconds of new parts
# Results under $OUT/<mode>/ (default ./gpu_out). The machine has no git: pass
# WARPTRUNC_GIT_COMMIT. Run after the staging of ../shared/device/README.md (PYTHONPATH=/tmp/site).
set -uo pipefail
MODES="sharded_ab, sharded_c, loop, workers or indent2"
# shellcheck source=examples/gpu_checks/_wave_head.sh
source "$(dirname "$0")/_wave_head.sh"
case "$mode" in
sharded_ab)
    OUT="$dir" PARTS="a b" BUDGET=${BUDGET:-400} bash examples/gpu_checks/sharded_x4.sh
    ;;
sharded_c)
    OUT="$dir" PARTS=c BUDGET=${BUDGET:-540} bash examples/gpu_checks/sharded_x4.sh
    ;;
loop)
    WARPTRUNC_DEVICE=cuda:0 timeout 120 python3 -m pytest -q -p no:cacheprovider \
        tests/test_device_loop.py tests/test_westergaard.py 2>&1 | tail -3
    timeout 60 python3 -m pytest -q -p no:cacheprovider -m gpu tests/test_sweep_batch.py 2>&1 \
        | tail -3
    OUT="$dir" TAMAAS_LIMIT=${TAMAAS_LIMIT:-400} bash examples/gpu_checks/solver_loop.sh
    ;;
workers)
    OUT="$dir" BUDGET_S=${BUDGET_S:-330} bash examples/gpu_checks/workers_bench.sh
    ;;
indent2)
    budget=${2:-200}
    CUDA_VISIBLE_DEVICES=0,1 OUT="$dir" REPRO=/tmp/wt_repro2 \
        bash examples/gpu_checks/wave6_checks.sh indent "$budget"
    ;;
*)
    echo "unknown mode $mode"
    exit 2
    ;;
esac
echo "wave7.sh $mode: ${SECONDS} s"
