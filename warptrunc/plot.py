# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""All matplotlib figures of warptrunc, in one style.

matplotlib is imported inside the functions, so ``import warptrunc`` stays light. Every
function takes result objects, returns the ``matplotlib.figure.Figure`` and, with ``path=``,
also saves a PNG. Lengths on axes are in µm, as the paper's figures.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

UM = 1e6  # m → µm on axes
FIGSIZE = (5.0, 4.0)
DPI = 150
CONTACT_RGB = (214, 39, 40)  # contact (truncated) areas, as the paper's red; also in render.py
CONTACT_COLOR = "#d62728"  # the same red for matplotlib
SPREAD_ALPHA = 0.25  # shaded spread over seeds
HEIGHT_CMAP = "viridis"  # height maps; "gray" under a red contact overlay
PAPER_ALPHA_D = (0.209, 0.090)  # the paper's α = 0.209·D_in + 0.090 (Table 3, D_in)


def _figure(figsize: tuple[float, float] = FIGSIZE, ncols: int = 1, nrows: int = 1):
    """A pyplot-free Figure (renders with Agg, needs no display) and its axes grid."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(figsize[0] * ncols, figsize[1] * nrows), dpi=DPI, layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False)
    return fig, axes


def _finish(fig: Any, path: str | Path | None) -> Any:
    if path is not None:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=DPI)
    return fig


def _as_list(x: Any) -> list:
    """A single result object or a sequence of them, as a list."""
    return list(x) if isinstance(x, (list, tuple)) else [x]


def _is_group(x: Any) -> bool:
    """A group of seeds of one case: a list/tuple of result objects (drawn as mean ± spread)."""
    return isinstance(x, (list, tuple))


def _length_axes(ax: Any, x: str = "x", y: str = "y") -> None:
    """Label both axes as lengths in µm."""
    ax.set_xlabel(f"{x} (µm)")
    ax.set_ylabel(f"{y} (µm)")


def _band(xs: list, ys: list, *, log: bool, n: int = 200, spread: str = "sd"):
    """Mean and spread over curves (x_i, y_i), on a grid over the x range they all cover.

    In log mode x and y are interpolated and averaged as logarithms (geometric mean and
    sd). Returns (grid, centre, lower, upper); spread "sd" is ±1 sample standard deviation,
    "range" is min–max.
    """
    import numpy as np

    f = np.log if log else np.asarray
    inv = np.exp if log else np.asarray
    lo = max(float(np.min(x)) for x in xs)
    hi = min(float(np.max(x)) for x in xs)
    if not hi > lo:
        raise ValueError("the curves of a group share no x range; plot them separately")
    grid = np.geomspace(lo, hi, n) if log else np.linspace(lo, hi, n)
    v = np.stack(
        [
            np.interp(f(grid), f(np.asarray(x)), f(np.asarray(y)))
            for x, y in zip(xs, ys, strict=True)
        ]
    )
    c = v.mean(axis=0)
    if spread == "range":
        a, b = v.min(axis=0), v.max(axis=0)
    elif spread == "sd":
        s = v.std(axis=0, ddof=1) if len(xs) > 1 else np.zeros_like(c)
        a, b = c - s, c + s
    else:
        raise ValueError(f"spread must be 'sd' or 'range', got {spread!r}")
    return grid, inv(c), inv(a), inv(b)


# --- stiffness and load (Fig. 9) ---------------------------------------------------------------


def stiffness_load(
    curves: Any,
    fits: Any = None,
    *,
    labels: Any = None,
    title: str | None = None,
    spread: str = "sd",
    path: str | Path | None = None,
):
    """E_c/E against F/(E·A) in log–log, with the fitted power laws (the paper's Fig. 9).

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
    title : str, optional
        Axes title.
    spread : {"sd", "range"}
        Shaded band of a group: ±1 standard deviation of log(E_c/E), or min–max.
    path : path, optional
        Save the figure as PNG here.
    """
    import numpy as np

    curves = _as_list(curves)
    if fits is not None:
        fits = _as_list(fits)
        if len(fits) != len(curves):
            raise ValueError(
                f"need one fit (or list of fits) per curve, got {len(fits)} for {len(curves)}"
            )
    fig, axes = _figure()
    ax = axes[0, 0]
    for i, c in enumerate(curves):
        lab = labels[i] if labels is not None else None
        if _is_group(c):
            sels = [g.load > 0 for g in c]
            x, m, lo, hi = _band(
                [g.F_over_EA[s] for g, s in zip(c, sels, strict=True)],
                [g.Ec_over_E[s] for g, s in zip(c, sels, strict=True)],
                log=True, spread=spread,
            )  # fmt: skip
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
        if _is_group(f):
            f = [g for g in f if g is not None]
            if not f:
                continue
            al = np.array([g.alpha for g in f])
            beta = float(np.exp(np.mean(np.log([g.beta for g in f]))))
            alpha = float(al.mean())
            sd = f" ± {al.std(ddof=1):.3f}" if al.size > 1 else ""
            xr = np.geomspace(
                np.exp(np.mean(np.log([g.F_over_EA_min for g in f]))),
                np.exp(np.mean(np.log([g.F_over_EA_max for g in f]))), 50,
            )  # fmt: skip
            text = f"fit α = {alpha:.3f}{sd}, β = {beta:.3g}"
        else:
            alpha, beta = f.alpha, f.beta
            xr = np.geomspace(f.F_over_EA_min, f.F_over_EA_max, 50)
            text = f"fit α = {f.alpha:.3f}, β = {f.beta:.3g}, r² = {f.r2:.3f}"
        color = "k" if len(curves) == 1 else line.get_color()
        ax.loglog(xr, beta * xr**alpha, "--", color=color, lw=1.6, zorder=3, label=text)
    ax.set_xlabel("normalised load F/(E·A)")
    ax.set_ylabel("normalised stiffness E$_c$/E")
    ax.grid(True, which="both", alpha=0.3)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=7)
    return _finish(fig, path)


def alpha_vs_D(
    summary: Any,
    *,
    min_pixels: int | None = None,
    paper: bool = True,
    title: str | None = None,
    path: str | Path | None = None,
):
    """Exponent α (mean ± sd over seeds) against D_in, with the fitted line (Fig. 10, Table 3).

    Parameters
    ----------
    summary : dict or SweepTable
        The ``summary.json`` content of ``examples/parametric_sweep.py`` (``fit_ranges`` →
        {min_pixels: {"per_D": [...], "alpha_vs_D": {...}}}), or a sweep's cases table
        (:func:`warptrunc.sweep.load`, a DataFrame) or :class:`~warptrunc.sweep.SweepTable`.
    min_pixels : int, optional
        Draw this fit range only (default: every fit range in ``summary``).
    paper : bool
        Also draw the paper's line α = 0.209·D_in + 0.090.
    title : str, optional
        Axes title.
    path : path, optional
        Save the figure as PNG here.
    """
    import numpy as np

    ranges = _alpha_ranges(summary)
    if min_pixels is not None:
        ranges = {k: v for k, v in ranges.items() if int(k) == int(min_pixels)}
        if not ranges:
            raise ValueError(f"no fit range with min_pixels = {min_pixels} in the summary")
    fig, axes = _figure()
    ax = axes[0, 0]
    d_all = []
    for k, v in sorted(ranges.items(), key=lambda kv: int(kv[0])):
        rows = [r for r in v["per_D"] if r["n"] > 0 and np.isfinite(r["alpha_mean"])]
        if not rows:
            continue
        d = np.array([r["D_in"] for r in rows], dtype=float)
        a = np.array([r["alpha_mean"] for r in rows], dtype=float)
        s = np.array([r["alpha_sd"] if np.isfinite(r["alpha_sd"]) else 0.0 for r in rows])
        d_all.extend(d)
        eb = ax.errorbar(d, a, yerr=s, fmt="o", ms=4, capsize=3, label=f"min_pixels = {k}")
        line = v.get("alpha_vs_D")
        if line:
            x = np.array([d.min(), d.max()])
            ax.plot(
                x, line["slope"] * x + line["intercept"], "-", color=eb[0].get_color(), lw=1.2,
                label=f"α = {line['slope']:.3f}·D$_{{in}}$ {'+' if line['intercept'] >= 0 else '−'} "
                f"{abs(line['intercept']):.3f} (r = {line['r']:.2f})",
            )  # fmt: skip
    if paper and d_all:
        x = np.array([min(d_all), max(d_all)])
        ax.plot(x, PAPER_ALPHA_D[0] * x + PAPER_ALPHA_D[1], ":", color="k", lw=1.4,
                label="paper: α = 0.209·D$_{in}$ + 0.090")  # fmt: skip
    ax.set_xlabel("input fractal dimension D$_{in}$")
    ax.set_ylabel("stiffness exponent α")
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=7)
    return _finish(fig, path)


def _alpha_ranges(summary: Any) -> dict:
    """{min_pixels: {"per_D": [...], "alpha_vs_D": line or None}} from a summary or a table."""
    if isinstance(summary, dict):
        return dict(summary["fit_ranges"])
    from .sweep import alpha_summary

    return alpha_summary(summary)["fit_ranges"]


# --- islands (Fig. 8) --------------------------------------------------------------------------


def island_number(
    curves: Any,
    indicators: Any = None,
    *,
    labels: Any = None,
    title: str | None = None,
    path: str | Path | None = None,
):
    """Normalised island number against depth, with the indicator depths (the paper's Fig. 8a).

    Parameters
    ----------
    curves : IslandCurve or sequence of them
        Island counts against depth; each is normalised by its maximum.
    indicators : Indicators or sequence, optional
        One per curve: the depth of the largest growth rate (dashed), the fractality depth
        (dotted) and the island-count peak (dash-dotted) are marked in the curve's colour.
    labels : sequence of str, optional
        Legend labels.
    path : path, optional
        Save the figure as PNG here.
    """
    curves = list(curves) if isinstance(curves, (list, tuple)) else [curves]
    if indicators is not None:
        indicators = list(indicators) if isinstance(indicators, (list, tuple)) else [indicators]
    fig, axes = _figure()
    ax = axes[0, 0]
    marks = (
        ("max_growth_depth", "--", "max. growth rate"),
        ("fractal_depth", ":", "end of constant slit exponent"),
        ("peak_depth", "-.", "island-count peak"),
    )
    for i, c in enumerate(curves):
        lab = labels[i] if labels is not None else None
        (line,) = ax.plot(100 * c.depth_fraction, c.normalised_island_number, lw=1.2, label=lab)
        if indicators is not None and indicators[i] is not None:
            ind = indicators[i]
            for name, style, what in marks:
                d = getattr(ind, name)
                if d == d:  # not NaN
                    ax.axvline(
                        100 * d / ind.rt, ls=style, lw=1.0, color=line.get_color(),
                        label=(what if len(curves) > 1 else f"{what}: {100 * d / ind.rt:.1f} % R$_t$")
                        if i == 0 else None,
                    )  # fmt: skip
    ax.set_xlabel("truncation depth ω (% R$_t$)")
    ax.set_ylabel("normalised island number n/n$_{max}$")
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=7)
    return _finish(fig, path)


def slit_islands(
    curve: Any,
    *,
    min_pixels: int | None = None,
    title: str | None = None,
    path: str | Path | None = None,
):
    """Island perimeter against area, log–log, with slit-island fits (the paper's Fig. 8b).

    Parameters
    ----------
    curve : IslandCurve or sequence of IslandSizes
        The islands at a few depths (``IslandCurve.sizes``, from ``snapshot_depths=``).
    min_pixels : int, optional
        Smallest island in the fits (pixels); the curve's own by default, else 10. Smaller
        islands are drawn in grey.
    path : path, optional
        Save the figure as PNG here.
    """
    import numpy as np

    from .islands import MIN_PIXELS, slit_island_fit

    sizes = list(getattr(curve, "sizes", curve))
    if min_pixels is None:
        min_pixels = getattr(curve, "min_pixels", MIN_PIXELS)
    rt = getattr(curve, "rt", None)
    fig, axes = _figure()
    ax = axes[0, 0]
    for sz in sizes:
        if sz.n_islands == 0:
            continue
        big = sz.area_pixels >= min_pixels
        fit = slit_island_fit(sz, min_pixels=min_pixels)
        at = f"ω = {100 * sz.depth / rt:.1f} % R$_t$" if rt else f"ω = {sz.depth * UM:.3g} µm"
        (pts,) = ax.loglog(sz.area[big] * UM**2, sz.perimeter[big] * UM, ".", ms=2.5, alpha=0.6)
        ax.loglog(sz.area[~big] * UM**2, sz.perimeter[~big] * UM, ".", ms=2, color="0.75", zorder=0)
        if fit.exponent == fit.exponent:
            a = np.geomspace(sz.area[big].min(), sz.area[big].max(), 20)
            ax.loglog(
                a * UM**2, 10**fit.intercept * a**fit.exponent * UM, "-",
                color=pts.get_color(), lw=1.4,
                label=f"{at}: exponent {fit.exponent:.3f} (D = {fit.dimension:.2f}, "
                f"r² = {fit.r2:.3f}, {fit.n_islands} islands)",
            )  # fmt: skip
        else:
            pts.set_label(f"{at}: too few islands ≥ {min_pixels} px")
    ax.set_xlabel("island area A (µm²)")
    ax.set_ylabel("island perimeter L (µm)")
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title(title or f"slit islands (grey: < {min_pixels} pixels, not fitted)")
    ax.legend(fontsize=6)
    return _finish(fig, path)


# --- descriptors and fractal dimension (PSD, Fig. 10) ------------------------------------------

_METHOD_LABELS = {
    "tri": "triangulation D$_{tri}$",
    "box": "box counting D$_{box}$",
    "vs": "vertical sections D$_{vs}$",
    "sp": "power spectrum D$_{sp}$",
}


def psd(
    psds: Any,
    *,
    labels: Any = None,
    Wr: float | None = None,
    title: str | None = None,
    path: str | Path | None = None,
):
    """Power spectral densities against wavelength 1/f (µm), log–log.

    Parameters
    ----------
    psds : PSD or sequence of PSD
        From :func:`warptrunc.descriptors.radial_psd` (m⁴) or ``profile_psd`` (m³).
    labels : sequence of str, optional
        Legend labels; default the PSD kind.
    Wr : float, optional
        Roll-off wavelength W_r (m), drawn as a vertical line.
    path : path, optional
        Save the figure as PNG here.
    """
    psds = list(psds) if isinstance(psds, (list, tuple)) else [psds]
    fig, axes = _figure()
    ax = axes[0, 0]
    for i, p in enumerate(psds):
        unit = "m$^4$" if p.kind == "radial" else "m$^3$"
        lab = labels[i] if labels is not None else f"{p.kind} ({unit})"
        ax.loglog(UM / p.frequency, p.psd, "-", lw=1.0, label=lab)
    if Wr is not None:
        ax.axvline(Wr * UM, color="k", ls=":", lw=1.0, label=f"W$_r$ = {Wr * UM:.3g} µm")
    ax.invert_xaxis()
    ax.set_xlabel("wavelength 1/f (µm)")
    ax.set_ylabel("PSD C(f)")
    ax.grid(True, which="both", alpha=0.3)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=7)
    return _finish(fig, path)


def fractal_fits(fits: Any, *, title: str | None = None, path: str | Path | None = None):
    """The log–log fits behind each fractal dimension, one panel per method.

    Parameters
    ----------
    fits : dict of FractalFit
        ``{method: FractalFit}`` from :func:`warptrunc.fractal.fractal_dimensions`.
    path : path, optional
        Save the figure as PNG here.
    """
    import numpy as np

    items = list(fits.items())
    ncols = min(2, len(items))
    nrows = (len(items) + ncols - 1) // ncols
    fig, axes = _figure((4.0, 3.2), ncols=ncols, nrows=nrows)
    ylab = {
        "tri": "area ratio A/A$_{proj}$",
        "box": "cubes N(ε)",
        "vs": "⟨Δz²⟩ (m²)",
        "sp": "band variance (m²)",
    }
    for k, (m, f) in enumerate(items):
        ax = axes[k // ncols, k % ncols]
        x = f.scale * UM
        ax.loglog(x, f.measure, "o", ms=3, mfc="none", color="0.5")
        ax.loglog(x[f.fitted], f.measure[f.fitted], "o", ms=3, color="C0")
        xs = np.geomspace(f.fit_range[0] or x[f.fitted].min() / UM, f.fit_range[1], 20)
        xs = xs[(xs >= f.scale[f.fitted].min() * 0.999) & (xs <= f.scale[f.fitted].max() * 1.001)]
        ax.loglog(xs * UM, 10 ** (f.intercept + f.slope * np.log10(xs)), "--", color="k", lw=1.2)
        ax.set_title(f"{_METHOD_LABELS.get(m, m)} = {f.D:.3f} (r² = {f.r2:.3f})", fontsize=8)
        ax.set_xlabel("scale (µm)")
        ax.set_ylabel(ylab.get(m, "measure"))
        if m == "tri":  # ratios just above 1: plain numbers read better than 1×10⁰
            from matplotlib.ticker import FormatStrFormatter, NullFormatter

            ax.yaxis.set_major_formatter(FormatStrFormatter("%.6g"))
            ax.yaxis.set_minor_formatter(NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
    for k in range(len(items), nrows * ncols):
        axes[k // ncols, k % ncols].set_visible(False)
    if title:
        fig.suptitle(title)
    return _finish(fig, path)


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
    path : path, optional
        Save the figure as PNG here.
    """
    import numpy as np

    fig, axes = _figure()
    ax = axes[0, 0]
    d_in = np.asarray(d_in, dtype=float)
    for m, v in d_out.items():
        err = None if d_out_std is None else d_out_std.get(m)
        ax.errorbar(d_in, v, yerr=err, marker="o", ms=4, capsize=2, label=_METHOD_LABELS.get(m, m))
    ax.plot([2, 3], [2, 3], ":", color="k", lw=1.0, label="D$_{out}$ = D$_{in}$")
    ax.set_xlabel("input fractal dimension D$_{in}$")
    ax.set_ylabel("estimated fractal dimension D$_{out}$")
    ax.set_xlim(d_in.min() - 0.05, d_in.max() + 0.05)
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=7)
    return _finish(fig, path)


def calibration_history(cal: Any, *, path: str | Path | None = None):
    """The evaluations of a calibration: D_out against D_in in order, with the target band.

    Parameters
    ----------
    cal : Calibration
        From :func:`warptrunc.calibrate.calibrate`.
    path : path, optional
        Save the figure as PNG here.
    """
    fig, axes = _figure()
    ax = axes[0, 0]
    t = cal.target
    tol = cal.rtol * t.D
    ax.axhspan(t.D - tol, t.D + tol, color="C2", alpha=0.15, label=f"target ± {cal.rtol:.0%}")
    ax.axhline(t.D, color="C2", lw=1.0)
    ax.errorbar(
        cal.history_D_in, cal.history_D_out, yerr=cal.history_D_out_std, fmt="o", ms=4,
        capsize=2, color="C0", label="evaluations (mean ± sd over seeds)",
    )  # fmt: skip
    for i, (x, y) in enumerate(zip(cal.history_D_in, cal.history_D_out, strict=True)):
        ax.annotate(str(i + 1), (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.plot([cal.D_in], [cal.D_out], "*", ms=12, color="C3", label=f"D$_{{in}}$' = {cal.D_in:.3f}")
    ax.set_xlabel("D$_{in}$")
    ax.set_ylabel(f"D$_{{out}}$ ({t.method})")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return _finish(fig, path)


# --- height maps and truncated-area fraction ---------------------------------------------------


def height_map(
    surface: Any,
    *,
    depth: float | None = None,
    depth_fraction: float | None = None,
    max_pixels: int = 1024,
    pooling: str = "area",
    cmap: str | None = None,
    title: str | None = None,
    path: str | Path | None = None,
):
    """Height map z(x, y) in µm with a colour bar, optionally with the contact set in red.

    Parameters
    ----------
    surface : Surface
        The height map (m).
    depth : float, optional
        Overlay the contact set z ≥ float32(z_top − ω) at this depth ω (m) in red.
    depth_fraction : float, optional
        The same, with ω given as a fraction of R_t (dimensionless).
    max_pixels : int
        Larger maps are shown in blocks of mean height, and the title says so.
    pooling : {"area", "any"}
        Contact overlay of a block: ``"area"`` (default) red with an opacity equal to the
        fraction of its pixels in contact, so the red measures A_c/A; ``"any"`` (max-pooling)
        opaque red when any pixel touches, which shows every spot but overstates the area.
    cmap : str, optional
        Colour map of the heights (default viridis, grey under a contact overlay).
    title : str, optional
        Axes title.
    path : path, optional
        Save the figure as PNG here.

    Notes
    -----
    ``imshow(z, origin="lower", extent=(0, Lx, 0, Ly))``: row iy of ``z`` is drawn at
    y = iy·dy, so x runs to the right and y up, as in the 3-D pictures.
    """
    import math

    import numpy as np

    from ._blocks import check_pooling, pool_blocks

    check_pooling(pooling)

    if depth is not None and depth_fraction is not None:
        raise ValueError("give depth or depth_fraction, not both")
    if depth_fraction is not None:
        depth = float(depth_fraction) * surface.rt
    z = surface.heights
    f = max(1, math.ceil(max(z.shape) / int(max_pixels)))
    shown = pool_blocks(z, f, "mean") if f > 1 else z
    fig, axes = _figure(figsize=(5.4, 4.4))
    ax = axes[0, 0]
    ext = (0.0, surface.lx * UM, 0.0, surface.ly * UM)
    im = ax.imshow(
        shown * UM, origin="lower", extent=ext, interpolation="nearest",
        cmap=cmap or (HEIGHT_CMAP if depth is None else "gray"),
    )  # fmt: skip
    fig.colorbar(im, ax=ax, label="height z (µm)", shrink=0.9)
    label = ""
    if depth is not None:
        thr = np.float32(np.float64(z.max()) - float(depth))
        mask = z >= thr  # as truncation.truncate compares
        frac = float(np.count_nonzero(mask)) / mask.size
        if f > 1:
            mask = pool_blocks(mask, f, "max" if pooling == "any" else "mean")
        rgba = np.zeros((*mask.shape, 4))
        rgba[..., :3] = [c / 255 for c in CONTACT_RGB]
        rgba[..., 3] = mask
        ax.imshow(rgba, origin="lower", extent=ext, interpolation="nearest")
        label = f"contact at ω = {depth * UM:.3g} µm ({100 * depth / surface.rt:.3g} % R$_t$): A$_c$/A = {100 * frac:.3g} %"
    _length_axes(ax)
    note = f"{surface.nx}×{surface.ny} px" + (f", shown in {f}×{f} blocks" if f > 1 else "")
    if f > 1 and depth is not None:
        note += (
            " (max-pooling: red where any pixel touches)"
            if pooling == "any"
            else " (red opacity = contact fraction)"
        )
    ax.set_title("\n".join(t for t in (title, label, note) if t), fontsize=8)
    return _finish(fig, path)


def area_fraction(
    curves: Any,
    *,
    labels: Any = None,
    relative: bool = True,
    log: bool = False,
    spread: str = "sd",
    title: str | None = None,
    path: str | Path | None = None,
):
    """Truncated-area fraction A_c/A (%) against truncation depth ω.

    Parameters
    ----------
    curves : TruncationCurve, or sequence of TruncationCurve or of groups
        Curves to draw; a list of curves (the seeds of one case) is drawn as the mean with a
        shaded spread.
    labels : sequence of str, optional
        Legend labels, one per curve or group.
    relative : bool
        Depth as a percentage of R_t; otherwise in µm.
    log : bool
        Logarithmic A_c/A axis (the first, small contacts).
    spread : {"sd", "range"}
        Shaded band of a group: ±1 standard deviation, or min–max.
    title : str, optional
        Axes title.
    path : path, optional
        Save the figure as PNG here.
    """
    curves = _as_list(curves)

    def xy(c):
        x = 100 * c.depth / c.rt if relative else c.depth * UM
        return x, 100 * c.area_fraction

    fig, axes = _figure()
    ax = axes[0, 0]
    for i, c in enumerate(curves):
        lab = labels[i] if labels is not None else None
        if _is_group(c):
            pts = [xy(g) for g in c]
            x, m, lo, hi = _band([p[0] for p in pts], [p[1] for p in pts], log=False, spread=spread)
            what = "±1 sd" if spread == "sd" else "min–max"
            (line,) = ax.plot(
                x, m, "-", lw=1.4, label=f"{lab} ({len(c)} seeds, {what})" if lab else None
            )
            ax.fill_between(x, lo, hi, color=line.get_color(), alpha=SPREAD_ALPHA, lw=0)
        else:
            ax.plot(*xy(c), "-", lw=1.2, label=lab)
    ax.set_xlabel("truncation depth ω (% R$_t$)" if relative else "truncation depth ω (µm)")
    ax.set_ylabel("truncated area A$_c$/A (%)")
    if log:
        ax.set_yscale("log")
    ax.grid(True, which="both", alpha=0.3)
    if title:
        ax.set_title(title)
    if labels is not None:
        ax.legend(fontsize=7)
    return _finish(fig, path)
