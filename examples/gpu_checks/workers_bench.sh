#!/usr/bin/env bash
# Sweeps on every GPU of the host (issue 39, items 3 and 4): whole `warptrunc sweep` commands
# in process on cuda:0, then on 1, 2, 4 Dask workers (one per GPU; the largest count written
# `--workers auto`), for 2000 light cases at 2048² and 96 elastic cases at 4096²
# (--bem-fractions 0.1), with where the time goes; then whether the stored rows are identical
# bit for bit (in process twice on cuda:0, and 2 and N workers against in process).
# Run on the 4-GPU kind (nvidia-h100-x4) or the 2-GPU kind, from the repo root:
#   bash examples/gpu_checks/workers_bench.sh     # results in $OUT (or ./workers_bench_out)
# Writes $OUT/benchmark_workers.json (GPUs, commit, commands, every measure) and
# $OUT/commands.log; prints the table last. Extra arguments of the benchmark: $BENCH_ARGS.
# A dry run on a CPU machine: SMALL=1 BENCH_ARGS="--device cpu --workers 2" bash ...
# Needs dask and distributed: the WHEELS line of sweep_two_gpus.sh (pip install --no-deps).
# Not dask-cuda: without it the LocalCluster with one worker pinned per GPU is used.
# Time on 4 H100s, estimated from 2026-11-27 measurements (96 light 2048² cases: 2.6 s in
# process; 24 elastic 2048² cases with two fractions: 14.3 s; a 4096² solve about 3× a
# 2048² one): light ≈ 6 + 15 + 10 + 8 s, elastic ≈ 70 + 75 + 40 + 25 s, the check ≈ 40 s,
# clusters timed alone ≈ 20 s, the first (compiling) warm-ups ≈ 60 s: about 6 min. Worker
# counts run largest first; no timed run starts after BUDGET_S (default 300 s) and none runs
# past it by more than 60 s (then listed as rc 124), the check (≈ 60 s) last: at most 7 min.
set -uo pipefail
OUT=${OUT:-workers_bench_out}
mkdir -p "$OUT"
pip install -q --no-deps --no-build-isolation -e . >/dev/null 2>&1 || true
nvidia-smi -L || true
NGPU=$(nvidia-smi -L 2>/dev/null | grep -c '^GPU' || true)
python - <<'PY' || { echo "dask/distributed missing: install the WHEELS of sweep_two_gpus.sh"; exit 1; }
import dask, distributed, pandas, pyarrow
print("dask", dask.__version__, "distributed", distributed.__version__,
      "pandas", pandas.__version__, "pyarrow", pyarrow.__version__)
try:
    import dask_cuda
    print("dask-cuda", dask_cuda.__version__, "(LocalCUDACluster)")
except ImportError:
    print("no dask-cuda: LocalCluster, one worker pinned per GPU")
PY
CHECK="2"
[ "${NGPU:-0}" -gt 2 ] && CHECK="2 $NGPU"
t0=$(date +%s)
# shellcheck disable=SC2086  # BENCH_ARGS: several words
SIZES="--full"
[ "${SMALL:-0}" = 1 ] && SIZES=""
python examples/benchmarks/benchmark_workers.py $SIZES --out "$OUT" \
    --budget-s "${BUDGET_S:-300}" --grace-s 60 --timeout-s 240 --check-workers $CHECK ${BENCH_ARGS:-} \
    2> "$OUT/benchmark_stderr.log"
status=$?
[ $status -ne 0 ] && tail -n 30 "$OUT/benchmark_stderr.log"
echo "workers_bench.sh: $(( $(date +%s) - t0 )) s, exit $status"
exit $status
