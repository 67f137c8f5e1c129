#!/usr/bin/env bash
# GPU checks of the eighth wave (issues 39 and 42) on a 4-GPU host, one mode per device call:
#   bash examples/gpu_checks/wave8.sh big      # 42 (c): bem-check --n 65536 --devices 4 (H200s)
#   bash examples/gpu_checks/wave8.sh f64      # the suite's device-loop tests on cuda:0; 42 (b):
#                                              # 32768² float64 on GPUs 0,1 to convergence, beside
#                                              # 39: LIGHT_CASES light cases on GPUs 2,3 (in process,
#                                              # 1 and 2 workers); then sweep --workers 2 --devices 2
#   bash examples/gpu_checks/wave8.sh indent   # 39 (c): the indentation stage in process, on 1, 2
#                                              # and 4 workers (indent_workers.sh)
# Results under $OUT/<mode>/ (default ./gpu_out). The machine has no git: pass
# WARPTRUNC_GIT_COMMIT. Run after the staging of ../shared/device/README.md (PYTHONPATH=/tmp/site).
set -uo pipefail
MODES="big, f64 or indent"
# shellcheck source=examples/gpu_checks/_wave_head.sh
source "$(dirname "$0")/_wave_head.sh"
case "$mode" in
big)
    OUT="$dir" PARTS=c BUDGET=${BUDGET:-540} bash examples/gpu_checks/sharded_x4.sh
    ;;
f64)
    WARPTRUNC_DEVICE=cuda:0 WARPTRUNC_TEST_DEVICES=cuda:0 timeout 90 python3 -m pytest -q -p no:cacheprovider \
        tests/test_device_loop.py tests/test_westergaard.py 2>&1 \
        | tail -3 | tee "$dir/tests.txt"
    (CUDA_VISIBLE_DEVICES=0,1 OUT="$dir/b" PARTS=b BUDGET=${BUDGET_B:-330} \
        bash examples/gpu_checks/sharded_x4.sh >"$dir/b.log" 2>&1) &
    b=$!
    if [ -n "${LIGHT_CASES:-}" ]; then
        OUT="$dir/light" GPUS=2,3 LIGHT_CASES=$LIGHT_CASES BUDGET_S=${BUDGET_L:-240} \
            BENCH_ARGS="--runs light" bash examples/gpu_checks/workers_bench.sh \
            >"$dir/light.log" 2>&1
    fi
    wait $b
    tail -12 "$dir/b.log"
    tail -14 "$dir/light.log" 2>/dev/null
    OUT="$dir/groups" bash examples/gpu_checks/sweep_groups.sh
    ;;
indent)
    OUT="$dir" BUDGET_S=${BUDGET_S:-480} bash examples/gpu_checks/indent_workers.sh
    ;;
*)
    echo "unknown mode $mode"
    exit 2
    ;;
esac
echo "wave8.sh $mode: ${SECONDS} s"
