# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The paper's study as stages (Fig. 2, Fig. 5, Table 1, Figs. 7–8/Table 2, Fig. 9/10, Table 3),
and how far truncation is from elastic contact (stage ``elastic``, :mod:`warptrunc.reproduce.elastic`: Eq. 2,
island-resolved truncation and warptrunc's BEM solver), and the paper's indentation experiment in
silico (stage ``indentation``, :mod:`warptrunc.reproduce.indentation`).

Every stage is a function of the profile returning a JSON-serialisable dict; :func:`run_study`
runs them through a :class:`~warptrunc.reproduce.store.StageStore`, so a rerun reuses finished
stages. The parametric groups (Table 3, Figs. 9–10) run on :func:`warptrunc.sweep.run_sweep`
with their result stores in ``<out>/sweeps/group1`` and ``<out>/sweeps/group2``: one row per
surface × fit range, the four fractal dimensions of each group-2 surface, every curve; an
interrupted group resumes from its store, and ``warptrunc.sweep.load`` reads it.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from typing import Any

import numpy as np

from .._support.progress import progress_bar
from ..calibrate import CalibrationError, CalibrationSettings, CalibrationTarget, calibrate
from ..fractal import METHODS, fractal_dimensions
from ..islands.depths import island_curve
from ..islands.fits import applicable_depth, slit_bootstrap
from ..islands.settings import ISLANDS_TRUNCATION, IndicatorSettings, IslandSettings
from ..stiffness import DEFAULT_MIN_PIXELS, NORMALISATION_E, stiffness_curve
from ..sweep.grid import SweepGrid
from ..sweep.options import SweepOptions
from ..sweep.read import load_curves
from ..sweep.run import run_sweep
from ..sweep.store import conflict
from ..truncation.api import truncate
from ..wm import wm_surface
from .asperity import bounds_summary, pixel_area_bounds, run_asperity
from .paper import TABLE1
from .profiles import Profile
from .store import StageConflict, StageStore

__all__ = ["STAGES", "fit_ranges", "group_sweep", "run_study", "select_stages"]

UM = 1e-6
LOADS = (1e-7, 1e-6, 1e-5, 1e-4)
"""F/(E·A) at which Fig. 5 reads E_c/E."""


def _tqdm(it, desc, total=None):
    return progress_bar(it, desc=desc, total=total, unit="surface", leave=False)


def fit_ranges(profile: Profile, n: int) -> dict[str, int | float]:
    """Fit ranges: ``default`` = the package's ≥ 10 contact pixels; ``late`` = a float f, meaning
    increments with ≥ f × the surface's final contact pixels (the deep part of each curve).

    Parameters
    ----------
    profile : Profile
        Gives f (``late_fit_fraction``, dimensionless).
    n : int
        Pixels per side of the surfaces (not used by the current ranges).

    Returns
    -------
    dict of str to int or float
        ``{"default": DEFAULT_MIN_PIXELS (pixels), "late": f (dimensionless)}``.
    """

    return {"default": DEFAULT_MIN_PIXELS, "late": float(profile.late_fit_fraction)}


def _fractal(surface, device) -> dict[str, Any]:
    out = {}
    for k, f in fractal_dimensions(surface, device=device).items():
        opts = {kk: v for kk, v in f.options.items() if kk not in ("box_sizes", "lags")}
        out[k] = {"D": f.D, "r2": f.r2, "fit_range_m": list(f.fit_range), "options": opts}
    return out


# --- stages --------------------------------------------------------------------------------------


def stage_asperity(p: Profile, device) -> dict[str, Any]:
    """Fig. 2: the sphere through truncate + stiffness_curve, with the closed forms."""

    res = run_asperity(n=p.asperity_n, n_increments=p.asperity_increments, device=device)
    a, _ = res.curves["truncation"]
    lo, hi = pixel_area_bounds(res.d, res.R, res.dx)
    exact = res.curves["truncation_exact"][0]
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(exact > 0, np.abs(a - exact) / exact, 0.0)
    return {
        "curves": res.to_dict(),
        "bounds": bounds_summary(res),
        "pixel_bound_holds": bool(((a >= lo) & (a <= hi)).all()),
        "max_rel_area_error_last_half": float(rel[rel.size // 2 :].max()),
    }


def _read_at(sc, loads) -> list[float | None]:
    sel = sc.load > 0
    x, y = np.log(sc.F_over_EA[sel]), np.log(sc.Ec_over_E[sel])
    return [
        float(np.exp(np.interp(math.log(v), x, y))) if x[0] <= math.log(v) <= x[-1] else None
        for v in loads
    ]


def stage_fig5(p: Profile, device) -> dict[str, Any]:
    """Fig. 5: E_c/E at fixed F/(E·A) against resolution and against the increment count."""

    kw = {"D": 2.5, "Wr": 100e-6, "L": 1e-3, "Rt": 10e-6}
    rows = []
    cases = [
        (n, inc, s)
        for n in p.fig5_sizes
        for inc in (p.fig5_increments[0],)
        for s in range(p.fig5_seeds)
    ]
    n_last = p.fig5_sizes[-1]
    cases += [(n_last, inc, s) for inc in p.fig5_increments[1:] for s in range(p.fig5_seeds)]
    for n, inc, seed in _tqdm(cases, "Fig. 5"):
        s = wm_surface(kw["D"], kw["Wr"], L=kw["L"], n=n, Rt=kw["Rt"], seed=seed, device=device)
        sc = stiffness_curve(truncate(s, inc, max_depth_fraction=0.5, device=device))
        rows.append({"n": n, "increments": inc, "seed": seed, "Ec_over_E": _read_at(sc, LOADS)})
    return {"inputs": kw, "max_depth_fraction": 0.5, "loads": LOADS, "rows": rows}


def table1_target(
    name: str, method: str, n: int, L: float, options: dict | None = None
) -> CalibrationTarget:
    """The calibration target of one Table 1 surface and fractal method.

    Parameters
    ----------
    name : str
        The surface's name in Table 1 (a key of :data:`warptrunc.reproduce.paper.TABLE1`).
    method : str
        The fractal method whose D is matched (a key of :data:`warptrunc.fractal.METHODS`).
    n : int
        Pixels per side of the calibration surfaces.
    L : float
        Their side (m); W_r = 2·L for Ps, whose W_r is "≫ the scan" in Table 1.
    options : dict, optional
        The method's options; default none.

    Returns
    -------
    CalibrationTarget
        The paper's D of the method, R_rms and R_t (m) on n² pixels over ``L``.
    """
    Rt, rrms, wr, *d_paper = TABLE1[name]
    return CalibrationTarget(
        D=dict(zip(METHODS, d_paper, strict=True))[method],
        method=method,
        Rrms=rrms * UM,
        Rt=Rt * UM,
        Wr=2 * L if wr is None else wr * UM,
        L=L,
        n=n,
        source=f"Table 1 {name}",
        method_options=options or {},
    )


def calibration_fields(cal: Any) -> dict[str, Any]:
    """The row fields of a calibration result: D_in, R_t' and R_rms (m) reached, evaluations.

    Parameters
    ----------
    cal : Calibration
        The result of :func:`warptrunc.calibrate.calibrate`.

    Returns
    -------
    dict
        ``D_in``, ``Rt_m``, ``Rrms_m``, ``iterations``.
    """
    return {"D_in": cal.D_in, "Rt_m": cal.Rt, "Rrms_m": cal.Rrms, "iterations": cal.iterations}


def table1_targets(methods, n: int, L: float, method_options: dict | None = None):
    """The calibration targets of Table 1's simulated surfaces, one per surface and method.

    Parameters
    ----------
    methods : sequence of str
        Fractal methods whose D is matched (keys of :data:`warptrunc.fractal.METHODS`).
    n : int
        Pixels per side of the calibration surfaces.
    L : float
        Their side (m).
    method_options : dict, optional
        Options of each method (method → dict); default none.

    Yields
    ------
    name : str
        The surface's name in Table 1.
    paper_d : dict of str to float
        The paper's D by method (dimensionless).
    target : CalibrationTarget
        :func:`table1_target` of the surface and method.
    """
    for name, (_, _, _, *d_paper) in TABLE1.items():
        paper_d = dict(zip(METHODS, d_paper, strict=True))
        for m in methods:
            yield name, paper_d, table1_target(name, m, n, L, (method_options or {}).get(m))


def stage_table1(p: Profile, device) -> dict[str, Any]:
    """Table 1: calibrate D_in and R_t' of each simulated surface; D_out by the four methods."""

    L = p.table1_n * UM
    seeds = tuple(range(p.table1_seeds))
    rows = []
    for name, _, target in table1_targets(p.table1_methods, p.table1_n, L):
        row: dict[str, Any] = {"surface": name, "matched": target.method, "Wr_m": target.Wr}
        try:
            settings = CalibrationSettings(seeds=seeds, rtol=p.table1_rtol)
            cal = calibrate(target, settings=settings, progress=True, device=device)
        except (CalibrationError, ValueError) as exc:
            row.update(status="not reached", message=str(exc))
            rows.append(row)
            continue
        ds = [
            _fractal(
                wm_surface(
                    cal.D_in, target.Wr, L=L, n=p.table1_n, Rt=cal.Rt, seed=s, device=device
                ),
                device,
            )
            for s in seeds
        ]
        row.update(
            status="ok",
            **calibration_fields(cal),
            D_out={k: float(np.mean([d[k]["D"] for d in ds])) for k in METHODS},
            D_options={k: ds[0][k]["options"] for k in METHODS},
        )
        rows.append(row)
    return {"n": p.table1_n, "L_m": L, "seeds": list(seeds), "rows": rows}


def stage_islands(p: Profile, table1: dict[str, Any], device) -> dict[str, Any]:
    """Fig. 7 panel, Fig. 8 and Table 2 on the calibrated surfaces (first matched method)."""

    out: dict[str, Any] = {"n": p.islands_n, "L_m": p.islands_L, "surfaces": {}}
    done = set()
    for r in table1["rows"]:
        if r["status"] != "ok" or r["surface"] in done:
            continue
        done.add(r["surface"])
        per = []
        for seed in _tqdm(range(p.islands_seeds), f"islands {r['surface']}"):
            s = wm_surface(
                r["D_in"],
                r["Wr_m"],
                L=p.islands_L,
                n=p.islands_n,
                Rt=r["Rt_m"],
                seed=seed,
                device=device,
            )
            snaps = tuple(np.asarray(SLIT_BAND["percent_Rt"]) / 100)
            depths = ISLANDS_TRUNCATION.replace(increments=p.islands_increments)
            c = island_curve(
                s, truncation=depths, settings=IslandSettings(snapshots=snaps), device=device
            )
            min_islands = 5 if p.islands_n < 512 else 50
            ind = applicable_depth(c, IndicatorSettings(min_islands=min_islands))
            per.append(
                {
                    "seed": seed,
                    "indicators": ind.to_dict(),
                    "depth_fraction": c.depth_fraction,
                    "normalised": c.normalised_island_number,
                    "slit_exponent": c.slit_exponent,
                    "slit_band": slit_band(c, min_islands),
                }
            )
        out["surfaces"][r["surface"]] = {
            "D_in": r["D_in"],
            "Rt_m": r["Rt_m"],
            "Wr_m": r["Wr_m"],
            "seeds": per,
        }
    return out


SLIT_BAND = {
    "percent_Rt": tuple(2.5 * k for k in range(1, 21)),
    "resamples": 200,
    "level": 0.95,
    "seed": 0,
}
"""Depths (% R_t) and bootstrap of the slit-exponent band of the island stage."""


def slit_band(curve, min_islands: int) -> dict[str, list]:
    """Slit exponent with its bootstrap band over islands at the snapshot depths of ``curve``.

    Parameters
    ----------
    curve : IslandCurve
        Island curve with ``sizes`` at the depths of :data:`SLIT_BAND`.
    min_islands : int
        Fewest fitted islands for an exponent (count), as in ``applicable_depth``.

    Returns
    -------
    dict of str to list
        ``percent_Rt`` (depth, % R_t), ``exponent``, ``lo``, ``hi`` (dimensionless; None where
        fewer than ``min_islands`` islands) and ``n_islands`` (islands fitted).
    """
    out: dict[str, list] = {"percent_Rt": [], "exponent": [], "lo": [], "hi": [], "n_islands": []}
    for sz in curve.sizes:
        e, lo, hi = slit_bootstrap(
            sz,
            resamples=SLIT_BAND["resamples"],
            level=SLIT_BAND["level"],
            min_pixels=curve.min_pixels,
            min_islands=min_islands,
            seed=SLIT_BAND["seed"],
        )
        out["percent_Rt"].append(100 * sz.depth / curve.Rt)
        for k, v in (("exponent", e), ("lo", lo), ("hi", hi)):
            out[k].append(v if math.isfinite(v) else None)
        out["n_islands"].append(int((np.asarray(sz.area_pixels) >= curve.min_pixels).sum()))
    return out


def group_sweep(p: Profile, which: int) -> tuple[SweepGrid, SweepOptions]:
    """The :class:`~warptrunc.sweep.SweepGrid` and :class:`~warptrunc.sweep.SweepOptions` of
    Table 3 group 1 (D_in = 2.5, δ sweep) or group 2 (δ = 0.01, D_in sweep).

    Parameters
    ----------
    p : Profile
        Sizes of the run.
    which : int
        1 or 2 (any value other than 1 gives group 2).

    Returns
    -------
    grid : SweepGrid
        D_in × δ × seeds of the group.
    options : SweepOptions
        Options of :func:`~warptrunc.sweep.run_sweep` (lengths in m): size, W_r, increments,
        both fit ranges and the fractal methods (all four for group 2).
    """

    ranges = fit_ranges(p, p.n)
    seeds = tuple(range(p.seeds))
    if which == 1:
        grid = SweepGrid(D=(2.5,), delta=tuple(p.group1_delta), seeds=seeds)
        fractal = p.fractal_on_group1
    else:
        grid = SweepGrid(D=tuple(p.group2_D), delta=(0.01,), seeds=seeds)
        fractal = True
    opts = SweepOptions(
        n=p.n,
        L=p.L,
        Wr=p.Wr,
        increments=p.truncation.increments,
        max_depth_fraction=p.truncation.max_depth_fraction,
        max_depth=p.truncation.max_depth,
        beta_prime=p.truncation.beta_prime,
        min_pixels=(ranges["default"],),
        min_pixels_fraction=(ranges["late"],),
        fractal_methods=METHODS if fractal else None,
    )
    return grid, opts


def _row(case_rows, curve, ranges: dict[str, int | float], curve_points: int) -> dict[str, Any]:
    """A stage row (as the report reads it) from a case's store rows and curve."""
    first = case_rows[0]
    row: dict[str, Any] = {
        "D_in": first["D_in"],
        "delta": first["delta"],
        "seed": first["seed"],
        "Rt_m": first["Rt_measured_m"],
        "case_id": first["case_id"],
        "fits": {},
    }
    for name, mp in ranges.items():
        if isinstance(mp, int):  # an absolute fit range
            r = next(
                x for x in case_rows if x["min_pixels_fraction"] is None and x["min_pixels"] == mp
            )
        else:  # relative to the surface's final contact pixels
            r = next(x for x in case_rows if x["min_pixels_fraction"] == mp)
        fitted = r["alpha"] is not None and math.isfinite(float(r["alpha"]))
        if r["fit_error"] is None or fitted:  # a fit, worth reading or not
            row["fits"][name] = {
                "alpha": r["alpha"],
                "beta": r["beta"],
                "r2": r["r2"],
                "n_points": r["n_points"],
                "min_pixels": r["min_pixels"],
            }
            if r["fit_error"] is not None:
                row["fits"][name]["warning"] = r["fit_error"]
        else:  # too few increments: recorded, not dropped
            row["fits"][name] = {
                "alpha": None,
                "beta": None,
                "error": r["fit_error"],
                "min_pixels": r["min_pixels"],
            }
    if first["fractal_options"] is not None:
        info = json.loads(first["fractal_options"])
        row["D"] = {
            m: {
                "D": first[f"D_{m}"],
                "r2": first[f"D_{m}_r2"],
                "fit_range_m": [v["fit_min_m"], v["fit_max_m"]],
                "options": {
                    k: o for k, o in v["options"].items() if k not in ("box_sizes", "lags")
                },
            }
            for m, v in info.items()
        }
    k = np.unique(np.linspace(0, len(curve) - 1, curve_points).astype(int))
    row["curve"] = {
        "F_over_EA": curve["F_over_EA"].to_numpy()[k],
        "Ec_over_E": curve["Ec_over_E"].to_numpy()[k],
    }
    return row


def stage_group(
    p: Profile, which: int, out, device, *, overwrite: bool = False, curve_points: int = 60
) -> dict[str, Any]:
    """Table 3 group 1 or 2 through the sweep store ``<out>/sweeps/group<which>`` (resumed)."""

    grid, opts = group_sweep(p, which)
    path = Path(out) / "sweeps" / f"group{which}"
    why = conflict(path, grid, opts)
    if why is not None and not overwrite:
        raise StageConflict(f"{why} (group {which} of warptrunc reproduce)")
    df = run_sweep(
        grid, path, options=opts, overwrite=why is not None, progress=True, device=device
    )
    ranges = fit_ranges(p, p.n)
    rows, failed = [], []
    curves = dict(
        tuple(load_curves(path).groupby("case_id", sort=False))
    )  # one pass over the parts
    for cid, part in df.groupby("case_id", sort=False):
        recs = [
            {k: (None if _isna(v) else v) for k, v in r.items()} for r in part.to_dict("records")
        ]
        if recs[0]["error"] is not None:
            failed.append({k: recs[0][k] for k in ("case_id", "D_in", "delta", "seed", "error")})
            continue
        rows.append(_row(recs, curves[cid].reset_index(drop=True), ranges, curve_points))
    return {
        "fit_ranges": ranges,
        "rows": rows,
        "failed": failed,
        "store": str(Path("sweeps") / f"group{which}"),
    }


def _isna(v) -> bool:
    import pandas as pd

    return v is None or (not isinstance(v, (list, dict, str)) and bool(pd.isna(v)))


STAGES = ("asperity", "fig5", "table1", "islands", "group1", "group2", "elastic", "indentation")
DEPENDS = {"islands": ("table1",)}
"""Stages whose input is another stage's result: selecting one selects the other too."""


def select_stages(stages: Any = None) -> tuple[str, ...]:
    """The stages to compute, in :data:`STAGES` order, with their dependencies.

    Parameters
    ----------
    stages : str, sequence of str or None
        Stage names (a comma-separated string is split); None: every stage.

    Returns
    -------
    tuple of str
        The selected stages and those they depend on (``DEPENDS``: the islands stage needs table1).

    Raises
    ------
    ValueError
        A name that is not a stage; the message lists the allowed names.
    """
    if stages is None:
        return STAGES
    if isinstance(stages, str):
        stages = [x.strip() for x in stages.split(",") if x.strip()]
    names = set(stages)
    bad = sorted(names - set(STAGES))
    if bad or not names:
        raise ValueError(f"stages must be names among {', '.join(STAGES)}, got {list(stages)!r}")
    for n in list(names):
        names |= set(DEPENDS.get(n, ()))
    return tuple(n for n in STAGES if n in names)


def _stage_call(
    name: str,
    profile: Profile,
    res: dict[str, Any],
    store: StageStore,
    device,
    deadline: float | None,
    client=None,
    task_device=None,
):
    """(parameters, function) of a stage; None when an input stage is missing."""
    t = profile.truncation
    full = {
        **profile.to_dict(),
        "increments": t.increments,
        "max_depth_fraction": t.max_depth_fraction,
    }  # the groups' stored keys
    group = ("n", "seeds", "L", "Wr", "increments", "max_depth_fraction")  # both groups' surfaces
    keys = {
        "asperity": ("asperity_n", "asperity_increments"),
        "fig5": ("fig5_sizes", "fig5_seeds", "fig5_increments"),
        "table1": ("table1_n", "table1_seeds", "table1_methods", "table1_rtol"),
        "islands": ("islands_n", "islands_L", "islands_seeds", "islands_increments"),
        "group1": (*group, "group1_delta", "fractal_on_group1", "late_fit_fraction"),
        "group2": (*group, "group2_D", "late_fit_fraction"),
    }
    base = {k: full[k] for k in keys.get(name, ())}
    if name in ("fig5", "group1", "group2"):  # stages written before hold E_c/E* (changelog)
        base["normalisation"] = NORMALISATION_E
    if name == "elastic":
        from .elastic import stage_elastic, stage_params

        return stage_params(profile), lambda: stage_elastic(
            profile, store.out, device if client is None else task_device, client=client
        )
    if name == "indentation":
        from .indentation.stage import stage_indentation
        from .indentation.stage import stage_params as indent_params

        return indent_params(profile.indentation), lambda: stage_indentation(
            profile.indentation,
            store.out,
            device if client is None else task_device,
            overwrite=store.overwrite,
            deadline=deadline,
            client=client,
        )
    if name == "islands":
        if "table1" not in res:
            return None
        return (
            {**base, "table1": res["table1"], "slit_band": SLIT_BAND},
            lambda: stage_islands(profile, res["table1"], device),
        )
    if name.startswith("group"):
        return base, lambda w=int(name[-1]): stage_group(
            profile, w, store.out, device, overwrite=store.overwrite
        )
    return base, {
        "asperity": lambda: stage_asperity(profile, device),
        "fig5": lambda: stage_fig5(profile, device),
        "table1": lambda: stage_table1(profile, device),
    }[name]


def run_study(
    profile: Profile,
    store: StageStore,
    *,
    device=None,
    stages: Any = None,
    deadline: float | None = None,
    client=None,
    task_device=None,
) -> dict[str, Any]:
    """Run (or reuse) the stages; returns {stage: result} and the wall time per stage.

    Parameters
    ----------
    profile : Profile
        Sizes of the run.
    store : StageStore
        Stage store in the output folder: a stage stored with the same parameters is reused.
    device : str, optional
        Warp device.
    stages : str, sequence of str or None
        Stages to compute (:func:`select_stages`); None: every stage. A stage not selected is
        read from the store when it is stored with the same parameters, else left out.
    deadline : float, optional
        ``time.perf_counter()`` value after which the ``indentation`` stage starts no new
        piece (it is then reported in ``incomplete``, not stored).
    client : distributed.Client, optional
        Dask client on which the ``indentation`` stage runs its parts and the ``elastic`` stage
        its maps; None: in this process.
    task_device : str, optional
        Warp device of those parts (None: each worker's pinned GPU).

    Returns
    -------
    dict of str to dict
        ``{"results": {stage: result}, "wall_s": {stage: seconds}, "skipped": [...],
        "incomplete": {stage: message}}`` in the order of :data:`STAGES`.

    Raises
    ------
    StageConflict
        If a selected stage is stored with other parameters and the store does not overwrite.
    ValueError
        ``stages`` names no stage.
    """
    from .indentation.stage import StageIncomplete

    selected = select_stages(stages)
    res: dict[str, Any] = {}
    wall: dict[str, float] = {}
    skipped: list[str] = []
    incomplete: dict[str, str] = {}
    bar = progress_bar(STAGES, desc="reproduce", unit="stage")
    for name in bar:
        bar.set_postfix_str(name)
        t0 = time.perf_counter()
        call = _stage_call(name, profile, res, store, device, deadline, client, task_device)
        if call is None:
            skipped.append(name)
            continue
        params, fn = call
        if name not in selected:
            if store.matches(name, params):
                res[name] = store.run(name, params, fn)  # reused, never computed
                wall[name] = time.perf_counter() - t0
            else:
                skipped.append(name)
            continue
        try:
            res[name] = store.run(name, params, fn)
        except StageIncomplete as exc:
            incomplete[name] = str(exc)
            continue
        wall[name] = time.perf_counter() - t0
    return {"results": res, "wall_s": wall, "skipped": skipped, "incomplete": incomplete}
