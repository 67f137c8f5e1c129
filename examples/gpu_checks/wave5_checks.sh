#!/usr/bin/env bash
# GPU checks of the fifth wave (issues 37, 38): the suite's solver, indentation and WM tests on
# cuda:0, then the refinement of indentation cells at the paper's pixel on one surface.
# Usage on the GPU machine, after the staging of ../shared/device/README.md:
#   bash examples/gpu_checks/wave5_checks.sh tests      # the tests on cuda:0 (≈ 3 min)
#   bash examples/gpu_checks/wave5_checks.sh refine     # GB300s (10240² over 1 mm, the paper's pixel), 54.1 µm punch, 3 placements, H = ∞
# Writes under $OUT (default ./gpu_out).
set -uo pipefail
OUT=${OUT:-gpu_out}; mkdir -p "$OUT"
nvidia-smi --query-gpu=name,memory.total --format=csv,noheader | tee "$OUT/device.txt"
git rev-parse --short HEAD 2>/dev/null | tee "$OUT/commit.txt"
case "${1:-tests}" in
tests)
  WARPTRUNC_TEST_DEVICES=cuda:0 WARPTRUNC_DEVICE=cuda:0 timeout 420 python3 -m pytest -q \
    -p no:cacheprovider --durations=15 tests/test_contact.py tests/test_bccg.py tests/test_plastic.py \
    tests/test_transforms.py tests/test_fft_plan.py tests/test_indent.py tests/test_indent_refine.py \
    tests/test_indent_face.py tests/test_wm.py tests/test_stiffness.py tests/test_analysis.py \
    tests/test_truncation.py tests/test_bem.py 2>&1 | tee "$OUT/pytest_cuda.txt" | tail -25
  ;;
refine)
  /usr/bin/time -v python3 -m warptrunc indent --preset GB300s --punch-diameter 54.1e-6 \
    --placements 3 --L 1e-3 --n 10240 --hardness inf --device cuda:0 --dtype float32 --out "$OUT/refine_gb300s" \
    2>&1 | tee "$OUT/refine_gb300s.txt" | grep -v "^\s" | tail -30
  ;;
esac
