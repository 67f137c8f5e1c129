# Sourced by the GPU checks that take a mode as their first argument (indent_workers.sh,
# plastic_indent_checks.sh, reproduce_paper_profile.sh), after they set MODES (the modes' names,
# for the usage line) and DEFAULT_MODE: the mode from $1, its results folder $dir under $OUT
# (default ./gpu_out), PYTHONPATH (when unset: $STAGE, default /tmp/site, the folder the GPU
# machine's packages are installed into with `pip install --target`), the GPUs and the commit
# recorded in $dir, and SECONDS reset.
OUT=${OUT:-gpu_out}
mode=${1:-${DEFAULT_MODE:?mode: $MODES}}
dir="$OUT/$mode"
mkdir -p "$dir"
export PYTHONPATH=${PYTHONPATH:-${STAGE-/tmp/site}} MPLBACKEND=Agg PYTHONUNBUFFERED=1
nvidia-smi --query-gpu=index,name,memory.total --format=csv,noheader 2>/dev/null | tee "$dir/device.txt"
echo "commit ${WARPTRUNC_GIT_COMMIT:-$(git rev-parse --short HEAD 2>/dev/null || echo unknown)}" \
    | tee "$dir/commit.txt"
SECONDS=0
