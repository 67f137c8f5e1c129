# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The matplotlib figure set: orientation, plotted data against NumPy references, files.

Figures are pyplot-free (Agg). The data drawn is read back from the artists and compared with
quantities computed here from the inputs (masks, area fractions, analytic power laws).
"""

from types import SimpleNamespace

import numpy as np
import pytest

from warptrunc import from_heights, plot, truncate
from warptrunc.stiffness import fit_power_law, stiffness_curve
from warptrunc.sweep import SweepTable
from warptrunc.wm import wm_surface


def _pixels(fig):
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())[..., :3].astype(int)


def _axes_box(fig, ax):
    """(row0, row1, col0, col1) of the axes in the canvas pixel array (row 0 at the top)."""
    b = ax.get_window_extent()
    h = fig.canvas.get_width_height()[1]
    return int(h - b.y1) + 3, int(h - b.y0) - 3, int(b.x0) + 3, int(b.x1) - 3


@pytest.mark.parametrize("axis", ["x", "y"])
def test_height_map_orientation_origin_lower(axis):
    """imshow(z, origin="lower", extent=(0, Lx, 0, Ly)): x to the right, y up."""
    iy, ix = np.mgrid[0:40, 0:60]
    z = (ix if axis == "x" else iy).astype(np.float32) * 1e-7
    s = from_heights(z, 1e-5)
    fig = plot.height_map(s, cmap="gray")
    ax = fig.axes[0]
    im = ax.images[0]
    assert im.origin == "lower"
    np.testing.assert_allclose(im.get_extent(), (0, 600, 0, 400))  # µm
    np.testing.assert_allclose(np.asarray(im.get_array()), z * 1e6, rtol=1e-6)
    full = _pixels(fig)  # draws (and lays out) first
    r0, r1, c0, c1 = _axes_box(fig, ax)
    px = full[r0:r1, c0:c1, 0]
    if axis == "x":  # dark on the left, bright on the right
        assert px[:, :5].mean() < 40 and px[:, -5:].mean() > 215
    else:  # dark at the bottom (small y), bright at the top
        assert px[-5:, :].mean() < 40 and px[:5, :].mean() > 215
    assert ax.get_xlabel() == "x (µm)" and ax.get_ylabel() == "y (µm)"


def test_height_map_contact_overlay_is_the_numpy_mask():
    s = wm_surface(2.5, 100e-6, n=(64, 48), L=(1e-3, 0.75e-3), Rt=5e-6, seed=1, device="cpu")
    fig = plot.height_map(s, depth_fraction=0.3)
    over = np.asarray(fig.axes[0].images[1].get_array())
    z = s.heights
    ref = z >= np.float32(np.float64(z.max()) - 0.3 * s.Rt)
    np.testing.assert_array_equal(over[..., 3] > 0, ref)
    red = over[ref, :3]
    np.testing.assert_allclose(red, np.broadcast_to(np.array(plot.CONTACT_RGB) / 255, red.shape))
    assert f"A$_c$/A = {100 * ref.mean():.3g} %" in fig.axes[0].get_title()


def test_height_map_of_a_large_map_is_block_pooled_and_says_so(tmp_path):
    s = wm_surface(2.5, 100e-6, n=(300, 200), L=(1.5e-3, 1e-3), Rt=5e-6, seed=2, device="cpu")
    fig = plot.height_map(s, depth_fraction=0.2, max_pixels=64, path=tmp_path / "h.png")
    ax = fig.axes[0]
    assert "shown in 5×5 blocks" in ax.get_title()
    shown = np.asarray(ax.images[0].get_array())
    z = s.heights.astype(np.float64)
    np.testing.assert_allclose(shown[0, 0], z[:5, :5].mean() * 1e6, rtol=1e-6)
    np.testing.assert_allclose(shown.shape, (40, 60))
    mask = s.heights >= np.float32(np.float64(s.heights.max()) - 0.2 * s.Rt)
    pooled = mask.reshape(40, 5, 60, 5).any(axis=(1, 3))
    np.testing.assert_array_equal(np.asarray(ax.images[1].get_array())[..., 3] > 0, pooled)
    assert (tmp_path / "h.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_area_fraction_plots_the_counts():
    s = wm_surface(2.5, 100e-6, n=64, Rt=5e-6, seed=1, device="cpu")
    c = truncate(s, 20, max_depth_fraction=0.5, device="cpu")
    fig = plot.area_fraction(c)
    x, y = fig.axes[0].lines[0].get_data()
    z = s.heights
    ref = [
        np.count_nonzero(z >= t) / z.size
        for t in (np.float64(z.max()) - c.depth).astype(np.float32)
    ]
    np.testing.assert_allclose(y, 100 * np.array(ref))
    np.testing.assert_allclose(x, np.linspace(0, 50, 21))
    fig = plot.area_fraction(c, relative=False)
    np.testing.assert_allclose(fig.axes[0].lines[0].get_xdata(), c.depth * 1e6)
    assert "µm" in fig.axes[0].get_xlabel()


def test_stiffness_load_keeps_the_analyze_signature(tmp_path):
    s = wm_surface(2.5, 100e-6, n=64, Rt=10e-6, seed=1, device="cpu")
    sc = stiffness_curve(truncate(s, 50, max_depth_fraction=0.3, device="cpu"))
    fit = fit_power_law(sc, min_pixels=3)
    fig = plot.stiffness_load(
        sc, fit, labels=["truncation analysis"], title="t", path=tmp_path / "k.png"
    )
    ax = fig.axes[0]
    x, y = ax.lines[0].get_data()
    sel = sc.load > 0
    np.testing.assert_array_equal(x, sc.F_over_EA[sel])
    np.testing.assert_array_equal(y, sc.Ec_over_E[sel])
    fx, fy = ax.lines[1].get_data()
    np.testing.assert_allclose(fy, fit.beta * fx**fit.alpha, rtol=1e-12)
    assert fx[0] == pytest.approx(fit.F_over_EA_min) and fx[-1] == pytest.approx(fit.F_over_EA_max)
    assert ax.get_xscale() == ax.get_yscale() == "log"
    assert (tmp_path / "k.png").stat().st_size > 10_000


def _power_law_curve(beta, alpha, x):
    return SimpleNamespace(load=x, F_over_EA=x, Ec_over_E=beta * x**alpha)


def _fit(beta, alpha, lo, hi):
    return SimpleNamespace(alpha=alpha, beta=beta, r2=1.0, F_over_EA_min=lo, F_over_EA_max=hi)


def test_stiffness_load_group_draws_geometric_mean_and_sd_band():
    """Seeds y_i = β_i x^α: log-linear, so the mean is (Π β_i)^{1/n} x^α and the band ± sd of log β."""
    betas = np.array([0.5, 1.0, 2.0])
    group = [
        _power_law_curve(b, 0.6, np.geomspace(1e-8 * (1 + i), 1e-5, 40))
        for i, b in enumerate(betas)
    ]
    other = _power_law_curve(0.3, 0.8, np.geomspace(1e-8, 1e-5, 40))
    fits = [[_fit(b, a, 1e-7, 1e-6) for b, a in zip(betas, (0.58, 0.6, 0.62), strict=True)], None]
    fig = plot.stiffness_load([group, other], fits, labels=["D = 2.5", "single"])
    ax = fig.axes[0]
    x, y = ax.lines[0].get_data()
    assert x[0] == pytest.approx(3e-8) and x[-1] == pytest.approx(1e-5)  # common range
    gm = np.exp(np.log(betas).mean())
    np.testing.assert_allclose(y, gm * x**0.6, rtol=1e-9)
    band = ax.collections[0].get_paths()[0].vertices
    sd = np.log(betas).std(ddof=1)
    top = band[1 : len(x) + 1]  # fill_between: the upper edge is the first half after the start
    lo_hi = np.sort(np.stack([top[:, 1], band[len(x) + 2 : 2 * len(x) + 2, 1][::-1]]), axis=0)
    np.testing.assert_allclose(lo_hi[0], gm * np.exp(-sd) * x**0.6, rtol=1e-9)
    np.testing.assert_allclose(lo_hi[1], gm * np.exp(sd) * x**0.6, rtol=1e-9)
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "D = 2.5 (3 seeds, ±1 sd)" in legend
    assert any("α = 0.600 ± 0.020" in t for t in legend)
    # the mean fit: α mean, β geometric mean
    fx, fy = ax.lines[1].get_data()
    np.testing.assert_allclose(fy, gm * fx**0.6, rtol=1e-9)


def test_alpha_vs_D_from_summary_and_from_table():
    rows = {"D_in": [], "alpha": [], "min_pixels": [], "seed": []}
    rng = np.random.default_rng(0)
    for D in (2.1, 2.5, 2.9):
        for seed in range(4):
            rows["D_in"].append(D)
            rows["alpha"].append(0.3 * D - 0.1 + 0.01 * rng.standard_normal())
            rows["min_pixels"].append(10)
            rows["seed"].append(seed)
    table = SweepTable({k: np.array(v) for k, v in rows.items()})
    fig = plot.alpha_vs_D(table)
    ax = fig.axes[0]
    a = np.array(rows["alpha"]).reshape(3, 4)
    means = ax.containers[0].lines[0].get_ydata()
    np.testing.assert_allclose(means, a.mean(axis=1))
    fitted = np.polyfit([2.1, 2.5, 2.9], a.mean(axis=1), 1)
    line = next(ln for ln in ax.lines if ln.get_linestyle() == "-")
    np.testing.assert_allclose(line.get_ydata(), np.polyval(fitted, [2.1, 2.9]))
    paper = next(ln for ln in ax.lines if ln.get_linestyle() == ":")
    np.testing.assert_allclose(paper.get_ydata(), [0.209 * 2.1 + 0.090, 0.209 * 2.9 + 0.090])
    summary = {
        "fit_ranges": {
            "10": {
                "per_D": [
                    {"D_in": 2.1, "alpha_mean": 0.5, "alpha_sd": 0.02, "n": 4},
                    {"D_in": 2.5, "alpha_mean": float("nan"), "alpha_sd": float("nan"), "n": 0},
                ],
                "alpha_vs_D": None,
            }
        }
    }
    fig = plot.alpha_vs_D(summary, min_pixels=10)
    np.testing.assert_allclose(fig.axes[0].containers[0].lines[0].get_ydata(), [0.5])
    with pytest.raises(ValueError, match="min_pixels = 100"):
        plot.alpha_vs_D(summary, min_pixels=100)


def _drawn_ticklabels(ax, axis):
    """Tick labels with text that the drawn axes shows, as (text, window bbox)."""
    ax.figure.canvas.draw()
    box = ax.get_window_extent()
    out = []
    for t in getattr(ax, f"get_{axis}ticklabels")(which="both"):
        if not (t.get_visible() and t.get_text()):
            continue
        bb = t.get_window_extent()
        c = (bb.x0 + bb.x1) / 2 if axis == "x" else (bb.y0 + bb.y1) / 2
        lo, hi = (box.x0, box.x1) if axis == "x" else (box.y0, box.y1)
        if lo - 1 <= c <= hi + 1:
            out.append((t.get_text(), bb))
    return out


def test_fractal_fits_tick_labels_are_readable():
    # the scales span about a decade and the triangulation's area ratios less than one:
    # matplotlib's default log ticks labelled minor ticks on top of each other (x) or gave
    # the triangulation panel a single y label
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from warptrunc.fractal import fractal_dimensions

    fits = fractal_dimensions(wm_surface(n=128, D=2.4, seed=1))
    fig = plot.fractal_fits(fits)
    FigureCanvasAgg(fig)
    for ax in [a for a in fig.axes if a.get_visible()]:
        for axis in ("x", "y"):
            labels = _drawn_ticklabels(ax, axis)
            assert 2 <= len(labels) <= 7, (ax.get_title(), axis, [t for t, _ in labels])
            for (t0, b0), (t1, b1) in zip(labels, labels[1:], strict=False):
                assert not b0.overlaps(b1), (ax.get_title(), axis, t0, t1)


def _alpha_table():
    pd = pytest.importorskip("pandas")
    d = np.array([2.1, 2.3, 2.5, 2.7, 2.9])
    rows = {"D_in": d, "size_ratio": 8.0, "n": 256, "range": "all"}
    # points wherever a legend could go: high and low at both ends
    for m, y in {
        "eq2": [0.95, 0.9, 0.5, 0.35, 0.3],
        "islands": [0.3, 0.4, 0.6, 0.9, 0.97],
        "bem": [0.5, 0.6, 0.65, 0.7, 0.8],
    }.items():
        rows[f"alpha_{m}_mean"] = y
        rows[f"alpha_{m}_min"] = np.array(y) - 0.02
        rows[f"alpha_{m}_max"] = np.array(y) + 0.02
    return pd.DataFrame(rows)


def test_alpha_vs_D_routes_legend_covers_no_data_point():
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = plot.alpha_vs_D_routes(_alpha_table())
    FigureCanvasAgg(fig)
    fig.canvas.draw()
    ax = fig.axes[0]
    legends = [lg for lg in [ax.get_legend(), *fig.legends] if lg is not None]
    assert len(legends) == 1 and len(legends[0].get_texts()) == 5
    lb = legends[0].get_window_extent()
    pts = np.concatenate(
        [
            ax.transData.transform(np.column_stack(line.get_data()))
            for line in ax.get_lines()
            if len(line.get_xdata()) == 5
        ]
    )
    assert len(pts) >= 15
    inside = (
        (pts[:, 0] >= lb.x0) & (pts[:, 0] <= lb.x1) & (pts[:, 1] >= lb.y0) & (pts[:, 1] <= lb.y1)
    )
    assert not inside.any()
    assert not lb.overlaps(ax.get_window_extent())  # outside the axes altogether
