# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The comparison study: WM cases (:func:`study_cases`), the resumable Parquet store
(:func:`compare_study`, :func:`load_comparison`) and its tables (:func:`summarize`); see
:mod:`warptrunc.compare`."""

from __future__ import annotations

import io
import json
import math
import time
from dataclasses import asdict
from pathlib import Path
from typing import Any

import numpy as np
import warp as wp

from .._support.docs import SHARED_DOCS, fill_doc
from .._support.outputs import read_json, store_rollback, strict_json, write_atomic
from .._support.provenance import provenance
from ..contact.settings import ELASTIC_TRUNCATION, SolverSettings
from ..stiffness import Material
from ..theory.columns import THEORY_COLUMNS
from ..truncation.settings import TruncationSettings
from .design import MapStudy, StudyDesign
from .models import LOW_FRACTION, ROUTES, ModelComparison, _k_vs_F, compare_models

__all__ = ["CASE_COLUMNS", "FORMAT", "compare_study", "load_comparison", "study_cases", "summarize"]

FORMAT = "warptrunc-compare/1"
"""Format tag of ``study.json``."""


CASE_COLUMNS = (
    "case_id",
    "source",
    "D_in",
    "seed",
    "size_ratio",
    "Wr_m",
    "L_m",
    "n",
    "dx_m",
    "Rt_m",
    "Wc_m",
    "M",
    "gamma",
    "depth_fraction_of_Rt",
    "depth_m",
    "trunc_area_m2",
    "n_islands",
    "eq2_stiffness_N_per_m",
    "eq2_load_N",
    "islands_stiffness_N_per_m",
    "islands_load_N",
    "bem_stiffness_N_per_m",
    "bem_load_N",
    "bem_area_m2",
    "bem_mean_gap_m",
    "eq2_k_ratio",
    "eq2_F_ratio",
    "islands_k_ratio",
    "islands_F_ratio",
    "area_ratio",
    "converged",
    "n_iterations",
    "solve_time_s",
    "case_seconds",
    "device",
    "slope_rms",
    "curvature_rms_per_m",
    "slope_rms_spectrum",
    *THEORY_COLUMNS,
)
"""Columns of a case file, in order; SI units in the names. ``size_ratio`` is L/W_r; the
ratios are model/BEM (``area_ratio`` = A'/A_BEM); ``case_seconds`` is the case's wall time (s);
``slope_rms`` and ``curvature_rms_per_m`` are the map's h′_rms (dimensionless) and h″_rms (1/m)
by finite differences at its pixel, ``slope_rms_spectrum`` the WM terms' h′_rms (NaN for a map
read from a file) (:func:`warptrunc.slope.slope_record`); ``bem_mean_gap_m`` the elastic mean gap
(m); then Persson's and GW's predictions at the nominal pressure F_BEM/L² of each row
(:data:`warptrunc.theory.columns.THEORY_COLUMNS`: from the WM terms' spectrum, or a file's
periodogram up to its noise floor ``spectrum_q_max_per_m``)."""


def study_cases(design: StudyDesign | None = None) -> list[dict[str, Any]]:
    """The WM cases of a study: D × (L/W_r at a fixed pixel size, plus one halved pixel size)
    × seeds.

    Parameters
    ----------
    design : StudyDesign, optional
        The surfaces (:class:`~warptrunc.compare.StudyDesign`; default ``StudyDesign()``);
        its ``fractions`` are not read here.

    Returns
    -------
    list of dict
        One dict per case: ``case_id``, ``D_in``, ``seed``, ``size_ratio``, ``n``, ``L_m``,
        ``dx_m``, ``Wr_m``, ``Wc_m``, ``Rt_m``, ``M``, ``gamma``; smallest maps first.

    Raises
    ------
    ValueError
        L/W_r × pixels per W_r is not a whole number of at least 4 pixels.
    """
    g = StudyDesign() if design is None else design
    ppw, Wr = g.pixels_per_Wr, g.Wr
    grids = []
    for r in g.size_ratios:
        grids.append((r, _pixels(r * ppw)))
    if g.refine_ratio is not None:
        grids.append((float(g.refine_ratio), _pixels(2 * g.refine_ratio * ppw)))
    grids = sorted(set(grids), key=lambda x: (x[1], x[0]))
    cases = []
    for r, n in grids:
        for Dv in g.D:
            for s in g.seeds:
                L = r * Wr
                cases.append(
                    {
                        "case_id": f"D{Dv:g}_L{r:g}Wr_n{n}_s{s}",
                        "source": "wm",
                        "D_in": Dv,
                        "seed": s,
                        "size_ratio": r,
                        "n": n,
                        "L_m": L,
                        "dx_m": L / n,
                        "Wr_m": Wr,
                        "Wc_m": 2 * Wr / ppw,
                        "Rt_m": g.Rt_over_Wr * Wr,
                        "M": g.M,
                        "gamma": g.gamma,
                    }
                )
    return cases


def _pixels(v: float) -> int:
    n = round(v)
    if abs(n - v) > 1e-9 * max(1.0, v) or n < 4:
        raise ValueError(f"L/W_r × pixels per W_r must be a whole number ≥ 4 of pixels, got {v!r}")
    return int(n)


def _settings(
    fractions: Any, material: Material, truncation: TruncationSettings, settings: SolverSettings
) -> dict[str, Any]:
    """The record of ``study.json``: what makes two stores of the same study (the adhesion
    law only when there is one, so that the stores of non-adhesive studies stay as they
    were)."""
    law = settings.adhesion
    return {
        **({"adhesion": law.to_dict()} if law.active else {}),
        "fractions": [float(f) for f in fractions],
        "material": asdict(material),
        "E_star_Pa": material.contact_modulus,
        "beta_prime": float(truncation.beta_prime),
        "increments": int(truncation.increments),
        "connectivity": int(truncation.connectivity),
        "dtype": settings.dtype,
        "pressure_tol": float(settings.pressure_tol),
        "pentol_m": settings.pentol,
        "maxiter": int(settings.maxiter),
        "substrate": settings.substrate,
        "stiffness_method": "barber",
    }


@fill_doc(SHARED_DOCS)
def compare_study(
    out: str | Path,
    study: StudyDesign | MapStudy | None = None,
    *,
    material: Material | None = None,
    truncation: TruncationSettings | None = None,
    settings: SolverSettings | None = None,
    overwrite: bool = False,
    progress: bool = True,
    device: wp.DeviceLike = None,
    client=None,
    devices: Any = None,
):
    """Run (or resume) a study of the three routes and store one Parquet file per case.

    Parameters
    ----------
    out : str or Path
        Store folder (``study.json``, ``cases/*.parquet``); created if needed.
    study : StudyDesign or MapStudy, optional
        The WM cases of a :class:`~warptrunc.compare.StudyDesign` (:func:`study_cases`) at
        its fractions, or your own map at its fractions (:class:`~warptrunc.compare.MapStudy`,
        stored as the single case ``input``); default ``StudyDesign()``.
    material, truncation, settings
        As in :func:`compare_models`; recorded in ``study.json`` with the fractions. A store
        made with other values is refused unless ``overwrite``.
    overwrite : bool
        Replace a store made with other settings (its case files are deleted).
    progress : bool
        Report the cases on stderr (a bar on a terminal, else lines).
    {warp_device}
    client : distributed.Client, optional
        Run the cases as tasks of this Dask cluster (one per case, the largest maps first),
        each written by its worker into ``out`` (a filesystem the workers share); ``device``
        is then the tasks' device (None: each worker's pinned GPU). Default: in this process.
    devices : int, "auto" or list, optional
        Spread each elastic solve over several devices (``contact_solver(..., devices=...)``;
        JAX); default None: ``device`` alone. Not with ``client`` (ValueError).

    Returns
    -------
    pandas.DataFrame
        The stored rows of ``cases`` (:func:`load_comparison`, other cases in the store left
        out).

    Raises
    ------
    ValueError
        If the store was made with other settings and ``overwrite`` is off.

    Notes
    -----
    A case counts as done once its file exists; each file is written to a temporary name and
    renamed (atomic), so an interrupted study resumes where it stopped.
    """
    out = Path(out)
    if client is not None and devices not in (None, 1):
        raise ValueError(
            f"devices={devices!r} with a Dask client (a worker spreading its solves "
            "over several devices) is not supported yet; run in this process"
        )
    study = StudyDesign() if study is None else study
    material = Material() if material is None else material
    truncation = ELASTIC_TRUNCATION if truncation is None else truncation
    settings = SolverSettings() if settings is None else settings
    fractions = [float(f) for f in study.fractions]
    record = _settings(fractions, material, truncation, settings)
    surface = None
    if isinstance(study, MapStudy):
        surface = study.surface
        p = dict(surface.params)
        cases = [
            {
                "case_id": "input",
                "source": str(p.get("source", "input")),
                "D_in": float(p["D"]) if "D" in p else math.nan,
                "seed": int(p.get("seed", -1)),
                "size_ratio": (surface.lx / p["Wr"]) if "Wr" in p else math.nan,
                "n": surface.nx,
                "L_m": surface.lx,
                "dx_m": surface.dx,
                "Wr_m": float(p.get("Wr", math.nan)),
                "Rt_m": surface.Rt,
                "Wc_m": float(p.get("Wc") or math.nan),
                "M": int(p.get("M", -1)),
                "gamma": float(p.get("gamma", math.nan)),
            }
        ]
    else:
        cases = study_cases(study)
    ids = [c["case_id"] for c in cases]
    if len(set(ids)) != len(ids):
        raise ValueError(f"case_id values must be unique (a D given twice?), got {ids}")
    with store_rollback(out, keep=lambda: any((out / "cases").glob("*.parquet"))):
        _open_store(out, record, overwrite)
        job = (surface, fractions, material, truncation, settings)
        _run_cases(out, cases, job, progress, device, client, devices)
    rows = load_comparison(out)
    return rows[rows["case_id"].isin(ids)].reset_index(drop=True)


def _run_cases(out, cases, job, progress, device, client=None, devices=None) -> None:
    """Compute and store the cases that ``out`` does not hold yet (in this process, or one
    task per case on the Dask ``client``, each written by its worker); ``job`` is
    :func:`_one_case`'s (surface, fractions, material, truncation, settings)."""
    from .._support.progress import progress_bar

    todo = [c for c in cases if not _case_path(out, c["case_id"]).exists()]
    if client is None:
        for c in progress_bar(todo, desc="compare", unit="case", enabled=progress):
            _one_case(str(out), c, job, device, devices)
        return
    from distributed import as_completed

    # the largest maps first, so that the last task is a small one
    todo.sort(key=lambda c: -(int(c["n"]) ** 2))
    futs = {
        client.submit(
            _one_case,
            str(Path(out).resolve()),
            c,
            job,
            device,
            pure=False,
            key=f"compare-{c['case_id']}",
        ): c
        for c in todo
    }
    with progress_bar(total=len(todo), desc="compare", unit="case", enabled=progress) as bar:
        for fut in as_completed(futs):
            c = futs[fut]
            try:
                fut.result()
            except Exception:  # a lost worker: its case once more here, unless its file landed
                if not _case_path(out, c["case_id"]).exists():
                    _one_case(str(out), c, job, device)
            bar.update()


def _one_case(out: str, c: dict[str, Any], job: tuple, device: Any, devices: Any = None) -> str:
    """Compute one case and write its file (atomically); returns its case id."""
    from ..slope import slope_record
    from ..wm import wm_surface

    surface, fractions, material, truncation, settings = job
    t0 = time.perf_counter()
    if surface is not None:
        s = surface
    else:
        s = wm_surface(
            c["D_in"],
            c["Wr_m"],
            L=c["L_m"],
            n=c["n"],
            Rt=c["Rt_m"],
            M=c["M"],
            gamma=c["gamma"],
            Wc=c["Wc_m"],
            seed=c["seed"],
            device=device,
        )
    rec = slope_record(s, limit=settings.slope_limit)  # before the solves release the map
    r = compare_models(
        s,
        fractions,
        material=material,
        truncation=truncation,
        settings=settings,
        device=device,
        devices=devices,
    )
    theory = _theory_columns(s, r, material)
    spectrum = rec["spectrum"]["slope_rms"] if rec["spectrum"] else float("nan")
    c = {
        **c,
        "Rt_m": r.Rt,
        "slope_rms": rec["slope_rms"],
        "curvature_rms_per_m": rec["curvature_rms_per_m"],
        "slope_rms_spectrum": spectrum,
    }
    _write_case(Path(out), c, r, time.perf_counter() - t0, theory)
    return c["case_id"]


def _theory_columns(s: Any, r: ModelComparison, material: Material) -> dict[str, Any]:
    """Persson's and GW's columns at the rows' nominal pressures (NaN when the map has no
    spectrum to read)."""
    from ..theory.columns import surface_spectrum, theory_columns

    a0 = s.lx * s.ly
    try:
        psd = surface_spectrum(s)
    except ValueError:
        m = r.depth.size
        return {k: np.full(m, "" if k == "spectrum_source" else np.nan) for k in THEORY_COLUMNS}
    return theory_columns(psd, r.bem_load, a0, material=material, area=r.bem_area)


def _case_path(out: Path, case_id: str) -> Path:
    return out / "cases" / f"{case_id}.parquet"


def _open_store(out: Path, settings: dict[str, Any], overwrite: bool) -> None:
    meta = out / "study.json"
    doc = {"format": FORMAT, "settings": settings}
    if meta.exists():
        old = read_json(meta)
        same = json.loads(strict_json(doc)) == json.loads(
            strict_json({"format": old.get("format"), "settings": old.get("settings")})
        )
        if same:
            return
        if not overwrite:
            diff = sorted(k for k in settings if old.get("settings", {}).get(k) != settings[k])
            raise ValueError(
                f"{out} holds a comparison study made with other settings (differing: "
                f"{', '.join(diff) or 'format'}); use another folder, or overwrite"
            )
        for f in (out / "cases").glob("*.parquet"):
            f.unlink()
    doc["provenance"] = provenance()
    write_atomic(meta, strict_json(doc))


def _write_case(
    out: Path,
    case: dict[str, Any],
    r: ModelComparison,
    seconds: float,
    theory: dict[str, Any] | None = None,
) -> None:
    import pandas as pd

    cols = {**r.to_dict(), **(theory or {})}
    m = r.depth.size
    data: dict[str, Any] = {}
    for k in CASE_COLUMNS:
        if k in cols:
            data[k] = cols[k]
        elif k == "case_seconds":
            data[k] = np.full(m, seconds)
        elif k == "device":
            data[k] = [str(r.settings["solver"].get("device", ""))] * m
        else:
            data[k] = [case[k]] * m
    df = pd.DataFrame(data, columns=list(CASE_COLUMNS))
    buf = io.BytesIO()
    df.to_parquet(buf, index=False)
    write_atomic(_case_path(out, case["case_id"]), buf.getvalue())


def load_comparison(out: str | Path):
    """Every stored row of a comparison study.

    Parameters
    ----------
    out : str or Path
        The study's store folder.

    Returns
    -------
    pandas.DataFrame
        One row per (case, approach), columns :data:`CASE_COLUMNS`, sorted by case and d/R_t.

    Raises
    ------
    FileNotFoundError
        If ``out`` holds no ``study.json``.
    """
    import pandas as pd

    out = Path(out)
    if not (out / "study.json").exists():
        raise FileNotFoundError(f"no comparison study in {out} (study.json missing)")
    files = sorted((out / "cases").glob("*.parquet"))
    if not files:
        return pd.DataFrame(columns=list(CASE_COLUMNS))
    df = pd.concat([pd.read_parquet(f) for f in files], ignore_index=True)
    return df.sort_values(
        ["n", "size_ratio", "D_in", "seed", "depth_fraction_of_Rt"], kind="stable"
    ).reset_index(drop=True)


def _stats(v) -> dict[str, float]:
    x = np.asarray(v, dtype=np.float64)
    x = x[np.isfinite(x)]
    if x.size == 0:
        return {"mean": math.nan, "min": math.nan, "max": math.nan, "n": 0}
    return {"mean": float(x.mean()), "min": float(x.min()), "max": float(x.max()), "n": int(x.size)}


def summarize(rows) -> dict[str, Any]:
    """The study's tables, recomputed from its rows.

    Parameters
    ----------
    rows : pandas.DataFrame
        Rows of :func:`load_comparison`.

    Returns
    -------
    dict
        ``ratios``: DataFrame, one row per (D_in, size_ratio, n, d/R_t) with mean, min and max
        over seeds of k/k_BEM and F/F_BEM for ``eq2`` and ``islands`` and of A'/A_BEM, and the
        number of converged seeds. ``alpha``: DataFrame, one row per (D_in, size_ratio, n, range)
        with mean, min and max over seeds of α by the three routes; range ``all`` fits every
        approach, ``low`` those with d/R_t ≤ :data:`LOW_FRACTION`.
    """
    import pandas as pd

    keys = ["D_in", "size_ratio", "n"]
    out_r = []
    for (Dv, r, n, f), g in rows.groupby([*keys, "depth_fraction_of_Rt"], sort=True, dropna=False):
        rec: dict[str, Any] = {
            "D_in": Dv,
            "size_ratio": r,
            "n": n,
            "depth_fraction_of_Rt": f,
            "seeds": int(g["seed"].nunique()),
            "converged": int(g["converged"].sum()),
        }
        for col in (
            "eq2_k_ratio",
            "islands_k_ratio",
            "eq2_F_ratio",
            "islands_F_ratio",
            "area_ratio",
        ):
            s = _stats(g[col])
            for k in ("mean", "min", "max"):
                rec[f"{col}_{k}"] = s[k]
        out_r.append(rec)
    out_a = []
    for (Dv, r, n), g in rows.groupby(keys, sort=True, dropna=False):
        for rng, lim in (("all", None), ("low", LOW_FRACTION)):
            fits: dict[str, list[float]] = {m: [] for m in ROUTES}
            for _, c in g.groupby("case_id", sort=True):
                c = c[c["depth_fraction_of_Rt"] <= lim * (1 + 1e-9)] if lim else c
                for m in ROUTES:
                    fits[m].append(_k_vs_F(c[f"{m}_load_N"], c[f"{m}_stiffness_N_per_m"])["alpha"])
            rec = {
                "D_in": Dv,
                "size_ratio": r,
                "n": n,
                "range": rng,
                "seeds": int(g["seed"].nunique()),
            }
            for m in ROUTES:
                s = _stats(fits[m])
                for k in ("mean", "min", "max"):
                    rec[f"alpha_{m}_{k}"] = s[k]
            out_a.append(rec)
    return {"ratios": pd.DataFrame(out_r), "alpha": pd.DataFrame(out_a)}
