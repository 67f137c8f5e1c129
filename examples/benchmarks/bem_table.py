# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation against elastic BEM across fractal dimensions: the README's ratio table.

For each D and seed, a WM surface is generated (the defaults of ``analyze``: L = 1 mm,
W_r = 100 µm, R_t = 10 µm) and :func:`warptrunc.bem_check` compares truncation with the
non-periodic elastic boundary-element solution at δ/R_t = 0.05 … 0.4. Writes OUT/bem_table.json
(every case's summary and columns) and OUT/bem_table.md (the ranges of the ratios, the solve
time per case and per solve). Needs ``pip install "warptrunc[bem]"``.

Run: ``python examples/benchmarks/bem_table.py --n 512 --out out/bem_table`` (the record kept: ``benchmarks/records/bem_table_cpu_2026-11-23.json``) (about 1.5 min per case on 2 cores).
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path

import numpy as np


def tables(info: dict) -> str:
    """Markdown: ranges over approaches and seeds per D, then seed means per approach."""
    cases = info["cases"]
    Ds = sorted({c["D"] for c in cases})

    def rng(key: str, D: float) -> str:
        v = [c[key] for c in cases if c["D"] == D and c[key] is not None]
        return f"{min(x[0] for x in v):.2f}–{max(x[1] for x in v):.2f}" if v else "n/a"

    lines = [
        "| D | F'/F_BEM | k'/k_BEM | A'/A_BEM | converged | s per solve | s per case |",
        "|---|---|---|---|---|---|---|",
    ]
    for D in Ds:
        cs = [c for c in cases if c["D"] == D]
        lines.append(
            f"| {D} | {rng('load_ratio', D)} | {rng('stiffness_ratio', D)} | "
            f"{rng('area_ratio', D)} | {sum(c['all_converged'] for c in cs)}/{len(cs)} | "
            f"{np.mean([c['time_per_solve_s'] for c in cs]):.1f} | "
            f"{np.mean([c['wall_s'] for c in cs]):.0f} |"
        )
    lines += [
        "",
        "| D | δ/R_t | F'/F_BEM | k'/k_BEM | A'/A_BEM | A_BEM/A |",
        "|---|---|---|---|---|---|",
    ]
    for D in Ds:
        cols = [c["columns"] for c in cases if c["D"] == D]
        for i, f in enumerate(cols[0]["depth_fraction_of_Rt"]):

            def ms(key: str, i: int = i, cols: list = cols) -> str:
                v = np.array([c[key][i] for c in cols], dtype=float)
                return f"{v.mean():.2f} ({v.min():.2f}–{v.max():.2f})"

            frac = np.mean([c["bem_area_m2"][i] for c in cols]) / 1e-6  # A = 1 mm²
            lines.append(
                f"| {D} | {f:.2f} | {ms('load_ratio')} | {ms('stiffness_ratio')} | "
                f"{ms('area_ratio')} | {100 * frac:.2g} % |"
            )
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    """Run the cases and write the table."""
    p = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    p.add_argument("--device", default="cpu", help="Warp device for generation and truncation")
    p.add_argument("--n", type=int, default=512, help="pixels per side")
    p.add_argument("--D", type=float, nargs="+", default=[2.1, 2.5, 2.9], help="fractal dimensions")
    p.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2], help="seeds")
    p.add_argument("--seed", type=int, default=None, help="a single seed (overrides --seeds)")
    p.add_argument("--out", type=Path, default=Path("out/bem_table"), help="output folder")
    p.add_argument("--quick", action="store_true", help="64², one D, one seed")
    p.add_argument("--no-show", action="store_true", help="no-op (no window is opened)")
    p.add_argument(
        "--tables-only", action="store_true", help="rewrite OUT/bem_table.md from its JSON"
    )
    a = p.parse_args(argv)
    if a.tables_only:
        text = tables(json.loads((a.out / "bem_table.json").read_text()))
        (a.out / "bem_table.md").write_text(text)
        print(text)
        return 0

    from warptrunc import bem_check
    from warptrunc.stiffness import Material
    from warptrunc.wm import wm_surface

    n, Ds, seeds = a.n, a.D, a.seeds if a.seed is None else [a.seed]
    if a.quick:
        n, Ds, seeds = 64, Ds[:1], seeds[:1]
    a.out.mkdir(parents=True, exist_ok=True)
    material = Material()
    cases = []
    for D in Ds:
        for seed in seeds:
            s = wm_surface(D, 100e-6, L=1e-3, n=n, Rt=10e-6, seed=seed, device=a.device)
            t0 = time.perf_counter()
            res = bem_check(s, material=material, progress=False, device=a.device)
            wall = time.perf_counter() - t0
            sm = res.summary()
            cases.append(
                {
                    "D": D,
                    "seed": seed,
                    "n": n,
                    "wall_s": wall,
                    **sm,
                    "columns": {k: np.asarray(v).tolist() for k, v in res.to_dict().items()},
                }
            )
            print(
                f"D={D} seed={seed}: F'/F {sm['load_ratio']}, k'/k {sm['stiffness_ratio']}, "
                f"A'/A {sm['area_ratio']}, converged={sm['all_converged']}, "
                f"{sm['time_per_solve_s']:.2f} s/solve, case {wall:.0f} s",
                flush=True,
            )
    info = {
        "machine": f"{platform.processor() or platform.machine()}, shared 2-core CPU",
        "material": {k: (str(v) if v == float("inf") else v) for k, v in material.__dict__.items()},
        "cases": cases,
    }
    (a.out / "bem_table.json").write_text(json.dumps(info, indent=1, default=str) + "\n")

    text = tables(info)
    (a.out / "bem_table.md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
