#!/usr/bin/env bash
# GPU checks of the sixth wave (issues 38, 39): the paper profile's indentation stage on every GPU
# of the host (one Dask worker per GPU), resumable across calls.
# Usage on the GPU machine, after the staging of ../shared/device/README.md (with the dask wheels):
#   bash examples/gpu_checks/wave6_checks.sh indent 480   # run / continue the stage for ≤ 480 s of new parts
#   bash examples/gpu_checks/wave6_checks.sh tests        # the parts' CPU tests and the workers' tests on cuda
# The reproduction folder is $REPRO (default /tmp/wt_repro: it survives between calls while the
# machine stays warm); its report, stage file and pieces are copied under $OUT (default ./gpu_out).
set -uo pipefail
OUT=${OUT:-gpu_out}; mkdir -p "$OUT"
REPRO=${REPRO:-/tmp/wt_repro}
nvidia-smi --query-gpu=index,name,memory.total --format=csv,noheader | tee "$OUT/device.txt"
git rev-parse --short HEAD 2>/dev/null | tee "$OUT/commit.txt"
case "${1:-indent}" in
indent)
  budget=${2:-480}
  start=$(date +%s.%N)
  python3 -m warptrunc reproduce --profile paper --stages indentation --workers auto \
    --time-budget "$budget" --out "$REPRO" 2>&1 | tee -a "$OUT/indent_log.txt" | grep -v "^\s" | tail -15
  end=$(date +%s.%N)
  echo "call wall: $(python3 -c "print(f'{$end - $start:.1f}')") s" | tee -a "$OUT/indent_calls.txt"
  mkdir -p "$OUT/repro"
  cp -r "$REPRO/indentation" "$OUT/repro/" 2>/dev/null
  cp -r "$REPRO/stages" "$OUT/repro/" 2>/dev/null
  cp "$REPRO"/report.md "$REPRO"/results.json "$REPRO"/*.png "$OUT/repro/" 2>/dev/null
  ls "$REPRO/indentation" | wc -l
  ;;
tests)
  WARPTRUNC_DEVICE=cuda:0 timeout 300 python3 -m pytest -q -p no:cacheprovider \
    tests/test_reproduce_workers.py tests/test_indent_face.py 2>&1 | tail -5
  ;;
esac
