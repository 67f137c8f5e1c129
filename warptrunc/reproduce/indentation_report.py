# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Figure and report section "Indentation in silico (Fig. 6)" of the ``indentation`` stage
(:mod:`warptrunc.reproduce.indentation`). Every number and every claim of the text is computed
from the stage result and its analysis (:func:`~warptrunc.reproduce.indentation_analysis.analyse_indentation`);
which model truncation tracks follows the rule stated in the section."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from .._support.docs import fill_doc
from .indentation_analysis import cells
from .report_sections import fmt_value, new_figure, save_figure
from .store import STAGE_DOCS

__all__ = ["indentation_figures", "indentation_lines", "model_label"]

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


def model_label(stage: dict[str, Any], model: str) -> str:
    """Readable name of a model key of the stage.

    Parameters
    ----------
    stage : dict
        The stage result (its ``hardness_Pa``).
    model : str
        ``truncation``, ``elastic`` or ``elastic_plastic_<f>H`` (``_partial`` appended: the
        partial-unloading secant).

    Returns
    -------
    str
        E.g. ``"elastic–plastic, H = 1 GPa"``.
    """
    base, part = (model[: -len("_partial")], " (partial unloading)") if model.endswith("_partial") else (model, "")
    if base == "truncation":
        return "truncation (Eq. 2)"
    h = stage["hardness_Pa"].get(base)
    if h is None:
        return "elastic (H = ∞)" + part
    return f"elastic–plastic, H = {h / 1e9:g} GPa" + part


def indentation_figures(stage: dict[str, Any], ana: dict[str, Any], out: str | Path) -> list[str]:
    """Fig. 6 in silico: one panel per surface, E_c/E against F/(E·A) for every model.

    Parameters
    ----------
    stage : dict
        The stage result.
    ana : dict
        Its analysis (:func:`~warptrunc.reproduce.indentation_analysis.analyse_indentation`).
    out : str or Path
        Output folder.

    Returns
    -------
    list of str
        ``["indentation_fig6.png"]``.
    """
    surfaces = stage["surfaces"]
    ncol = 2 if len(surfaces) > 1 else 1
    nrow = math.ceil(len(surfaces) / ncol)
    fig, axs = new_figure(ncol, nrow, w=5.6, h=4.4)
    c = cells(stage)
    models = ["truncation", *stage["models"]]
    colours = model_colours(models)
    for ax, s in zip(axs, surfaces, strict=False):
        for m in models:
            colour = colours[m]
            xs_all = []
            for k, d in enumerate(stage["punches_m"]):
                pts = sorted((v["F_over_EA"], v["E_c_over_E"]) for (ss, mm, dd, _f), v in c.items()
                             if ss == s and mm == m and dd == d and v["E_c_over_E"])  # fmt: skip
                if not pts:
                    continue
                x, y = np.array(pts).T
                xs_all += list(x)
                ax.loglog(x, y, MARKERS[k % len(MARKERS)], color=colour, mfc="none", ms=4,
                          ls="--" if m == "truncation" else "none", lw=0.6)  # fmt: skip
            f = ana["fits"][s].get(m)
            if f and xs_all:
                xx = np.geomspace(min(xs_all), max(xs_all), 20)
                ax.loglog(xx, f["beta"] * xx ** f["alpha"], "-", color=colour, lw=1.2,
                          label=f"{model_label(stage, m)}: α = {f['alpha']:.3f}, β = {f['beta']:.3g}")  # fmt: skip
        ax.axhline(ana["smooth_Ec_over_E"], color="k", ls=":", lw=0.8, label="smooth punch: E*/E")
        for k, d in enumerate(stage["punches_m"]):
            ax.plot([], [], MARKERS[k % len(MARKERS)], color="grey", mfc="none",
                    label=f"d = {d * 1e6:g} µm")  # fmt: skip
        ax.set(xlabel="F/(E·A)", ylabel="E$_c$/E", title=f"{s} ({stage['n']}² over {stage['L_m'] * 1e3:g} mm)")
        ax.legend(fontsize=6)
    for ax in axs[len(surfaces):]:
        ax.set_axis_off()
    fig.suptitle("Fig. 6 in silico: unloading stiffness of three contact models and Eq. 2 truncation "
                 "(geometric mean over placements; lines: fits over every punch and load)", fontsize=9)  # fmt: skip
    return [save_figure(fig, Path(out), "indentation_fig6.png")]


def _runs(per: dict[str, Any]) -> str:
    if not per["runs"]:
        return "nowhere"
    by: dict[float, list[str]] = {}
    for d, lo, hi, _n in per["runs"]:
        by.setdefault(d, []).append(f"{lo * 1e3:.3g} mN" if lo == hi else f"{lo * 1e3:.3g}–{hi * 1e3:.3g} mN")
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
        :func:`~warptrunc.reproduce.indentation_analysis.tracking` of that surface.

    Returns
    -------
    str
        One Markdown paragraph.
    """
    band = f"±{100 * t['band']:.0f} %"
    n = max((v["n_cells"] for v in t["per_model"].values()), default=0)
    if t["tracked"] is None:
        head = (f"**{s}: truncation tracks none of the contact models** within {band} at any of the "
                f"{n} (punch, load) cells.")  # fmt: skip
    else:
        m = t["tracked"]
        head = (f"**{s}: truncation tracks the {model_label(stage, m)} unloading stiffness** "
                f"(within {band} in {t['per_model'][m]['n_good']} of {t['per_model'][m]['n_cells']} "
                f"(punch, load) cells: {_runs(t['per_model'][m])}).")  # fmt: skip
    rest = []
    for m, v in t["per_model"].items():
        if m == t["tracked"] or not v["n_cells"]:
            continue
        rest.append(f"{model_label(stage, m)}: {v['n_good']} of {v['n_cells']} cells"
                    + (f" ({_runs(v)})" if v["n_good"] else "")
                    + f", median E_c,trunc/E_c = {v['median_ratio']:.2f}")  # fmt: skip
    closest = ", ".join(f"{model_label(stage, m)} {k}" for m, k in t["closest"].items() if k)
    return (head + (" Against the others: " + "; ".join(rest) + "." if rest else "")
            + (f" Nearest model per cell: {closest}." if closest else ""))  # fmt: skip


@fill_doc(STAGE_DOCS)
def indentation_lines(stage: dict[str, Any], ana: dict[str, Any], seconds: float | None,
                      figure_names: list[str] | None = None) -> list[str]:  # fmt: skip
    """The report section "Indentation in silico (Fig. 6)".

    Parameters
    ----------
    stage : dict
        The stage result (:func:`~warptrunc.reproduce.indentation.summary_from_pieces`).
    ana : dict
        Its analysis (:func:`~warptrunc.reproduce.indentation_analysis.analyse_indentation`).
    {report_extras}
        Markdown lines; every number and every sentence's claim comes from ``stage`` and ``ana``.
    """
    from ..presets import TABLE1

    mat = stage["material"]
    mp = ana["mean_pressure"]
    hs = [v for v in stage["hardness_Pa"].values() if v is not None]
    L = ["## Indentation in silico (Fig. 6)\n"]
    surf = ", ".join(f"{s} (D_in = {TABLE1[s].D:g}, R_t′ = {TABLE1[s].Rt * 1e6:.4g} µm, "
                     f"W_r = {TABLE1[s].Wr * 1e6:g} µm)" for s in stage["surfaces"])  # fmt: skip
    L.append(
        "The paper's experiment (§ 4.1) on its simulated Table 1 surfaces (`warptrunc.presets.TABLE1`: "
        f"{surf}), each {stage['n']}² over {stage['L_m'] * 1e3:g} mm (pixel {stage['dx_m'] * 1e9:.1f} nm), "
        f"by `warptrunc.indent`: rigid flat punches of {', '.join(f'{d * 1e6:g}' for d in stage['punches_m'])} µm, "
        f"{stage['placements']} random placement(s) per punch (the same on every surface and every H), "
        f"{len(stage['loads_N'])} peak loads each twice the previous up to {max(stage['loads_N']) * 1e3:g} mN, "
        "each peak followed by a partial unloading of 10 %. Aluminium alloy E = "
        f"{mat['E_Pa'] / 1e9:g} GPa, ν = {mat['nu']:g} against diamond (E_i = {mat['E_i_Pa'] / 1e9:g} GPa, "
        f"ν_i = {mat['nu_i']:g}; E* = {mat['E_star_Pa'] / 1e9:.2f} GPa). Three contact models on the same "
        "punch windows (free half-space, contact solver in "
        f"{stage['dtype']}): **elastic** (H = ∞), and **elastic–perfectly-plastic** with the local pressure "
        "capped at H = " + " and ".join(f"{h / 1e9:g} GPa" for h in hs) + ": "
        f"{mat['H_alloy_Pa'] / 1e9:g} GPa is a treated alloy's indentation hardness (6061-T6: 107 HV = "
        "1.05 GPa, ASM Handbook Vol. 2, 1990; Tabor's H ≈ 3σ_y with σ_y = 276 MPa gives 0.83 GPa; the paper "
        "does not name its alloy), and twice that brackets a harder treated surface. The unloading "
        "stiffness K is Barber's initial slope at each peak (the plastic state frozen); the paper's "
        "partial-unloading secant is fitted too. **Eq. 2 truncation** runs on the same punch disks: "
        "A = the punch area πd²/4, first touch = the highest pixel inside the disk, "
        "k = (2/√π)E*√A_c read where F(ω) = ∫k dω reaches each peak load. All models give "
        "E_c = √π·K/(2√A), plotted as E_c/E against F/(E·A) with E the Young's modulus (Fig. 6's "
        f"normalisation): a smooth surface gives E*/E = {ana['smooth_Ec_over_E']:.3f}, not 1.\n"
    )  # fmt: skip
    if mp["H_min_Pa"] is not None:
        L.append(
            f"The largest load, {mp['load_N'] * 1e3:g} mN on the {mp['punch_m'] * 1e6:g} µm punch, is a mean "
            f"pressure of {mp['p_mean_Pa'] / 1e6:.0f} MPa, "
            + (f"below H = {mp['H_min_Pa'] / 1e9:g} GPa: the punch as a whole never yields, and plasticity "
               "stays at the scale of the asperities." if mp["below_H"] else
               f"above H = {mp['H_min_Pa'] / 1e9:g} GPa: the whole punch area flows.")
            + " H caps the pressure of each pixel, so the plastic area depends on the pixel size (resolution "
            "check below).\n"
        )  # fmt: skip
    if ana["max_overlap"] > 0:
        L.append(f"The {max(stage['punches_m']) * 1e6:g} µm punch's placements cannot be kept apart on a "
                 f"{stage['L_m'] * 1e3:g} mm map: they overlap by up to {100 * ana['max_overlap']:.0f} % of "
                 "its area (the paper's 3 mm discs would hold them apart).\n")  # fmt: skip
    L.append(f"Solves not converged: {ana['not_converged']} of {ana['n_solved_rows']} cycles "
             "(left out of the fits and of the comparison).\n")  # fmt: skip
    # alpha/beta
    models = ["truncation", *stage["models"]] + [m + "_partial" for m in stage["models"]]
    L.append("**E_c/E = β·[F/(E·A)]^α** per surface and model (least squares in log–log over every "
             "converged punch × placement × load; r² in brackets):\n")  # fmt: skip
    L.append("| surface | " + " | ".join(model_label(stage, m) for m in models) + " |")
    L.append("|---|" + "---|" * len(models))
    for s in stage["surfaces"]:
        cells_ = []
        for m in models:
            f = ana["fits"][s].get(m)
            cells_.append("—" if f is None else f"α = {f['alpha']:.3f}, β = {f['beta']:.3g} ({f['r2']:.2f})")
        L.append(f"| {s} | " + " | ".join(cells_) + " |")
    L.append("")
    # tracking
    band = f"±{100 * ana['good_band']:.0f} %"
    L.append(
        f"**Which model truncation tracks.** Rule: at each (surface, punch, peak load) cell, E_c/E of every "
        "model is the geometric mean over the converged placements; truncation *tracks* a model there when "
        f"E_c,trunc/E_c,model is within {band} of 1. Per surface, the model tracked is the one with the largest "
        "fraction of its cells in the band (ties: more cells, then the one nearest to truncation in more "
        "cells); the load ranges are the runs of consecutive peak loads in the band, per punch.\n"
    )  # fmt: skip
    L.append("| surface | model | cells within " + band + " | median E_c,trunc/E_c | range | load ranges in the band |")
    L.append("|---|---|---|---|---|---|")
    for s in stage["surfaces"]:
        t = ana["tracking"][s]
        for m, v in t["per_model"].items():
            rng = "—" if v["range"] is None else f"{v['range'][0]:.2f}–{v['range'][1]:.2f}"
            L.append(f"| {s} | {model_label(stage, m)} | {v['n_good']} of {v['n_cells']} | "
                     f"{fmt_value(v['median_ratio'], '.2f')} | {rng} | {_runs(v)} |")  # fmt: skip
    L.append("")
    for s in stage["surfaces"]:
        L.append(tracking_sentence(stage, s, ana["tracking"][s]) + "\n")
    for nme in figure_names or []:
        L.append(f"![{nme}]({nme})\n")
    # resolution
    r = ana["resolution"]
    if r:
        L.append(
            f"**Resolution check** ({r['surface']}, {r['punch_m'] * 1e6:g} µm punch at the map centre, the "
            f"largest load; the same surface — same phases and cut-off — at {r['n_coarse']}² "
            f"({r['dx_coarse_m'] * 1e9:.1f} nm pixels) and {r['n_fine']}² ({r['dx_fine_m'] * 1e9:.1f} nm)):\n"
        )  # fmt: skip
        L.append("| model | quantity | coarse | fine | fine/coarse |")
        L.append("|---|---|---|---|---|")
        names = {"unloading_stiffness_N_per_m": "K (N/m)", "partial_unloading_stiffness_N_per_m":
                 "K partial (N/m)", "contact_area_m2": "contact area (µm²)",
                 "plastic_area_m2": "plastic area (µm²)", "truncation_E_c_over_E": "truncation E_c/E"}  # fmt: skip
        for m, v in r["models"].items():
            for q, lab in names.items():
                a, b, ratio = v[q]
                scale = 1e12 if q.endswith("m2") else 1.0
                fa = "—" if a is None else f"{a * scale:.4g}"
                fb = "—" if b is None else f"{b * scale:.4g}"
                L.append(f"| {model_label(stage, m)} | {lab} | {fa} | {fb} | {fmt_value(ratio, '.3f')} |")
        L.append("")
    # timings
    L.append("**Pieces** (one per surface × model; stored under "
             f"`{stage['store']}/`, a rerun continues an interrupted stage):\n")  # fmt: skip
    L.append("| surface | model | seconds | of which elastic–plastic / elastic / truncation | "
             "cycles taken from the elastic piece | largest window (px) | not converged | device |")
    L.append("|---|---|---|---|---|---|---|---|")
    for t in stage["timings"]:
        w = t["largest_window_px"]
        L.append(f"| {t['surface']} | {model_label(stage, t['model'])} | {t['piece_s']:.1f} | "
                 f"{t['elastic_plastic_s']:.1f} / {t['elastic_s']:.1f} / {t['truncation_s']:.1f} | "
                 f"{t.get('reused_elastic_cycles', 0)} | "
                 f"{w[0]}×{w[1]} | {t['n_not_converged']} | {t['device']} |")  # fmt: skip
    L.append("\nAn elastic–plastic piece takes from the elastic piece each punch's leading cycles "
             "whose elastic peak pressure stays below H (no pixel reaches the cap, so the two "
             "solutions are one) and solves the rest.\n")
    tot = "" if seconds is None else f" The stage took {seconds:.1f} s in its last run."
    L.append(f"\nTotal over the pieces: {sum(t['piece_s'] for t in stage['timings']):.1f} s.{tot}\n")
    return L
