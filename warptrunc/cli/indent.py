# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Flat-punch indentation in silico: the paper's nanoindentation experiment (§ 4.1, Fig. 6).

Rigid circular flat punches (--punch-diameter, default the paper's 54.1, 108.7 and 502.6 µm)
press on the surface at increasing peak loads (--peak-loads, default ten levels doubling up to
500 mN); at each peak the unloading stiffness K of the elastic–perfectly-plastic contact
(pressure capped at --hardness) is measured with the plastic state frozen, as Barber's initial
slope and as the secant of a partial unloading by --unload-fraction, and turned into
E_c = √π·K/(2√A) (A the punch area). The elastic solution (H = ∞) and Eq. 2 truncation run on
the same punch disks and placements (--placements random positions per punch, apart, from
--placement-seed).

A generated map is 3 mm per side unless --L is given (the paper's island maps; the default
placements of the 502.6 µm punch never overlap there), at the preset's or the defaults' pixel
unless --n is given; --seeds indents several realisations. On a WM map each (punch,
placement, peak) cell is solved again at half the pixel until its unloading stiffness and
contact area change by less than --resolution-tol with at least --min-contact-pixels in
contact, up to --refine-max; the fits use only the cells resolved, not saturated and
converged (``in_fit``), at least 6, with 95 % intervals by a bootstrap over the indents.

The punch as the experiment had it: --punch-tilt (degrees, a misaligned flat held against
rotation) and a rough face, generated (--punch-roughness rms, --punch-hurst, --punch-cutoff-short,
--punch-cutoff-long, --punch-face-seed) or read (--punch-face-file); the gap is the punch plane
minus the sum of the sample's and the face's heights; truncation stays the sample's.

Writes OUT/indent.csv (one row per realisation × punch × placement × peak; SI units in the
column names), OUT/indent.json (settings, the fits E_c/E = β·[F/(E·A)]^α per model with their
intervals, the resolution counts, provenance; strict JSON: a hardness of null is ∞) and
OUT/indent.png (E_c/E against F/(E·A), log–log, as Fig. 6; the cells left out of the fits
hollow). All or nothing: the files are moved into OUT only when every one of them is written.

Exit status: 0; 2 for bad input (one line naming the option and its allowed range); 3 when a
solve did not converge (the outputs are written and flag it), unless --accept-unconverged.
"""

from __future__ import annotations

import argparse
import re
import sys
import warnings

from .._support.atomic import staged_output
from ..contact.settings import SolverSettings
from ..material import Material
from ..params import add_options, from_args
from ._common import (
    add_devices,
    add_run_outputs,
    add_surface_source,
    integer,
    prepare_devices,
    read_input,
    wm_spec_from_args,
)

NAME = "indent"
HELP = "flat-punch indentation with partial unloadings, against truncation (Fig. 6)"
EXIT_NOT_CONVERGED = 3
"""Exit status when any solve did not converge (without --accept-unconverged)."""

MAP_SIDE = 3e-3
"""Side of ``indent``'s generated map (m) unless ``--L`` is given: the paper's island maps
(3 mm, § 4.3), large enough that the default placements of the 502.6 µm punch never overlap."""

_OPTION = {
    "punch_diameter": "--punch-diameter", "punch_diameters": "--punch-diameter",
    "peak_loads": "--peak-loads", "unload_fraction": "--unload-fraction",
    "placements": "--placements", "hardness": "--hardness", "placement_seed": "--placement-seed",
    "truncation_increments": "--truncation-increments", "resolution_tol": "--resolution-tol",
    "min_contact_pixels": "--min-contact-pixels", "refine_max": "--refine-max",
    "punch_tilt_deg": "--punch-tilt", "punch_tilt_azimuth_deg": "--punch-tilt-azimuth",
    "punch_roughness": "--punch-roughness", "punch_hurst": "--punch-hurst",
    "punch_cutoff_short": "--punch-cutoff-short", "punch_cutoff_long": "--punch-cutoff-long",
    "punch_face_seed": "--punch-face-seed", "punch_face_file": "--punch-face-file",
}  # fmt: skip


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc indent``."""
    from ..indent.protocol import MATERIAL_DEFAULTS, IndentProtocol

    add_surface_source(p, scan_rule="read")
    p.add_argument(
        "--seeds", type=integer(0, 2**32 - 1), nargs="+", default=None, metavar="SEED",
        help="WM surface realisations: the phase seeds of the surfaces indented (the same "
        "punches and placements on each; the fits' intervals resample their indents); "
        "default: the one surface of --seed",
    )  # fmt: skip
    g = add_options(p, IndentProtocol, title="indentation protocol")
    g.add_argument(  # a path: not a numeric parameter field (IndentProtocol.punch_face_file)
        "--punch-face-file", metavar="FILE", default=None,
        help="a height map of the punch face (heights toward the sample, its own pixel), "
        "centred on every punch, levelled over its disk and resampled bilinearly; instead of "
        "--punch-roughness",
    )  # fmt: skip
    add_options(p, Material, title="material (default: aluminium alloy against diamond)",
                defaults=MATERIAL_DEFAULTS)  # fmt: skip
    add_options(p, SolverSettings, title="contact solver (free half-space on each punch's window)",
                exclude=("substrate",))  # fmt: skip
    add_devices(p, "the indentation cycles (each punch window; rows of its floor added where N "
                "does not divide the window's)")
    p.add_argument(
        "--no-elastic", action="store_true",
        help="skip the elastic solution (H = ∞) on the same punches (its columns are NaN)",
    )  # fmt: skip
    p.add_argument(
        "--accept-unconverged", action="store_true",
        help=f"exit 0 even when a solve did not converge (default: exit {EXIT_NOT_CONVERGED})",
    )  # fmt: skip
    add_run_outputs(p, "indent", "skip indent.png")


def _options(msg: str) -> str:
    """A library message with the parameter names replaced by their option names."""
    return re.sub(r"\b(" + "|".join(_OPTION) + r")\b", lambda m: _OPTION[m.group(1)], msg)


def run(args: argparse.Namespace) -> int:
    """Run the experiment and write the outputs."""
    from .._support.provenance import git_commit
    from .._support.version import __version__
    from ..indent import IndentProtocol, PlacementOverlapWarning, indent
    from ..indent.face import FACE_FIELDS
    from ..indent.fits import MIN_FIT_POINTS
    from ..indent.protocol import MATERIAL_DEFAULTS

    try:
        material = from_args(Material, args, defaults=MATERIAL_DEFAULTS)
        protocol = from_args(IndentProtocol, args, punch_face_file=args.punch_face_file)
        settings = from_args(SolverSettings, args, substrate="free")
        if args.devices not in (None, 1) and settings.algorithm != "bccg":
            raise ValueError(f"--devices {args.devices} spreads only --algorithm bccg (the "
                             f"default), got --algorithm {settings.algorithm}")  # fmt: skip
        prepare_devices(args.devices)
        surfaces = _surfaces(args)
        s = surfaces[0]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", PlacementOverlapWarning)
            res = indent(
                surfaces, punch_diameter=protocol.punch_diameters, peak_loads=protocol.peak_loads,
                unload_fraction=protocol.unload_fraction, material=material,
                placements=protocol.placements, seed=protocol.placement_seed, overlap=protocol.overlap,
                truncation_increments=protocol.truncation_increments, settings=settings,
                resolution_tol=protocol.resolution_tol, refine_max=protocol.refine_max,
                min_contact_pixels=protocol.min_contact_pixels,
                **{k: getattr(protocol, k) for k in FACE_FIELDS},
                elastic=not args.no_elastic, device=args.device, devices=args.devices,
                progress=not args.no_progress and sys.stderr.isatty(),
            )  # fmt: skip
    except ValueError as exc:
        raise ValueError(_options(str(exc))) from None
    for w in caught:
        if issubclass(w.category, PlacementOverlapWarning):
            print(f"warptrunc {NAME}: warning: {w.message}", file=sys.stderr)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    provenance = {"warptrunc_version": __version__, "git_commit": git_commit(),
                  "command": ["warptrunc", *sys.argv[1:]]}  # fmt: skip
    files = ["indent.csv", "indent.json"]
    with staged_output(args.out) as out:  # all or nothing
        res.to_csv(out / "indent.csv")
        res.to_json(out / "indent.json", provenance=provenance)
        if not args.no_plot:
            from ..plot import indentation

            indentation(res, out / "indent.png",
                        title=f"{s.nx}×{s.ny} over {s.lx * 1e3:.3g} mm, R$_t$ = "
                        f"{s.Rt * 1e6:.3g} µm, H = {_h(material)}")  # fmt: skip
            files.append("indent.png")
    fits = res.fit_summary()
    n_real = len(surfaces)
    lines = [
        f"{s.nx}×{s.ny} surface over {s.lx * 1e3:.4g} × {s.ly * 1e3:.4g} mm"
        + (f" ({n_real} realisations)" if n_real > 1 else "") + f", R_t = {s.Rt * 1e6:.4g} µm; "
        f"E = {material.E / 1e9:.4g} GPa, E* = {material.contact_modulus / 1e9:.4g} GPa, "
        f"H = {_h(material)}; {res.peak_load.size} cells in "
        f"{res.settings['seconds']['total_s']:.3g} s",
        _resolution_line(res),
        *_face_lines(res),
    ]
    for name, fit in fits.items():
        if not fit["made"]:
            lines.append(f"  {name:24s} no fit: {fit['n_points']} cells in_fit, "
                         f"at least {MIN_FIT_POINTS} needed")  # fmt: skip
            continue
        (a0, a1), (b0, b1) = fit["alpha_ci95"], fit["beta_ci95"]
        lines.append(
            f"  {name:24s} E_c/E = {fit['beta']:.4g}·[F/(E·A)]^{fit['alpha']:.4f}  (E Young's "
            f"modulus); α 95 % [{a0:.4f}, {a1:.4f}], β 95 % [{b0:.4g}, {b1:.4g}]; "
            f"r² = {fit['r2']:.4f}, {fit['n_points']} cells of {fit['n_indents']} indents"
        )  # fmt: skip
    print("\n".join(lines))
    print(f"wrote {args.out}/{', '.join(files)}")
    if not res.all_converged or not (args.no_elastic or res.elastic_converged.all()):
        n_bad = int((~res.converged).sum()) + (
            0 if args.no_elastic else int((~res.elastic_converged).sum()))
        print(f"WARNING: {n_bad} cycles did not converge (flagged in indent.csv)", file=sys.stderr)
        if not args.accept_unconverged:
            print(f"warptrunc {NAME}: exit {EXIT_NOT_CONVERGED}: not every solve converged "
                  "(--accept-unconverged to exit 0)", file=sys.stderr)  # fmt: skip
            return EXIT_NOT_CONVERGED
    return 0


def _h(material: Material) -> str:
    return "∞ (elastic)" if material.elastic else f"{material.hardness / 1e9:.4g} GPa"


def map_spec(args: argparse.Namespace):
    """The WM surface of the options, on a map of :data:`MAP_SIDE` per side unless ``--L`` is
    given, at the pixel of the preset or of the defaults unless ``--n`` is given.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``warptrunc indent``.

    Returns
    -------
    WMSpec
        E.g. ``--preset GB300s``: 3 mm over 30720 pixels (the preset's 97.7 nm); no preset:
        3 mm over 3072 (the defaults' 0.977 µm); ``--n 512``: 3 mm over 512.
    """
    spec = wm_spec_from_args(args)
    if args.L is None:
        lx, ly = spec.L if isinstance(spec.L, tuple) else (spec.L, spec.L)
        nx, ny = spec.n if isinstance(spec.n, tuple) else (spec.n, spec.n)
        if args.n is None:  # the pixel of the preset or the defaults, on a larger map
            nx, ny = round(nx * MAP_SIDE / lx), round(ny * MAP_SIDE / ly)
        spec = spec.replace(L=MAP_SIDE, n=(nx, ny) if nx != ny else nx)
    return spec


def _surfaces(args: argparse.Namespace) -> list:
    """The surfaces indented: the file of ``--input``, or the WM surface of :func:`map_spec`,
    one per ``--seeds``."""
    from ..wm import wm_surface

    if args.input is not None:
        if args.seeds is not None:
            raise ValueError("--seeds generates WM surfaces; it cannot be used with --input")
        return [read_input(args.input, args)]
    spec = map_spec(args)
    seeds = [spec.seed] if args.seeds is None else list(args.seeds)
    return [wm_surface(spec.replace(seed=k), device=args.device) for k in seeds]


def _resolution_line(res) -> str:
    """One line: how many cells are resolved, saturated and in the fits."""
    c = res.resolution_counts()
    n = c["n_cells"]
    ep = c["elastic_plastic"]
    text = (f"  cells: {ep['resolved']}/{n} resolved, {ep['saturated']} saturated, "
            f"{ep['in_fit']} in_fit (elastic–plastic)")  # fmt: skip
    if "elastic" in c and not res.material.elastic:
        el = c["elastic"]
        text += f"; {el['resolved']} resolved, {el['saturated']} saturated, {el['in_fit']} in_fit (elastic)"
    notes = ", ".join(f"{v} {k}" for k, v in sorted(ep["notes"].items()))
    return text + f"; elastic–plastic notes: {notes}"


def _face_lines(res) -> list[str]:
    """One line per punch face that is not an aligned smooth flat."""
    out = []
    for f in res.settings.get("punch_face") or []:
        text = f"  punch {f['diameter_m'] * 1e6:.4g} µm: tilt {f['tilt_deg']:.4g}°"
        if f["tilt_deg"] > 0:
            text += (f" (azimuth {f['tilt_azimuth_deg']:.4g}°, "
                     f"{f['tilt_rise_over_diameter_m'] * 1e6:.3g} µm over the diameter)")  # fmt: skip
        r = f.get("roughness")
        if r and "hurst" in r:
            text += (f"; rough face R_q {r['rms_m'] * 1e6:.3g} µm, H {r['hurst']:.3g}, "
                     f"λ {r['cutoff_short_m'] * 1e6:.3g}–{r['cutoff_long_m'] * 1e6:.4g} µm")  # fmt: skip
        elif r:
            text += f"; face read from {r['file']} (R_q {r['rms_m'] * 1e6:.3g} µm levelled)"
        out.append(text)
    return out
