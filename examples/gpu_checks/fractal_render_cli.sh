#!/usr/bin/env bash
# Fractal dimension, render and CLI output on cuda:0; run from the repository root.
# - D_tri/D_box with height_scaling="cube" upload a rescaled copy of the heights to cuda:0;
#   the kernels are unchanged, so cpu and cuda:0 must agree (tests over the device fixture).
# - Pictures: area pooling (block contact fraction) on a device-made contact index.
# - Output: with a CUDA driver present the Warp notice never appears; nothing else printed.
set -euo pipefail
export WARPTRUNC_TEST_DEVICES=cpu,cuda:0
python -m pytest -q tests/test_fractal.py tests/test_render.py tests/test_cli_output.py \
    tests/test_import_layout.py tests/test_cli_bad_input.py
# the evidence table on the GPU (1024², 3 seeds): values must match the README's CPU table
WARPTRUNC_DEVICE=cuda:0 python examples/benchmarks/height_scaling_evidence.py --n 1024 --seeds 0 1 2 --device cuda:0
