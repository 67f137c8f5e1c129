# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Flat-punch indentation in silico: the paper's nanoindentation experiment (§ 4.1, Fig. 6).

Rigid circular flat punches (--punch-diameters, default the paper's 54.1, 108.7 and 502.6 µm)
press on the surface at increasing peak loads (--peak-loads, default the paper's five heaviest,
31.25–500 mN, each twice the previous); at each peak the unloading stiffness K of the
elastic–perfectly-plastic contact (pressure capped at --hardness) is measured with the plastic
state frozen, as Barber's initial slope and as the secant of a partial unloading by
--unload-fraction, and turned into E_c = √π·K/(2√A) (A the punch area). The elastic solution (H
= ∞; --no-elastic skips it) and Eq. 2 truncation run on the same punch disks and placements
(--placements random positions per punch, apart, from --placement-seed).

A generated map is --map-side per side (default 1 mm, the paper's simulated maps; the default
two placements of the 502.6 µm punch are apart there) unless --L is given, at the preset's or
the defaults' pixel unless --n is given; --seeds indents several realisations. A cell (punch,
placement, peak) is resolved when converged with at least --min-contact-pixels in contact;
with --refine-max 4 or more, a WM map's cell is solved again at half the pixel until the
Richardson error of its unloading stiffness over the last two halvings is within
--resolution-tol, up to --refine-max (a window larger than --max-window-pixels is cut to a
sub-window that holds the contact). The fits are per punch over its loads (at least 3 with
cells resolved, not saturated and converged: ``in_fit``; else no fit, with the reason), the
pooled one only where the punches' α intervals agree, with 95 % intervals by a hierarchical
bootstrap over realisations and placements spanning both cell rules. Depth is also read from
surface detection at --detection-load (``threshold_depth_m``); cells at the bulk-yield pressure
of the cap model are flagged (``bulk_yield``). The defaults are a quick run
of the experiment (about a minute on two CPU cores at the defaults' 0.977 µm pixel); the
paper's design, its ten loads, three placements and refined cells, is the indentation stage of
``warptrunc reproduce --profile paper``.

The punch as the experiment had it: --face-tilt-deg (a misaligned flat held against rotation)
and a rough face, generated (--face-roughness rms, --face-hurst, --face-cutoff-short,
--face-cutoff-long, --face-seed) or read (--face-file); the gap is the punch plane minus the sum
of the sample's and the face's heights; truncation stays the sample's.

Writes OUT/indent.csv (one row per realisation × punch × placement × peak; SI units in the
column names), OUT/indent.json (protocol, material, settings, the fits E_c/E = β·[F/(E·A)]^α
per model with their intervals, the resolution counts, provenance; strict JSON: a hardness of
null is ∞) and OUT/indent.png (E_c/E against F/(E·A), log–log, as Fig. 6; the cells left out of
the fits hollow). All or nothing: the files are moved into OUT only when every one of them is
written.

Exit status: 0; 2 for bad input (one line naming the option and its allowed range); 3 when a
solve did not converge (the outputs are written and flag it), unless --accept-unconverged.
"""

from __future__ import annotations

import argparse
import re
import sys
import warnings

from .._support.outputs import staged_output
from .._support.provenance import provenance
from ..contact.adhesion import Adhesion
from ..contact.settings import SolverSettings
from ..indent.face import PunchFaceSpec
from ..indent.maps import IndentMaps
from ..indent.protocol import MATERIAL_DEFAULTS, IndentProtocol
from ..material import Material
from ..params import add_options, from_args, param_info
from ._common import (
    add_accept_unconverged,
    add_devices,
    add_run_outputs,
    add_surface_source,
    generate_surface,
    prepare_devices,
    read_input,
    refuse_unconverged,
    slope_line,
    spec_from_args,
)

NAME = "indent"
HELP = "flat-punch indentation with partial unloadings, against truncation (Fig. 6)"
EXIT_NOT_CONVERGED = 3
"""Exit status when any solve did not converge (without --accept-unconverged)."""
FACE = "face-"
"""Prefix of the punch face's options (``--face-tilt-deg`` sets ``IndentProtocol.face.tilt_deg``)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc indent``."""
    add_surface_source(p, scan_rule="read")
    add_options(p, IndentMaps, title="generated maps")
    add_options(p, IndentProtocol, title="indentation protocol")
    add_options(p, PunchFaceSpec, prefix=FACE, title="punch face (default: an aligned smooth flat)")
    add_options(
        p,
        Material,
        title="material (default: aluminium alloy against diamond)",
        defaults=MATERIAL_DEFAULTS,
    )
    add_options(
        p,
        SolverSettings,
        title="contact solver (free half-space on each punch's window)",
        exclude=("substrate",),
    )
    add_options(
        p, Adhesion, title="adhesion of the punch face and the surface (needs --hardness inf)"
    )
    add_devices(
        p,
        "the indentation cycles (each punch window; rows of its floor added where N "
        "does not divide the window's)",
    )
    add_accept_unconverged(p, EXIT_NOT_CONVERGED)
    add_run_outputs(p, "indent", "skip indent.png")


def _named_by_option(msg: str) -> str:
    """A library message that names a protocol field first (``peak_loads must ...``) or
    anywhere by its underscored name, or a face field as ``face.<field>``, with the option that
    sets it (the field's name with dashes, as :func:`warptrunc.params.add_options` makes it)."""

    def option(name: str, prefix: str = "") -> str:
        return f"--{prefix}{name}".replace("_", "-")

    face = "|".join(param_info(PunchFaceSpec))
    msg = re.sub(rf"\bface\.({face})\b", lambda m: option(m.group(1), FACE), msg)
    names = list(param_info(IndentProtocol))
    lead = re.match(r"(" + "|".join(names) + r")\b", msg)
    if lead:
        msg = option(lead.group(1)) + msg[lead.end() :]
    named = "|".join(n for n in names if "_" in n)
    return re.sub(rf"(?<![-\w])({named})\b", lambda m: option(m.group(1)), msg)


def run(args: argparse.Namespace) -> int:
    """Run the experiment and write the outputs."""
    from ..indent import PlacementOverlapWarning, indent

    try:
        material = from_args(Material, args, defaults=MATERIAL_DEFAULTS)
        face = from_args(PunchFaceSpec, args, prefix=FACE)
        protocol = from_args(IndentProtocol, args, face=face)
        solver = from_args(
            SolverSettings, args, substrate="free", adhesion=from_args(Adhesion, args)
        )
        if args.devices not in (None, 1) and solver.algorithm != "bccg":
            raise ValueError(
                f"--devices {args.devices} spreads only --algorithm bccg (the "
                f"default), got --algorithm {solver.algorithm}"
            )
        prepare_devices(args.devices)
        surfaces = _surfaces(args)
        s = surfaces[0]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", PlacementOverlapWarning)
            res = indent(
                surfaces,
                protocol=protocol,
                material=material,
                solver=solver,
                progress=not args.no_progress,
                device=args.device,
                devices=args.devices,
            )
    except ValueError as exc:
        raise ValueError(_named_by_option(str(exc))) from None
    for w in caught:
        if issubclass(w.category, PlacementOverlapWarning):
            print(f"warptrunc {NAME}: warning: {w.message}", file=sys.stderr)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    from ..plausibility import report
    from ..slope import slope_warnings

    metas = res.settings["surface"]
    metas = metas if isinstance(metas, list) else [metas]
    slope_found = slope_warnings({**metas[0]["slope"], "limit": solver.slope_limit})
    report(slope_found)
    files = ["indent.csv", "indent.json"]
    with staged_output(args.out) as out:  # all or nothing
        res.to_csv(out / "indent.csv")
        res.to_json(
            out / "indent.json",
            provenance=provenance(args.device),
            warnings=[w.to_dict() for w in slope_found],
        )
        if not args.no_plot:
            from ..plot import indentation

            indentation(
                res,
                out / "indent.png",
                title=f"{_case_name(args, s, len(surfaces))}\n{s.nx}×{s.ny} over "
                f"{s.lx * 1e3:.3g} mm, R$_t$ = {s.Rt * 1e6:.3g} µm, H = {_h(material)}",
            )
            files.append("indent.png")
    fits = res.fit_summary()
    n_real = len(surfaces)
    lines = [
        f"{s.nx}×{s.ny} surface over {s.lx * 1e3:.4g} × {s.ly * 1e3:.4g} mm"
        + (f" ({n_real} realisations)" if n_real > 1 else "")
        + f", R_t = {s.Rt * 1e6:.4g} µm; "
        f"E = {material.E / 1e9:.4g} GPa, E* = {material.contact_modulus / 1e9:.4g} GPa, "
        f"H = {_h(material)}; {res.peak_load.size} cells in "
        f"{res.settings['seconds']['total_s']:.3g} s",
        _resolution_line(res),
        *_face_lines(res),
        *[line for line in [slope_line(metas[0]["slope"]).rstrip()] if line],
    ]
    lines += _fit_lines(fits, res)
    print("\n".join(lines))
    print(f"wrote {args.out}/{', '.join(files)}")
    elastic = protocol.elastic
    if not res.all_converged or not (not elastic or res.elastic_converged.all()):
        n_bad = int((~res.converged).sum()) + (
            int((~res.elastic_converged).sum()) if elastic else 0
        )
        print(f"WARNING: {n_bad} cycles did not converge (flagged in indent.csv)", file=sys.stderr)
        if not args.accept_unconverged:
            return refuse_unconverged(NAME, EXIT_NOT_CONVERGED)
    return 0


def _h(material: Material) -> str:
    return "∞ (elastic)" if material.elastic else f"{material.hardness / 1e9:.4g} GPa"


def _surfaces(args: argparse.Namespace) -> list:
    """The surfaces indented: the file of ``--input``, or the generated surfaces of the options
    (WM, or self-affine with ``--surface self-affine``) on the maps of
    :class:`~warptrunc.indent.maps.IndentMaps` (``--map-side`` unless ``--L`` is given), one per
    ``--seeds``."""
    if args.input is not None:
        if args.seeds is not None:
            raise ValueError("--seeds generates WM surfaces; it cannot be used with --input")
        return [read_input(args.input, args)]
    return [generate_surface(spec, args.device) for spec in map_specs(args)]


def _case_name(args: argparse.Namespace, s, n_real: int) -> str:
    """What was indented, for the figure's title: the file read, the preset, or the WM
    surface's D (and the realisations)."""
    from pathlib import Path

    if getattr(args, "input", None) is not None:
        name = Path(str(args.input)).name.replace("$", r"\$")
    elif getattr(args, "preset", None) is not None:
        name = f"preset {args.preset}"
    else:
        d = s.params.get("D")
        name = f"WM surface, D = {d:g}" if isinstance(d, (int, float)) else "surface"
    return name + (f", {n_real} realisations" if n_real > 1 else "")


def map_specs(args: argparse.Namespace) -> list:
    """The WM surfaces of the options, one per ``--seeds``, on maps of ``--map-side``
    (:class:`~warptrunc.indent.maps.IndentMaps`, 1 mm) unless ``--L`` is given, at the pixel of
    the preset or of the defaults unless ``--n`` is given.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``warptrunc indent``.

    Returns
    -------
    list of WMSpec
        E.g. ``--preset GB300s``: 1 mm over 10240 pixels (the preset's 97.7 nm); no preset:
        1 mm over 1024 (the defaults' 0.977 µm); ``--n 512``: 1 mm over 512.
    """
    if args.L is not None and args.map_side is not None:
        raise ValueError(f"--L and --map-side {args.map_side} both give the map's side; give one")
    maps = from_args(IndentMaps, args, **({"map_side": None} if args.L is not None else {}))
    return maps.specs(spec_from_args(args), keep_n=args.n is not None)


def _resolution_line(res) -> str:
    """One line: how many cells are resolved, saturated and in the fits."""
    c = res.resolution_counts()
    n = c["n_cells"]
    ep = c["elastic_plastic"]
    text = (
        f"  cells: {ep['resolved']}/{n} resolved, {ep['saturated']} saturated, "
        f"{ep['in_fit']} in_fit (elastic–plastic)"
    )
    if "elastic" in c and not res.material.elastic:
        el = c["elastic"]
        text += f"; {el['resolved']} resolved, {el['saturated']} saturated, {el['in_fit']} in_fit (elastic)"
    notes = ", ".join(f"{v} {k}" for k, v in sorted(ep["notes"].items()))
    return text + f"; elastic–plastic notes: {notes}"


def _fit_lines(fits: dict, res) -> list[str]:
    """Per model, one line per punch (its fit over loads, or why not) and the pooled fit."""
    out = []
    for name, mf in fits.items():
        for f in [*mf["per_punch"], {**mf["pooled"], "pooled": True}]:
            d = f.get("punch_diameter_m")
            who = "pooled" if f.get("pooled") else ("flat" if d is None else f"{d * 1e6:.4g} µm")
            head = f"  {name:24s} {who:>9s}"
            if not f["made"]:
                out.append(f"{head} no fit: {f['reason']}")
                continue
            (a0, a1), (b0, b1) = f["alpha_ci95"], f["beta_ci95"]
            out.append(
                f"{head} E_c/E = {f['beta']:.4g}·[F/(E·A)]^{f['alpha']:.4f}; α 95 % "
                f"[{a0:.4f}, {a1:.4f}], β 95 % [{b0:.4g}, {b1:.4g}] (both cell rules); "
                f"r² = {f['r2']:.4f}, {f['n_points']} cells, {f['n_loads']} loads, "
                f"{f['n_indents']} indents"
            )
    return out


def _face_lines(res) -> list[str]:
    """One line per punch face that is not an aligned smooth flat."""
    out = []
    for f in res.settings.get("punch_face") or []:
        text = f"  punch {f['diameter_m'] * 1e6:.4g} µm: tilt {f['tilt_deg']:.4g}°"
        if f["tilt_deg"] > 0:
            text += (
                f" (azimuth {f['tilt_azimuth_deg']:.4g}°, "
                f"{f['tilt_rise_over_diameter_m'] * 1e6:.3g} µm over the diameter)"
            )
        r = f.get("roughness")
        if r and "hurst" in r:
            text += (
                f"; rough face R_q {r['rms_m'] * 1e6:.3g} µm, H {r['hurst']:.3g}, "
                f"λ {r['cutoff_short_m'] * 1e6:.3g}–{r['cutoff_long_m'] * 1e6:.4g} µm"
            )
        elif r:
            text += f"; face read from {r['file']} (R_q {r['rms_m'] * 1e6:.3g} µm levelled)"
        out.append(text)
    return out
