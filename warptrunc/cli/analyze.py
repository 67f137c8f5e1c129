# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation analysis: contact area, stiffness and load against depth, and the power-law fit.

Writes OUT/curve.csv (depth_m, n_contact_pixels, contact_area_m2, stiffness_N_per_m, load_N,
Ec_over_E, F_over_EA, Ec_over_Estar, then the island-resolved model's
stiffness_islands_N_per_m, load_islands_N, Ec_over_E_islands, Ec_over_Estar_islands; Ec_over_E
is E_c/E with E the Young's modulus, as the paper's Figs. 6 and 9, Ec_over_Estar is E_c/E*, E*
the contact modulus), OUT/fit.json (alpha and beta of E_c/E = beta·[F/(E·A)]^alpha,
beta_contact_modulus of E_c/E*, normalisation "E_c/E", r2 and the fit range of Eq. 2;
"islands": the same fit of the island-resolved model), OUT/stiffness.png
(E_c/E against F/(E·A), log–log, with the fitted line, as the paper's Fig. 9) and
OUT/area_fraction.png (A_c/A against depth).

All or nothing: the files are written under temporary names and moved into OUT only when the
whole result is good; a failed run leaves OUT as it was (and no OUT if it did not exist).
fit.json is strict JSON: "E_i": null in "material" means a rigid flat (E_i = ∞).

A generated surface that needs more than half of the free memory of the device or of the host
(which holds the map's copy) is streamed: generated and truncated by row bands, never held whole
(``warptrunc.stream``; ``--stream`` forces it). The counts are those of the in-memory path.
fit.json says which path the computation took (``"path": "in-memory"`` or ``"streamed"``); a
map read from a file is named in its provenance (``"input"``: path, size, SHA-256).

Island-resolved truncation (``--islands``, on by default for maps in memory): besides Eq. 2's
one flat punch of the whole truncated area, k' = β'(2/√π)E*√A', every island of the truncated
set is a punch of its own, k_isl = β'(2/√π)E*·Σ_i √A_i (islands by ``--connectivity``), and
F_isl = ∫k_isl dω (``warptrunc.stiffness.island_stiffness_curve``). It costs one island pass
over the depths (about 0.1 s at 1024², 200 depths, on a CPU). A streamed map has no island
pass (fit.json: "islands": null).
"""

from __future__ import annotations

import argparse
import contextlib
import math

from .._support.outputs import staged_output, strict_json
from .._support.provenance import provenance
from ..material import Material
from ..plot._worker import FigureWorker, plain
from ._common import (
    add_device,
    add_fit_range,
    add_material,
    add_no_plot,
    add_out,
    add_streaming,
    add_surface_source,
    add_truncation,
    add_warnings,
    fit_range_from_args,
    material_from_args,
    slope_line,
    surface_from_args,
    truncation_from_args,
    warnings_of,
    wm_spec_from_args,
)

NAME = "analyze"
HELP = "truncation analysis to the stiffness–load power law"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc analyze``."""
    add_surface_source(p, scan_rule="fit")
    add_truncation_options(p)
    add_fit_range(p.add_argument_group("fit range"))
    add_device(p)
    add_streaming(p)
    add_out(p)
    add_no_plot(p, "stiffness.png and area_fraction.png")


def add_truncation_options(p: argparse.ArgumentParser, *, many: bool = False) -> None:
    """Truncation (:class:`~warptrunc.truncation.settings.TruncationSettings`) and material
    (:class:`Material`, no hardness) options (shared with ``warptrunc sweep``); ``many`` (the
    sweep) lets the sweepable ones take several values (a sweep axis)."""
    g = p.add_argument_group("truncation and material")
    add_truncation(g, many=many)
    add_material(g, many=many)


def run(args: argparse.Namespace) -> int:
    """Analyse and write the outputs."""
    truncation = truncation_from_args(args)
    fit_range = fit_range_from_args(args)
    if truncation.islands and args.stream:
        raise ValueError("--islands needs the map in memory; a streamed map has no island pass")
    if args.stream and args.input is not None:
        raise ValueError(f"--stream applies to generated surfaces, not to --input {args.input}")
    if args.stream and fit_range.rt_percentile is not None:
        raise ValueError("--rt-percentile needs the map in memory; it cannot be streamed")
    # the figures' process starts first: matplotlib's import overlaps Warp's (in ..analysis)
    figures = None if args.no_plot else FigureWorker()
    with figures or contextlib.nullcontext():
        return _run(args, truncation, fit_range, figures)


def _run(args: argparse.Namespace, truncation, fit_range, figures) -> int:
    """:func:`run` with its settings and figure worker (None: ``--no-plot``)."""
    from ..analysis import FitRangeError, analyze

    material = material_from_args(args)
    generated_whole = args.input is not None or getattr(args, "surface", "wm") == "self-affine"
    source = surface_from_args(args) if generated_whole else wm_spec_from_args(args)
    tickets: dict[str, int] = {}

    def draw_area(curve) -> None:  # drawn while the islands are counted
        if figures is not None:
            tickets["area"] = figures.submit(
                "area_fraction", plain(curve, "depth", "Rt", "area_fraction"), log=True
            )

    try:
        a = analyze(
            source,
            truncation=truncation,
            fit=fit_range,
            material=material,
            stream=True if args.stream else "auto",
            band_rows=args.band_rows,
            device=args.device,
            on_curve=draw_area,
        )
    except FitRangeError as exc:
        if args.input is not None and fit_range.spikes:
            from ..plausibility import check_spikes

            add_warnings(args, check_spikes(source))  # the rule's report never came back
        raise ValueError(_fit_range_message(exc, truncation, fit_range)) from None
    curve, sc, fit, meta = a.curve, a.stiffness, a.fit, a.surface
    nx, ny, Rt = meta["nx"], meta["ny"], meta["Rt_m"]
    isl, isl_fit = a.islands, a.islands_fit
    add_warnings(args, list(a.warnings))
    if figures is not None:  # drawn while curve.csv and fit.json are written
        if "area" not in tickets:
            draw_area(curve)
        both = isl_fit is not None
        sc_, fit_ = _plain_stiffness(sc), _plain_fit(fit)
        tickets["stiffness"] = figures.submit(
            "stiffness_load",
            [sc_, _plain_stiffness(isl)] if both else sc_,
            [fit_, _plain_fit(isl_fit)] if both else fit_,
            labels=["Eq. 2 (one punch)", "islands (one punch each)"]
            if both
            else ["truncation analysis"],
            flags=[a.fit_error, a.islands_fit_error] if both else [a.fit_error],
            title=_plot_title(meta, material, nx, ny, Rt),
        )
    with staged_output(args.out) as out:  # all or nothing
        sc.to_csv(out / "curve.csv", islands=a.islands)
        (out / "fit.json").write_text(
            strict_json(
                {
                    **a.summary(),
                    "provenance": provenance(args.device, input_path=args.input),
                    "warnings": warnings_of(args),
                }
            )
        )
        if figures is not None:
            (out / "stiffness.png").write_bytes(figures.result(tickets["stiffness"]))
            (out / "area_fraction.png").write_bytes(figures.result(tickets["area"]))
    print(
        f"{nx}×{ny} surface{_source(args)} ({_describe(a.path)}), R_t = {Rt * 1e6:.4g} µm; "
        f"{truncation.increments} increments to "
        f"ω_max = {curve.depth[-1] * 1e6:.4g} µm; final contact {curve.area_fraction[-1]:.3%} of A\n"
        f"E_c/E = {fit.beta:.4g}·[F/(E·A)]^{fit.alpha:.4f}  (E Young's modulus; r² = {fit.r2:.4f}, "
        f"{fit.n_points} increments with ≥ {fit.min_pixels} contact pixels)\n"
        + _islands_note(a.islands_fit)
        + slope_line(meta.get("slope"))
        + _clip_note(meta)
        + _range_note(a.fit_range)
        + f"wrote {args.out}/curve.csv, fit.json"
        + ("" if args.no_plot else ", stiffness.png, area_fraction.png")
    )
    return 0


def _plain_stiffness(curve):
    """What stiffness.png reads of a stiffness curve, for the figure process."""
    return plain(curve, "load", "F_over_EA", "Ec_over_E")


def _plain_fit(fit):
    """What stiffness.png reads of a power-law fit (None stays None)."""
    names = ("alpha", "beta", "r2", "F_over_EA_min", "F_over_EA_max")
    return None if fit is None else plain(fit, *names)


def _islands_note(fit) -> str:
    if fit is None:
        return ""
    return (
        f"islands: E_c/E = {fit.beta:.4g}·[F/(E·A)]^{fit.alpha:.4f}  (r² = {fit.r2:.4f}; "
        "one flat punch per island)\n"
    )


def _plot_title(meta: dict, material: Material, nx: int, ny: int, Rt: float) -> str:
    """stiffness.png's title: the map (its file when read, D when generated), its size in
    pixels and in µm or mm, R_t, and the material."""
    from pathlib import Path

    d = meta.get("D")
    name = Path(str(meta.get("source") or "")).name.replace("$", r"\$")
    name = f"{name[:28]}…{name[-12:]}" if len(name) > 41 else name
    head = name or (f"WM surface, D = {d:g}" if isinstance(d, (int, float)) else "")
    mm = max(meta.get("lx_m", 0.0), meta.get("ly_m", 0.0)) >= 1e-3
    f, u = (1e3, "mm") if mm else (1e6, "µm")
    size = f"{meta['lx_m'] * f:.4g}×{meta['ly_m'] * f:.4g} {u}, " if "lx_m" in meta else ""
    flat = "rigid flat" if math.isinf(material.E_i) else f"E$_i$ = {material.E_i / 1e9:.3g} GPa"
    return (
        f"{head + chr(10) if head else ''}{nx}×{ny} px, {size}R$_t$ = {Rt * 1e6:.3g} µm\n"
        f"E = {material.E / 1e9:.3g} GPa, ν = {material.nu:g}, {flat}"
    )


def _range_note(rule: dict) -> str:
    if rule.get("rule") != "auto":
        return ""
    spikes = rule["spikes_masked"]
    done = [f"{spikes['count']} spike pixels masked"] if spikes else []
    for action in ("extended", "cut"):
        if rule.get(f"depth_{action}"):
            done.append(f"ω_max {action} to {rule[f'depth_{action}']['to_fraction']:.3g}·R_t")
    return (
        f"automatic rule (--fit-range auto; {rule['reason']}): {', '.join(done)}; "
        f"ω_max = {rule['max_depth_m'] * 1e6:.4g} µm\n"
    )


def _clip_note(meta: dict) -> str:
    if "rt_percentile" not in meta:
        return ""
    lo, hi = meta["rt_percentile"]
    return (
        f"heights clipped to percentiles {lo:g}–{hi:g} (--rt-percentile): R_t "
        f"{meta['Rt_raw_m'] * 1e6:.4g} → {meta['Rt_m'] * 1e6:.4g} µm, "
        f"{meta['n_clipped_above']} pixels above, {meta['n_clipped_below']} below\n"
    )


def _fit_range_message(exc, truncation, fit_range) -> str:
    """The fit's error (a ``FitRangeError``) with the option values that would work for
    this map."""
    from ..robust import fit_range_advice

    s = exc.surface
    msg = str(exc).split("; need at least")[0]
    msg = msg.replace("(min_pixels=", "(--min-pixels ").replace(", depth_window=None", "")
    msg = msg.replace(", depth_window=", ", --depth-window ")
    if s is None:
        return f"{msg}; need at least 3: lower --min-pixels, raise --max-depth-fraction"
    advice = fit_range_advice(
        s.heights,
        increments=truncation.increments,
        max_depth_fraction=truncation.max_depth_fraction,
        max_depth=truncation.max_depth,
        min_pixels=fit_range.min_pixels,
        depth_window=fit_range.depth_window,
    )
    if not advice:
        return (
            f"{msg}; need at least 3, and no single change of --max-depth-fraction, "
            "--min-pixels or --rt-percentile gives them on this map"
        )
    return f"{msg}; need at least 3; for this map any one of these works: " + "; ".join(advice)


def _source(args: argparse.Namespace) -> str:
    """The words naming the file a map was read from (empty for a generated map)."""
    return "" if args.input is None else f" from {args.input}"


def _describe(path: dict) -> str:
    if path["path"] == "streamed":
        st = path["streaming"]
        return f"streamed: {st['n_bands']} bands of {st['band_rows']} rows, {st['reason']}"
    return "in memory"
