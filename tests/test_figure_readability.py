# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Pictures a reader can read (issue 41, item 4), on the figure objects and rendered images.

``bem.png``'s ratio panel labels values where its curves lie; ``psd.png`` runs wavelength to
the right and puts the unit on its y axis; ``fractal_fits.png`` says which points were
fitted; the ``analyze`` figure of a scan names the file and its size; ``truncation.png``
keeps its axes off the surface, labels that do not collide, a height scale and a caption
that says once what red means. References: the data plotted, the file's grid, the map's
heights, and the same picture drawn without annotations.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

pytest.importorskip("matplotlib")


def _labelled_ticks(axis) -> list[float]:
    """The major tick values of a matplotlib axis that carry a label, inside the view."""
    ax = axis.axes
    ax.figure.canvas.draw()
    lo, hi = sorted(axis.get_view_interval())
    return [
        t.get_loc()
        for t in axis.get_major_ticks()
        if t.label1.get_text() and lo <= t.get_loc() <= hi
    ]


def test_bem_ratio_panel_labels_values_where_its_curves_lie():
    from warptrunc.plot import plot_bem_check

    d = np.array([0.5, 1.0, 1.5, 2.0, 3.0, 4.0]) * 1e-6
    load = np.array([0.73, 0.58, 0.42, 0.38, 0.40, 0.52])  # F'/F_BEM (a bem-check at 128²)
    stiff = np.array([0.62, 0.41, 0.32, 0.35, 0.51, 0.75])  # k'/k_BEM
    area = np.array([1.14, 1.21, 1.46, 2.26, 4.9, 8.7])  # A'/A_BEM
    f = np.geomspace(1, 100, d.size)
    res = SimpleNamespace(
        depth=d,
        bem_load=f,
        trunc_load=f * load,
        bem_stiffness=f * 1e6,
        trunc_stiffness=f * 1e6 * stiff,
        area_ratio=area,
        load_ratio=load,
        stiffness_ratio=stiff,
        converged=np.ones(d.size, bool),
    )
    fig = plot_bem_check(res)
    ratio = fig.axes[2]
    ticks = _labelled_ticks(ratio.yaxis)
    below = min(load.min(), stiff.min()), max(load.max(), stiff.max())
    inside = [t for t in ticks if below[0] <= t <= below[1]]
    assert inside, f"no labelled tick within the curves below 1 ({below}): {ticks}"
    assert 1.0 in ticks and len(ticks) <= 8
    import matplotlib.pyplot as plt

    plt.close(fig)


@pytest.fixture(scope="module")
def surf():
    from warptrunc.wm import wm_surface

    return wm_surface(2.5, 100e-6, L=0.5e-3, n=128, Rt=10e-6, seed=4, device="cpu")


def test_psd_wavelength_increases_to_the_right_and_y_axis_has_the_unit(surf):
    from warptrunc import plot
    from warptrunc.spectra import profile_psd, radial_psd

    both = plot.psd([radial_psd(surf), profile_psd(surf)], Wr=100e-6)
    ax = both.axes[0]
    lo, hi = ax.get_xlim()
    assert lo < hi and not ax.xaxis_inverted()
    # the x data are the wavelengths 1/f: the left end is the shortest
    x = ax.lines[0].get_xdata()
    assert ax.transData.transform((x.min(), 1.0))[0] < ax.transData.transform((x.max(), 1.0))[0]
    assert "m$^4$" in ax.get_ylabel() and "m$^3$" in ax.get_ylabel()
    one = plot.psd(radial_psd(surf)).axes[0]
    assert one.get_ylabel() == "PSD C(f) (m$^4$)"


def test_fractal_fits_legend_tells_the_two_point_families_apart(surf):
    from warptrunc import plot
    from warptrunc.fractal import fractal_dimensions

    fits = fractal_dimensions(surf, ["vs", "tri"], device="cpu")
    assert not fits["vs"].fitted.all()  # this panel has points outside the fit range
    fig = plot.fractal_fits(fits)
    vs = next(a for a in fig.axes if a.get_title().startswith("vertical sections"))
    leg = vs.get_legend()
    assert leg is not None
    labels = [t.get_text() for t in leg.get_texts()]
    assert "fitted" in labels and "outside the fit range" in labels
    # the hollow markers are those outside the range, as many as the fit left out
    hollow = next(ln for ln in vs.lines if ln.get_label() == "outside the fit range")
    assert len(hollow.get_xdata()) == int((~fits["vs"].fitted).sum())


def test_analyze_figure_of_a_scan_names_the_file_and_its_size(tmp_path, monkeypatch):
    from warptrunc import plot
    from warptrunc.cli import main

    z = np.random.default_rng(0).normal(size=(128, 160)) * 1e-6
    p = tmp_path / "sample 7.txt"
    np.savetxt(p, z)
    seen = {}
    real = plot.stiffness_load

    def spy(*a, **kw):
        seen["title"] = kw.get("title")
        return real(*a, **kw)

    monkeypatch.setattr(plot, "stiffness_load", spy)
    code = main(
        [
            "analyze",
            "--input",
            str(p),
            "--dx",
            "2e-6",
            "--out",
            str(tmp_path / "o"),
            "--device",
            "cpu",
            "--fit-range",
            "legacy",
            "--min-pixels",
            "1",
        ]
    )
    assert code == 0
    title = seen["title"]
    assert title.splitlines()[0] == "sample 7.txt"
    assert "160×128 px" in title and "320×256 µm" in title  # 160 × 2 µm by 128 × 2 µm


# --- truncation.png ---------------------------------------------------------------------------


def _pv():
    return pytest.importorskip("pyvista")


def test_render_axes_stay_off_the_surface(surf):
    """Annotated and bare oblique panels share their camera (a spare panel holds the caption):
    wherever the annotations changed the picture, the bare one shows background, not surface."""
    _pv()
    from warptrunc.render import RenderSettings, render_truncation

    o = RenderSettings(depth_fractions=(0.1, 0.2, 0.3, 0.4, 0.5), window_size=(780, 440))
    a = render_truncation(surf, settings=o, device="cpu").image[:220, :260].astype(int)
    bare = o.replace(annotate=False)
    b = render_truncation(surf, settings=bare, device="cpu").image[:220, :260].astype(int)
    surface = b.min(-1) < 250
    drawn = np.abs(a - b).max(-1) > 40
    assert drawn.sum() > 500  # ticks, labels, titles, the height bar
    assert (drawn & surface).sum() == 0


@pytest.mark.parametrize("top_view", [False, True], ids=["oblique", "top"])
def test_render_labels_do_not_collide_and_show_the_height_scale(surf, top_view):
    _pv()
    from warptrunc.render.scene import Panel, Scene, vtk_quiet

    scene = Scene(surf, 1, 10.0)
    with vtk_quiet():
        panel = Panel(scene, (520, 440), top_view=top_view, lighting=False, annotate=True, ve=10.0)
        try:
            panel.frame(np.zeros(scene.shape, bool), "ω")
        finally:
            panel.close()
    ov = panel.overlay
    boxes = ov.boxes
    for i, b in enumerate(boxes):
        assert 0 <= b[0] and b[2] <= 520 and 0 <= b[1] and b[3] <= 440, b
        for c in boxes[:i]:
            assert b[2] < c[0] or c[2] < b[0] or b[3] < c[1] or c[3] < b[1], (b, c)
    texts = [t[1] for t in ov.texts]
    assert "x (µm)" in texts and "y (µm)" in texts
    # the corner both axes start from is labelled once (the ramp's top is 0 too)
    assert texts.count("0") == (2 if top_view else 1)
    if top_view:  # grey ramp from the lowest to the highest height, below the top (µm)
        z = surf.heights.astype(np.float64)
        assert ov.ramp is not None
        low = f"{(z.min() - z.max()) * 1e6:.3g}".replace("-", "−")
        assert low in texts and "0" in texts
    else:  # a bar of the largest 1-2-5 height not above R_t = 10 µm
        assert "height\n10 µm" in texts


def test_render_caption_says_once_what_red_means(surf):
    _pv()
    from warptrunc.render import RenderSettings, render_truncation

    o = RenderSettings(depth_fractions=(0.3,), window_size=(200, 200), downsample=2)
    r = render_truncation(surf, settings=o, device="cpu")
    assert r.caption.count("red") <= 2 and r.caption.count("red:") == 1
    assert "red = " not in r.caption and "fraction of its pixels" in r.caption


# --- figures that say no more than their data -------------------------------------------------


def _points_under_legend(ax) -> int:
    """Data vertices (lines and markers, in display coordinates) inside the legend's box."""
    ax.figure.draw_without_rendering()
    leg = ax.get_legend()
    if leg is None:
        return 0
    box = leg.get_window_extent()
    n = 0
    for ln in ax.get_lines():
        xy = np.asarray(ln.get_xydata(), dtype=float)
        if not len(xy):
            continue
        p = ax.transData.transform(xy)
        p = p[np.isfinite(p).all(axis=1)]
        n += int(((p[:, 0] >= box.x0) & (p[:, 0] <= box.x1) & (p[:, 1] >= box.y0)
                  & (p[:, 1] <= box.y1)).sum())  # fmt: skip
    return n


def test_alpha_vs_D_legend_covers_no_point_and_names_the_hollow_ones():
    pd = pytest.importorskip("pandas")
    from warptrunc import plot

    rng = np.random.default_rng(3)
    rows = [(d, 0.01, s, 0.5 + 0.3 * (d - 2.2) + 0.05 * rng.standard_normal(), None)
            for d in (2.2, 2.5, 2.8) for s in range(5)]  # fmt: skip
    rows[0] = (2.2, 0.01, 0, 1.05, "not worth reading: fit: α = 1.05 is outside (0, 1]")
    df = pd.DataFrame(rows, columns=["D_in", "delta", "seed", "alpha", "fit_error"])
    df["min_pixels"] = 10
    ax = plot.alpha_vs_D(df).axes[0]
    assert _points_under_legend(ax) == 0
    assert _labelled_ticks(ax.xaxis) == [2.2, 2.5, 2.8]  # one tick per D of the sweep


def test_stiffness_figure_marks_a_fit_not_worth_reading():
    from types import SimpleNamespace

    from warptrunc import plot

    F = np.geomspace(1e-8, 1e-5, 40)
    curve = SimpleNamespace(load=F, F_over_EA=F, Ec_over_E=20 * F**0.6)
    fit = SimpleNamespace(alpha=1.181, beta=3e3, r2=0.8, F_over_EA_min=1e-7, F_over_EA_max=1e-6)
    ok = SimpleNamespace(alpha=0.6, beta=20.0, r2=1.0, F_over_EA_min=1e-8, F_over_EA_max=1e-5)
    fig = plot.stiffness_load([curve, curve], [ok, fit], labels=["Eq. 2", "islands"],
                              flags=[None, "not worth reading: islands fit: r² = 0.8"])  # fmt: skip
    fig.draw_without_rendering()
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    flagged = [t for t in labels if "1.181" in t]
    assert flagged and all("not worth reading" in t for t in flagged)
    assert not any("not worth reading" in t for t in labels if "0.600" in t)
    assert len(_labelled_ticks(ax.yaxis)) >= 3


def test_island_number_says_the_plateau_was_never_left():
    from types import SimpleNamespace

    from warptrunc import plot

    frac = np.linspace(0, 0.5, 51)
    curve = SimpleNamespace(depth_fraction=frac, normalised_island_number=np.sin(np.pi * frac))
    ind = SimpleNamespace(max_growth_depth=0.2, fractal_depth=0.5, peak_depth=0.45, Rt=1.0,
                          fractal_depth_censored=True)  # fmt: skip
    labels = [t.get_text() for t in plot.island_number(curve, ind).axes[0].get_legend().get_texts()]
    assert not any(t.startswith("end of constant slit exponent") for t in labels)
    assert any("≥ 50.0 % R$_t$" in t and "never left" in t for t in labels)
    done = SimpleNamespace(**{**vars(ind), "fractal_depth_censored": False, "fractal_depth": 0.3})
    labels = [
        t.get_text() for t in plot.island_number(curve, done).axes[0].get_legend().get_texts()
    ]
    assert "end of constant slit exponent: 30.0 % R$_t$" in labels


def test_ratio_vs_size_ticks_at_the_sizes_labels_inside_the_data_and_a_title():
    pd = pytest.importorskip("pandas")
    from warptrunc.plot import ratio_vs_size

    rows = []
    for d in (2.1, 2.9):
        for r in (1, 3, 10):
            rec = {"D_in": d, "size_ratio": r, "n": 16 * r, "depth_fraction_of_Rt": 0.1,
                   "seeds": 3}  # fmt: skip
            for m in ("eq2", "islands"):
                v = 1.4 + (d - 2) * (1.6 if m == "eq2" else 1.1) / (1 + r / 10)
                rec |= {f"{m}_k_ratio_mean": v, f"{m}_k_ratio_min": 0.95 * v,
                        f"{m}_k_ratio_max": 1.05 * v}  # fmt: skip
            rows.append(rec)
    fig = ratio_vs_size(pd.DataFrame(rows))
    fig.draw_without_rendering()  # the tick labels are made at a draw
    ax = fig.axes[0]
    assert _labelled_ticks(ax.xaxis) == [1.0, 3.0, 10.0]
    y = [v for rec in rows for k, v in rec.items() if k.endswith("_ratio_mean")]
    inside = [t for t in _labelled_ticks(ax.yaxis) if min(y) <= t <= max(y)]
    assert len(inside) >= 2, _labelled_ticks(ax.yaxis)
    title = fig.get_suptitle()
    assert "3 seeds" in title and "min–max" in title


def _reproduce_figure(monkeypatch, make, *args):
    """The Figure a ``warptrunc.reproduce.figures`` function saves (not written)."""
    from warptrunc.reproduce import figures

    saved = []
    monkeypatch.setattr(figures, "save_figure", lambda fig, out, name: saved.append(fig) or name)
    getattr(figures, make)(*args)
    return saved[0]


def test_fig10_one_series_for_identical_fit_ranges_signs_once_and_flags_hollow(monkeypatch):
    from warptrunc.reproduce.analysis import D_KEYS
    from warptrunc.sweep import linear_fit

    d = np.array([2.2, 2.2, 2.5, 2.5, 2.8, 2.8])
    a = 0.61 * d - 0.618 + np.array([0.01, -0.01, 0.02, -0.02, 0.0, 0.01])
    flag = [False, False, False, True, False, False]

    def fits(i):
        f = {"alpha": float(a[i]), "beta": 10.0}
        return f | ({"warning": "not worth reading: fit: r² = 0.8"} if flag[i] else {})

    rows = [{"D_in": float(x), "delta": 0.01, "fits": {"default": fits(i), "late": fits(i)},
             "D": {k: {"D": float(x)} for k in D_KEYS if k != "in"}} for i, x in enumerate(d)]  # fmt: skip
    keep = ~np.array(flag)
    line = linear_fit(d[keep], a[keep])
    paper = {"slope": 0.209, "intercept": 0.09, "r": 0.94}
    t3 = {k: {"ours": line, "paper": paper} for k in D_KEYS}
    ana = {"table3_alpha": {"default": t3, "late": t3},
           "table3_beta": {f: {"ours": {"b": 10.0, "p": -0.6}} for f in ("default", "late")}}  # fmt: skip
    g = {"fit_ranges": {"default": 10, "late": 0.05}, "rows": rows}
    fig = _reproduce_figure(monkeypatch, "fig10", {"group1": g, "group2": g}, ana, None)
    fig.draw_without_rendering()
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "fit range default = late" in labels  # one series, both ranges named
    assert sum(t.startswith("fit range") for t in labels) == 1
    assert "+ -" not in " ".join(labels) and any("·D − " in t for t in labels)
    hollow = [ln for ln in ax.lines if ln.get_markerfacecolor() == "none"]
    assert len(hollow) == 1 and len(hollow[0].get_xdata()) == 1
    assert fig.axes[5].get_title() and "paper" in fig.axes[5].get_title()


def test_fig7_paints_contact_in_the_contact_red_with_a_scale_bar(monkeypatch):
    from matplotlib.colors import to_rgba
    from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar

    from warptrunc.plot import CONTACT_COLOR

    row = {"status": "ok", "surface": "GB300s", "D_in": 2.5, "Wr_m": 20e-6, "Rt_m": 1e-6}
    res = {"table1": {"rows": [row], "n": 64, "L_m": 64e-6}}
    fig = _reproduce_figure(monkeypatch, "fig7", res, None, "cpu")
    for ax in fig.axes:
        contact = ax.get_images()[1].get_cmap()
        assert contact(1.0) == to_rgba(CONTACT_COLOR)
        bars = [c for c in ax.get_children() if isinstance(c, AnchoredSizeBar)]
        assert bars and bars[0].txt_label.get_text().endswith("µm")
    assert "red" in fig.get_suptitle()
