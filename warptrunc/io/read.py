# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Reading and writing height maps: :func:`read_scan` (the map, its missing points and
metadata), :func:`read_height_map` (a :class:`~warptrunc.Surface`, missing points refused or
filled) and :func:`write_height_map`. Part of :mod:`warptrunc.io`."""

from __future__ import annotations

import errno
from pathlib import Path

import numpy as np

from .._support.messages import MAX_MESSAGE_CHARS, one_line
from .._support.validate import check_range
from ..surface import Surface
from .builtin import read_numpy, read_text, write_warptrunc_file
from .instrument import read_surfacetopography
from .options import ENGINES
from .scan import (
    NUMPY_SUFFIXES,
    TEXT_SUFFIXES,
    MissingExtraError,
    Scan,
)

__all__ = ["read_height_map", "read_scan", "write_height_map"]


def read_scan(
    path: str | Path,
    *,
    dx: float | None = None,
    dy: float | None = None,
    height_unit: float = 1.0,
    engine: str = "auto",
    channel: int | None = None,
) -> Scan:
    """Read a height map with its missing points and metadata, in SI units.

    Parameters
    ----------
    path : str or Path
        File to read (see the module docstring for the formats).
    dx : float, optional
        Pixel spacing along x (m). Required for files that do not declare it (plain arrays and
        matrices); when given, it overrides the file's own value.
    dy : float, optional
        Pixel spacing along y (m). Defaults to ``dx`` when ``dx`` is given, else to the file's
        value.
    height_unit : float
        Factor from the file's height numbers to metres for files that declare no height unit
        (e.g. 1e-6 when a plain matrix holds µm) (m per file unit). Files that declare their
        unit are converted from the declaration; giving another factor than 1.0 for them raises
        ValueError.
    engine : {"auto", "builtin", "surfacetopography"}
        ``"auto"`` reads .npz/.npy/.csv/.txt/.tsv with the built-in readers and everything else
        with SurfaceTopography.
    channel : int, optional
        Data channel for multi-channel instrument files (SurfaceTopography only); default: the
        file's default channel.

    Returns
    -------
    Scan

    Raises
    ------
    FileNotFoundError
        The file does not exist.
    ValueError
        The file is empty, damaged or not a height map, or the pixel spacing is missing; the
        message is one line of at most a few hundred characters that names the file.
    MissingExtraError
        An instrument file needs SurfaceTopography and this environment lacks it
        (``pip install SurfaceTopography``).
    """
    path = Path(path)
    if engine not in ENGINES:
        raise ValueError(f"engine must be one of {ENGINES}, got {engine!r}")
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such file")
    if not path.is_file():
        raise ValueError(f"{path}: not a file")
    if dx is not None:
        dx = check_range("dx", dx, 0.0, unit="m")
    if dy is not None:
        dy = check_range("dy", dy, 0.0, unit="m")
    if dy is None and dx is not None:
        dy = dx
    height_unit = check_range("height_unit", height_unit, 0.0, unit="m per file unit")
    suffix = path.suffix.lower()
    builtin = suffix in NUMPY_SUFFIXES + TEXT_SUFFIXES
    if engine == "builtin" and not builtin:
        raise ValueError(
            f"{path}: the built-in readers handle {NUMPY_SUFFIXES + TEXT_SUFFIXES}, got "
            f"{suffix!r}; use engine='surfacetopography'"
        )
    if path.stat().st_size == 0:
        raise ValueError(f"{path}: empty file (0 bytes): no height map to read")
    try:
        if engine == "surfacetopography" or (engine == "auto" and not builtin):
            return read_surfacetopography(path, dx, dy, height_unit, channel)
        if suffix in NUMPY_SUFFIXES:
            return read_numpy(path, dx, dy, height_unit)
        return read_text(path, dx, dy, height_unit)
    except (MissingExtraError, MemoryError):
        raise
    except OSError as exc:
        if exc.errno in _IO_ERRNOS:  # the file system refused: say so, naming the file
            raise OSError(exc.errno, exc.strerror, str(path)) from None
        raise ValueError(_damaged(path, suffix, exc)) from None  # e.g. a seek past a cut zip
    except ValueError as exc:  # ours: keep the type, keep the message one short line that
        msg = str(exc)  # names the file
        if len(msg) <= MAX_MESSAGE_CHARS and "\n" not in msg and str(path) in msg:
            raise
        if str(path) not in msg:
            raise ValueError(_damaged(path, suffix, exc)) from None
        raise ValueError(one_line(msg)) from None
    except Exception as exc:  # numpy, zipfile, pickle guards, ...: a damaged file
        raise ValueError(_damaged(path, suffix, exc)) from None


_IO_ERRNOS = {
    errno.EACCES,
    errno.EPERM,
    errno.EIO,
    errno.ENOENT,
    errno.EISDIR,
    errno.ENOMEM,
    errno.EMFILE,
    errno.ENFILE,
    errno.ETIMEDOUT,
}
"""Errors of the file system (not of the file's content), kept as OSError by :func:`read_scan`."""


def _damaged(path: Path, suffix: str, exc: BaseException) -> str:
    return (
        f"{path}: cannot read, the file is damaged or not a {suffix or 'known'} height map "
        f"({type(exc).__name__}: {one_line(exc, 160)})"
    )


def read_height_map(
    path: str | Path,
    *,
    dx: float | None = None,
    dy: float | None = None,
    height_unit: float = 1.0,
    missing: str = "error",
    fill: str = "nearest",
    level: bool = False,
    engine: str = "auto",
    channel: int | None = None,
) -> Surface:
    """Read a height map file into a :class:`~warptrunc.Surface` (SI units).

    Parameters
    ----------
    path : str or Path
        .npz/.npy written by :func:`write_height_map` (its ``params`` are kept), a plain
        .npy/.npz array, a .csv/.txt/.tsv
        matrix, or an instrument file (through SurfaceTopography).
    dx, dy : float, optional
        Pixel spacings (m); required when the file does not declare them. See
        :func:`read_scan`.
    height_unit : float
        Factor to metres for files without a declared height unit (m per file unit).
    missing : {"error", "fill"}
        Missing points: raise with their count (default) or fill them.
    fill : {"nearest", "harmonic", "mean"}
        Fill method for ``missing="fill"`` (see :func:`fill_missing`).
    level : bool
        Subtract the least-squares plane.
    engine : {"auto", "builtin", "surfacetopography"}
        Reader choice (see :func:`read_scan`).
    channel : int, optional
        Data channel of multi-channel instrument files.

    Returns
    -------
    Surface
        Heights (m) ``z[iy, ix]``, ``dx``, ``dy`` (m); ``params`` records the source, the
        number of missing points and what was done with them.

    Raises
    ------
    FileNotFoundError
        The file does not exist.
    ValueError
        The file is malformed (message names the file and the problem), the pixel spacing is
        missing, or there are missing points with ``missing="error"``.
    MissingExtraError
        An instrument file needs SurfaceTopography and this environment lacks it
        (``pip install SurfaceTopography``).

    Examples
    --------
    >>> s = read_height_map("scan.csv", dx=1e-6, height_unit=1e-6)  # doctest: +SKIP
    """
    scan = read_scan(path, dx=dx, dy=dy, height_unit=height_unit, engine=engine, channel=channel)
    return scan.to_surface(missing=missing, fill=fill, level=level)


def write_height_map(surface: Surface, path: str | Path) -> Path:
    """Write a surface as .npz (heights + JSON metadata), .npy (heights) + .json sidecar, or a
    .csv/.txt/.tsv matrix; a path without a suffix gets ``.npz``.

    :func:`read_height_map` reads every one of them back.

    The text matrix has a ``#`` header with ``nx``, ``ny``, ``dx``, ``dy`` (m) and
    ``height unit=1 m``, then one row per ``iy``; values are written with 9 significant digits,
    so float32 heights read back exactly.

    Parameters
    ----------
    surface : Surface
        The height map (m) and its metadata.
    path : str or Path
        Output file; its suffix chooses the format (``.npz``, ``.npy``, ``.csv``, ``.txt``,
        ``.tsv``).

    Returns
    -------
    Path
        The path written.

    Raises
    ------
    ValueError
        The suffix is none of the formats above.
    """

    path = Path(path)
    if not path.suffix:
        path = path.with_suffix(".npz")
    suffix = path.suffix.lower()
    if suffix in NUMPY_SUFFIXES:
        return write_warptrunc_file(surface, path)
    if suffix not in TEXT_SUFFIXES:
        raise ValueError(
            f"{path}: can write {NUMPY_SUFFIXES + TEXT_SUFFIXES}, got suffix {suffix!r}"
        )
    delim = {".csv": ",", ".tsv": "\t"}.get(suffix, " ")
    header = "\n".join(
        [
            "warptrunc height map (one row per iy, columns ix, heights in metres)",
            f"nx={surface.nx} ny={surface.ny}",
            f"dx={surface.dx!r} m",
            f"dy={surface.dy!r} m",
            "height unit=1 m",
        ]
    )
    np.savetxt(path, surface.heights, fmt="%.9g", delimiter=delim, header=header, comments="# ")
    return path
