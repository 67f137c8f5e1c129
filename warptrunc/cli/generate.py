# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Generate a Weierstrass–Mandelbrot surface (paper Eq. 4) and save it (.npz, or .npy + .json)."""

from __future__ import annotations

import argparse

from .._support.outputs import staged_output
from ..io import write_height_map
from ._common import add_device, add_output_file, add_surface_source, surface_from_args

NAME = "generate"
HELP = "generate a WM surface and save it"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc generate``."""
    add_surface_source(p)
    add_device(p)
    add_output_file(
        p, "surface.npz", "output file: .npz (heights + metadata) or .npy (heights) + .json sidecar"
    )


def run(args: argparse.Namespace) -> int:
    """Generate and save."""
    if args.input is not None:
        raise ValueError("generate makes a new surface; --input is not used here")
    s = surface_from_args(args)
    with staged_output(args.output.parent) as out:  # the .npy and its .json sidecar together
        write_height_map(s, out / args.output.name)
    path = args.output
    meta = s.to_dict()
    print(
        f"wrote {path}: {s.nx}×{s.ny} pixels, {s.lx * 1e3:g}×{s.ly * 1e3:g} mm, "
        f"R_t = {s.Rt * 1e6:.4g} µm, n_max = {meta['n_max']}, {meta['n_terms']} terms"
    )
    return 0
