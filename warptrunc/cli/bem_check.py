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
import itertools
import sys

from .._support.atomic import staged_output
from ._common import (
    add_devices,
    add_material,
    add_run_outputs,
    add_surface_source,
    check_increments,
    integer,
    material_from_args,
    positive,
    prepare_devices,
    real,
    surface_from_args,
    warnings_of,
)

NAME = "bem-check"
HELP = "elastic boundary-element cross-check of truncation"
EXIT_NOT_CONVERGED = 3
"""Exit status when any solve did not converge (without --accept-unconverged)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc bem-check``."""
    add_surface_source(p)
    a = p.add_argument_group("approaches (default: 0.05 0.1 0.15 0.2 0.3 0.4 of R_t)")
    x = a.add_mutually_exclusive_group()
    x.add_argument(
        "--fractions", type=real(0.0, 1.0, unit="(fraction of R_t)"), nargs="+", default=None,
        help="approaches δ as fractions of R_t, strictly increasing, in (0, 1)",
    )  # fmt: skip
    x.add_argument(
        "--depths", type=positive("m"), nargs="+", default=None,
        help="approaches δ (m), strictly increasing, in (0, R_t)",
    )  # fmt: skip
    g = p.add_argument_group("material (as analyze)")
    add_material(g)
    g.add_argument("--beta-prime", type=positive(), default=1.0, help="geometric factor β' of Eq. 2")
    g.add_argument(
        "--increments", type=integer(1, 10_000_000), default=400,
        help="truncation depth increments from 0 to the largest δ (load integral)",
    )  # fmt: skip
    s = p.add_argument_group("boundary-element solver")
    s.add_argument(
        "--solver", choices=["warptrunc", "contactmechanics"], default="warptrunc",
        help="warptrunc: constrained CG on --device; contactmechanics: the CPU reference "
        '(needs pip install "warptrunc[bem]")',
    )  # fmt: skip
    s.add_argument(
        "--stiffness", choices=["central", "barber"], default="central",
        help="k = dF/dδ by the central difference, or by Barber's flat punch of the contact set "
        "(warptrunc solver only)",
    )  # fmt: skip
    s.add_argument(
        "--dtype", choices=["float64", "float32"], default="float64",
        help="precision of the warptrunc solver",
    )  # fmt: skip
    s.add_argument(
        "--substrate", choices=["free", "periodic"], default="free",
        help="free: non-periodic half-space, zero-padded to 2nx × 2ny; periodic: for periodic maps",
    )  # fmt: skip
    s.add_argument(
        "--fd-step", type=real(0.0, 1.0), default=0.02,
        help="relative step h of the central difference k = dF/dδ over δ(1 ± h)",
    )  # fmt: skip
    s.add_argument(
        "--pressure-tol", type=positive(), default=1e-5,
        help="tolerance on tensile/pad pressure relative to E* (dimensionless)",
    )  # fmt: skip
    s.add_argument(
        "--pentol", type=positive("m"), default=None,
        help="tolerance on penetration (m); default rms height/(10·mean n)",
    )  # fmt: skip
    s.add_argument("--maxiter", type=integer(1), default=10000, help="largest CG iterations per solve")
    add_devices(s, "the elastic cross-check (warptrunc solver)")
    s.add_argument(
        "--accept-unconverged", action="store_true",
        help=f"exit 0 even when a solve stopped at --maxiter (default: exit {EXIT_NOT_CONVERGED})",
    )  # fmt: skip
    add_run_outputs(p, "bem", "skip the PNG")


def _check_approaches(args: argparse.Namespace, Rt: float | None) -> None:
    """--fractions / --depths increase strictly; --depths lie below R_t of the map (when
    ``Rt`` is given). Errors name the option, the values as typed and the rule."""
    for opt, vals, what in (("--fractions", args.fractions, "fractions of R_t, each in (0, 1)"),
                            ("--depths", args.depths, "m, each in (0, R_t)")):  # fmt: skip
        if vals is None:
            continue
        got = " ".join(f"{v:g}" for v in vals)
        if any(b <= a for a, b in itertools.pairwise(vals)):
            raise ValueError(f"{opt} must increase strictly (approaches δ in {what}), got {got}")
        if opt == "--depths" and Rt is not None and max(vals) >= Rt:
            raise ValueError(
                f"--depths must be in (0, R_t) = (0, {Rt:.6g}) m for this surface, got {got} "
                "(metres; --fractions takes fractions of R_t)"
            )


def _rng(r: list[float] | None) -> str:
    return "n/a (no BEM contact)" if r is None else f"{r[0]:.3g}–{r[1]:.3g}"


def run(args: argparse.Namespace) -> int:
    """Run the comparison and write the outputs."""
    check_increments(args.increments, "--increments")
    from ..contact.check import bem_check, require_bem
    from ..plot.bem import plot_bem_check

    if args.stiffness == "barber" and args.solver != "warptrunc":
        print(f"warptrunc {NAME}: error: --stiffness barber needs --solver warptrunc",
              file=sys.stderr)  # fmt: skip
        return 2
    if args.solver == "contactmechanics":
        try:
            require_bem()
        except ImportError as exc:
            print(f"warptrunc {NAME}: error: {exc}", file=sys.stderr)
            return 2
    if args.devices not in (None, 1) and args.solver != "warptrunc":
        print(f"warptrunc {NAME}: error: --devices {args.devices} needs --solver warptrunc "
              "(ContactMechanics runs on the CPU)", file=sys.stderr)  # fmt: skip
        return 2
    try:
        prepare_devices(args.devices)
    except ValueError as exc:
        print(f"warptrunc {NAME}: error: {exc}", file=sys.stderr)
        return 2
    _check_approaches(args, None)  # before the surface is made
    material = material_from_args(args)
    s = surface_from_args(args)
    _check_approaches(args, s.Rt)
    res = bem_check(
        s, args.depths, fractions=args.fractions, material=material,
        beta_prime=args.beta_prime, substrate=args.substrate, increments=args.increments,
        fd_step=args.fd_step, pressure_tol=args.pressure_tol, pentol=args.pentol,
        maxiter=args.maxiter, solver=args.solver, stiffness=args.stiffness, dtype=args.dtype,
        progress=not args.no_progress and sys.stderr.isatty(), device=args.device,
        devices=args.devices,
    )  # fmt: skip
    files = "bem.csv, bem.json"
    with staged_output(args.out) as out:  # all or nothing
        res.to_csv(out / "bem.csv")
        res.to_json(out / "bem.json", warnings=warnings_of(args))
        if not args.no_plot:
            import matplotlib.pyplot as plt

            fig = plot_bem_check(
                res, out / "bem.png",
                title=f"{s.nx}×{s.ny}, R$_t$ = {s.Rt * 1e6:.3g} µm, E* = "
                f"{material.contact_modulus / 1e9:.4g} GPa, {args.substrate} half-space "
                f"({args.solver})",
            )  # fmt: skip
            plt.close(fig)
            files += ", bem.png"
    sm = res.summary()
    print(
        f"{s.nx}×{s.ny} surface, R_t = {s.Rt * 1e6:.4g} µm, E* = "
        f"{material.contact_modulus / 1e9:.4g} GPa, {args.substrate} half-space ({args.solver} solver); "
        f"{res.depth.size} approaches δ/R_t = "
        f"{res.depth_fraction.min():.3g}–{res.depth_fraction.max():.3g}\n"
        f"F'/F_BEM {_rng(sm['load_ratio'])}, k'/k_BEM {_rng(sm['stiffness_ratio'])}, "
        f"A'/A_BEM {_rng(sm['area_ratio'])}; "
        f"{sm['time_per_solve_s']:.3g} s per solve"
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
        print(
            f"warptrunc {NAME}: exit {EXIT_NOT_CONVERGED}: not every solve converged "
            "(--accept-unconverged to exit 0)",
            file=sys.stderr,
        )
        return EXIT_NOT_CONVERGED
    return 0
