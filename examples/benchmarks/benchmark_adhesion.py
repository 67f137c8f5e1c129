# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The adhesive contact solve against the non-adhesive one on the same surface and approach.

The surface is a periodic patch of the contact-mechanics challenge's surface at the challenge's
own pixel (3.05 nm; ``challenge_patch_spec``), where its adhesive law (exponential, w = 50 mJ/m²,
ρ = 2.071 nm, E* = 25 MPa) is resolved. At each size of ``--n`` one approach δ = ``--depth``·h_rms
is solved from rest on the periodic half-space, in ``--dtype``, twice each: a cold solve (the
first of the process at that size: kernels, FFT plans) and a warm one (a fresh solver, the same
solve). Recorded per size and law: set-up, cold and warm times (s), iterations, convolutions,
convergence, the repulsive and attractive areas, the load, the device's peak memory (CUDA's
memory pool, bytes) against ``memory_bytes``; and the ratio of the warm times (adhesive over
non-adhesive). Sizes are tried in order; one that does not fit in memory, or whose
``memory_bytes`` exceeds the device's free memory, ends the list (the largest size solved is
the last row).

Writes ``--out/adhesion_<machine>_<commit>.json`` after every row and prints a table. Run::

    python examples/benchmarks/benchmark_adhesion.py --device cuda:0 --n 8192 16384 32768

CPU smoke run: ``--device cpu --n 64 128``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RECORDS, machine_fields, record_name


def _solve(h, dx, e_star, settings, depth, dev):
    import warp as wp

    from warptrunc.contact import ContactSolver

    t0 = time.perf_counter()
    solver = ContactSolver(h, dx, e_star, settings=settings, device=dev)
    wp.synchronize_device(dev)
    t1 = time.perf_counter()
    state = solver.solve(depth)
    wp.synchronize_device(dev)
    t2 = time.perf_counter()
    return solver, state, t1 - t0, t2 - t1


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__.splitlines()[0],
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    ap.add_argument("--device", default=None)
    ap.add_argument("--n", type=int, nargs="+", default=[8192], help="pixels per side, in order")
    ap.add_argument("--dtype", choices=("float32", "float64"), default="float32")
    ap.add_argument("--depth", type=float, default=1.0, help="approach δ in units of h_rms")
    ap.add_argument("--maxiter", type=int, default=20000, help="iteration limit per solve")
    ap.add_argument("--out", type=Path, default=RECORDS)
    args = ap.parse_args(argv)

    import numpy as np
    import warp as wp

    import warptrunc as wt
    from warptrunc.compare.challenge import ADHESION, challenge_patch_spec
    from warptrunc.contact import Adhesion
    from warptrunc.contact.memory import memory_bytes
    from warptrunc.contact.settings import SolverSettings
    from warptrunc.presets import CHALLENGE_MATERIAL
    from warptrunc.selfaffine import self_affine_surface

    dev = wt.resolve_device(args.device)
    e_star = CHALLENGE_MATERIAL.contact_modulus
    law = Adhesion(
        "exponential", work=ADHESION["work_of_adhesion"], range=ADHESION["interaction_range"]
    )
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / record_name("adhesion", str(dev))
    rows: list[dict] = []

    def write() -> None:  # after every row: a run stopped by its time limit keeps what it did
        doc = {
            "title": "adhesive against non-adhesive contact solves, same surface and approach",
            "source": "examples/benchmarks/benchmark_adhesion.py",
            **machine_fields(str(dev)),
            "device_name": getattr(dev, "name", str(dev)),
            "argv": sys.argv[1:] if argv is None else list(argv),
            "law": law.to_dict(),
            "contact_modulus_Pa": e_star,
            "rows": rows,
        }
        path.write_text(json.dumps(doc, indent=1, default=lambda v: None if v != v else v) + "\n")

    print(f"{'n':>6} {'law':>12} {'setup s':>8} {'cold s':>8} {'warm s':>8} {'it':>6} "
          f"{'conv':>5} {'a_r':>7} {'a_att':>7} {'peak GB':>8} {'model GB':>8}")  # fmt: skip
    for n in args.n:
        need = memory_bytes((n, n), "periodic", args.dtype, cuda=dev.is_cuda, adhesion=True)
        if dev.is_cuda:
            free = wp.get_device(dev).free_memory
            if need > 0.9 * free:
                print(f"{n}²: memory_bytes {need / 1e9:.1f} GB > 90 % of the free {free / 1e9:.1f} GB")
                break
        surface = self_affine_surface(challenge_patch_spec(n), device=dev)
        h = np.asarray(surface.heights, dtype=np.float64)
        h_rms = float(h.std())
        depth = args.depth * h_rms
        a0 = h.size * surface.dx * surface.dy
        warm = {}
        for name, adh in (("non-adhesive", Adhesion()), ("exponential", law)):
            settings = SolverSettings(
                substrate="periodic", dtype=args.dtype, adhesion=adh, maxiter=args.maxiter
            )
            try:
                if dev.is_cuda:
                    wp.synchronize_device(dev)
                _, _, _, cold = _solve(h, surface.dx, e_star, settings, depth, dev)
                if dev.is_cuda and wp.is_mempool_enabled(dev):
                    wp.set_mempool_release_threshold(dev, 0)
                solver, st, setup, t = _solve(h, surface.dx, e_star, settings, depth, dev)
            except (MemoryError, RuntimeError) as exc:
                print(f"{n}² {name}: {type(exc).__name__}: {exc}")
                write()
                return 0
            peak = None
            if dev.is_cuda:
                peak = int(wp.get_mempool_used_mem_high(dev))
            warm[name] = t
            rows.append(
                {
                    "n": n,
                    "law": name,
                    "pixel_m": surface.dx,
                    "h_rms_m": h_rms,
                    "depth_m": depth,
                    "setup_s": setup,
                    "cold_s": cold,
                    "warm_s": t,
                    "n_iterations": int(st.n_iterations),
                    "n_convolutions": float(st.n_convolutions),
                    "converged": bool(st.converged),
                    "area_fraction": st.contact_area / a0,
                    "attractive_area_fraction": st.attractive_area / a0,
                    "pressure_over_E_star": st.load / a0 / e_star,
                    "peak_pool_bytes": peak,
                    "memory_bytes": memory_bytes(
                        (n, n), "periodic", args.dtype, cuda=dev.is_cuda, adhesion=adh.active
                    ),
                }
            )
            r = rows[-1]
            print(f"{n:>6} {name:>12} {setup:8.3f} {cold:8.3f} {t:8.3f} {r['n_iterations']:>6} "
                  f"{str(r['converged']):>5} {r['area_fraction']:7.4f} "
                  f"{r['attractive_area_fraction']:7.4f} "
                  f"{(peak or 0) / 1e9:8.2f} {r['memory_bytes'] / 1e9:8.2f}")  # fmt: skip
            del solver
            write()
        if len(warm) == 2:
            rows[-1]["warm_ratio_adhesive_over_non_adhesive"] = (
                warm["exponential"] / warm["non-adhesive"]
            )
            print(f"{n}²: adhesive / non-adhesive warm time {rows[-1]['warm_ratio_adhesive_over_non_adhesive']:.2f}")
            write()
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
