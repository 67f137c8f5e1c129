# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The punch as the experiment had it, on Ps: tilt and tip roughness against the aligned smooth flat.

What it does
    Indents the Ps preset (Table 1's polished surface, matched to D_vs: R_t′ = 0.2324 µm) on a
    ``--L`` map of ``--n``² pixels, as ``warptrunc indent --preset Ps --n 512`` does, with the
    502.6 µm punch at ``--placements`` positions and the paper's ten peak loads, once per punch
    face: aligned and smooth (the reference), tilted by each of ``--tilts`` (degrees), and with
    a generated rough tip of ``--roughness`` rms (Hurst 0.8, long cut-off the punch diameter)
    at each short cut-off of ``--cutoffs`` (m; 0 = the default, 2 map pixels), alone and with
    the tilt ``--rough-tilt``. Per cell it records Barber's K, E_c/E and the contact pixels of
    the elastic–plastic and the elastic solutions, the pixel, the resolution flags, the
    approach δ and the truncation depth ω against R_t′, Eq. 2's E_c/E, and K over the
    reference's K at the same placement and load; per face the full-contact load of a tilted
    smooth flat on a flat, 4E*a²·tan θ.

Run
    python examples/benchmarks/punch_face_ps.py --device cpu --out benchmarks/records
    python examples/benchmarks/punch_face_ps.py --L 1e-3 --n 1024 --diameter 54.1e-6 \
        --tilts 0.05 0.1 --cutoffs 0 --rough-tilt 0 --suffix _54um --device cpu --out benchmarks/records
    python examples/benchmarks/punch_face_ps.py --n 256 --tilts 0.1 --cutoffs 0 --out out  # quick
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import sys
import time
import warnings
from pathlib import Path

import numpy as np
from _common import record_name

from warptrunc._support.provenance import git_commit
from warptrunc.indent import (
    PAPER_PEAK_LOADS,
    IndentProtocol,
    PunchFaceSpec,
    default_material,
    indent,
)
from warptrunc.presets import preset
from warptrunc.wm import wm_surface

COLUMNS = (
    "peak_load_N",
    "F_over_EA",
    "unloading_stiffness_N_per_m",
    "E_c_over_E",
    "n_contact_pixels",
    "elastic_unloading_stiffness_N_per_m",
    "elastic_E_c_over_E",
    "elastic_n_contact_pixels",
    "pixel_size_m",
    "resolved",
    "saturated",
    "in_fit",
    "elastic_resolved",
    "displacement_m",
    "truncation_depth_m",
    "truncation_E_c_over_E",
    "converged",
    "elastic_converged",
)


def _faces(args):
    out = [("aligned smooth", {})]
    out += [(f"tilt {t:g}°", {"tilt_deg": t}) for t in args.tilts if t > 0]
    for c in args.cutoffs:
        rough = {"roughness": args.roughness}
        name = f"rough {args.roughness * 1e6:g} µm"
        if c > 0:
            rough["cutoff_short"] = c
            name += f", λ_s {c * 1e6:g} µm"
        out.append((name, rough))
        if args.rough_tilt > 0:
            out.append(
                (f"{name} + tilt {args.rough_tilt:g}°", {**rough, "tilt_deg": args.rough_tilt})
            )
    return out


def summarise(doc: dict) -> dict:
    """Per face and peak load over the placements: the geometric mean, least and largest
    K/K_ref (elastic–plastic and elastic), contact pixels, resolved placements; the reference's
    E_c/E, truncation's E_c/E, δ/R_t′ and ω/R_t′; α, β of E_c/E = β·[F/(E·A)]^α over every cell
    (resolved or not) and over the cells in_fit."""
    m = len(doc["peak_loads_N"])

    def per(v):
        return np.asarray(v, np.float64).reshape(-1, m)

    ref = doc["cases"][0]["rows"]
    out = {
        "peak_loads_N": doc["peak_loads_N"],
        "reference": {
            k: per(ref[k]).mean(0).tolist()
            for k in (
                "E_c_over_E",
                "elastic_E_c_over_E",
                "truncation_E_c_over_E",
                "displacement_over_Rt",
                "truncation_depth_over_Rt",
            )
        },
        "faces": [],
    }
    for c in doc["cases"]:
        r = c["rows"]
        x, y = np.log(r["F_over_EA"]), np.log(r["E_c_over_E"])
        ok = np.asarray(r["in_fit"], bool)
        fits = {"all_cells": np.polyfit(x, y, 1).tolist()}
        if ok.sum() >= 3:
            fits["in_fit"] = np.polyfit(x[ok], y[ok], 1).tolist()
        row = {
            "face": c["face"],
            "n_in_fit": int(ok.sum()),
            "alpha_beta": {k: {"alpha": v[0], "beta": math.exp(v[1])} for k, v in fits.items()},
            "resolved_per_load": per(r["resolved"]).sum(0).astype(int).tolist(),
            "n_contact_pixels_mean": per(r["n_contact_pixels"]).mean(0).tolist(),
        }
        for pre in ("", "elastic_"):
            q = per(r[f"{pre}K_over_reference"])
            row[f"{pre}K_over_reference_geomean"] = np.exp(np.log(q).mean(0)).tolist()
            row[f"{pre}K_over_reference_range"] = [q.min(0).tolist(), q.max(0).tolist()]
        out["faces"].append(row)
    return out


def main(argv=None) -> int:
    """Run every face and write ``punch_face_ps<suffix>_<machine>_<commit>.json``."""
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--n", type=int, default=512, help="pixels per side of the map")
    p.add_argument("--L", type=float, default=3e-3, help="map side (m)")
    p.add_argument("--diameter", type=float, default=502.6e-6, help="punch diameter (m)")
    p.add_argument("--placements", type=int, default=1)
    p.add_argument(
        "--tilts",
        type=float,
        nargs="+",
        default=[0.02, 0.05, 0.1],
        help="tilts of the smooth punch (degrees)",
    )
    p.add_argument("--roughness", type=float, default=0.05e-6, help="tip rms (m)")
    p.add_argument(
        "--cutoffs",
        type=float,
        nargs="+",
        default=[0.0, 2e-6],
        help="short cut-offs of the rough tip (m); 0 = 2 map pixels",
    )
    p.add_argument(
        "--rough-tilt",
        type=float,
        default=0.05,
        help="tilt added to each rough tip (degrees); 0 = none",
    )
    p.add_argument("--refine-max", type=int, default=8)
    p.add_argument("--device", default="cpu")
    p.add_argument("--out", type=Path, default=Path("out/punch_face_ps"))
    p.add_argument("--suffix", default="", help="appended to the JSON's name (another punch)")
    args = p.parse_args(argv)

    spec = preset("Ps").replace(L=args.L, n=args.n)
    surface = wm_surface(spec, device=args.device)
    material = default_material()
    rt = float(surface.Rt)
    a = 0.5 * args.diameter
    cases = []
    ref = None
    for name, face in _faces(args):
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            protocol = IndentProtocol(
                punch_diameters=args.diameter,
                peak_loads=PAPER_PEAK_LOADS,
                placements=args.placements,
                refine_max=args.refine_max,
                face=PunchFaceSpec(**face),
            )
            res = indent(surface, protocol=protocol, material=material, device=args.device)
        d = res.to_dict()
        rows = {k: np.asarray(d[k]).tolist() for k in COLUMNS}
        rows["displacement_over_Rt"] = (d["displacement_m"] / rt).tolist()
        rows["truncation_depth_over_Rt"] = (d["truncation_depth_m"] / rt).tolist()
        if ref is None:
            ref = d
        for pre in ("", "elastic_"):
            k = f"{pre}unloading_stiffness_N_per_m"
            rows[f"{pre}K_over_reference"] = (d[k] / ref[k]).tolist()
        tilt = math.radians(face.get("tilt_deg", 0.0))
        cases.append(
            {
                "face": name,
                "options": face,
                "seconds": time.perf_counter() - t0,
                "full_contact_load_smooth_flat_N": 4
                * material.contact_modulus
                * a
                * a
                * math.tan(tilt),
                "settings_punch_face": res.settings["punch_face"],
                "punches": res.settings["punches"],
                "rows": rows,
            }
        )
        print(
            f"{name}: {cases[-1]['seconds']:.1f} s; K/K_ref (elastic–plastic) "
            + " ".join(f"{v:.2f}" for v in rows["K_over_reference"])
        )
    command = [
        "python",
        "examples/benchmarks/punch_face_ps.py",
        *(sys.argv[1:] if argv is None else argv),
    ]
    doc = {
        "what": "Ps (Table 1, D_vs preset) under the 502.6 µm punch: tilt and tip roughness "
        "against the aligned smooth flat",
        "command": " ".join(command),
        "git_commit": git_commit(),
        "device": args.device,
        "platform": platform.platform(),
        "processor": platform.processor(),
        "date": time.strftime("%Y-%m-%d"),
        "surface": {
            "preset": "Ps",
            "n": args.n,
            "L_m": args.L,
            "pixel_m": surface.dx,
            "Rt_m": rt,
            "params": surface.params,
        },
        "punch_diameter_m": args.diameter,
        "placements": args.placements,
        "peak_loads_N": list(PAPER_PEAK_LOADS),
        "material": material.to_dict(),
        "refine_max": args.refine_max,
        "cases": cases,
    }
    doc["summary"] = summarise(doc)
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / record_name(f"punch_face_ps{args.suffix}", args.device)
    path.write_text(json.dumps(doc, indent=1, default=float))
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
