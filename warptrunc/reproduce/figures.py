# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The figures of ``warptrunc reproduce`` (PNG) from the stage results and analysis: Fig. 2, 5,
7, 8, 9, 10, the fit-range map, and those of the ``elastic`` and ``indentation`` stages (drawn
with the helpers of :mod:`warptrunc.reproduce.style`)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..truncation.curve import contact_index_map
from ..wm import wm_surface
from .analysis import D_KEYS
from .style import new_figure, save_figure

__all__ = ["D_LABELS", "fig_fit_range", "figures"]


D_LABELS = {
    "in": "D$_{in}$",
    "tri": "D$_{tri}$",
    "box": "D$_{box}$",
    "vs": "D$_{vs}$",
    "sp": "D$_{sp}$",
}


def fig2(res, out) -> str:
    c = res["asperity"]["curves"]
    fig, (ax,) = new_figure(w=6.4, h=5.0)
    for key, style, lab in (
        ("hertz", "k--", "Hertz"),
        ("plastic", "k:", "fully plastic"),
        ("truncation_exact", "r-", "truncation, closed form"),
    ):
        ax.loglog(c[f"{key}_load_norm"][1:], c[f"{key}_area_norm"][1:], style, label=lab)
    n = len(c["truncation_load_norm"])
    step = max(1, n // 60)
    ax.loglog(
        c["truncation_load_norm"][1::step],
        c["truncation_area_norm"][1::step],
        "ro",
        ms=3,
        mfc="none",
        label=f"truncation, {c['n']}² pixel sphere",
    )
    ms = sorted(
        float(k[len("storakers_m") : -len("_area_norm")])
        for k in c
        if k.startswith("storakers_m") and k.endswith("_area_norm")
    )
    cmap = __import__("matplotlib").colormaps["viridis"]
    for i, m in enumerate(ms):
        ax.loglog(
            c[f"storakers_m{m:g}_load_norm"][1:],
            c[f"storakers_m{m:g}_area_norm"][1:],
            "-",
            color=cmap(i / max(1, len(ms) - 1)),
            lw=1,
            label=f"Storåkers m$_B$ = {m:g}",
        )
    ax.set_xlabel("F/(E·πR²)")
    ax.set_ylabel("A$_c$/(πR²)")
    ax.set_title("Fig. 2: single asperity, d ≤ 100 ω$_c$")
    ax.legend(fontsize=7)
    return save_figure(fig, out, "fig2_asperity.png")


def _fixed_log_ticks(axis: Any, values: Any) -> None:
    """Major ticks of a log axis at ``values`` (the values the data were made at), labelled
    as plain numbers; no minor labels."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter, NullLocator

    axis.set_major_locator(FixedLocator(sorted(values)))
    axis.set_major_formatter(FuncFormatter(lambda v, _p: f"{v:g}"))
    axis.set_minor_locator(NullLocator())
    axis.set_minor_formatter(NullFormatter())


def fig5(res, ana, out) -> str:
    from ..plot._style import readable_log_ticks

    f5 = ana["fig5"]
    loads = res["fig5"]["loads"]
    fig, (a1, a2) = new_figure(2)
    incs = sorted({int(k.split("|")[1]) for k in f5})
    base = incs[0]
    ns = sorted({int(k.split("|")[0]) for k in f5 if int(k.split("|")[1]) == base})
    missing = []
    for i, L in enumerate(loads):
        y = [f5[f"{n}|{base}"][i] for n in ns]
        ys = [f5.get(f"{ns[-1]}|{k}", [None] * len(loads))[i] for k in incs]
        if all(v is None for v in (*y, *ys)):  # no map reaches this load: no series to list
            missing.append(f"{L:g}")
            continue
        (ln,) = a1.semilogy(
            ns, [np.nan if v is None else v for v in y], "o-", label=f"F/(EA) = {L:g}"
        )
        a2.semilogy(incs, [np.nan if v is None else v for v in ys], "o-", color=ln.get_color())
    a1.set_xscale("log", base=2)
    a2.set_xscale("log")
    _fixed_log_ticks(a1.xaxis, ns)
    _fixed_log_ticks(a2.xaxis, incs)
    for ax in (a1, a2):
        ax.get_ylim()
        readable_log_ticks(ax.yaxis, min_ticks=3)
        ax.grid(True, which="major", alpha=0.3)
    a1.set(xlabel="pixels per side (1 mm)", ylabel="E$_c$/E", title=f"Fig. 5a ({base} increments)")
    a2.set(xlabel="increments", ylabel="E$_c$/E", title=f"Fig. 5b ({ns[-1]}²)")
    note = (
        f"; F/(EA) = {', '.join(missing)} not reached on these maps (the deepest increment's "
        "load is below it)"
        if missing
        else ""
    )
    fig.suptitle(f"Fig. 5: E$_c$/E at fixed loads, mean over the seeds{note}", fontsize=9)
    if a1.get_legend_handles_labels()[0]:
        fig.legend(
            *a1.get_legend_handles_labels(),
            loc="outside lower center",
            ncols=4,
            fontsize=7,
            frameon=False,
        )
    return save_figure(fig, out, "fig5_convergence.png")


def fig7(res, out, device) -> str:
    from matplotlib.colors import ListedColormap
    from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar

    from ..plot._style import CONTACT_COLOR

    rows = [r for r in res["table1"]["rows"] if r["status"] == "ok"]
    r = next((x for x in rows if x["surface"] == "GB300s"), rows[0])
    n = res["table1"]["n"]
    s = wm_surface(
        r["D_in"], r["Wr_m"], L=res["table1"]["L_m"], n=n, Rt=r["Rt_m"], seed=0, device=device
    )
    fig, axs = new_figure(5, 1, w=2.6, h=2.8)
    fr = (0.1, 0.2, 0.3, 0.4, 0.5)
    idx = contact_index_map(s, np.asarray(fr) * s.Rt, device=device)
    lx, ly = s.lx * 1e6, s.ly * 1e6  # µm
    e = 10.0 ** np.floor(np.log10(lx / 4))
    bar = max(m * e for m in (1, 2, 5) if m * e <= lx / 4 * (1 + 1e-9))  # 1-2-5 µm, ≤ L/4
    red = ListedColormap([CONTACT_COLOR])  # the contact red of every picture (render's too)
    for k, (ax, f) in enumerate(zip(axs, fr, strict=True)):
        ext = (0.0, lx, 0.0, ly)
        ax.imshow(s.heights, cmap="gray", origin="lower", extent=ext)
        ax.imshow(
            np.ma.masked_where(idx > k, np.ones_like(s.heights)),
            cmap=red,
            origin="lower",
            extent=ext,
            vmin=0,
            vmax=1,
            interpolation="nearest",
        )
        ax.add_artist(
            AnchoredSizeBar(
                ax.transData,
                bar,
                f"{bar:g} µm",
                "lower right",
                pad=0.3,
                color="white",
                frameon=False,
                size_vertical=ly / 80,
                fontproperties={"size": 7},
            )
        )
        ax.set_title(f"ω = {int(f * 100)} % R$_t$", fontsize=9)
        ax.set_axis_off()
    fig.suptitle(
        f"Fig. 7: truncation sections of the simulated {r['surface']} ({n}² over "
        f"{s.lx * 1e3:.3g} mm); red: contact, the pixels within ω of the highest",
        fontsize=10,
    )
    return save_figure(fig, out, "fig7_sections.png")


def fig8(res, out) -> str:
    fig, (a1, a2) = new_figure(2)
    for name, s in res["islands"]["surfaces"].items():
        fr = np.asarray(s["seeds"][0]["depth_fraction"]) * 100
        nn = np.mean([x["normalised"] for x in s["seeds"]], axis=0)
        (ln,) = a1.plot(fr, nn, label=name)
        g = [x["indicators"].get("max_growth_rate_depth_percent_Rt") for x in s["seeds"]]
        g = [v for v in g if v is not None]
        if g:
            a1.axvline(np.mean(g), color=ln.get_color(), ls="--", lw=0.8)
        ex = np.array(
            [[np.nan if v is None else v for v in x["slit_exponent"]] for x in s["seeds"]]
        )
        a2.plot(fr, ex[0], color=ln.get_color(), lw=0.8, label=name)
        b = s["seeds"][0].get("slit_band")
        if b:  # the bootstrap band over islands at the snapshot depths
            nan = lambda v: [np.nan if x is None else x for x in v]  # noqa: E731
            a2.fill_between(
                b["percent_Rt"], nan(b["lo"]), nan(b["hi"]), color=ln.get_color(), alpha=0.25, lw=0
            )
            a2.plot(b["percent_Rt"], nan(b["exponent"]), "o", color=ln.get_color(), ms=3)
    a1.set(xlabel="depth (% R$_t$)", ylabel="normalised island number", title="Fig. 8a")
    a2.set(
        xlabel="depth (% R$_t$)",
        ylabel="slit-island exponent (L ∝ A$^x$)",
        title="Fig. 8b: seed 0, 95 % bootstrap band",
    )
    a1.legend(fontsize=8)
    return save_figure(fig, out, "fig8_islands.png")


def _mean_curves(rows, key, fit="default"):
    groups: dict[float, list] = {}
    for r in rows:
        groups.setdefault(r[key], []).append(r["curve"])
    return groups


def fig9(res, out) -> list[str]:
    from ..plot._style import place_legend, readable_log_ticks, settle_legends

    names = []
    for g, key, lab, tag in (
        (res["group1"], "delta", "δ", "a"),
        (res["group2"], "D_in", "D$_{in}$", "b"),
    ):
        fig, (ax,) = new_figure(w=6, h=4.6)
        for k, cs in sorted(_mean_curves(g["rows"], key).items()):
            x = np.exp(np.mean([np.log(np.maximum(c["F_over_EA"], 1e-300)) for c in cs], axis=0))
            y = np.exp(np.mean([np.log(np.maximum(c["Ec_over_E"], 1e-300)) for c in cs], axis=0))
            sel = x > 1e-299
            ax.loglog(x[sel], y[sel], label=f"{lab} = {k:g}")
        ax.set(xlabel="F/(E·A)", ylabel="E$_c$/E", title=f"Fig. 9{tag} (geometric mean over seeds)")
        ax.get_xlim(), ax.get_ylim()
        readable_log_ticks(ax.xaxis)
        readable_log_ticks(ax.yaxis, min_ticks=4)
        ax.grid(True, which="major", alpha=0.3)
        place_legend(ax)
        settle_legends(fig)
        names.append(save_figure(fig, out, f"fig9{tag}.png"))
    return names


def _line_text(f: dict[str, float]) -> str:
    """``0.610·D − 0.618, r = 0.935``: the sign of the intercept once."""
    sign = "−" if f["intercept"] < 0 else "+"
    slope = f"{f['slope']:.3f}".replace("-", "−")
    return f"{slope}·D {sign} {abs(f['intercept']):.3f}, r = {f['r']:.3f}"


def _same_fits(rows, a: str, b: str) -> bool:
    """Fit ranges ``a`` and ``b`` gave every row the same fit (α, β and flag): one series."""

    def num(v):
        return np.nan if v is None else float(v)

    return all(
        np.allclose(
            [num(r["fits"][a].get("alpha")), num(r["fits"][a].get("beta"))],
            [num(r["fits"][b].get("alpha")), num(r["fits"][b].get("beta"))],
            rtol=1e-9,
            equal_nan=True,
        )
        and bool(r["fits"][a].get("warning")) == bool(r["fits"][b].get("warning"))
        for r in rows
    )


def fig10(res, ana, out) -> str:
    """α against D by each method and β against δ: the fits worth reading filled, those flagged
    (``warning``: not worth reading) hollow and out of the lines; fit ranges that give the same
    line drawn once."""
    from ..plot._style import place_legend, settle_legends

    g2 = res["group2"]
    fig, axs = new_figure(3, 2, w=4.2, h=3.5)
    ranges = list(g2["fit_ranges"])
    for ax, k in zip(axs[:5], D_KEYS, strict=True):
        lines = {fit: ana["table3_alpha"][fit][k]["ours"] for fit in ranges}
        drawn: list[str] = []
        for fit, mk in zip(ranges, ("o", "s"), strict=False):
            if any(_same_fits(g2["rows"], d, fit) for d in drawn):
                continue  # identical points and line: named in the first one's label
            twins = [f for f in ranges if f != fit and _same_fits(g2["rows"], fit, f)]
            name = " = ".join([fit, *twins])
            pts = {"ok": ([], []), "flagged": ([], [])}
            for r in g2["rows"]:
                fr = r["fits"][fit]
                x = r["D_in"] if k == "in" else r.get("D", {}).get(k, {}).get("D")
                if fr.get("alpha") is not None and x is not None:
                    key = "flagged" if fr.get("warning") else "ok"
                    pts[key][0].append(x)
                    pts[key][1].append(fr["alpha"])
            (p,) = ax.plot(*pts["ok"], mk, ms=4, label=f"fit range {name}")
            if pts["flagged"][0]:
                ax.plot(*pts["flagged"], mk, mfc="none", ms=5, color=p.get_color(),
                        label=f"{name}: not worth reading (left out of the line)")  # fmt: skip
            f = lines[fit]
            xs = pts["ok"][0]
            if f and xs:
                xx = np.linspace(min(xs), max(xs), 2)
                ax.plot(
                    xx,
                    f["slope"] * xx + f["intercept"],
                    "-",
                    color=p.get_color(),
                    lw=1,
                    label=_line_text(f),
                )
            drawn.append(fit)
        pp = ana["table3_alpha"]["default"][k]["paper"]
        xx = np.linspace(2.0, 3.0, 2)
        ax.plot(xx, pp["slope"] * xx + pp["intercept"], "k--", lw=0.8,
                label=f"paper: {_line_text(pp)}")  # fmt: skip
        ax.set(xlabel=D_LABELS[k], ylabel="α")
        ax.grid(True, alpha=0.3)
        place_legend(ax, fontsize=6)
    ax = axs[5]
    g1 = res["group1"]
    fits_b = {fit: ana["table3_beta"][fit]["ours"] for fit in g1["fit_ranges"]}
    shown: list[str] = []
    for fit, mk in zip(g1["fit_ranges"], ("o", "s"), strict=False):
        pts = [
            (r["delta"], r["fits"][fit]["beta"])
            for r in g1["rows"]
            if r["fits"][fit].get("beta") and not r["fits"][fit].get("warning")
        ]
        f = fits_b[fit]
        if not pts or any(_same_fits(g1["rows"], d, fit) for d in shown):
            continue
        (p,) = ax.loglog(*zip(*pts, strict=True), mk, ms=4)
        if f:
            xx = np.array([min(x for x, _ in pts), max(x for x, _ in pts)])
            ax.loglog(
                xx,
                f["b"] * xx ** f["p"],
                "-",
                color=p.get_color(),
                lw=1,
                label=f"{fit}: β = {f['b']:.3g}·δ$^{{{f['p']:.3f}}}$",
            )
        shown.append(fit)
    flagged = [
        (r["delta"], r["fits"][fit]["beta"])
        for fit in list(g1["fit_ranges"])[:1]
        for r in g1["rows"]
        if r["fits"][fit].get("beta") and r["fits"][fit].get("warning")
    ]
    if flagged:
        ax.loglog(*zip(*flagged, strict=True), "o", mfc="none", ms=5, color="0.4",
                  label="not worth reading (left out)")  # fmt: skip
    if not shown:
        ax.text(0.5, 0.5, "no β worth reading", transform=ax.transAxes, ha="center", fontsize=8)
    xx = np.array([6.25e-4, 0.16])
    ax.loglog(xx, 0.0386 * xx**-1.122, "k--", lw=0.8, label="paper: 0.0386·δ$^{-1.122}$")
    ax.set(xlabel="δ = R$_t$/W$_r$", ylabel="β of E$_c$/E = β·[F/(E·A)]$^α$")
    ax.set_title(
        "β ∝ δ$^{−α}$ here: one surface scaled in height by δ (report, Table 3);\n"
        "the paper's β differs in magnitude and slope",
        fontsize=7,
    )
    ax.grid(True, which="major", alpha=0.3)
    place_legend(ax, fontsize=6)
    fig.suptitle(
        "Fig. 10: α against D by each method (one point per surface; hollow: not worth "
        "reading, out of the lines); β against δ"
    )
    settle_legends(fig)
    return save_figure(fig, out, "fig10.png")


def fig_fit_range(fm: dict[str, Any], out: Path) -> str:
    """Fit-range map: α(D) slope and α(2.5) against the fit range, Table 3 marked; β's exponent.

    Parameters
    ----------
    fm : dict of str to Any
        :func:`~warptrunc.reproduce.fitrange.fit_range_map`.
    out : Path
        Output folder.

    Returns
    -------
    str
        File name written (``fit_range_map.png``).
    """
    fig, axs = new_figure(3, 2, w=4.3, h=3.3)
    kinds = (
        ("min_pixels", "fit range: ≥ m contact pixels", "log"),
        ("fraction", "fit range: ≥ f × final contact pixels", "log"),
    )
    for row, (kind, xlabel, scale) in enumerate(kinds):
        rs = [r for r in fm["ranges"] if r["kind"] == kind]
        xs = [r["value"] for r in rs]
        a_s, a_a, a_b = axs[3 * row : 3 * row + 3]
        for k in D_KEYS:
            fs = [fm["alpha"][r["name"]][k] for r in rs]
            if all(f is None for f in fs):
                continue
            sl = [np.nan if f is None else f["slope"] for f in fs]
            (p,) = a_s.plot(xs, sl, "o-", ms=3, label=D_LABELS[k])
            a_s.axhline(fm["paper"][k]["slope"], color=p.get_color(), ls="--", lw=0.7)
            aa = [np.nan if f is None else f["alpha_2_5"] for f in fs]
            a_a.plot(xs, aa, "o-", ms=3, color=p.get_color(), label=D_LABELS[k])
            a_a.axhline(fm["paper"][k]["alpha_2_5"], color=p.get_color(), ls="--", lw=0.7)
        bs = [fm["beta"][r["name"]] for r in rs]
        a_b.plot(
            xs, [np.nan if b is None else b["p"] for b in bs], "o-", ms=3, label="p of β = b·δ^p"
        )
        a_b.plot(
            xs,
            [np.nan if b is None else b["minus_alpha"] for b in bs],
            "x:",
            label="−mean α, group 1",
        )
        a_b.axhline(fm["paper_beta"]["p"], color="k", ls="--", lw=0.7, label="paper −1.122")
        for ax, yl in (
            (a_s, "slope of α(D)"),
            (a_a, "α(2.5) of the α(D) line"),
            (a_b, "exponent p of β(δ)"),
        ):
            ax.set_xscale(scale)
            ax.set(xlabel=xlabel, ylabel=yl)
        a_s.legend(fontsize=6, title="dashed: Table 3", title_fontsize=6)
        a_b.legend(fontsize=6)
    fig.suptitle("Fit-range map: Table 3 re-fitted from the stored curves (dashed: the paper)")
    return save_figure(fig, out, "fit_range_map.png")


def figures(res: dict[str, Any], ana: dict[str, Any], out: Path, device=None) -> list[str]:
    """Write every figure into ``out``; returns the file names.

    Parameters
    ----------
    res : dict of str to Any
        Stage results (:func:`~warptrunc.reproduce.study.run_study`).
    ana : dict of str to Any
        Derived numbers (:func:`~warptrunc.reproduce.analysis.analyse`).
    out : Path
        Output folder.
    device : str, optional
        Warp device (Fig. 7 regenerates the calibrated surfaces).

    Returns
    -------
    list of str
        File names written: Fig. 2, 5, 7 (when a Table 1 row is ok), 8 (when the island stage
        has surfaces), 9, 10, the ``elastic`` stage's two figures and the ``indentation``
        stage's; a stage left out of ``res`` gives none.
    """
    names = []
    if "asperity" in res:
        names.append(fig2(res, out))
    if "fig5" in res:
        names.append(fig5(res, ana, out))
    if "table1" in res and any(r["status"] == "ok" for r in res["table1"]["rows"]):
        names.append(fig7(res, out, device))
    if "islands" in res and res["islands"]["surfaces"]:
        names.append(fig8(res, out))
    if "group1" in res and "group2" in res:
        names += fig9(res, out)
        names.append(fig10(res, ana, out))
    if "fit_range_map" in ana:
        names.append(fig_fit_range(ana["fit_range_map"], out))
    if "elastic" in res:
        from .elastic_report import elastic_figures

        names += elastic_figures(res["elastic"], out)
    if "indentation" in res:
        from .indentation.report import indentation_figures

        names += indentation_figures(res["indentation"], ana["indentation"], out)
    return names
