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
from pathlib import Path

from .._support.outputs import staged_outputs, strict_json
from .._support.provenance import provenance
from ..fractal.settings import METHODS, FractalSettings
from ..params import add_options, from_args
from ._common import (
    add_device,
    add_figures_out,
    add_generation,
    add_json_output,
    add_scan_file,
    add_warnings,
    generate_surface,
    read_scan,
    spec_from_args,
    warnings_of,
)

NAME = "describe"
HELP = "descriptors (R_t, R_rms, R_a, skewness, kurtosis, W_r) and D by the four methods"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc describe``."""
    add_scan_file(p, required=False)
    add_generation(
        p.add_argument_group("or a generated surface (no FILE: a preset or the WM / self-affine options)")
    )
    add_options(p.add_argument_group("fractal methods"), FractalSettings)
    add_json_output(p)
    add_figures_out(p, "psd.png and fractal_fits.png")
    add_device(p)


def describe_surface(s, settings: FractalSettings, device) -> dict:
    """Descriptors and D values as one flat dict (the JSON of ``describe``): ``{"result":
    that dict, "fits": {method: FractalFit}, "descriptors": Descriptors}``; a method that
    cannot fit the map gives its reason in ``error_<method>``."""
    from ..descriptors import describe
    from ..fractal import fractal_dimensions
    from ..slope import slope_statistics, spectrum_slope

    d = describe(s)
    fits, errors = {}, {}
    options = settings.options()
    for m in settings.methods:
        if not s.Rt > 0:
            errors[m] = "the map is flat (R_t = 0): no roughness to fit"
            continue
        try:
            fits.update(fractal_dimensions(s, [m], options={m: options[m]}, device=device))
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
    fd = slope_statistics(s)  # at the map's pixel, with the rms slope per decade of wavelength
    sp = spectrum_slope(s.params)
    out.update(
        {
            "slope_rms": fd.slope_rms,
            "curvature_rms_per_m": fd.curvature_rms,
            "slope_method": fd.method,
            "decade_edges_m": list(fd.decade_edges),
            "slope_rms_per_decade": list(fd.slope_rms_per_decade),
            "slope_rms_spectrum": None if sp is None else sp.slope_rms,
            "curvature_rms_spectrum_per_m": None if sp is None else sp.curvature_rms,
            "slope_rms_per_decade_spectrum": None if sp is None else list(sp.slope_rms_per_decade),
            "decade_edges_spectrum_m": None if sp is None else list(sp.decade_edges),
        }
    )
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


def _with_spectrum(fd: float, sp: float | None, unit: str, dx: float) -> str:
    """A slope or curvature by finite differences at the pixel, and the spectrum's where known."""
    text = f"{fd:.4g}{unit} (finite differences at the {dx * 1e9:.4g} nm pixel"
    return text + (f"; spectrum {sp:.4g}{unit})" if sp is not None else ")")


def _generated_name(args: argparse.Namespace, s) -> str:
    """How the output names a generated surface: its preset or generator and parameters."""
    gen = s.params.get("generator")
    if getattr(args, "preset", None):
        return f"preset {args.preset}"
    if gen == "self-affine":
        return f"self-affine surface, H = {s.params['hurst']:g}"
    return f"WM surface, D = {s.params.get('D'):g}"


def run(args: argparse.Namespace) -> int:
    """Describe the file, or the generated surface."""
    from ..descriptors import profile_psd, radial_psd
    from ..plausibility import check_dimensions

    settings = from_args(FractalSettings, args)
    s = read_scan(args)
    if s is None:  # no FILE: the generated surface of the options
        s = generate_surface(spec_from_args(args), args.device)
        args.file = Path(_generated_name(args, s))
    res = describe_surface(s, settings, args.device)
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
            ("h′_rms", _with_spectrum(out["slope_rms"], out["slope_rms_spectrum"], "", s.dx)),
            ("h″_rms", _with_spectrum(out["curvature_rms_per_m"],
                                      out["curvature_rms_spectrum_per_m"], " 1/m", s.dx)),
        ]
        for m in settings.methods:
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
