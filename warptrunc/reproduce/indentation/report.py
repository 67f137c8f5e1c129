# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Figure and report section "Indentation in silico (Fig. 6)" of the ``indentation`` stage
(:mod:`warptrunc.reproduce.indentation.stage`). Every number and every claim of the text is computed
from the stage result and its analysis (:func:`~warptrunc.reproduce.indentation.analysis.analyse_indentation`);
which model truncation tracks follows the rule stated in the section."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from ..._support.docs import fill_doc
from ..store import STAGE_DOCS
from ..style import fmt_value, new_figure, save_figure
from .analysis import cells
from .tables import (
    _design,
    agreement_lines,
    cost_lines,
    face_lines,
    fit_lines,
    hardness_lines,
    model_label,
    resolution_lines,
)

__all__ = ["indentation_figures", "indentation_lines", "model_colours", "model_label"]

COLOURS = {"truncation": "C3", "elastic": "C0"}
MARKERS = ("o", "s", "^", "D", "v")
_MORE_COLOURS = ("C2", "C4", "C1", "C5", "C6", "C8", "C9", "C7")


def model_colours(models: list[str]) -> dict[str, str]:
    """One matplotlib colour per model key, distinct: truncation red, elastic blue, the
    elastic–plastic models from a palette that skips those two.

    Parameters
    ----------
    models : list of str
        Model keys (``truncation``, ``elastic``, ``elastic_plastic_1H``, …).

    Returns
    -------
    dict of str to str
        Model key → colour (``"C0"`` … ``"C9"``, cycling past ten models).
    """
    more = iter(_MORE_COLOURS * (1 + len(models) // len(_MORE_COLOURS)))
    return {m: COLOURS[m] if m in COLOURS else next(more) for m in models}


def _fig_design(stage: dict[str, Any], s: str) -> str:
    """The design a surface's Fig. 6 panel shows: the statistics when it has any, else the sweep."""
    return (
        "stats"
        if any(t["surface"] == s and t["design"] == "stats" for t in stage["timings"])
        else "sweep"
    )


def _log_ticks(ax) -> None:
    """Labels at 1, 2 and 5 × 10^k only, none on the minor ticks: a panel spanning less than a
    decade otherwise labels every minor tick, and the labels run into each other."""
    from matplotlib.ticker import LogLocator, NullFormatter

    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        axis.set_minor_formatter(NullFormatter())


def indentation_figures(stage: dict[str, Any], ana: dict[str, Any], out: str | Path) -> list[str]:
    """Fig. 6 in silico (one panel per surface) and the depth at the largest load against H.

    Parameters
    ----------
    stage : dict
        The stage result.
    ana : dict
        Its analysis (:func:`~warptrunc.reproduce.indentation.analysis.analyse_indentation`).
    out : str or Path
        Output folder.

    Returns
    -------
    list of str
        ``["indentation_fig6.png", "indentation_depth_vs_H.png"]``.
    """
    surfaces = stage["surfaces"]
    ncol = 2 if len(surfaces) > 1 else 1
    nrow = math.ceil(len(surfaces) / ncol)
    fig, axs = new_figure(ncol, nrow, w=5.6, h=4.4)
    c = cells(stage)
    fits = {(f["surface"], f["design"], f["model"]): f for f in ana["fits"]}
    colours = model_colours(
        ["truncation", *dict.fromkeys(m for v in stage["models"].values() for m in v)]
    )
    for ax, s in zip(axs, surfaces, strict=False):
        design = _fig_design(stage, s)
        models = ["truncation", *[m for m in stage["models"][design] if (s, design, m) in fits]]
        for m in models:
            f = fits.get((s, design, m)) or {}
            per = {g.get("punch_diameter_m"): g for g in f.get("per_punch", [])}
            for k, d in enumerate(stage["punches_m"]):
                pts = sorted(
                    (v["F_over_EA"], v["E_c_over_E"])
                    for (ss, dd_, mm, dd, _f), v in c.items()
                    if ss == s and dd_ == design and mm == m and dd == d and v["E_c_over_E"]
                )
                if not pts:
                    continue
                x, y = np.array(pts).T
                ax.loglog(
                    x,
                    y,
                    MARKERS[k % len(MARKERS)],
                    color=colours[m],
                    mfc="none",
                    ms=4,
                    ls="--" if m == "truncation" else "none",
                    lw=0.6,
                )
                g = per.get(d) or {}
                if g.get("made"):  # the punch's own fit over its loads
                    xx = np.geomspace(x.min(), x.max(), 20)
                    ax.loglog(
                        xx,
                        g["beta"] * xx ** g["alpha"],
                        "-",
                        color=colours[m],
                        lw=1.2,
                        label=f"{model_label(stage, m)}, {d * 1e6:g} µm: α = {g['alpha']:.3f}",
                    )
        ax.axhline(ana["smooth_Ec_over_E"], color="k", ls=":", lw=0.8, label="smooth punch: E*/E")
        for k, d in enumerate(stage["punches_m"]):
            ax.plot(
                [],
                [],
                MARKERS[k % len(MARKERS)],
                color="grey",
                mfc="none",
                label=f"d = {d * 1e6:g} µm",
            )
        g = stage["designs"][design]
        ax.set(
            xlabel="F/(E·A)",
            ylabel="E$_c$/E",
            title=f"{s} ({stage['n']}² over {stage['L_m'] * 1e3:g} mm; {len(g['seeds'])}×{g['placements']} indents)",
        )
        _log_ticks(ax)
        ax.legend(fontsize=6)
    for ax in axs[len(surfaces) :]:
        ax.set_axis_off()
    fig.suptitle(
        "Fig. 6 in silico: unloading stiffness of the contact models and Eq. 2 truncation on "
        "resolved cells (geometric mean over indents; lines: each punch's fit over its loads)",
        fontsize=9,
    )
    names = [save_figure(fig, Path(out), "indentation_fig6.png")]
    fig, (ax,) = new_figure(1, 1, w=6.0, h=4.4)
    lo, hi = stage["depth_band_m"]
    for k, (s, v) in enumerate(ana["hardness"].items()):
        pts = [
            (h, lo_, hi_)
            for h, lo_, hi_ in zip(
                v["hardness_Pa"], v["depth_min_m"], v["depth_max_m"], strict=True
            )
            if hi_
        ]
        if pts:
            x, ylo, yhi = np.array(pts).T
            (ln,) = ax.loglog(x / 1e9, yhi * 1e6, "-" + MARKERS[k % len(MARKERS)], ms=4, label=s)
            ax.fill_between(x / 1e9, ylo * 1e6, yhi * 1e6, color=ln.get_color(), alpha=0.15, lw=0)
            if v["elastic_depth_m"]:
                er = v.get("elastic_depth_range_m") or [None, v["elastic_depth_m"]]
                ax.axhline(er[1] * 1e6, color=ln.get_color(), ls=":", lw=0.8)
    ax.axhspan(
        lo * 1e6,
        hi * 1e6,
        color="0.85",
        zorder=0,
        label=f"{lo * 1e6:g}–{hi * 1e6:g} µm (paper: ≈ 5 µm)",
    )
    ax.set(
        xlabel="hardness H (GPa)",
        ylabel=f"threshold depth at {max(stage['loads_N']) * 1e3:g} mN (µm)",
        title="Deepest placement (band: min–max over placements) against H (sweep; dotted: H = ∞)",
    )
    hs = sorted(
        {h for v in ana["hardness"].values() for h in v["hardness_Pa"] if h and math.isfinite(h)}
    )
    _log_ticks(ax)
    if hs:  # the swept H values themselves, in GPa
        ax.set_xticks([h / 1e9 for h in hs], [f"{h / 1e9:g}" for h in hs])
    ax.legend(fontsize=7)
    names.append(save_figure(fig, Path(out), "indentation_depth_vs_H.png"))
    return names


def _runs(per: dict[str, Any]) -> str:
    if not per["runs"]:
        return "nowhere"
    by: dict[float, list[str]] = {}
    for d, lo, hi, _n in per["runs"]:
        by.setdefault(d, []).append(
            f"{lo * 1e3:.3g} mN" if lo == hi else f"{lo * 1e3:.3g}–{hi * 1e3:.3g} mN"
        )
    return "; ".join(f"{d * 1e6:g} µm at {', '.join(v)}" for d, v in sorted(by.items()))


def tracking_sentence(stage: dict[str, Any], s: str, t: dict[str, Any]) -> str:
    """The plain statement for one surface: which model truncation tracks, where.

    Parameters
    ----------
    stage : dict
        The stage result.
    s : str
        Surface name.
    t : dict
        :func:`~warptrunc.reproduce.indentation.analysis.tracking` of that surface.

    Returns
    -------
    str
        One Markdown paragraph.
    """
    band = f"±{100 * t['band']:.0f} %"
    n = max((v["n_cells"] for v in t["per_model"].values()), default=0)
    if t["tracked"] is None:
        head = (
            f"**{s}: truncation tracks none of the contact models** within {band} at any of the "
            f"{n} (punch, load) cells."
        )
    else:
        m = t["tracked"]
        head = (
            f"**{s}: truncation tracks the {model_label(stage, m)} unloading stiffness** "
            f"(within {band} in {t['per_model'][m]['n_good']} of {t['per_model'][m]['n_cells']} "
            f"(punch, load) cells: {_runs(t['per_model'][m])})."
        )
    rest = []
    for m, v in t["per_model"].items():
        if m == t["tracked"] or not v["n_cells"]:
            continue
        rest.append(
            f"{model_label(stage, m)}: {v['n_good']} of {v['n_cells']} cells"
            + (f" ({_runs(v)})" if v["n_good"] else "")
            + f", median E_c,trunc/E_c = {v['median_ratio']:.2f}"
        )
    closest = ", ".join(f"{model_label(stage, m)} {k}" for m, k in t["closest"].items() if k)
    return (
        head
        + (" Against the others: " + "; ".join(rest) + "." if rest else "")
        + (f" Nearest model per cell: {closest}." if closest else "")
    )


MATERIAL_TEXT = (
    "**The material is assumed, not the paper's**: the paper names neither its alloy nor E, ν, E_i, "
    "ν_i or H. E = {E:g} GPa and ν = {nu:g} are typical of wrought aluminium alloys (handbook values "
    "of about 69–72 GPa and 0.33, e.g. ASM Handbook Vol. 2); the punches are diamond, E_i = {Ei:g} GPa, "
    "ν_i = {nui:g} (Oliver & Pharr, J. Mater. Res. 7, 1564 (1992)); E* = {Es:.2f} GPa. **The hardness "
    "is swept, not assumed**: handbook Vickers hardness of aluminium alloys runs from about HV 20–30 "
    "(pure aluminium, annealed) to about HV 150–175 (7075-T6) (ASM Handbook Vol. 2; order-of-magnitude "
    "ranges), i.e. H ≈ 0.0098·HV GPa ≈ 0.2–1.7 GPa (HV is the load over the indent's surface area; the "
    "mean pressure over its projected area, which the model caps, is about 8 % higher); "
    "nanoindentation a few hundred nm deep reads more, of the order of 1–2 GPa for common alloys (the "
    "indentation size effect; W.D. Nix, H. Gao, J. Mech. Phys. Solids 46, 411 (1998)); and SMAT and "
    "grit blasting work-harden the surface layer, by tens of percent or more (order of magnitude; for "
    "SMAT e.g. K. Lu, J. Lu, Mater. Sci. Eng. A 375–377, 38 (2004)). Tabor's H ≈ 3σ_y (D. Tabor, *The "
    "Hardness of Metals*, Oxford, 1951) links H to the yield stress. The sweep, {Hs} GPa, spans these "
    "and more."
)
"""What the report says of the material, with the sources."""


@fill_doc(STAGE_DOCS)
def indentation_lines(
    stage: dict[str, Any],
    ana: dict[str, Any],
    seconds: float | None,
    figure_names: list[str] | None = None,
) -> list[str]:
    """The report section "Indentation in silico (Fig. 6)".

    Parameters
    ----------
    stage : dict
        The stage result (:func:`~warptrunc.reproduce.indentation.summary.summary_from_pieces`).
    ana : dict
        Its analysis (:func:`~warptrunc.reproduce.indentation.analysis.analyse_indentation`).
    {report_extras}
        Markdown lines; every number and every sentence's claim comes from ``stage`` and ``ana``.
    """
    from ...presets import TABLE1

    mat = stage["material"]
    mp = ana["mean_pressure"]
    hs = sorted(h for h in stage["hardness_Pa"].values() if h is not None)
    L = ["## Indentation in silico (Fig. 6)\n"]
    surf = ", ".join(
        f"{s} (D_in = {TABLE1[s].D:g}, R_t′ = {stage['Rt_m'][s] * 1e6:.4g} µm, "
        f"W_r = {TABLE1[s].Wr * 1e6:g} µm)"
        for s in stage["surfaces"]
    )
    des = stage["designs"]
    L.append(
        "The paper's experiment (§ 4.1) on its simulated Table 1 surfaces (`warptrunc.presets.TABLE1`: "
        f"{surf}), each {stage['n']}² over {stage['L_m'] * 1e3:g} mm (pixel {stage['dx_m'] * 1e9:.1f} nm), "
        f"by `warptrunc.indent`: rigid flat punches of {', '.join(f'{d * 1e6:g}' for d in stage['punches_m'])} µm, "
        f"{len(stage['loads_N'])} peak loads each twice the previous up to {max(stage['loads_N']) * 1e3:g} mN, "
        "each followed by a partial unloading of 10 %. Two designs: a **sweep** of the hardness, "
        f"H = {', '.join(f'{h / 1e9:g}' for h in hs)} GPa and ∞, on {len(des['sweep']['seeds'])} realisation × "
        f"{des['sweep']['placements']} random placement(s) per punch; and **statistics**, "
        f"{len(des['stats']['seeds'])} realisations (phase seeds {', '.join(map(str, des['stats']['seeds']))}) "
        f"× {des['stats']['placements']} placements per punch, for "
        + (
            " and ".join(
                {
                    "elastic": "H = ∞",
                    "depth-match": "the one H of the sweep that best matches the paper's "
                    "maximal depth over every surface",
                }[m]
                for m in stage["stats_requested"]
            )
            or "nothing"
        )
        + ". Contact models on the same punch windows (free half-space, contact solver in "
        f"{stage['dtype']}): **elastic** (H = ∞) and **elastic–perfectly-plastic**, the local pressure "
        "capped at H. The unloading stiffness K is Barber's initial slope at each peak (the plastic state "
        "frozen); the paper's partial-unloading secant is fitted too. **Eq. 2 truncation** runs on the "
        "same punch disks: A = πd²/4, first touch = the highest pixel inside the disk, k = (2/√π)E*√A_c "
        "read where F(ω) = ∫k dω reaches each peak load. All give E_c = √π·K/(2√A), plotted as E_c/E "
        f"against F/(E·A) (Fig. 6): a smooth surface gives E*/E = {ana['smooth_Ec_over_E']:.3f}, not 1.\n"
    )
    L.append(
        MATERIAL_TEXT.format(
            E=mat["E_Pa"] / 1e9,
            nu=mat["nu"],
            Ei=mat["E_i_Pa"] / 1e9,
            nui=mat["nu_i"],
            Es=mat["E_star_Pa"] / 1e9,
            Hs=", ".join(f"{h / 1e9:g}" for h in hs),
        )
        + "\n"
    )
    a = mp["punch_m"] / 2
    L.append(
        f"The largest load, {mp['load_N'] * 1e3:g} mN on the {mp['punch_m'] * 1e6:g} µm punch, is a mean "
        f"pressure of {mp['p_mean_Pa'] / 1e6:.0f} MPa"
        + (
            f", below every H of the sweep: the punch as a whole never yields, plasticity stays at the "
            "asperities, and the depth cannot exceed the roughness under the punch plus the elastic sink "
            f"(a smooth punch: F/(2E*a) = {mp['load_N'] / (2 * mat['E_star_Pa'] * a) * 1e6:.2f} µm)"
            if hs and mp["p_mean_Pa"] < hs[0]
            else ""
        )
        + (
            f". {ana['bulk_yield']['n_rows']} cells reach the bulk-yield pressure of the cap "
            "model (" + ana["bulk_yield"]["criterion"] + ") and are flagged `bulk_yield`, left "
            "out of the fits: there the alloy would sink in bulk, which a pressure cap does not "
            "represent (those above H·A are not solved)"
            if ana.get("bulk_yield", {}).get("n_rows")
            else ""
        )
        + ". H caps the pressure of each pixel, so the plastic area depends on the pixel size (the "
        "resolution table below).\n"
    )
    if ana["max_overlap"] > 0:
        L.append(
            f"The {max(stage['punches_m']) * 1e6:g} µm punch's placements cannot be kept apart on a "
            f"{stage['L_m'] * 1e3:g} mm map: they overlap by up to {100 * ana['max_overlap']:.0f} % of "
            "its area (a 3 mm map, or fewer placements, would hold them apart).\n"
        )
    L.append(
        f"Solves not converged: {ana['not_converged']} of {ana['n_solved_rows']} cycles (left out of "
        "the fits and the comparisons, as are the cells not resolved).\n"
    )
    L.append(
        "**Hardness as a question**: the punch's threshold depth at the largest load for each "
        "H, its spread over the placements beside the paper's ≈ 5 µm:\n"
    )
    L += hardness_lines(stage, ana)
    frac = [
        f"{x['surface']} {model_label(stage, x['model'])} ({_design(stage, x['design'])}): "
        f"{x['in_fit']}/{x['n_cells']}"
        for x in ana.get("in_fit_fraction", [])
    ]
    L.append(
        "**E_c/E = β·[F/(E·A)]^α** per surface, design (realisations × placements per punch), "
        "model and punch, over its loads: least squares in log–log over the resolved cells "
        "(`in_fit`, the one rule: K converged over two halvings of the pixel) only. Cells in_fit "
        "by that rule: " + ("; ".join(frac) if frac else "none") + ":\n"
    )
    L += fit_lines(stage, ana)
    L += agreement_lines(stage, ana)
    band = f"±{100 * ana['good_band']:.0f} %"
    L.append(
        f"**Which model truncation tracks, on resolved cells.** At each (surface, punch, load) cell, "
        "E_c,trunc/E_c,model is the geometric mean over the resolved indents; truncation *tracks* a model "
        f"there when it is within {band} of 1. Per surface and design, the model tracked is the one with "
        "the largest fraction of its cells in the band (ties: more cells, then nearest to truncation in "
        "more cells); the load ranges are runs of consecutive loads in the band, per punch.\n"
    )
    for t in ana["tracking"]:
        d = stage["designs"][t["design"]]
        L.append(
            f"*{'Sweep' if t['design'] == 'sweep' else 'Statistics'} ({len(d['seeds'])}×{d['placements']})* — "
            + tracking_sentence(stage, t["surface"], t)
            + "\n"
        )
    for nme in figure_names or []:
        L.append(f"![{nme}]({nme})\n")
    L += face_lines(stage, ana)
    r = ana["resolution"]
    if r:
        L.append(
            f"**Resolution check** ({r['surface']}, {r['punch_m'] * 1e6:g} µm punch at the map centre, the "
            f"largest load; the same surface — same phases and cut-off — at {r['n_coarse']}² "
            f"({r['dx_coarse_m'] * 1e9:.1f} nm pixels) and {r['n_fine']}² ({r['dx_fine_m'] * 1e9:.1f} nm)):\n"
        )
        L.append("| model | quantity | coarse | fine | fine/coarse |")
        L.append("|---|---|---|---|---|")
        names = {
            "unloading_stiffness_N_per_m": "K (N/m)",
            "partial_unloading_stiffness_N_per_m": "K partial (N/m)",
            "contact_area_m2": "contact area (µm²)",
            "plastic_area_m2": "plastic area (µm²)",
            "truncation_E_c_over_E": "truncation E_c/E",
        }
        for m, v in r["models"].items():
            for q, lab in names.items():
                x, y, ratio = v[q]
                scale = 1e12 if q.endswith("m2") else 1.0
                fa = "—" if x is None else f"{x * scale:.4g}"
                fb = "—" if y is None else f"{y * scale:.4g}"
                L.append(
                    f"| {model_label(stage, m)} | {lab} | {fa} | {fb} | {fmt_value(ratio, '.3f')} |"
                )
        L.append("")
    L += resolution_lines(stage, ana)
    L += cost_lines(stage, ana, seconds)
    L.append(
        "An elastic–plastic piece of the sweep takes from the sweep's elastic piece each unrefined "
        "punch's leading cycles whose elastic peak pressure stays below H (no pixel reaches the cap, "
        "so the two solutions are one) and solves the rest; a refined punch solves every cycle.\n"
    )
    return L
