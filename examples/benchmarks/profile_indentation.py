"""Where the time of the indentation cycles goes: solves, CG iterations, convolutions and seconds
per phase (loading, Barber's stiffness, partial unloading), per surface × hardness × punch.

Example: ``python profile_indentation.py --n 1024 --dtype float32 --surfaces Ps,GB300s
--hardness-factors inf,1`` (Table 1 presets over 1 mm, one placement per punch, the paper's ten
loads). ``--verbose`` prints every solve as it ends. Measured figures (CPU and H100) are in
``docs/guide/indentation.md``.
"""

import argparse
import collections
import math
import time

import warptrunc as wt
from warptrunc.contact.settings import SolverSettings
from warptrunc.contact.solver import ContactSolver
from warptrunc.indent import cycles
from warptrunc.indent import protocol as P
from warptrunc.indent.punch import place_punches, punch_window
from warptrunc.presets import TABLE1


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=1024, help="pixels per side over 1 mm")
    ap.add_argument("--dtype", default="float32", choices=("float32", "float64"))
    ap.add_argument("--surfaces", default="Ps,GB300s", help="Table 1 presets, comma-separated")
    ap.add_argument("--hardness-factors", default="inf,1",
                    help="H as multiples of the alloy's 1 GPa, comma-separated (inf = elastic)")
    ap.add_argument("--punches-um", default="", help="punch diameters (µm); default the paper's")
    ap.add_argument("--device", default="cpu")
    ap.add_argument("--load-control", default="offset", choices=("offset", "secant"))
    ap.add_argument("--algorithm", default="pk", choices=("pk", "bccg"),
                    help="the contact solver's iteration (SolverSettings.algorithm)")
    ap.add_argument("--maxiter", type=int, default=1000, help="iteration limit per solve")
    ap.add_argument("--verbose", action="store_true", help="print every solve")
    a = ap.parse_args(argv)
    n, dtype, dev, lc, verbose = a.n, a.dtype, a.device, a.load_control, a.verbose
    surfs = a.surfaces.split(",")
    facs = [float(x) for x in a.hardness_factors.split(",")]
    punches = ([float(x) * 1e-6 for x in a.punches_um.split(",")] if a.punches_um
               else P.PAPER_PUNCH_DIAMETERS)
    stats = collections.defaultdict(lambda: [0, 0, 0.0, 0.0])  # calls, iterations, convolutions, s
    orig_solve, orig_k = ContactSolver.solve, ContactSolver.punch_stiffness
    phase = ["?"]

    def solve(self, *a, **k):
        t = time.perf_counter()
        s = orig_solve(self, *a, **k)
        dt = time.perf_counter() - t
        key = phase[0] + ("/load" if "load" in k else "/depth") + ("/frozen" if self.plastic_frozen else "")
        st = stats[key]
        st[0] += 1
        st[1] += s.n_iterations
        st[2] += s.n_convolutions
        st[3] += dt
        if verbose or not s.converged:
            print(f"  {key} F={s.load:.4g} it={s.n_iterations} conv={s.converged} {dt:.2f}s", flush=True)
        return s

    def pk(self, *a, **k):
        t = time.perf_counter()
        r = orig_k(self, *a, **k)
        st = stats[phase[0] + "/barber"]
        st[0] += 1
        st[1] += r[1]
        st[2] += r[1]
        st[3] += time.perf_counter() - t
        return r

    ContactSolver.solve, ContactSolver.punch_stiffness = solve, pk
    for s in surfs:
        surf = wt.wm_surface(TABLE1[s].replace(n=n, L=1e-3), device=dev)
        z, dx = surf.heights, surf.dx
        for f in facs:
            mat = P.default_material(hardness=math.inf if math.isinf(f) else f * P.ALUMINIUM_HARDNESS)
            for i, d in enumerate(punches):
                c, _ = place_punches((n * dx, n * dx), d, 1, seed=(0, i))
                w = punch_window(z, (dx, dx), d, tuple(c[0]))
                phase[0] = f"{s}/{f:g}H/{d * 1e6:.0f}um/{w.mask.shape[0]}px"
                t = time.perf_counter()
                out = cycles.run_cycles(w, P.PAPER_PROTOCOL, mat, device=dev,
                                        solver=SolverSettings(dtype=dtype, maxiter=a.maxiter,
                                                              load_control=lc, algorithm=a.algorithm))
                print(phase[0], f"{time.perf_counter() - t:.2f}s", "contact pixels",
                      out["n_contact"][[0, -1]], "converged", bool(out["converged"].all()), flush=True)
    for k, v in stats.items():
        print(f"{k:50s} calls {v[0]:4d} it {v[1]:6d} conv {v[2]:8.1f} s {v[3]:7.2f}", flush=True)


if __name__ == "__main__":
    main()
