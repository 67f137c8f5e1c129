#!/usr/bin/env bash
# The contact solver against tamaas, and the start-up of `warptrunc analyze`, on a GPU host,
# under 5 minutes with a warm
# kernel cache (a cold one adds the compilation of the analyze and contact kernels, ~1 min):
#  1. benchmarks/benchmark_peers.py: warptrunc's ContactSolver on cuda:0 (float64, float32)
#     against tamaas' PolonskyKeerRey on every core, on tamaas' own surface (periodic, p̄ = 0.05 E*)
#     at N = $SIZES. To stay short: tamaas is timed by one solve at $TAMAAS_TOL (the tolerance
#     its walk chose on the CPU: benchmarks/records/peers_cpu_e2af04c.json) and the tight reference is
#     warptrunc float64 at pentol 1e-11·rms (on the CPU the peers' own references agreed with it);
#     every row records whether its area and mean gap are within 1e-4 of it. A tamaas solve is
#     stopped after $TAMAAS_LIMIT s, and larger N are then skipped.
#  2. benchmarks/startup.py: 5 fresh processes of `warptrunc analyze --n $N_START --device cuda:0`
#     against `python -c "import warp; warp.init(); warp.get_device('cuda:0')"` in the same run,
#     with the phase breakdown.
# Needs tamaas (pip install tamaas==2.9.0, a wheel) and warptrunc (pip install --no-deps .) with
# warp-lang, numpy, scipy, matplotlib, cupy importable (PYTHONPATH: when unset, $STAGE, default
# /tmp/site, the folder the GPU machine's packages are installed into with `pip install --target`).
# Results under $OUT: peers_cuda0.json, startup_cuda0.json, the two logs; a short table last.
# Run from the repository root:  OUT=gpu_out bash examples/gpu_checks/peers_startup.sh
set -uo pipefail
: "${OUT:?set OUT to a folder for the results}"
SIZES=${SIZES:-"256 512 1024 2048"}
TAMAAS_TOL=${TAMAAS_TOL:-1e-4}
TAMAAS_LIMIT=${TAMAAS_LIMIT:-190}
N_START=${N_START:-10240}
DEVICE=${DEVICE:-cuda:0}  # DEVICE=cpu SIZES=64 N_START=256: a dry run on any machine
TAG=${DEVICE//:/}
PY=${PY:-python3}
export PYTHONPATH=${PYTHONPATH:-${STAGE-/tmp/site}} MPLBACKEND=Agg PYTHONUNBUFFERED=1
mkdir -p "$OUT"
cd "$(dirname "$0")/../.." || exit 1
export WARPTRUNC_GIT_COMMIT=${WARPTRUNC_GIT_COMMIT:-$(git rev-parse --short HEAD 2>/dev/null || echo unknown)}
$PY -c "import tamaas, warptrunc, warp; print('tamaas', tamaas.__version__, tamaas.TamaasInfo.backend, '| warp', warp.config.version)" || exit 1
nproc

SECONDS=0
# shellcheck disable=SC2086
$PY examples/benchmarks/benchmark_peers.py --device "$DEVICE" --sizes $SIZES --surfaces tamaas \
  --substrates periodic --peers tamaas --reference warptrunc --tamaas-tol "$TAMAAS_TOL" \
  --no-tamaas-one-thread --time-limit "$TAMAAS_LIMIT" --out "$OUT" 2>&1 \
  | grep -v "^   \|^Warp " | tee "$OUT/peers.log"
echo "peers: ${SECONDS} s"
SECONDS=0
$PY examples/benchmarks/startup.py --n "$N_START" --device "$DEVICE" --runs 5 --out "$OUT" 2>&1 \
  | grep -v "^   \|^Warp " | tee "$OUT/startup.log"
echo "startup: ${SECONDS} s"

$PY - "$OUT" "$TAG" <<'EOF'
import json, sys
from pathlib import Path
out, tag = Path(sys.argv[1]), sys.argv[2]
p = json.loads((out / f"peers_{tag}.json").read_text())
print(f"\n== peers: warptrunc on {p['device_name']} against tamaas on {p['cpu_cores']} cores "
      f"({p['cpu']}), commit {p['commit']}")
print("| N | tamaas s (it, matched) | warptrunc f64 s (it) | f32 s (it) | tamaas ÷ f64 |")
print("|---|---|---|---|---|")
for n in p["sizes"]:
    rows = {r["solver"].split(" (")[0] if r["solver"].startswith("tamaas") else r["solver"]: r
            for r in p["rows"] if r["n"] == n}
    tm, f64, f32 = rows.get("tamaas"), rows.get("warptrunc periodic float64"), rows.get("warptrunc periodic float32")
    def cell(r):
        if r is None or "time_s" not in r:
            return "-"
        return f"{r['time_s']:.4g} ({r.get('iterations', '-')}{'' if r.get('matched') else ', NO MATCH'})"
    ratio = (f"{tm['time_s'] / f64['time_s']:.0f}×" if tm and f64 and "time_s" in tm
             and not tm.get("timed_out") and "time_s" in f64 else "-")
    print(f"| {n}² | {cell(tm)} | {cell(f64)} | {cell(f32)} | {ratio} |")
s = json.loads((out / f"startup_{tag}.json").read_text())
m = s["median_s"]
print(f"\n== start-up, analyze --n {s['n']} on {s['device_name']}: job median {m['job']:.2f} s, "
      f"floor {m['floor']:.2f} s, excess {s['excess_s']:.2f} s (target ≤ 1.0 s)")
b = s["breakdown_s"]
if "cold" in b:
    ph = {**b["start"], **{k: v for k, v in b["cold"].items() if k != "total"}}
    print("phases (cold, s): " + ", ".join(f"{k} {v:.2f}" for k, v in ph.items()))
EOF
