#!/usr/bin/env bash
# One contact problem over 4 GPUs, on a host with 4 GPUs:
#   (a) strong scaling, SCALE_N² (16384²) float32 on 1, 2 and 4 GPUs, and weak scaling, WEAK_N²
#       (32768²) float32 on 4: the sharded FFT floor (one K·x) measured in the same process,
#       per-iteration and per-convolution time against it, peak memory per GPU against
#       ContactSolver.memory_bytes(..., devices=n) (examples/benchmarks/benchmark_sharded.py
#       solve, the steps of sharded.sh);
#   (b) F64_N² (32768², the paper's map size) float64 on 2 GPUs: the model says 77.8 GB per
#       device, more than an H100 gives JAX: expect a MemoryError recorded on H100s;
#   (c) `warptrunc bem-check --n BIG_N --devices 4 --dtype float32` (65536², 91.3 GB per device
#       by the model): only when every GPU has at least 100 GB (H200), else the line
#       "skipped: needs H200" is recorded. Writes $OUT/bem_BIG_N/ (bem.csv, bem.json and the
#       figure bem.png: F and k against δ, BEM and truncation, and their ratios) and a JSON line.
# Run from the repo root:
#   OUT=sharded_x4_out bash examples/gpu_checks/sharded_x4.sh              # all parts
#   PARTS="a b" OUT=sharded_x4_out bash examples/gpu_checks/sharded_x4.sh  # some parts
# Results: $OUT/sharded_x4.jsonl (one JSON line per measurement; failures, time-outs and skips
# included), $OUT/sharded_summary.json and the table printed at the end (benchmark_sharded.py
# report); each step's log in $OUT/log_*.txt. Every step runs in its own process under `timeout`
# and within what is left of BUDGET seconds (default 570: one 10-minute call); a step that fails
# or times out is recorded and the next one goes on.
#
# Expected times, from benchmarks/records/sharded_h100x2_789c425.jsonl (2 × H100; 16384² f32: set-up
# 8.6 s, floor 25 ms, cold 12.4 s at maxiter 100, warm 7.6 s on 2 GPUs; 11.1 / 10.7 / 8.4 s on
# one; the floor doubles with the pixels per GPU), plus about 10 s per process for imports and
# compilation:
#   start-up (pip, JAX import, maps 16384² and 32768² on the host)   ≈ 30 s
#   (a) 16384² on 1, 2, 4 GPUs ≈ 40 s each; 32768² on 4 ≈ 70 s        ≈ 190 s
#   (b) 32768² f64 on 2 (floor ≈ 2 × 70 ms; 300 convolutions a solve) ≈ 130 s (seconds on H100:
#       refused by the memory check before allocating)
#   (c) 65536² f32 on 4: WM map and truncation on cuda:0, three approaches with Barber's
#       stiffness (floor ≈ 140 ms, about 0.5 s an iteration)        ≈ 300–500 s (least certain)
# So (a) + (b) fit one 10-minute call and (c) needs a second one (PARTS=c) on 4 H200s.
# Sizes and settings: SCALE_N, WEAK_N, F64_N, BIG_N, DTYPE (float32, of (a)), BIG_FRACTIONS
# ("0.1 0.2 0.3"), BIG_MAXITER (10000), F64_MAXITER (1000: (b)'s solves run to convergence;
# (a) keeps benchmark_sharded.py's 100), MIN_GPU_GB (100). A CPU dry run of the logic (no GPU; JAX
# on 4 host devices, Warp on the CPU):
#   DRY_CPU=1 SCALE_N=128 WEAK_N=128 F64_N=128 BIG_N=128 OUT=/tmp/x4 \
#       bash examples/gpu_checks/sharded_x4.sh
set -uo pipefail
OUT=${OUT:-sharded_x4_out}
mkdir -p "$OUT"
export XLA_PYTHON_CLIENT_PREALLOCATE=false  # JAX would take 75 % of every GPU at start
export XLA_PYTHON_CLIENT_MEM_FRACTION=${XLA_PYTHON_CLIENT_MEM_FRACTION:-0.95}
PARTS=${PARTS:-a b c}
SCALE_N=${SCALE_N:-16384}
WEAK_N=${WEAK_N:-32768}
F64_N=${F64_N:-32768}
BIG_N=${BIG_N:-65536}
DTYPE=${DTYPE:-float32}
BIG_FRACTIONS=${BIG_FRACTIONS:-0.1 0.2 0.3}
BIG_MAXITER=${BIG_MAXITER:-10000}
F64_MAXITER=${F64_MAXITER:-1000}  # (b) converges: the warm step is timed to convergence
F64_MAP=${F64_MAP:-selfaffine}  # (b)'s map: selfaffine, or wm (the paper's kind: D = 2.5 WM)
MIN_GPU_GB=${MIN_GPU_GB:-100}
BUDGET=${BUDGET:-570}
MAPS=${MAPS:-$OUT/maps}
J="$OUT/sharded_x4.jsonl"
B=examples/benchmarks/benchmark_sharded.py
start=$SECONDS
WARP_DEVICE=cuda:0
if [ -n "${DRY_CPU:-}" ]; then  # the logic on the CPU: 4 host devices, Warp on the CPU
    export JAX_PLATFORMS=cpu XLA_FLAGS="${XLA_FLAGS:-} --xla_force_host_platform_device_count=4"
    export WARPTRUNC_DEVICE=cpu
    WARP_DEVICE=cpu
    NGPU=4
    GPU_MB=$(( ${DRY_GPU_GB:-0} * 1000000000 / 1048576 ))
else
    pip install -q --no-deps --no-build-isolation -e . >/dev/null 2>&1 || true
    nvidia-smi -L
    NGPU=$(nvidia-smi -L | wc -l)
    # the smallest GPU's memory (MiB)
    GPU_MB=$(nvidia-smi --query-gpu=memory.total --format=csv,noheader,nounits | sort -n | head -1)
fi
python -c "import jax; print('jax', jax.__version__, jax.devices())" || {
    echo '{"step": "start", "error": "JAX is missing (pip install jax[cuda12])"}' >>"$J"; exit 1; }

record() {  # record KIND NAME ARGS ERROR: one JSON line (python for the quoting); KIND is
    # benchmark_sharded.py's step (solve, maps) or bem_check, so that its report lists it
    python - "$@" <<'EOF' >>"$J"
import json, sys, time
print(json.dumps({"time": time.strftime("%Y-%m-%dT%H:%M:%S"), "step": sys.argv[1],
                  "name": sys.argv[2], "args": sys.argv[3], "error": sys.argv[4]}))
EOF
}

left() { echo $((BUDGET - (SECONDS - start))); }

run_step() {  # run_step KIND NAME LIMIT CMD...: one process, bounded by LIMIT and what is left
    local kind=$1 name=$2 limit=$3
    shift 3
    local l
    l=$(left)
    if [ "$l" -lt 20 ]; then
        record "$kind" "$name" "$*" "skipped: budget of ${BUDGET} s spent"
        echo "skipped (budget): $name"
        return 1
    fi
    [ "$limit" -gt "$l" ] && limit=$l
    timeout "$limit" "$@" >"$OUT/log_$name.txt" 2>&1
    local rc=$?
    if [ "$rc" -ne 0 ]; then
        record "$kind" "$name" "$*" "exit $rc (124: timed out after $limit s); log_$name.txt: $(tail -c 300 "$OUT/log_$name.txt" | tr '\n"' ' ')"
    fi
    echo "$name -> exit $rc at $((SECONDS - start)) s"
    return $rc
}

bench() {  # bench NAME LIMIT STEP ARGS...: a benchmark_sharded.py step into the jsonl
    local name=$1 limit=$2
    shift 2
    run_step "$1" "$name" "$limit" python "$B" "$@" --device "$WARP_DEVICE" --jsonl "$J" --maps "$MAPS"
}

has() { case " $PARTS " in *" $1 "*) return 0 ;; *) return 1 ;; esac; }

if has a; then
    bench maps_scale 60 maps --n "$SCALE_N"
    bench maps_weak 90 maps --n "$WEAK_N"
    for nd in 1 2 4; do
        bench "strong_${SCALE_N}_${nd}" 90 solve --n "$SCALE_N" --ndev "$nd" --dtype "$DTYPE"
    done
    if [ "$NGPU" -ge 4 ]; then
        bench "weak_${WEAK_N}_4" 150 solve --n "$WEAK_N" --ndev 4 --dtype "$DTYPE"
    else
        record solve "weak_${WEAK_N}_4" "" "skipped: $NGPU GPUs, 4 needed"
    fi
fi
if has b; then
    bench maps_f64 90 maps --n "$F64_N" --map "$F64_MAP"
    bench "f64_${F64_N}_2" 420 solve --n "$F64_N" --ndev 2 --dtype float64 --maxiter "$F64_MAXITER" \
        --map "$F64_MAP"
fi
if has c; then
    need_mb=$((MIN_GPU_GB * 1000000000 / 1048576))
    if [ "$NGPU" -lt 4 ]; then
        record bem_check "bem_check_${BIG_N}_4" "" "skipped: $NGPU GPUs, 4 needed"
    elif [ "${GPU_MB:-0}" -lt "$need_mb" ] && [ -z "${FORCE_BIG:-}" ]; then
        record bem_check "bem_check_${BIG_N}_4" "" "skipped: needs H200 (each GPU ${GPU_MB} MiB, ${MIN_GPU_GB} GB needed; the model: 91.3 GB per device at 65536² f32)"
        echo "skipped: bem-check ${BIG_N}² needs GPUs of ${MIN_GPU_GB} GB (H200)"
    else
        bo="$OUT/bem_${BIG_N}"
        tv=()
        [ -x /usr/bin/time ] && tv=(/usr/bin/time -v)  # the host's peak memory, where present
        smi=""
        if [ -z "${DRY_CPU:-}" ]; then  # each GPU's memory in use (JAX and Warp) every 5 s
            nvidia-smi --query-gpu=timestamp,index,memory.used --format=csv,noheader -l 5 \
                >"$OUT/gpu_memory_c.csv" 2>/dev/null &
            smi=$!
        fi
        # shellcheck disable=SC2086
        run_step bem_check "bem_check_${BIG_N}_4" 560 "${tv[@]}" warptrunc bem-check --n "$BIG_N" \
            --devices 4 --dtype float32 --stiffness barber --fractions $BIG_FRACTIONS \
            --maxiter "$BIG_MAXITER" --accept-unconverged --no-progress --out "$bo"
        [ -n "$smi" ] && kill "$smi" 2>/dev/null
        [ -f "$OUT/gpu_memory_c.csv" ] && python - "$OUT/gpu_memory_c.csv" <<'EOF' >>"$J"
import csv, json, sys
peak = {}
for row in csv.reader(open(sys.argv[1])):
    if len(row) == 3:
        i, mib = int(row[1]), float(row[2].split()[0])
        peak[i] = max(peak.get(i, 0.0), mib)
print(json.dumps({"step": "bem_check_gpu_memory", "sampled_every_s": 5,
                  "peak_used_MiB_per_gpu": peak}))
EOF
        [ -f "$bo/bem.json" ] && python - "$bo" "$BIG_N" "$OUT/log_bem_check_${BIG_N}_4.txt" <<'EOF' >>"$J"
import json, re, sys, time
from pathlib import Path
out, n, log = Path(sys.argv[1]), int(sys.argv[2]), Path(sys.argv[3])
rec = {"time": time.strftime("%Y-%m-%dT%H:%M:%S"), "step": "bem_check", "n": n, "ndev": 4,
       "dtype": "float32", "command": f"warptrunc bem-check --n {n} --devices 4 --dtype float32"}
try:
    from warptrunc._support.provenance import git_commit
    from warptrunc.contact import ContactSolver
    rec["commit"] = git_commit()
    rec["model_bytes_per_device"] = ContactSolver.memory_bytes((n, n), "free", "float32", devices=4)
    doc = json.loads((out / "bem.json").read_text())
    cols = doc["columns"]
    rec.update({k: cols[k] for k in cols if k.startswith(("depth", "bem_", "converged",
                                                           "n_iterations", "solve_time"))})
    rec["settings"] = {k: doc.get("settings", {}).get(k) for k in ("device", "dtype", "substrate")}
    rec["figure"] = str(out / "bem.png") if (out / "bem.png").exists() else None
    rec["seconds_per_solve"] = doc["summary"].get("time_per_solve_s")
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", log.read_text())
    rec["host_peak_bytes"] = int(m.group(1)) * 1024 if m else None
    m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", log.read_text())
    rec["wall"] = m.group(1) if m else None
except Exception as exc:  # recorded; the report goes on
    rec["error"] = f"{type(exc).__name__}: {exc}"
print(json.dumps(rec, default=float))
EOF
    fi
fi
python "$B" report --jsonl "$J"
grep '"step": "bem_check"' "$J" | tail -1
echo "total $((SECONDS - start)) s"
