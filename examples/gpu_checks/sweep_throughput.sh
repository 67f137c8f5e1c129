#!/usr/bin/env bash
# Sweep throughput. Each command prints one table naming the device; the results
# are appended to $OUT/bench_sweep.jsonl. Tables: docs/guide/sweeps_store.md ("Throughput").
#  (a) one GPU (H100): light cases, the kernel loop (one surface at a time), the batched kernel
#      loop and run_sweep in process (targets: 2048² ≥ 2000 surfaces/s, 10240² ≥ 200);
#  (b) two workers sharing one GPU against one worker, elastic 512² cases (target ≥ 1.0×);
#  (c) the machine's CPU cores: LocalCluster of 1, 2, 4, 8 CPU workers on elastic 512² cases
#      (target: ≥ 0.8 × linear up to 8; about 6 minutes).
# (b) and (c) need dask/distributed (the WHEELS line of sweep_two_gpus.sh).
set -euo pipefail
unset WARPTRUNC_DEVICE
OUT=${OUT:-gpu_out}
mkdir -p "$OUT"
cd "$(dirname "$0")/../benchmarks"
python benchmark_sweep.py --device cuda:0 --n 512 1024 2048 --cases 2000 --runs kernel batch inproc --json "$OUT/bench_sweep.jsonl"
python benchmark_sweep.py --device cuda:0 --n 10240 --cases 200 --runs kernel inproc --json "$OUT/bench_sweep.jsonl"
python benchmark_sweep.py --device cuda:0 --n 512 --cases 128 --bem-fractions 0.05 0.1 0.2 \
    --runs kernel workers --workers 1 2 --json "$OUT/bench_sweep.jsonl"
python benchmark_sweep.py --device cpu --n 512 --cases 64 --bem-fractions 0.05 0.1 0.2 \
    --runs workers --workers 1 2 4 8 --json "$OUT/bench_sweep.jsonl"
