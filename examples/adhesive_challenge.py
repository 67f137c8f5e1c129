# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The contact-mechanics challenge's adhesive problem on a patch at its own pixel
==============================================================================

What it shows
    The adhesive variant of the contact-mechanics challenge (Müser et al., Tribol. Lett. 65, 118
    (2017)): the challenge's self-affine surface (Hurst H = 0.8, short cut-off λ_s = 0.1 µm,
    E* = 25 MPa against a rigid flat) with short-range adhesion, work of adhesion
    w = 50 mJ/m² over a range ρ = 2.071 nm (the exponential law σ(g) = (w/ρ)·e^(−g/ρ), peak
    stress w/ρ = 24 MPa ≈ E*). The flat approaches, presses to a nominal pressure of about
    0.1 E* and retracts under displacement control, on the periodic half-space; drawn are the
    load against the approach on both branches (the pull-off force is the unloading branch's
    most tensile load) and the repulsive and attractive areas against the load, beside the
    non-adhesive solution at the same approaches.

    The patch. The range ρ = 2.071 nm is about the challenge's own pixel (3.05 nm on its
    32768² grid of L = 100 µm). A coarser grid of the full side would put a hundred ranges into
    one pixel, and the law would act pixel by pixel, not as a field: a grid-dependent answer.
    This example keeps the pixel and takes a periodic patch of 512² pixels (1.5625 µm) with the
    challenge's spectrum C(q) on the wavelengths the patch holds (1.56 µm down to 0.1 µm; the
    longer ones, and with them most of the rms height, are gone): h_rms = 0.099 µm instead of
    0.78 µm, h′_rms 0.90 instead of 1 (``challenge_patch_spec``). Loads are per unit nominal
    area (p = F/A₀), so the patch reads as a piece of the interface.

Key steps
    ``challenge_patch_spec(n)`` → ``self_affine_surface`` → ``solve_contact`` with
    ``SolverSettings(adhesion=Adhesion("exponential", work=w, range=ρ), substrate="periodic")``
    over approaches that rise and fall, and the same without adhesion → ``force_approach``
    (pull-off, jump-in, jump-out, dissipated work).

Outputs (in ``--out``)
    adhesion.csv (each row: branch, approach, p/E*, a_r, attractive a_r, mean gap, the
    non-adhesive p/E* and a_r, convergence), adhesion.json (the surface, the law, the cycle's
    summary), adhesion.png.

Run::

    python examples/adhesive_challenge.py --out results/adhesion          # 512², about 15 min on 2 cores
    python examples/adhesive_challenge.py --quick --out results/adhesion  # 64², seconds
    python examples/adhesive_challenge.py --device cuda:0 --n 2048 --out results/adhesion
"""

from __future__ import annotations

import argparse
import csv
import json
from pathlib import Path

import numpy as np

from warptrunc import Material
from warptrunc.compare.challenge import ADHESION, challenge_patch_spec
from warptrunc.contact import Adhesion, force_approach, solve_contact
from warptrunc.contact.settings import CurveSettings, SolverSettings
from warptrunc.presets import CHALLENGE_MATERIAL
from warptrunc.selfaffine import self_affine_surface
from warptrunc.slope import slope_statistics


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ... (default: CUDA if present)")
    ap.add_argument("--n", type=int, default=512, help="pixels per side of the patch (3.05 nm each)")
    ap.add_argument("--seed", type=int, default=0, help="phase seed")
    ap.add_argument("--steps", type=int, default=11, help="approaches on the way in (and out)")
    ap.add_argument(
        "--law", choices=("exponential", "maugis"), default="exponential", help="interaction law"
    )
    ap.add_argument("--out", type=Path, default=Path("results/adhesion"), help="output folder")
    ap.add_argument("--quick", action="store_true", help="64², 6 approaches each way")
    ap.add_argument(
        "--no-show", action="store_true", help="do not open a window (figures are saved)"
    )
    args = ap.parse_args(argv)
    n, steps = (64, 6) if args.quick else (args.n, args.steps)

    spec = challenge_patch_spec(n, seed=args.seed)
    surface = self_affine_surface(spec, device=args.device)
    h = np.asarray(surface.heights, dtype=np.float64)
    slope = slope_statistics(surface, per_decade=False)
    h_rms = float(h.std())
    law = Adhesion(
        args.law, work=ADHESION["work_of_adhesion"], range=ADHESION["interaction_range"]
    )
    material: Material = CHALLENGE_MATERIAL
    e_star = material.contact_modulus
    # from half an rms height apart (out of the range: no force) to two rms heights of approach
    up = np.linspace(-0.5, 2.0, steps) * h_rms
    depths = np.concatenate([up, up[::-1][1:]])
    solve = dict(
        pixel_size=surface.dx, material=material, curve=CurveSettings(stiffness="none"),
        device=args.device,
    )  # fmt: skip
    adhesive = solve_contact(
        h, depths, settings=SolverSettings(adhesion=law, substrate="periodic"), **solve
    )
    # without adhesion a flat that has not reached the highest point carries nothing: solved
    # only at the positive approaches, zero load and area at the others
    touch = depths > 0
    plain = solve_contact(
        h, depths[touch], settings=SolverSettings(substrate="periodic"), **solve
    )
    p0, area0 = np.zeros(depths.size), np.zeros(depths.size)
    p0[touch], area0[touch] = plain.load, plain.area
    cycle = force_approach(adhesive)

    a0 = h.size * surface.dx * surface.dy
    p = adhesive.load / a0 / e_star
    p0 /= a0 * e_star
    branch = np.where(cycle.loading, "loading", "unloading")
    args.out.mkdir(parents=True, exist_ok=True)
    with open(args.out / "adhesion.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["branch", "approach_m", "p_over_E_star", "area_fraction",
                    "attractive_area_fraction", "mean_gap_m", "p_over_E_star_non_adhesive",
                    "area_fraction_non_adhesive", "converged"])  # fmt: skip
        for i in range(depths.size):
            w.writerow([branch[i], f"{depths[i]:.9g}", f"{p[i]:.9g}",
                        f"{adhesive.area[i] / a0:.9g}", f"{adhesive.attractive_area[i] / a0:.9g}",
                        f"{adhesive.mean_gap[i]:.9g}", f"{p0[i]:.9g}", f"{area0[i] / a0:.9g}",
                        bool(adhesive.converged[i])])  # fmt: skip
    summary = {
        "surface": {**spec.to_dict(), "h_rms_m": h_rms, "slope_rms": slope.slope_rms,
                    "pixel_m": surface.dx},  # fmt: skip
        "adhesion": law.to_dict(),
        "contact_modulus_Pa": e_star,
        "range_over_pixel": law.range / surface.dx,
        "cycle": cycle.to_dict(),
        "pull_off_pressure_over_E_star": cycle.pull_off_force / a0 / e_star,
        "all_converged": bool(adhesive.all_converged and plain.all_converged),
        "iterations": {"adhesive": int(adhesive.n_iterations.sum()),
                       "non_adhesive": int(plain.n_iterations.sum())},  # fmt: skip
    }
    (args.out / "adhesion.json").write_text(json.dumps(summary, indent=2, default=float) + "\n")

    print(
        f"{n}² patch of {n * surface.dx * 1e6:.4g} µm ({surface.dx * 1e9:.3g} nm pixels, "
        f"ρ = {law.range / surface.dx:.2f} pixel), h_rms = {h_rms * 1e6:.3g} µm, "
        f"h′_rms = {slope.slope_rms:.3f}"
    )
    print(
        f"pull-off p/E* = {summary['pull_off_pressure_over_E_star']:.3g} "
        f"(σ = {cycle.pull_off_force / a0 / 1e6:.3g} MPa), jump-in {cycle.jump_in}, "
        f"jump-out {cycle.jump_out}, dissipated work {cycle.dissipated_work / a0 * 1e3:.3g} mJ/m²"
        f"; converged: {summary['all_converged']}"
    )

    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
    load = cycle.loading
    ax1.plot(depths[load] / h_rms, p[load], "o-", color="C0", label="adhesive, loading")
    ax1.plot(depths[~load] / h_rms, p[~load], "s--", color="C3", label="adhesive, unloading")
    ax1.plot(depths[load] / h_rms, p0[load], "-", color="0.5", label="non-adhesive")
    ax1.axhline(0.0, color="0.8", lw=0.8)
    i = int(np.argmin(adhesive.load))
    ax1.annotate("pull-off", (depths[i] / h_rms, p[i]), textcoords="offset points",
                 xytext=(10, -12))  # fmt: skip
    ax1.set(xlabel="approach δ / h_rms", ylabel="nominal pressure p / E*")
    ax1.legend(fontsize=8)
    ax2.plot(p[load], adhesive.area[load] / a0, "o-", color="C0", label="repulsive, loading")
    ax2.plot(p[~load], adhesive.area[~load] / a0, "s--", color="C3", label="repulsive, unloading")
    ax2.plot(p, adhesive.attractive_area / a0, ".", color="C2", label="attractive (within ρ)")
    ax2.plot(p0[load], area0[load] / a0, "-", color="0.5", label="non-adhesive")
    ax2.set(xlabel="nominal pressure p / E*", ylabel="area fraction a_r")
    ax2.legend(fontsize=8)
    fig.suptitle(
        f"challenge's adhesive problem: {n}² patch at {surface.dx * 1e9:.3g} nm, "
        f"w = {law.work * 1e3:g} mJ/m², ρ = {law.range * 1e9:.3g} nm ({args.law}), "
        f"E* = {e_star / 1e6:g} MPa",
        fontsize=9,
    )
    fig.savefig(args.out / "adhesion.png", dpi=120)
    print(f"wrote {args.out}/adhesion.csv, adhesion.json, adhesion.png")
    if not args.no_show:  # pragma: no cover - interactive use only
        plt.show()
    plt.close(fig)
    return 0


if __name__ == "__main__":
    if (status := main()) != 0:
        raise SystemExit(status)
