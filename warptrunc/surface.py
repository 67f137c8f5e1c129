# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Height maps: the :class:`Surface` result object, its I/O, and Weierstrass–Mandelbrot synthesis.

The WM synthesis evaluates Eq. (4) of the paper on the device (kernels in
``warptrunc.kernels.wm``); everything here is host-side validation, allocation and bookkeeping.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from ._validate import check_height_map, check_range

__all__ = ["Surface", "from_heights", "load_surface"]


@dataclass(frozen=True, eq=False)
class Surface:
    """A height map on a regular grid.

    Heights are ``z[iy, ix]`` at ``x = ix·dx``, ``y = iy·dy`` (pixel corner at the origin).
    """

    heights: np.ndarray
    """(ny, nx) float32 heights z (m)."""
    dx: float
    """Pixel spacing along x (m)."""
    dy: float
    """Pixel spacing along y (m)."""
    params: dict[str, Any] = field(default_factory=dict)
    """Generation or provenance parameters (SI units; JSON-serialisable)."""

    def __post_init__(self) -> None:
        z = check_height_map(self.heights)
        z.setflags(write=False)
        object.__setattr__(self, "heights", z)
        object.__setattr__(self, "dx", check_range("dx", self.dx, 0.0, unit="m"))
        object.__setattr__(self, "dy", check_range("dy", self.dy, 0.0, unit="m"))
        object.__setattr__(self, "params", dict(self.params))

    @property
    def ny(self) -> int:
        """Number of pixels along y."""
        return int(self.heights.shape[0])

    @property
    def nx(self) -> int:
        """Number of pixels along x."""
        return int(self.heights.shape[1])

    @property
    def lx(self) -> float:
        """Side length along x, nx·dx (m)."""
        return self.nx * self.dx

    @property
    def ly(self) -> float:
        """Side length along y, ny·dy (m)."""
        return self.ny * self.dy

    @property
    def pixel_area(self) -> float:
        """Area of one pixel, dx·dy (m²)."""
        return self.dx * self.dy

    @property
    def apparent_area(self) -> float:
        """Apparent (projected) area A = Lx·Ly (m²)."""
        return self.lx * self.ly

    @cached_property
    def rt(self) -> float:
        """Peak-to-valley height R_t = max z − min z (m), in float64."""
        z = self.heights
        return float(np.float64(z.max()) - np.float64(z.min()))

    def to_dict(self) -> dict[str, Any]:
        """Scalar metadata (grid and parameters), JSON-serialisable."""
        return {
            "nx": self.nx,
            "ny": self.ny,
            "dx_m": self.dx,
            "dy_m": self.dy,
            "lx_m": self.lx,
            "ly_m": self.ly,
            "rt_m": self.rt,
            **{k: _jsonable(v) for k, v in self.params.items()},
        }

    def save(self, path: str | Path) -> Path:
        """Save to ``.npz`` (heights + JSON metadata) or ``.npy`` (heights) + ``.json`` sidecar.

        Returns the path of the file holding the heights.
        """
        path = Path(path)
        meta = json.dumps(
            {"dx": self.dx, "dy": self.dy, "params": _jsonable(self.params)}, sort_keys=True
        )
        if path.suffix == ".npy":
            np.save(path, self.heights)
            path.with_suffix(".json").write_text(meta + "\n")
        else:
            if path.suffix != ".npz":
                path = (
                    path.with_suffix(path.suffix + ".npz")
                    if path.suffix
                    else path.with_suffix(".npz")
                )
            np.savez_compressed(path, heights=self.heights, metadata=np.array(meta))
        return path


def load_surface(path: str | Path) -> Surface:
    """Load a surface written by :meth:`Surface.save` (``.npz``, or ``.npy`` + ``.json``)."""
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


def from_heights(z: np.ndarray, dx: float, dy: float | None = None, **params: Any) -> Surface:
    """Wrap a user height map ``z[iy, ix]`` (m) with pixel spacing ``dx`` (and ``dy``) (m)."""
    return Surface(z, dx, dx if dy is None else dy, params)


def _jsonable(v: Any) -> Any:
    if isinstance(v, dict):
        return {str(k): _jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_jsonable(x) for x in v]
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, float) and not math.isfinite(v):
        return str(v)
    return v
