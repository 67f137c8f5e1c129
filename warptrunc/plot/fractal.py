# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Descriptors and fractal dimension: PSD, fractal fits, D_out against D_in, calibration
history (Fig. 10)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ._style import (
    UM,
    as_list,
    figure_doc,
    finish_axes,
    finish_figure,
    new_figure,
    readable_log_ticks,
)

_METHOD_LABELS = {
    "tri": "triangulation D$_{tri}$",
    "box": "box counting D$_{box}$",
    "vs": "vertical sections D$_{vs}$",
    "sp": "power spectrum D$_{sp}$",
}


@figure_doc
def psd(
    psds: Any,
    *,
    labels: Any = None,
    Wr: float | None = None,
    title: str | None = None,
    path: str | Path | None = None,
):
    """Power spectral densities against wavelength 1/f (µm), log–log, wavelength increasing
    to the right; the y axis carries the unit (m⁴ radial, m³ profile).

    Parameters
    ----------
    psds : PSD or sequence of PSD
        From :func:`warptrunc.descriptors.radial_psd` (m⁴) or ``profile_psd`` (m³).
    labels : sequence of str, optional
        Legend labels; default the PSD kind.
    Wr : float, optional
        Roll-off wavelength W_r (m), drawn as a vertical line.
    {title}
    {path}

    {returns}
    """
    psds = as_list(psds)
    fig, axes = new_figure()
    ax = axes[0, 0]
    units = {"radial": "m$^4$", "profile": "m$^3$"}
    for i, p in enumerate(psds):
        lab = labels[i] if labels is not None else p.kind
        ax.loglog(UM / p.frequency, p.psd, "-", lw=1.0, label=lab)
    if Wr is not None:
        ax.axvline(Wr * UM, color="k", ls=":", lw=1.0, label=f"W$_r$ = {Wr * UM:.3g} µm")
    ax.set_xlabel("wavelength 1/f (µm)")
    kinds = list(dict.fromkeys(p.kind for p in psds))
    unit = (
        units.get(kinds[0], "?")
        if len(kinds) == 1
        else ", ".join(f"{k}: {units.get(k, '?')}" for k in kinds)
    )
    ax.set_ylabel(f"PSD C(f) ({unit})")
    return finish_axes(fig, ax, path, title=title, which="both")


@figure_doc
def fractal_fits(fits: Any, *, title: str | None = None, path: str | Path | None = None):
    """The log–log fits behind each fractal dimension, one panel per method.

    Parameters
    ----------
    fits : dict of FractalFit
        ``{method: FractalFit}`` from :func:`warptrunc.fractal.fractal_dimensions`.
    title : str, optional
        Figure title (suptitle).
    {path}

    {returns}
    """

    items = list(fits.items())
    ncols = min(2, len(items))
    nrows = (len(items) + ncols - 1) // ncols
    fig, axes = new_figure((4.0, 3.2), ncols=ncols, nrows=nrows)
    ylab = {
        "tri": "area ratio A/A$_{proj}$",
        "box": "cubes N(ε)",
        "vs": "⟨Δz²⟩ (m²)",
        "sp": "band variance (m²)",
    }
    for k, (m, f) in enumerate(items):
        ax = axes[k // ncols, k % ncols]
        x = f.scale * UM
        out = ~np.asarray(f.fitted, dtype=bool)
        ax.loglog(
            x[out],
            f.measure[out],
            "o",
            ms=3,
            mfc="none",
            color="0.5",
            label="outside the fit range",
        )
        ax.loglog(x[f.fitted], f.measure[f.fitted], "o", ms=3, color="C0", label="fitted")
        xs = np.geomspace(f.fit_range[0] or x[f.fitted].min() / UM, f.fit_range[1], 20)
        xs = xs[(xs >= f.scale[f.fitted].min() * 0.999) & (xs <= f.scale[f.fitted].max() * 1.001)]
        ax.loglog(
            xs * UM,
            10 ** (f.intercept + f.slope * np.log10(xs)),
            "--",
            color="k",
            lw=1.2,
            label=f"fit, slope {f.slope:.3g}",
        )
        if out.any():  # two families of points: say which is which
            ax.legend(fontsize=7)
        ax.set_title(f"{_METHOD_LABELS.get(m, m)} = {f.D:.3f} (r² = {f.r2:.3f})", fontsize=8)
        ax.set_xlabel("scale (µm)")
        ax.set_ylabel(ylab.get(m, "measure"))
        # a few labelled ticks per axis: a range under a decade (the triangulation's area
        # ratios, the scales) would otherwise get overlapping minor labels or none at all
        readable_log_ticks(ax.xaxis, max_ticks=5)
        readable_log_ticks(ax.yaxis)
        ax.grid(True, which="both", alpha=0.3)
    for k in range(len(items), nrows * ncols):
        axes[k // ncols, k % ncols].set_visible(False)
    if title:
        fig.suptitle(title)
    return finish_figure(fig, path)


@figure_doc
def d_out_vs_d_in(
    d_in: Any,
    d_out: Any,
    *,
    d_out_std: Any = None,
    title: str | None = None,
    path: str | Path | None = None,
):
    """D_out of simulated surfaces against D_in, one line per method (cf. §3.2, Fig. 10).

    Parameters
    ----------
    d_in : (k,) array_like
        Input fractal dimensions (dimensionless).
    d_out : dict of (k,) array_like
        ``{method: D_out}`` (dimensionless).
    d_out_std : dict of (k,) array_like, optional
        Error bars (seed standard deviations).
    {title}
    {path}

    {returns}
    """

    fig, axes = new_figure()
    ax = axes[0, 0]
    d_in = np.asarray(d_in, dtype=float)
    for m, v in d_out.items():
        err = None if d_out_std is None else d_out_std.get(m)
        ax.errorbar(d_in, v, yerr=err, marker="o", ms=4, capsize=2, label=_METHOD_LABELS.get(m, m))
    ax.plot([2, 3], [2, 3], ":", color="k", lw=1.0, label="D$_{out}$ = D$_{in}$")
    ax.set_xlabel("input fractal dimension D$_{in}$")
    ax.set_ylabel("estimated fractal dimension D$_{out}$")
    ax.set_xlim(d_in.min() - 0.05, d_in.max() + 0.05)
    return finish_axes(fig, ax, path, title=title)


@figure_doc
def calibration_history(cal: Any, *, path: str | Path | None = None):
    """The evaluations of a calibration: D_out against D_in in order, with the target band.

    Parameters
    ----------
    cal : Calibration
        From :func:`warptrunc.calibrate.calibrate`.
    {path}

    {returns}
    """
    fig, axes = new_figure()
    ax = axes[0, 0]
    t = cal.target
    tol = cal.rtol * t.D
    ax.axhspan(t.D - tol, t.D + tol, color="C2", alpha=0.15, label=f"target ± {cal.rtol:.0%}")
    ax.axhline(t.D, color="C2", lw=1.0)
    ax.errorbar(
        cal.history_D_in,
        cal.history_D_out,
        yerr=cal.history_D_out_std,
        fmt="o",
        ms=4,
        capsize=2,
        color="C0",
        label="evaluations (mean ± sd over seeds)",
    )
    for i, (x, y) in enumerate(zip(cal.history_D_in, cal.history_D_out, strict=True)):
        ax.annotate(str(i + 1), (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.plot([cal.D_in], [cal.D_out], "*", ms=12, color="C3", label=f"D$_{{in}}$' = {cal.D_in:.3f}")
    ax.set_xlabel("D$_{in}$")
    ax.set_ylabel(f"D$_{{out}}$ ({t.method})")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return finish_figure(fig, path)
