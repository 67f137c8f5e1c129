# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The :class:`Scan` record (a height map as read, missing points kept), the suffixes and
units the readers know, and :class:`MissingExtraError`."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._support.validate import check_range
from ..surface import Surface
from .repair import FILL_METHODS, fill_missing, level_plane

NUMPY_SUFFIXES = (".npz", ".npy")
TEXT_SUFFIXES = (".csv", ".txt", ".tsv")
INSTRUMENT_SUFFIXES = (
    ".sur",
    ".x3p",
    ".datx",
    ".plu",
    ".plux",
    ".opd",
    ".opdx",
    ".vk4",
    ".vk6",
    ".vk7",
    ".gwy",
    ".spm",
    ".mdt",
    ".nid",
    ".ibw",
    ".sdf",
    ".al3d",
    ".frt",
    ".lext",
    ".zon",
    ".asc",
    ".dat",
    ".xyz",
    ".tif",
    ".tiff",
    ".vk3",
    ".apx",
    ".001",
    ".002",
    ".003",
    ".004",
    ".005",
    ".ezd",
    ".os3d",
    ".oir",
    ".poir",
    ".zmg",
    ".mi",
    ".tmd",
    ".top",
    ".cur",
    ".stp",
    ".tom",
    ".hfm",
    ".h5",
    ".nc",
    ".mat",
    ".xlsx",
    ".bcr",
    ".bcrf",
    ".jpk",
    ".mnt",
    ".qep",
    ".nms",
    ".hgt",
    ".zip",
)
"""Suffixes of the instrument files SurfaceTopography (1.27) reads, most common first, the
built-in suffixes left out (it also recognises a file by its content, whatever its suffix)."""
_NAMED = 12  # instrument suffixes a message names before "and N more"


def unrecognised_format(path: Any, *, tried: int | None) -> str:
    """One line for a file that is no height-map format warptrunc reads.

    Parameters
    ----------
    path : path
        The file.
    tried : int or None
        How many of SurfaceTopography's readers tried the file; None when SurfaceTopography
        is not installed.

    Returns
    -------
    str
        The file, its suffix, the formats read (built in, and instrument files through
        SurfaceTopography) and, without SurfaceTopography, how to install it.
    """
    from pathlib import Path

    p = Path(path)
    what = p.suffix or "no suffix"
    if tried is not None:
        what += f"; none of the {tried} SurfaceTopography readers that tried it knows it"
    formats = (
        f"read: {' '.join(NUMPY_SUFFIXES + TEXT_SUFFIXES)} built in, and instrument files "
        f"({' '.join(INSTRUMENT_SUFFIXES[:_NAMED])} and {len(INSTRUMENT_SUFFIXES) - _NAMED} more: "
        "warptrunc.io.INSTRUMENT_SUFFIXES) through SurfaceTopography"
    )
    tail = (
        ""
        if tried is not None
        else (
            ", which this environment lacks (a dependency of warptrunc): pip install SurfaceTopography"
        )
    )
    return f"{p}: not a recognised height-map format ({what}); {formats}{tail}"


LENGTH_UNITS = {
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
    """A dependency that reads the file is missing; the message says what to install."""


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
        """Scalar metadata, JSON-serialisable.

        Returns
        -------
        dict of str to Any
            The scalar metadata of the scan (lengths in m).
        """
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
        n_inf = int(np.count_nonzero(np.isinf(z)))
        what = (
            "missing (NaN)"
            if not n_inf
            else "infinite (±inf)"
            if n_inf == n_missing
            else f"missing (NaN) or infinite ({n_inf} ±inf)"
        )
        if n_missing == z.size:
            raise ValueError(f"{self.source}: every point is {what}")
        if n_missing and missing == "error":
            iy, ix = np.argwhere(~valid)[0]
            raise ValueError(
                f"{self.source}: {n_missing} of {z.size} points are {what}; first at "
                f"iy={iy}, ix={ix}; pass missing='fill' (fill={'|'.join(FILL_METHODS)}; CLI: "
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
