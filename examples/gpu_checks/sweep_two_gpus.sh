#!/usr/bin/env bash
# Sweeps on GPUs: CUDA sweep equal to the CPU one, --workers 2 pinned one per GPU,
# throughput. Run on the 2-GPU kind (nvidia-h200-x2) from the repo root.
#   bash sweep_two_gpus.sh            # results in $OUT (or ./sweep_two_gpus_out)
# The GPU machine has pandas and pyarrow but not dask/distributed; install these wheels first
# (pip install --no-deps <wheel files>). All are pure Python except tornado (one small abi3
# C extension: the cp39-abi3 manylinux x86_64 wheel, any CPython >= 3.9; 6.6 needs >= 3.11); importlib_metadata and zipp are
# needed on Python < 3.12 only; pytest-timeout only arms the tests' hang guard.
# WHEELS: dask==2026.8.0 distributed==2026.8.0 partd==1.4.2 locket==1.0.0 tblib==3.2.2 zict==3.0.0 tornado==6.5.2 importlib_metadata==8.7.0 zipp==3.23.0 pytest-timeout==2.4.0
set -uo pipefail
OUT=${OUT:-sweep_two_gpus_out}
mkdir -p "$OUT"
pip install -q --no-deps --no-build-isolation -e . >/dev/null 2>&1 || true
nvidia-smi -L
NGPU=$(nvidia-smi -L | wc -l)
python - <<'PY' || { echo "dask/distributed missing: install the WHEELS line above"; exit 1; }
import dask, distributed, pandas, pyarrow
print("dask", dask.__version__, "distributed", distributed.__version__,
      "pandas", pandas.__version__, "pyarrow", pyarrow.__version__)
PY
status=0
# 1. the sweep tests (CPU cases, Dask cluster, kills) on this machine
WARPTRUNC_DEVICE=cpu python -m pytest -q tests/test_sweep.py 2>&1 | tail -5 || status=1
# 2. a CUDA sweep: in-process on cuda:0 equals the CPU sweep in counts; workers pinned per GPU
# (a file with a __main__ guard: Dask spawns its worker processes, which re-import __main__)
cat > "$OUT/check_sweep_gpu.py" <<'PY'
import sys

import numpy as np

from warptrunc.sweep import RUN_COLUMNS, SweepExecution, SweepGrid, SweepOptions, run_sweep


def main(out, ngpu):
    g = SweepGrid([2.3, 2.7], [0.01], "0-3")
    opts = SweepOptions(n=1024, min_pixels=(1, 10))
    gpu = run_sweep(g, f"{out}/store_gpu", options=opts, overwrite=True, progress=False, device="cuda:0")
    cpu = run_sweep(g, f"{out}/store_cpu", options=opts, overwrite=True, progress=False, device="cpu")
    assert gpu["error"].isna().all(), gpu["error"].dropna().unique()
    assert set(gpu["device"]) == {"cuda:0"}
    same = (gpu["final_contact_pixels"].to_numpy() == cpu["final_contact_pixels"].to_numpy()).mean()
    print(f"cuda:0 vs cpu: final contact pixels identical in {same:.0%} of rows; "
          f"max |dalpha| = {np.nanmax(np.abs(gpu.alpha - cpu.alpha)):.2e}")
    if ngpu >= 2:
        w = run_sweep(g, f"{out}/store_w2", options=opts, execution=SweepExecution(workers=2),
                      overwrite=True, progress=False)
        print("--workers 2 devices:", sorted(set(w["device"])), set(w["device_name"]))
        assert sorted(set(w["device"])) == ["cuda:0", "cuda:1"], "one worker per GPU"
        cols = [c for c in gpu.columns if c not in RUN_COLUMNS]
        print("2 workers = in-process on cuda:0:", gpu[cols].equals(w[cols]))
    print("CUDA sweep checks passed")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
PY
python "$OUT/check_sweep_gpu.py" "$OUT" "$NGPU" || status=1
# 3. throughput (surfaces/s): in-process on one GPU, then --workers 2 (one per GPU)
RUNS="kernel inproc"; WORKERS="1"; [ "$NGPU" -ge 2 ] && RUNS="kernel inproc workers" && WORKERS="1 2"
python examples/benchmarks/benchmark_sweep.py --n 2048 --cases 48 --runs $RUNS --workers $WORKERS --json "$OUT/bench.jsonl" || status=1
python examples/benchmarks/benchmark_sweep.py --n 10240 --cases 24 --runs $RUNS --workers $WORKERS --json "$OUT/bench.jsonl" || status=1
rm -rf "$OUT"/store_* "$OUT/check_sweep_gpu.py"
exit $status
