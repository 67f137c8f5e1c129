# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The punch face as the experiment had it: a misaligned flat and a rough tip.

Its parameters are a :class:`PunchFaceSpec` (``IndentProtocol.face``); :func:`make_face` turns
them into the :class:`PunchFace` of one punch diameter.

Heights of the face are measured toward the sample (a protrusion of the face is positive), in
the punch's own frame: x, y from the punch centre along the map's axes (m). The composite
surface the contact solver sees inside the disk is the sample's heights plus the face's, so the
gap is the punch's rigid plane minus the sum of both surfaces' heights.

* **Tilt** (``tilt_deg`` θ, ``tilt_azimuth_deg`` φ): the plane
  tan θ·(x cos φ + y sin φ) — a rotation of the flat about the axis through the punch centre
  perpendicular to the direction φ (from +x toward +y), the edge in direction φ nearest the
  sample. The tilt is held fixed, as the indenter's shaft holds it: the punch translates and
  does not rotate (no moment equilibrium), so Barber's unloading stiffness is that of the
  contact set, as for an aligned punch. The projection of the disk (its cos θ shortening,
  1.5·10⁻⁶ at 0.1°) is neglected. Analytic: the same plane at any pixel.
  ``tilt_reference = "local"`` measures θ against the sample's least-squares plane over the
  disk at each placement instead of the map's mean plane (a long wave tilts the sample under a
  punch by itself: Ps's 2 mm wave by about 0.02° rms): the face's plane is the tilt less that
  local plane, fitted once at the map's pixel and kept at every finer pixel, so that the
  composite's mean plane over the disk is tilted by θ exactly, and 0° is a face aligned with
  the surface under it. ``tilt_azimuths = n`` turns the azimuth by 360°/n from one placement
  to the next (:func:`placement_face`), so that averages over the placements are averages over
  azimuth, as over the unknown orientation of an instrument's misalignment.
* **A generated rough face** (``roughness`` R_q > 0): a self-affine, Fourier-filtered
  Gaussian field, C(q) ∝ q^(−2−2H) for 2π/λ_L ≤ abs(q) ≤ 2π/λ_s and 0 outside, on a periodic
  square of side P = 2·max(d, λ_L) centred on the punch; white noise from
  ``numpy.random.default_rng(seed)`` on the host (the same face on every device), filtered by
  its FFT. The face is the field's trigonometric interpolant (band-limited: no content beyond
  2π/λ_s), evaluated at the pixel centres of any window by a separable Fourier sum, so a window
  generated at a finer pixel (:mod:`warptrunc.indent.refine`) holds the same face, as a WM
  window holds the same surface. It is then levelled (least-squares plane over the disk, on
  its reference grid of spacing P/N ≤ λ_s/2) and scaled so that its rms over the disk is R_q:
  a levelled face, as a profilometer reads a tip, so that the tilt alone is set by θ.
  Defaults: Hurst exponent H = 0.8 (:data:`DEFAULT_HURST`); λ_s = 2 pixels of the map (the
  finest wavelength its pixel holds); λ_L = the punch diameter (a longer wave is the face's
  form — tilt, curvature — not its roughness).
* **A measured face** (``file``): a height map (:func:`warptrunc.io.read_height_map`,
  with its own pixel) centred on the punch, levelled by its least-squares plane over the disk
  and resampled to the window's pixel centres by bilinear interpolation of its pixel-centre
  values (the same continuous face at any pixel). It must cover the disk.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..params import Parameters, check_fields, param

__all__ = [
    "DEFAULT_HURST",
    "MAX_FACE_GRID",
    "PunchFace",
    "PunchFaceSpec",
    "check_same_face",
    "face_record",
    "face_settings",
    "make_face",
    "placement_face",
    "punch_faces",
    "self_affine_field",
]

DEFAULT_HURST = 0.8
"""Hurst exponent H of a generated rough face (dimensionless): C(q) ∝ q^(−2−2H), fractal
dimension 3 − H = 2.2, the value most measured engineering surfaces fall near (Persson,
Tribol. Lett. 2014, doi:10.1007/s11249-014-0313-4). The paper does not give the tip's
spectrum, only its rms of about 0.05 µm."""

MAX_FACE_GRID = 4096
"""Largest side N of a generated face's reference grid (P/N ≤ λ_s/2): its Fourier modes span
at most N/2 − 1 per axis."""


@dataclass(frozen=True)
class PunchFaceSpec(Parameters):
    """The punch face's parameters: its tilt, held fixed, and its roughness, generated or read.

    The default is an aligned smooth flat. A generated face (``roughness`` > 0) is one face per
    punch diameter (seed ``(seed, diameter index)``), the same at every placement and
    realisation; a read face (``file``) is centred on every punch.

    Raises
    ------
    ValueError
        A field out of its range (the message names it, its value and the range), or both
        ``roughness`` and ``file``.

    Examples
    --------
    >>> PunchFaceSpec(tilt_deg=0.1).is_flat
    False
    """

    tilt_deg: float = param(
        0.0,
        "tilt θ of the punch face against the sample's mean plane, held fixed as the "
        "indenter's shaft holds it (0.1° rises 0.88 µm over 502.6 µm)",
        unit="°",
        ge=0.0,
        le=5.0,
    )
    tilt_azimuth_deg: float = param(
        0.0,
        "direction of the tilted face's edge nearest the sample, from +x toward +y, the "
        "same for every placement (tilt_azimuths spreads it)",
        unit="°",
        ge=0.0,
        lt=360.0,
        sweep=False,
    )
    tilt_reference: str = param(
        "map",
        "what the tilt is measured against: 'map' (the map's mean plane: one misalignment "
        "at every placement) or 'local' (the sample's least-squares plane over the disk at "
        "each placement: the tilt of the punch relative to the surface under it; 0° then "
        "aligns the face with that plane)",
        choices=("map", "local"),
        sweep=False,
    )
    tilt_azimuths: int = param(
        1,
        "azimuths of the tilt spread over the placements: the i-th placement of a punch "
        "(counted over realisations, then placements) tilts toward tilt_azimuth_deg + "
        "360°·(i mod n)/n, so that averages over the placements average over azimuth; 1 = "
        "tilt_azimuth_deg at every placement",
        kind="int",
        ge=1,
        le=360,
        sweep=False,
    )
    roughness: float = param(
        0.0,
        "rms R_q of a generated self-affine rough punch face, over the disk after "
        "levelling; 0 = smooth",
        unit="m",
        ge=0.0,
    )
    hurst: float = param(
        DEFAULT_HURST,
        "Hurst exponent H of the rough punch face, C(q) ∝ q^(−2−2H)",
        gt=0.0,
        le=1.0,
        sweep=False,
    )
    cutoff_short: float | None = param(
        None,
        "shortest wavelength λ_s of the rough punch face; none = 2 pixels of the map",
        unit="m",
        gt=0.0,
        optional=True,
        sweep=False,
    )
    cutoff_long: float | None = param(
        None,
        "longest wavelength λ_L of the rough punch face; none = the punch diameter",
        unit="m",
        gt=0.0,
        optional=True,
        sweep=False,
    )
    seed: int = param(
        0,
        "seed of the rough punch face (one face per punch diameter, the same at every placement)",
        kind="int",
        ge=0,
        le=2**32 - 1,
        sweep=False,
    )
    file: str | None = param(
        None,
        "a height map of the punch face (heights toward the sample, its own pixel), "
        "centred on every punch, levelled over its disk and resampled bilinearly; instead of "
        "a generated roughness",
        kind="str",
        optional=True,
        metavar="FILE",
        sweep=False,
    )

    def __post_init__(self) -> None:
        if isinstance(self.file, os.PathLike):
            object.__setattr__(self, "file", os.fspath(self.file))
        check_fields(self)
        if self.file is not None:
            if not self.file:
                raise ValueError(f"file must be a path, got {self.file!r}")
            if self.roughness > 0:
                raise ValueError(
                    f"roughness ({self.roughness!r} m) and file ({self.file!r}) both give the "
                    "punch face's roughness; give one"
                )

    @property
    def is_flat(self) -> bool:
        """Whether the face is an aligned smooth flat (no tilt against the map, no roughness,
        no file)."""
        return (
            self.tilt_deg == 0.0
            and self.tilt_reference == "map"
            and self.roughness == 0.0
            and self.file is None
        )


def self_affine_field(
    n: int, period: float, hurst: float, cutoff_short: float, cutoff_long: float, seed: Any
) -> tuple[np.ndarray, np.ndarray]:
    """A periodic self-affine Gaussian field by Fourier filtering of white noise (host, float64).

    Parameters
    ----------
    n : int
        Samples per side N of the square grid (even).
    period : float
        Side P of the periodic square (m); sample j lies at j·P/N.
    hurst : float
        Hurst exponent H in (0, 1]: C(q) ∝ q^(−2−2H) inside the band.
    cutoff_short : float
        Shortest wavelength λ_s (m); the band ends at q_s = 2π/λ_s.
    cutoff_long : float
        Longest wavelength λ_L (m); the band starts at q_L = 2π/λ_L.
    seed : int or sequence of int
        Seed of ``numpy.random.default_rng`` (the white noise, in raster order).

    Returns
    -------
    field : (N, N) ndarray of float64
        The field (arbitrary scale, zero mean).
    spectrum : (N, N) ndarray of complex128
        Its FFT (``numpy.fft.fft2`` of the field), zero outside q_L ≤ abs(q) ≤ q_s.
    """
    noise = np.random.default_rng(seed).standard_normal((n, n))
    k = np.fft.fftfreq(n, d=period / n) * 2 * math.pi  # rad/m
    q = np.hypot(k[:, None], k[None, :])
    band = (q >= 2 * math.pi / cutoff_long) & (q <= 2 * math.pi / cutoff_short)
    filt = np.zeros_like(q)
    filt[band] = q[band] ** (-1.0 - hurst)  # |amplitude|² ∝ C(q) ∝ q^(−2−2H)
    spectrum = np.fft.fft2(noise) * filt
    return np.fft.ifft2(spectrum).real, spectrum


def _one_blas_thread():
    """One BLAS thread (threadpoolctl) for the products below: OpenBLAS splits a product
    differently over a different number of threads, which changes its last bits, and a Dask
    worker runs with one thread where this process has several."""
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:  # an install without it: the default threads
        import contextlib

        return contextlib.nullcontext()
    return threadpool_limits(limits=1, user_api="blas")


def _plane_fit(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Least-squares plane z ≈ a + b·x + c·y (coefficients a, b, c)."""
    a = np.column_stack([np.ones_like(x), x, y])
    with _one_blas_thread():
        return np.linalg.lstsq(a, z, rcond=None)[0]


@dataclass(frozen=True, eq=False)
class _Fourier:
    """A levelled, scaled band-limited face: Re Σ c_kl e^{2πi(k·X + l·Y)/P} − plane."""

    period: float
    freqs: np.ndarray
    coef: np.ndarray
    plane: np.ndarray

    def heights(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        ph = 2j * math.pi / self.period
        ex = np.exp(ph * np.outer(x + 0.5 * self.period, self.freqs))
        ey = np.exp(ph * np.outer(y + 0.5 * self.period, self.freqs))
        with _one_blas_thread():  # the sums' order, and so their last bits, as on any machine
            z = ((ey @ self.coef) @ ex.T).real
        a, b, c = self.plane
        return z - (a + b * x[None, :] + c * y[:, None])


@dataclass(frozen=True, eq=False)
class _Bilinear:
    """A face read from a file: bilinear in its pixel-centre values, centred on the punch."""

    z: np.ndarray
    pixel: tuple[float, float]
    plane: np.ndarray

    def heights(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        def axis(u: np.ndarray, n: int, h: float) -> tuple[np.ndarray, np.ndarray]:
            s = np.clip(u / h + 0.5 * (n - 1), 0.0, n - 1.0)  # index in pixel centres
            i = np.minimum(np.floor(s).astype(np.int64), n - 2)
            return i, s - i

        ny, nx = self.z.shape
        ix, wx = axis(x, nx, self.pixel[0])
        iy, wy = axis(y, ny, self.pixel[1])
        z = self.z
        top = z[iy][:, ix] * (1 - wx) + z[iy][:, ix + 1] * wx
        bot = z[iy + 1][:, ix] * (1 - wx) + z[iy + 1][:, ix + 1] * wx
        a, b, c = self.plane
        return top * (1 - wy[:, None]) + bot * wy[:, None] - (a + b * x[None, :] + c * y[:, None])


@dataclass(frozen=True, eq=False)
class PunchFace:
    """The face of one punch: its tilt and its roughness, as heights toward the sample (m)."""

    diameter: float
    """Punch diameter d (m)."""
    tilt: float
    """Tilt θ of the face against the sample's mean plane (rad), held fixed."""
    azimuth: float
    """Direction φ in which the face comes nearest the sample (rad, from +x toward +y)."""
    rough: Any = None
    """The roughness (a generated or a read face), None for a smooth face."""
    info: dict = field(default_factory=dict)
    """What the face is (JSON-able): tilt, roughness parameters, defaults taken."""
    level: tuple[float, float] = (0.0, 0.0)
    """Slopes (∂z/∂x, ∂z/∂y) of the sample's local plane under this placement that the face
    takes out (dimensionless): the face's plane is the tilt less this plane, so that the tilt
    is relative to the surface under the punch (``tilt_reference = "local"``); zeros
    otherwise."""

    def plane(self, x: Any, y: Any) -> np.ndarray:
        """The face's plane at points (m): tan θ·(x cos φ + y sin φ) − (b·x + c·y).

        Parameters
        ----------
        x, y : array_like
            Offsets from the punch centre (m), broadcast together.

        Returns
        -------
        ndarray of float64
        """
        x = np.asarray(x, dtype=np.float64)
        y = np.asarray(y, dtype=np.float64)
        t = math.tan(self.tilt)
        b, c = self.level
        return (t * math.cos(self.azimuth) - b) * x + (t * math.sin(self.azimuth) - c) * y

    def heights(self, x: Any, y: Any) -> np.ndarray:
        """Heights of the face toward the sample on a grid (m).

        Parameters
        ----------
        x : (wx,) array_like
            x of the columns from the punch centre (m).
        y : (wy,) array_like
            y of the rows from the punch centre (m).

        Returns
        -------
        (wy, wx) ndarray of float64
            :meth:`plane` (the tilt, less the local plane it is measured against) plus the
            rough face.
        """
        x = np.asarray(x, dtype=np.float64)
        y = np.asarray(y, dtype=np.float64)
        out = np.broadcast_to(self.plane(x[None, :], y[:, None]), (y.size, x.size)).copy()
        if self.rough is not None:
            out += self.rough.heights(x, y)
        return out


def _disk_points(n: int, h: float, d: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Reference-grid offsets (x, y) from the grid centre, and which lie in the disk."""
    u = (np.arange(n) - n // 2) * h
    x, y = np.meshgrid(u, u)
    return x, y, x * x + y * y <= 0.25 * d * d


def make_face(
    diameter: float,
    face: PunchFaceSpec | None = None,
    *,
    index: int = 0,
    pixel: float | None = None,
    surface: Any = None,
) -> PunchFace | None:
    """The face of a punch of diameter d: tilted, rough (generated or read), or None if neither.

    Parameters
    ----------
    diameter : float
        Punch diameter d (m).
    face : PunchFaceSpec, optional
        The face's tilt and roughness (default: an aligned smooth flat).
    index : int
        The punch's index among the run's diameters: a generated face draws its white noise
        with the seed ``(face.seed, index)``.
    pixel : float, optional
        The map's pixel side (m), for the default λ_s.
    surface : Surface, optional
        The measured face of ``face.file`` as read (heights toward the sample, its own pixel);
        excludes ``face.roughness``.

    Returns
    -------
    PunchFace or None
        None for an aligned smooth face (θ = 0, no roughness).

    Raises
    ------
    ValueError
        Cut-offs that leave no band, a band too wide for :data:`MAX_FACE_GRID`, a read face that
        does not cover the disk, or a read face beside a generated roughness.
    """
    face = PunchFaceSpec() if face is None else face
    d = float(diameter)
    tilt_deg = face.tilt_deg
    info: dict[str, Any] = {
        "tilt_deg": float(tilt_deg),
        "tilt_azimuth_deg": float(face.tilt_azimuth_deg),
        "tilt_rise_over_diameter_m": d * math.tan(math.radians(tilt_deg)),
        "tilt_axis": "through the punch centre, perpendicular to the azimuth; the punch is held "
        "against rotation (no moment equilibrium)",
        "composite": "gap = punch plane - (sample heights + face heights), face heights toward "
        "the sample",
    }
    rough: Any = None
    if surface is not None and face.roughness > 0:
        raise ValueError(
            f"face.roughness ({face.roughness!r} m) and a read face ({face.file!r}) both give "
            "the face's roughness; give one"
        )
    if surface is not None:
        rough, info["roughness"] = _read_face(surface, d, face.file)
    elif face.roughness > 0:
        rough, info["roughness"] = _generated_face(d, face, (face.seed, index), pixel)
    else:
        info["roughness"] = None
    info["tilt_reference"] = face.tilt_reference
    info["tilt_azimuths"] = int(face.tilt_azimuths)
    if tilt_deg == 0.0 and rough is None and face.tilt_reference == "map":
        return None
    return PunchFace(d, math.radians(tilt_deg), math.radians(face.tilt_azimuth_deg), rough, info)


def placement_face(
    face: PunchFace | None, spec: PunchFaceSpec, index: int, sample: Any = None
) -> PunchFace | None:
    """The face of one placement: its azimuth (``spec.tilt_azimuths``) and, for a tilt
    relative to the surface (``spec.tilt_reference = "local"``), the sample's plane under it
    taken out.

    Parameters
    ----------
    face : PunchFace or None
        The punch diameter's face (:func:`make_face`).
    spec : PunchFaceSpec
        Its parameters.
    index : int
        The placement's index among the punch's placements, counted over realisations then
        placements.
    sample : PunchWindow, optional
        The placement's window without a face (the sample's heights at the map's pixel): the
        local plane is the least-squares plane of its disk pixels. Needed for ``"local"``.

    Returns
    -------
    PunchFace or None
        ``face`` itself when neither applies; else a copy with the azimuth
        φ = ``tilt_azimuth_deg`` + 360°·(index mod n)/n and the local plane's slopes in
        :attr:`PunchFace.level`, ``info`` recording both (``local_plane_tilt_deg``, the local
        plane's own tilt against the map).
    """
    if face is None or (spec.tilt_reference == "map" and spec.tilt_azimuths == 1):
        return face
    azimuth = math.radians(
        spec.tilt_azimuth_deg + 360.0 * (index % spec.tilt_azimuths) / spec.tilt_azimuths
    )
    info = {**face.info, "tilt_azimuth_deg": math.degrees(azimuth) % 360.0}
    level = (0.0, 0.0)
    if spec.tilt_reference == "local":
        if sample is None:
            raise ValueError("a tilt relative to the local plane needs the placement's window")
        iy, ix = np.nonzero(sample.mask)
        x = (ix + sample.origin[1] + 0.5) * sample.pixel_size[0] - sample.centre[0]
        y = (iy + sample.origin[0] + 0.5) * sample.pixel_size[1] - sample.centre[1]
        _a, b, c = _plane_fit(x, y, sample.surface_disk_heights)
        level = (float(b), float(c))
        info["local_plane_tilt_deg"] = math.degrees(math.atan(math.hypot(b, c)))
        info["local_plane_slopes"] = list(level)
    return PunchFace(face.diameter, face.tilt, azimuth, face.rough, info, level)


def _generated_face(
    d: float, face: PunchFaceSpec, seed: Any, pixel: float | None
) -> tuple[_Fourier, dict]:
    rms, hurst = face.roughness, face.hurst
    if face.cutoff_short is None:
        if pixel is None:
            raise ValueError("face.cutoff_short (m) is needed without the map's pixel")
        lam_s, short_how = 2.0 * float(pixel), "default: 2 pixels of the map"
    else:
        lam_s, short_how = float(face.cutoff_short), "given"
    lam_l, long_how = (
        (d, "default: the punch diameter")
        if face.cutoff_long is None
        else (float(face.cutoff_long), "given")
    )
    if not lam_l > lam_s:
        raise ValueError(
            f"face.cutoff_long ({lam_l:.6g} m, {long_how}) must exceed face.cutoff_short "
            f"({lam_s:.6g} m, {short_how}): no wavelength is left for the face's roughness"
        )
    period = 2.0 * max(d, lam_l)
    m = math.floor(period / lam_s * (1 + 1e-12))  # modes per axis: |k| ≤ P/λ_s
    n = 2 * m + 2
    if n > MAX_FACE_GRID:
        raise ValueError(
            f"face.cutoff_short must be at least {period / (MAX_FACE_GRID / 2 - 1):.4g} m for "
            f"this punch (its face's Fourier modes would exceed {MAX_FACE_GRID // 2 - 1} per "
            f"axis), got {lam_s:.6g} m ({short_how})"
        )
    zc, spec = self_affine_field(n, period, hurst, lam_s, lam_l, seed)
    h = period / n
    x, y, disk = _disk_points(n, h, d)
    # sample j lies at j·h = P/2 + (j − n/2)·h: sample n/2 is the punch centre
    plane = _plane_fit(x[disk], y[disk], zc[disk])
    res = zc[disk] - (plane[0] + plane[1] * x[disk] + plane[2] * y[disk])
    scale = rms / float(np.sqrt(np.mean(res * res)))
    freqs = np.arange(-m, m + 1)
    sub = spec[np.ix_(freqs % n, freqs % n)] / (n * n)
    face = _Fourier(period, freqs.astype(np.float64), scale * sub, scale * plane)
    info = {
        "kind": "self-affine (Fourier-filtered Gaussian), levelled over the disk",
        "rms_m": float(rms),
        "hurst": float(hurst),
        "cutoff_short_m": lam_s,
        "cutoff_short": short_how,
        "cutoff_long_m": lam_l,
        "cutoff_long": long_how,
        "seed": list(np.atleast_1d(seed).tolist()),
        "period_m": period,
        "modes_per_axis": 2 * m + 1,
        "reference_grid": n,
    }
    return face, info


def _read_face(surface: Any, d: float, source: str | None) -> tuple[_Bilinear, dict]:
    z = np.asarray(surface.heights, dtype=np.float64)
    dx, dy = float(surface.dx), float(surface.dy)
    ny, nx = z.shape
    hx, hy = 0.5 * (nx - 1) * dx, 0.5 * (ny - 1) * dy  # half-extent of the pixel centres
    if min(nx, ny) < 2 or hx < 0.5 * d * (1 - 1e-9) or hy < 0.5 * d * (1 - 1e-9):
        raise ValueError(
            f"face.file must cover the punch disk: its pixel centres span "
            f"{2 * hx:.6g} × {2 * hy:.6g} m, the punch is {d:.6g} m across (file {source!r})"
        )
    x = (np.arange(nx) - 0.5 * (nx - 1)) * dx
    y = (np.arange(ny) - 0.5 * (ny - 1)) * dy
    xx, yy = np.meshgrid(x, y)
    disk = xx * xx + yy * yy <= 0.25 * d * d
    plane = _plane_fit(xx[disk], yy[disk], z[disk])
    res = z[disk] - (plane[0] + plane[1] * xx[disk] + plane[2] * yy[disk])
    info = {
        "kind": "read from a height map, centred on the punch, levelled over the disk, "
        "resampled by bilinear interpolation of its pixel-centre values",
        "file": source,
        "shape": [ny, nx],
        "pixel_m": [dx, dy],
        "rms_m": float(np.sqrt(np.mean(res * res))),
    }
    return _Bilinear(z, (dx, dy), plane), info


# --- the faces of a run (warptrunc.indent) -------------------------------------------------------


def punch_faces(face: PunchFaceSpec, diameters: tuple, pixel: float) -> list[PunchFace | None]:
    """The face of each punch diameter of a run.

    Parameters
    ----------
    face : PunchFaceSpec
        The face's parameters (``IndentProtocol.face``); its ``file`` is read here, once.
    diameters : tuple of float or None
        The punch diameters (m); None: a flat larger than the map (no face allowed).
    pixel : float
        The map's larger pixel side (m), for the default short cut-off.

    Returns
    -------
    list of PunchFace or None
        One per diameter; the generated face of diameter i from the seed ``(face.seed, i)``.

    Raises
    ------
    ValueError
        A face on a flat larger than the map, a file that cannot be read, or a face that
        cannot be made (:func:`make_face`).
    """
    surface = None
    if face.file is not None:
        from ..io import read_height_map

        try:
            surface = read_height_map(face.file)
        except (OSError, ValueError) as e:
            raise ValueError(f"face.file {face.file!r}: {e}") from None
    out: list[PunchFace | None] = []
    for i, d in enumerate(diameters):
        if d is None:
            if not face.is_flat:
                raise ValueError(
                    "a tilted or rough punch face needs a finite punch_diameters, got none "
                    "(a flat larger than the map)"
                )
            out.append(None)
            continue
        out.append(make_face(d, face, index=i, pixel=pixel, surface=surface))
    return out


def face_settings(diameters: tuple, faces: list[PunchFace | None]) -> list[dict] | None:
    """What ``indent.json``'s ``settings`` records of the punch faces.

    Parameters
    ----------
    diameters : tuple of float or None
        The punch diameters (m).
    faces : list of PunchFace or None
        Their faces (:func:`punch_faces`).

    Returns
    -------
    list of dict or None
        Per diameter: ``diameter_m`` and the face's ``info`` (tilt, roughness parameters and
        the defaults taken); None when every face is an aligned smooth flat.
    """
    if all(f is None for f in faces):
        return None
    return [
        {"diameter_m": d, **(f.info if f is not None else {"tilt_deg": 0.0, "roughness": None})}
        for d, f in zip(diameters, faces, strict=True)
    ]


def face_record(window: Any) -> dict[str, float]:
    """The face as the map's pixel sampled it under one punch placement (for ``settings``).

    Parameters
    ----------
    window : PunchWindow
        A punch window at the map's pixel.

    Returns
    -------
    dict
        ``face_Rt_m`` (peak-to-valley) and ``face_roughness_rms_m`` (rms of the face less its
        plane) over the disk's pixels, ``composite_Rt_m``, ``face_tilt_azimuth_deg`` and, for a
        tilt relative to the surface, ``local_plane_tilt_deg`` (the sample's local plane
        against the map); empty without a face.
    """
    if window.face is None:
        return {}
    f = window.face_heights[window.mask]
    rough = window.untilted_disk_heights - window.surface_disk_heights
    out = {
        "face_Rt_m": float(np.ptp(f)),
        "face_roughness_rms_m": float(np.std(rough)),
        "composite_Rt_m": float(np.ptp(window.disk_heights)),
        "face_tilt_azimuth_deg": math.degrees(window.face.azimuth) % 360.0,
    }
    if "local_plane_tilt_deg" in window.face.info:
        out["local_plane_tilt_deg"] = window.face.info["local_plane_tilt_deg"]
    return out


def check_same_face(reuse: Any, protocol: Any) -> None:
    """Refuse an elastic run given as ``reuse`` that was run with another punch face.

    Parameters
    ----------
    reuse : IndentationResult or dict
        The elastic run (its columns carry no face: a dict is not checked).
    protocol : IndentProtocol
        This run's protocol.

    Raises
    ------
    ValueError
        A face field that differs, named.
    """
    theirs = getattr(reuse, "protocol", None)
    if theirs is None:
        return
    for k, v in protocol.face.to_dict().items():
        if getattr(theirs.face, k) != v:
            raise ValueError(
                f"reuse was run with face.{k} = {getattr(theirs.face, k)!r}, this run with "
                f"{v!r}; give the same punch face"
            )
