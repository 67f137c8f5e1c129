# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stiffness against load and α against D (Fig. 9)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ._style import (
    FLAGGED_LABEL,
    PAPER_ALPHA_D,
    SPREAD_ALPHA,
    as_list,
    figure_doc,
    finish_axes,
    is_group,
    new_figure,
    readable_log_ticks,
    shade_band,
)


@figure_doc
def stiffness_load(
    curves: Any,
    fits: Any = None,
    *,
    labels: Any = None,
    flags: Any = None,
    title: str | None = None,
    spread: str = "sd",
    path: str | Path | None = None,
):
    """E_c/E against F/(E·A) in log–log, with the fitted power laws (the paper's Fig. 9).

    E is the Young's modulus of the rough body (``Ec_over_E``, ``beta``), as the paper's Fig. 9
    normalises; the contact-modulus form E_c/E* (``Ec_over_Estar``, ``beta_contact_modulus``)
    is a constant factor E/E* lower.

    Parameters
    ----------
    curves : StiffnessCurve, or sequence of StiffnessCurve or of groups
        Curves to draw (increments with zero load are skipped). An element that is itself a
        list of curves (the seeds of one case) is drawn as its geometric mean with a shaded
        spread over the F/(E·A) range all its curves cover.
    fits : PowerLawFit or sequence, optional
        One fit per curve (dashed line over its fit range); for a group, the list of its
        fits, drawn with mean α ± sd and the geometric mean β.
    labels : sequence of str, optional
        Legend labels, one per curve or group.
    flags : sequence of str or None, optional
        One per fit: why it is not worth reading (``fit_error`` of ``fit.json``, the sweep's
        :func:`~warptrunc.sweep.worth_reading`), or None. A flagged fit is drawn thin and
        dotted, its legend entry says "not worth reading", and it is no reading of the data.
    {title}
    spread : {"sd", "range"}
        Shaded band of a group: ±1 standard deviation of log(E_c/E), or min–max.
    {path}

    {returns}
    """

    curves = as_list(curves)
    if fits is not None:
        fits = as_list(fits)
        if len(fits) != len(curves):
            raise ValueError(
                f"need one fit (or list of fits) per curve, got {len(fits)} for {len(curves)}"
            )
    fig, axes = new_figure()
    ax = axes[0, 0]
    for i, c in enumerate(curves):
        lab = labels[i] if labels is not None else None
        if is_group(c):
            sels = [g.load > 0 for g in c]
            x, m, lo, hi = shade_band(
                [g.F_over_EA[s] for g, s in zip(c, sels, strict=True)],
                [g.Ec_over_E[s] for g, s in zip(c, sels, strict=True)],
                log=True,
                spread=spread,
            )
            what = "±1 sd" if spread == "sd" else "min–max"
            (line,) = ax.loglog(
                x, m, "-", lw=1.4, label=f"{lab} ({len(c)} seeds, {what})" if lab else None
            )
            ax.fill_between(x, lo, hi, color=line.get_color(), alpha=SPREAD_ALPHA, lw=0)
        else:
            sel = c.load > 0
            (line,) = ax.loglog(c.F_over_EA[sel], c.Ec_over_E[sel], "-", lw=1.2, label=lab)
        f = fits[i] if fits is not None else None
        if f is None:
            continue
        if is_group(f):
            f = [g for g in f if g is not None]
            if not f:
                continue
            al = np.array([g.alpha for g in f])
            beta = float(np.exp(np.mean(np.log([g.beta for g in f]))))
            alpha = float(al.mean())
            sd = f" ± {al.std(ddof=1):.3f}" if al.size > 1 else ""
            xr = np.geomspace(
                np.exp(np.mean(np.log([g.F_over_EA_min for g in f]))),
                np.exp(np.mean(np.log([g.F_over_EA_max for g in f]))),
                50,
            )
            text = f"fit α = {alpha:.3f}{sd}, β = {beta:.3g} (E$_c$/E)"
        else:
            alpha, beta = f.alpha, f.beta
            xr = np.geomspace(f.F_over_EA_min, f.F_over_EA_max, 50)
            text = f"fit α = {f.alpha:.3f}, β = {f.beta:.3g} (E$_c$/E), r² = {f.r2:.3f}"
        color = "k" if len(curves) == 1 else line.get_color()
        if flags is not None and flags[i]:
            ax.loglog(
                xr,
                beta * xr**alpha,
                ":",
                color=color,
                lw=1.0,
                alpha=0.7,
                zorder=3,
                label=f"{text} — not worth reading (fit_error)",
            )
            continue
        ax.loglog(xr, beta * xr**alpha, "--", color=color, lw=1.6, zorder=3, label=text)
    ax.set_xlabel("normalised load F/(E·A)")
    ax.set_ylabel("normalised stiffness E$_c$/E (E: Young's modulus)")
    ax.get_xlim(), ax.get_ylim()  # the autoscaled limits, which the ticks below freeze
    readable_log_ticks(ax.xaxis)
    readable_log_ticks(ax.yaxis)
    return finish_axes(fig, ax, path, title=title, which="both")


@figure_doc
def alpha_vs_D(
    summary: Any,
    *,
    min_pixels: int | None = None,
    paper: bool = True,
    title: str | None = None,
    path: str | Path | None = None,
):
    """Exponent α against D_in: mean ± sd over the seeds per δ, the line α(D_in), and the
    fits left out drawn hollow (Fig. 10, Table 3).

    The means, error bars and lines use only the fits worth reading
    (:func:`warptrunc.sweep.worth_reading`, the filter of ``warptrunc sweep``'s summary):
    a fit flagged ``fit_error`` is drawn as a hollow marker at its α and enters neither a
    mean nor a line. The statistics are over the seeds (independent surfaces); each δ is its
    own series, never pooled.

    Parameters
    ----------
    summary : dict or DataFrame or SweepTable
        :func:`warptrunc.sweep.alpha_summary`'s dict (``fit_ranges`` → {key: {"per_D":
        [...], "alpha_vs_D": [...], "flagged": [...]}}, as ``summary.json`` of
        ``examples/parametric_sweep.py`` holds it), or a sweep's cases table
        (:func:`warptrunc.sweep.load`) or :class:`~warptrunc.sweep.SweepTable`, summarised so.
    min_pixels : int, optional
        Draw this fit range only (default: every fit range in ``summary``).
    paper : bool
        Also draw the paper's line α = 0.209·D_in + 0.090.
    {title}
    {path}

    {returns}
    """

    ranges = _alpha_ranges(summary)
    if min_pixels is not None:
        ranges = {k: v for k, v in ranges.items() if k == str(int(min_pixels))}
        if not ranges:
            raise ValueError(f"no fit range with min_pixels = {min_pixels} in the summary")
    fig, axes = new_figure()
    ax = axes[0, 0]
    d_all: list[float] = []
    several_ranges = len(ranges) > 1
    any_flagged = False
    series = [
        (k, delta)
        for k, v in sorted(ranges.items(), key=lambda kv: _range_order(kv[0]))
        for delta in dict.fromkeys(r.get("delta") for r in v["per_D"])
    ]
    d_values = sorted({r["D_in"] for v in ranges.values() for r in v["per_D"]})
    # series side by side at each D (a tenth of the closest spacing between them), so that
    # equal values (the δ of one seed give one α) stay visible
    step = 0.1 * (min(np.diff(d_values)) if len(d_values) > 1 else 0.1) / max(1, len(series) - 1)
    for i, (k, delta) in enumerate(series):
        v = ranges[k]
        rows_all = v["per_D"]
        lines = {line.get("delta"): line for line in v.get("alpha_vs_D") or []}
        shift = step * (i - (len(series) - 1) / 2) if len(series) > 1 else 0.0
        rows = [
            r
            for r in rows_all
            if r.get("delta") == delta and r["n"] > 0 and np.isfinite(r["alpha_mean"])
        ]
        flagged = [f for f in v.get("flagged", []) if f.get("delta") == delta]
        if not rows and not flagged:
            continue
        name = ", ".join(
            ([f"min_pixels = {k}" if k[0].isdigit() else k] if several_ranges else [])
            + ([f"δ = {delta:g}"] if delta is not None else [])
        )
        color = None
        if rows:
            d = np.array([r["D_in"] for r in rows], dtype=float) + shift
            a = np.array([r["alpha_mean"] for r in rows], dtype=float)
            sd = [r["alpha_sd"] if np.isfinite(r["alpha_sd"]) else 0.0 for r in rows]
            d_all.extend(d)
            n = sorted({int(r["n"]) for r in rows})
            seeds = f"{n[0]}" if len(n) == 1 else f"{n[0]}–{n[-1]}"
            eb = ax.errorbar(
                d,
                a,
                yerr=sd,
                fmt="o",
                ms=5,
                capsize=3,
                label=(f"{name}: " if name else "")
                + f"mean ± sd over {seeds} seed{'s' if n[-1] != 1 else ''}",
            )
            color = eb[0].get_color()
        if flagged:
            any_flagged = True
            (h,) = ax.plot(
                [f["D_in"] + shift for f in flagged],
                [f["alpha"] for f in flagged],
                ls="none",
                marker="o",
                ms=6,
                mfc="none",
                mew=1.2,
                color=color,
            )
            color = h.get_color()
            d_all.extend(f["D_in"] for f in flagged)
        line = lines.get(delta)
        if line and rows:
            x = np.array([d.min(), d.max()])
            sign = "+" if line["intercept"] >= 0 else "−"
            slope = f"{line['slope']:.3f}".replace("-", "−")
            ax.plot(
                x,
                line["slope"] * (x - shift) + line["intercept"],
                "-",
                color=color,
                lw=1.2,
                label=f"α = {slope}·D$_{{in}}$ {sign} "
                f"{abs(line['intercept']):.3f} (r = {line['r']:.2f})",
            )
    if any_flagged:
        ax.plot([], [], ls="none", marker="o", ms=6, mfc="none", color="0.4", label=FLAGGED_LABEL)
    if paper and d_all:
        x = np.array([min(d_all), max(d_all)])
        ax.plot(
            x,
            PAPER_ALPHA_D[0] * x + PAPER_ALPHA_D[1],
            ":",
            color="k",
            lw=1.4,
            label="paper: α = 0.209·D$_{in}$ + 0.090",
        )
    if 0 < len(d_values) <= 8:
        ax.set_xticks(d_values, [f"{d:g}" for d in d_values])
    ax.set_xlabel("input fractal dimension D$_{in}$")
    ax.set_ylabel("stiffness exponent α")
    return finish_axes(fig, ax, path, title=title)


def _range_order(key: str) -> tuple[int, float]:
    """Sort key of a fit range: the ``min_pixels`` counts first, then the fractions."""
    if key.startswith("fraction="):
        return (1, float(key.split("=", 1)[1]))
    return (0, float(key))


def _alpha_ranges(summary: Any) -> dict:
    """{key: {"per_D": [...], "alpha_vs_D": [...], "flagged": [...]}} from a summary or a table."""
    if isinstance(summary, dict):
        return dict(summary["fit_ranges"])
    from ..sweep.stats import alpha_summary  # the sweep package (and Warp) only for a table

    return alpha_summary(summary)["fit_ranges"]
