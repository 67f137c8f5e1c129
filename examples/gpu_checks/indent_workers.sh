#!/usr/bin/env bash
# The `reproduce` indentation stage on every GPU of the host: how much faster on Dask workers
# (one per GPU) than in one process, and whether the workers store the same numbers bit for bit.
# examples/benchmarks/benchmark_indentation_workers.py runs whole `warptrunc reproduce --profile
# paper --stages indentation` processes, the paper profile with its indentation map at N² pixels
# (default N=2048: 488 nm pixels over 1 mm instead of the paper's 10240², 97.7 nm; a departure,
# recorded in the JSON). Per run: wall time, speed-up, pieces, the sum of the pieces' own seconds,
# the busiest device's seconds; the in-process run again on its finished store (fixed_s); and the
# stage's stored numbers of each worker run compared bit for bit with in process. Records:
# benchmarks/records/indentation_workers_<machine>_<commit>.json.
#
# Modes (run from the repository root on a 2- or 4-GPU host with dask and distributed installed;
# the machine may have no git: name the commit with WARPTRUNC_GIT_COMMIT=<sha>):
#   run      (default) one benchmark process: in process on cuda:0, then on N_GPU, 2 and 1
#            workers, after an untimed warm-up that compiles the kernels; results in $OUT (default
#            ./indent_workers_out): benchmark_indentation_workers.json, commands.log,
#            benchmark_stderr.log, the table printed last. GPUS=0,1 runs on a subset
#            (CUDA_VISIBLE_DEVICES); BENCH_ARGS are passed on; no timed run starts after BUDGET_S
#            (default 420 s) or when expected to end past it ("skipped: budget"), none runs more
#            than 30 s past it or longer than TIMEOUT_S (default 580 s; stopped, rc 124).
#            In process alone takes about 510 s at N=2048 on an H200
#            (benchmarks/records/indentation_workers_h200x4_fab6f70.json), so one 10-minute call
#            holds in process or the workers:
#              BENCH_ARGS="--workers" BUDGET_S=560 bash examples/gpu_checks/indent_workers.sh
#              BENCH_ARGS="--no-inprocess --workers 4 2 --reference A/values_inproc.json.gz
#                --reference-wall WALL" bash examples/gpu_checks/indent_workers.sh
#            (A: the first call's OUT, carried back; WALL: its in-process wall).
#   warm     the indentation profile once at 256² on cuda:0 (fills Warp's kernel cache), the
#            versions of the packages, the GPU–CPU topology, each GPU's CPUs and what the workers
#            of a local cluster inherit (device, MALLOC_TRIM_THRESHOLD_, Dask's profiler, CPUs)
#   split    three benchmark processes at once on disjoint GPUs (4-GPU host): in process on GPU 0,
#            1 worker on GPU 1, 2 workers on GPUs 2,3, under the same host load (≈ 530 s at 2048²);
#            values kept in $W (default /tmp/indent_workers) for `four`
#   four     4 workers against split's in-process run, then every run compared bit for bit
#            (identity.json)
#   probe    examples/benchmarks/benchmark_worker_overhead.py on GPU 0 at PROBE_N² (1024): the
#            indentation parts in the main thread against a one-worker cluster, unbound, then
#            bound to the CPUs near the GPU
# warm, split, four and probe write under $OUT/MODE/ (default ./gpu_out; _mode_head.sh). BIND=1
# (default) runs the in-process benchmark of split under `taskset -c` with the CPUs near its GPU
# (`python -m warptrunc.sweep._affinity`), as the workers of a local cluster bind themselves;
# BIND=0 leaves every process unbound (WARPTRUNC_CPU_AFFINITY=0).
# CPU dry runs (about a minute on 2 cores):
#   N=128 BENCH_ARGS="--profile tiny --device cpu --workers 2" bash examples/gpu_checks/indent_workers.sh
#   N=128 BENCH_ARGS="--profile tiny --device cpu" bash examples/gpu_checks/indent_workers.sh split
set -uo pipefail
B=examples/benchmarks/benchmark_indentation_workers.py
N=${N:-2048}
if [ "${1:-run}" = run ]; then
    OUT=${OUT:-indent_workers_out}
    mkdir -p "$OUT"
    python3 -c "import warptrunc" 2>/dev/null || python3 -m pip install -q --no-deps --no-build-isolation -e . >/dev/null 2>&1 || true
    nvidia-smi -L || true
    if [ -n "${GPUS:-}" ]; then  # a subset of the host's GPUs: the workers see only these
        export CUDA_VISIBLE_DEVICES=$GPUS
        echo "GPUS=$GPUS: CUDA_VISIBLE_DEVICES=$CUDA_VISIBLE_DEVICES"
    fi
    # shellcheck source=examples/gpu_checks/_dask_head.sh
    source "$(dirname "$0")/_dask_head.sh"
    t0=$(date +%s)
    # shellcheck disable=SC2086  # BENCH_ARGS: several words
    python3 "$B" --out "$OUT" --n "$N" --budget-s "${BUDGET_S:-420}" --grace-s 30 \
        --timeout-s "${TIMEOUT_S:-580}" ${BENCH_ARGS:-} 2> "$OUT/benchmark_stderr.log"
    status=$?
    [ $status -ne 0 ] && tail -n 30 "$OUT/benchmark_stderr.log"
    echo "indent_workers.sh: $(( $(date +%s) - t0 )) s, exit $status"
    exit $status
fi

MODES="run, warm, split, four or probe"
# shellcheck source=examples/gpu_checks/_mode_head.sh
source "$(dirname "$0")/_mode_head.sh"
W=${W:-/tmp/indent_workers}
indent() {  # indent NAME GPUS ARGS...: one benchmark process on GPUS, its folder $W/NAME
    local name=$1 gpus=$2 bind=()
    shift 2
    # the in-process run bound to the CPUs near its GPU, as the workers bind themselves
    if [ "${BIND:-1}" = 1 ] && [ "$name" = inproc ] && command -v taskset > /dev/null; then
        local cpus
        cpus=$(CUDA_VISIBLE_DEVICES=$gpus python3 -m warptrunc.sweep._affinity 0)
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
    nvidia-smi topo -m > "$dir/topo.txt" 2>&1
    for g in $(nvidia-smi --query-gpu=index --format=csv,noheader); do
        echo "GPU $g: CPUs $(python3 -m warptrunc.sweep._affinity "$g")"
    done | tee "$dir/gpu_cpus.txt"
    python3 -c "from warptrunc.sweep.cluster import open_client; import os
from warptrunc.sweep._affinity import format_cpulist
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
split)
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
four)
    ref=$W/inproc/values_inproc.json.gz
    wall=$(python3 -c "import json; r=[x for x in json.load(open('$W/inproc/benchmark_indentation_workers.json'))['runs'] if x['run']=='inproc']; print(r[0]['wall_s'])")
    indent w4 0,1,2,3 --no-inprocess --workers 4 --reference "$ref" --reference-wall "$wall"
    cp "$W/w4/benchmark_indentation_workers.json" "$dir/w4.json" 2>/dev/null
    cp "$W/w4"/values_*.json.gz "$W/w4.txt" "$dir/" 2>/dev/null
    tail -n 8 "$W/w4.txt"
    python3 "$B" compare "$ref" "$W"/w*/values_workers_*.json.gz --json "$dir/identity.json"
    ;;
probe)
    P=examples/benchmarks/benchmark_worker_overhead.py
    WARPTRUNC_CPU_AFFINITY=0 python3 "$P" --n "${PROBE_N:-1024}" --device cuda:0 --repeat 4 \
        --profile-top 0 --settings main worker --out "$dir/unbound" 2>&1 | grep -v -i warn | tail -n 4
    python3 "$P" --n "${PROBE_N:-1024}" --device cuda:0 --repeat 4 --bind near \
        --profile-top 0 --settings main worker --out "$dir/bound" 2>&1 | grep -v -i warn | tail -n 5
    ;;
*)
    echo "unknown mode $mode (modes: $MODES)"
    exit 2
    ;;
esac
echo "indent_workers.sh $mode: ${SECONDS} s"
