# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic boundary-element cross-check of truncation on the same height map.

Solves the elastic contact of the surface against a rigid flat (non-periodic FFT half-space,
zero-padded to 2nx × 2ny; or periodic with --substrate periodic) at each approach δ with
warptrunc's constrained-CG solver on --device (default), or ContactMechanics' on the CPU
(--solver contactmechanics, needs the extra: pip install "warptrunc[bem]"), and compares load,
stiffness and contact area with the truncation formulas of ``analyze``. Writes OUT/bem.csv (SI
units in the column names), OUT/bem.json (ratios, solver settings, convergence flags, times) and
OUT/bem.png. All or nothing: the files are moved into OUT only when every one of them is
written.

Exit status: 0 when every solve converged; 3 (``EXIT_NOT_CONVERGED``) when any solve stopped
at --maxiter (the outputs are written and flag it), unless --accept-unconverged; 2 for bad
arguments or a missing extra.
"""

from __future__ import annotations

import argparse
import sys

from .._support.outputs import staged_output
from ..contact.adhesion import Adhesion
from ..contact.settings import ELASTIC_TRUNCATION, BemCheckSettings, SolverSettings
from ..params import add_options, from_args
from ._common import (
    add_accept_unconverged,
    add_devices,
    add_material,
    add_run_outputs,
    add_surface_source,
    add_truncation,
    add_warnings,
    material_from_args,
    prepare_devices,
    refuse_unconverged,
    slope_line,
    surface_from_args,
    truncation_from_args,
    warnings_of,
)

NAME = "bem-check"
HELP = "elastic boundary-element cross-check of truncation"
EXIT_NOT_CONVERGED = 3
"""Exit status when any solve did not converge (without --accept-unconverged)."""

SOLVER_FIELDS = ("dtype", "substrate", "pressure_tol", "pentol", "maxiter")
"""The fields of :class:`~warptrunc.contact.SolverSettings` that ``bem-check`` sets."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc bem-check``."""
    add_surface_source(p)
    add_options(
        p,
        BemCheckSettings,
        only=("fractions", "depths"),
        title="approaches (default: 0.05 0.1 0.15 0.2 0.3 0.4 of R_t)",
    )
    g = p.add_argument_group("material and truncation (as analyze)")
    add_material(g)
    add_truncation(g, only=("beta_prime", "increments"), defaults=ELASTIC_TRUNCATION.to_dict())
    s = p.add_argument_group("boundary-element solver")
    add_options(s, BemCheckSettings, only=("solver", "stiffness", "fd_step"))
    add_options(
        s,
        SolverSettings,
        only=SOLVER_FIELDS,
        docs={
            "pentol": "tolerance on penetration; none = rms height/(10·mean(nx, ny)), "
            "ContactMechanics' (fixed for the whole check)"
        },
    )
    add_options(p, Adhesion, title="adhesion (the BEM side, warptrunc's solver; default: none)")
    add_devices(s, "the elastic cross-check (warptrunc solver)")
    add_accept_unconverged(s, EXIT_NOT_CONVERGED)
    add_run_outputs(p, "bem", "skip the PNG")


def _rng(r: list[float] | None) -> str:
    return "n/a (no BEM contact)" if r is None else f"{r[0]:.3g}–{r[1]:.3g}"


def run(args: argparse.Namespace) -> int:
    """Run the comparison and write the outputs."""
    check = from_args(BemCheckSettings, args)
    truncation = truncation_from_args(args, ELASTIC_TRUNCATION.to_dict())
    settings = from_args(SolverSettings, args, adhesion=from_args(Adhesion, args))
    adhesion = settings.adhesion
    from ..contact.check import bem_check, require_bem
    from ..plot.bem import plot_bem_check
    from ..slope import slope_warnings

    if check.solver == "contactmechanics":
        try:
            require_bem()
        except ImportError as exc:
            print(f"warptrunc {NAME}: error: {exc}", file=sys.stderr)
            return 2
    if adhesion.active and check.solver != "warptrunc":
        print(
            f"warptrunc {NAME}: error: --adhesion {adhesion.law} needs --solver warptrunc "
            "(ContactMechanics' solver here is not adhesive)",
            file=sys.stderr,
        )
        return 2
    if args.devices not in (None, 1) and check.solver != "warptrunc":
        print(
            f"warptrunc {NAME}: error: --devices {args.devices} needs --solver warptrunc "
            "(ContactMechanics runs on the CPU)",
            file=sys.stderr,
        )
        return 2
    try:
        prepare_devices(args.devices)
    except ValueError as exc:
        print(f"warptrunc {NAME}: error: {exc}", file=sys.stderr)
        return 2
    material = material_from_args(args)
    s = surface_from_args(args)
    try:
        check.approaches(s.Rt)  # depths below R_t of this map, before any solve
    except ValueError as exc:
        raise ValueError(f"--{exc}") from None
    res = bem_check(
        s,
        check=check,
        truncation=truncation,
        material=material,
        settings=settings,
        progress=not args.no_progress,
        device=args.device,
        devices=args.devices,
    )
    slope = res.settings["surface"]["slope"]
    add_warnings(args, slope_warnings(slope))
    files = "bem.csv, bem.json"
    with staged_output(args.out) as out:  # all or nothing
        res.to_csv(out / "bem.csv")
        res.to_json(out / "bem.json", warnings=warnings_of(args))
        if not args.no_plot:
            import matplotlib.pyplot as plt

            fig = plot_bem_check(
                res,
                out / "bem.png",
                title=f"{s.nx}×{s.ny}, R$_t$ = {s.Rt * 1e6:.3g} µm, E* = "
                f"{material.contact_modulus / 1e9:.4g} GPa, {settings.substrate} half-space "
                f"({check.solver})",
            )
            plt.close(fig)
            files += ", bem.png"
    sm = res.summary()
    print(
        f"{s.nx}×{s.ny} surface, R_t = {s.Rt * 1e6:.4g} µm, E* = "
        f"{material.contact_modulus / 1e9:.4g} GPa, {settings.substrate} half-space ({check.solver} solver); "
        f"{res.depth.size} approaches δ/R_t = "
        f"{res.depth_fraction.min():.3g}–{res.depth_fraction.max():.3g}\n"
        f"F'/F_BEM {_rng(sm['load_ratio'])}, k'/k_BEM {_rng(sm['stiffness_ratio'])}, "
        f"A'/A_BEM {_rng(sm['area_ratio'])}; "
        f"{sm['time_per_solve_s']:.3g} s per solve\n" + slope_line(slope).rstrip("\n")
    )
    if adhesion.active:
        print(
            f"adhesion: {adhesion.law}, w = {adhesion.work:g} J/m², range {adhesion.range:g} m "
            f"(peak stress {adhesion.peak_stress:.4g} Pa); F_BEM includes the law's pull, "
            "A_BEM is the repulsive contact, truncation is not adhesive"
        )
    kappa = sm.get("kappa") or {}
    if kappa.get("bem") is not None:
        print(
            f"κ = (A/A₀)E*h′_rms/p at small load ({kappa['n_solves']} approaches, A/A₀ ≤ "
            f"{kappa['max_area_fraction']:g}): BEM {kappa['bem']:.3g}, Persson "
            f"{kappa['persson']:.3g} (√(8/π) = {kappa['persson_limit']:.3f}), GW "
            f"{kappa['gw']:.3g}; BGT's limit √(2π) = {kappa['bgt_limit']:.3f} "
            "(persson_*, gw_* columns in bem.csv)"
        )
    if not sm["all_converged"]:
        bad = res.depth[~res.converged]
        print(
            f"WARNING: {sm['n_not_converged']} approaches did not converge "
            f"(δ = {', '.join(f'{v:.4g}' for v in bad)} m; flagged in bem.csv/bem.json)",
            file=sys.stderr,
        )
    if sm["any_edge_contact"]:
        print(
            "note: BEM contact reaches the border of the map at some approaches "
            "(edge_contact in bem.csv)",
            file=sys.stderr,
        )
    print(f"wrote {args.out}/{files}")
    if not sm["all_converged"] and not args.accept_unconverged:
        return refuse_unconverged(NAME, EXIT_NOT_CONVERGED)
    return 0
