# Sourced by wave7.sh, wave8.sh and wave9.sh after they set MODES (the modes' names, for the
# usage line): the mode from $1, its results folder $dir under $OUT (default ./gpu_out), the
# staging's PYTHONPATH (/tmp/site), the GPUs and the commit recorded, and SECONDS reset.
OUT=${OUT:-gpu_out}
mode=${1:?mode: $MODES}
dir="$OUT/$mode"
mkdir -p "$dir"
export PYTHONPATH=${PYTHONPATH:-/tmp/site} MPLBACKEND=Agg PYTHONUNBUFFERED=1
nvidia-smi --query-gpu=index,name,memory.total --format=csv,noheader | tee "$dir/device.txt"
echo "commit ${WARPTRUNC_GIT_COMMIT:-unknown}" | tee "$dir/commit.txt"
SECONDS=0
