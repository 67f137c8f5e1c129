# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Roughness descriptors and the four fractal dimensions of a height-map file (Table 1).

Prints a table and, with --json, writes (or prints, with --json -) a JSON object with the keys
Rt_m, Rrms_m, Ra_m, skewness, kurtosis, Wr_m, D_tri, D_box, D_vs, D_sp (SI units), plus
Wr_resolved, r2_<method>, the grid, and convention_<method>: the height convention that
produced each D ("cube": heights mapped onto the lateral extent, Gwyddion's, the default;
"si": metres as measured; "none" for D_vs and D_sp, which do not depend on it). With --out DIR, also writes DIR/psd.png and
DIR/fractal_fits.png.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from ..descriptors import describe, profile_psd, radial_psd
from ..fractal import DEFAULT_HEIGHT_SCALING, HEIGHT_SCALINGS, METHODS, fractal_dimensions
from ._common import add_device, add_reader_options, input_file, output_dir, output_file, read_input

NAME = "describe"
HELP = "descriptors (R_t, R_rms, R_a, skewness, kurtosis, W_r) and D by the four methods"


def add_scan_arguments(p: argparse.ArgumentParser, *, required: bool = True) -> None:
    """FILE and the reader options shared by ``describe`` and ``calibrate``."""
    p.add_argument(
        "file", type=input_file, nargs=None if required else "?", default=None,
        help="height map: .npz/.npy (warptrunc or plain), .csv/.txt matrix, or an instrument "
        "file (.sur, .x3p, .datx, ... needs the 'scans' extra)",
    )  # fmt: skip
    add_reader_options(p.add_argument_group("reading the file"))


def read_scan_args(args: argparse.Namespace):
    """The Surface named by ``args.file`` with the reader options; reports missing points."""
    return read_input(args.file, args)


def add_height_scaling(g) -> None:
    """``--height-scaling`` of D_tri and D_box (shared with ``calibrate``)."""
    g.add_argument(
        "--height-scaling", choices=list(HEIGHT_SCALINGS), default=DEFAULT_HEIGHT_SCALING,
        help="height convention of D_tri and D_box: 'cube' maps the height range onto the "
        "lateral extent first (Gwyddion's; independent of units and amplitude), 'si' uses "
        "metres as measured (D drifts to 2 on gently sloped maps)",
    )  # fmt: skip


def method_options(method: str, height_scaling: str) -> dict:
    """The options of ``method`` that carry the height convention (tri, box)."""
    return {"height_scaling": height_scaling} if method in ("tri", "box") else {}


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc describe``."""
    add_scan_arguments(p)
    g = p.add_argument_group("fractal methods")
    g.add_argument(
        "--methods", nargs="+", choices=list(METHODS), default=list(METHODS),
        help="fractal methods to run",
    )  # fmt: skip
    add_height_scaling(g)
    g.add_argument(
        "--sp-kind", choices=["profile", "radial"], default="profile",
        help="spectrum of the power-spectrum method",
    )  # fmt: skip
    g.add_argument(
        "--vs-axis", choices=["both", "x", "y"], default="both",
        help="profile direction of the vertical-sections method",
    )  # fmt: skip
    p.add_argument(
        "--json", type=_json_path, default=None, metavar="PATH",
        help="write JSON here ('-': stdout)",
    )  # fmt: skip
    p.add_argument(
        "--out", type=output_dir, default=None, help="folder for psd.png and fractal_fits.png"
    )
    add_device(p)


def _json_path(text: str) -> str:
    """``-`` (stdout) or a file to write (see :func:`warptrunc.cli._common.output_file`)."""

    return text if text == "-" else str(output_file(text))


def describe_surface(s, methods, options, device) -> dict:
    """Descriptors and D values as one flat dict (the JSON of ``describe``)."""

    d = describe(s)
    fits = fractal_dimensions(s, methods, options=options, device=device)
    out = {k: v for k, v in d.to_dict().items() if k != "mean_m"}
    for m in METHODS:
        out[f"D_{m}"] = fits[m].D if m in fits else None
    for m in METHODS:
        out[f"r2_{m}"] = fits[m].r2 if m in fits else None
    for m in METHODS:
        if m not in fits:
            out[f"convention_{m}"] = None
        else:
            out[f"convention_{m}"] = fits[m].options.get("height_scaling", "none")
    out.update({"nx": s.nx, "ny": s.ny, "dx_m": s.dx, "dy_m": s.dy})
    return {"result": out, "fits": fits, "descriptors": d}


def run(args: argparse.Namespace) -> int:
    """Describe the file."""
    s = read_scan_args(args)
    options = {
        "sp": {"kind": args.sp_kind},
        "vs": {"axis": args.vs_axis},
        "tri": method_options("tri", args.height_scaling),
        "box": method_options("box", args.height_scaling),
    }
    options = {k: v for k, v in options.items() if k in args.methods}
    res = describe_surface(s, args.methods, options, args.device)
    out = {"file": str(args.file), **res["result"]}
    text = json.dumps(out, indent=2) + "\n"
    if args.json == "-":
        sys.stdout.write(text)
    else:
        u = 1e6
        print(f"{args.file}: {s.nx}×{s.ny} pixels, {s.lx * u:.4g} × {s.ly * u:.4g} µm")
        rows = [
            ("R_t", f"{out['Rt_m'] * u:.4g} µm"),
            ("R_rms", f"{out['Rrms_m'] * u:.4g} µm"),
            ("R_a", f"{out['Ra_m'] * u:.4g} µm"),
            ("skewness", f"{out['skewness']:.4g}"),
            ("kurtosis", f"{out['kurtosis']:.4g}"),
            ("W_r", f"{out['Wr_m'] * u:.4g} µm" + ("" if out["Wr_resolved"] else " (unresolved)")),
        ]
        for m in args.methods:
            conv = out[f"convention_{m}"]
            note = f", heights: {conv}" if conv != "none" else ""
            rows.append((f"D_{m}", f"{out[f'D_{m}']:.4f}  (r² = {out[f'r2_{m}']:.4f}{note})"))
        w = max(len(r[0]) for r in rows)
        for k, v in rows:
            print(f"  {k:<{w}}  {v}")
        if args.json:
            Path(args.json).write_text(text)
            print(f"wrote {args.json}")
    if args.out is not None:
        from .. import plot

        args.out.mkdir(parents=True, exist_ok=True)
        psds = [radial_psd(s)]
        if abs(s.dx - s.dy) <= 1e-9 * s.dx and s.nx == s.ny:
            psds.append(profile_psd(s))
        plot.psd(psds, Wr=out["Wr_m"], path=args.out / "psd.png", title=str(args.file.name))
        plot.fractal_fits(res["fits"], path=args.out / "fractal_fits.png")
        if args.json != "-":
            print(f"wrote {args.out}/psd.png, fractal_fits.png")
    return 0
