# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""A finite rigid circular flat punch on a height map: which pixels it can touch, where it is
placed, and the window of the map that the contact solve runs on.

Geometry (host, float64). Pixel (iy, ix) has its centre at ((ix + ½)·dx, (iy + ½)·dy) (pixel
corner at the origin, as everywhere in warptrunc). A punch of diameter d centred at (x_c, y_c)
can touch exactly the pixels whose centre lies in the closed disk
(x − x_c)² + (y − y_c)² ≤ (d/2)²; the others never touch.

The contact solve runs on the disk's bounding window (the rows and columns that hold a disk
pixel), not on the whole map: a 54.1 µm punch on a 10240² map over 1 mm is a 554² solve. The
free half-space of :mod:`warptrunc.contact.halfspace` zero-pads the window, so the body around
it is the unloaded half-space. Inside the window the pixels outside the disk are set far below
the disk (by ``drop``, m, beneath its lowest pixel), so that they never touch: the gap there
stays larger than any approach the punch can make (:func:`punch_window`).

A tilted or rough punch face (:mod:`warptrunc.indent.face`) is added to the heights inside the
disk (``face``): the solver sees the composite surface, sample plus face.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._support.validate import check_int, check_range
from ..contact.halfspace import fft_size

__all__ = [
    "PlacementOverlapWarning",
    "PunchWindow",
    "disk_bounds",
    "disk_mask",
    "disk_pixel_count",
    "lens_fraction",
    "place_punches",
    "punch_window",
    "punch_window_at",
]


class PlacementOverlapWarning(UserWarning):
    """Random punch placements that could not be kept apart on the map (they overlap)."""


def _disk_in(
    rows: np.ndarray,
    cols: np.ndarray,
    pixel_size: tuple[float, float],
    centre: tuple[float, float],
    diameter: float,
) -> np.ndarray:
    dx, dy = pixel_size
    x = (cols.astype(np.float64) + 0.5) * dx - centre[0]
    y = (rows.astype(np.float64) + 0.5) * dy - centre[1]
    r = 0.5 * diameter
    return x[None, :] ** 2 + y[:, None] ** 2 <= r * r


def disk_mask(
    shape: tuple[int, int],
    pixel_size: float | tuple[float, float],
    centre: tuple[float, float],
    diameter: float,
) -> np.ndarray:
    """Pixels of a (ny, nx) map whose centre lies in a disk.

    Parameters
    ----------
    shape : (int, int)
        Map size (ny, nx).
    pixel_size : float or (float, float)
        Pixel sides dx, dy (m).
    centre : (float, float)
        Disk centre (x, y) (m), from the map's corner.
    diameter : float
        Disk diameter d (m).

    Returns
    -------
    (ny, nx) ndarray of bool
        True where ((ix + ½)dx − x_c)² + ((iy + ½)dy − y_c)² ≤ (d/2)².
    """
    dx, dy = _pixel_pair(pixel_size)
    ny, nx = shape
    return _disk_in(np.arange(ny), np.arange(nx), (dx, dy), centre, diameter)


def _pixel_pair(pixel_size: Any) -> tuple[float, float]:
    if np.ndim(pixel_size) == 0:
        v = check_range("pixel_size", pixel_size, 0.0, unit="m")
        return v, v
    dx, dy = pixel_size
    return check_range("pixel_size", dx, 0.0, unit="m"), check_range(
        "pixel_size", dy, 0.0, unit="m"
    )


def lens_fraction(distance: Any, diameter: float) -> np.ndarray:
    """Overlap of two disks of one diameter, as a fraction of one disk's area.

    Parameters
    ----------
    distance : float or ndarray
        Distance s between the centres (m).
    diameter : float
        Disk diameter d (m).

    Returns
    -------
    ndarray of float64
        [2r²·acos(s/2r) − (s/2)·√(4r² − s²)] / (πr²), r = d/2 (dimensionless); 0 for s ≥ d,
        1 for s = 0.
    """
    s = np.asarray(distance, dtype=np.float64)
    r = 0.5 * diameter
    u = np.clip(s / (2 * r), 0.0, 1.0)
    lens = 2 * r * r * np.arccos(u) - s * np.sqrt(np.maximum(4 * r * r - s * s, 0.0)) / 2
    return np.where(u >= 1.0, 0.0, lens / (math.pi * r * r))


def place_punches(
    map_size: tuple[float, float],
    diameter: float,
    placements: int | None = 3,
    *,
    seed: int = 0,
    overlap: str = "warn",
) -> tuple[np.ndarray, np.ndarray]:
    """Centres of ``placements`` punches on a map, inside it and apart from each other.

    Parameters
    ----------
    map_size : (float, float)
        Map sides (Lx, Ly) (m).
    diameter : float
        Punch diameter d (m); at most min(Lx, Ly).
    placements : int or None
        Number of punches; None: one punch at the map centre.
    seed : int
        Seed of the random positions (NumPy ``default_rng``).
    overlap : {"warn", "error"}
        When the punches cannot be kept apart: place them as far apart as the search finds and
        warn (:class:`PlacementOverlapWarning`) with the overlap and the map size needed, or
        raise ValueError saying the same.

    Returns
    -------
    centres : (n, 2) ndarray of float64
        Centres (x, y) (m); each disk lies inside the map (d/2 ≤ x ≤ Lx − d/2, likewise y).
    overlap_fraction : (n,) ndarray of float64
        Largest area fraction of each punch covered by another one (dimensionless); zeros when
        they are apart.

    Raises
    ------
    ValueError
        ``diameter`` larger than the map, ``placements`` not a positive integer, or (with
        ``overlap="error"``) punches that cannot be kept apart.

    Notes
    -----
    Random sequential placement: each centre is drawn uniformly in the allowed square and kept
    when it is at least d from the centres kept before (up to 200 draws per punch, 50 fresh
    starts). If that fails, the centres are chosen by farthest-point sampling among 4096
    uniform candidates (the first one drawn from the seed), which spreads them as far as the
    map allows. A square map of side ⌈√n⌉·d always holds n punches apart.
    """
    lx, ly = (float(v) for v in map_size)
    d = check_range("punch_diameter", diameter, 0.0, unit="m")
    if d > min(lx, ly) * (1 + 1e-12):
        raise ValueError(
            f"punch_diameters must be at most the map's smaller side min(Lx, Ly) = "
            f"{min(lx, ly):.6g} m, got {d:.6g} m; use a larger map or a smaller punch"
        )
    if overlap not in ("warn", "error"):
        raise ValueError(f"overlap must be 'warn' or 'error', got {overlap!r}")
    r = 0.5 * d
    if placements is None:
        return np.array([[0.5 * lx, 0.5 * ly]]), np.zeros(1)
    n = check_int("placements", placements, 1)
    rng = np.random.default_rng(seed)
    lo = np.array([r, r])
    span = np.array([max(lx - d, 0.0), max(ly - d, 0.0)])

    def draw(k: int) -> np.ndarray:
        return lo + rng.random((k, 2)) * span

    for _start in range(50):
        kept: list[np.ndarray] = []
        for _ in range(n):
            for _try in range(200):
                c = draw(1)[0]
                if all(np.hypot(*(c - k)) >= d for k in kept):
                    kept.append(c)
                    break
            else:
                break
        if len(kept) == n:
            return np.array(kept), np.zeros(n)
    cand = draw(4096)
    chosen = [0]
    dist = np.hypot(*(cand - cand[0]).T)
    for _ in range(n - 1):
        j = int(np.argmax(dist))
        chosen.append(j)
        dist = np.minimum(dist, np.hypot(*(cand - cand[j]).T))
    centres = cand[chosen]
    sep = np.hypot(*(centres[:, None, :] - centres[None, :, :]).transpose(2, 0, 1))
    np.fill_diagonal(sep, np.inf)
    frac = lens_fraction(sep.min(axis=1), d)
    side = math.ceil(math.sqrt(n)) * d
    msg = (
        f"{n} punches of diameter {d:.6g} m cannot be placed apart on a {lx:.6g} × {ly:.6g} m "
        f"map: placed as far apart as found, they overlap by up to {frac.max():.1%} of a "
        f"punch's area; a map of at least {side:.6g} m per side holds them apart (or use fewer "
        "placements)"
    )
    if overlap == "error":
        raise ValueError(f"placements: {msg}")
    warnings.warn(msg, PlacementOverlapWarning, stacklevel=2)
    return centres, frac


@dataclass(frozen=True, eq=False)
class PunchWindow:
    """The part of a map under one punch, ready for the contact solver and for truncation."""

    diameter: float | None
    """Punch diameter d (m); None: a flat larger than the map (every pixel can touch)."""
    centre: tuple[float, float]
    """Punch centre (x, y) (m), from the map's corner."""
    origin: tuple[int, int]
    """(iy0, ix0): the window's first row and column in the map."""
    mask: np.ndarray
    """(wy, wx) bool: the window's pixels that the punch can touch (centre inside the disk).
    The window is the disk's bounding box grown at its far ends to 7-smooth sides
    (:func:`warptrunc.contact.halfspace.fft_size`), so the FFTs of the solve run at full speed;
    the added pixels are outside the disk."""
    heights: np.ndarray
    """(wy, wx) float64 heights for the solver (m): the map's inside the disk, ``floor``
    outside it."""
    floor: float
    """Height given to the window's pixels outside the disk (m), far below the disk."""
    pixel_size: tuple[float, float]
    """Pixel sides (dx, dy) (m)."""
    area: float
    """Punch area A (m²): πd²/4, or Lx·Ly of the map for ``diameter=None``."""
    face: Any = None
    """The punch face (:class:`~warptrunc.indent.face.PunchFace`: tilt, roughness), None for an
    aligned smooth flat."""
    face_heights: np.ndarray | None = None
    """(wy, wx) float64 heights of the face toward the sample at the disk's pixels, 0 outside
    (m); ``heights`` holds the sample's plus these (the composite surface). None without a
    face."""
    n_disk: int | None = None
    """Pixels of the whole disk when this window is a sub-window of it (``region`` of
    :func:`punch_window_at`: the part of the disk that holds the contact and its interaction
    range; the disk's other pixels are left out of the solve); None for the whole disk."""

    @property
    def n_pixels(self) -> int:
        """Pixels of the window the punch can touch (count)."""
        return int(np.count_nonzero(self.mask))

    @property
    def is_sub_window(self) -> bool:
        """Whether the window holds only part of the disk (:attr:`n_disk`)."""
        return self.n_disk is not None

    @property
    def n_disk_pixels(self) -> int:
        """Pixels of the whole disk (count): :attr:`n_pixels`, or :attr:`n_disk` for a
        sub-window."""
        return self.n_pixels if self.n_disk is None else self.n_disk

    @property
    def pixel_area(self) -> float:
        """Area of one pixel dx·dy (m²)."""
        return self.pixel_size[0] * self.pixel_size[1]

    @property
    def disk_heights(self) -> np.ndarray:
        """(n_pixels,) float64 heights of the pixels the punch can touch (m), in raster order."""
        return self.heights[self.mask]

    @property
    def surface_disk_heights(self) -> np.ndarray:
        """(n_pixels,) float64 heights of the sample alone at the disk's pixels (m): the
        composite :attr:`disk_heights` less the punch face's."""
        if self.face_heights is None:
            return self.disk_heights
        return (self.heights - self.face_heights)[self.mask]

    @property
    def untilted_disk_heights(self) -> np.ndarray:
        """(n_pixels,) float64 composite heights at the disk's pixels less the face's plane
        (m; its tilt and the local plane it takes out): the sample and the face's roughness
        (the solver's default tolerance)."""
        f = self.face
        if f is None or (f.tilt == 0.0 and f.level == (0.0, 0.0)):
            return self.disk_heights
        iy, ix = np.nonzero(self.mask)  # raster order, as the mask indexes
        x = (ix + self.origin[1] + 0.5) * self.pixel_size[0] - self.centre[0]
        y = (iy + self.origin[0] + 0.5) * self.pixel_size[1] - self.centre[1]
        return self.disk_heights - f.plane(x, y)

    @property
    def top(self) -> float:
        """Highest height inside the disk (m): where the punch first touches."""
        return float(self.disk_heights.max())


def punch_window(
    heights: np.ndarray,
    pixel_size: float | tuple[float, float],
    diameter: float | None,
    centre: tuple[float, float] | None = None,
    *,
    drop: float | None = None,
    face: Any = None,
) -> PunchWindow:
    """The window of a map under a punch, with the pixels outside the disk set far below.

    Parameters
    ----------
    heights : (ny, nx) array_like
        Heights z (m) of the map.
    pixel_size : float or (float, float)
        Pixel sides dx, dy (m).
    diameter : float or None
        Punch diameter d (m); None: the whole map (every pixel can touch, A = Lx·Ly).
    centre : (float, float), optional
        Punch centre (x, y) (m); default the map centre. The disk must lie inside the map.
    drop : float, optional
        How far below the disk's lowest pixel the outside pixels are put (m); it must exceed
        every approach of the punch. Default: 10·(R_t of the disk + d).
    face : PunchFace, optional
        The punch face (:func:`warptrunc.indent.face.make_face`): its heights are added to the
        map's inside the disk. A finite punch only.

    Returns
    -------
    PunchWindow

    Raises
    ------
    ValueError
        A punch larger than the map, a disk reaching outside it, or a face on a flat larger
        than the map.
    """
    z = np.asarray(heights, dtype=np.float64)
    dx, dy = _pixel_pair(pixel_size)
    ny, nx = z.shape
    if diameter is None:
        if face is not None:
            raise ValueError(
                "a tilted or rough punch face needs a finite punch_diameters, got none"
            )
        lx, ly = nx * dx, ny * dy
        c = (0.5 * lx, 0.5 * ly) if centre is None else tuple(float(v) for v in centre)
        mask = np.ones((ny, nx), dtype=bool)
        return PunchWindow(None, c, (0, 0), mask, z.copy(), float(z.min()), (dx, dy), lx * ly)
    return punch_window_at(
        lambda o, s: z[o[0] : o[0] + s[0], o[1] : o[1] + s[1]],
        z.shape,
        (dx, dy),
        diameter,
        centre,
        drop=drop,
        face=face,
    )


def punch_window_at(
    generate: Callable[[tuple[int, int], tuple[int, int]], np.ndarray],
    map_shape: tuple[int, int],
    pixel_size: float | tuple[float, float],
    diameter: float,
    centre: tuple[float, float] | None = None,
    *,
    drop: float | None = None,
    face: Any = None,
    region: tuple[int, int, int, int] | None = None,
) -> PunchWindow:
    """:func:`punch_window` on a map known through the heights of any window of it.

    Only the disk's bounding window is asked for, so a map too large to hold (a WM surface
    generated again at a finer pixel, :func:`warptrunc.wm.wm_window`) can be indented; with
    ``region``, only the part of it inside a rectangle (a sub-window).

    Parameters
    ----------
    generate : callable
        ``generate((iy0, ix0), (wy, wx))`` → (wy, wx) heights (m) of rows iy0 … iy0 + wy − 1
        and columns ix0 … ix0 + wx − 1 of the map.
    map_shape : (int, int)
        The map's size (ny, nx).
    pixel_size : float or (float, float)
        Pixel sides dx, dy (m).
    diameter : float
        Punch diameter d (m).
    centre : (float, float), optional
        Punch centre (x, y) (m); default the map centre. The disk must lie inside the map.
    drop : float, optional
        As for :func:`punch_window` (m).
    face : PunchFace, optional
        As for :func:`punch_window`: evaluated at this window's pixel centres, so a finer
        window holds the same face.
    region : (int, int, int, int), optional
        (iy0, ix0, iy1, ix1), first and last row and column of the map (inclusive): the window
        is the disk's bounding box cut to this rectangle, and only the disk's pixels inside it
        can touch (a sub-window; :attr:`PunchWindow.n_disk` counts the whole disk). None: the
        whole disk.

    Returns
    -------
    PunchWindow

    Raises
    ------
    ValueError
        A punch larger than the map, a disk reaching outside it or covering no pixel centre, or
        a region that holds no pixel of the disk.
    """
    dx, dy = _pixel_pair(pixel_size)
    ny, nx = (int(v) for v in map_shape)
    lx, ly = nx * dx, ny * dy
    if centre is None:
        centre = (0.5 * lx, 0.5 * ly)
    cx, cy = (float(v) for v in centre)
    d = check_range("punch_diameter", diameter, 0.0, unit="m")
    if d > min(lx, ly) * (1 + 1e-12):
        raise ValueError(
            f"punch_diameters must be at most the map's smaller side min(Lx, Ly) = "
            f"{min(lx, ly):.6g} m, got {d:.6g} m; use a larger map or a smaller punch"
        )
    r = 0.5 * d
    tol = 1e-9 * max(lx, ly)
    if cx - r < -tol or cx + r > lx + tol or cy - r < -tol or cy + r > ly + tol:
        raise ValueError(
            f"a punch of diameter {d:.6g} m centred at ({cx:.6g}, {cy:.6g}) m reaches outside "
            f"the {lx:.6g} × {ly:.6g} m map; centres must lie in [d/2, L − d/2]"
        )
    # rows/columns whose pixel centre can lie in the disk: (i + ½)·dx ∈ [c − r, c + r]
    ix0 = max(0, math.ceil((cx - r) / dx - 0.5))
    ix1 = min(nx - 1, math.floor((cx + r) / dx - 0.5))
    iy0 = max(0, math.ceil((cy - r) / dy - 0.5))
    iy1 = min(ny - 1, math.floor((cy + r) / dy - 0.5))
    if ix1 < ix0 or iy1 < iy0:
        raise ValueError(
            f"a punch of diameter {d:.6g} m covers no pixel centre of a map with pixels of "
            f"{dx:.6g} × {dy:.6g} m; use a larger punch"
        )
    n_disk = None
    if region is not None:
        n_disk = disk_pixel_count((iy0, ix0, iy1, ix1), (dx, dy), (cx, cy), d)
        ry0, rx0, ry1, rx1 = (int(v) for v in region)
        iy0, ix0, iy1, ix1 = max(iy0, ry0), max(ix0, rx0), min(iy1, ry1), min(ix1, rx1)
        if ix1 < ix0 or iy1 < iy0:
            raise ValueError(f"region {tuple(region)!r} holds no pixel of the punch's disk")
    mask = _disk_in(np.arange(iy0, iy1 + 1), np.arange(ix0, ix1 + 1), (dx, dy), (cx, cy), d)
    if region is not None and int(mask.sum()) == n_disk:
        n_disk = None  # the region holds the whole disk
    if not mask.any():
        raise ValueError(
            f"a punch of diameter {d:.6g} m centred at ({cx:.6g}, {cy:.6g}) m covers no pixel "
            "centre; use a larger punch"
        )
    win = np.array(generate((iy0, ix0), mask.shape), dtype=np.float64)
    if win.shape != mask.shape:
        raise ValueError(f"generate gave a {win.shape} window, {mask.shape} was asked for")
    fh = None
    if face is not None:  # the composite surface: the sample's heights plus the face's
        x = (np.arange(ix0, ix0 + mask.shape[1]) + 0.5) * dx - cx
        y = (np.arange(iy0, iy0 + mask.shape[0]) + 0.5) * dy - cy
        fh = np.where(mask, face.heights(x, y), 0.0)
        win = win + fh
    inside = win[mask]
    if drop is None:
        drop = 10.0 * (float(np.ptp(inside)) + d)
    floor = float(inside.min()) - check_range("drop", drop, 0.0, unit="m")
    win[~mask] = floor
    # grow the window past the disk's bounding box to a length the FFT transforms at full
    # speed (more pixels at the floor, outside the disk: the contact is unchanged)
    wy, wx = mask.shape
    gy, gx = fft_size(wy), fft_size(wx)
    if (gy, gx) != (wy, wx):
        win = np.pad(win, ((0, gy - wy), (0, gx - wx)), constant_values=floor)
        mask = np.pad(mask, ((0, gy - wy), (0, gx - wx)), constant_values=False)
        if fh is not None:
            fh = np.pad(fh, ((0, gy - wy), (0, gx - wx)))
    return PunchWindow(
        d, (cx, cy), (iy0, ix0), mask, win, floor, (dx, dy), math.pi * r * r, face, fh, n_disk
    )


def disk_bounds(
    map_shape: tuple[int, int],
    pixel_size: float | tuple[float, float],
    diameter: float,
    centre: tuple[float, float],
) -> tuple[int, int, int, int]:
    """The rows and columns of a map whose pixel centre can lie in a disk.

    Parameters
    ----------
    map_shape : (int, int)
        The map's size (ny, nx).
    pixel_size : float or (float, float)
        Pixel sides dx, dy (m).
    diameter : float
        Disk diameter d (m).
    centre : (float, float)
        Disk centre (x, y) (m).

    Returns
    -------
    (int, int, int, int)
        (iy0, ix0, iy1, ix1), inclusive, clipped to the map: (i + ½)·dx ∈ [x_c − d/2, x_c + d/2].
    """
    dx, dy = _pixel_pair(pixel_size)
    ny, nx = (int(v) for v in map_shape)
    cx, cy = (float(v) for v in centre)
    r = 0.5 * float(diameter)
    return (
        max(0, math.ceil((cy - r) / dy - 0.5)),
        max(0, math.ceil((cx - r) / dx - 0.5)),
        min(ny - 1, math.floor((cy + r) / dy - 0.5)),
        min(nx - 1, math.floor((cx + r) / dx - 0.5)),
    )


def disk_pixel_count(
    bounds: tuple[int, int, int, int],
    pixel_size: tuple[float, float],
    centre: tuple[float, float],
    diameter: float,
) -> int:
    """Pixels whose centre lies in a disk, counted row by row without a mask.

    Parameters
    ----------
    bounds : (int, int, int, int)
        (iy0, ix0, iy1, ix1) that hold the disk (:func:`disk_bounds`).
    pixel_size : (float, float)
        Pixel sides dx, dy (m).
    centre : (float, float)
        Disk centre (x, y) (m).
    diameter : float
        Disk diameter d (m).

    Returns
    -------
    int
        The count of :func:`disk_mask` (the same closed-disk test, row by row).
    """
    iy0, ix0, iy1, ix1 = bounds
    dx, dy = pixel_size
    cx, cy = centre
    r2 = (0.5 * diameter) ** 2
    cols = np.arange(ix0, ix1 + 1)
    x2 = ((cols + 0.5) * dx - cx) ** 2
    n = 0
    for iy in range(iy0, iy1 + 1):  # one row at a time: a fine window's mask need not exist
        y2 = ((iy + 0.5) * dy - cy) ** 2
        n += int(np.count_nonzero(x2 + y2 <= r2))
    return n
