# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Instrument formats (``.sur``, ``.x3p``, ``.datx``, ...) through SurfaceTopography, an optional
extra imported only when such a file is read."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from .builtin import need_spacing
from .scan import LENGTH_UNITS, MissingExtraError, Scan


def read_surfacetopography(path: Path, dx, dy, height_unit, channel) -> Scan:
    try:
        from SurfaceTopography import open_topography
    except ImportError:
        raise MissingExtraError(
            f"{path}: reading {path.suffix or 'this'} files needs SurfaceTopography; install the "
            'optional extra: pip install "warptrunc[scans]" (or pip install SurfaceTopography)'
        ) from None
    reader = None
    try:
        reader = open_topography(str(path))
        if not reader.channels:
            raise ValueError(f"{path}: holds no data channel (no height map) to read")
        ch = reader.default_channel if channel is None else reader.channels[channel]
        kwargs: dict[str, Any] = {"channel_index": ch.index}
        if len(ch.nb_grid_pts) != 2:
            raise ValueError(
                f"{path}: holds a 1-D line scan of {ch.nb_grid_pts[0]} points; a 2-D height map "
                "(ny, nx) is needed"
            )
        if ch.physical_sizes is None or ch.unit is None:
            # the file lacks sizes or units: the user's dx, dy (m) define them, heights are
            # multiplied by height_unit
            nx_, ny_ = ch.nb_grid_pts
            pdx, pdy = need_spacing(path, dx, dy, "this instrument file (no physical size)")
            f = 1.0 if ch.unit is None else LENGTH_UNITS.get(str(ch.unit).lower())
            if f is None:
                raise ValueError(f"{path}: unknown length unit {ch.unit!r} in the file")
            if ch.physical_sizes is None:  # else fixed by the file, in an unknown unit
                kwargs["physical_sizes"] = (nx_ * pdx / f, ny_ * pdy / f)
            if ch.unit is None:
                kwargs["unit"] = "m"
        topo = reader.topography(**kwargs)
    except IndexError:
        n = len(reader.channels) if reader is not None else 0
        raise ValueError(f"{path}: channel {channel} does not exist; the file has {n}") from None
    except ValueError as exc:
        if str(exc).startswith(str(path)):
            raise
        raise ValueError(f"{path}: cannot read ({type(exc).__name__}: {exc})") from None
    except Exception as exc:  # SurfaceTopography raises many kinds on malformed files
        raise ValueError(f"{path}: cannot read ({type(exc).__name__}: {exc})") from None
    if topo.dim != 2:
        raise ValueError(
            f"{path}: holds a 1-D line scan of {topo.nb_grid_pts[0]} points; a 2-D height map "
            "(ny, nx) is needed"
        )
    declared = ch.unit is not None
    if declared and height_unit != 1.0:
        raise ValueError(
            f"{path}: the file declares its unit ({ch.unit}); height_unit={height_unit!r} would "
            "conflict with it"
        )
    topo = topo.to_unit("m")
    h = topo.heights()
    if np.ma.isMaskedArray(h):
        h = np.ma.filled(h.astype(np.float64), np.nan)
    # SurfaceTopography indexes h[ix, iy]
    z = np.asarray(h, dtype=np.float64).T * (1.0 if declared else height_unit)
    sx, sy = topo.physical_sizes
    ny, nx = z.shape
    meta: dict[str, Any] = {
        "reader": type(reader).__name__,
        "channel": str(ch.name),
        "declared_unit": None if ch.unit is None else str(ch.unit),
    }
    info = {k: v for k, v in (topo.info or {}).items() if k != "raw_metadata"}
    if "instrument" in info:
        meta["instrument"] = json.loads(json.dumps(info["instrument"], default=str))
    return Scan(
        z,
        float(sx) / nx if dx is None else dx,
        float(sy) / ny if dy is None else dy,
        str(path),
        type(reader).__name__,
        meta,
    )
