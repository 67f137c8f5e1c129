# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: contact-solver iterations against the grid, per iteration algorithm.

What it shows
    Cold-start (from zero pressure) and warm-start iterations and convolutions of
    :class:`warptrunc.contact.ContactSolver` per map size N, for ``algorithm="pk"`` (Polonsky &
    Keer) and ``"bccg"`` (preconditioned bound-constrained CG; by its default rule, and as
    ``bccg/always`` with ``precondition_above=0`` and ``bccg/2%`` with 0.02), at a fixed relative
    tolerance
    (pentol = 1e-4·rms height), on D = 2.5 WM maps over L = 1 mm (W_r = 100 µm, R_t = 10 µm,
    free boundary) in two families: **fixed content** (cut-off W_c = L/64: the same modes
    sampled finer) and **W_c = pixel** (finer pixels add roughness). Cases: the whole map at
    δ = 0.20·R_t (cold) and 0.21·R_t (warm, from that solution); a rigid flat disk of 0.9·L on
    the fixed-content map at δ = 10·R_t (about 80 % contact, cold), where Polonsky–Keer's O(√N)
    growth shows most.

Run
    python examples/benchmarks/iterations_vs_grid.py --n 256 512 1024 --json /tmp/iters.json
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from warptrunc.contact import ContactSolver, SolverSettings
from warptrunc.wm import wm_surface

E_STAR = 70e9 / (1 - 0.33**2)


def _maps(n: int, family: str) -> np.ndarray:
    wc = {"Wc": 1e-3 / 64} if family == "fixed content" else {}
    s = wm_surface(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6, seed=0, device="cpu", **wc)
    return np.asarray(s.heights, dtype=np.float64)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, nargs="+", default=[256, 512, 1024], help="map sides (pixels)")
    ap.add_argument("--device", default="cpu", help="Warp device")
    ap.add_argument("--dtype", default="float64", choices=("float64", "float32"))
    ap.add_argument("--json", type=Path, default=None, help="write the rows here")
    ap.add_argument(
        "--variants",
        nargs="+",
        default=["pk", "bccg"],
        choices=["pk", "bccg", "bccg/always", "bccg/2%"],
        help="iterations (bccg/always: precondition_above=0; bccg/2%%: 0.02)",
    )
    ap.add_argument("--no-punch", action="store_true", help="the whole-map cases only")
    a = ap.parse_args(argv)
    rows = []
    print(
        f"{'case':34s} {'N':>6s} {'algorithm':>11s} {'iterations':>10s} {'convolutions':>12s} "
        f"{'seconds':>8s} {'load (N)':>12s}"
    )
    for family in ("fixed content", "W_c = pixel"):
        for n in a.n:
            h = _maps(n, family)
            rt = float(np.ptp(h))
            cases = [
                ("map, cold 0.20 R_t", h, [0.20 * rt]),
                ("map, warm 0.21 R_t", h, [0.20 * rt, 0.21 * rt]),
            ]
            if family == "fixed content" and not a.no_punch:
                y, x = np.mgrid[0:n, 0:n]
                hp = h.copy()
                hp[(x - n / 2 + 0.5) ** 2 + (y - n / 2 + 0.5) ** 2 >= (0.45 * n) ** 2] = (
                    h.min() - 1e-3
                )
                cases.append(("punch 0.9 L, cold 10 R_t", hp, [10 * rt]))
            for name, z, depths in cases:
                inside = z > h.min() - 1e-4
                pentol = 1e-4 * float(np.std(z[inside]))
                for alg in a.variants:
                    algorithm, _, rule = alg.partition("/")
                    pc = {"": None, "always": 0.0, "2%": 0.02}[rule]
                    sol = ContactSolver(
                        z,
                        1e-3 / n,
                        E_STAR,
                        device=a.device,
                        settings=SolverSettings(
                            algorithm=algorithm, pentol=pentol, dtype=a.dtype, precondition_above=pc
                        ),
                    )
                    for d in depths[:-1]:
                        sol.solve(d)
                    t = time.perf_counter()
                    st = sol.solve(depths[-1])
                    dt = time.perf_counter() - t
                    row = {
                        "family": family,
                        "case": name,
                        "n": n,
                        "algorithm": alg,
                        "iterations": st.n_iterations,
                        "convolutions": st.n_convolutions,
                        "seconds": dt,
                        "load_N": st.load,
                        "converged": st.converged,
                        "device": a.device,
                        "dtype": a.dtype,
                    }
                    rows.append(row)
                    print(
                        f"{family + ': ' + name:34s} {n:6d} {alg:>11s} {st.n_iterations:10d} "
                        f"{st.n_convolutions:12.1f} {dt:8.2f} {st.load:12.6g}"
                        f"{'' if st.converged else ' (not converged)'}",
                        flush=True,
                    )
    if a.json:
        a.json.parent.mkdir(parents=True, exist_ok=True)
        a.json.write_text(json.dumps({"rows": rows}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
