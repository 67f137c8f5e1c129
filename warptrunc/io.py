# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Measured height maps as input: NumPy and text matrices built in, instrument files optional.

Built-in formats (no extra dependency):

``.npz`` / ``.npy`` written by :meth:`warptrunc.Surface.save`
    Pixel sizes and parameters come from the file (``.npy`` from its ``.json`` sidecar).
plain ``.npy`` / ``.npz`` arrays
    A 2-D array ``z[iy, ix]``; an ``.npz`` must hold one array or one named ``heights`` or ``z``.
    The pixel spacing must be given (``dx=``, ``dy=``) and heights are multiplied by
    ``height_unit`` to get metres.
``.csv`` / ``.txt`` / ``.tsv`` matrices
    One row of the map per line (row ``iy``, columns ``ix``), separated by commas, semicolons,
    tabs or blanks. Leading header lines are read as ``key=value`` (or ``key: value``, an
    optional ``#`` in front); the keys ``dx``, ``dy``, ``pixel size``, ``height unit``,
    ``height conversion factor (-> m)``, ``nx``/``w`` and ``ny``/``h`` are understood (lengths
    may carry a unit: m, mm, µm/um, nm, pm). :func:`write_height_map` writes this format.
    ``nan`` and empty fields are missing points.

Instrument formats (``.sur``, ``.x3p``, ``.datx``, ``.plu``, ``.opd``, ``.vk4``, ``.gwy``,
``.di``, ``.top``, ``.asc``, ... over forty) are read through SurfaceTopography (MIT licence),
an optional extra: ``pip install "warptrunc[scans]"``. It is imported only when such a file is
read. Units and pixel sizes come from the file's metadata; SurfaceTopography indexes heights
as ``h[ix, iy]``, which is transposed here to ``z[iy, ix]``.

Missing points (NaN) are never ignored: :func:`read_scan` returns them with a validity mask,
and :func:`read_height_map` either raises (``missing="error"``, the default, with the count
and the options) or fills them (``missing="fill"``) and records the count in
``Surface.params["n_missing"]``.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ._validate import check_range
from .surface import Surface, load_surface

__all__ = [
    "FILL_METHODS",
    "MissingExtraError",
    "Scan",
    "fill_missing",
    "level_plane",
    "read_height_map",
    "read_scan",
    "write_height_map",
]

NUMPY_SUFFIXES = (".npz", ".npy")
TEXT_SUFFIXES = (".csv", ".txt", ".tsv")
FILL_METHODS = ("nearest", "harmonic", "mean")
ENGINES = ("auto", "builtin", "surfacetopography")

_LENGTH_UNITS = {
    "m": 1.0,
    "mm": 1e-3,
    "um": 1e-6,
    "µm": 1e-6,
    "μm": 1e-6,
    "nm": 1e-9,
    "pm": 1e-12,
    "a": 1e-10,
    "å": 1e-10,
}


class MissingExtraError(ImportError, ValueError):
    """An optional dependency is missing; the message names the extra to install."""


@dataclass(frozen=True, eq=False)
class Scan:
    """A measured height map as read, before any filling: may hold missing points.

    Heights are ``z[iy, ix]`` at ``x = ix·dx``, ``y = iy·dy``.
    """

    heights: np.ndarray
    """(ny, nx) float64 heights z (m); NaN where a point is missing."""
    dx: float
    """Pixel spacing along x (m)."""
    dy: float
    """Pixel spacing along y (m)."""
    source: str
    """Path of the file read."""
    format: str
    """Reader used: ``"warptrunc"``, ``"npy"``, ``"npz"``, ``"text"`` or the SurfaceTopography
    reader's class name."""
    metadata: dict[str, Any] = field(default_factory=dict)
    """Metadata found in the file (JSON-serialisable): header keys, declared units, ..."""

    def __post_init__(self) -> None:
        z = np.asarray(self.heights, dtype=np.float64)
        if z.ndim != 2:
            raise ValueError(f"{self.source}: heights must be 2-D (ny, nx), got shape {z.shape}")
        z = np.ascontiguousarray(z)
        z.setflags(write=False)
        object.__setattr__(self, "heights", z)
        object.__setattr__(self, "dx", check_range("dx", self.dx, 0.0, unit="m"))
        object.__setattr__(self, "dy", check_range("dy", self.dy, 0.0, unit="m"))

    @property
    def valid(self) -> np.ndarray:
        """(ny, nx) bool mask, True where a height was measured (finite)."""
        return np.isfinite(self.heights)

    @property
    def n_missing(self) -> int:
        """Number of missing (NaN or infinite) points."""
        return int(self.heights.size - np.count_nonzero(self.valid))

    @property
    def shape(self) -> tuple[int, int]:
        """(ny, nx)."""
        return (int(self.heights.shape[0]), int(self.heights.shape[1]))

    def to_dict(self) -> dict[str, Any]:
        """Scalar metadata, JSON-serialisable."""
        ny, nx = self.shape
        return {
            "source": self.source,
            "format": self.format,
            "nx": nx,
            "ny": ny,
            "dx_m": self.dx,
            "dy_m": self.dy,
            "lx_m": nx * self.dx,
            "ly_m": ny * self.dy,
            "n_missing": self.n_missing,
        }

    def to_surface(
        self, *, missing: str = "error", fill: str = "nearest", level: bool = False
    ) -> Surface:
        """Turn the scan into a :class:`~warptrunc.Surface`.

        Parameters
        ----------
        missing : {"error", "fill"}
            What to do with missing points: ``"error"`` raises ValueError naming the count and
            the options; ``"fill"`` fills them with :func:`fill_missing`.
        fill : {"nearest", "harmonic", "mean"}
            Fill method for ``missing="fill"``.
        level : bool
            Subtract the least-squares plane (fitted on the measured points only, before
            filling).

        Returns
        -------
        Surface
            ``params`` holds ``source``, ``format``, ``n_missing``, ``missing`` (what was done),
            ``levelled`` and the file metadata.
        """
        if missing not in ("error", "fill"):
            raise ValueError(f"missing must be 'error' or 'fill', got {missing!r}")
        if fill not in FILL_METHODS:
            raise ValueError(f"fill must be one of {FILL_METHODS}, got {fill!r}")
        z = np.array(self.heights)
        valid = self.valid
        n_missing = self.n_missing
        if n_missing == z.size:
            raise ValueError(f"{self.source}: every point is missing (NaN)")
        if n_missing and missing == "error":
            iy, ix = np.argwhere(~valid)[0]
            raise ValueError(
                f"{self.source}: {n_missing} of {z.size} points are missing (NaN; first at "
                f"iy={iy}, ix={ix}); pass missing='fill' (fill={'|'.join(FILL_METHODS)}; CLI: "
                "--missing fill) to fill them, or use warptrunc.io.read_scan to keep the mask"
            )
        if level:
            z = level_plane(z, self.dx, self.dy, mask=valid)
        if n_missing:
            z = fill_missing(z, valid, method=fill)
        params = dict(self.metadata.get("params", {})) if self.format == "warptrunc" else {}
        params |= {
            "source": self.source,
            "format": self.format,
            "n_missing": n_missing,
            "missing": f"fill:{fill}" if n_missing else "none",
            "levelled": bool(level),
        }
        if self.metadata and self.format != "warptrunc":
            params["file_metadata"] = self.metadata
        return Surface(z, self.dx, self.dy, params)


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
    if engine == "surfacetopography" or (engine == "auto" and not builtin):
        return _read_surfacetopography(path, dx, dy, height_unit, channel)
    if suffix in NUMPY_SUFFIXES:
        return _read_numpy(path, dx, dy, height_unit)
    return _read_text(path, dx, dy, height_unit)


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
        .npz/.npy written by :meth:`Surface.save`, a plain .npy/.npz array, a .csv/.txt/.tsv
        matrix, or an instrument file (needs the ``scans`` extra).
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
        An instrument file needs SurfaceTopography (``pip install "warptrunc[scans]"``).

    Examples
    --------
    >>> s = read_height_map("scan.csv", dx=1e-6, height_unit=1e-6)  # doctest: +SKIP
    """
    scan = read_scan(path, dx=dx, dy=dy, height_unit=height_unit, engine=engine, channel=channel)
    return scan.to_surface(missing=missing, fill=fill, level=level)


def write_height_map(surface: Surface, path: str | Path) -> Path:
    """Write a surface as .npz/.npy (via :meth:`Surface.save`) or a .csv/.txt/.tsv matrix.

    The text matrix has a ``#`` header with ``nx``, ``ny``, ``dx``, ``dy`` (m) and
    ``height unit=1 m``, then one row per ``iy``; values are written with 9 significant digits,
    so float32 heights read back exactly.

    Returns
    -------
    Path
        The path written.
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix in NUMPY_SUFFIXES:
        return surface.save(path)
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


# --- missing points and levelling --------------------------------------------------------------


def fill_missing(z: np.ndarray, valid: np.ndarray, *, method: str = "nearest") -> np.ndarray:
    """Fill the points where ``valid`` is False.

    Parameters
    ----------
    z : (ny, nx) ndarray
        Heights (m); values where ``valid`` is False are ignored.
    valid : (ny, nx) bool ndarray
        True where a height was measured.
    method : {"nearest", "harmonic", "mean"}
        ``"nearest"``: the height of the nearest measured pixel (Euclidean distance in pixel
        units, ties broken by ``scipy.ndimage.distance_transform_edt``). ``"harmonic"``: the
        solution of Laplace's equation ∇²z = 0 on the missing points with the measured points as
        Dirichlet data (5-point stencil, reflecting edges), the smoothest fill; a component of
        missing points with no measured neighbour anywhere falls back to the mean.
        ``"mean"``: the mean of the measured heights.

    Returns
    -------
    (ny, nx) float64 ndarray
        Filled heights (m); measured points are unchanged.
    """
    z = np.array(z, dtype=np.float64)
    valid = np.asarray(valid, dtype=bool)
    if valid.shape != z.shape:
        raise ValueError(f"valid must have the shape of z {z.shape}, got {valid.shape}")
    if method not in FILL_METHODS:
        raise ValueError(f"method must be one of {FILL_METHODS}, got {method!r}")
    bad = ~valid
    if not bad.any():
        return z
    if not valid.any():
        raise ValueError("cannot fill: every point is missing")
    if method == "mean":
        z[bad] = z[valid].mean()
        return z
    from scipy import ndimage

    if method == "nearest":
        idx = ndimage.distance_transform_edt(bad, return_distances=False, return_indices=True)
        return z[tuple(idx)]
    # harmonic: sparse Laplace solve on the missing pixels only
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve

    ny, nx = z.shape
    unknown = np.flatnonzero(bad.ravel())
    index = -np.ones(z.size, dtype=np.int64)
    index[unknown] = np.arange(unknown.size)
    iy, ix = np.divmod(unknown, nx)
    rows, cols, vals = [], [], []
    rhs = np.zeros(unknown.size)
    diag = np.zeros(unknown.size)
    zf = np.where(valid, z, 0.0).ravel()
    for dy_, dx_ in ((-1, 0), (1, 0), (0, -1), (0, 1)):
        jy, jx = iy + dy_, ix + dx_
        inside = (jy >= 0) & (jy < ny) & (jx >= 0) & (jx < nx)
        k = np.flatnonzero(inside)
        nb = jy[k] * nx + jx[k]
        diag[k] += 1.0
        nb_unknown = index[nb] >= 0
        rows.append(k[nb_unknown])
        cols.append(index[nb][nb_unknown])
        vals.append(-np.ones(int(nb_unknown.sum())))
        np.add.at(rhs, k[~nb_unknown], zf[nb[~nb_unknown]])
    # a tiny diagonal shift keeps components without measured neighbours solvable; they are
    # then set to the mean below
    a = coo_matrix(
        (
            np.concatenate([diag + 1e-12, *vals]),
            (
                np.concatenate([np.arange(unknown.size), *rows]),
                np.concatenate([np.arange(unknown.size), *cols]),
            ),
        ),
        shape=(unknown.size, unknown.size),
    ).tocsr()
    sol = spsolve(a, rhs)
    labels, _ = ndimage.label(bad)
    touching = np.unique(labels[ndimage.binary_dilation(valid) & bad])
    isolated = ~np.isin(labels.ravel()[unknown], touching)
    sol[isolated] = z[valid].mean()
    out = z.ravel()
    out[unknown] = sol
    return out.reshape(ny, nx)


def level_plane(
    z: np.ndarray, dx: float = 1.0, dy: float = 1.0, *, mask: np.ndarray | None = None
) -> np.ndarray:
    """Subtract the least-squares plane a + b·x + c·y fitted on the points of ``mask``.

    Parameters
    ----------
    z : (ny, nx) ndarray
        Heights (m); may hold NaN outside ``mask``.
    dx, dy : float
        Pixel spacings (m); they do not change the result, only the fitted slopes' units.
    mask : (ny, nx) bool ndarray, optional
        Points used in the fit; default: the finite points.

    Returns
    -------
    (ny, nx) float64 ndarray
        ``z`` minus the plane (NaN stays NaN); the mean over ``mask`` is zero.
    """
    z = np.asarray(z, dtype=np.float64)
    if mask is None:
        mask = np.isfinite(z)
    ny, nx = z.shape
    yy, xx = np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")
    a = np.stack([np.ones(int(mask.sum())), xx[mask], yy[mask]], axis=1)
    coef, *_ = np.linalg.lstsq(a, z[mask], rcond=None)
    return z - (coef[0] + coef[1] * xx + coef[2] * yy)


# --- built-in readers --------------------------------------------------------------------------


def _need_spacing(path: Path, dx: float | None, dy: float | None, what: str) -> tuple[float, float]:
    if dx is None or dy is None:
        raise ValueError(
            f"{path}: {what} carries no pixel spacing; give dx= (and dy= if different) in metres "
            "(CLI: --dx/--dy)"
        )
    return dx, dy


def _as_map(path: Path, a: np.ndarray) -> np.ndarray:
    if a.dtype.kind not in "biuf":
        raise ValueError(f"{path}: heights must be real numbers, got dtype {a.dtype}")
    if a.ndim == 1 or (a.ndim == 2 and min(a.shape) == 1):
        raise ValueError(
            f"{path}: holds a 1-D profile of {a.size} points (shape {a.shape}); a 2-D height "
            "map (ny, nx) with ny, nx >= 2 is needed"
        )
    if a.ndim != 2:
        raise ValueError(f"{path}: heights must be a 2-D array (ny, nx), got shape {a.shape}")
    return a.astype(np.float64)


def _try_warptrunc_file(path: Path) -> Surface | None:
    """A file written by Surface.save, else None."""
    if not path.exists():
        return None
    if path.suffix.lower() == ".npy":
        return load_surface(path) if path.with_suffix(".json").exists() else None
    try:
        # open the file ourselves: np.load leaks its handle when a zip is corrupt
        with open(path, "rb") as fh, np.load(fh, allow_pickle=False) as f:
            is_ours = "heights" in f.files and "metadata" in f.files
    except Exception as exc:
        raise ValueError(f"{path}: not a readable .npz file ({exc})") from None
    return load_surface(path) if is_ours else None


def _read_numpy(path: Path, dx, dy, height_unit) -> Scan:
    suffix = path.suffix.lower()
    try:
        ours = _try_warptrunc_file(path)
    except (ValueError, KeyError, json.JSONDecodeError) as exc:
        raise ValueError(f"{path}: corrupt warptrunc metadata ({exc})") from None
    if ours is not None:
        return Scan(
            np.asarray(ours.heights, np.float64) * height_unit,
            ours.dx if dx is None else dx,
            ours.dy if dy is None else dy,
            str(path),
            "warptrunc",
            {"params": ours.params},
        )
    try:
        if suffix == ".npy":
            with open(path, "rb") as fh:
                a = np.load(fh, allow_pickle=False)
        else:
            with open(path, "rb") as fh, np.load(fh, allow_pickle=False) as f:
                names = f.files
                key = next((k for k in ("heights", "z") if k in names), None)
                if key is None and len(names) == 1:
                    key = names[0]
                if key is None:
                    raise ValueError(
                        f"{path}: cannot tell which array holds the heights among {names}; "
                        "name it 'heights' or store a single array"
                    )
                a = f[key]
    except ValueError as exc:
        if str(exc).startswith(str(path)):
            raise
        raise ValueError(f"{path}: not a readable {suffix} file ({exc})") from None
    except (OSError, EOFError) as exc:
        raise ValueError(f"{path}: not a readable {suffix} file ({exc})") from None
    z = _as_map(path, np.asarray(a))
    dx, dy = _need_spacing(path, dx, dy, f"a plain {suffix} array")
    return Scan(z * height_unit, dx, dy, str(path), suffix[1:], {})


_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def _length(value: str, path: Path, key: str) -> float:
    m = re.fullmatch(rf"\s*({_NUM})\s*([^\s\d]*)\s*", value)
    if not m:
        raise ValueError(f"{path}: header {key}={value!r} is not a length such as '1.5e-6 m'")
    unit = m.group(2).lower() or "m"
    if unit not in _LENGTH_UNITS:
        raise ValueError(
            f"{path}: header {key}={value!r} has unit {unit!r}; known: {sorted(_LENGTH_UNITS)}"
        )
    return float(m.group(1)) * _LENGTH_UNITS[unit]


def _parse_header(lines: list[str], path: Path) -> dict[str, str]:
    out: dict[str, str] = {}
    for line in lines:
        s = line.strip().lstrip("#").strip()
        if not s:
            continue
        tokens = s.split()
        if len(tokens) > 1 and all("=" in t for t in tokens):
            pairs = [t.split("=", 1) for t in tokens]
        else:
            m = re.match(r"([^=:]+?)\s*[=:]\s*(.*)$", s)
            pairs = [(m.group(1), m.group(2))] if m else []
        for k, v in pairs:
            out[k.strip().lower()] = v.strip()
    return out


def _split(line: str, delim: str | None) -> list[str]:
    if delim is None:
        return line.split()
    return [t.strip() for t in line.split(delim)]


def _to_floats(tokens: list[str], path: Path, lineno: int) -> np.ndarray:
    try:
        return np.array([float(t) if t else math.nan for t in tokens], dtype=np.float64)
    except ValueError:
        for col, t in enumerate(tokens):
            try:
                float(t) if t else None
            except ValueError:
                raise ValueError(
                    f"{path}: line {lineno}, column {col + 1}: {t!r} is not a number"
                ) from None
        raise


def _is_numeric_line(line: str, delim: str | None) -> bool:
    try:
        for t in _split(line, delim):
            if t:
                float(t)
        return True
    except ValueError:
        return False


def _read_text(path: Path, dx, dy, height_unit) -> Scan:
    try:
        text = path.read_text(encoding="utf-8", errors="strict")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not a text file ({exc.reason} at byte {exc.start})") from None
    lines = text.splitlines()
    first = next(
        (i for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith("#")), None
    )
    # header: leading comment lines and non-numeric lines
    delim: str | None = None
    start = None
    for i, ln in enumerate(lines):
        s = ln.strip()
        if not s or s.startswith("#"):
            continue
        d = "," if "," in s else ";" if ";" in s else "\t" if "\t" in s.strip() else None
        if _is_numeric_line(s, d):
            start, delim = i, d
            break
    if first is None or start is None:
        raise ValueError(f"{path}: no numeric rows found")
    header = _parse_header(lines[:start], path)
    rows = []
    width = None
    for i in range(start, len(lines)):
        s = lines[i].strip()
        if not s or s.startswith("#"):
            continue
        r = _to_floats(_split(s, delim), path, i + 1)
        if width is None:
            width = r.size
        elif r.size != width:
            raise ValueError(
                f"{path}: line {i + 1} has {r.size} values, expected {width} as in line "
                f"{start + 1} (truncated or ragged file)"
            )
        rows.append(r)
    z = _as_map(path, np.array(rows))
    ny, nx = z.shape
    for keys, n, what in (
        (("ny", "h", "rows"), ny, "rows"),
        (("nx", "w", "columns"), nx, "columns"),
    ):
        for k in keys:
            if k in header:
                try:
                    want = int(float(header[k]))
                except ValueError:
                    raise ValueError(
                        f"{path}: header {k}={header[k]!r} is not an integer"
                    ) from None
                if want != n:
                    raise ValueError(
                        f"{path}: header says {k}={want} but the file has {n} {what} "
                        "(truncated file?)"
                    )
    fdx = fdy = None
    for k, v in header.items():
        if k in ("dx", "pixel size x", "x pixel size"):
            fdx = _length(v, path, k)
        elif k in ("dy", "pixel size y", "y pixel size"):
            fdy = _length(v, path, k)
        elif k in ("pixel size", "pixel spacing"):
            fdx = fdy = _length(v, path, k)
    if fdx is not None and fdy is None:
        fdy = fdx
    factor = None
    for k, v in header.items():
        if k.startswith("height conversion factor") or k in ("height unit", "z unit"):
            try:
                factor = _length(v, path, k)
            except ValueError:
                raise ValueError(
                    f"{path}: header {k}={v!r} is not a height unit such as '1e-6' or '1 nm'"
                ) from None
    if factor is not None and height_unit != 1.0:
        raise ValueError(
            f"{path}: the file declares its height unit ({factor:g} m); height_unit="
            f"{height_unit!r} would conflict with it"
        )
    dx = fdx if dx is None else dx
    dy = fdy if dy is None else dy
    dx, dy = _need_spacing(path, dx, dy, "a text matrix without a 'dx=' or 'pixel size=' header")
    scale = factor if factor is not None else height_unit
    return Scan(z * scale, dx, dy, str(path), "text", {"header": header} if header else {})


# --- instrument formats via SurfaceTopography -------------------------------------------------


def _read_surfacetopography(path: Path, dx, dy, height_unit, channel) -> Scan:
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
        ch = reader.default_channel if channel is None else reader.channels[channel]
        kwargs: dict[str, Any] = {"channel_index": ch.index}
        if ch.physical_sizes is None or ch.unit is None:
            # the file lacks sizes or units: the user's dx, dy (m) define them, heights are
            # multiplied by height_unit
            nx_, ny_ = ch.nb_grid_pts
            pdx, pdy = _need_spacing(path, dx, dy, "this instrument file (no physical size)")
            f = 1.0 if ch.unit is None else _LENGTH_UNITS.get(str(ch.unit).lower())
            if f is None:
                raise ValueError(f"{path}: unknown length unit {ch.unit!r} in the file")
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
