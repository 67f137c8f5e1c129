# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Roughness descriptors of a height map: amplitude statistics, power spectra, roll-off W_r.

Table 1 of the paper describes each surface by R_t, R_rms, the roll-off wavelength W_r and a
fractal dimension D (see :mod:`warptrunc.fractal` for D). Everything is float64.

Where it runs
-------------
A surface made from NumPy is analysed on the host with NumPy, as before. A device-resident
surface (``surface.device`` set, e.g. from :func:`warptrunc.wm_surface`) is analysed where it
lives, with no host copy of the map:

* amplitude statistics (mean, R_rms, R_a, skewness, kurtosis) are two Warp reductions with
  float64 accumulation (``warptrunc.kernels.reduce``); R_t comes from the surface's validation
  reduction;
* spectra (periodogram, profile PSD, band variances, W_r) use **CuPy's cuFFT** on the Warp array,
  shared zero-copy through ``__cuda_array_interface__``, when the surface is on a CUDA device and
  CuPy is installed; binning (``bincount``) also runs on the GPU and only the binned arrays come
  back. Otherwise (CPU device, or no CuPy) NumPy's FFT runs on a host view (CPU device: the
  Warp array's own memory, no copy) or on the surface's lazy host copy (CUDA without CuPy).

Why cuFFT and not Warp's tile FFT: ``wp.tile_fft`` transforms one tile per block in shared
memory, so a row must fit a block's shared memory as a power-of-two complex tile; a 10240-point
float64 row (10240 is not a power of two, 160 KiB complex) does not, and the 2-D periodogram of
W_r needs a full 2-D transform of the map. cuFFT handles any size and both transforms in float64
at memory bandwidth, and CuPy is the standard way to reach it from Python.

Conventions
-----------
Heights ``z[iy, ix]`` (m), spacings ``dx``, ``dy`` (m), side lengths ``Lx = nx·dx``,
``Ly = ny·dy``. Spatial frequency ``f = 1/λ`` (1/m), not the angular wavenumber ``q = 2πf``.

* 2-D PSD ``C(f_x, f_y)`` (m⁴): periodogram ``|DFT(w·(z − z̄))|² dx dy / (nx ny ⟨w²⟩)``, with
  window ``w``, so that ``Σ C Δf_x Δf_y`` is the variance R_rms² (Parseval, exact without a
  window). The radial average ``C(f)`` averages ``C`` over annuli of ``|f|``; then
  ``R_rms² ≈ ∫ C(f) 2πf df``. A self-affine surface of Hurst exponent H has
  ``C(f) ∝ f^−2(1+H)``.
* Profile PSD ``C₁(f)`` (m³): one-sided, averaged over all rows (x) and/or columns (y), so that
  ``Σ_{f>0} C₁ Δf`` is the profile variance; self-affine: ``C₁ ∝ f^−(1+2H)``.
* Band variance: the variance carried by the frequencies of a logarithmic band
  ``[f_k, f_k·10^(1/b))``, b bands per decade. For a self-affine surface it scales as ``f^−2H``
  for the 2-D and the profile spectrum alike; for the line spectrum of a Weierstrass–Mandelbrot
  surface it is the sum of the lines in the band, which keeps the same scaling when a band is at
  least as wide as the line spacing γ (10^(1/b) ≥ γ) and avoids the empty bins and spikes of a
  per-bin average.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import warp as wp

from ._support.results import fields_to_dict
from .kernels import reduce as _kr
from .spectra import (
    PSD,
    band_variance,
    periodogram,
    profile_psd,
    radial_psd,
    roll_off_wavelength,
)
from .surface import Surface

_MOMENT_LANES = 65536

__all__ = [
    "PSD",
    "Descriptors",
    "band_variance",
    "describe",
    "height_statistics",
    "periodogram",
    "profile_psd",
    "radial_psd",
    "roll_off_wavelength",
    "surface_statistics",
]


@dataclass(frozen=True)
class Descriptors:
    """Amplitude and spatial descriptors of one height map (Table 1 of the paper)."""

    Rt: float
    """Peak-to-valley height R_t = max z − min z (m)."""
    Rrms: float
    """Root-mean-square roughness R_rms = √⟨(z − z̄)²⟩ (m)."""
    Ra: float
    """Arithmetic mean roughness R_a = ⟨abs(z − z̄)⟩ (m)."""
    skewness: float
    """Skewness R_sk = ⟨(z − z̄)³⟩ / R_rms³ (dimensionless)."""
    kurtosis: float
    """Kurtosis R_ku = ⟨(z − z̄)⁴⟩ / R_rms⁴ (dimensionless; 3 for a Gaussian)."""
    Wr: float
    """Roll-off wavelength W_r (m), see :func:`roll_off_wavelength`."""
    Wr_resolved: bool
    """False when W_r > min(Lx, Ly)/3: fewer than three roll-off wavelengths fit in the map and
    ``Wr`` is only a lower bound of the order of the map size."""
    mean: float
    """Mean height z̄ (m)."""

    def to_dict(self) -> dict[str, Any]:
        """Scalars with unit-suffixed keys (``Rt_m``, ``Rrms_m``, ...), JSON-serialisable.

        Returns
        -------
        dict
            Every field; ``Rt``, ``Rrms``, ``Ra``, ``Wr`` and ``mean`` (m) under the keys
            ``Rt_m``, ``Rrms_m``, ``Ra_m``, ``Wr_m``, ``mean_m``; ``Wr_resolved`` as a bool.
        """
        d = fields_to_dict(self, {k: f"{k}_m" for k in ("Rt", "Rrms", "Ra", "Wr", "mean")})
        return {**d, "Wr_resolved": bool(self.Wr_resolved)}


def height_statistics(z: np.ndarray) -> dict[str, float]:
    """R_t, R_rms, R_a, skewness, kurtosis and mean of a height array (float64, about the mean).

    Parameters
    ----------
    z : ndarray
        Heights (m), any shape; must be finite.

    Returns
    -------
    dict
        ``Rt``, ``Rrms``, ``Ra`` (m), ``skewness``, ``kurtosis`` (dimensionless), ``mean`` (m).
        Skewness and kurtosis are 0 and 3 by convention for a constant map.
    """
    z = np.asarray(z, dtype=np.float64).ravel()
    if z.size == 0 or not np.isfinite(z).all():
        raise ValueError("heights must be non-empty and finite")
    mean = float(z.mean())
    d = z - mean
    m2 = float(np.mean(d * d))
    rrms = math.sqrt(m2)
    if m2 > 0.0:
        skew = float(np.mean(d**3)) / m2**1.5
        kurt = float(np.mean(d**4)) / m2**2
    else:
        skew, kurt = 0.0, 3.0
    return {
        "Rt": float(z.max() - z.min()),
        "Rrms": rrms,
        "Ra": float(np.mean(np.abs(d))),
        "skewness": skew,
        "kurtosis": kurt,
        "mean": mean,
    }


def surface_statistics(surface: Surface) -> dict[str, float]:
    """:func:`height_statistics` of a surface, where it lives.

    A NumPy surface: :func:`height_statistics` of its heights. A device-resident surface: two
    Warp reductions on its device (float64 sum, then float64 central moments about the mean),
    R_t from its validation; no host copy of the map.

    Parameters
    ----------
    surface : Surface
        The height map (m), on the host or on a Warp device.

    Returns
    -------
    dict
        ``Rt``, ``Rrms``, ``Ra`` (m), ``skewness``, ``kurtosis`` (dimensionless), ``mean`` (m),
        as float. Skewness and kurtosis are 0 and 3 by convention for a constant map.
    """

    if surface.device is None:
        return height_statistics(surface.heights)

    z = surface.device_heights()
    dev = z.device
    n = surface.nx * surface.ny
    flat = z.flatten()
    lanes = min(_MOMENT_LANES, n)
    chunk = 0 if dev.is_cuda else -(-n // lanes)
    acc = wp.zeros(1, dtype=wp.float64, device=dev)
    wp.launch(_kr.sum_kernel, dim=lanes, inputs=[flat, lanes, chunk], outputs=[acc], device=dev)
    mean = float(acc.numpy()[0]) / n  # sync point
    mom = wp.zeros(4, dtype=wp.float64, device=dev)
    wp.launch(
        _kr.central_moments_kernel,
        dim=lanes,
        inputs=[flat, lanes, chunk, mean],
        outputs=[mom],
        device=dev,
    )
    a1, a2, a3, a4 = (float(v) / n for v in mom.numpy())  # sync point
    rrms = math.sqrt(a2)
    if a2 > 0.0:
        skew, kurt = a3 / a2**1.5, a4 / a2**2
    else:
        skew, kurt = 0.0, 3.0
    lo, hi = surface.extremes()
    return {
        "Rt": float(np.float64(hi) - np.float64(lo)),
        "Rrms": rrms,
        "Ra": a1,
        "skewness": skew,
        "kurtosis": kurt,
        "mean": mean,
    }


def describe(surface: Surface, *, smoothing: float = 0.05) -> Descriptors:
    """Descriptors of a surface: R_t, R_rms, R_a, skewness, kurtosis and W_r.

    Parameters
    ----------
    surface : Surface
        Height map (m). Statistics are about the mean height; level the map first
        (``warptrunc.io.level_plane``) when a tilt is not part of the roughness.
    smoothing : float
        Kernel width for W_r in decades (see :func:`roll_off_wavelength`).

    Returns
    -------
    Descriptors

    Raises
    ------
    ValueError
        For a map of fewer than 2 × 2 pixels (a single point or a profile): its spectra and
        W_r are not defined.
    """
    if min(surface.ny, surface.nx) < 2:
        what = (
            "a single point"
            if surface.ny * surface.nx == 1
            else (
                f"a profile of {surface.nx} points along x"
                if surface.ny == 1
                else f"a profile of {surface.ny} points along y"
            )
        )
        raise ValueError(
            f"describe needs a map of at least 2 × 2 pixels; this one is "
            f"{surface.ny}×{surface.nx}, {what}"
        )
    st = surface_statistics(surface)
    wr, resolved = roll_off_wavelength(surface, smoothing=smoothing)
    return Descriptors(
        Rt=st["Rt"],
        Rrms=st["Rrms"],
        Ra=st["Ra"],
        skewness=st["skewness"],
        kurtosis=st["kurtosis"],
        Wr=wr,
        Wr_resolved=resolved,
        mean=st["mean"],
    )
