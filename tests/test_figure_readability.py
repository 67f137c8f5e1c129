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
