#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
# Large maps on cuda:0: sizes past 2^31 pixels in memory, streamed truncation and islands.
#
#   bash large_maps_and_streaming.sh            # tests + 32768², 46400², 65536² + 131072² streamed analyze
#   SKIP_131072=1 bash large_maps_and_streaming.sh
#   FULL=1 bash large_maps_and_streaming.sh      # also wm_surface (host copy) at 46400² and 65536² (+1-2 min)
#   DEVICE=cpu SMALL=1 bash large_maps_and_streaming.sh   # dry run of the script logic on small grids
#
# Needs warptrunc installed in the active Python (pip install -e .). Results: $OUT (default
# ./out_gpu_8b): tests_8b.txt, large_<n>.json, analyze_big/{fit.json,time.txt,smi_peak_MiB.txt} (n = 131072),
# summary_8b.json. Big files (maps) go to a temporary folder that is deleted at the end.
# Expected on an H100: tests 1-3 min (cold kernel cache), the 46400² test ~1 min,
# benchmarks 2-3 min; each step has its own timeout.
set -uo pipefail
OUT=${OUT:-$PWD/out_gpu_8b}
mkdir -p "$OUT"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
export WARPTRUNC_DEVICE=${DEVICE:-cuda:0}
if [ "${SMALL:-0}" = 1 ]; then N1=512 N2=640 N3=768 N4=1024 N5=256 B5=16 DEVS=cpu; else
    N1=32768 N2=46400 N3=65536 N4=131072 N5=16384 B5=1024 DEVS=cpu,cuda:0; fi
status=()
step() { # name, command...
    local name=$1; shift
    local t0=$SECONDS
    "$@"; local rc=$?
    echo "== $name: rc=$rc, $((SECONDS - t0)) s" | tee -a "$OUT/steps.txt"
    status+=("\"$name\": $rc")
}
nvidia-smi --query-gpu=name,memory.total,memory.used --format=csv 2>&1 | tee "$OUT/gpu.txt"

# 1. tests on cpu and cuda:0 (the banded and streamed paths, and the truncation/WM suites)
step tests timeout 300 bash -c "WARPTRUNC_TEST_DEVICES=$DEVS python -m pytest -q -p no:cacheprovider \
    tests/test_stream.py tests/test_limits.py tests/test_stream_islands.py tests/test_truncation.py tests/test_wm.py \
    2>&1 | tail -30 | tee '$OUT/tests_8b.txt'"

# 1b. past 2^31 pixels in memory (46400²) against the streamed path and NumPy (~1 min)
[ "${SMALL:-0}" = 1 ] || step test_46400 timeout 180 bash -c "WARPTRUNC_SLOW=1 python -m pytest -q \
    -p no:cacheprovider tests/test_limits.py -k past_2_31 2>&1 | tail -5 | tee '$OUT/test_46400.txt'"

# 2. generate + truncate, each case in its own process (peak memory per case)
step large_$N1 timeout 150 python examples/benchmarks/benchmark_large.py --n $N1 --path device surface stream \
    --json "$OUT/large_$N1.json"
step large_$N2 timeout 150 python examples/benchmarks/benchmark_large.py --n $N2 --path device stream \
    --json "$OUT/large_$N2.json"
step large_$N3 timeout 150 python examples/benchmarks/benchmark_large.py --n $N3 --path auto stream \
    --json "$OUT/large_$N3.json"
if [ "${FULL:-0}" = 1 ]; then  # the user path with the host copy (17 GB at 65536²), slower
    step large_${N2}_surface timeout 150 python examples/benchmarks/benchmark_large.py --n $N2 \
        --path surface --no-warmup --json "$OUT/large_${N2}_surface.json"
    step large_${N3}_surface timeout 150 python examples/benchmarks/benchmark_large.py --n $N3 \
        --path surface --no-warmup --json "$OUT/large_${N3}_surface.json"
fi

# 2b. streamed islands: equal to the in-memory labelling at 16384² (16 bands), and past the
#     in-memory labelling limit (2^30 pixels) at 46400²
step islands_16384 timeout 120 python examples/stream_islands.py --n $N5 --band-rows $B5 \
    --json "$OUT/stream_islands_16384.json"
step islands_$N2 timeout 120 python examples/stream_islands.py --n $N2 --json "$OUT/stream_islands_$N2.json"

# 3. the CLI at 46400² (2.15e9 pixels, past 2^31): generate and save a .npy (8.6 GB, temporary)
step generate_$N2 timeout 120 bash -c "TIMEFORMAT='real %R s'; { time warptrunc generate --n $N2 \
    -o '$TMP/s$N2.npy' ; } 2>&1 | tail -3 | tee '$OUT/generate_$N2.txt'; rm -f '$TMP'/s$N2.*"

# 4. warptrunc analyze --n 131072 as a whole process (auto: streamed), with peak GPU memory
if [ "${SKIP_131072:-0}" != 1 ]; then
    mkdir -p "$OUT/analyze_big"
    nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits -lms 200 \
        > "$TMP/smi.txt" 2>/dev/null &
    smi=$!
    step analyze_big bash -c "TIMEFORMAT='real %R s, user %U s, sys %S s'; { time \
        timeout 240 warptrunc analyze --n $N4 --no-plot --out '$TMP/abig' ; } \
        > '$OUT/analyze_big/time.txt' 2>&1; rc=\$?; cat '$OUT/analyze_big/time.txt' \
        | tr '\r' '\n' | grep -v '^stream pass.*[0-9]%|' | tail -8; exit \$rc"
    kill "$smi" 2>/dev/null
    cp "$TMP"/abig/fit.json "$OUT/analyze_big/" 2>/dev/null
    sort -n "$TMP/smi.txt" | tail -1 > "$OUT/analyze_big/smi_peak_MiB.txt"
    echo "peak GPU memory used during analyze (MiB): $(cat "$OUT/analyze_big/smi_peak_MiB.txt")"
fi

python - "$OUT" "${status[@]}" <<'EOF'
import glob, json, os, sys
out = sys.argv[1]
summary = {"steps": json.loads("{" + ", ".join(sys.argv[2:]) + "}"), "large": []}
for f in sorted(glob.glob(os.path.join(out, "large_*.json"))):
    d = json.load(open(f))
    summary["device_name"] = d.get("device_name")
    for r in d["rows"]:
        summary["large"].append({**r, "counts_equal_across_paths": d["counts_equal_across_paths"]})
        print(f"{r['n']:>6}² {r['path']:<8} {r['seconds']:8.3f} s  "
              f"pool peak {r.get('mempool_high_GiB', float('nan')):6.2f} GiB  "
              f"host rss {r['host_maxrss_GiB']:6.2f} GiB  equal={d['counts_equal_across_paths']}")
summary["stream_islands"] = [json.load(open(f)) for f in sorted(glob.glob(os.path.join(out, "stream_islands_*.json")))]
for d in summary["stream_islands"]:
    print(f"islands {d['n']:>6}² streamed {d['seconds']:8.3f} s  counts {d['n_islands']}  "
          f"equal to in-memory: {d.get('equal_to_in_memory', 'n/a (past the limit)')}")
fit = os.path.join(out, "analyze_big", "fit.json")
if os.path.exists(fit):
    info = json.load(open(fit))
    summary["analyze_big"] = {k: info.get(k) for k in ("path", "streaming", "alpha", "beta", "r2")}
    summary["analyze_big"]["time"] = open(os.path.join(out, "analyze_big", "time.txt")).read()[-300:]
    print("analyze (largest n):", summary["analyze_big"])
json.dump(summary, open(os.path.join(out, "summary_8b.json"), "w"), indent=2)
EOF
