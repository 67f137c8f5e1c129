# Sourced by indent_workers.sh and workers_bench.sh: checks that dask and distributed (and the
# modules named in $DASK_HEAD_MODULES) import, says whether dask-cuda's LocalCUDACluster will be
# used, and sets WARPTRUNC_GIT_COMMIT (the machine may have no git: pass it). Exits 1 without Dask.
python3 - ${DASK_HEAD_MODULES:-} <<'PY' || { echo "dask/distributed missing: install the WHEELS of sweep_two_gpus.sh"; exit 1; }
import importlib, sys
names = ["dask", "distributed", *sys.argv[1:]]
print(" ".join(f"{n} {importlib.import_module(n).__version__}" for n in names))
try:
    import dask_cuda
    print("dask-cuda", dask_cuda.__version__, "(LocalCUDACluster)")
except ImportError:
    print("no dask-cuda: LocalCluster, one worker pinned per GPU")
PY
export WARPTRUNC_GIT_COMMIT=${WARPTRUNC_GIT_COMMIT:-$(git rev-parse HEAD 2>/dev/null)}
[ -z "$WARPTRUNC_GIT_COMMIT" ] && echo "warning: no commit (no git here): set WARPTRUNC_GIT_COMMIT"
