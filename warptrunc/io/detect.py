# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""What a text or NumPy file holds, decided before it is read as a height map.

Never misread: a file that is not a height matrix is either read onto its grid or refused
with what it is.

Text tables (``.csv``/``.txt``/``.tsv``)
    * The header is the leading lines that are comments (``#``), ``key=value``/``key: value``
      pairs, or text only (column names). A line before the data that mixes numbers and text
      (``1,2,foo``) is an error naming its line and column, as is any non-numeric cell in
      the data.
    * Three columns whose first two hold coordinates on a regular lattice (every (x, y) once,
      uniform spacings) are an **XYZ point list**: read onto the grid, ``z[iy, ix]``, absent
      lattice points missing (NaN). The spacing is the lattice step in the file's unit
      (times ``height_unit``; the same unit as the heights) unless ``dx``/``dy`` are given.
      Three columns of coordinates (values repeated row after row) that do not form a regular
      lattice are refused (scattered points need resampling first).
    * Two columns whose first one is strictly monotonic are a **line scan** (x, z), refused.
    * ``Value units:`` (Gwyddion's text export) sets the height unit; ``Width:``/``Height:``
      with a length unit set the pixel spacing when no ``dx`` is given.

NumPy ``.npz``
    The heights must be under a known key: ``heights`` or ``z`` (or ``arr_0`` when it is the
    only array, as ``numpy.savez(f, z)`` writes it). Anything else is refused with the keys
    found.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from .scan import LENGTH_UNITS

__all__ = [
    "HEIGHT_KEYS",
    "find_data_start",
    "header_units",
    "npz_height_key",
    "shape_words",
    "table_to_map",
]

HEIGHT_KEYS = ("heights", "z")
"""Keys of a plain ``.npz`` that hold the heights."""

_KV = re.compile(r"^\s*#?\s*[^=:]*[A-Za-z_][^=:]*\s*[=:]")


def _tokens(line: str, delim: str | None) -> list[str]:
    return line.split() if delim is None else [t.strip() for t in line.split(delim)]


def _is_number(t: str) -> bool:
    try:
        float(t)
    except ValueError:
        return False
    return True


def _delimiter(s: str) -> str | None:
    return "," if "," in s else ";" if ";" in s else "\t" if "\t" in s.strip() else None


def find_data_start(lines: list[str], path: Path) -> tuple[int, str | None] | None:
    """Index of the first data line and its delimiter, or None when there is none.

    Blank lines, ``#`` comments, ``key=value``/``key: value`` lines and text-only lines
    (column names) before it are the header.

    Parameters
    ----------
    lines : list of str
        The file's lines.
    path : Path
        The file, named in the error message.

    Returns
    -------
    tuple of (int, str or None) or None
        ``(index, delimiter)``: the 0-based index in ``lines`` of the first line of numbers
        and its delimiter (``","``, ``";"``, ``"\\t"``, or None for whitespace); None when no
        line holds numbers only.

    Raises
    ------
    ValueError
        A line before the data mixes numbers and text (not a header of text only); the message
        names the line and the column of the first non-numeric cell.
    """
    for i, ln in enumerate(lines):
        s = ln.strip()
        if not s or s.startswith("#"):
            continue
        d = _delimiter(s)
        toks = _tokens(s, d)
        numeric = [bool(t) and _is_number(t) for t in toks]
        if all(numeric or not t for numeric, t in zip(numeric, toks, strict=True)):
            if any(numeric):
                return i, d
            continue
        if _KV.match(s) or not any(numeric):
            continue  # key=value / key: value, or text only (column names)
        col = next(j for j, (ok, t) in enumerate(zip(numeric, toks, strict=True)) if t and not ok)
        raise ValueError(
            f"{path}: line {i + 1}, column {col + 1}: {toks[col]!r} is not a number (a line "
            "before the data must be a header of text only, '#' comments or key=value pairs)"
        )
    return None


def header_units(
    header: dict[str, str], path: Path
) -> tuple[float | None, float | None, float | None]:
    """(height unit, physical width, physical height) (m) of a Gwyddion-style header, or None.

    Parameters
    ----------
    header : dict of str to str
        Header entries, keys lower-cased (``"value units"``, ``"width"``/``"breite"``,
        ``"height"``/``"höhe"``), values such as ``"nm"`` or ``"10.0 µm"``.
    path : Path
        The file, named in the error message.

    Returns
    -------
    unit : float or None
        Metres per height unit of ``Value units`` (m), or None without that key.
    width, height : float or None
        Physical width and height of the map (m), or None when absent or not a length.

    Raises
    ------
    ValueError
        ``Value units`` is not a known length unit.
    """

    def length(v: str) -> float | None:
        m = re.fullmatch(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)?\s*(\S+)\s*", v)
        if not m or m.group(2).lower() not in LENGTH_UNITS:
            return None
        return float(m.group(1) or 1.0) * LENGTH_UNITS[m.group(2).lower()]

    unit = None
    if "value units" in header:
        unit = length(header["value units"])
        if unit is None:
            raise ValueError(
                f"{path}: header 'Value units: {header['value units']}' is not a length unit; "
                f"known: {sorted(LENGTH_UNITS)}"
            )
    width = next((length(header[k]) for k in ("width", "breite") if k in header), None)
    height = next((length(header[k]) for k in ("height", "höhe") if k in header), None)
    return unit, width, height


def _lattice(v: np.ndarray, rtol: float = 1e-6) -> tuple[np.ndarray, float] | None:
    """(index of each value on a uniform lattice, step), or None when not uniform."""
    u = np.unique(v)
    if u.size < 2:
        return None
    step = float(np.min(np.diff(u)))
    idx = (v - u[0]) / step
    if not np.all(np.isfinite(idx)) or float(idx.max()) > 4.0 * u.size:
        return None  # most lattice sites empty (or beyond int64): not a grid of these points
    k = np.rint(idx)
    if np.max(np.abs(idx - k)) > rtol * max(1.0, float(k.max())):
        return None
    return k.astype(np.int64), step


def _looks_like_points(x: np.ndarray, y: np.ndarray) -> bool:
    """Whether columns x, y (finite) repeat their values as the coordinates of a point list."""
    n = x.size
    if n < 4:
        return False
    nux, nuy = np.unique(x).size, np.unique(y).size
    return not (nux * nuy > 4 * n or nux > n // 2 or nuy > n // 2)


def table_to_map(
    table: np.ndarray, path: Path, height_unit: float, dx: float | None, dy: float | None
) -> tuple[np.ndarray, float, float, dict] | None:
    """An XYZ point list read onto its grid as (z (m), dx, dy, metadata); None for a matrix.

    Parameters
    ----------
    table : (n, ncol) ndarray
        The numeric rows of the file, in the file's units.
    path : Path
        The file, named in error messages.
    height_unit : float
        Metres per unit of the file (m); scales the heights and the lattice steps.
    dx, dy : float or None
        Pixel spacings (m) that override the lattice steps; None to use them.

    Returns
    -------
    tuple of (ndarray, float, float, dict) or None
        ``(z, dx, dy, metadata)``: ``(ny, nx)`` float64 heights ``z[iy, ix]`` (m), NaN at
        lattice points absent from the list; the spacings (m); ``{"xyz": {"points",
        "grid_points", "x_step", "y_step"}}`` (steps in the file's unit). None when the table
        is not a three-column point list (a height matrix).

    Raises
    ------
    ValueError
        The table is a line scan (two columns, the first strictly monotonic, more than two
        rows), or a point list whose x or y values are not on a uniform lattice or not finite.
    """
    n, ncol = table.shape
    if ncol == 2 and n > 2:
        x = table[:, 0]
        xf = x[np.isfinite(x)]  # np.diff of ±inf would warn (inf − inf)
        dxs = np.diff(xf)
        if xf.size > 2 and (np.all(dxs > 0) or np.all(dxs < 0)):
            raise ValueError(
                f"{path}: holds a line scan (x, z) of {n} points (two columns, the first "
                "strictly monotonic); a 2-D height map is needed"
            )
    if ncol != 3 or n < 4:
        return None
    x, y, h = table[:, 0], table[:, 1], table[:, 2]
    finite = np.isfinite(x) & np.isfinite(y)
    if not np.all(finite):
        if _looks_like_points(x[finite], y[finite]):
            k = int(np.argmin(finite))
            raise ValueError(
                f"{path}: holds an XYZ point list with a coordinate that is not finite (data "
                f"row {k + 1}: x = {float(x[k])!r}, y = {float(y[k])!r}); every point needs finite x and y"
            )
        return None  # a 3-column height matrix with missing points
    if not _looks_like_points(x, y):
        return None  # coordinates are not repeated: a 3-column height matrix
    lx, ly = _lattice(x), _lattice(y)
    if lx is None or ly is None:
        raise ValueError(
            f"{path}: holds an XYZ point list ({n} points) that is not on a regular grid "
            "(non-uniform x or y spacing); resample it onto a grid first"
        )
    (ix, sx), (iy, sy) = lx, ly
    nx, ny = int(ix.max()) + 1, int(iy.max()) + 1
    key = iy * nx + ix
    if np.unique(key).size != n or nx < 2 or ny < 2:
        return None  # repeated (x, y): not a point list
    z = np.full((ny, nx), np.nan)
    z[iy, ix] = h
    meta = {"xyz": {"points": int(n), "grid_points": nx * ny, "x_step": sx, "y_step": sy}}
    return (
        z * height_unit,
        sx * height_unit if dx is None else dx,
        sy * height_unit if dy is None else dy,
        meta,
    )


def shape_words(shape: tuple[int, ...]) -> str:
    """What an array of ``shape`` that is no 2-D map holds, in words.

    Parameters
    ----------
    shape : tuple of int
        Shape of the array read from the file.

    Returns
    -------
    str
        A phrase for an error message, e.g. ``"holds a 1-D profile of 512 points (shape
        (512,))"``.
    """
    size = int(np.prod(shape))
    if size == 0:
        return f"holds no points (shape {shape})"
    if size == 1:
        return f"holds a single point (shape {shape})"
    if len(shape) == 1:
        return f"holds a 1-D profile of {size} points (shape {shape})"
    if len(shape) == 2 and shape[0] == 1:
        return f"holds a 1-D profile of {size} points along x (one row, shape {shape})"
    if len(shape) == 2 and shape[1] == 1:
        return f"holds a 1-D profile of {size} points along y (one column, shape {shape})"
    return f"holds an array of shape {shape}"


def npz_height_key(names: list[str], path: Path) -> str:
    """The key of the heights in a plain ``.npz`` (see the module docstring).

    Parameters
    ----------
    names : list of str
        The array names in the archive.
    path : Path
        The file, named in the error message.

    Returns
    -------
    str
        The first of :data:`HEIGHT_KEYS` in ``names``, else ``"arr_0"`` when it is the only
        name.

    Raises
    ------
    ValueError
        No known key; the message lists the names found.
    """

    key = next((k for k in HEIGHT_KEYS if k in names), None)
    if key is None and names == ["arr_0"]:
        key = "arr_0"
    if key is None:
        raise ValueError(
            f"{path}: no height array under a known key ({', '.join(HEIGHT_KEYS)}, or a single "
            f"unnamed arr_0); found {names}. Save the heights as numpy.savez(f, heights=z)"
        )
    return key
