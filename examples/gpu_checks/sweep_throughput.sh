#!/usr/bin/env bash
# Sweep throughput (issue 21). Each command prints one table naming the device.
#  (a) one GPU (H100): light cases, run_sweep in process against the kernel loop
#      (targets: 2048² ≥ 2000 surfaces/s, 10240² ≥ 200 surfaces/s);
#  (b) the machine's CPU cores: LocalCluster of 1, 2, 4, 8 CPU workers on elastic 512² cases
#      (target: ≥ 0.8 × linear up to 8);
#  (c) two workers sharing one GPU against one worker (target ≥ 1.0×).
# (b) and (c) need dask/distributed. Results are appended to $OUT/bench_sweep.jsonl.
set -euo pipefail
unset WARPTRUNC_DEVICE
OUT=${OUT:-gpu_out}
mkdir -p "$OUT"
python examples/benchmarks/benchmark_sweep.py --n 2048 10240 --cases 200 --json "$OUT/bench_sweep.jsonl"
python examples/benchmarks/benchmark_sweep.py --device cpu --n 512 --cases 64 --bem-fractions 0.05 0.1 0.2 \
    --runs workers --workers 1 2 4 8 --json "$OUT/bench_sweep.jsonl"
python examples/benchmarks/benchmark_sweep.py --device cuda:0 --n 512 --cases 128 --bem-fractions 0.05 0.1 0.2 \
    --runs workers --workers 1 2 --json "$OUT/bench_sweep.jsonl"
