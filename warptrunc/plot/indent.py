# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Indentation in silico against truncation: E_c/E against F/(E·A) as the paper's Fig. 6."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ._style import figure_doc, finish_figure, new_figure, place_legend

if TYPE_CHECKING:
    from ..indent import IndentationResult

__all__ = ["indentation"]

_MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")
_DRAWN = (  # (model, column, colour, label, solid fit line)
    (
        "elastic_plastic_partial",
        "E_c_partial_over_E",
        "C3",
        "elastic–plastic, {f:g} % unloading",
        True,
    ),
    ("elastic_plastic", "E_c_over_E", "C1", "elastic–plastic, initial slope (Barber)", False),
    ("elastic", "elastic_E_c_over_E", "C0", "elastic (H = ∞), initial slope", False),
    ("truncation", "truncation_E_c_over_E", "C2", "truncation (Eq. 2)", True),
)


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
        twice: the paper's partial-unloading secant red, Barber's initial slope orange); the
        cells a model's fit uses (``in_fit``: resolved, not saturated, converged) filled, the
        others hollow; each model's fit E_c/E = β·[F/(E·A)]^α drawn over the cells it used,
        α and β with their 95 % intervals in the legend. With ``hardness = inf`` the
        elastic–plastic model is the elastic one and is drawn once.
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
    for model, col, colour, label, solid in _DRAWN:
        if elastic_only and model.startswith("elastic_plastic"):
            continue
        y = np.asarray(cols[col], dtype=np.float64)
        ok = np.isfinite(y) & (y > 0)
        if not ok.any():
            continue
        used = result.fit_cells(model)["mask"]
        for i, d in enumerate([*keys, None] if has_flat else keys):
            sel = ok & (~np.isfinite(diam) if d is None else np.isclose(diam, d))
            for part, face in ((sel & used, colour), (sel & ~used, "none")):  # excluded: hollow
                ax.loglog(
                    x[part],
                    y[part],
                    _MARKERS[i % len(_MARKERS)],
                    ms=4,
                    ls="none",
                    color=colour,
                    mfc=face,
                    alpha=0.8,
                )
        fit = fits.get(model)
        text = label.format(f=100 * result.protocol.unload_fraction)
        if fit is not None:
            g = np.geomspace(fit.F_over_EA_min, fit.F_over_EA_max, 50)
            (a0, a1), (b0, b1) = fit.alpha_ci95, fit.beta_ci95
            ax.loglog(
                g,
                fit.beta * g**fit.alpha,
                "-" if solid else "--",
                color=colour,
                lw=1.2,
                label=f"{text}: α = {fit.alpha:.3f} [{a0:.3f}, {a1:.3f}], "
                f"β = {fit.beta:.3g} [{b0:.3g}, {b1:.3g}]",
            )
        else:
            ax.plot([], [], "-", color=colour, label=f"{text}: no fit (< 6 cells in_fit)")
    handles, _ = ax.get_legend_handles_labels()
    for i, d in enumerate([*keys, None] if has_flat else keys):
        name = "flat ≥ map" if d is None else f"d = {d * 1e6:.4g} µm"
        handles.append(
            Line2D(
                [],
                [],
                marker=_MARKERS[i % len(_MARKERS)],
                ls="none",
                color="0.3",
                mfc="0.3",
                label=name,
            )
        )
    handles.append(
        Line2D(
            [],
            [],
            marker="o",
            ls="none",
            color="0.3",
            mfc="none",
            label="hollow: left out of the fit (unresolved, saturated or not converged)",
        )
    )
    ax.set(xlabel="F/(E·A)", ylabel="E$_c$/E")
    ax.grid(True, which="both", alpha=0.3)
    m = result.material
    h = "∞" if elastic_only else f"{m.hardness / 1e9:.3g} GPa"
    ax.set_title(
        title or f"H = {h}, E = {m.E / 1e9:.3g} GPa, E* = {m.contact_modulus / 1e9:.4g} GPa",
        fontsize=9,
    )
    place_legend(ax, handles=handles, fontsize=7)  # off the points
    return finish_figure(fig, path)
