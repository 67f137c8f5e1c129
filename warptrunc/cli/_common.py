# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Argument groups shared by the sub-commands: surface source, device, output folder."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..surface import Surface


def add_device(p: argparse.ArgumentParser) -> None:
    """``--device``."""
    p.add_argument(
        "--device",
        default=None,
        help="Warp device: cpu, cuda:0, ... (default: $WARPTRUNC_DEVICE, else CUDA if present, "
        "else cpu)",
    )


def add_out(p: argparse.ArgumentParser, default: str = "out") -> None:
    """``--out DIR``."""
    p.add_argument("--out", type=Path, default=Path(default), help="output folder")


def add_surface_source(p: argparse.ArgumentParser) -> None:
    """A height-map file, or WM generation parameters (all SI)."""
    g = p.add_argument_group("surface source (a height-map file, or WM generation parameters)")
    g.add_argument(
        "--input",
        "-i",
        type=Path,
        default=None,
        help="height map file (.npz/.npy written by warptrunc, .npy/.csv/.txt matrix with "
        "--dx, or an instrument file); overrides the generation parameters",
    )
    g.add_argument(
        "--dx", type=float, default=None, help="pixel spacing along x for plain matrices (m)"
    )
    g.add_argument("--dy", type=float, default=None, help="pixel spacing along y (m); default dx")
    g.add_argument(
        "--height-unit",
        type=float,
        default=1.0,
        help="multiply plain-matrix heights by this to get metres (e.g. 1e-6 for µm)",
    )
    g.add_argument(
        "--D", type=float, default=2.5, help="fractal dimension D, 2 < D < 3 (dimensionless)"
    )
    g.add_argument("--Wr", type=float, default=100e-6, help="roll-off wavelength W_r (m)")
    g.add_argument("--L", type=float, nargs="+", default=[1e-3], help="side length L, or Lx Ly (m)")
    g.add_argument("--n", type=int, nargs="+", default=[1024], help="pixels per side, or nx ny")
    g.add_argument("--Rt", type=float, default=10e-6, help="target peak-to-valley height R_t (m)")
    g.add_argument(
        "--G",
        type=float,
        default=None,
        help="topothesy G (m); when given, heights are not rescaled to --Rt",
    )
    g.add_argument("--M", type=int, default=10, help="number of superposed ridges M")
    g.add_argument(
        "--gamma", type=float, default=1.5, help="frequency density γ > 1 (dimensionless)"
    )
    g.add_argument(
        "--Wc",
        type=float,
        default=None,
        help="cut-off wavelength W_c (m); default from --cutoff",
    )
    g.add_argument(
        "--cutoff",
        choices=["nyquist", "pixel"],
        default="nyquist",
        help="default W_c: 'nyquist' = 2 pixel spacings (no aliasing), 'pixel' = 1 spacing "
        "(the paper's literal reading)",
    )
    g.add_argument("--seed", type=int, default=0, help="seed of the random phases α_mn")


def _pair(v: list) -> float | tuple:
    if len(v) == 1:
        return v[0]
    if len(v) == 2:
        return (v[0], v[1])
    raise ValueError(f"expected one or two values, got {v!r}")


def surface_from_args(args: argparse.Namespace) -> Surface:
    """Read ``--input`` or generate a WM surface from the parameters."""
    if args.input is not None:
        from ..io import read_height_map

        return read_height_map(args.input, dx=args.dx, dy=args.dy, height_unit=args.height_unit)
    from ..wm import wm_surface

    return wm_surface(
        args.D,
        args.Wr,
        L=_pair(args.L),
        n=_pair(args.n),
        Rt=None if args.G is not None else args.Rt,
        G=args.G,
        M=args.M,
        gamma=args.gamma,
        Wc=args.Wc,
        cutoff=args.cutoff,
        seed=args.seed,
        device=args.device,
    )
