# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Indentation in silico against truncation: E_c/E against F/(E·A) as the paper's Fig. 6."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ._style import figure_doc, finish_figure, new_figure

if TYPE_CHECKING:
    from ..indent import IndentationResult

__all__ = ["indentation"]

_MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")
_DRAWN = (  # (model, column, colour, label, filled markers)
    ("elastic_plastic_partial", "E_c_partial_over_E", "C3", "elastic–plastic, {f:g} % unloading", True),
    ("elastic_plastic", "E_c_over_E", "C3", "elastic–plastic, initial slope (Barber)", False),
    ("elastic", "elastic_E_c_over_E", "C0", "elastic (H = ∞), initial slope", False),
    ("truncation", "truncation_E_c_over_E", "C2", "truncation (Eq. 2)", True),
)  # fmt: skip


@figure_doc
def indentation(
    result: IndentationResult,
    path: str | Path | None = None,
    *,
    title: str | None = None,
):
    """E_c/E against F/(E·A), log–log, for the three contact models, with their power laws.

    Parameters
    ----------
    result : IndentationResult
        From :func:`warptrunc.indent`.
    path : str or Path, optional
        Save the figure as PNG here.
    {title}

    Returns
    -------
    matplotlib.figure.Figure
        One marker shape per punch diameter, one colour per model (the elastic–plastic model
        twice: the paper's partial-unloading secant filled, Barber's initial slope open); each
        model's fit E_c/E = β·[F/(E·A)]^α drawn over the rows it used, α and β in the legend.
        Rows that did not converge are left out. With ``hardness = inf`` the elastic–plastic
        model is the elastic one and is drawn once.
    """
    from matplotlib.lines import Line2D

    fig, axes = new_figure((6.4, 4.8))
    ax = axes[0, 0]
    cols = result.to_dict()
    x = result.F_over_EA
    fits = result.fits()
    elastic_only = not np.isfinite(result.material.hardness)
    diam = result.punch_diameter
    keys = sorted({float(d) for d in diam[np.isfinite(diam)]})
    has_flat = bool(np.any(~np.isfinite(diam)))
    for model, col, colour, label, filled in _DRAWN:
        if elastic_only and model.startswith("elastic_plastic"):
            continue
        y = np.asarray(cols[col], dtype=np.float64)
        ok = np.isfinite(y) & (y > 0)
        conv = {"truncation": None}.get(model, "elastic_converged" if model == "elastic"
                                        else "converged")  # fmt: skip
        if conv is not None:
            ok &= np.asarray(cols[conv], dtype=bool)
        if not ok.any():
            continue
        for i, d in enumerate([*keys, None] if has_flat else keys):
            sel = ok & (~np.isfinite(diam) if d is None else np.isclose(diam, d))
            ax.loglog(x[sel], y[sel], _MARKERS[i % len(_MARKERS)], ms=4, ls="none",
                      color=colour, mfc=colour if filled else "none", alpha=0.8)  # fmt: skip
        fit = fits.get(model)
        text = label.format(f=100 * result.protocol.unload_fraction)
        if fit is not None:
            g = np.geomspace(fit.F_over_EA_min, fit.F_over_EA_max, 50)
            ax.loglog(g, fit.beta * g**fit.alpha, "-" if filled else "--", color=colour, lw=1.2,
                      label=f"{text}: α = {fit.alpha:.3f}, β = {fit.beta:.3g}")  # fmt: skip
        else:
            ax.plot([], [], "-", color=colour, label=f"{text}: no fit")
    handles, _ = ax.get_legend_handles_labels()
    for i, d in enumerate([*keys, None] if has_flat else keys):
        name = "flat ≥ map" if d is None else f"d = {d * 1e6:.4g} µm"
        handles.append(Line2D([], [], marker=_MARKERS[i % len(_MARKERS)], ls="none",
                              color="0.3", mfc="none", label=name))  # fmt: skip
    ax.legend(handles=handles, fontsize=7)
    ax.set(xlabel="F/(E·A)", ylabel="E$_c$/E")
    ax.grid(True, which="both", alpha=0.3)
    m = result.material
    h = "∞" if elastic_only else f"{m.hardness / 1e9:.3g} GPa"
    ax.set_title(title or f"H = {h}, E = {m.E / 1e9:.3g} GPa, E* = "
                 f"{m.contact_modulus / 1e9:.4g} GPa", fontsize=9)  # fmt: skip
    return finish_figure(fig, path)
