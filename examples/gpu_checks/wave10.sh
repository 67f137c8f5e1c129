#!/usr/bin/env bash
# GPU checks of issues 39 and 42 on a 4-GPU host with 141-GB GPUs (nvidia-h200-x4), one mode per
# device call, back to back on the same warm machine (after the staging of
# ../shared/device/README.md; the machine has no git: pass WARPTRUNC_GIT_COMMIT):
#   bash examples/gpu_checks/wave10.sh warm     # the indentation profile once at 256² on cuda:0
#                                               # (fills Warp's kernel cache) and the versions of
#                                               # the packages the engines need (≈ 40 s)
#   bash examples/gpu_checks/wave10.sh big      # 42 (c): bem-check --n 65536 --devices 4 float32
#                                               # (the FFT-size fix and the unit-force check; ≈ 350 s)
#   bash examples/gpu_checks/wave10.sh indent3  # 39 (c), (4): the indentation stage at 2048², three
#                                               # benchmark processes at once on disjoint GPUs: in
#                                               # process on GPU 0, 1 worker on GPU 1, 2 workers on
#                                               # GPUs 2,3 (≈ 530 s; values kept in /tmp/wave10)
#   bash examples/gpu_checks/wave10.sh probe    # benchmark_worker_overhead.py (main thread against a
#                                               # one-worker cluster) unbound, then bound (≈ 150 s)
#   bash examples/gpu_checks/wave10.sh indent4  # 4 workers against that in-process run, then every
#                                               # worker count compared with it bit for bit (≈ 170 s)
#   bash examples/gpu_checks/wave10.sh pair     # 42 (b) 32768² float64 on GPUs 0,1 on the D = 2.5
#                                               # WM map, and at the same time 42 (1) the FFT
#                                               # engines' floors (JAX, cuFFTMp) on GPUs 2,3 (≈ 260 s)
# Results under $OUT/<mode>/ (default ./gpu_out). Running the three indentation runs at once puts
# the in-process reference and the 1- and 2-worker runs under the same host load; the 4-worker run
# follows alone (the in-process run alone took 510.6 s at fab6f70, so the record can tell).
# BIND=1 (default) runs the in-process benchmark under `taskset -c` with the CPUs near its GPU
# (`python -m warptrunc._support.affinity`), as the workers of a local cluster bind
# themselves (PinDevice); BIND=0 leaves every process unbound (WARPTRUNC_CPU_AFFINITY=0).
# A CPU dry run of indent3 and indent4 (tiny profile, about a minute on 2 cores):
#   N=128 BENCH_ARGS="--profile tiny --device cpu" bash examples/gpu_checks/wave10.sh indent3
set -uo pipefail
MODES="warm, big, indent3, indent4, probe or pair"
# shellcheck source=examples/gpu_checks/_wave_head.sh
source "$(dirname "$0")/_wave_head.sh"
export MAPS=${MAPS:-/tmp/maps}
W=/tmp/wave10
B=examples/benchmarks/benchmark_indentation_workers.py
N=${N:-2048}
indent() {  # indent NAME GPUS ARGS...: one benchmark process on GPUS, its folder $W/NAME
    local name=$1 gpus=$2 bind=()
    shift 2
    # the in-process run bound to the CPUs near its GPU, as the workers bind themselves
    # (PinDevice; BIND=0 leaves both unbound: WARPTRUNC_CPU_AFFINITY=0)
    if [ "${BIND:-1}" = 1 ] && [ "$name" = inproc ] && command -v taskset > /dev/null; then
        local cpus
        cpus=$(CUDA_VISIBLE_DEVICES=$gpus python3 -m warptrunc._support.affinity 0)
        [ -n "$cpus" ] && bind=(taskset -c "$cpus")
    fi
    echo "$name (GPUs $gpus): CPUs ${bind[2]:-not bound}" | tee -a "$W/binding.txt"
    # shellcheck disable=SC2086  # BENCH_ARGS: several words
    CUDA_VISIBLE_DEVICES=$gpus "${bind[@]}" python3 "$B" --out "$W/$name" --n "$N" --warmup-n 0 \
        --timeout-s "${TIMEOUT_S:-560}" ${BENCH_ARGS:-} "$@" > "$W/$name.txt" 2>&1
    echo "$name (GPUs $gpus): exit $? at ${SECONDS} s"
}
[ "${BIND:-1}" = 1 ] || export WARPTRUNC_CPU_AFFINITY=0
case "$mode" in
warm)
    python3 -m pip list 2>/dev/null | grep -i -E "nvmath|cupy|mpi4py|nvshmem|cufft|cuda|jax|dask" \
        | tee "$dir/packages.txt"
    python3 "$B" run --profile paper --n 256 --device cuda:0 --workers none --out "$W/warm" --warmup \
        > "$dir/warm.txt" 2>&1
    echo "warm-up: exit $? at ${SECONDS} s"
    rm -rf "$W/warm"
    # the host's GPU-CPU topology, and what the workers of a local cluster inherit: no
    # MALLOC_TRIM_THRESHOLD_ (fcb7142), no Dask profiler, CPUs near their GPU (cc0e4f7)
    nvidia-smi topo -m > "$dir/topo.txt" 2>&1
    for g in $(nvidia-smi --query-gpu=index --format=csv,noheader); do
        echo "GPU $g: CPUs $(python3 -m warptrunc._support.affinity "$g")"
    done | tee "$dir/gpu_cpus.txt"
    python3 -c "from warptrunc.sweep.cluster import open_client; import os
from warptrunc._support.affinity import format_cpulist
def env():
    import dask
    return (os.environ.get('WARPTRUNC_DEVICE'), os.environ.get('MALLOC_TRIM_THRESHOLD_'),
            dask.config.get('distributed.worker.profile.enabled'),
            format_cpulist(os.sched_getaffinity(0)))
with open_client(workers='auto', progress=False) as (c, _, _):
    for w, e in sorted(c.run(env).items(), key=lambda x: str(x[1])):
        print('worker', w, 'device, trim, profiler, CPUs:', e)" \
        2>&1 | tail -n 5 | tee "$dir/worker_env.txt"
    ;;
big)
    OUT="$dir" PARTS=c BUDGET=${BUDGET:-520} bash examples/gpu_checks/sharded_x4.sh
    ;;
indent3)
    mkdir -p "$W"
    indent inproc 0 --workers &
    indent w1 1 --no-inprocess --workers 1 &
    indent w2 2,3 --no-inprocess --workers 2 &
    wait
    cp "$W/binding.txt" "$dir/" 2>/dev/null
    for r in inproc w1 w2; do
        cp "$W/$r/benchmark_indentation_workers.json" "$dir/$r.json" 2>/dev/null
        cp "$W/$r"/values_*.json.gz "$W/$r.txt" "$dir/" 2>/dev/null
        tail -n 8 "$W/$r.txt"
    done
    ;;
probe)  # benchmark_worker_overhead.py on GPU 0 at 1024², unbound then bound (≈ 150 s)
    P=examples/benchmarks/benchmark_worker_overhead.py
    WARPTRUNC_CPU_AFFINITY=0 python3 "$P" --n "${PROBE_N:-1024}" --device cuda:0 --repeat 4 \
        --profile-top 0 --settings main worker --out "$dir/unbound" 2>&1 | grep -v -i warn | tail -n 4
    python3 "$P" --n "${PROBE_N:-1024}" --device cuda:0 --repeat 4 --bind near \
        --profile-top 0 --settings main worker --out "$dir/bound" 2>&1 | grep -v -i warn | tail -n 5
    ;;
indent4)
    ref=$W/inproc/values_inproc.json.gz
    wall=$(python3 -c "import json; r=[x for x in json.load(open('$W/inproc/benchmark_indentation_workers.json'))['runs'] if x['run']=='inproc']; print(r[0]['wall_s'])")
    indent w4 0,1,2,3 --no-inprocess --workers 4 --reference "$ref" --reference-wall "$wall"
    cp "$W/w4/benchmark_indentation_workers.json" "$dir/w4.json" 2>/dev/null
    cp "$W/w4"/values_*.json.gz "$W/w4.txt" "$dir/" 2>/dev/null
    tail -n 8 "$W/w4.txt"
    python3 "$B" compare "$ref" "$W"/w*/values_workers_*.json.gz --json "$dir/identity.json"
    ;;
pair)
    (CUDA_VISIBLE_DEVICES=0,1 OUT="$dir/f64" PARTS=b F64_MAP=wm BUDGET=${BUDGET:-420} \
        bash examples/gpu_checks/sharded_x4.sh > "$dir/f64.txt" 2>&1; echo "f64: exit $?") &
    (GPUS=2,3 OUT="$dir/fft" WHEELS=${WHEELS:-} BUDGET=${FFT_BUDGET:-300} \
        bash examples/gpu_checks/fft_engines.sh > "$dir/fft.txt" 2>&1; echo "fft: exit $?") &
    wait
    tail -n 25 "$dir/f64.txt" "$dir/fft.txt"
    ;;
*)
    echo "unknown mode $mode"
    exit 2
    ;;
esac
echo "wave10.sh $mode: ${SECONDS} s"
