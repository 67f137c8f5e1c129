# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One float32 contact solve at 32768² on cuda:0 (free boundary unless told), each phase printed as it ends
(surface, solver set-up, cold solve at 0.20·R_t, warm solve at 0.21·R_t), with the pool's
high-water mark against ContactSolver.memory_bytes. The scaling benchmark's map and approach.

Run (GPU machine): python examples/gpu_checks/solve_32768.py [N] [algorithm] [maxiter] [fft_plan]
[substrate] [precondition_above]
"""

import sys
import time

import warp as wp

from warptrunc.contact import ContactSolver, SolverSettings
from warptrunc.wm import wm_surface

n = int(sys.argv[1]) if len(sys.argv) > 1 else 32768
algo = sys.argv[2] if len(sys.argv) > 2 else "bccg"
maxiter = int(sys.argv[3]) if len(sys.argv) > 3 else 400
plan = sys.argv[4] if len(sys.argv) > 4 else "auto"
substrate = sys.argv[5] if len(sys.argv) > 5 else "free"
pc_above = None if len(sys.argv) <= 6 or sys.argv[6] == "auto" else float(sys.argv[6])
dev = wp.get_device("cuda:0")
E = 70e9 / (1 - 0.33**2)
t = time.perf_counter()
need = ContactSolver.memory_bytes((n, n), substrate, "float32", cuda=True, algorithm=algo,
                                  fft_plan="pruned")
print(f"N={n} {algo} {substrate} precondition_above {pc_above}: model {need / 1e9:.1f} GB "
      f"({need / n**2:.1f} B/px), free "
      f"{wp.get_device(dev).free_memory / 1e9:.1f} GB", flush=True)
s = wm_surface(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6, seed=0, device=dev)
h = s.heights
wp.synchronize_device(dev)
print(f"surface {time.perf_counter() - t:.1f} s", flush=True)
base = wp.get_mempool_used_mem_high(dev)
t = time.perf_counter()
settings = SolverSettings(dtype="float32", algorithm=algo, maxiter=maxiter, fft_plan=plan,
                          substrate=substrate, precondition_above=pc_above)
solver = ContactSolver(h, (s.dx, s.dy), E, settings=settings, device=dev)
wp.synchronize_device(dev)
need = ContactSolver.memory_bytes((n, n), substrate, "float32", cuda=True, algorithm=algo,
                                  fft_plan=solver.fft_plan, device=dev)
print(f"setup {time.perf_counter() - t:.1f} s, fft_plan {solver.fft_plan} (model "
      f"{need / 1e9:.1f} GB)", flush=True)
for name, frac in (("cold", 0.20), ("warm", 0.21)):
    t = time.perf_counter()
    r = solver.solve(frac * s.Rt)
    wp.synchronize_device(dev)
    dt = time.perf_counter() - t
    print(f"{name}: {dt:.2f} s, {r.n_iterations} it, {r.n_convolutions} conv "
          f"({dt / max(r.n_convolutions, 1) * 1e3:.1f} ms/conv), converged {r.converged}, "
          f"load {r.load:.4g} N, contact {r.n_contact / n**2:.4f}, residual {r.residual:.3g}",
          flush=True)
high = wp.get_mempool_used_mem_high(dev)
print(f"pool high-water {high / 1e9:.1f} GB ({high / n**2:.1f} B/px, surface included; before "
      f"the solver {base / 1e9:.1f} GB) against the model {need / 1e9:.1f} GB", flush=True)
