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

from .._support.outputs import staged_output, strict_json
from .._support.provenance import provenance
from ..params import add_options, from_args
from ..render.settings import AnimationSettings, RenderSettings
from ..truncation.settings import TruncationSettings
from ._common import (
    add_device,
    add_file_in_out,
    add_no_progress,
    add_out,
    add_surface_source,
    surface_from_args,
    warnings_of,
)

NAME = "render"
HELP = "render truncation sections (Fig. 7), an animation, a VTK file"
VTK = "vtk-"
"""Prefix of the VTK export's depth options (``--vtk-increments``)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc render``."""
    add_surface_source(p)
    g = p.add_argument_group("picture")
    add_options(g, RenderSettings)
    add_file_in_out(
        g, "--output", (".png",), "truncation.png", "picture file name (.png) inside --out"
    )
    a = p.add_argument_group("animation and VTK export")
    add_file_in_out(
        a,
        "--animate",
        (".gif", ".mp4"),
        "truncation.gif",
        "also write an animation (.gif, or .mp4 with imageio-ffmpeg) inside --out",
        optional=True,
    )
    add_options(a, AnimationSettings)
    add_file_in_out(
        a,
        "--vtk",
        (".vti", ".vtk"),
        "surface.vti",
        "also write heights and first-contact depths for ParaView (.vti or .vtk)",
        optional=True,
    )
    add_options(
        a,
        TruncationSettings,
        only=("increments",),
        prefix=VTK,
        docs={"increments": "depth increments n of the first-contact depths, up to ω = R_t"},
    )
    add_device(p)
    add_out(p)
    add_no_progress(p)


def run(args: argparse.Namespace) -> int:
    """Render and write the outputs."""
    picture = from_args(RenderSettings, args)
    animation = from_args(AnimationSettings, args)
    vtk = from_args(TruncationSettings, args, prefix=VTK)
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
    if picture.depths is not None and max(picture.depths) > s.Rt:
        raise ValueError(
            f"--depths must be in (0, R_t] = (0, {s.Rt:.6g}] m for this surface, got "
            f"{' '.join(f'{d:g}' for d in picture.depths)} (metres; --depth-fractions takes "
            "fractions of R_t)"
        )
    with staged_output(args.out) as out:  # all or nothing
        r, written = _render(s, args, out, picture, animation, vtk)
    written = [args.out / p.relative_to(out) for p in written]
    print(r.caption)
    for d, f, af in zip(r.depth, r.depth_fraction, r.area_fraction, strict=True):
        print(f"  ω = {d * 1e6:.4g} µm ({100 * f:.3g} % R_t): A_c/A = {100 * af:.4g} %")
    print("wrote " + ", ".join(str(p) for p in written))
    return 0


def _render(s, args: argparse.Namespace, out, picture, animation, vtk):
    """(picture result, files written), every file under ``out``."""
    from ..io.vtk import export_vtk

    written = []
    if args.vtk:
        written.append(
            export_vtk(s, out / args.vtk, n_increments=vtk.increments, device=args.device)
        )
    try:
        from .. import render
    except ImportError as exc:  # pragma: no cover
        raise ValueError(str(exc)) from None  # rolls the staged files back
    try:
        r = render.render_truncation(s, out / args.output, settings=picture, device=args.device)
        written.append(r.path)
        info = {"picture": r.to_dict()}
        if args.animate:
            a = render.animate_truncation(
                s,
                out / args.animate,
                settings=picture,
                animation=animation,
                progress=not args.no_progress,
                device=args.device,
            )
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
