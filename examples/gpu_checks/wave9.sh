#!/usr/bin/env bash
# GPU checks after the fixes of fab6f70 → 20c8bec and later (issues 39 and 42), on a 4-GPU host
# with 141-GB GPUs (nvidia-h200-x4), one mode per device call, back to back:
#   bash examples/gpu_checks/wave9.sh big       # 42 (c) again: bem-check --n 65536 --devices 4
#                                               # (the FFT-size fix and the unit-force check),
#                                               # then (a): 16384² f32 on 1, 2, 4 and 32768² f32 on
#                                               # 4, recording the GPU compile's memory (≈ 560 s)
#   bash examples/gpu_checks/wave9.sh f64wm     # 42 (b): 32768² float64 on 2 GPUs on the D = 2.5
#                                               # WM map (the paper's kind; ≈ 250 s)
#   bash examples/gpu_checks/wave9.sh inproc    # 39 (c): the indentation stage at 2048² in process
#                                               # alone (≈ 520 s; keeps values_inproc.json.gz)
#   bash examples/gpu_checks/wave9.sh workers   # 39 (c): 4 and 2 workers against that in-process
#                                               # run (≈ 150 + 270 s), on the same warm machine
# Results under $OUT/<mode>/ (default ./gpu_out); `inproc` leaves its values in
# /tmp/wave9_inproc for `workers`. The machine has no git: pass WARPTRUNC_GIT_COMMIT. Run after
# the staging of ../shared/device/README.md (PYTHONPATH=/tmp/site).
set -uo pipefail
MODES="big, f64wm, inproc or workers"
# shellcheck source=examples/gpu_checks/_wave_head.sh
source "$(dirname "$0")/_wave_head.sh"
export MAPS=${MAPS:-/tmp/maps}
case "$mode" in
big)
    OUT="$dir" PARTS=c BUDGET=${BUDGET_C:-380} bash examples/gpu_checks/sharded_x4.sh
    OUT="$dir/a" PARTS=a BUDGET=$((${BUDGET:-560} - SECONDS)) bash examples/gpu_checks/sharded_x4.sh
    ;;
f64wm)  # 42 (b) on the paper's kind of map: 32768² float64 on GPUs 0,1, the D = 2.5 WM surface
    CUDA_VISIBLE_DEVICES=0,1 OUT="$dir" PARTS=b F64_MAP=wm BUDGET=${BUDGET:-400} \
        bash examples/gpu_checks/sharded_x4.sh
    ;;
inproc)
    OUT=/tmp/wave9_inproc BENCH_ARGS="--workers" BUDGET_S=${BUDGET_S:-560} \
        bash examples/gpu_checks/indent_workers.sh
    cp /tmp/wave9_inproc/benchmark_indentation_workers.json /tmp/wave9_inproc/commands.log "$dir/"
    ;;
workers)
    ref=/tmp/wave9_inproc/values_inproc.json.gz
    wall=$(python3 -c "import json; r=[x for x in json.load(open('/tmp/wave9_inproc/benchmark_indentation_workers.json'))['runs'] if x['run']=='inproc']; print(r[0]['wall_s'])")
    OUT="$dir" BENCH_ARGS="--no-inprocess --warmup-n 0 --workers 4 2 --reference $ref --reference-wall $wall" \
        BUDGET_S=${BUDGET_S:-540} bash examples/gpu_checks/indent_workers.sh
    ;;
*)
    echo "unknown mode $mode"
    exit 2
    ;;
esac
echo "wave9.sh $mode: ${SECONDS} s"
