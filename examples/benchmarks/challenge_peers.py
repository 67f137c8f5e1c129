# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: the contact-mechanics challenge's surface solved by warptrunc, tamaas and
ContactMechanics on the periodic half-space, at several loads: do they agree?

What it shows
    The challenge's surface (:func:`warptrunc.compare.challenge.challenge_spec`: L = 100 µm,
    H = 0.8, λ_r = 20 µm, λ_s = 0.1 µm, h′_rms = 1, E* = 25 MPa) at ``--n`` pixels (2048²: 48.8 nm
    pixels, λ_s = 2.05 pixels; the grid holds every mode of the challenge's spectrum, so this is
    the 32768² surface sampled 16 times coarser), one realisation (seed 0), the same float64
    heights for every solver, at mean pressures ``--loads`` × E* (load control):

    * warptrunc ``ContactSolver`` (periodic, float64) at its default tolerance and at a tight one
      (pentol = 10⁻¹⁰·rms height);
    * tamaas ``PolonskyKeerRey`` (periodic, float64, as ``benchmark_peers.py`` uses it) at
      tolerance 10⁻⁸ and at its own tight 10⁻¹⁰;
    * ContactMechanics (``PeriodicFFTElasticHalfSpace``, Polonsky–Keer CG) at pentol 10⁻⁶·rms
      and at its own tight 10⁻⁹·rms.

    Each solve is cold (zero pressure) and runs in a worker process with a time limit
    (``--time-limit``). The relative contact area (pixels with p > 0) and the mean gap (the gap
    shifted to zero mean over the contact set, averaged over the map; ``benchmark_peers.summarize``)
    of each peer's solves are compared with warptrunc's tight solve and with the peer's own
    tight solve; agreement means within ``--match`` (10⁻³, relative). A solve that does not
    finish in the limit is recorded as such, with the time.

Run
    python examples/benchmarks/challenge_peers.py --n 2048 --loads 1e-4 1e-3 1e-2 1e-1 \\
        --out benchmarks/records          # writes challenge_peers_cpu_<commit>.json
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from _common import cpu_name, git_commit, record_name  # noqa: E402
from benchmark_peers import (  # noqa: E402
    contactmechanics_solve,
    tamaas_solve,
    versions,
    warptrunc_solve,
)

TOLERANCES = {
    "warptrunc": {"default": None, "tight": 1e-10},  # × rms height
    "tamaas": {"loose": 1e-8, "tight": 1e-10},  # its relative error
    "contactmechanics": {"loose": 1e-6, "tight": 1e-9},  # × rms height
}


def challenge_heights(n: int) -> tuple[np.ndarray, dict]:
    """The challenge's float64 heights (m) at n² and what they are."""
    from warptrunc.compare.challenge import challenge_spec
    from warptrunc.selfaffine import self_affine_surface

    spec = challenge_spec(n)
    s = self_affine_surface(spec, device="cpu")
    h = np.asarray(s.heights, dtype=np.float64)
    info = {
        "spec": spec.to_dict(),
        "pixel_m": s.dx,
        "short_cutoff_pixels": spec.short_cutoff / s.dx,
        "h_rms_m": float(s.params["h_rms_m"]),
        "slope_rms": float(s.params["slope_rms"]),
        "C0_m4": float(s.params["C0_m4"]),
        "Rt_m": float(s.Rt),
    }
    return h, info


def solve(kind: str, h: np.ndarray, L: float, E: float, p: float, tol: float | None) -> dict:
    """One cold solve at mean pressure ``p`` (Pa) on the periodic half-space."""
    n = h.shape[0]
    rms = float(np.std(h))
    if kind == "tamaas":
        return tamaas_solve(h, L, E, p, tol, 20000)
    if kind == "contactmechanics":
        forcetol = 1e-5 * E * (L / n) ** 2
        return contactmechanics_solve(h, L, E, p * L * L, tol * rms, forcetol, True)
    from warptrunc.contact import ContactSolver, SolverSettings

    st = SolverSettings(
        substrate="periodic",
        dtype="float64",
        pentol=None if tol is None else tol * rms,
        maxiter=20000,
    )
    s = ContactSolver(h, L / n, E, settings=st, device="cpu")
    return {**warptrunc_solve(s, p * L * L), "pentol_m": s.pentol}


def worker_main(argv: list[str]) -> None:
    """``--worker KIND PATH.npy L E P TOL``: one solve, its JSON on a ``RESULT`` line."""
    kind, path, L, E, p, tol = argv
    h = np.load(path)
    res = solve(kind, h, float(L), float(E), float(p), None if tol == "None" else float(tol))
    print("RESULT " + json.dumps(res), flush=True)


def run_worker(kind, path, L, E, p, tol, limit) -> dict:
    """One solve in a fresh process, stopped after ``limit`` seconds."""
    env = dict(os.environ, OMP_NUM_THREADS=str(os.cpu_count() or 1))
    cmd = [
        sys.executable,
        __file__,
        "--worker",
        kind,
        str(path),
        repr(L),
        repr(E),
        repr(p),
        repr(tol),
    ]
    t0 = time.perf_counter()
    try:
        r = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=limit)
    except subprocess.TimeoutExpired:
        return {"timed_out": True, "time_s": limit, "converged": False}
    for ln in r.stdout.splitlines():
        if ln.startswith("RESULT "):
            return json.loads(ln[7:])
    return {
        "failed": (r.stderr or "")[-800:],
        "converged": False,
        "time_s": time.perf_counter() - t0,
    }


def rel(a: dict, b: dict, key: str) -> float:
    """|a − b|/|b| of ``key``, NaN when either is missing."""
    if key not in a or key not in b:
        return math.nan
    return abs(a[key] - b[key]) / abs(b[key])


def main(argv: list[str] | None = None) -> dict:
    """Run the comparison; returns the record."""
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--worker"]:
        worker_main(argv[1:])
        return {}
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--n", type=int, default=2048, help="pixels per side")
    ap.add_argument(
        "--loads",
        type=float,
        nargs="+",
        default=[1e-4, 1e-3, 1e-2, 1e-1],
        help="mean pressures p/E*",
    )
    ap.add_argument("--peers", nargs="+", default=["tamaas", "contactmechanics"])
    ap.add_argument("--match", type=float, default=1e-3, help="relative agreement asked")
    ap.add_argument("--time-limit", type=float, default=1800.0, help="s per solve")
    ap.add_argument("--out", type=Path, default=None, help="folder for the JSON record")
    args = ap.parse_args(argv)
    from warptrunc.presets import CHALLENGE, CHALLENGE_MATERIAL

    L, E = float(CHALLENGE.L), float(CHALLENGE_MATERIAL.contact_modulus)
    h, info = challenge_heights(args.n)
    record = {
        "benchmark": "challenge_peers",
        "commit": git_commit(),
        "date": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()),
        "device": "cpu",
        "cpu": cpu_name(),
        "cpu_cores": os.cpu_count(),
        "versions": versions(),
        "n": args.n,
        "surface": info,
        "contact_modulus_Pa": E,
        "L_m": L,
        "substrate": "periodic",
        "tolerances": TOLERANCES,
        "tolerance_units": {
            "warptrunc": "× rms height (pentol)",
            "tamaas": "relative error",
            "contactmechanics": "× rms height (pentol)",
        },
        "match": args.match,
        "time_limit_s": args.time_limit,
        "rule": "relative area (p > 0) and mean gap (gap shifted to zero mean over the contact "
        "set) of each solve against warptrunc's tight solve and against the peer's own tight "
        "solve; agreement within `match`",
        "loads": [],
    }
    name = record_name("challenge_peers", "cpu")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "h.npy"
        np.save(path, h)
        for frac in args.loads:
            p = frac * E
            row: dict = {"pressure_over_E_star": frac, "pressure_Pa": p, "solves": {}}
            for kind in ["warptrunc", *args.peers]:
                for label, tol in TOLERANCES[kind].items():
                    res = run_worker(kind, path, L, E, p, tol, args.time_limit)
                    res["tol"] = tol
                    row["solves"][f"{kind} {label}"] = res
                    print(
                        f"p/E* {frac:g} {kind} {label}: "
                        + json.dumps(
                            {
                                k: res.get(k)
                                for k in ("area_fraction", "mean_gap_m", "time_s", "converged")
                            }
                        ),
                        flush=True,
                    )
            ref = row["solves"]["warptrunc tight"]
            agree = {}
            for key, res in row["solves"].items():
                kind, label = key.split()
                own = row["solves"].get(f"{kind} tight", {})
                agree[key] = {
                    "area_vs_warptrunc": rel(res, ref, "area_fraction"),
                    "gap_vs_warptrunc": rel(res, ref, "mean_gap_m"),
                    "area_vs_own_tight": rel(res, own, "area_fraction"),
                    "gap_vs_own_tight": rel(res, own, "mean_gap_m"),
                }
                a = agree[key]
                a["within_match_of_warptrunc"] = bool(
                    res.get("converged")
                    and max(a["area_vs_warptrunc"], a["gap_vs_warptrunc"]) <= args.match
                )
            row["agreement"] = agree
            record["loads"].append(row)
            if args.out is not None:  # after every load, in case a later one is stopped
                args.out.mkdir(parents=True, exist_ok=True)
                (args.out / name).write_text(json.dumps(record, indent=1) + "\n")
    for row in record["loads"]:
        for key, a in row["agreement"].items():
            print(
                f"p/E* {row['pressure_over_E_star']:g} {key:28s} area {a['area_vs_warptrunc']:.2e} "
                f"gap {a['gap_vs_warptrunc']:.2e} (vs own tight: {a['area_vs_own_tight']:.2e}, "
                f"{a['gap_vs_own_tight']:.2e})"
            )
    return record


if __name__ == "__main__":
    main()
