export PYTHONPATH=/tmp/site MPLBACKEND=Agg
for p in GB300s Ps; do for a in none always 10 4; do python3 examples/gpu_checks/precondition_rule.py $p $a 2>&1 | grep after=; done; done
B=examples/benchmarks/benchmark_solver_scaling.py
python3 $B --device cuda:0 --n 2048 16384 --dtype float32 --precondition-above auto --pentol-rms 1e-4 --wc-pixels 8 2>&1 | grep "N="
python3 $B --device cuda:0 --n 16384 --dtype float32 --precondition-above auto --pentol-rms 1e-4 2>&1 | grep "N="
