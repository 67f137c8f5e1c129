# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Roughness descriptors and the four fractal dimensions of a height-map file (Table 1).

FILE may be given as ``--input FILE`` (``-i``) as in every other command. Prints a table and,
with --json, writes (or prints, with --json -) a JSON object with the keys
Rt_m, Rrms_m, Ra_m, skewness, kurtosis, Wr_m, D_tri, D_box, D_vs, D_sp (SI units), plus
Wr_resolved, r2_<method>, the grid, and convention_<method>: the height convention that
produced each D ("cube": heights mapped onto the lateral extent, Gwyddion's, the default;
"si": metres as measured; "none" for D_vs and D_sp, which do not depend on it). With --out DIR, also writes DIR/psd.png and
DIR/fractal_fits.png.

A method that cannot fit this map gives D_<method> = null and its reason in
error_<method> (a line in the table); the other methods are reported. A flat map (R_t = 0) is
called flat. The JSON is strict (null, never NaN/Infinity) and holds "provenance" (version,
commit, command line, device, time). All or nothing: the JSON and the figures are written under
temporary names and renamed into place once every one of them is complete.
"""

from __future__ import annotations

import argparse
import sys

from .._support.atomic import staged_outputs, strict_json
from .._support.provenance import provenance
from ..descriptors import describe, profile_psd, radial_psd
from ..fractal import DEFAULT_HEIGHT_SCALING, HEIGHT_SCALINGS, METHODS, fractal_dimensions
from ..plausibility import check_dimensions
from ._common import (
    add_device,
    add_reader_options,
    add_warnings,
    input_file,
    output_dir,
    output_file,
    read_input,
    warnings_of,
)

NAME = "describe"
HELP = "descriptors (R_t, R_rms, R_a, skewness, kurtosis, W_r) and D by the four methods"


_FILE_HELP = (
    "height map: .npz/.npy (warptrunc or plain), .csv/.txt matrix, or an instrument file (.sur, "
    ".x3p, .datx, ... over forty formats, through SurfaceTopography)"
)


def add_scan_arguments(p: argparse.ArgumentParser, *, required: bool = True) -> None:
    """FILE (positional, or ``--input/-i FILE`` as in every other command) and the reader
    options shared by ``describe`` and ``calibrate``."""
    p.add_argument(
        "file", type=input_file, nargs="?", default=None, metavar="FILE",
        help=_FILE_HELP + ("" if required else " (optional: the targets may be typed in)"),
    )  # fmt: skip
    g = p.add_argument_group("reading the file")
    g.add_argument(
        "--input", "-i", type=input_file, default=None, metavar="FILE",
        help="the height map, as FILE (the same file; give one of the two)",
    )  # fmt: skip
    add_reader_options(g)
    p.set_defaults(_file_required=required)


def scan_file(args: argparse.Namespace):
    """The file named by FILE or ``--input`` (None when neither is given and it is optional).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments of :func:`add_scan_arguments`; ``args.file`` is set to the file.

    Returns
    -------
    Path or None
        The file to read.

    Raises
    ------
    ValueError
        Both forms name a file, or neither does and the command needs one.
    """
    f, i = args.file, getattr(args, "input", None)
    if f is not None and i is not None and f != i:
        raise ValueError(f"give the height map once, as FILE or --input FILE, got {f} and {i}")
    args.file = f if f is not None else i
    if args.file is None and getattr(args, "_file_required", True):
        raise ValueError("the height map is missing: give FILE or --input FILE")
    return args.file


def read_scan_args(args: argparse.Namespace):
    """The Surface named by FILE or ``--input`` with the reader options; reports missing
    points."""
    return read_input(scan_file(args), args)


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
    fits, errors = {}, {}
    for m in methods:
        if not s.Rt > 0:
            errors[m] = "the map is flat (R_t = 0): no roughness to fit"
            continue
        try:
            fits.update(fractal_dimensions(s, [m], options={m: options.get(m, {})}, device=device))
        except ValueError as exc:
            errors[m] = _user_words(str(exc), m, s)
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
    for m in METHODS:
        out[f"error_{m}"] = errors.get(m)
    out.update({"nx": s.nx, "ny": s.ny, "dx_m": s.dx, "dy_m": s.dy, "flat": not s.Rt > 0})
    return {"result": out, "fits": fits, "descriptors": d}


_INTERNAL_NAMES = {
    "box_sizes": "the default box sizes",
    "fit_range": "the default fit range",
    "lags": "the default lags",
    "array(": "(",
}


def _user_words(msg: str, method: str, s) -> str:
    """A method's error without the keyword names of the Python API (the CLI has none)."""
    if msg.startswith(f"{method}: "):
        msg = msg[len(method) + 2 :]
    for k, v in _INTERNAL_NAMES.items():
        msg = msg.replace(k, v)
    return f"cannot fit on this {s.nx}×{s.ny} map: {msg}"


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
    add_warnings(args, check_dimensions({m: res["result"][f"D_{m}"] for m in METHODS}))
    out = {"file": str(args.file), **res["result"], "warnings": warnings_of(args)}
    text = strict_json({**out, "provenance": provenance(args.device)})
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
            if out[f"D_{m}"] is None:
                rows.append((f"D_{m}", f"— ({out[f'error_{m}']})"))
                continue
            conv = out[f"convention_{m}"]
            note = f", heights: {conv}" if conv != "none" else ""
            rows.append((f"D_{m}", f"{out[f'D_{m}']:.4f}  (r² = {out[f'r2_{m}']:.4f}{note})"))
        if out["flat"]:
            rows.insert(0, ("flat", "every height is the same: R_t = 0"))
        w = max(len(r[0]) for r in rows)
        for k, v in rows:
            print(f"  {k:<{w}}  {v}")
    with staged_outputs() as st:  # the JSON and both figures, or none of them
        if args.json and args.json != "-":
            st.file(args.json).write_text(text)
        if args.out is not None:
            from .. import plot

            psds = [radial_psd(s)]
            if abs(s.dx - s.dy) <= 1e-9 * s.dx and s.nx == s.ny:
                psds.append(profile_psd(s))
            stage = st.folder(args.out)
            plot.psd(psds, Wr=out["Wr_m"], path=stage / "psd.png", title=str(args.file.name))
            if res["fits"]:  # none when no method could fit
                plot.fractal_fits(res["fits"], path=stage / "fractal_fits.png")
    if args.json and args.json != "-":
        print(f"wrote {args.json}")
    if args.out is not None and args.json != "-":
        print(f"wrote {args.out}/psd.png" + (", fractal_fits.png" if res["fits"] else ""))
    return 0
