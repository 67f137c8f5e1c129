#!/usr/bin/env bash
# GPU checks of the elastic–plastic contact and the indentation in silico, one mode per call:
#   suite [S]      the test suite on cuda:0 only (at most S seconds, default 420)
#   analyze        `warptrunc analyze --n 10240` as a whole process, median of 5 (and of an older
#                  source tree in ./_base when present, for a comparison in the same run)
#   indent [B] [T] `reproduce --profile paper --stages indentation` on cuda:0 for at most B seconds
#                  of new pieces (default 400; the command under `timeout T`, default 540);
#                  resumable: pieces of earlier calls carried back in ./_gpu_pieces are reused
#   refine         `warptrunc indent` on GB300s at the paper's pixel (10240² over 1 mm), the
#                  54.1 µm punch, 3 placements, H = ∞: the refinement of indentation cells
#   scaling [N] [B] [A]  the contact solver at 10240², 16384², 32768² (both algorithms)
#   iterations [N] [T]   iterations against the grid on cuda:0 (benchmarks/iterations_vs_grid.py)
# Run from the repository root: OUT=gpu_out bash examples/gpu_checks/plastic_indent_checks.sh MODE
# Results under $OUT/MODE/ (_mode_head.sh: PYTHONPATH from $STAGE, default /tmp/site, when unset).
set -uo pipefail
MODES="suite, analyze, indent, refine, scaling or iterations"
DEFAULT_MODE=suite
# shellcheck source=examples/gpu_checks/_mode_head.sh
source "$(dirname "$0")/_mode_head.sh"
OUT=$dir
export OUT
case $mode in
suite)
  (cd tests && WARPTRUNC_TEST_DEVICES=cuda:0 timeout ${2:-420} python3 -m pytest -q -p no:cacheprovider 2>&1 | tail -25) ;;
refine)
  /usr/bin/time -v python3 -m warptrunc indent --preset GB300s --punch-diameter 54.1e-6 \
    --placements 3 --L 1e-3 --n 10240 --hardness inf --device cuda:0 --dtype float32 --out "$OUT/refine_gb300s" \
    2>&1 | tee "$OUT/refine_gb300s.txt" | grep -v "^\s" | tail -30 ;;
analyze)
  python3 - <<'PY'
import json, os, statistics, subprocess, sys, time
out = os.environ["OUT"]
def bench(cwd, env, label):
    cmd = [sys.executable, "-m", "warptrunc", "analyze", "--n", "10240", "--device", "cuda:0", "--out", f"/tmp/an_{label}"]
    subprocess.run(cmd, cwd=cwd, env=env, capture_output=True)  # warm the kernel cache
    ts = []
    for _ in range(5):
        t = time.perf_counter(); r = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True); ts.append(time.perf_counter() - t)
        if r.returncode: print(r.stderr[-2000:]); break
    return ts
env = dict(os.environ)
res = {"new": bench("/tmp", env, "new")}
if os.path.isdir("_base"):
    e2 = dict(env, PYTHONPATH=os.path.abspath("_base") + ":" + os.environ.get("PYTHONPATH", ""))
    res["base"] = bench(os.path.abspath("_base"), e2, "base")
for k, v in res.items():
    print(f"analyze --n 10240 ({k}): median {statistics.median(v):.2f} s, min {min(v):.2f}, max {max(v):.2f}, runs {[round(x, 2) for x in v]}")
json.dump(res, open(f"{out}/analyze_10240.json", "w"))
PY
  ;;
indent)
  # pieces of earlier calls (a cold machine lost /tmp) travel back in ./_gpu_pieces (carried)
  mkdir -p /tmp/repro_paper/indentation
  [ -d _gpu_pieces ] && cp -n _gpu_pieces/*.json /tmp/repro_paper/indentation/ 2>/dev/null
  timeout ${3:-540} python3 -m warptrunc reproduce --profile paper --out /tmp/repro_paper --stages indentation --time-budget ${2:-400} --device cuda:0 > $OUT/indent.log 2>&1
  echo "reproduce exit $?"; tail -5 $OUT/indent.log
  tar -C /tmp/repro_paper/indentation -cf $OUT/pieces.tar . 2>/dev/null  # one file back
  python3 - <<'PY'
import glob, json, os
tot, surf = 0.0, {}
for f in sorted(glob.glob("/tmp/repro_paper/indentation/*.json")):
    r = json.load(open(f)); s = r.get("seconds", {})
    if not isinstance(s, dict):  # the resolution check: one number
        t = float(s)
    else:
        t = s.get("piece_s", 0.0)
        surf[os.path.basename(f).split("__")[0]] = s.get("surface_s", 0.0)
    tot += t
    print(f"{os.path.basename(f):40s} {t:8.1f} s  not converged {r.get('n_not_converged')}  reused {r.get('reused_elastic_cycles')}  {r.get('device')}")
print(f"surfaces {sum(surf.values()):.1f} s; pieces {tot:.1f} s; sum {tot + sum(surf.values()):.1f} s")
PY
  (cd /tmp/repro_paper && tar -cf $OUT/report.tar --exclude=indentation . 2>/dev/null) ;;
scaling)
  python3 examples/benchmarks/benchmark_solver_scaling.py --device cuda:0 --n ${2:-10240 16384 32768} --dtype float32 --budget ${3:-400} --algorithm ${4:-bccg pk} --out $OUT/scaling 2>&1 | tail -20 ;;
iterations)
  # iterations and convolutions against the grid, both algorithms (the CPU record:
  # benchmarks/records/iterations_vs_grid_cpu_2026-11-25.json)
  timeout ${3:-400} python3 examples/benchmarks/iterations_vs_grid.py --device cuda:0 --dtype float32 --n ${2:-1024 2048 4096} --json $OUT/iterations_gpu.json 2>&1 | tail -40 ;;
*)
  echo "unknown mode $mode (modes: $MODES)"; exit 2 ;;
esac
