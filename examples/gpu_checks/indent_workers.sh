#!/usr/bin/env bash
# The reproduce indentation stage on every GPU of the host (issue 39, items 3(c) and 4):
# examples/benchmarks/benchmark_indentation_workers.py. Whole `warptrunc reproduce --profile paper
# --stages indentation` processes, the paper profile with its indentation map at N² pixels
# (default N=2048: 488 nm pixels over 1 mm instead of the paper's 10240², 97.7 nm; a departure,
# recorded in the JSON), in process on cuda:0, then on N_GPU, 2 and 1 Dask workers (one per GPU;
# the largest count written `--workers auto`), after an untimed warm-up that compiles the
# kernels. Per run: wall time, speed-up, pieces, the sum of the pieces' own seconds, the busiest
# device's seconds; the in-process run again on its finished store (fixed_s); and the stage's
# stored numbers of each worker run compared bit for bit with in process.
# Run on the 4-GPU kind (nvidia-h100-x4) or the 2-GPU kind, from the repo root, staged as for
# workers_bench.sh (dask and distributed installed; the machine has no git: name the commit):
#   WARPTRUNC_GIT_COMMIT=<sha> bash examples/gpu_checks/indent_workers.sh
# Results in $OUT (or ./indent_workers_out): benchmark_indentation_workers.json (GPUs, Warp,
# commit, the profile's departures from the paper, every command and measure), commands.log
# (the children's output) and benchmark_stderr.log; the table is printed last.
# A subset of the GPUs: GPUS=0,1 (sets CUDA_VISIBLE_DEVICES; worker counts 2 1). Map size: N
# (pixels per side over 1 mm). Extra arguments of the benchmark: $BENCH_ARGS. A dry run on a CPU
# machine (about 30 s on 2 cores): N=128 BENCH_ARGS="--profile tiny --device cpu --workers 2" bash ...
# Time, measured (4 x H200, fab6f70, benchmarks/records/indentation_workers_h200x4_fab6f70.json): at N=2048
# the pieces' own seconds sum to 536 GPU-s; in process 510.6 s, 4 workers 152.3 s; the warm-up on
# a fresh machine about 60 s. So one 10-minute call holds in process alone, or the workers: run
#   1st call: BENCH_ARGS="--workers" BUDGET_S=560 bash examples/gpu_checks/indent_workers.sh
#   2nd call: BENCH_ARGS="--no-inprocess --workers 4 2 --reference A/values_inproc.json.gz
#             --reference-wall WALL" bash examples/gpu_checks/indent_workers.sh
# (A: the first call's OUT, carried back; WALL: its in-process wall). No timed run starts after
# BUDGET_S (default 420 s) or when expected to end past it ("skipped: budget"), and none runs
# more than 30 s past it or longer than TIMEOUT_S (default 580 s; stopped, rc 124).
set -uo pipefail
OUT=${OUT:-indent_workers_out}
mkdir -p "$OUT"
python3 -c "import warptrunc" 2>/dev/null || python3 -m pip install -q --no-deps --no-build-isolation -e . >/dev/null 2>&1 || true
nvidia-smi -L || true
if [ -n "${GPUS:-}" ]; then  # a subset of the host's GPUs: the workers see only these
    export CUDA_VISIBLE_DEVICES=$GPUS
    echo "GPUS=$GPUS: CUDA_VISIBLE_DEVICES=$CUDA_VISIBLE_DEVICES"
fi
# shellcheck source=examples/gpu_checks/_dask_head.sh
source "$(dirname "$0")/_dask_head.sh"
t0=$(date +%s)
# shellcheck disable=SC2086  # BENCH_ARGS: several words
python3 examples/benchmarks/benchmark_indentation_workers.py --out "$OUT" --n "${N:-2048}" \
    --budget-s "${BUDGET_S:-420}" --grace-s 30 --timeout-s "${TIMEOUT_S:-580}" ${BENCH_ARGS:-} \
    2> "$OUT/benchmark_stderr.log"
status=$?
[ $status -ne 0 ] && tail -n 30 "$OUT/benchmark_stderr.log"
echo "indent_workers.sh: $(( $(date +%s) - t0 )) s, exit $status"
exit $status
