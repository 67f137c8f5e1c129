# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Argument groups shared by the sub-commands: surface source, device, output folder."""

from __future__ import annotations

import argparse
import sys
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
    add_reader_options(g)
    g.add_argument(
        "--D", type=float, default=2.5, help="fractal dimension D, 2 < D < 3 (dimensionless)"
    )
    add_wm_shape(g)
    g.add_argument("--Rt", type=float, default=10e-6, help="target peak-to-valley height R_t (m)")
    g.add_argument(
        "--G",
        type=float,
        default=None,
        help="topothesy G (m); when given, heights are not rescaled to --Rt",
    )
    g.add_argument("--seed", type=int, default=0, help="seed of the random phases α_mn")


def add_wm_shape(g: argparse._ActionsContainer) -> None:
    """WM options other than D, R_t/G and the seed: W_r, L, n, M, γ, W_c, cut-off (SI)."""
    g.add_argument("--Wr", type=float, default=100e-6, help="roll-off wavelength W_r (m)")
    g.add_argument("--L", type=float, nargs="+", default=[1e-3], help="side length L, or Lx Ly (m)")
    g.add_argument("--n", type=int, nargs="+", default=[1024], help="pixels per side, or nx ny")
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


def add_reader_options(g: argparse._ActionsContainer) -> None:
    """Options for reading a height-map file (spacing, units, missing points, levelling)."""
    g.add_argument(
        "--dx", type=float, default=None, help="pixel spacing along x (m) if not in the file"
    )
    g.add_argument("--dy", type=float, default=None, help="pixel spacing along y (m); default dx")
    g.add_argument(
        "--height-unit", type=float, default=1.0,
        help="metres per height unit, for files that declare none (e.g. 1e-6 for µm)",
    )  # fmt: skip
    g.add_argument(
        "--missing", choices=["error", "fill"], default="error",
        help="missing (NaN) points: stop with their count, or fill them",
    )  # fmt: skip
    g.add_argument(
        "--fill", choices=["nearest", "harmonic", "mean"], default="nearest",
        help="fill method with --missing fill",
    )  # fmt: skip
    g.add_argument("--level", action="store_true", help="subtract the least-squares plane")
    g.add_argument(
        "--engine", choices=["auto", "builtin", "surfacetopography"], default="auto",
        help="reader: built-in for .npz/.npy/.csv/.txt/.tsv, SurfaceTopography otherwise",
    )  # fmt: skip
    g.add_argument("--channel", type=int, default=None, help="data channel of instrument files")


def read_input(path: Path, args: argparse.Namespace) -> Surface:
    """Read ``path`` with the options of :func:`add_reader_options`; reports filled points."""
    from ..io import read_height_map

    s = read_height_map(
        path, dx=args.dx, dy=args.dy, height_unit=args.height_unit, missing=args.missing,
        fill=args.fill, level=args.level, engine=args.engine, channel=args.channel,
    )  # fmt: skip
    n_missing = s.params.get("n_missing", 0)
    if n_missing:
        print(f"{path}: {n_missing} missing points filled ({args.fill})", file=sys.stderr)
    return s


def _pair(v: list) -> float | tuple:
    if len(v) == 1:
        return v[0]
    if len(v) == 2:
        return (v[0], v[1])
    raise ValueError(f"expected one or two values, got {v!r}")


def wm_kwargs(args: argparse.Namespace) -> dict:
    """The WM generation keywords (``wm_spec``/``wm_surface``) of the parsed arguments."""
    return dict(
        D=args.D,
        Wr=args.Wr,
        L=_pair(args.L),
        n=_pair(args.n),
        Rt=None if args.G is not None else args.Rt,
        G=args.G,
        M=args.M,
        gamma=args.gamma,
        Wc=args.Wc,
        cutoff=args.cutoff,
        seed=args.seed,
    )


def surface_from_args(args: argparse.Namespace) -> Surface:
    """Read ``--input`` or generate a WM surface from the parameters."""
    if args.input is not None:
        return read_input(args.input, args)
    from ..wm import wm_surface

    return wm_surface(**wm_kwargs(args), device=args.device)
