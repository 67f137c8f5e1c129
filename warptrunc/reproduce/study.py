# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The paper's study as stages (Fig. 2, Fig. 5, Table 1, Figs. 7–8/Table 2, Fig. 9/10, Table 3).

Every stage is a function of the profile returning a JSON-serialisable dict; :func:`run_study`
runs them through a :class:`~warptrunc.reproduce.store.StageStore`, so a rerun reuses finished
stages. :func:`run_case` is the per-surface unit of the parametric groups (one WM surface →
stiffness fits for each fit range, and optionally its four fractal dimensions); it is small on
purpose so that a sweep result store can replace it.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from .profiles import Profile
from .store import StageStore

__all__ = ["STAGES", "fit_ranges", "run_case", "run_study"]

UM = 1e-6
LOADS = (1e-7, 1e-6, 1e-5, 1e-4)
"""F/(E·A) at which Fig. 5 reads E_c/E."""


def _tqdm(it, desc, total=None):
    from tqdm.auto import tqdm

    return tqdm(it, desc=desc, total=total, unit="surface", leave=False)


def fit_ranges(profile: Profile, n: int) -> dict[str, int | float]:
    """Fit ranges: ``default`` = the package's ≥ 10 contact pixels; ``late`` = a float f, meaning
    increments with ≥ f × the surface's final contact pixels (the deep part of each curve)."""
    from ..stiffness import DEFAULT_MIN_PIXELS

    return {"default": DEFAULT_MIN_PIXELS, "late": float(profile.late_fit_fraction)}


def _fractal(surface, device) -> dict[str, Any]:
    from ..fractal import fractal_dimensions

    out = {}
    for k, f in fractal_dimensions(surface, device=device).items():
        opts = {kk: v for kk, v in f.options.items() if kk not in ("box_sizes", "lags")}
        out[k] = {"D": f.D, "r2": f.r2, "fit_range_m": list(f.fit_range), "options": opts}
    return out


def run_case(
    D: float, delta: float, seed: int, *, n: int, L: float, Wr: float, increments: int,
    max_depth_fraction: float, min_pixels: dict[str, int | float], fractal: bool, curve_points: int = 0,
    device=None,
) -> dict[str, Any]:  # fmt: skip
    """One WM surface (D_in = D, R_t = δ·W_r): power-law fits per fit range, optionally D."""
    from ..stiffness import DEFAULT_MIN_PIXELS, fit_power_law, stiffness_curve
    from ..truncation import truncate
    from ..wm import wm_surface

    s = wm_surface(D, Wr, L=L, n=n, Rt=delta * Wr, seed=seed, device=device)
    sc = stiffness_curve(truncate(s, increments, max_depth_fraction=max_depth_fraction, device=device))
    row: dict[str, Any] = {"D_in": D, "delta": delta, "seed": seed, "Rt_m": s.rt, "fits": {}}
    for name, mp in min_pixels.items():
        if isinstance(mp, float):  # a fraction of the final contact pixels
            mp = max(DEFAULT_MIN_PIXELS, math.ceil(mp * int(sc.n_contact_pixels[-1])))
        try:
            f = fit_power_law(sc, min_pixels=mp)
            row["fits"][name] = {"alpha": f.alpha, "beta": f.beta, "r2": f.r2, "n_points": f.n_points,
                                 "min_pixels": mp}  # fmt: skip
        except ValueError as exc:  # too few increments: recorded, not dropped
            row["fits"][name] = {"alpha": None, "beta": None, "error": str(exc), "min_pixels": mp}
    if fractal:
        row["D"] = _fractal(s, device)
    if curve_points:
        k = np.unique(np.linspace(0, sc.depth.size - 1, curve_points).astype(int))
        row["curve"] = {"F_over_EA": sc.F_over_EA[k], "Ec_over_E": sc.Ec_over_E[k]}
    return row


# --- stages --------------------------------------------------------------------------------------


def stage_asperity(p: Profile, device) -> dict[str, Any]:
    """Fig. 2: the sphere through truncate + stiffness_curve, with the closed forms."""
    from .asperity import bounds_summary, pixel_area_bounds, run_asperity

    res = run_asperity(n=p.asperity_n, n_increments=p.asperity_increments, device=device)
    a, _ = res.curves["truncation"]
    lo, hi = pixel_area_bounds(res.d, res.R, res.dx)
    exact = res.curves["truncation_exact"][0]
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(exact > 0, np.abs(a - exact) / exact, 0.0)
    return {
        "curves": res.to_dict(), "bounds": bounds_summary(res),
        "pixel_bound_holds": bool(((a >= lo) & (a <= hi)).all()),
        "max_rel_area_error_last_half": float(rel[rel.size // 2 :].max()),
    }  # fmt: skip


def _read_at(sc, loads) -> list[float | None]:
    sel = sc.load > 0
    x, y = np.log(sc.F_over_EA[sel]), np.log(sc.Ec_over_E[sel])
    return [float(np.exp(np.interp(math.log(v), x, y))) if x[0] <= math.log(v) <= x[-1] else None
            for v in loads]  # fmt: skip


def stage_fig5(p: Profile, device) -> dict[str, Any]:
    """Fig. 5: E_c/E at fixed F/(E·A) against resolution and against the increment count."""
    from ..stiffness import stiffness_curve
    from ..truncation import truncate
    from ..wm import wm_surface

    kw = {"D": 2.5, "Wr": 100e-6, "L": 1e-3, "Rt": 10e-6}
    rows = []
    cases = [(n, inc, s) for n in p.fig5_sizes for inc in (p.fig5_increments[0],)
             for s in range(p.fig5_seeds)]  # fmt: skip
    n_last = p.fig5_sizes[-1]
    cases += [(n_last, inc, s) for inc in p.fig5_increments[1:] for s in range(p.fig5_seeds)]
    for n, inc, seed in _tqdm(cases, "Fig. 5"):
        s = wm_surface(kw["D"], kw["Wr"], L=kw["L"], n=n, Rt=kw["Rt"], seed=seed, device=device)
        sc = stiffness_curve(truncate(s, inc, max_depth_fraction=0.5, device=device))
        rows.append({"n": n, "increments": inc, "seed": seed, "Ec_over_E": _read_at(sc, LOADS)})
    return {"inputs": kw, "max_depth_fraction": 0.5, "loads": LOADS, "rows": rows}


def stage_table1(p: Profile, device) -> dict[str, Any]:
    """Table 1: calibrate D_in and R_t' of each simulated surface; D_out by the four methods."""
    from ..calibrate import CalibrationError, CalibrationTarget, calibrate
    from ..fractal import METHODS
    from ..wm import wm_surface
    from .paper import TABLE1

    L = p.table1_n * UM
    seeds = tuple(range(p.table1_seeds))
    rows = []
    for name, (rt, rrms, wr, *d_paper) in TABLE1.items():
        wr_m = 2 * L if wr is None else wr * UM
        paper_d = dict(zip(METHODS, d_paper, strict=True))
        for m in p.table1_methods:
            row: dict[str, Any] = {"surface": name, "matched": m, "Wr_m": wr_m}
            target = CalibrationTarget(D=paper_d[m], method=m, Rrms=rrms * UM, Rt=rt * UM,
                                       Wr=wr_m, L=L, n=p.table1_n, source=f"Table 1 {name}")  # fmt: skip
            try:
                cal = calibrate(target, seeds=seeds, rtol=p.table1_rtol, progress=True, device=device)
            except (CalibrationError, ValueError) as exc:
                row.update(status="not reached", message=str(exc))
                rows.append(row)
                continue
            ds = [_fractal(wm_surface(cal.D_in, wr_m, L=L, n=p.table1_n, Rt=cal.Rt, seed=s,
                                      device=device), device) for s in seeds]  # fmt: skip
            row.update(status="ok", D_in=cal.D_in, Rt_m=cal.Rt, Rrms_m=cal.Rrms,
                       iterations=cal.iterations,
                       D_out={k: float(np.mean([d[k]["D"] for d in ds])) for k in METHODS},
                       D_options={k: ds[0][k]["options"] for k in METHODS})  # fmt: skip
            rows.append(row)
    return {"n": p.table1_n, "L_m": L, "seeds": list(seeds), "rows": rows}


def stage_islands(p: Profile, table1: dict[str, Any], device) -> dict[str, Any]:
    """Fig. 7 panel, Fig. 8 and Table 2 on the calibrated surfaces (first matched method)."""
    from ..islands import applicable_depth, island_curve
    from ..wm import wm_surface

    out: dict[str, Any] = {"n": p.islands_n, "L_m": p.islands_L, "surfaces": {}}
    done = set()
    for r in table1["rows"]:
        if r["status"] != "ok" or r["surface"] in done:
            continue
        done.add(r["surface"])
        per = []
        for seed in _tqdm(range(p.islands_seeds), f"islands {r['surface']}"):
            s = wm_surface(r["D_in"], r["Wr_m"], L=p.islands_L, n=p.islands_n, Rt=r["Rt_m"],
                           seed=seed, device=device)  # fmt: skip
            c = island_curve(s, p.islands_increments, max_depth_fraction=0.5, device=device)
            ind = applicable_depth(c, min_islands=5 if p.islands_n < 512 else 50)
            per.append({"seed": seed, "indicators": ind.to_dict(),
                        "depth_fraction": c.depth_fraction, "normalised": c.normalised_island_number,
                        "slit_exponent": c.slit_exponent})  # fmt: skip
        out["surfaces"][r["surface"]] = {"D_in": r["D_in"], "Rt_m": r["Rt_m"], "Wr_m": r["Wr_m"],
                                         "seeds": per}  # fmt: skip
    return out


def stage_group(p: Profile, which: int, device) -> dict[str, Any]:
    """Table 3 group 1 (D_in = 2.5, δ sweep) or group 2 (δ = 0.01, D_in sweep)."""
    ranges = fit_ranges(p, p.n)
    if which == 1:
        cases = [(2.5, d) for d in p.group1_delta]
        fractal = p.fractal_on_group1
    else:
        cases = [(D, 0.01) for D in p.group2_D]
        fractal = True
    todo = [(D, d, s) for D, d in cases for s in range(p.seeds)]
    rows = [
        run_case(D, d, s, n=p.n, L=p.L, Wr=p.Wr, increments=p.increments,
                 max_depth_fraction=p.max_depth_fraction, min_pixels=ranges, fractal=fractal,
                 curve_points=60, device=device)
        for D, d, s in _tqdm(todo, f"group {which}")
    ]  # fmt: skip
    return {"fit_ranges": ranges, "rows": rows}


STAGES = ("asperity", "fig5", "table1", "islands", "group1", "group2")


def run_study(profile: Profile, store: StageStore, *, device=None) -> dict[str, Any]:
    """Run (or reuse) every stage; returns {stage: result} and the wall time per stage."""
    from tqdm.auto import tqdm

    full = profile.to_dict()
    keys = {
        "asperity": ("asperity_n", "asperity_increments"),
        "fig5": ("fig5_sizes", "fig5_seeds", "fig5_increments"),
        "table1": ("table1_n", "table1_seeds", "table1_methods", "table1_rtol"),
        "islands": ("islands_n", "islands_L", "islands_seeds", "islands_increments"),
        "group1": ("n", "seeds", "L", "Wr", "increments", "max_depth_fraction", "group1_delta",
                   "fractal_on_group1", "late_fit_fraction"),
        "group2": ("n", "seeds", "L", "Wr", "increments", "max_depth_fraction", "group2_D",
                   "late_fit_fraction"),
    }  # fmt: skip
    res: dict[str, Any] = {}
    wall: dict[str, float] = {}
    bar = tqdm(STAGES, desc="reproduce", unit="stage")
    for name in bar:
        bar.set_postfix_str(name)
        t0 = time.perf_counter()
        base = {k: full[k] for k in keys[name]}
        if name == "islands":
            params = {**base, "table1": res["table1"]}
            fn = lambda: stage_islands(profile, res["table1"], device)  # noqa: E731
        elif name.startswith("group"):
            params, fn = base, (lambda w=int(name[-1]): stage_group(profile, w, device))
        else:
            params = base
            fn = {"asperity": lambda: stage_asperity(profile, device),
                  "fig5": lambda: stage_fig5(profile, device),
                  "table1": lambda: stage_table1(profile, device)}[name]  # fmt: skip
        res[name] = store.run(name, params, fn)
        wall[name] = time.perf_counter() - t0
    return {"results": res, "wall_s": wall}
