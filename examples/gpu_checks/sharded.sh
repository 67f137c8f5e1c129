#!/usr/bin/env bash
# One contact problem over 2–4 GPUs: 2 GPUs against 1 at CHECK_N² (free and periodic,
# float64 and float32), then the sharded FFT floor, per-iteration time and peak memory per GPU
# at SCALE_N² on 1, 2, 4 GPUs (strong scaling) and WEAK_N² on 4 (weak scaling). Run on a 2- or
# 4-GPU machine from the repo root:
#   OUT=sharded_out bash examples/gpu_checks/sharded.sh
# Results: $OUT/sharded.jsonl (one JSON line per measurement, errors included),
# $OUT/sharded_summary.json and the table printed at the end; each step's log in $OUT/log_*.txt.
# Every step runs in its own process under `timeout`, within a total budget of BUDGET seconds
# (default 330, so that the whole script ends within 6 minutes); a step that fails or times out
# is recorded and the next one goes on. Sizes: CHECK_N (4096), SCALE_N (16384), WEAK_N (32768),
# DTYPE (float32) of the scaling runs; EXTRA="solve --n 32768 --ndev 2 --dtype float64" adds one
# more step (e.g. the paper's map in float64 on 2 GPUs, given the time).
set -uo pipefail
OUT=${OUT:-sharded_out}
mkdir -p "$OUT"
export XLA_PYTHON_CLIENT_PREALLOCATE=false  # JAX would take 75 % of every GPU at start
# the most JAX may allocate on a GPU (its default, 0.75, would refuse the largest maps)
export XLA_PYTHON_CLIENT_MEM_FRACTION=${XLA_PYTHON_CLIENT_MEM_FRACTION:-0.95}
CHECK_N=${CHECK_N:-4096}
SCALE_N=${SCALE_N:-16384}
WEAK_N=${WEAK_N:-32768}
DTYPE=${DTYPE:-float32}
BUDGET=${BUDGET:-330}
MAPS=${MAPS:-$OUT/maps}
J="$OUT/sharded.jsonl"
B=examples/benchmarks/benchmark_sharded.py
start=$SECONDS
pip install -q --no-deps --no-build-isolation -e . >/dev/null 2>&1 || true
nvidia-smi -L
NGPU=$(nvidia-smi -L | wc -l)
python -c "import jax; print('jax', jax.__version__, jax.devices())" || {
    echo "JAX with CUDA is missing (pip install 'jax[cuda12]')"; exit 1; }

step() {  # step LIMIT ARGS...: one process, bounded by LIMIT and by what is left of BUDGET
    local limit=$1
    shift
    local left=$((BUDGET - (SECONDS - start)))
    local name
    name=$(echo "$*" | tr ' ' '_' | tr -d '-')
    if [ "$left" -lt 15 ]; then
        echo "{\"step\": \"$1\", \"args\": \"$*\", \"error\": \"skipped: budget of ${BUDGET} s spent\"}" >>"$J"
        echo "skipped (budget): $*"
        return
    fi
    [ "$limit" -gt "$left" ] && limit=$left
    timeout "$limit" python "$B" "$@" --jsonl "$J" --maps "$MAPS" >"$OUT/log_$name.txt" 2>&1
    local rc=$?
    if [ "$rc" -ne 0 ]; then
        echo "{\"step\": \"$1\", \"args\": \"$*\", \"error\": \"exit $rc (124: timed out after $limit s)\"}" >>"$J"
    fi
    echo "$* -> exit $rc at $((SECONDS - start)) s"
}

# 1. correctness: 2 GPUs against 1 (Warp on cuda:0, direct_max=0), 4 cases
step 110 check --n "$CHECK_N"
# 2. the maps of the scaling runs, made once on the host (cached as .npy)
step 60 maps --n "$SCALE_N"
[ "$NGPU" -ge 4 ] && step 60 maps --n "$WEAK_N"
# 3. strong scaling at SCALE_N² (2 GPUs first), then weak scaling on 4
step 90 solve --n "$SCALE_N" --ndev 2 --dtype "$DTYPE"
step 45 solve --n "$SCALE_N" --ndev 1 --dtype "$DTYPE"
[ "$NGPU" -ge 4 ] && step 80 solve --n "$SCALE_N" --ndev 4 --dtype "$DTYPE"
[ "$NGPU" -ge 4 ] && step 100 solve --n "$WEAK_N" --ndev 4 --dtype "$DTYPE"
# shellcheck disable=SC2086
[ -n "${EXTRA:-}" ] && step 120 $EXTRA
python "$B" report --jsonl "$J"
echo "total $((SECONDS - start)) s"
