# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""How the reported numbers depend on a surface's shortest wavelength W_c (the content cut-off).

For each Table 1 preset (the D_vs ones) and each W_c in ``--wc`` (default 1.95, 0.98, 0.49 and
0.195 µm: the calibration scan's 2 pixels, then down to the paper's 2 pixels at 97.7 nm), the
same surface (seed, phases, height scale on the calibration scan's grid) is generated at the
``--n``² pixel over ``--L`` and measured:

- its slope: h′_rms and h″_rms by finite differences at the pixel and from its terms;
- the truncation analysis on its defaults (200 increments to 0.1·R_t): α, β of E_c/E = β[F/(EA)]^α;
- with ``--indent``, the flat-punch indentation of the paper at one load (``--load``, default
  500 mN) with the punch of ``--punch`` (default 502.6 µm), one placement, no refinement: the
  unloading stiffness K (N/m), the contact area (m²) and the punch's displacement (m) of the
  elastic–perfectly-plastic solve at ``--hardness`` (default 1 GPa, an assumption: the order of
  an aluminium alloy's) and of the elastic one.

Writes ``--out/content_sensitivity_<machine>_<commit>.json`` (a run record) and prints a table.
Run (one H200, the paper's pixel)::

    python examples/benchmarks/content_sensitivity.py --device cuda:0 --n 10240 --indent

CPU smoke run: ``--device cpu --n 512 --punch 108.7e-6 --indent``.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RECORDS, record_name

WCS = (2e-3 / 1024, 1e-3 / 1024, 0.5e-3 / 1024, 0.2e-3 / 1024)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__.splitlines()[0],
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    ap.add_argument("--device", default=None)
    ap.add_argument("--n", type=int, default=10240, help="pixels per side")
    ap.add_argument("--L", type=float, default=1e-3, help="map side (m)")
    ap.add_argument("--wc", type=float, nargs="+", default=list(WCS), help="W_c values (m)")
    ap.add_argument("--presets", nargs="+", default=["Ps", "SMATs", "GB300s", "GB50s"])
    ap.add_argument("--indent", action="store_true", help="also the indentation at one load")
    ap.add_argument("--punch", type=float, default=502.6e-6, help="punch diameter (m)")
    ap.add_argument("--load", type=float, default=0.5, help="peak load (N)")
    ap.add_argument("--hardness", type=float, default=1e9, help="pressure cap H (Pa)")
    ap.add_argument("--out", type=Path, default=RECORDS)
    args = ap.parse_args(argv)

    import warptrunc as wt
    from warptrunc.analysis import analyze
    from warptrunc.contact.settings import SolverSettings
    from warptrunc.indent import indent
    from warptrunc.indent.protocol import IndentProtocol
    from warptrunc.presets import TABLE1
    from warptrunc.slope import slope_record

    dev = wt.resolve_device(args.device)
    rows = []
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / record_name("content_sensitivity", str(dev))

    def write() -> None:  # after every row: a run stopped by its time limit keeps what it did
        doc = {
            "title": "sensitivity of the reported numbers to the content cut-off W_c",
            "source": "examples/benchmarks/content_sensitivity.py",
            "device": str(dev),
            "device_name": getattr(dev, "name", str(dev)),
            "argv": sys.argv[1:] if argv is None else list(argv),
            "rows": rows,
        }
        path.write_text(json.dumps(doc, indent=1, default=lambda v: None if v != v else v) + "\n")

    for name in args.presets:
        for wc in args.wc:
            spec = TABLE1[name].replace(n=args.n, L=args.L, Wc=wc)
            t0 = time.perf_counter()
            s = wt.wm_surface(spec, device=dev)
            slope = slope_record(s)
            a = analyze(s, device=dev)
            row = {
                "preset": name,
                "Wc_m": wc,
                "n": args.n,
                "L_m": args.L,
                "pixel_m": args.L / args.n,
                "Rt_m": s.Rt,
                "slope_rms": slope["slope_rms"],
                "curvature_rms_per_m": slope["curvature_rms_per_m"],
                "slope_rms_spectrum": slope["spectrum"]["slope_rms"],
                "alpha": a.fit.alpha,
                "beta": a.fit.beta,
                "r2": a.fit.r2,
                "fit_error": a.fit_error,
            }
            if args.indent:
                protocol = IndentProtocol(
                    punch_diameters=(args.punch,),
                    peak_loads=(args.load,),
                    placements=1,
                    refine_max=1,
                    elastic=True,
                )
                material = wt.Material.against_diamond(hardness=args.hardness)
                r = indent(
                    s, protocol=protocol, material=material, solver=SolverSettings(), device=dev
                )
                row.update(
                    {
                        "hardness_Pa": args.hardness,
                        "punch_m": args.punch,
                        "load_N": args.load,
                        "K_N_per_m": float(r.unloading_stiffness[-1]),
                        "contact_area_m2": float(r.contact_area[-1]),
                        "depth_m": float(r.displacement[-1]),
                        "elastic_K_N_per_m": float(r.elastic_unloading_stiffness[-1]),
                        "elastic_contact_area_m2": float(r.elastic_contact_area[-1]),
                        "elastic_depth_m": float(r.elastic_displacement[-1]),
                        "converged": bool(r.converged.all() and r.elastic_converged.all()),
                    }
                )
            row["seconds"] = time.perf_counter() - t0
            rows.append(row)
            msg = (
                f"{name:7s} Wc {wc * 1e6:6.3f} µm  h′ {row['slope_rms']:8.4g}  α {row['alpha']:.4f}"
                f"  β {row['beta']:.4g}"
            )
            if args.indent:
                msg += (
                    f"  K {row['K_N_per_m']:.4g} N/m  A {row['contact_area_m2'] * 1e12:.4g} µm²"
                    f"  depth {row['depth_m'] * 1e6:.4g} µm  K_el {row['elastic_K_N_per_m']:.4g}"
                )
            print(msg + f"  ({row['seconds']:.1f} s)", flush=True)
            write()
            del s
    print(f"wrote {path}")
    return 0 if all(math.isfinite(r["alpha"]) for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
