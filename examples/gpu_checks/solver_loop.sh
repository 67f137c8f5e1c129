#!/usr/bin/env bash
# The contact solver's iteration on a GPU host, one call (about 6–8 min on an H100):
#  0. With TESTS=1, first the device-loop and Westergaard tests on cuda:0 and the GPU-marked
#     tests of the batched sweep.
#  1. In the background on the LAST GPU ($PEER_DEVICE, default the highest cuda:N): the peer
#     benchmark at N = $PEER_SIZES (default 2048) against tamaas on this host's cores, each
#     tamaas solve stopped after $TAMAAS_LIMIT s (default 420): the largest N tamaas finishes.
#     tamaas' pip wheel is serial (one core), so it hardly meets the foreground's work on cuda:0.
#  2. On cuda:0: benchmarks/iteration_breakdown.py (the host loop against the device loop, the
#     parts of an iteration) at 2048², 4096², 8192², 16384² float32 and 10240² float64; then
#     benchmarks/benchmark_solver_scaling.py (the solver table: cold/warm, float32 and float64,
#     per convolution ÷ the FFT floor) at 2048²–16384² both precisions and 32768² float32, with
#     SolverSettings.loop=$LOOP (default graph).
#  3. On cuda:0: benchmarks/startup.py, 5 fresh `warptrunc analyze --n 10240` processes against
#     the floor `import warp; warp.init(); warp.get_device('cuda:0')`, with the breakdown.
# Results under $OUT: breakdown/breakdown.json, scaling/scaling.json, peers_<dev>.json,
# startup_cuda0.json and the logs (the records solver_loop_*, solver_scaling_*, peers_*,
# startup_* of benchmarks/records/). PYTHONPATH: when unset, $STAGE (default /tmp/site), the
# folder the GPU machine's packages (tamaas among them) are installed into with
# `pip install --target`. Run from the repo root:
#   OUT=loop_out WARPTRUNC_GIT_COMMIT=<sha> bash examples/gpu_checks/solver_loop.sh
# A dry run on the CPU: DEVICE=cpu PEER_DEVICE=cpu SIZES="256 512" PEER_SIZES=64 N_START=256 ...
set -uo pipefail
: "${OUT:?set OUT to a folder for the results}"
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)  # absolute: the benchmarks run from examples/benchmarks
cd "$(dirname "$0")/../.." || exit 1
export PYTHONPATH=${PYTHONPATH:-${STAGE-/tmp/site}} MPLBACKEND=Agg PYTHONUNBUFFERED=1
export WARPTRUNC_GIT_COMMIT=${WARPTRUNC_GIT_COMMIT:-$(git rev-parse --short HEAD 2>/dev/null || echo unknown)}
PY=${PY:-python3}
DEVICE=${DEVICE:-cuda:0}
NGPU=$(nvidia-smi -L 2>/dev/null | grep -c '^GPU' || echo 0)
PEER_DEVICE=${PEER_DEVICE:-cuda:$((NGPU > 0 ? NGPU - 1 : 0))}
[ "$NGPU" -eq 0 ] && PEER_DEVICE=${PEER_DEVICE/cuda:0/cpu}
PEER_SIZES=${PEER_SIZES:-2048}
TAMAAS_LIMIT=${TAMAAS_LIMIT:-420}
SIZES=${SIZES:-"2048 4096 8192 16384"}
BIG=${BIG:-32768}
N_START=${N_START:-10240}
nvidia-smi -L 2>/dev/null || true
nproc
SECONDS=0

if [ "${TESTS:-0}" = 1 ]; then
    WARPTRUNC_DEVICE=cuda:0 WARPTRUNC_TEST_DEVICES=cuda:0 timeout 120 $PY -m pytest -q \
        -p no:cacheprovider tests/test_device_loop.py tests/test_westergaard.py 2>&1 | tail -3
    timeout 60 $PY -m pytest -q -p no:cacheprovider -m gpu tests/test_sweep_batch.py 2>&1 | tail -3
fi

peer_pid=
if $PY -c "import tamaas" 2>/dev/null; then
    # shellcheck disable=SC2086
    $PY examples/benchmarks/benchmark_peers.py --device "$PEER_DEVICE" --sizes $PEER_SIZES \
        --surfaces tamaas --substrates periodic --peers tamaas --reference warptrunc \
        --tamaas-tol "${TAMAAS_TOL:-1e-4}" --no-tamaas-one-thread --time-limit "$TAMAAS_LIMIT" \
        --out "$OUT" >"$OUT/peers.log" 2>&1 &
    peer_pid=$!
    echo "peers on $PEER_DEVICE in the background (pid $peer_pid)"
else
    echo "no tamaas: the peer benchmark is skipped"
fi

# shellcheck disable=SC2086
(cd examples/benchmarks && $PY iteration_breakdown.py --device "$DEVICE" --n $SIZES \
    --out "$OUT/breakdown") 2>&1 | grep -v "^Warp " | tee "$OUT/breakdown.log"
[ "$DEVICE" != cpu ] && (cd examples/benchmarks && $PY iteration_breakdown.py --device "$DEVICE" \
    --n 10240 --dtype float64 --out "$OUT/breakdown_f64") 2>&1 | grep -v "^Warp " \
    | tee -a "$OUT/breakdown.log"
echo "breakdown: ${SECONDS} s"

# shellcheck disable=SC2086
(cd examples/benchmarks && $PY benchmark_solver_scaling.py --device "$DEVICE" --n $SIZES \
    --dtype float32 float64 --loop "${LOOP:-graph}" --budget 200 --out "$OUT/scaling") 2>&1 | grep -v "^Warp " \
    | tee "$OUT/scaling.log"
[ "$DEVICE" != cpu ] && (cd examples/benchmarks && $PY benchmark_solver_scaling.py \
    --device "$DEVICE" --n "$BIG" --dtype float32 --loop "${LOOP:-graph}" --budget 150 \
    --out "$OUT/scaling_big") \
    2>&1 | grep -v "^Warp " | tee -a "$OUT/scaling.log"
echo "scaling: ${SECONDS} s"

$PY examples/benchmarks/startup.py --n "$N_START" --device "$DEVICE" --runs 5 --out "$OUT" 2>&1 \
    | grep -v "^   \|^Warp " | tee "$OUT/startup.log"
echo "startup: ${SECONDS} s"

if [ -n "$peer_pid" ]; then
    echo "waiting for the peer benchmark …"
    wait "$peer_pid"
    grep -v "^   \|^Warp " "$OUT/peers.log" | tail -n 25
fi
echo "solver_loop.sh: ${SECONDS} s"
