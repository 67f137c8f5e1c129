#!/usr/bin/env bash
# `sweep --workers M --devices N` on a GPU host (each worker takes N GPUs of its own): the same elastic sweep run (1) in process with --devices N (one solve spread over GPUs
# 0 … N-1) and (2) on M workers taking N GPUs each; the stored rows compared bit for bit
# (compare_outputs.py) and both walls printed. Needs M × N GPUs (default 2 × 2).
# Run from the repo root (dask, distributed and JAX installed):
#   OUT=groups_out bash examples/gpu_checks/sweep_groups.sh
# Sizes: N_PX (4096), SEEDS (0-7), WORKERS (2), DEVICES (2). Expected: about 8 × 2 s of solves
# plus the cluster's start (≈ 10 s): under 90 s.
set -uo pipefail
OUT=${OUT:-groups_out}
mkdir -p "$OUT"
export XLA_PYTHON_CLIENT_PREALLOCATE=false XLA_PYTHON_CLIENT_MEM_FRACTION=0.9
N_PX=${N_PX:-4096}
SEEDS=${SEEDS:-0-7}
WORKERS=${WORKERS:-2}
DEVICES=${DEVICES:-2}
args=(sweep --n "$N_PX" --D 2.3 2.6 --delta 0.01 --seeds "$SEEDS" --bem-fractions 0.1
      --devices "$DEVICES" --no-progress)
run() {  # run NAME EXTRA...: one whole command, its wall time
    local name=$1
    shift
    local t0=$SECONDS
    rm -rf "/tmp/groups_$name"
    timeout 240 python3 -m warptrunc "${args[@]}" "$@" --out "/tmp/groups_$name" \
        >"$OUT/log_$name.txt" 2>&1
    echo "$name: exit $? in $((SECONDS - t0)) s (wall, whole command)" | tee -a "$OUT/groups.txt"
}
run inprocess
run workers --workers "$WORKERS"
python3 examples/gpu_checks/compare_outputs.py /tmp/groups_inprocess /tmp/groups_workers \
    2>&1 | tail -5 | tee -a "$OUT/groups.txt"
python3 - <<'PY' | tee -a "$OUT/groups.txt"
import pandas as pd
for name in ("inprocess", "workers"):
    df = pd.read_parquet(f"/tmp/groups_{name}/cases.parquet")
    print(name, len(df), "cases; bem errors:", int(df["bem_error"].notna().sum()),
          "; sum of bem_seconds:", round(float(df["bem_seconds"].sum()), 1), "s",
          "; devices:", sorted(set(map(str, df.get("device", pd.Series(["?"]))))))
PY
