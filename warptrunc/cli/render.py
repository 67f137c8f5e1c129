# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Pictures of truncation sections (the paper's Fig. 7), off-screen with pyvista.

Writes OUT/truncation.png (the surface with its contact set in red at each depth, one panel per
depth) and OUT/render.json (depths, full-resolution A_c/A, down-sampling factor, vertical
exaggeration); optionally OUT/truncation.gif (or .mp4), an animation of the truncation
deepening, and OUT/surface.vti, the heights and first-contact depths for ParaView.

All or nothing: file names and extensions are checked before anything is computed, the files
are written under temporary names and moved into OUT only when every one of them is done.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from .._support.atomic import staged_output, strict_json
from .._support.provenance import provenance
from ..io.vtk import export_vtk
from ._common import (
    add_device,
    add_out,
    add_surface_source,
    check_increments,
    fraction,
    integer,
    positive,
    surface_from_args,
    warnings_of,
)

NAME = "render"
HELP = "render truncation sections (Fig. 7), an animation, a VTK file"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc render``."""
    add_surface_source(p)
    g = p.add_argument_group("picture")
    g.add_argument(
        "--depth-fractions", type=fraction(), nargs="+", default=[0.1, 0.2, 0.3, 0.4, 0.5],
        metavar="F",
        help="truncation depths as fractions of R_t, each in (0, 1], one panel each "
        "(dimensionless)",
    )  # fmt: skip
    g.add_argument(
        "--depths", type=positive("m"), nargs="+", default=None, metavar="OMEGA",
        help="truncation depths ω in metres, each in (0, R_t] of the map; override "
        "--depth-fractions",
    )  # fmt: skip
    g.add_argument("--top", action="store_true", help="orthographic view from above")
    g.add_argument(
        "--size", type=integer(16, 16384), nargs=2, default=None, metavar=("W", "H"),
        help="picture size in pixels (default 520×440 per panel)",
    )  # fmt: skip
    g.add_argument(
        "--ncols", type=integer(1), default=None, help="panels per row (default up to 3)"
    )
    g.add_argument(
        "--exaggeration", type=positive(), default=None,
        help="vertical exaggeration (dimensionless); default: R_t drawn as 1/10 of the side",
    )  # fmt: skip
    g.add_argument(
        "--downsample", type=integer(1), default=None,
        help="block side of the drawn mesh in pixels (default: about one block per screen "
        "pixel, at most 1024 blocks per side)",
    )  # fmt: skip
    g.add_argument(
        "--pooling", choices=["area", "any"], default="area",
        help="colour of a block of pixels: 'area' = share of red equal to the fraction of its "
        "pixels in contact (red measures A_c/A); 'any' = max-pooling, red when any pixel "
        "touches (shows every contact spot, overstates the area)",
    )  # fmt: skip
    g.add_argument(
        "--output",
        type=_file_name_with((".png",)),
        default="truncation.png",
        help="picture file name (.png) inside --out",
    )
    a = p.add_argument_group("animation and VTK export")
    a.add_argument(
        "--animate", type=_file_name_with((".gif", ".mp4")), nargs="?", const="truncation.gif", default=None, metavar="FILE",
        help="also write an animation (.gif, or .mp4 with imageio-ffmpeg) inside --out",
    )  # fmt: skip
    a.add_argument("--frames", type=integer(2, 100_000), default=26, help="animation frames")
    a.add_argument("--fps", type=positive(), default=8.0, help="animation frames per second")
    a.add_argument(
        "--max-depth-fraction", type=fraction(), default=0.5,
        help="last depth of the animation as a fraction of R_t (dimensionless)",
    )  # fmt: skip
    a.add_argument(
        "--vtk", type=_file_name_with((".vti", ".vtk")), nargs="?", const="surface.vti", default=None, metavar="FILE",
        help="also write heights and first-contact depths for ParaView (.vti or .vtk)",
    )  # fmt: skip
    a.add_argument(
        "--vtk-increments", type=integer(1, 10_000_000), default=200,
        help="depth increments n of the first-contact depths, up to ω = R_t",
    )  # fmt: skip
    add_device(p)
    add_out(p)


def _file_name(text: str) -> str:
    """A ``type=`` for a plain file name (written inside --out)."""

    if not text or Path(text).name != text or text in (".", ".."):
        raise argparse.ArgumentTypeError(f"must be a file name without folders, got {text!r}")
    return text


def _file_name_with(suffixes: tuple[str, ...]):
    """A ``type=`` for a plain file name ending in one of ``suffixes`` (checked at parse time)."""

    def parse(text: str) -> str:
        name = _file_name(text)
        if not name.lower().endswith(suffixes):
            raise argparse.ArgumentTypeError(f"must end in {' or '.join(suffixes)}, got {text!r}")
        return name

    parse.__name__ = "file name"
    return parse


def run(args: argparse.Namespace) -> int:
    """Render and write the outputs."""
    check_increments(args.vtk_increments, "--vtk-increments")
    names = [args.output, args.animate, args.vtk, "render.json"]
    names = [n for n in names if n]
    if len(set(names)) != len(names):
        raise ValueError(f"--output, --animate and --vtk must name different files, got {names}")
    if args.animate and args.animate.lower().endswith(".mp4"):
        try:
            import imageio.v2  # noqa: F401
        except ImportError:
            raise ValueError(
                "--animate: MP4 animations need imageio and ffmpeg (pip install imageio "
                "imageio-ffmpeg), or name a .gif"
            ) from None
    if args.out.joinpath(args.output).is_dir():
        raise ValueError(f"--output names a folder inside --out: {args.out / args.output}")
    s = surface_from_args(args)
    if args.depths is not None and max(args.depths) > s.Rt:
        raise ValueError(
            f"--depths must be in (0, R_t] = (0, {s.Rt:.6g}] m for this surface, got "
            f"{' '.join(f'{d:g}' for d in args.depths)} (metres; --depth-fractions takes "
            "fractions of R_t)"
        )
    with staged_output(args.out) as out:  # all or nothing
        r, written = _render(s, args, out)
    written = [args.out / p.relative_to(out) for p in written]
    print(r.caption)
    for d, f, af in zip(r.depth, r.depth_fraction, r.area_fraction, strict=True):
        print(f"  ω = {d * 1e6:.4g} µm ({100 * f:.3g} % R_t): A_c/A = {100 * af:.4g} %")
    print("wrote " + ", ".join(str(p) for p in written))
    return 0


def _render(s, args: argparse.Namespace, out):
    """(picture result, files written), every file under ``out``."""
    written = []
    if args.vtk:

        written.append(
            export_vtk(s, out / args.vtk, n_increments=args.vtk_increments, device=args.device)
        )
    try:
        from .. import render
    except ImportError as exc:  # pragma: no cover
        raise ValueError(str(exc)) from None  # rolls the staged files back
    try:
        r = render.render_truncation(
            s, out / args.output, depth_fractions=args.depth_fractions, depths=args.depths,
            top_view=args.top, window_size=args.size, ncols=args.ncols,
            vertical_exaggeration=args.exaggeration, downsample=args.downsample,
            pooling=args.pooling, device=args.device,
        )  # fmt: skip
        written.append(r.path)
        info = {"picture": r.to_dict()}
        if args.animate:
            a = render.animate_truncation(
                s, out / args.animate, max_depth_fraction=args.max_depth_fraction,
                n_frames=args.frames, fps=args.fps, top_view=args.top,
                vertical_exaggeration=args.exaggeration, downsample=args.downsample,
                pooling=args.pooling, device=args.device,
            )  # fmt: skip
            written.append(a.path)
            info["animation"] = a.to_dict()
    except ImportError as exc:
        raise ValueError(str(exc)) from None  # rolls the staged files back
    for v in info.values():
        for k in ("depth_m", "depth_fraction_of_Rt", "area_fraction"):
            v[k] = [float(x) for x in v[k]]
    info["surface"] = s.to_dict()
    info["warnings"] = warnings_of(args)
    info["provenance"] = provenance(args.device)
    (out / "render.json").write_text(strict_json(info))
    written.append(out / "render.json")
    return r, written
