# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The contact-mechanics challenge's figure: a_r(p), ū(p), K(p) and the distributions at the
reference load, elastic (BEM) beside Persson, GW, BGT and truncation."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..compare.challenge import ChallengeStudy

__all__ = ["plot_challenge"]

_MODELS = (
    ("persson", "Persson", "C1", "-"),
    ("gw", "GW", "C2", "--"),
    ("bgt", "BGT", "C4", "-."),
    ("truncation", "truncation (Eq. 2)", "C3", ":"),
)


def plot_challenge(
    study: ChallengeStudy,
    path: str | Path | None = None,
    *,
    title: str | None = None,
    distributions: bool = True,
):
    """a_r, ū and K against p/E*, and (with ``distributions``) P(σ), P(u) and the patch areas.

    Parameters
    ----------
    study : ChallengeStudy
        :func:`warptrunc.compare.challenge.challenge_study`.
    path : str or Path, optional
        PNG to save the figure to.
    title : str, optional
        Figure title.
    distributions : bool
        Add the second row: the distributions at the reference load.

    Returns
    -------
    matplotlib.figure.Figure

    Notes
    -----
    BEM points that are not resolved (fewer contact pixels than
    :data:`~warptrunc.compare.challenge.MIN_CONTACT_PIXELS`) or did not converge are drawn
    hollow; so are truncation's unresolved rows. The coarser grid of the grid study is drawn
    as small grey points. Lengths in µm, pressures in MPa, stiffness in MPa/µm.
    """
    import matplotlib.pyplot as plt

    from ..compare.challenge import MIN_CONTACT_PIXELS
    from ._style import place_legend

    rows = 2 if distributions and study.distributions else 1
    fig, axes = plt.subplots(rows, 3, figsize=(14, 4.4 * rows), constrained_layout=True)
    axes = np.atleast_2d(axes)
    x = study.pressure / study.contact_modulus
    good = (study.n_contact >= MIN_CONTACT_PIXELS) & study.converged
    curves = (
        ("area_fraction", 1.0, "relative contact area a$_r$ = A/A$_0$"),
        ("mean_gap", 1e6, "mean gap ū (µm)"),
        ("stiffness", 1e-12, "stiffness K = −dp/dū (MPa/µm)"),
    )
    for ax, (name, scale, label) in zip(axes[0], curves, strict=True):
        y = getattr(study, name) * scale
        ax.plot(x[good], y[good], "ko", ms=5, label="BEM (periodic)")
        if (~good).any():
            ax.plot(x[~good], y[~good], "o", mfc="none", mec="k", ms=5, label="BEM, unresolved")
        if name != "stiffness":
            coarse = getattr(study, f"coarse_{name}") * scale
            if np.isfinite(coarse).any():
                n0 = study.grid_study.get("n", ["N"])[0]
                ax.plot(x, coarse, ".", color="0.6", ms=4, label=f"BEM at {n0}² (grid study)")
        for key, lab, color, ls in _MODELS:
            ym = getattr(study, f"{key}_{name}") * scale
            if key == "truncation":
                ok = study.truncation_resolved & np.isfinite(ym)
                ax.plot(x[ok], ym[ok], ls, color=color, label=lab)
                weak = ~study.truncation_resolved & np.isfinite(ym)
                if weak.any():
                    ax.plot(
                        x[weak],
                        ym[weak],
                        "s",
                        mfc="none",
                        mec=color,
                        ms=4,
                        label="truncation, unresolved",
                    )
            else:
                ax.plot(x, ym, ls, color=color, label=lab)
        ax.set_xscale("log")
        ax.set_xlabel("nominal pressure p/E*")
        ax.set_ylabel(label)
        if name != "mean_gap":
            ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
    k = study.kappa
    if k.get("bem") is not None:
        axes[0, 0].set_title(
            f"κ: BEM {k['bem']:.2f}, Persson {k['persson']:.2f}, BGT {k['bgt']:.2f}",
            fontsize=9,
        )
    sl = study.stiffness_slope
    if sl.get("bem") is not None:
        axes[0, 2].set_title(
            f"d ln K/d ln p: BEM {sl['bem']:.2f}, Persson {sl['persson']:.2f}", fontsize=9
        )
    for ax in axes[0]:
        place_legend(ax, fontsize=7)
    if rows == 2:
        _distribution_row(axes[1], study)
    if title:
        fig.suptitle(title)
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def _distribution_row(ax, study: ChallengeStudy) -> None:
    from ._style import place_legend

    d = study.distributions
    ref = d["reference_pressure_over_contact_modulus"]
    pr = d["pressure"]
    s = np.asarray(pr["stress_Pa"]) / 1e6
    ax[0].step(s, np.asarray(pr["bem_density_per_Pa"]) * 1e6, where="mid", color="k", label="BEM")
    ax[0].plot(s, np.asarray(pr["persson_density_per_Pa"]) * 1e6, "-", color="C1", label="Persson")
    ax[0].plot(s, np.asarray(pr["gw_density_per_Pa"]) * 1e6, "--", color="C2", label="GW")
    ax[0].set(
        xlabel="contact pressure σ (MPa)",
        ylabel="P(σ) (1/MPa)",
        yscale="log",
        title=f"pressure at p/E* = {ref:g}",
    )
    ga = d["gap"]
    u = np.asarray(ga["gap_m"]) * 1e6
    ax[1].step(u, np.asarray(ga["bem_density_per_m"]) * 1e-6, where="mid", color="k", label="BEM")
    ax[1].plot(u, np.asarray(ga["persson_density_per_m"]) * 1e-6, "-", color="C1", label="Persson")
    ax[1].plot(
        u, np.asarray(ga["gw_density_per_m"]) * 1e-6, "--", color="C2", label="GW (rigid flat at d)"
    )
    ax[1].step(
        u,
        np.asarray(ga["truncation_density_per_m"]) * 1e-6,
        where="mid",
        color="C3",
        ls=":",
        label="truncation (Eq. 2)",
    )
    ax[1].set(xlabel="gap u (µm)", ylabel="P(u) (1/µm)", title=f"gap at p/E* = {ref:g}")
    pa = d["patch_area"]
    a = np.asarray(pa["area_m2"]) * 1e12
    scale = 1e-24 * 1e12  # 1/m⁴ → 1/(µm² · µm²)
    for key, lab, color, style in (
        ("bem", f"BEM ({pa['bem_count']} patches)", "k", "o"),
        ("gw", f"GW ({pa['gw_count']:.0f})", "C2", "--"),
        ("truncation", f"truncation ({pa['truncation_count']})", "C3", "s"),
    ):
        y = np.asarray(pa[f"{key}_density_per_m4"]) * scale
        ok = y > 0
        ax[2].plot(
            a[ok], y[ok], style, color=color, mfc="none" if style == "s" else color, ms=4, label=lab
        )
    seen = np.concatenate(
        [np.asarray(pa[f"{k}_density_per_m4"]) * scale for k in ("bem", "truncation")]
    )
    seen = seen[seen > 0]
    if seen.size:  # GW's Gaussian tail falls by hundreds of decades: keep the counted range
        ax[2].set_ylim(seen.min() / 30, seen.max() * 30)
    ax[2].set(
        xlabel="patch area a (µm²)",
        ylabel="patches per µm² of A₀ per µm² of a",
        xscale="log",
        yscale="log",
        title=f"contact patches at p/E* = {ref:g}",
    )
    for a_ in ax:
        a_.grid(True, which="both", alpha=0.3)
        place_legend(a_, fontsize=7)
