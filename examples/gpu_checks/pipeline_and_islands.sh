#!/usr/bin/env bash
# Device-resident pipeline and islands on cuda:0: tests on cpu and cuda:0, benchmark_pipeline.py at
# 10240² and 4096², benchmark_islands.py at 10240².
# Run on the GPU machine from the repository root:  OUT=/some/dir bash pipeline_and_islands.sh
# Writes $OUT/pytest_8a.txt, $OUT/bench.json (10240², end to end) and $OUT/bench_cpu_ref.txt.
set -u
OUT=${OUT:-$(pwd)/gpu_out_8a}
mkdir -p "$OUT"
python -c "import warp as wp; wp.init(); print(wp.get_device('cuda:0').name)" | tee "$OUT/device.txt"
python -c "import cupy; print('cupy', cupy.__version__)" 2>&1 | tail -1 | tee -a "$OUT/device.txt"
# 1. the tests of the device-resident surfaces, on cpu and cuda:0 (the conftest device fixture)
WARPTRUNC_TEST_DEVICES=cpu,cuda:0 python -m pytest -q -p no:cacheprovider \
    tests/test_surface.py tests/test_islands.py tests/test_truncation.py tests/test_wm.py \
    tests/test_descriptors.py tests/test_fractal.py 2>&1 | tee "$OUT/pytest_8a.txt" | tail -30
# 2. end-to-end benchmark at 10240² (generate → truncate → stiffness → fit; islands with
#    statistics at 200 depths; describe + four D methods; CuPy references when installed)
python examples/benchmarks/benchmark_pipeline.py --device cuda:0 --n 10240 --repeats 7 \
    --out "$OUT" --json "$OUT/bench.json" 2>&1 | tail -12
# 3. a smaller size for the ratio to 10240²
python examples/benchmarks/benchmark_pipeline.py --device cuda:0 --n 4096 --repeats 7 --no-kernels \
    --out "$OUT/n4096" --json "$OUT/bench_4096.json" 2>&1 | tail -4
# 4. labelling with per-island statistics from a NumPy mask and from a device mask (10240²)
python examples/benchmarks/benchmark_islands.py --device cuda:0 --n 10240 --out "$OUT/islands" 2>&1 | tail -12
