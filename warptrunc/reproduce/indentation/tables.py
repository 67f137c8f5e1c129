# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The tables of the report section "Indentation in silico (Fig. 6)": the hardness question,
the fits with their intervals, the agreement depths against the paper's ranges, the
resolution per load and the cost. Each function turns the stage result and its analysis
(:func:`~warptrunc.reproduce.indentation.analysis.analyse_indentation`) into Markdown lines;
every number comes from them."""

from __future__ import annotations

import math
from typing import Any

from ..._support.docs import fill_doc
from ..paper import TABLE2
from ..style import fmt_value

__all__ = [
    "agreement_lines",
    "cost_lines",
    "face_lines",
    "fit_lines",
    "hardness_lines",
    "model_label",
    "resolution_lines",
]

DESIGN_WORDS = {"sweep": "sweep", "stats": "statistics", "face": "punch face"}
VERDICTS = {
    "explains": "**explains it**: with this face truncation leaves the band where the paper's Ps leaves "
    "the experiment, while with the aligned smooth flat it stays within it",
    "does-not-explain": "**does not explain it**: truncation stays within the band beyond the paper's "
    "range with this face too",
    "too-early": "**too strong**: with this face truncation leaves the band before the paper's range",
    "aligned-leaves": "not needed: truncation already leaves the band of the aligned smooth flat by the "
    "paper's range",
    "undecided": "undecided: no resolved cell deep enough to tell",
    "no-cells": "no resolved cells",
}
"""The plain words of each verdict of :func:`~warptrunc.reproduce.indentation.analysis.analyse_indentation`'s ``faces``."""


TABLE_DOCS = {
    "{stage_ana}": "Parameters\n----------\nstage : dict\n    The stage result.\nana : dict\n"
    "    Its analysis.",
}
"""The parameters every table of the stage's report takes, written once
(:func:`~warptrunc._support.docs.fill_doc`)."""


def model_label(stage: dict[str, Any], model: str) -> str:
    """Readable name of a model key of the stage.

    Parameters
    ----------
    stage : dict
        The stage result (its ``hardness_Pa``).
    model : str
        ``truncation``, ``elastic`` or ``elastic_plastic_<H>GPa`` (``_partial`` appended: the
        partial-unloading secant).

    Returns
    -------
    str
        E.g. ``"elastic–plastic, H = 1 GPa"``.
    """
    base, part = (
        (model[: -len("_partial")], " (partial unloading)")
        if model.endswith("_partial")
        else (model, "")
    )
    if base == "truncation":
        return "truncation (Eq. 2)"
    h = stage["hardness_Pa"].get(base)
    if h is None:
        return "elastic (H = ∞)" + part
    return f"elastic–plastic, H = {h / 1e9:g} GPa" + part


def _um(v: float | None, fmt: str = ".3g") -> str:
    return "—" if v is None else format(v * 1e6, fmt)


def _gpa(v: float) -> str:
    return f"{v / 1e9:.3g}"


def _design(stage: dict[str, Any], design: str) -> str:
    d = stage["designs"][design]
    n = len(d["seeds"])
    return f"{DESIGN_WORDS[design]} ({n}×{d['placements']})"


@fill_doc(TABLE_DOCS)
def hardness_lines(stage: dict[str, Any], ana: dict[str, Any]) -> list[str]:
    """The threshold depth at the largest load per H, with its spread over the placements,
    against the paper's ≈ 5 µm (its maximum over all tests), and the H it allows.

    {stage_ana}

    Returns
    -------
    list of str
        Markdown lines: one table row per surface, a row of the maximum over every surface, and
        a sentence per surface.
    """
    lo, hi = stage["depth_band_m"]
    at = max(stage["loads_N"]) * 1e3
    allh = ana.get("hardness_all") or {}
    hs = sorted({h for v in ana["hardness"].values() for h in v["hardness_Pa"]})

    def span_of(rg: dict[str, Any]) -> str:
        if rg["low"] is None:
            return "none in the sweep"
        out = " ∪ ".join(f"{a / 1e9:.3g}–{b / 1e9:.3g} GPa" for a, b in rg["intervals"])
        return (
            out
            + (" (or softer)" if rg["open_below"] else "")
            + (" (or harder)" if rg["open_above"] else "")
        )

    L = [
        "| surface | punch | "
        + " | ".join(f"H = {h / 1e9:g} GPa" for h in hs)
        + f" | H = ∞ | H with the deepest placement in {_um(lo, 'g')}–{_um(hi, 'g')} µm |",
        "|---|---|" + "---|" * (len(hs) + 2),
    ]
    words = []
    for s, v in ana["hardness"].items():
        cells = []
        for h in hs:
            k = v["hardness_Pa"].index(h) if h in v["hardness_Pa"] else None
            a = None if k is None else v["depth_min_m"][k]
            b = None if k is None else v["depth_max_m"][k]
            cells.append("—" if a is None else _um(a) if a == b else f"{_um(a)}–{_um(b)}")
        el = v.get("elastic_depth_range_m")
        punch = next((p for p in v["punch_m"] if p is not None), None)
        L.append(
            f"| {s} | {'—' if punch is None else f'{punch * 1e6:g} µm'} | "
            + " | ".join(cells)
            + " | "
            + (
                "—"
                if not el or el[0] is None
                else _um(el[0])
                if el[0] == el[1]
                else f"{_um(el[0])}–{_um(el[1])}"
            )
            + " | "
            f"{span_of(v['range'])} |"
        )
        deep = [x for x in v["depth_max_m"] if x is not None]
        if v["range"]["low"] is None and deep:
            side = "shallower" if max(deep) < lo else "deeper"
            words.append(
                f"{s}: every H of the sweep gives a deepest placement {side} than "
                f"{_um(lo, 'g')}–{_um(hi, 'g')} µm ("
                + (
                    f"{_um(min(deep))}"
                    if min(deep) == max(deep)
                    else f"{_um(min(deep))}–{_um(max(deep))}"
                )
                + " µm)."
            )
    if allh.get("hardness_Pa"):
        cells = []
        for h in hs:
            k = allh["hardness_Pa"].index(h) if h in allh["hardness_Pa"] else None
            cells.append(
                "—" if k is None else f"{_um(allh['max_depth_m'][k])} ({allh['surface'][k]})"
            )
        L.append(
            "| **every surface (largest)** | — | " + " | ".join(cells) + " | — | "
            f"{span_of(allh['range'])} |"
        )
        mt = allh["match"]
        words.append(
            "Over every surface: the largest threshold depth at "
            f"{at:g} mN lies in {_um(lo, 'g')}–{_um(hi, 'g')} µm for H = {span_of(allh['range'])}"
            + (
                f"; {_um(stage['depth_target_m'], 'g')} µm at H ≈ {_gpa(mt['H_target'])} GPa"
                if mt.get("H_target") is not None
                else ""
            )
            + (
                f"; the statistics run at H = {_gpa(mt['H_match'])} GPa (the sweep's H nearest)."
                if mt.get("H_match") is not None
                else "; no H of the sweep reaches the band, so no elastic–plastic statistics."
            )
        )
    L.append("")
    reading = next((v.get("reading") for v in ana["hardness"].values() if v.get("reading")), None)
    L.append(
        f"Depth: the punch's depth at the largest load, {at:g} mN, "
        + (
            "read as an indenter reads it, from surface detection (the approach at the "
            "detection load subtracted: `warptrunc.indent.depth`), "
            if reading == "from surface detection"
            else "from first touch at the highest pixel under the punch, "
        )
        + "on the punch that goes deepest (named), min–max over the sweep's placements, in µm; "
        'the paper: the maximal indentation depth "is around 5 µm" (§ 4.1) — its maximum over '
        f"all its tests, taken here as {_um(lo, 'g')}–{_um(hi, 'g')} µm and compared with the "
        "deepest placement, per surface and over every surface. The H ranges join the sweep's "
        'points by straight lines in log H – log depth; "or softer/harder": the band is met at '
        "the sweep's end, beyond which it says nothing. The statistics use one H for every "
        "surface, the sweep's H nearest the one where the largest depth over every surface is "
        "the target.\n"
    )
    L += [w + "\n" for w in words]
    return L


def _ci(f: dict[str, Any], key: str, fmt: str) -> str:
    lo, hi = f.get(f"{key}_ci95") or (None, None)
    if lo is None or hi is None or not (math.isfinite(lo) and math.isfinite(hi)):
        return format(f[key], fmt)
    return f"{format(f[key], fmt)} [{format(lo, fmt)}, {format(hi, fmt)}]"


@fill_doc(TABLE_DOCS)
def fit_lines(stage: dict[str, Any], ana: dict[str, Any]) -> list[str]:
    """α, β with 95 % intervals per surface × design × model × punch, over loads, and the pooled
    fit where the punches agree.

    {stage_ana}

    Returns
    -------
    list of str
        Markdown lines of the table and its notes.
    """
    L = [
        "| surface | design | model | punch | α [95 %] | β [95 %] | loads | cells | indents | "
        "α shift, K and A rule |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    dalpha, refused = [], 0
    for f in ana["fits"]:
        lead = (
            f"| {f['surface']} | {_design(stage, f['design'])} | {model_label(stage, f['model'])} |"
        )
        rows = [*f.get("per_punch", []), {**f.get("pooled", {"made": False}), "pooled": True}]
        for g in rows:
            d = g.get("punch_diameter_m")
            who = "pooled" if g.get("pooled") else ("flat" if d is None else f"{d * 1e6:g} µm")
            if not g.get("made"):
                if g.get("pooled") and not any(x.get("made") for x in f.get("per_punch", [])):
                    continue  # nothing fitted: the per-punch rows say why
                refused += 1
                L.append(f"{lead} {who} | not made: {g.get('reason', '')} | — | "
                         f"{g.get('n_loads', '—')} | — | — | — |")  # fmt: skip
                continue
            shift = g.get("rule_shift_alpha")
            L.append(
                f"{lead} {who} | {_ci(g, 'alpha', '.3f')} | {_ci(g, 'beta', '.3g')} | "
                f"{g['n_loads']} | {g['n_points']} | {g['n_indents']} | "
                f"{'—' if shift is None or not math.isfinite(shift) else format(shift, '.3f')} |"
            )
        pa = {x.get("punch_diameter_m"): x for x in (f.get("partial") or {}).get("per_punch", [])}
        for g in f.get("per_punch", []):
            q = pa.get(g.get("punch_diameter_m"))
            if g.get("made") and q and q.get("made"):
                dalpha.append(abs(q["alpha"] - g["alpha"]))
    L.append("")
    L.append(
        "A power law in the load, per punch: made only over at least three distinct peak loads "
        "of that punch with cells in_fit (a slope between punch sizes at one load measures how K "
        "scales with the punch, not with the load); the pooled fit over the punches only where "
        "their 95 % intervals of α share a value. The intervals: a hierarchical bootstrap "
        "(realisations first, then placements; `warptrunc.indent.fits`), spanning the fits "
        "under both cell rules — K converged over two halvings of the pixel (the one rule) and "
        "K with the contact area converged too; the last column is how far the second rule "
        "moves α. None where a punch has a single indent.\n"
    )
    if dalpha:
        L.append(
            f"The paper's partial-unloading secant instead of Barber's initial slope changes α by at "
            f"most {max(dalpha):.3f} over these fits.\n"
        )
    return L


@fill_doc(TABLE_DOCS)
def agreement_lines(stage: dict[str, Any], ana: dict[str, Any]) -> list[str]:
    """How deep truncation stays within the band of each model, beside the paper's ranges.

    {stage_ana}

    Returns
    -------
    list of str
        Markdown lines of the rule and the table.
    """
    band = f"±{100 * ana['good_band']:.0f} %"
    L = [
        f"**How deep truncation stays within {band} of each model**. Rule: per "
        "surface, design and model, each (punch, load) cell whose indents are resolved gives "
        "E_c,trunc/E_c,model (the geometric mean over those indents of each indent's ratio, truncation "
        "read on the same disk at the same pixel) and its truncation depth ω (the median over the same "
        "indents, from the highest pixel under the punch, in % of the map's R_t′). The cells of all "
        "punches are walked in order of ω from the shallowest; the agreement reaches the ω of the last "
        "cell in the band before the first cell outside it, which is where it *leaves*. The paper's "
        "ranges (§ 4.2, Table 2, first column) compare truncation with the **experiment**; here the "
        "reference is a **contact model** on the same simulated surface, and ω is measured under each "
        "punch, not from the top of the whole map as the paper's is.\n",
        f"| surface | design | model | within {band} up to (% R_t′) | leaves at (% R_t′) | cells in / walked | "
        "deepest cell (% R_t′) | the paper (vs experiment) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for a in ana["agreement"]:
        paper = TABLE2.get(a["surface"], ((None, None),))[0]
        ptxt = "—" if paper[0] is None else f"{paper[0]:g}–{paper[1]:g} %"
        upto = (
            "none (the shallowest cell is outside)"
            if a["depth"] is None and a["n_cells"]
            else fmt_value(a["depth"], ".3g")
        )
        leave = (
            "never (to the deepest cell)"
            if a["leaves_at"] is None and a["n_cells"]
            else fmt_value(a["leaves_at"], ".3g")
        )
        L.append(
            f"| {a['surface']} | {_design(stage, a['design'])} | {model_label(stage, a['model'])} | "
            f"{upto} | {leave} | {a['n_in']} / {a['n_cells']} | {fmt_value(a['deepest'], '.3g')} | {ptxt} |"
        )
    L.append("")
    return L


@fill_doc(TABLE_DOCS)
def resolution_lines(stage: dict[str, Any], ana: dict[str, Any]) -> list[str]:
    """Per surface × load, for each design and model: cells resolved, median contact pixels,
    largest refinement.

    {stage_ana}

    Returns
    -------
    list of str
        Markdown lines.
    """
    cols = []
    for t in ana["resolution_table"]:
        k = (t["design"], t["model"])
        if k not in cols:
            cols.append(k)
    head = " | ".join(f"{model_label(stage, m)}, {_design(stage, d)}" for d, m in cols)
    L = [
        "**Resolution of the cells per load.** Each entry: cells resolved / cells, the median "
        "number of contact pixels, and the largest refinement of the pixel reached (×1: the map's "
        f"{stage['dx_m'] * 1e9:.1f} nm; refined punches: "
        + ", ".join(f"{d * 1e6:g} µm" for d in stage["refine_punches_m"])
        + f", up to ×{stage['refine_max']}; a resolved cell changes K and A by less than "
        f"{100 * stage['resolution_tol']:g} % at its last halving and has at least "
        f"{stage['min_contact_pixels']} contact pixels; unrefined punches: the contact-pixel rule "
        "alone). Over every punch and indent.\n",
        f"| surface | load (mN) | {head} |",
        "|---|---|" + "---|" * len(cols),
    ]
    tab = {(t["surface"], t["design"], t["model"], t["load_N"]): t for t in ana["resolution_table"]}
    for s in stage["surfaces"]:
        for f in stage["loads_N"]:
            row = []
            for d, m in cols:
                t = tab.get((s, d, m, f))
                row.append(
                    "—"
                    if t is None
                    else f"{t['resolved']}/{t['n']}, {fmt_value(t['median_contact_px'], '.0f')} px, ×{t['max_refinement']}"
                )
            L.append(f"| {s} | {f * 1e3:.4g} | " + " | ".join(row) + " |")
    L.append("")
    return L


@fill_doc(TABLE_DOCS)
def cost_lines(stage: dict[str, Any], ana: dict[str, Any], seconds: float | None) -> list[str]:
    """Seconds per piece and per refinement level, the largest refinement reached.

    {stage_ana}
    seconds : float or None
        Compute time of the stage's last run (s), if known.

    Returns
    -------
    list of str
        Markdown lines.
    """
    c = ana["cost"]
    L = [
        f"**Cost.** Pieces (one per surface × design × H, and per punch face; stored under `{stage['store']}/`, a rerun "
        "continues an interrupted stage):\n",
        "| surface | design | model | realisations × placements | seconds | of which solves at the map's "
        "pixel / refinement / truncation | cycles taken from the elastic piece | cells per pixel "
        "(×f: n) | largest window (px) | not converged | device |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for t in stage["timings"]:
        w = t["largest_window_px"]
        per = ", ".join(f"×{k}: {v}" for k, v in t["cells_per_factor"].items())
        face = f", {t['face']}" if t.get("face") else ""
        L.append(
            f"| {t['surface']} | {DESIGN_WORDS[t['design']]} | {model_label(stage, t['model'])}{face} | "
            f"{len(t['seeds'])} × {t['placements']} | {t['piece_s']:.1f} | "
            f"{t.get('elastic_plastic_s', 0) + t.get('elastic_s', 0):.1f} / "
            f"{t.get('refinement_s', 0):.1f} / {t.get('truncation_s', 0):.1f} | "
            f"{t.get('reused_elastic_cycles', 0)} | {per} | {w[0]}×{w[1]} | "
            f"{t['n_not_converged']} | {t['device']} |"
        )
    L.append("")
    if c["levels"]:
        L.append(
            "Per refinement level (cells solved there: those whose final pixel is that fine or finer; "
            "seconds **apportioned**: `warptrunc.indent` records the refinement's seconds per punch, "
            "split here by cells × window pixels at each level):\n"
        )
        L += [
            "| level | cells solved | largest window (px) | seconds (apportioned) |",
            "|---|---|---|---|",
        ]
        for f, v in c["levels"].items():
            side = round(math.sqrt(v["window_px"]))
            L.append(f"| ×{f} | {v['cells']} | ≈{side}² | {v['seconds']:.1f} |")
        L.append("")
    L.append(
        f"Largest refinement reached: ×{c['largest_refinement']}. "
        + "; ".join(f"{DESIGN_WORDS[d]}: {v:.1f} s" for d, v in c["per_design"].items())
        + f"; total over the pieces {c['pieces_s']:.1f} s."
        + ("" if seconds is None else f" The stage took {seconds:.1f} s in its last run.")
        + "\n"
    )
    return L


@fill_doc(TABLE_DOCS)
def face_lines(stage: dict[str, Any], ana: dict[str, Any]) -> list[str]:
    """The punch-face runs: whether a tilted or rough face explains the divergence of Ps.

    {stage_ana}

    Returns
    -------
    list of str
        Markdown lines: the rule, the table and one sentence per face.
    """
    head = (
        '**Ps with a tilted or rough punch face** (§ 4.2: "the misalignment of the indenter with '
        "tested surfaces and roughness features that may be present on the flat diamond tip (measured "
        "to have an RMS roughness of around 0.05 µm)\" among the likely causes of Ps's divergence for "
        "interferences beyond 15 % R_t′). "
    )
    if not ana.get("faces"):
        return [
            head + "Not run: the profile names no punch face (`indentation.face_surface`, "
            "`indentation.face_tilts_deg`, `indentation.face_roughness`).\n"
        ]
    f0 = ana["faces"][0]
    lo, hi = f0["paper_range"]
    band = f"±{100 * ana['good_band']:.0f} %"
    L = [
        head
        + f"The sweep's indents of {f0['surface']} again, at {model_label(stage, f0['model'])}, with each "
        "face (`PunchFaceSpec.tilt_deg`, held fixed as the indenter's shaft holds it; "
        "`PunchFaceSpec.roughness`, a self-affine face of Hurst exponent 0.8 from 2 map pixels, or the finest its "
        "punch's face grid holds, to the punch diameter); a tilt marked *local* is relative to the "
        "sample's least-squares plane under each placement (`PunchFaceSpec.tilt_reference`), its "
        "azimuth turned from one placement to the next so that the placements average over it, and "
        "is compared with the face at 0° local (aligned with the surface under it), the others with "
        "the aligned smooth flat of the sweep"
        + (
            f" (the sample's own plane tilts by {f0['local_plane_tilt_deg_rms']:.3g}° rms under "
            "the punches)"
            if f0.get("local_plane_tilt_deg_rms")
            else ""
        )
        + "; truncation stays the sample's. A face **explains** the divergence when, with it, truncation "
        f"leaves the {band} band of the model between the last cell inside and the first outside a "
        f"bracket that meets the paper's {lo:g}–{hi:g} % R_t′, while with the aligned flat it stays "
        "within the band beyond that range (the agreement walk above; ω in % of the map's R_t′).\n",
        f"| face | within {band} up to (% R_t′) | leaves at (% R_t′) | cells in / walked | "
        "K / K of the reference, median [range] | reference | verdict |",
        "|---|---|---|---|---|---|---|",
    ]
    ref = f0["aligned"]
    if ref is not None:
        L.append(
            f"| aligned smooth flat (the sweep) | {fmt_value(ref['depth'], '.3g')} | "
            f"{'never' if ref['leaves_at'] is None else format(ref['leaves_at'], '.3g')} | "
            f"{ref['n_in']} / {ref['n_cells']} | 1 | — | reference |"
        )
    for f in ana["faces"]:
        kr = f["K_over_aligned_range"]
        ktxt = "—" if kr is None else f"{f['K_over_aligned_median']:.3g} [{kr[0]:.3g}–{kr[1]:.3g}]"
        L.append(
            f"| {f['label']} | {fmt_value(f['depth'], '.3g')} | "
            f"{'never' if f['leaves_at'] is None else format(f['leaves_at'], '.3g')} | "
            f"{f['n_in']} / {f['n_cells']} | {ktxt} | {f.get('reference', '—')} | "
            f"{VERDICTS[f['verdict']].split(':')[0]} |"
        )
    L.append("")
    for f in ana["faces"]:
        L.append(f"{f['surface']}, {f['label']}: {VERDICTS[f['verdict']]}.\n")
    return L
