# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Built-in readers (no extra dependency): NumPy ``.npy``/``.npz`` and text matrices
(``.csv``/``.txt``/``.tsv``) with an optional ``key=value`` header."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np

from .._support.outputs import jsonable
from ..surface import Surface
from .detect import find_data_start, header_units, npz_height_key, shape_words, table_to_map
from .scan import LENGTH_UNITS, Scan


def need_spacing(path: Path, dx: float | None, dy: float | None, what: str) -> tuple[float, float]:
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
            f"{path}: {shape_words(a.shape)}; a 2-D height map (ny, nx) with ny, nx >= 2 is needed"
        )
    if a.ndim != 2:
        raise ValueError(f"{path}: heights must be a 2-D array (ny, nx), got shape {a.shape}")
    return a.astype(np.float64)


def write_warptrunc_file(surface: Surface, path: Path) -> Path:
    """Save to ``.npz`` (heights + JSON metadata) or ``.npy`` (heights) + ``.json`` sidecar
    (the writer of :func:`warptrunc.write_height_map` for those suffixes).

    Returns the path of the file holding the heights.
    """
    from .._support.provenance import provenance

    meta = json.dumps(
        {"dx": surface.dx, "dy": surface.dy, "params": jsonable(surface.params, nonfinite="text"),
         "provenance": provenance()},
        sort_keys=True,
    )  # fmt: skip
    if path.suffix.lower() == ".npy":
        np.save(path, surface.heights)
        path.with_suffix(".json").write_text(meta + "\n")
    else:
        np.savez_compressed(path, heights=surface.heights, metadata=np.array(meta))
    return path


def load_warptrunc_file(path: Path) -> Surface:
    """A surface written by :func:`write_warptrunc_file` (``.npz``, or ``.npy`` + ``.json``)."""
    path = Path(path)
    if path.suffix == ".npy":
        side = path.with_suffix(".json")
        if not side.exists():
            raise ValueError(
                f"{path}: no metadata sidecar {side.name}; use warptrunc.io.read_height_map "
                "and give the pixel spacing"
            )
        meta = json.loads(side.read_text())
        z = np.load(path, allow_pickle=False)
    else:
        with np.load(path, allow_pickle=False) as f:
            if "heights" not in f or "metadata" not in f:
                raise ValueError(
                    f"{path}: not a warptrunc surface (needs 'heights' and 'metadata')"
                )
            z = f["heights"]
            meta = json.loads(str(f["metadata"]))
    return Surface(z, meta["dx"], meta["dy"], meta.get("params", {}))


NUMPY_MAGIC = {".npy": (b"\x93NUMPY",), ".npz": (b"PK\x03\x04", b"PK\x05\x06")}
"""How a NumPy file starts: the ``.npy`` format's magic string, the zip archive of ``.npz``."""


def check_numpy_file(path: Path) -> None:
    """Refuse a ``.npy``/``.npz`` that is not a NumPy file (text renamed, another format).

    Parameters
    ----------
    path : Path
        An existing ``.npy`` or ``.npz`` file.

    Raises
    ------
    ValueError
        "not a numpy archive", naming the file and what it starts with (text, nothing,
        other bytes), when its first bytes are not those of :data:`NUMPY_MAGIC`.
    """
    suffix = path.suffix.lower()
    with open(path, "rb") as fh:
        head = fh.read(64)
    if head.startswith(NUMPY_MAGIC.get(suffix, (b"",))):
        return
    magic = "numpy's magic string \\x93NUMPY" if suffix == ".npy" else "a zip archive's PK"
    try:
        text = head.decode("utf-8")
    except UnicodeDecodeError as exc:  # text whose last character the 64 bytes cut is text
        text = head[: exc.start].decode("utf-8") if exc.start > len(head) - 4 else None
    if not head:
        found, hint = "it is empty", ""
    elif text is not None and all(c.isprintable() or c.isspace() for c in text):
        line = text.strip().splitlines()[0][:40] if text.strip() else ""
        found = f"it holds text ({line!r} …)"
        hint = "; a text matrix needs a .csv, .txt or .tsv name"
    else:
        found, hint = f"it starts with the bytes {head[:8]!r}", " (another format under this name?)"
    raise ValueError(
        f"{path}: not a numpy archive: a {suffix} file starts with {magic}, and {found}{hint}"
    )


def _pickled(path: Path, exc: ValueError) -> ValueError | None:
    """numpy's refusal of pickled objects as warptrunc's words (None: another error)."""
    if "allow_pickle" not in str(exc):
        return None
    return ValueError(
        f"{path}: holds Python objects (pickled), not an array of numbers; warptrunc does not "
        "unpickle files (unpickling can run code): save the heights as a float array"
    )


def try_warptrunc_file(path: Path) -> Surface | None:
    """A file written by :func:`write_warptrunc_file`, else None."""
    if not path.exists():
        return None
    check_numpy_file(path)
    if path.suffix.lower() == ".npy":
        return load_warptrunc_file(path) if path.with_suffix(".json").exists() else None
    try:
        # open the file ourselves: np.load leaks its handle when a zip is corrupt
        with open(path, "rb") as fh, np.load(fh, allow_pickle=False) as f:
            is_ours = "heights" in f.files and "metadata" in f.files
    except Exception as exc:
        if isinstance(exc, ValueError) and (why := _pickled(path, exc)) is not None:
            raise why from None
        raise ValueError(f"{path}: not a readable .npz file ({exc})") from None
    return load_warptrunc_file(path) if is_ours else None


def read_numpy(path: Path, dx, dy, height_unit) -> Scan:
    suffix = path.suffix.lower()
    try:
        ours = try_warptrunc_file(path)
    except (ValueError, KeyError, json.JSONDecodeError) as exc:
        if str(exc).startswith(f"{path}: "):  # not numpy, or pickled: said already
            raise
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
                a = f[npz_height_key(list(names), path)]
    except ValueError as exc:
        if str(exc).startswith(str(path)):
            raise
        if (why := _pickled(path, exc)) is not None:
            raise why from None
        raise ValueError(f"{path}: not a readable {suffix} file ({exc})") from None
    except (OSError, EOFError) as exc:
        raise ValueError(f"{path}: not a readable {suffix} file ({exc})") from None
    z = _as_map(path, np.asarray(a))
    dx, dy = need_spacing(path, dx, dy, f"a plain {suffix} array")
    return Scan(z * height_unit, dx, dy, str(path), suffix[1:], {})


_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def _length(value: str, path: Path, key: str) -> float:
    m = re.fullmatch(rf"\s*({_NUM})\s*([^\s\d]*)\s*", value)
    if not m:
        raise ValueError(f"{path}: header {key}={value!r} is not a length such as '1.5e-6 m'")
    unit = m.group(2).lower() or "m"
    if unit not in LENGTH_UNITS:
        raise ValueError(
            f"{path}: header {key}={value!r} has unit {unit!r}; known: {sorted(LENGTH_UNITS)}"
        )
    return float(m.group(1)) * LENGTH_UNITS[unit]


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


def read_text(path: Path, dx, dy, height_unit) -> Scan:
    try:
        text = path.read_text(encoding="utf-8", errors="strict")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not a text file ({exc.reason} at byte {exc.start})") from None
    lines = text.splitlines()
    # header: leading comments, key=value lines and text-only lines; a mixed line is an error
    found = find_data_start(lines, path)
    if found is None:
        raise ValueError(f"{path}: no numeric rows found")
    start, delim = found
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
    gridded = table_to_map(np.array(rows), path, height_unit, dx, dy)  # XYZ, line scans
    if gridded is not None:
        z, gdx, gdy, meta = gridded
        return Scan(z, gdx, gdy, str(path), "xyz", {"header": header, **meta} if header else meta)
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
    factor, width, height = header_units(header, path)  # Gwyddion's text export
    if fdx is None and width is not None:
        fdx, fdy = width / nx, (height / ny if height is not None else width / nx)
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
    dx, dy = need_spacing(path, dx, dy, "a text matrix without a 'dx=' or 'pixel size=' header")
    scale = factor if factor is not None else height_unit
    return Scan(z * scale, dx, dy, str(path), "text", {"header": header} if header else {})
