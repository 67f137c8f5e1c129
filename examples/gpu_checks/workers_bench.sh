#!/usr/bin/env bash
# Sweeps on every GPU of the host: whole `warptrunc sweep` commands
# in process on cuda:0, then on 1, 2, 4 Dask workers (one per GPU; the largest count written
# `--workers auto`), for 2000 light cases at 2048² and 96 elastic cases at 4096²
# (--bem-fractions 0.1), with where the time goes; then whether the stored rows are identical
# bit for bit (in process twice on cuda:0, and 2 and N workers against in process).
# Run on a 4- or 2-GPU host from the repo root, with warptrunc, dask and distributed importable
# (where the GPU machine's packages live in $STAGE, default /tmp/site, installed with
# `pip install --target`: PYTHONPATH=$STAGE):
#   python3 -m pip install -q --no-deps --no-build-isolation --no-index . && \
#     WARPTRUNC_GIT_COMMIT=<sha> bash examples/gpu_checks/workers_bench.sh
# (the machine has no git: name the commit). Results in $OUT (or ./workers_bench_out):
# benchmark_workers.json (GPUs, commit, commands, every measure) and commands.log; the table
# is printed last. Extra arguments of the benchmark: $BENCH_ARGS.
# A dry run on a CPU machine: SMALL=1 BENCH_ARGS="--device cpu --workers 2" bash ...
# A subset of the GPUs of the host: GPUS=0,1 (sets CUDA_VISIBLE_DEVICES; worker counts 1 2 …
# up to the GPUs named, the check on 2). More light cases: LIGHT_CASES=20000 (seeds 0-4999 over
# the 4 D values, --light-cases of the benchmark), to see where the cluster's start stops
# mattering.
# Needs dask and distributed (the WHEELS line of sweep_two_gpus.sh), not dask-cuda: without it
# the LocalCluster with one worker pinned per GPU is used.
# Time on 4 H100s: about 6 min (total_s of benchmarks/records/workers_h100x4_1b64d9c.json). Worker
# counts run largest first; no timed run starts after BUDGET_S (default 300 s) or when it is
# expected to end more than 45 s past it (skipped), and none runs longer (stopped, rc 124); the
# check (≈ 60 s) runs last (the elastic `--workers 1` run, ≈ in process + 5 s, is the first to be
# cut).
set -uo pipefail
OUT=${OUT:-workers_bench_out}
mkdir -p "$OUT"
python3 -c "import warptrunc" 2>/dev/null || python3 -m pip install -q --no-deps --no-build-isolation -e . >/dev/null 2>&1 || true
nvidia-smi -L || true
NGPU=$(nvidia-smi -L 2>/dev/null | grep -c '^GPU' || true)
COUNTS=""
if [ -n "${GPUS:-}" ]; then  # a subset of the host's GPUs: the workers see only these
    export CUDA_VISIBLE_DEVICES=$GPUS
    NGPU=$(echo "$GPUS" | tr ',' '\n' | grep -c .)
    c=1
    while [ "$c" -lt "$NGPU" ]; do COUNTS="$COUNTS $c"; c=$((c * 2)); done
    COUNTS="--workers$COUNTS $NGPU"
    echo "GPUS=$GPUS: CUDA_VISIBLE_DEVICES=$CUDA_VISIBLE_DEVICES, $COUNTS"
fi
LIGHT=""
[ -n "${LIGHT_CASES:-}" ] && LIGHT="--light-cases $LIGHT_CASES"
# shellcheck source=examples/gpu_checks/_dask_head.sh
DASK_HEAD_MODULES="pandas pyarrow" source "$(dirname "$0")/_dask_head.sh"
CHECK="2"
[ "${NGPU:-0}" -gt 2 ] && CHECK="2 $NGPU"
t0=$(date +%s)
# shellcheck disable=SC2086  # BENCH_ARGS: several words
SIZES="--full"
[ "${SMALL:-0}" = 1 ] && SIZES=""
python3 examples/benchmarks/benchmark_workers.py $SIZES --out "$OUT" \
    --budget-s "${BUDGET_S:-300}" --grace-s 45 --timeout-s 240 --check-workers $CHECK $COUNTS \
    $LIGHT ${BENCH_ARGS:-} \
    2> "$OUT/benchmark_stderr.log"
status=$?
[ $status -ne 0 ] && tail -n 30 "$OUT/benchmark_stderr.log"
echo "workers_bench.sh: $(( $(date +%s) - t0 )) s, exit $status"
exit $status
