# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: warptrunc's contact solver against its peers, tamaas and ContactMechanics.

What it shows
    The same rough surfaces solved by each solver at the same mean pressure (load control,
    p̄ = 0.05·E*, E* = 1 Pa, a map of 1 m × 1 m), at matched accuracy, with the threads each one
    used:

    * surfaces: tamaas' own self-affine generator (``SurfaceGeneratorFilter2D`` with
      ``Isopowerlaw2D``: Hurst 0.8, q0 = q1 = 4, q2 = n/4, seed 1) scaled to a spectral rms
      slope of 1 (``Statistics2D.computeSpectralRMSSlope``), and a WM map
      (:func:`warptrunc.wm.wm_surface`, D = 2.5, W_r = L/10, seed 1) scaled to an rms slope of
      1 by periodic central differences;
    * periodic substrate: tamaas ``PolonskyKeerRey`` (float64, the only precision its wheel
      has), ContactMechanics ``PeriodicFFTElasticHalfSpace``, warptrunc ``ContactSolver``
      (``substrate="periodic"``, float64 and float32);
    * free substrate (zero-padded patch): ContactMechanics ``FreeFFTElasticHalfSpace`` and
      warptrunc (``substrate="free"``).

    Matched accuracy. Each problem (surface, substrate, N) has a tight reference: tamaas at
    tolerance 10⁻¹⁰ on the periodic substrate, ContactMechanics at pentol = 10⁻⁹·rms height on
    the free one (warptrunc float64 at 10⁻¹¹·rms when the peer is missing). The contact area
    (pixels with p > 0) and the mean gap (the gap map shifted to zero mean over the contact
    set, averaged over the map) of a solve *match* when both are within 10⁻⁴ (relative) of the
    reference's. The rule: each solver tightens its tolerance by decades from the loosest
    (tamaas ``tolerance`` 10⁻² … 10⁻¹⁰; ContactMechanics and warptrunc ``pentol`` 10⁻² … 10⁻¹⁰
    times the rms height, float32 down to 10⁻⁶) until two decades in a row match, and is timed
    at the looser of the two (at the tightest when only it matches; "no match" when none does).
    Every solve is cold (a new solver, zero pressure) and timed around ``solve`` alone (setup
    apart, warptrunc's kernels compiled by a warm-up solve first; warptrunc's time is the
    median of ``--repeats`` solves, the peers' one solve).

    Threads. tamaas and ContactMechanics run in worker processes (a fresh process per walk, so
    that ``--time-limit`` can stop one): tamaas with OMP_NUM_THREADS=1 and = all cores (its pip
    wheel's ``TamaasInfo.backend`` is recorded: ``cpp`` means no OpenMP); ContactMechanics
    uses NumPy's FFT (one thread). warptrunc on the CPU: Warp's kernels on one core, SciPy's
    FFTs with ``workers=os.cpu_count()``; on ``--device cuda:0`` one GPU (cuFFT through CuPy).

    A peer whose work at one N (tolerance walk and timings) exceeds ``--time-limit`` seconds
    is not run again (other surfaces at that N, larger N); a single solve is stopped at that
    limit. For large N on a GPU, ``--reference warptrunc`` (the tight reference from warptrunc
    float64 at 10⁻¹¹·rms) and ``--tamaas-tol`` (one tamaas solve at a given tolerance, its match
    recorded, instead of its walk) keep the run short. The JSON records the machine (CPU model, cores, GPU name), the
    commit, the versions and how tamaas was installed; a table is printed last.

Run
    python examples/benchmarks/benchmark_peers.py --device cpu --sizes 256 512 1024 \\
        --out benchmarks/records --name peers_cpu_<commit>.json
    python examples/benchmarks/benchmark_peers.py --device cuda:0 --sizes 256 512 1024 2048 \\
        --out $OUT
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from _common import cpu_name

E_STAR = 1.0  # Pa
P_MEAN = 0.05 * E_STAR  # Pa
MATCH = 1e-4  # relative, on the contact area and the mean gap
TAMAAS_TOLS = [10.0**-k for k in range(2, 11)]  # loosest first
PENTOLS = [10.0**-k for k in range(2, 11)]  # × rms height, loosest first
PENTOL32_START = 1e-6  # float32's walk ends here (× rms height: its round-off allows no less)
TAMAAS_REF_TOL = 1e-10  # 1e-12 stalls on the WM map at 512² (error ~1e-11)
CM_REF_PENTOL = 1e-9
WT_REF_PENTOL = 1e-11


# --- surfaces --------------------------------------------------------------------------------


def tamaas_surface(n: int, seed: int = 1) -> np.ndarray:
    """tamaas' self-affine surface (Hurst 0.8, q0 = q1 = 4, q2 = n/4), spectral rms slope 1."""
    import tamaas as tm

    sp = tm.Isopowerlaw2D()
    sp.q0, sp.q1, sp.q2, sp.hurst = 4, 4, max(n // 4, 5), 0.8
    gen = tm.SurfaceGeneratorFilter2D([n, n])
    gen.spectrum, gen.random_seed = sp, seed
    h = np.array(gen.buildSurface(), dtype=np.float64)
    return h / tm.Statistics2D.computeSpectralRMSSlope(h)


def fd_rms_slope(h: np.ndarray, dx: float) -> float:
    """rms slope by periodic central differences (dimensionless)."""
    gx = (np.roll(h, -1, 1) - np.roll(h, 1, 1)) / (2 * dx)
    gy = (np.roll(h, -1, 0) - np.roll(h, 1, 0)) / (2 * dx)
    return float(np.sqrt(np.mean(gx**2 + gy**2)))


def wm_map(n: int, seed: int = 1) -> np.ndarray:
    """A WM map (D = 2.5, W_r = L/10 over L = 1 m), rms slope 1 (central differences)."""
    from warptrunc.wm import wm_surface

    s = wm_surface(2.5, 0.1, L=1.0, n=n, Rt=1e-2, seed=seed, device="cpu")
    h = np.asarray(s.heights, dtype=np.float64)
    return h / fd_rms_slope(h, 1.0 / n)


def summarize(p: np.ndarray, gap: np.ndarray) -> dict:
    """Contact area fraction (p > 0) and mean gap (m; the gap shifted to zero mean over the
    contact set) of a solution."""
    c = p > 0
    g = gap - (gap[c].mean() if c.any() else 0.0)
    return {"area_fraction": float(c.mean()), "mean_gap_m": float(g.mean())}


# --- the solvers -----------------------------------------------------------------------------


def tamaas_solve(
    h: np.ndarray, size: float, modulus: float, pressure: float, tol: float, max_iter: int
) -> dict:
    """One cold tamaas PolonskyKeerRey solve (periodic, float64) of heights ``h`` (m) on a square
    of side ``size`` (m) at mean pressure ``pressure`` (Pa), stopped after ``max_iter``
    iterations (not converged): its summary, time (s), error and convergence."""
    import tamaas as tm

    n = h.shape[0]
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [size, size], [n, n])
    model.E, model.nu = modulus, 0.0
    solver = tm.PolonskyKeerRey(model, h, tol)
    solver.max_iter = max_iter
    t0 = time.perf_counter()
    solver.solve(pressure)
    t = time.perf_counter() - t0
    p = np.array(model.traction)
    res = summarize(p, np.array(model.displacement) - h)
    err = float(solver.computeError())
    # computeError() after the solve measures the final state again and reads a little above
    # the value at which tamaas' own loop stopped (1.12e-10 after it stopped at 9.6e-11 for
    # tol 1e-10 at 256²): a solve within 2 × tol has converged; a stalled one stays far above
    return {**res, "time_s": t, "converged": bool(err < 2 * tol), "error": err}


def contactmechanics_solve(
    h: np.ndarray,
    size: float,
    modulus: float,
    force: float,
    pentol: float,
    forcetol: float,
    periodic: bool,
) -> dict:
    """One cold ContactMechanics solve (Polonsky–Keer CG, float64) of heights ``h`` (m) on a
    square of side ``size`` (m) at total force ``force`` (N): its summary, time (s),
    convergence and iterations."""
    from ContactMechanics import FreeFFTElasticHalfSpace, PeriodicFFTElasticHalfSpace
    from ContactMechanics.Optimization import constrained_conjugate_gradients
    from SurfaceTopography import Topography

    n = h.shape[0]
    ht = np.ascontiguousarray(h.T)  # ContactMechanics: x first
    topo = Topography(ht, physical_sizes=(size, size), periodic=periodic)
    cls = PeriodicFFTElasticHalfSpace if periodic else FreeFFTElasticHalfSpace
    hs = cls(ht.shape, modulus, (size, size))
    t0 = time.perf_counter()
    r = constrained_conjugate_gradients(
        hs,
        topo,
        external_force=force,
        pentol=pentol,
        forcetol=forcetol,
        maxiter=100000,
    )
    t = time.perf_counter() - t0
    f = np.asarray(r.jac)
    u = np.asarray(r.x)[:n, :n]
    res = summarize(f.T, (u - ht - r.offset).T)
    return {**res, "time_s": t, "converged": bool(r.success), "iterations": int(r.nit)}


def warptrunc_solve(s, load: float) -> dict:
    """One timed solve of a warptrunc ContactSolver ``s`` at total load ``load`` (N), the device
    synchronised on both sides: its summary, time (s), convergence and iterations."""
    import warp as wp

    wp.synchronize_device(s.device)
    t0 = time.perf_counter()
    state = s.solve(load=load)
    wp.synchronize_device(s.device)
    t = time.perf_counter() - t0
    p, gap = s.maps()
    return {
        **summarize(p, gap),
        "time_s": t,
        "converged": bool(state.converged),
        "iterations": int(state.n_iterations),
    }


def solve_tamaas(h: np.ndarray, tol: float) -> dict:
    """One cold tamaas PolonskyKeerRey solve (periodic, float64) at mean pressure P_MEAN."""
    # a stalled solve stops after 3000 iterations (not converged)
    return tamaas_solve(h, 1.0, E_STAR, P_MEAN, tol, 3000)


def solve_cm(h: np.ndarray, substrate: str, pentol: float) -> dict:
    """One cold ContactMechanics solve (Polonsky–Keer CG, float64) at mean pressure P_MEAN."""
    n = h.shape[0]
    forcetol = 1e-5 * E_STAR / n**2
    return contactmechanics_solve(h, 1.0, E_STAR, P_MEAN, pentol, forcetol, substrate == "periodic")


def solve_warptrunc(
    h: np.ndarray, substrate: str, dtype: str, pentol: float | None, device: str
) -> dict:
    """One cold warptrunc ContactSolver solve at mean pressure P_MEAN (``pentol`` None: the
    default tolerance)."""
    from warptrunc.contact import ContactSolver, SolverSettings

    n = h.shape[0]
    st = SolverSettings(substrate=substrate, dtype=dtype, pentol=pentol, maxiter=2000)
    s = ContactSolver(h, 1.0 / n, E_STAR, settings=st, device=device)
    return warptrunc_solve(s, P_MEAN)


# --- matched accuracy ------------------------------------------------------------------------


def matches(res: dict, ref: dict) -> bool:
    """Contact area and mean gap both within MATCH (relative) of the reference's."""
    if not res.get("converged"):
        return False
    da = abs(res["area_fraction"] - ref["area_fraction"]) / abs(ref["area_fraction"])
    dg = abs(res["mean_gap_m"] - ref["mean_gap_m"]) / abs(ref["mean_gap_m"])
    res["area_rel_err"], res["gap_rel_err"] = da, dg
    return da <= MATCH and dg <= MATCH


def walk(solve, tols: list[float], ref: dict | None, deadline: float, emit=None) -> tuple:
    """Tighten the tolerance by decades from the loosest, ``tols[0]``, until two decades in a
    row match ``ref``; returns (the record of the looser of the two, or of the tightest
    tolerance when only it matched, or None; every solve's record). Without ``ref``: one solve
    at ``tols[0]``."""
    tried: list[dict] = []
    for tol in tols:
        res = solve(tol)
        res["tol"] = tol
        res["matches"] = ref is None or matches(res, ref)
        tried.append(res)
        if emit is not None:
            emit(res)
        if ref is None:
            return res, tried
        if res["matches"] and len(tried) > 1 and tried[-2]["matches"]:
            return tried[-2], tried
        if time.perf_counter() > deadline:
            break
    return chosen_of(tried, len(tols)), tried


def chosen_of(tried: list[dict], n_tols: int) -> dict | None:
    """The choice of :func:`walk` from its records (of a walk over ``n_tols`` tolerances,
    stopped early or not)."""
    for a, b in itertools.pairwise(tried):
        if a.get("matches") and b.get("matches"):
            return a
    if len(tried) == n_tols and tried[-1].get("matches"):
        return tried[-1]
    return None


# --- worker processes (tamaas, ContactMechanics) ---------------------------------------------


def worker_main(argv: list[str]) -> None:
    """``--worker KIND PATH.npy SUBSTRATE REF.json TOL,TOL,...``: the walk of one peer (one solve
    without a reference), a ``RESULT`` line of JSON per solve (tols are absolute)."""
    kind, path, substrate, ref_json, tols = argv
    h = np.load(path)
    ref = json.loads(ref_json)

    def solve(tol):
        return solve_tamaas(h, tol) if kind == "tamaas" else solve_cm(h, substrate, tol)

    def emit(res):
        sys.stderr.flush()
        print("RESULT " + json.dumps(res), flush=True)

    walk(solve, [float(t) for t in tols.split(",")], ref, math.inf, emit)


def _text(x) -> str:
    return x.decode() if isinstance(x, bytes) else (x or "")


def run_worker(
    kind: str,
    path: Path,
    substrate: str,
    ref: dict | None,
    tols: list[float],
    threads: int,
    limit: float,
) -> tuple:
    """A peer's walk (or one solve, without ``ref``) in a fresh process with OMP_NUM_THREADS =
    ``threads``; ``limit`` (s) stops it. Returns (chosen record or None, every solve's record)."""
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OPENBLAS_NUM_THREADS=str(threads))
    cmd = [
        sys.executable,
        __file__,
        "--worker",
        kind,
        str(path),
        substrate,
        json.dumps(ref),
        ",".join(repr(t) for t in tols),
    ]
    timed_out = False
    try:
        r = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=limit)
        out, err = r.stdout, r.stderr
    except subprocess.TimeoutExpired as e:
        timed_out, out, err = True, _text(e.stdout), _text(e.stderr)
    tried = [json.loads(ln[7:]) for ln in out.splitlines() if ln.startswith("RESULT ")]
    if kind == "tamaas":  # its C++ log (stderr): the first number of each solve's last line
        its: list = []
        for ln in err.splitlines():
            w = ln.split()
            if w and w[0] == "Iter":
                its.append(None)
            elif w and w[0].isdigit() and its:
                its[-1] = int(w[0])
        for res, it in zip(tried, its, strict=False):
            res["iterations"] = it
    if timed_out:
        tried.append({"timed_out": True, "time_s": limit, "converged": False, "matches": False})
    elif not tried:
        tried.append({"failed": err[-800:], "converged": False, "matches": False})
    if ref is None:
        return tried[0], tried
    return chosen_of(tried, len(tols)), tried


def versions() -> dict:
    """Versions of the solvers and their libraries, and how tamaas was installed."""
    from importlib import metadata

    out = {"python": platform.python_version()}
    for dist in ("warptrunc", "warp-lang", "numpy", "scipy", "tamaas", "ContactMechanics"):
        try:
            out[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            out[dist] = None
    try:
        d = metadata.distribution("tamaas")
        installer = (d.read_text("INSTALLER") or "").strip()
        direct = d.read_text("direct_url.json")
        whl = (d.read_text("WHEEL") or "").split("Tag:")[-1].strip()
        out["tamaas_install"] = (
            f"{installer or '?'} install tamaas=={d.version} "
            f"({'from ' + direct if direct else 'PyPI'} wheel {whl})"
        )
        import tamaas as tm

        out["tamaas_backend"] = str(tm.TamaasInfo.backend)
        out["tamaas_dtype"] = str(np.dtype(tm.dtype))
    except (metadata.PackageNotFoundError, ImportError):
        pass
    return out


def have(module: str) -> bool:
    """Whether ``module`` can be imported (without importing it)."""
    from importlib.util import find_spec

    return find_spec(module) is not None


# --- the benchmark ---------------------------------------------------------------------------


def bench_problem(h, surface, substrate, n, args, tmp, budget) -> list[dict]:
    """Every solver on one problem: the reference, the walks, the timings (records)."""
    rms = float(np.std(h))
    path = tmp / f"{surface}_{n}.npy"
    np.save(path, h)
    ncpu = os.cpu_count() or 1
    rows: list[dict] = []
    lim = args.time_limit
    base = {"surface": surface, "substrate": substrate, "n": n}
    use_tamaas = substrate == "periodic" and have("tamaas") and "tamaas" in args.peers
    use_cm = have("ContactMechanics") and "contactmechanics" in args.peers
    if args.reference == "warptrunc":
        ref = solve_warptrunc(h, substrate, "float64", WT_REF_PENTOL * rms, args.device)
        ref_by = f"warptrunc float64 pentol {WT_REF_PENTOL:g}·rms (--reference warptrunc)"
    elif use_tamaas and budget.get("tamaas", 0) < lim:
        ref = run_worker("tamaas", path, substrate, None, [TAMAAS_REF_TOL], ncpu, lim)[0]
        ref_by = f"tamaas tol {TAMAAS_REF_TOL:g}"
    elif use_cm and budget.get(f"cm-{substrate}", 0) < lim:
        ref = run_worker("cm", path, substrate, None, [CM_REF_PENTOL * rms], 1, lim)[0]
        ref_by = f"ContactMechanics pentol {CM_REF_PENTOL:g}·rms"
    else:
        ref = solve_warptrunc(h, substrate, "float64", WT_REF_PENTOL * rms, args.device)
        ref_by = f"warptrunc float64 pentol {WT_REF_PENTOL:g}·rms"
    if not ref.get("converged"):
        ref = solve_warptrunc(h, substrate, "float64", WT_REF_PENTOL * rms, args.device)
        ref_by = f"warptrunc float64 pentol {WT_REF_PENTOL:g}·rms (the peer's did not converge)"
    ref_row = {**base, "solver": "reference", "by": ref_by, **ref}
    rows.append(ref_row)
    print(
        f"  {surface} {substrate} {n}²: reference {ref_by}: A/A0 {ref['area_fraction']:.6f}, "
        f"mean gap {ref['mean_gap_m']:.6e} m, {ref['time_s']:.2f} s",
        flush=True,
    )

    def record(name, chosen, tried, threads, extra=None):
        row = {**base, "solver": name, "threads": threads, "walk": tried, **(extra or {})}
        if chosen is None or not chosen.get("matches"):
            row.update(matched=False, **{k: v for k, v in (chosen or {}).items() if k != "walk"})
        else:
            row.update(matched=True, **{k: v for k, v in chosen.items() if k != "walk"})
        rows.append(row)
        t = row.get("time_s")
        print(
            f"    {name:34s} tol {row.get('tol', float('nan')):8.0e} "
            f"{f'{t:.3f} s' if row.get('matched') else 'no match':>10s} "
            f"it {row.get('iterations', '-')}",
            flush=True,
        )

    if use_tamaas and budget.get("tamaas", 0) < lim:
        t0 = time.perf_counter()
        if args.tamaas_tol is None:
            chosen, tried = run_worker("tamaas", path, substrate, ref, TAMAAS_TOLS, ncpu, lim)
        else:  # one solve at the given tolerance, its match recorded
            chosen = run_worker("tamaas", path, substrate, None, [args.tamaas_tol], ncpu, lim)[0]
            chosen["matches"] = matches(chosen, ref)
            tried = []
        record(
            f"tamaas ({ncpu} threads)",
            chosen,
            tried,
            ncpu,
            {"tol_given": args.tamaas_tol is not None},
        )
        if chosen is not None and "tol" in chosen and ncpu > 1 and args.tamaas_one_thread:
            one = run_worker("tamaas", path, substrate, None, [chosen["tol"]], 1, lim)[0]
            one["matches"] = matches(one, ref)
            record("tamaas (1 thread)", one, [], 1)
        budget["tamaas"] = time.perf_counter() - t0
    key = f"cm-{substrate}"
    if use_cm and budget.get(key, 0) < lim:
        t0 = time.perf_counter()
        chosen, tried = run_worker("cm", path, substrate, ref, [t * rms for t in PENTOLS], 1, lim)
        for res in tried:  # the chosen one among them
            if "tol" in res:
                res["tol"] /= rms
        record(f"ContactMechanics {substrate}", chosen, tried, 1, {"tol_unit": "× rms height"})
        budget[key] = time.perf_counter() - t0
    for dtype in args.dtypes:
        solve_warptrunc(h, substrate, dtype, None, args.device)  # warm-up: kernels compiled
        tols = PENTOLS if dtype == "float64" else [t for t in PENTOLS if t >= PENTOL32_START]
        chosen, tried = walk(
            lambda tol, d=dtype: solve_warptrunc(h, substrate, d, tol * rms, args.device),
            tols,
            ref,
            time.perf_counter() + lim,
        )
        if chosen is not None and args.repeats > 1:  # the median of repeats at that tolerance
            ts = [chosen["time_s"]] + [
                solve_warptrunc(h, substrate, dtype, chosen["tol"] * rms, args.device)["time_s"]
                for _ in range(args.repeats - 1)
            ]
            chosen = {**chosen, "time_s": float(np.median(ts)), "times_s": ts}
        default = solve_warptrunc(h, substrate, dtype, None, args.device)
        matches(default, ref)
        record(
            f"warptrunc {substrate} {dtype}",
            chosen,
            tried,
            None,
            {"tol_unit": "× rms height", "default_tolerance": default},
        )
    return rows


def table(rows: list[dict], device_name: str) -> str:
    """The printed table: time at matched accuracy per solver, and tamaas' time ÷ warptrunc's."""
    lines = [
        f"| surface | substrate | N | solver | tol | iterations | time (s) | vs warptrunc f64 "
        f"({device_name}) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r["solver"] == "reference":
            continue
        wt = next(
            (
                x
                for x in rows
                if x["solver"] == f"warptrunc {r['substrate']} float64"
                and x["n"] == r["n"]
                and x["surface"] == r["surface"]
                and x.get("matched")
            ),
            None,
        )
        t = r.get("time_s") if r.get("matched") else None
        ratio = f"{t / wt['time_s']:.1f}×" if t and wt else "-"
        lines.append(
            f"| {r['surface']} | {r['substrate']} | {r['n']}² | {r['solver']} | "
            f"{r.get('tol', float('nan')):.0e} | {r.get('iterations', '-')} | "
            f"{f'{t:.3f}' if t else 'no match'} | {ratio} |"
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> dict:
    """Run the benchmark; returns the JSON record."""
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--worker"]:
        worker_main(argv[1:])
        return {}
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--device", default="cpu", help="warptrunc's device: cpu, cuda:0, ...")
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024], help="N (N² maps)")
    ap.add_argument("--surfaces", nargs="+", default=["tamaas", "wm"], choices=["tamaas", "wm"])
    ap.add_argument(
        "--substrates", nargs="+", default=["periodic", "free"], choices=["periodic", "free"]
    )
    ap.add_argument("--dtypes", nargs="+", default=["float64", "float32"])
    ap.add_argument("--peers", nargs="+", default=["tamaas", "contactmechanics"])
    ap.add_argument(
        "--time-limit",
        type=float,
        default=600.0,
        help="s per peer and N; larger N skipped for a peer past it",
    )
    ap.add_argument("--repeats", type=int, default=3, help="warptrunc's timed solves (median)")
    ap.add_argument(
        "--reference",
        choices=["peer", "warptrunc"],
        default="peer",
        help="the tight reference: the peer's own (tamaas periodic, ContactMechanics "
        "free) or warptrunc float64 at pentol 1e-11·rms (fast, for large N)",
    )
    ap.add_argument(
        "--tamaas-tol",
        type=float,
        default=None,
        help="time tamaas at this tolerance (one solve, its match recorded) "
        "instead of walking its tolerance",
    )
    ap.add_argument(
        "--tamaas-one-thread",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="also time tamaas with OMP_NUM_THREADS=1",
    )
    ap.add_argument("--out", type=Path, default=None, help="folder for the JSON")
    ap.add_argument("--name", default=None, help="JSON file name (default peers_<device>.json)")
    args = ap.parse_args(argv)
    import warp as wp

    wp.config.quiet = True
    wp.init()
    from warptrunc._support.provenance import git_commit

    dev = wp.get_device(args.device)
    dev_name = dev.name if dev.is_cuda else cpu_name()
    if "tamaas" in args.surfaces and not have("tamaas"):
        print("tamaas is not installed: its surface and solver are skipped")
        args.surfaces = [s for s in args.surfaces if s != "tamaas"]
    record = {
        "benchmark": "benchmark_peers",
        "date": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()),
        "commit": git_commit(),
        "device": args.device,
        "device_name": dev_name,
        "cpu": cpu_name(),
        "cpu_cores": os.cpu_count(),
        "versions": versions(),
        "threads": {
            "tamaas": "worker processes, OMP_NUM_THREADS = 1 and = cpu_count",
            "ContactMechanics": "NumPy FFT, one thread",
            "warptrunc": (
                "Warp CPU kernels on one core, scipy.fft workers = cpu_count"
                if not dev.is_cuda
                else f"one GPU, {dev_name}"
            ),
        },
        "load": {"mean_pressure_over_E_star": P_MEAN / E_STAR, "E_star_Pa": E_STAR, "L_m": 1.0},
        "reference": args.reference,
        "tamaas_tol_given": args.tamaas_tol,
        "rule": (
            f"area (p > 0) and mean gap within {MATCH:g} (relative) of the reference; each "
            "solver loosens its tolerance by decades from a tight start while it matches, "
            "timed at the loosest matching one (cold solve)"
        ),
        "sizes": args.sizes,
        "rows": [],
    }
    budget: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for n in args.sizes:
            for surface in args.surfaces:
                h = tamaas_surface(n) if surface == "tamaas" else wm_map(n)
                for substrate in args.substrates:
                    record["rows"] += bench_problem(
                        h, surface, substrate, n, args, Path(tmp), budget
                    )
            record["peer_seconds_at_last_n"] = dict(budget)
            if args.out is not None:  # written after every N, in case a later one is stopped
                args.out.mkdir(parents=True, exist_ok=True)
                name = args.name or f"peers_{args.device.replace(':', '')}.json"
                (args.out / name).write_text(json.dumps(record, indent=1))
    print(table(record["rows"], dev_name))
    return record


if __name__ == "__main__":
    main()
