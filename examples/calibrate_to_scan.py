# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Calibrate WM inputs to a scan (the paper's Fig. 4) and generate a high-resolution surface
=========================================================================================

What it shows
    1. Read a scan (any format that ``warptrunc.io.read_height_map`` reads; without ``--scan`` a
       stand-in "scan" is generated: a WM surface at 1 µm pixels with D_in = 2.45,
       W_r = 60 µm, R_t = 37 µm) and report its descriptors and the four D values.
    2. Targets: D by the chosen method, R_rms, R_t, W_r, the scan's size and resolution.
    3. The D loop (D_in such that the mean D_out over the seeds matches within rtol), then
       R_t' such that R_rms matches.
    4. Generate the calibrated surface at ``--n-out`` pixels per side and compare its descriptors.

Run::

    python examples/calibrate_to_scan.py --method vs --n-out 4096 --out out/calibrate
    python examples/calibrate_to_scan.py --scan ../shared/data/scans/sur-2.sur --Wr 200e-6
    python examples/calibrate_to_scan.py --quick --out out/calibrate   # 128² stand-in, seconds
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from warptrunc import plot
from warptrunc.calibrate import (
    CalibrationSettings,
    calibrate,
    calibrated_surface,
    target_from_surface,
)
from warptrunc.descriptors import describe, radial_psd
from warptrunc.fractal import METHODS, fractal_dimensions
from warptrunc.io import read_height_map, write_height_map
from warptrunc.wm import wm_surface


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--scan", type=Path, default=None, help="scan file (default: a stand-in)")
    ap.add_argument("--Wr", type=float, default=None, help="W_r (m) if the scan cannot give it")
    ap.add_argument("--method", choices=METHODS, default="vs", help="fractal method matched")
    ap.add_argument("--rtol", type=float, default=0.01, help="relative tolerance on D")
    ap.add_argument("--n", type=int, default=1024, help="pixels per side of the stand-in scan")
    ap.add_argument("--n-out", type=int, default=2048, help="pixels per side of the output")
    ap.add_argument("--seed", type=int, default=0, help="seed of the output surface")
    ap.add_argument("--device", default=None, help="Warp device (default: CUDA if present)")
    ap.add_argument("--out", type=Path, default=Path("out/calibrate"), help="output folder")
    ap.add_argument("--no-show", action="store_true", help="do not open figure windows")
    ap.add_argument("--quick", action="store_true", help="128² stand-in, 256² output, 2 seeds")
    args = ap.parse_args(argv)
    n, n_out, seeds = (128, 256, (0, 1)) if args.quick else (args.n, args.n_out, (0, 1, 2))
    args.out.mkdir(parents=True, exist_ok=True)

    if args.scan is None:
        wr = min(60e-6, n * 1e-6 / 8)  # at least 8 roll-off wavelengths in the scan
        scan = wm_surface(2.45, wr, L=n * 1e-6, n=n, Rt=37e-6, seed=99, device=args.device)
        name = f"stand-in WM scan ({n}², D_in = 2.45, W_r = {wr * 1e6:.3g} µm)"
    else:
        scan = read_height_map(args.scan, missing="fill", level=True)
        name = args.scan.name
    d = describe(scan)
    fits = fractal_dimensions(scan, device=args.device)
    dims = ", ".join(f"D_{m} = {f.D:.3f}" for m, f in fits.items())
    print(
        f"1. {name}: R_t = {d.Rt * 1e6:.4g} µm, R_rms = {d.Rrms * 1e6:.4g} µm, "
        f"W_r = {d.Wr * 1e6:.4g} µm; {dims}"
    )

    settings = CalibrationSettings(method=args.method, seeds=seeds, rtol=args.rtol)
    target = target_from_surface(scan, settings, Wr=args.Wr, device=args.device)
    print(f"2. target D_{args.method} = {target.D:.4f}, R_rms = {target.Rrms * 1e6:.4g} µm")
    cal = calibrate(target, settings=settings, progress=not args.quick, device=args.device)
    print(
        f"3. D_in' = {cal.D_in:.4f}, R_t' = {cal.Rt * 1e6:.4g} µm → D_{args.method} = "
        f"{cal.D_out:.4f} ± {cal.D_out_std:.4f}, R_rms = {cal.Rrms * 1e6:.4g} µm "
        f"after {cal.iterations} evaluations"
    )

    s = calibrated_surface(cal, n=n_out, seed=args.seed, device=args.device)
    ds = describe(s)
    print(
        f"4. {n_out}² surface: R_t = {ds.Rt * 1e6:.4g} µm, R_rms = {ds.Rrms * 1e6:.4g} µm "
        f"(at fixed R_t' it moves with the resolution), W_r = {ds.Wr * 1e6:.4g} µm"
    )
    path = write_height_map(s, args.out / "calibrated_surface.npz")
    info = {k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in cal.to_dict().items()}
    info["output"] = {"path": str(path), **ds.to_dict()}
    (args.out / "calibration.json").write_text(json.dumps(info, indent=2) + "\n")
    plot.calibration_history(cal, path=args.out / "calibration_history.png")
    plot.psd(
        [radial_psd(scan), radial_psd(s)],
        labels=[name, f"calibrated, {n_out}²"],
        Wr=target.Wr,
        path=args.out / "psd.png",
    )
    print(f"wrote {path}, {args.out}/calibration.json, calibration_history.png, psd.png")
    if not args.no_show:
        plot.show_pngs([args.out / "calibration_history.png", args.out / "psd.png"])
    return 0


if __name__ == "__main__":
    if (status := main()) != 0:
        raise SystemExit(status)
