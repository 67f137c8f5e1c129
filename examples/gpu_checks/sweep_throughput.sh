#!/usr/bin/env bash
# GPU check for branch sweep-fast (issue 9, item 6: ≥ 1.8× with two GPUs). Run on nvidia-h200-x2.
set -euo pipefail
unset WARPTRUNC_DEVICE
python examples/benchmark_sweep.py --n 2048 10240 --cases 40 --workers 0 2                    # default (worker writes on GPUs)
python examples/benchmark_sweep.py --n 2048 --cases 40 --workers 2 --no-worker-writes        # client writes, chunked
python examples/benchmark_sweep.py --n 2048 --cases 200 --workers 0 2                         # longer run: steady rate
