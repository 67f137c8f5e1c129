# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The contact-mechanics challenge: elastic contact beside Persson, GW, BGT and truncation
=======================================================================================

What it shows
    The problem of the contact-mechanics challenge (Müser et al., Tribol. Lett. 65, 118 (2017)):
    a periodic self-affine surface, L = 100 µm, Hurst H = 0.8, roll-off λ_r = 20 µm, short
    cut-off λ_s = 0.1 µm, rms gradient h′_rms = 1, against a rigid flat, E* = 25 MPa. The
    elastic solution on the periodic half-space (warptrunc's boundary-element solver) gives the
    relative contact area a_r(p), the mean gap ū(p) and the stiffness K(p) = −dp/dū over
    nominal pressures p/E* = 10⁻⁴ … 10⁻¹, drawn beside Persson's theory, Greenwood–Williamson
    (GW), Bush–Gibson–Thomas (BGT) and truncation (Eq. 2) on the same surface.

    The grid. The challenge's grid is 32768² (3.05 nm pixels, λ_s = 33 pixels). This example
    runs at 512² (195 nm pixels), where λ_s = 0.1 µm would be half a pixel: it **coarsens λ_s
    to 2 pixels** (0.39 µm) and keeps the challenge's spectrum C(q) for every wavelength above
    it. What that changes: the wavelengths between 0.1 and 0.39 µm are gone, and with them
    almost half of the mean square slope (h′_rms² grows as q_s^(2−2H)): h′_rms is 0.73
    instead of 1, so at a given load the contact area is larger (at small loads
    a_r ≈ κ p/(E* h′_rms)) and the pressures are less spread (their rms in full contact is
    E* h′_rms/2); h_rms, set by the roll-off, stays 0.782 µm (0.783 µm with λ_s = 0.1 µm),
    and ū, set by the long wavelengths, moves less than a_r. The theories read the spectrum of
    the map drawn, so they see the same coarsened surface. The grid study solves the same
    content again at 1024² and compares on the finer grid: how much a_r and ū move when the
    pixel is halved is printed and kept in challenge.json.

Key steps
    ``ChallengeSettings`` (grid, pressures) → ``challenge_study`` (the BEM at n² and 2n²,
    Persson, GW, BGT and truncation at the same pressures, the distributions at p = 0.01 E*) →
    ``plot_challenge`` (a_r, ū, K; ``--distributions`` adds P(σ), P(u) and the patch areas).

Outputs (in ``--out``)
    challenge.json (every column, the grid study, κ, the slope of K(p)), challenge.png.

Run::

    python examples/contact_challenge.py --out results/challenge          # 512² → 1024², minutes
    python examples/contact_challenge.py --quick --out results/challenge  # 128² → 256², seconds
"""

from __future__ import annotations

import argparse
from pathlib import Path

from warptrunc.compare.challenge import ChallengeSettings, challenge_study


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ... (default: CUDA if present)")
    ap.add_argument("--n", type=int, default=512, help="pixels per side (the grid study adds 2n)")
    ap.add_argument("--seed", type=int, default=0, help="phase seed")
    ap.add_argument("--per-decade", type=int, default=4, help="nominal pressures per decade")
    ap.add_argument("--no-refine", action="store_true", help="skip the grid study at 2n")
    ap.add_argument("--distributions", action="store_true", help="draw the distributions' row too")
    ap.add_argument("--out", type=Path, default=Path("results/challenge"), help="output folder")
    ap.add_argument("--quick", action="store_true", help="128² → 256², 2 pressures per decade")
    ap.add_argument(
        "--no-show", action="store_true", help="do not open a window (figures are saved)"
    )
    args = ap.parse_args(argv)
    n, per_decade = (128, 2) if args.quick else (args.n, args.per_decade)
    study = ChallengeSettings(n=n, seed=args.seed, per_decade=per_decade, refine=not args.no_refine)
    args.out.mkdir(parents=True, exist_ok=True)
    res = challenge_study(study=study, device=args.device)
    res.to_json(args.out / "challenge.json")

    g, k, s = res.grid_study, res.kappa, res.stiffness_slope
    spec = study.spec()
    print(
        f"{res.surface['grid'][0]}² ({res.surface['pixel_m'] * 1e9:.0f} nm pixels), "
        f"λ_s = {spec.short_cutoff * 1e6:.3g} µm, h_rms = {res.h_rms * 1e6:.3f} µm, "
        f"h′_rms = {res.slope_rms:.3f}"
    )
    if g:
        print(
            f"grid study {g['n'][0]}² → {g['n'][1]}²: a_r moves by up to "
            f"{100 * g['max_change_area_fraction']:.1f} %, ū by "
            f"{100 * g['max_change_mean_gap']:.2f} %"
        )
    if k.get("bem") is not None:
        print(
            f"small-load κ: BEM {k['bem']:.2f}, Persson {k['persson']:.2f} "
            f"(√(8/π) = {k['persson_limit']:.2f}), BGT {k['bgt']:.2f} "
            f"(√(2π) = {k['bgt_limit']:.2f}), GW {k['gw']:.2f}"
        )
    if s.get("bem") is not None:
        print(f"d ln K/d ln p: BEM {s['bem']:.2f}, Persson {s['persson']:.2f}")

    import matplotlib.pyplot as plt

    from warptrunc.plot.challenge import plot_challenge

    fig = plot_challenge(
        res,
        args.out / "challenge.png",
        title=f"contact-mechanics challenge at {res.surface['grid'][0]}² "
        f"(λ_s = {spec.short_cutoff * 1e6:.2g} µm, h′_rms = {res.slope_rms:.2f}, "
        f"E* = {res.contact_modulus / 1e6:g} MPa)",
        distributions=args.distributions,
    )
    print(f"wrote {args.out}/challenge.json, challenge.png")
    if not args.no_show:  # pragma: no cover - interactive use only
        plt.show()
    plt.close(fig)
    return 0


if __name__ == "__main__":
    if (status := main()) != 0:
        raise SystemExit(status)
