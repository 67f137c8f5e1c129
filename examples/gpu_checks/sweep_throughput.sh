#!/usr/bin/env bash
# Sweep throughput (surfaces/s) with chunked tasks, with and without worker-written curves, one
# GPU against two (issue 9, item 6: ≥ 1.8× with two GPUs). Run on nvidia-h200-x2.
set -euo pipefail
unset WARPTRUNC_DEVICE
python examples/benchmarks/benchmark_sweep.py --n 2048 10240 --cases 40 --workers 0 2                    # default (worker writes on GPUs)
python examples/benchmarks/benchmark_sweep.py --n 2048 --cases 40 --workers 2 --no-worker-writes        # client writes, chunked
python examples/benchmarks/benchmark_sweep.py --n 2048 --cases 200 --workers 0 2                         # longer run: steady rate
