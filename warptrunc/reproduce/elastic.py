# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stage ``bem`` of ``warptrunc reproduce``: truncation against an elastic BEM solution.

For D ∈ ``Profile.bem_D`` × ``Profile.bem_seeds`` seeds, a WM surface (L = 1 mm, W_r = 100 µm,
R_t = 10 µm, the ``analyze`` defaults) at ``Profile.bem_n``² is compared with the non-periodic
elastic boundary-element contact of :func:`warptrunc.contact.check.bem_check` at δ/R_t ∈
``Profile.bem_fractions``. The BEM runs on the CPU (ContactMechanics) whatever the device.
Needs the ``bem`` extra; without it the stage is skipped (not stored, so a rerun after installing
the extra computes it) and the report says so.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .profiles import Profile

__all__ = ["SURFACE", "analyse_bem", "bem_available", "bem_lines", "stage_bem"]

SURFACE = {"L": 1e-3, "Wr": 100e-6, "Rt": 10e-6}
"""WM surface of the cross-check (m): the ``analyze`` defaults, as the README's BEM table."""
EXTRA_HINT = 'pip install "warptrunc[bem]"'
RATIOS = ("load_ratio", "stiffness_ratio", "area_ratio")
GOOD = 0.2
"""|k'/k_BEM − 1| ≤ GOOD counts as a good stiffness estimate in the report's sentence (the ±20 %
of issue 12's measurement)."""


def bem_available() -> str | None:
    """None when the ``bem`` extra imports; else the reason (naming the install command).

    Returns
    -------
    str or None
        None when ContactMechanics and SurfaceTopography import, else the ImportError's
        message.
    """
    from ..contact.check import require_bem

    try:
        require_bem()
    except ImportError as exc:
        return str(exc)
    return None


def stage_params(p: Profile) -> dict[str, Any]:
    """The parameters that identify a stored ``bem`` stage."""
    from ..stiffness import Material

    m = Material()
    return {"bem_n": p.bem_n, "bem_seeds": p.bem_seeds, "bem_D": list(p.bem_D),
            "bem_fractions": list(p.bem_fractions), "surface": SURFACE,
            "material": {"E_Pa": m.E, "nu": m.nu, "E_star_Pa": m.reduced_modulus}}  # fmt: skip


def stage_bem(p: Profile, device) -> dict[str, Any]:
    """Run :func:`~warptrunc.contact.check.bem_check` (ContactMechanics' solver, the stage's
    reference) on every (D, seed); one case per surface.

    Each surface is a WM surface (:func:`~warptrunc.wm.wm_surface`) with the fixed ``SURFACE``
    W_r, L and R_t, ``p.bem_n`` pixels a side, D in ``p.bem_D`` and seeds
    ``0 .. p.bem_seeds − 1``, checked at the approaches ``p.bem_fractions`` of R_t.

    Parameters
    ----------
    p : Profile
        The reproduction profile (``bem_n``, ``bem_seeds``, ``bem_D``, ``bem_fractions``).
    device : str or warp.context.Device or None
        Warp device for the surfaces and the truncation part (the BEM runs on the CPU).

    Returns
    -------
    dict
        ``n``, ``surface`` (the ``SURFACE`` dict, m), ``fractions``, ``settings`` (the first
        check's settings without the per-surface entries) and ``cases``: one dict per
        (D, seed) with ``D``, ``seed``, ``Rt_m`` (m), ``summary`` (:meth:`BemCheck.summary`),
        ``pentol_m`` (m), ``columns`` (:meth:`BemCheck.to_dict`) and ``solves``.

    Raises
    ------
    ImportError
        The ``bem`` extra (ContactMechanics) is not installed.
    """
    from tqdm.auto import tqdm

    from ..contact.check import bem_check
    from ..wm import wm_surface

    cases = [(D, s) for D in p.bem_D for s in range(p.bem_seeds)]
    rows = []
    settings = None
    for D, seed in tqdm(cases, desc="BEM cross-check", unit="surface", leave=False):
        surf = wm_surface(D, SURFACE["Wr"], L=SURFACE["L"], n=p.bem_n, Rt=SURFACE["Rt"],
                          seed=seed, device=device)  # fmt: skip
        r = bem_check(surf, fractions=p.bem_fractions, solver="contactmechanics", progress=False,
                      device=device)  # fmt: skip
        if settings is None:
            settings = {
                k: v
                for k, v in r.settings.items()
                if k not in ("surface", "solves", "Rt_m", "pentol_m")
            }
        rows.append({"D": D, "seed": seed, "Rt_m": float(surf.Rt), "summary": r.summary(),
                     "pentol_m": r.settings["pentol_m"],
                     "columns": r.to_dict(),
                     "solves": [{k: s[k] for k in ("success", "n_iterations", "message")}
                                for s in r.settings["solves"]]})  # fmt: skip
    return {"n": p.bem_n, "surface": SURFACE, "fractions": list(p.bem_fractions),
            "settings": settings, "cases": rows}  # fmt: skip


def _stats(v: list[float | None]) -> dict[str, Any]:
    x = np.array([np.nan if a is None else a for a in v], dtype=float)
    ok = np.isfinite(x)
    if not ok.any():
        return {"mean": None, "min": None, "max": None, "n": 0}
    x = x[ok]
    return {"mean": float(x.mean()), "min": float(x.min()), "max": float(x.max()), "n": int(x.size)}


def analyse_bem(stage: dict[str, Any]) -> dict[str, Any]:
    """Per (D, δ/R_t): mean and range over seeds of the three ratios, convergence and edge
    counts; per D: time per solve; the cells where k' is within ±GOOD of k_BEM.

    Parameters
    ----------
    stage : dict
        The stored ``bem`` stage, as returned by :func:`stage_bem`, or
        ``{"status": "skipped", "reason": ...}``.

    Returns
    -------
    dict
        ``{"status": "skipped", "reason": ...}`` for a skipped stage. Otherwise
        ``status="ok"``, ``n``, ``fractions``, ``cells`` (per (D, fraction): ``load_ratio``,
        ``stiffness_ratio``, ``area_ratio`` as ``{mean, min, max, n}`` over the seeds with a
        finite ratio (dimensionless), ``converged``, ``n``, ``edge_contact`` counts and
        ``contact_fraction`` = mean A_BEM/L² (dimensionless)), ``per_D``
        (``time_per_solve_s`` (s), ``solves``, ``not_converged_rows``), ``good_band``,
        ``good_cells`` ([D, fraction] pairs with abs(k'/k_BEM − 1) ≤ ``GOOD``),
        ``other_stiffness_ratio_range``, ``all_converged``, ``rows``, ``solves`` and
        ``time_per_solve_s`` (s).
    """
    if stage.get("status") == "skipped":
        return {"status": "skipped", "reason": stage["reason"]}
    cells = []
    per_D = {}
    for D in sorted({c["D"] for c in stage["cases"]}):
        cs = [c for c in stage["cases"] if c["D"] == D]
        for i, f in enumerate(stage["fractions"]):
            cell: dict[str, Any] = {"D": D, "fraction": f}
            for k in RATIOS:
                cell[k] = _stats([c["columns"][k][i] for c in cs])
            cell["converged"] = sum(bool(c["columns"]["converged"][i]) for c in cs)
            cell["n"] = len(cs)
            cell["edge_contact"] = sum(bool(c["columns"]["edge_contact"][i]) for c in cs)
            cell["contact_fraction"] = float(np.mean(
                [c["columns"]["bem_area_m2"][i] for c in cs])) / stage["surface"]["L"] ** 2  # fmt: skip
            cells.append(cell)
        per_D[str(D)] = {
            "time_per_solve_s": float(np.mean([c["summary"]["time_per_solve_s"] for c in cs])),
            "solves": 3 * len(stage["fractions"]) * len(cs),
            "not_converged_rows": sum(c["summary"]["n_not_converged"] for c in cs),
        }  # fmt: skip
    k = [c["stiffness_ratio"]["mean"] for c in cells]
    good = [c for c, v in zip(cells, k, strict=True) if v is not None and abs(v - 1) <= GOOD]
    bad = [v for v in k if v is not None and abs(v - 1) > GOOD]
    n_rows = sum(len(c["columns"]["converged"]) for c in stage["cases"])
    return {"status": "ok", "n": stage["n"], "fractions": stage["fractions"], "cells": cells,
            "per_D": per_D, "good_band": GOOD,
            "good_cells": [[c["D"], c["fraction"]] for c in good],
            "other_stiffness_ratio_range": [min(bad), max(bad)] if bad else None,
            "all_converged": all(all(c["columns"]["converged"]) for c in stage["cases"]),
            "rows": n_rows, "solves": 3 * n_rows,
            "time_per_solve_s": float(np.mean([v["time_per_solve_s"] for v in per_D.values()]))}  # fmt: skip


def _r(s: dict[str, Any]) -> str:
    if s["mean"] is None:
        return "— (no BEM contact)"
    if s["n"] == 1:
        return f"{s['mean']:.2f}"
    return f"{s['mean']:.2f} ({s['min']:.2f}–{s['max']:.2f})"


def _sentence(a: dict[str, Any]) -> str:
    g = a["good_cells"]
    band = f"±{100 * a['good_band']:.0f} %"
    k_all = [
        c["stiffness_ratio"]["mean"] for c in a["cells"] if c["stiffness_ratio"]["mean"] is not None
    ]
    under = sum(v < 1 for v in k_all)
    where = ", ".join(f"D = {D:g} at δ/R_t = {f:g}" for D, f in g) if g else "no (D, δ) here"
    rng = a["other_stiffness_ratio_range"]
    rest = (f"; elsewhere the seed-mean k'/k_BEM lies between {rng[0]:.2f} and {rng[1]:.2f}"
            if rng else "")  # fmt: skip
    areas = [c["area_ratio"]["mean"] for c in a["cells"] if c["area_ratio"]["mean"] is not None]
    return (
        f"On these {a['n']}² maps the truncation stiffness k' is within {band} of the elastic "
        f"BEM stiffness (seed mean) for {where}{rest}; {under} of {len(k_all)} seed-mean ratios "
        f"are below 1 (truncation softer than the elastic solution), and the truncated area is "
        f"{min(areas):.1f}–{max(areas):.1f} × the elastic contact area."
    )  # fmt: skip


def bem_lines(stage: dict[str, Any], a: dict[str, Any], seconds: float | None) -> list[str]:
    """The report section "Elastic cross-check (BEM)" as Markdown lines.

    Parameters
    ----------
    stage : dict
        The stored ``bem`` stage (:func:`stage_bem`).
    a : dict
        Its analysis (:func:`analyse_bem`); a skipped one gives a one-line section.
    seconds : float or None
        Wall time of the stage (s), quoted when given.

    Returns
    -------
    list of str
        Markdown lines: heading, method paragraph, the per-(D, δ/R_t) ratio table, the
        per-D timing table and the summary sentences.
    """

    L = ["## Elastic cross-check (BEM)\n"]
    if a["status"] == "skipped":
        L.append(f"Skipped: the `bem` extra is not installed (`{EXTRA_HINT}`).\n")
        return L
    s, st = stage["surface"], stage["settings"]
    seeds = len({c["seed"] for c in stage["cases"]})
    L.append(
        f"Truncation (k' = (2/√π)·E*·√A', F' = ∫k' dω) against the elastic boundary-element "
        f"contact of the same map (`warptrunc.contact.check.bem_check`: ContactMechanics "
        f"{st['versions'].get('contactmechanics')}, {st['substrate']} half-space, "
        f"{st['padding'].split(':')[0]}; "
        f"k_BEM by a central difference over δ(1 ± {st['fd_step']:g}), three solves per approach). "
        f"WM surfaces at **{a['n']}²** over {s['L'] * 1e3:g} mm, W_r = {s['Wr'] * 1e6:g} µm, "
        f"R_t = {s['Rt'] * 1e6:g} µm, {seeds} seed{'s' if seeds > 1 else ''} per D; E* = {st['contact_modulus_Pa'] / 1e9:.2f} GPa. "
        f"The BEM runs on the CPU. "
        + ("Mean (min–max) over seeds:\n" if seeds > 1 else "One seed per cell:\n")
    )  # fmt: skip
    L.append("| D | δ/R_t | F'/F_BEM | k'/k_BEM | A'/A_BEM | A_BEM/A | converged | edge contact |")
    L.append("|---|---|---|---|---|---|---|---|")
    for c in a["cells"]:
        conv = f"{c['converged']}/{c['n']}" + (
            "" if c["converged"] == c["n"] else " **not converged: flagged**"
        )
        L.append(f"| {c['D']:g} | {c['fraction']:g} | {_r(c['load_ratio'])} | {_r(c['stiffness_ratio'])} | "
                 f"{_r(c['area_ratio'])} | {100 * c['contact_fraction']:.2g} % | {conv} | "
                 f"{c['edge_contact']}/{c['n']} |")  # fmt: skip
    L.append("\n| D | solves | s per solve (host CPU) | rows not converged |")
    L.append("|---|---|---|---|")
    for D, v in a["per_D"].items():
        L.append(
            f"| {D} | {v['solves']} | {v['time_per_solve_s']:.2f} | {v['not_converged_rows']} |"
        )
    tot = "" if seconds is None else f" The stage took {seconds:.1f} s."
    L.append(f"\n`converged` counts seeds whose three solves all met the tolerances "
             f"(pressure ≤ {st['pressure_tol']:g}·E*, penetration ≤ the library's "
             f"rms height/(10·mean n) of each map, "
             f"≤ {st['maxiter']} iterations); `edge contact`: the BEM contact reaches the map's "
             f"border (free half-space: the map ends there).{tot}\n")  # fmt: skip
    L.append(_sentence(a) + " The ratios depend on the grid (A_BEM is not converged in the "
             "pixel size on a fractal map); quote them with it.\n")  # fmt: skip
    return L
