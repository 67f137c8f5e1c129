#!/usr/bin/env bash
# `warptrunc reproduce --profile paper` on a GPU host, one mode per call:
#   all                the reproduce tests on cuda:0, then the whole profile on cuda:0, timed, and
#                      a rerun that must reuse every stage (seconds); $dir/paper/ holds report.md,
#                      results.json, the figures and stages/
#   indentation [B]    the indentation stage on every GPU of the host (`--workers auto`, one Dask
#                      worker per GPU; dask and distributed installed) for at most B seconds of new
#                      parts (default 480), resumable: call it again until the stage is complete.
#                      The reproduction folder is $REPRO (default /tmp/wt_repro, kept while the
#                      machine stays warm); its report, stage file and pieces are copied to
#                      $dir/repro/ and each call's wall time appended to $dir/indent_calls.txt.
#                      CUDA_VISIBLE_DEVICES=0,1 runs it on two GPUs.
#   tests              the workers' and the punch face's tests on cuda:0
# Run from the repository root: OUT=gpu_out bash examples/gpu_checks/reproduce_paper_profile.sh
# [MODE]; results under $OUT/MODE/ (_mode_head.sh: PYTHONPATH from $STAGE, default /tmp/site,
# when unset). To keep a run as a record, copy its report.md and PNGs to
# benchmarks/records/reproduce_paper_<machine>_<commit>/ (benchmarks/records/README.md).
set -uo pipefail
MODES="all, indentation or tests"
DEFAULT_MODE=all
# shellcheck source=examples/gpu_checks/_mode_head.sh
source "$(dirname "$0")/_mode_head.sh"
case "$mode" in
all)
    python3 -c "import warp as wp; wp.init(); print(wp.get_cuda_devices())"
    WARPTRUNC_DEVICE=cuda:0 python3 -m pytest -q -p no:cacheprovider tests/test_reproduce.py
    time python3 -m warptrunc reproduce --profile paper --out "$dir/paper" --device cuda:0
    # the rerun: every stage must be reused (seconds)
    time python3 -m warptrunc reproduce --profile paper --out "$dir/paper" --device cuda:0
    grep -E "wall time|reused" "$dir/paper/report.md" | head -3
    ;;
indentation)
    REPRO=${REPRO:-/tmp/wt_repro}
    budget=${2:-480}
    start=$(date +%s.%N)
    python3 -m warptrunc reproduce --profile paper --stages indentation --workers auto \
        --time-budget "$budget" --out "$REPRO" 2>&1 | tee -a "$dir/indent_log.txt" \
        | grep -v "^\s" | tail -15
    end=$(date +%s.%N)
    echo "call wall: $(python3 -c "print(f'{$end - $start:.1f}')") s" | tee -a "$dir/indent_calls.txt"
    mkdir -p "$dir/repro"
    cp -r "$REPRO/indentation" "$REPRO/stages" "$dir/repro/" 2>/dev/null
    cp "$REPRO"/report.md "$REPRO"/results.json "$REPRO"/*.png "$dir/repro/" 2>/dev/null
    ls "$REPRO/indentation" | wc -l
    ;;
tests)
    WARPTRUNC_DEVICE=cuda:0 timeout 300 python3 -m pytest -q -p no:cacheprovider \
        tests/test_reproduce_workers.py tests/test_indent_face.py 2>&1 | tail -5
    ;;
*)
    echo "unknown mode $mode (modes: $MODES)"
    exit 2
    ;;
esac
echo "reproduce_paper_profile.sh $mode: ${SECONDS} s"
