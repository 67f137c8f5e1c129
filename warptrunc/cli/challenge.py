# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The contact-mechanics challenge (Müser et al. 2017) beside Persson, GW, BGT and truncation.

Solves the elastic contact of the challenge's surface (periodic, L = 100 µm, H = 0.8,
λ_r = 20 µm, λ_s = 0.1 µm, h′_rms = 1; E* = 25 MPa) against a rigid flat on the periodic
half-space at nominal pressures p/E* from --p-min to --p-max, first on n² and 2n² pixels of the
same content (the grid study: how much a_r and ū move when the pixel is halved), then compares
the finer solution's relative contact area a_r(p), mean gap ū(p) and stiffness K(p) = −dp/dū,
and at --reference-pressure the distributions of pressure, gap and contact-patch area, with
Persson's theory, Greenwood–Williamson, Bush–Gibson–Thomas and truncation (Eq. 2) on the same
surface. Below 2048² the challenge's λ_s is under 2 pixels: the surface is then the challenge's
spectrum cut at 2 pixels (--short-cutoff to choose), which lowers h′_rms (0.73 at 512²).

--input FILE reads the challenge's own map from its HDF5 file (SurfaceTopography's h5 reader;
an HDF5 file stores no unit: --height-unit, else the heights are scaled to h′_rms = 1); the grid
study then refines the map by Fourier interpolation (--no-refine to skip it).

Writes OUT/challenge.json (every column and distribution, the grid study, κ, the slope of
K(p), the surface and the settings; strict JSON), OUT/challenge.csv (one row per pressure, SI
units in the names) and OUT/challenge.png (unless --no-plot); all or nothing.
"""

from __future__ import annotations

import argparse
import sys

from ..compare.challenge import ChallengeSettings
from ..contact.settings import SolverSettings
from ..params import add_options, from_args
from ._common import (
    add_input,
    add_run_outputs,
    add_warnings,
    slope_line,
    warnings_of,
)

NAME = "challenge"
HELP = "the contact-mechanics challenge beside Persson, GW, BGT and truncation"
SOLVER_FIELDS = ("dtype", "pressure_tol", "pentol", "maxiter")
"""The fields of :class:`~warptrunc.contact.SolverSettings` that ``challenge`` sets (the
half-space is periodic)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc challenge``."""
    g = p.add_argument_group("surface and loads")
    add_input(g, "the challenge's HDF5 file (its own realisation), instead of generating one")
    add_options(g, ChallengeSettings)
    s = p.add_argument_group("boundary-element solver (periodic half-space)")
    add_options(s, SolverSettings, only=SOLVER_FIELDS)
    add_run_outputs(p, "challenge", "skip the PNG")


def run(args: argparse.Namespace) -> int:
    """Run the study and write the outputs."""
    from .._support.outputs import staged_output, write_columns_csv
    from ..compare.challenge import challenge_study, read_challenge_surface
    from ..slope import slope_warnings

    study = from_args(ChallengeSettings, args)
    settings = from_args(SolverSettings, args, substrate="periodic")
    surface = None
    if args.input is not None:
        surface = read_challenge_surface(args.input, height_unit=study.height_unit)
    res = challenge_study(
        surface,
        study,
        settings=settings,
        progress=not args.no_progress,
        device=args.device,
    )
    rec = res.surface["slope"]
    add_warnings(args, slope_warnings(rec))
    files = "challenge.json, challenge.csv"
    with staged_output(args.out) as out:
        res.to_json(out / "challenge.json", warnings=warnings_of(args))
        write_columns_csv(out / "challenge.csv", res.to_dict())
        if not args.no_plot:
            import matplotlib.pyplot as plt

            from ..plot.challenge import plot_challenge

            g = res.grid_study
            fig = plot_challenge(
                res,
                out / "challenge.png",
                title=f"contact-mechanics challenge, {res.surface['grid'][0]}² "
                f"({res.surface['pixel_m'] * 1e9:.3g} nm pixels), h′_rms = {res.slope_rms:.3g}, "
                f"E* = {res.contact_modulus / 1e6:.3g} MPa"
                + (f"; grid study {g['n'][0]}² → {g['n'][1]}²" if g else ""),
            )
            plt.close(fig)
            files += ", challenge.png"
    _print_summary(res)
    print(slope_line(rec).rstrip("\n"))
    print(f"wrote {args.out}/{files}")
    return 0


def _print_summary(res) -> None:
    g, k, s = res.grid_study, res.kappa, res.stiffness_slope
    n = res.surface["grid"][0]
    if g:
        print(
            f"grid study {g['n'][0]}² → {g['n'][1]}² (the same content): a_r moves by up to "
            f"{g['max_change_area_fraction']:.3g}, ū by {g['max_change_mean_gap']:.3g} "
            f"(relative, {g['loads_judged']} loads); converged in the pixel within "
            f"{g['tolerance']:g}: {'yes' if g['converged_in_pixel'] else 'no'}"
        )
        if not g["converged_in_pixel"]:
            print(
                f"warning: the BEM at {n}² is not converged in the pixel within "
                f"{g['tolerance']:g}: read its a_r and ū with that change in mind",
                file=sys.stderr,
            )
    if k.get("bem") is not None:
        print(
            f"κ = a_r E* h′_rms/p at small load ({k['n_loads']} loads, a_r ≤ "
            f"{k['max_area_fraction']:g}): BEM {k['bem']:.3f} "
            f"({k['bem_range'][0]:.3f}–{k['bem_range'][1]:.3f}), Persson {k['persson']:.3f} "
            f"(limit √(8/π) = {k['persson_limit']:.3f}), BGT {k['bgt']:.3f} "
            f"(limit √(2π) = {k['bgt_limit']:.3f}), GW {k['gw']:.3f}"
        )
    if s.get("bem") is not None:
        tr = "n/a" if s.get("truncation") is None else f"{s['truncation']:.3f}"
        print(
            f"d ln K/d ln p over the same loads: BEM {s['bem']:.3f}, Persson "
            f"{s['persson']:.3f}, GW {s['gw']:.3f}, BGT {s['bgt']:.3f}, truncation {tr}"
        )
    bad = int((~res.converged).sum())
    if bad:
        print(f"warning: {bad} elastic solves did not converge (bem_converged)", file=sys.stderr)
