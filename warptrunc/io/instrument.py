# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Instrument formats (``.sur``, ``.x3p``, ``.datx``, ...) through SurfaceTopography, a dependency
imported only when such a file is read."""

from __future__ import annotations

import contextlib
import io
import json
import logging
import re
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from .._support.messages import one_line
from .builtin import need_spacing
from .scan import (
    INSTRUMENT_SUFFIXES,
    LENGTH_UNITS,
    NUMPY_SUFFIXES,
    TEXT_SUFFIXES,
    MissingExtraError,
    Scan,
    unrecognised_format,
)


@contextlib.contextmanager
def _quiet():
    """Silence what SurfaceTopography's readers (and igor2, ...) print or log on a damaged file:
    a log record may hold the file's bytes (megabytes on one line). The error raised says what
    went wrong."""
    sink = io.StringIO()
    previous = logging.root.manager.disable
    logging.disable(logging.CRITICAL)
    try:
        with contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
            yield
    finally:
        logging.disable(previous)


_TRIED = re.compile(r"tried (\w+):\s*(.*?)(?=\s*tried \w+:|\Z)", re.S)


def _cannot_read(path: Path, exc: BaseException) -> str:
    """One short line for a file no reader could read: the reader of its suffix and its
    reason when it tried (SurfaceTopography lists every reader's message, each may hold the
    file's bytes), else the error itself."""
    name = type(exc).__name__
    text = str(exc)
    tried = _TRIED.findall(text)
    if name == "CannotDetectFileFormat" and tried:
        ext = path.suffix.lower().lstrip(".")
        own = [(r, why) for r, why in tried if _reader_reads(r, ext)]
        if own:
            r, why = own[0]
            return (
                f"{path}: cannot read, the file is damaged or cut short ({r}: "
                f"{one_line(why, 160)}; {len(tried)} readers tried)"
            )
        if ext and f".{ext}" in INSTRUMENT_SUFFIXES:
            return (
                f"{path}: cannot read, the file is damaged or not a .{ext} height map (none of "
                f"the {len(tried)} SurfaceTopography readers that tried it recognises it)"
            )
        return unrecognised_format(path, tried=len(tried))
    return f"{path}: cannot read ({name}: {one_line(text, 200)})"


def _reader_reads(reader: str, ext: str) -> bool:
    """Whether SurfaceTopography's reader class ``reader`` is the one for ``ext``."""
    try:
        from SurfaceTopography.IO import readers
    except ImportError:  # pragma: no cover
        return False
    for r in readers:
        if r.__name__ == reader:
            exts = getattr(r, "_file_extensions", None) or []
            return ext in [e.lower() for e in exts]
    return False


def read_surfacetopography(path: Path, dx, dy, height_unit, channel) -> Scan:
    try:
        with warnings.catch_warnings():  # NuMPI: "Could not import mpi4py" (no MPI: fine here)
            warnings.simplefilter("ignore", ImportWarning)
            from SurfaceTopography import open_topography
    except ImportError:
        if path.suffix.lower() not in INSTRUMENT_SUFFIXES + NUMPY_SUFFIXES + TEXT_SUFFIXES:
            raise ValueError(unrecognised_format(path, tried=None)) from None
        raise MissingExtraError(
            f"{path}: reading {path.suffix} files needs SurfaceTopography, a dependency of "
            "warptrunc missing from this environment: pip install SurfaceTopography"
        ) from None
    reader = None
    try:
        with _quiet():
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
        with _quiet():
            topo = reader.topography(**kwargs)
    except IndexError:
        n = len(reader.channels) if reader is not None else 0
        raise ValueError(f"{path}: channel {channel} does not exist; the file has {n}") from None
    except ValueError as exc:
        if str(exc).startswith(str(path)):
            raise
        raise ValueError(_cannot_read(path, exc)) from None
    except Exception as exc:  # SurfaceTopography raises many kinds on malformed files
        raise ValueError(_cannot_read(path, exc)) from None
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
