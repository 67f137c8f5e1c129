#!/usr/bin/env bash
# The two distributed FFT engines' floors for the padded transform pair on 2 GPUs:
# examples/benchmarks/benchmark_fft_engines.py — JAX/XLA sharded in one process
# (`jax`, plus the solver's pruned convolution `jax-pruned`) against cuFFTMp through
# nvmath-python in 2 MPI ranks (`cufftmp`), at N in NS (default "8192 16384", padded to 2N),
# float32 then float64, each checked against numpy float64 at 256² first.
#
# Run from the repository root on a machine with 2 or more GPUs:
#   OUT=fft_engines_out WHEELS=/path/to/wheels bash examples/gpu_checks/fft_engines.sh
# WHEELS (optional): a folder of wheels (nvmath-python, cupy, mpi4py, nvidia-nvshmem,
# nvidia-cufftmp, ...) installed with --no-index --no-deps into $STAGE (default /tmp/site), which
# is put on PYTHONPATH when PYTHONPATH is unset. GPUS (0,1), NS, REPEATS (10), BUDGET (240 s)
# and STEP (75 s, the most one step may take) are read too. MPI: mpiexec on PATH (Open MPI gets
# --allow-run-as-root).
# Results: $OUT/fft_engines.jsonl (one JSON line per engine, n, ndev, dtype; errors included),
# the table printed at the end, each step's log in $OUT/log_*.txt. Every step runs in its own
# process under `timeout` (at most STEP s), within BUDGET seconds in all: a hang costs one step;
# a step that fails or times out is recorded and the next goes on. Expected time: 2–4 minutes
# (JAX's start and compiles, NVSHMEM's start, 12 timed calls per case). CPU dry run (no cuFFTMp):
#   JAX_PLATFORMS=cpu XLA_FLAGS=--xla_force_host_platform_device_count=2 NS="32 64" bash ...
set -uo pipefail
OUT=${OUT:-fft_engines_out}
mkdir -p "$OUT"
STAGE=${STAGE:-/tmp/site}
export PYTHONPATH=${PYTHONPATH:-$STAGE} PYTHONUNBUFFERED=1
export CUDA_VISIBLE_DEVICES=${GPUS:-0,1}
export XLA_PYTHON_CLIENT_PREALLOCATE=false  # JAX would take 75 % of every GPU at start
NS=${NS:-8192 16384}
REPEATS=${REPEATS:-10}
BUDGET=${BUDGET:-240}
STEP=${STEP:-75}
J="$OUT/fft_engines.jsonl"
B=examples/benchmarks/benchmark_fft_engines.py
start=$SECONDS

if [ -n "${WHEELS:-}" ] && compgen -G "$WHEELS/*.whl" >/dev/null; then
    python3 -m pip install -q --no-index --no-deps --target "$STAGE" "$WHEELS"/*.whl \
        >"$OUT/log_pip.txt" 2>&1 || echo "pip install of $WHEELS failed (log_pip.txt)"
fi
# cuda-pathfinder does not look on PYTHONPATH for libcufftMp (measured: "Failure finding
# libcufftMp.so.12" with the wheel installed under $STAGE): put its folder on LD_LIBRARY_PATH
IFS=: read -ra entries <<< "$PYTHONPATH"
for e in "${entries[@]}"; do
    if [ -d "$e/nvidia/cufftmp/cu13/lib" ]; then
        export LD_LIBRARY_PATH="$e/nvidia/cufftmp/cu13/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    fi
done
echo "commit ${WARPTRUNC_GIT_COMMIT:-unknown}, GPUs $CUDA_VISIBLE_DEVICES"
nvidia-smi -L
timeout 60 python3 "$B" diag | tee "$OUT/diag.json"
MPIEXEC=(mpiexec -n 2)
if command -v mpiexec >/dev/null; then
    if mpiexec --version 2>&1 | grep -qiE "open ?mpi|openrte"; then
        MPIEXEC=(mpiexec --allow-run-as-root -n 2)
        export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    fi
    mpiexec --version 2>&1 | head -2
else
    echo "mpiexec not found: the cufftmp steps will fail (recorded)"
fi

step() {  # step ENGINE DTYPE: one process (MPI ranks for cufftmp), bounded by STEP and BUDGET
    local engine=$1 dtype=$2
    local left=$((BUDGET - (SECONDS - start)))
    local limit=$STEP
    local log="$OUT/log_${engine}_${dtype}.txt"
    if [ "$left" -lt 20 ]; then
        echo "{\"record\": \"measurement\", \"engine\": \"$engine\", \"dtype\": \"$dtype\", \"ndev\": 2, \"error\": \"skipped: budget of ${BUDGET} s spent\"}" >>"$J"
        echo "skipped (budget): $engine $dtype"
        return
    fi
    [ "$limit" -gt "$left" ] && limit=$left
    # shellcheck disable=SC2086
    local args=(--n $NS --ndev 2 --dtype "$dtype" --repeats "$REPEATS" --jsonl "$J")
    if [ "$engine" = cufftmp ]; then
        timeout -k 10 "$limit" "${MPIEXEC[@]}" python3 "$B" cufftmp "${args[@]}" >"$log" 2>&1
    else
        timeout -k 10 "$limit" python3 "$B" jax "${args[@]}" >"$log" 2>&1
    fi
    local rc=$?
    if [ "$rc" -ne 0 ]; then
        echo "{\"record\": \"measurement\", \"engine\": \"$engine\", \"dtype\": \"$dtype\", \"ndev\": 2, \"error\": \"exit $rc (124: timed out after $limit s); see $log\"}" >>"$J"
        tail -5 "$log"
    fi
    echo "$engine $dtype -> exit $rc at $((SECONDS - start)) s"
}

# float32 on both engines first, then float64: a short budget still gives both engines' floors
step jax float32
step cufftmp float32
step jax float64
step cufftmp float64
python3 "$B" report --jsonl "$J"
echo "total $((SECONDS - start)) s"
