# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation sections of a rough surface at 10–50 % of R_t, contact in red (the paper's Fig. 7)
=============================================================================================

What it shows
    A WM surface (D_in = 2.5, W_r = 100 µm, L = 1 mm, R_t = 10 µm) rendered off-screen with
    pyvista: one panel per depth ω = 10, 20, 30, 40, 50 % R_t, the pixels with
    z ≥ z_top − ω in red over the grey surface, heights exaggerated, axes in µm. Also a top
    view (orthographic: its red pixels measure A_c/A), the VTK file for ParaView and,
    with ``--animate``, a GIF of the truncation deepening. Large maps are drawn in blocks of
    f×f pixels whose share of red is the fraction of their pixels in contact (so the red
    measures A_c/A; ``--pooling any`` paints a block red when any pixel touches instead, which
    shows every spot but overstates the area); f is printed and written into the picture.
    docs/truncation_sections.png is ``--n 2048 --palette`` (truncation.png).

Key steps
    ``wm_surface`` → ``render_truncation`` (oblique panels and the top view, off-screen) →
    ``export_vtk`` (heights and the first-contact depth per pixel) → ``animate_truncation``.
    Needs pyvista (``pip install pyvista``).

Run::

    python examples/render_truncated_section.py --n 2048 --out results/render
    python examples/render_truncated_section.py --quick --out results/render   # 128², seconds
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from warptrunc.io.vtk import export_vtk
from warptrunc.render import (
    AnimationSettings,
    RenderSettings,
    animate_truncation,
    render_truncation,
)
from warptrunc.wm import wm_surface


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ...")
    ap.add_argument("--n", type=int, default=1024, help="pixels per side")
    ap.add_argument("--seed", type=int, default=1, help="phase seed")
    ap.add_argument("--D", type=float, default=2.5, help="fractal dimension D_in")
    ap.add_argument("--out", type=Path, default=Path("results/render"), help="output folder")
    ap.add_argument(
        "--size",
        type=int,
        nargs=2,
        default=[1560, 880],
        metavar=("W", "H"),
        help="picture size in pixels",
    )
    ap.add_argument("--animate", action="store_true", help="also write truncation.gif")
    ap.add_argument(
        "--pooling",
        choices=["area", "any"],
        default="area",
        help="block colour: contact fraction ('area') or red when any pixel touches ('any')",
    )
    ap.add_argument(
        "--palette",
        action="store_true",
        help="re-save the PNGs with 256 colours (about half the size; the docs/ images)",
    )
    ap.add_argument("--quick", action="store_true", help="128², small pictures")
    ap.add_argument("--no-show", action="store_true", help="do not open the pictures")
    args = ap.parse_args(argv)
    size = tuple(args.size)
    if args.quick:
        args.n, size = 128, (780, 440)
    args.out.mkdir(parents=True, exist_ok=True)

    s = wm_surface(args.D, 100e-6, L=1e-3, n=args.n, Rt=10e-6, seed=args.seed, device=args.device)
    oblique = RenderSettings(window_size=size, pooling=args.pooling)
    r = render_truncation(s, args.out / "truncation.png", settings=oblique, device=args.device)
    top = render_truncation(
        s,
        args.out / "truncation_top.png",
        settings=oblique.replace(top_view=True),
        device=args.device,
    )
    vti = export_vtk(
        s, args.out / "surface.vti", n_increments=50 if args.quick else 200, device=args.device
    )
    written = [r.path, top.path, vti]
    if args.palette:
        for p in (r.path, top.path):
            _palette(p)
    if args.animate:
        frames = AnimationSettings(frames=6, frame_size=(320, 260)) if args.quick else None
        a = animate_truncation(s, args.out / "truncation.gif", animation=frames, device=args.device)
        written.append(a.path)
    (args.out / "render.json").write_text(
        json.dumps({"oblique": r.to_dict(), "top": top.to_dict()}, indent=2, default=list) + "\n"
    )
    print(r.caption)
    for d, f, af in zip(r.depth, r.depth_fraction, r.area_fraction, strict=True):
        print(f"  ω = {d * 1e6:.3g} µm ({100 * f:.0f} % R_t): A_c/A = {100 * af:.3g} %")
    print("wrote " + ", ".join(str(w) for w in written))
    if not args.no_show:
        import matplotlib.pyplot as plt

        for res in (r, top):
            plt.figure(figsize=(12, 7))
            plt.imshow(res.image)
            plt.axis("off")
        plt.show()
    return 0


def _palette(path: Path) -> None:
    """Re-save a PNG with an adaptive 256-colour palette, keeping its text chunks."""
    from PIL import Image
    from PIL.PngImagePlugin import PngInfo

    with Image.open(path) as im:
        info = PngInfo()
        for k, v in im.text.items():
            info.add_text(k, v)
        q = im.convert("RGB").quantize(256, method=Image.Quantize.MEDIANCUT)
    q.save(path, pnginfo=info, optimize=True)


if __name__ == "__main__":
    if (status := main()) != 0:
        raise SystemExit(status)
