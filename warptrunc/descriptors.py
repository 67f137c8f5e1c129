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

from ._validate import check_int, check_range
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

WINDOWS = ("hann", "none")


@dataclass(frozen=True)
class Descriptors:
    """Amplitude and spatial descriptors of one height map (Table 1 of the paper)."""

    Rt: float
    """Peak-to-valley height R_t = max z − min z (m)."""
    Rrms: float
    """Root-mean-square roughness R_rms = √⟨(z − z̄)²⟩ (m)."""
    Ra: float
    """Arithmetic mean roughness R_a = ⟨|z − z̄|⟩ (m)."""
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
        """Scalars with unit-suffixed keys (``Rt_m``, ``Rrms_m``, ...), JSON-serialisable."""
        return {
            "Rt_m": self.Rt,
            "Rrms_m": self.Rrms,
            "Ra_m": self.Ra,
            "skewness": self.skewness,
            "kurtosis": self.kurtosis,
            "Wr_m": self.Wr,
            "Wr_resolved": bool(self.Wr_resolved),
            "mean_m": self.mean,
        }


@dataclass(frozen=True, eq=False)
class PSD:
    """A power spectral density on a frequency axis."""

    frequency: np.ndarray
    """(k,) float64 spatial frequency f = 1/λ at the bin centres (1/m)."""
    psd: np.ndarray
    """(k,) float64 PSD: radial 2-D average C(f) (m⁴) or one-sided profile C₁(f) (m³)."""
    n_modes: np.ndarray
    """(k,) int64 number of Fourier modes averaged in each bin."""
    kind: str
    """``"radial"`` (2-D, m⁴) or ``"profile-x"``, ``"profile-y"``, ``"profile"`` (m³)."""

    def to_dict(self) -> dict[str, Any]:
        """Columns ``frequency_per_m``, ``psd``, ``n_modes`` and the ``kind``."""
        return {
            "frequency_per_m": self.frequency,
            "psd": self.psd,
            "n_modes": self.n_modes,
            "kind": self.kind,
        }


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
    """
    if surface.device is None:
        return height_statistics(surface.heights)
    import warp as wp

    from .kernels import reduce as _kr

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


def _array_module(surface: Surface):
    """(xp, z): the array module and the (ny, nx) heights to run the spectra with (module
    docstring: CuPy on the surface's CUDA device when available, else NumPy on a host view)."""
    dev = surface.device
    if dev is None:
        return np, surface.heights
    import warp as wp

    zd = surface.device_heights()
    if zd.device.is_cpu:
        return np, zd.numpy()  # a view of the device memory, no copy
    try:
        import cupy as cp
    except ImportError:
        return np, surface.heights  # the lazy host copy
    wp.synchronize_device(zd.device)  # CuPy works on its own stream
    with cp.cuda.Device(zd.device.ordinal):
        return cp, cp.asarray(zd)


def _cupy():
    import cupy

    return cupy


def _to_host(a):
    return a.get() if hasattr(a, "get") and not isinstance(a, np.ndarray) else a


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
    """
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


def _window(n: int, kind: str, xp=np) -> np.ndarray:
    if kind == "none":
        return xp.ones(n)
    # periodic Hann: tapers both edges of a non-periodic scan to zero
    return 0.5 - 0.5 * xp.cos(2.0 * np.pi * xp.arange(n) / n)


def periodogram(
    surface: Surface, *, window: str = "hann"
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The 2-D periodogram C(f_x, f_y) (m⁴) and its frequency grids (1/m).

    Parameters
    ----------
    surface : Surface
        Height map (m); the mean is subtracted.
    window : {"hann", "none"}
        Separable window applied before the FFT (``"hann"`` suppresses the leakage from the
        edges of a non-periodic scan); the result is divided by ⟨w²⟩.

    Returns
    -------
    C : (ny, nx) ndarray
        Periodogram in NumPy FFT order (m⁴); ``C.sum() Δf_x Δf_y`` is the (windowed) variance.
    fx, fy : (ny, nx) ndarray
        Frequencies of each entry (1/m).
    """
    c, fx, fy = _periodogram(surface, window)
    return _to_host(c), _to_host(fx), _to_host(fy)


def _periodogram(surface: Surface, window: str):
    """:func:`periodogram` where the surface lives (NumPy or CuPy arrays)."""
    if window not in WINDOWS:
        raise ValueError(f"window must be one of {WINDOWS}, got {window!r}")
    xp, z = _array_module(surface)
    z = xp.asarray(z, dtype=xp.float64)
    z = z - z.mean()
    ny, nx = z.shape
    w = xp.outer(_window(ny, window, xp), _window(nx, window, xp))
    f = xp.fft.fft2(z * w)
    c = (f.real**2 + f.imag**2) * surface.dx * surface.dy / (nx * ny * float(xp.mean(w * w)))
    fy, fx = xp.meshgrid(
        xp.fft.fftfreq(ny, surface.dy), xp.fft.fftfreq(nx, surface.dx), indexing="ij"
    )
    return c, fx, fy


def radial_psd(surface: Surface, *, window: str = "hann") -> PSD:
    """Radially averaged 2-D PSD C(f) (m⁴), averaged over annuli of width min(Δf_x, Δf_y).

    Bins run from the first non-zero frequency to the smaller Nyquist frequency; the DC term is
    left out. With ``window="none"``, ``Σ C(f_k) n_k Δf_x Δf_y`` over all bins plus the corners
    beyond the Nyquist circle is the variance.

    Returns
    -------
    PSD
        ``kind="radial"``.
    """
    c, fx, fy = _periodogram(surface, window)
    xp = np if isinstance(c, np.ndarray) else _cupy()
    fr = xp.hypot(fx, fy).ravel()
    df = min(1.0 / surface.lx, 1.0 / surface.ly)
    fmax = min(0.5 / surface.dx, 0.5 / surface.dy)
    nb = int(fmax / df)
    idx = xp.floor(fr / df + 0.5).astype(xp.int64)  # bin k holds |f| in [(k−½)Δf, (k+½)Δf)
    keep = (idx >= 1) & (idx <= nb)
    counts = _to_host(xp.bincount(idx[keep], minlength=nb + 1))[1:]
    sums = _to_host(xp.bincount(idx[keep], weights=c.ravel()[keep], minlength=nb + 1))[1:]
    ok = counts > 0
    freq = (np.arange(1, nb + 1) * df)[ok]
    return PSD(freq, sums[ok] / counts[ok], counts[ok].astype(np.int64), "radial")


def profile_psd(surface: Surface, *, axis: str = "both", window: str = "hann") -> PSD:
    """One-sided profile PSD C₁(f) (m³), averaged over all profiles along ``axis``.

    Parameters
    ----------
    surface : Surface
        Height map (m); each profile's mean is subtracted.
    axis : {"x", "y", "both"}
        Profiles along x (rows), along y (columns), or both averaged (requires dx = dy, else
        the two frequency axes differ).
    window : {"hann", "none"}
        Window applied to each profile.

    Returns
    -------
    PSD
        Frequencies k/L for k = 1 … n/2 (1/m); ``Σ C₁ Δf`` is the mean profile variance
        (exactly, without a window).
    """
    if axis not in ("x", "y", "both"):
        raise ValueError(f"axis must be 'x', 'y' or 'both', got {axis!r}")
    if window not in WINDOWS:
        raise ValueError(f"window must be one of {WINDOWS}, got {window!r}")
    if axis == "both" and not math.isclose(surface.dx, surface.dy, rel_tol=1e-9):
        raise ValueError(
            f"axis='both' needs square pixels, got dx={surface.dx!r}, dy={surface.dy!r}; "
            "use axis='x' or 'y'"
        )
    xp, z = _array_module(surface)
    z = xp.asarray(z, dtype=xp.float64)
    parts = []
    for ax in ("x", "y") if axis == "both" else (axis,):
        prof = z if ax == "x" else z.T
        h = surface.dx if ax == "x" else surface.dy
        n = prof.shape[1]
        w = _window(n, window, xp)
        p = prof - prof.mean(axis=1, keepdims=True)
        f = xp.fft.rfft(p * w, axis=1)
        c = _to_host((f.real**2 + f.imag**2).mean(axis=0)) * h / (n * float(xp.mean(w * w)))
        del f, p
        c[1:] *= 2.0  # one-sided
        if n % 2 == 0:
            c[-1] /= 2.0  # the Nyquist term has no negative twin
        parts.append((np.fft.rfftfreq(n, h)[1:], c[1:], prof.shape[0]))
    if len(parts) == 2 and parts[0][0].size != parts[1][0].size:
        raise ValueError(
            f"axis='both' needs a square map, got (ny, nx) = {surface.shape}; use axis='x' or 'y'"
        )
    freq = parts[0][0]
    psd = sum(p[1] * p[2] for p in parts) / sum(p[2] for p in parts)
    n_modes = np.full(freq.size, sum(p[2] for p in parts), dtype=np.int64)
    kind = "profile" if axis == "both" else f"profile-{axis}"
    return PSD(freq, psd, n_modes, kind)


def band_variance(
    surface: Surface,
    *,
    kind: str = "radial",
    bins_per_decade: int = 5,
    window: str = "hann",
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Variance carried by logarithmic frequency bands (m²).

    Parameters
    ----------
    surface : Surface
        Height map (m).
    kind : {"radial", "profile"}
        From the 2-D periodogram (annuli) or from the profile PSD (both directions when the
        pixels and the map are square, else along x).
    bins_per_decade : int
        Bands per decade b; band k is ``[f₀·10^(k/b), f₀·10^((k+1)/b))`` with f₀ the lowest
        non-zero frequency.
    window : {"hann", "none"}
        Window of the periodogram.

    Returns
    -------
    f_center : (k,) ndarray
        Geometric band centres (1/m), only bands holding at least one mode.
    variance : (k,) ndarray
        Variance in each band (m²).
    n_modes : (k,) ndarray
        Fourier modes (2-D) or profile frequencies in each band.
    """
    b = check_int("bins_per_decade", bins_per_decade, 1, 100)
    if kind == "radial":
        c, fx, fy = _periodogram(surface, window)
        xp = np if isinstance(c, np.ndarray) else _cupy()
        fr = xp.hypot(fx, fy).ravel()
        w = c.ravel() / (surface.lx * surface.ly)  # C Δf_x Δf_y
        f0 = min(1.0 / surface.lx, 1.0 / surface.ly)
        fmax = min(0.5 / surface.dx, 0.5 / surface.dy)
    elif kind == "profile":
        sq = math.isclose(surface.dx, surface.dy, rel_tol=1e-9) and surface.nx == surface.ny
        p = profile_psd(surface, axis="both" if sq else "x", window=window)
        fr = p.frequency
        w = p.psd * (p.frequency[0])  # C₁ Δf
        f0 = p.frequency[0]
        fmax = p.frequency[-1]
        xp = np
    else:
        raise ValueError(f"kind must be 'radial' or 'profile', got {kind!r}")
    keep = (fr > 0) & (fr <= fmax * (1 + 1e-12))
    k = xp.floor(xp.log10(fr[keep] / f0) * b + 1e-9).astype(xp.int64)
    nb = int(k.max()) + 1
    var = _to_host(xp.bincount(k, weights=w[keep], minlength=nb))
    cnt = _to_host(xp.bincount(k, minlength=nb))
    ok = cnt > 0
    centres = f0 * 10 ** ((np.arange(nb) + 0.5) / b)
    return centres[ok], var[ok], cnt[ok].astype(np.int64)


def roll_off_wavelength(
    surface: Surface, *, smoothing: float = 0.05, window: str = "hann"
) -> tuple[float, bool]:
    """Roll-off wavelength W_r: the wavelength carrying the most variance per log-frequency.

    Parameters
    ----------
    surface : Surface
        Height map (m).
    smoothing : float
        Width σ of the Gaussian kernel in log₁₀ f (decades) that smooths the variance density.
    window : {"hann", "none"}
        Window of the periodogram.

    Returns
    -------
    Wr : float
        W_r (m).
    resolved : bool
        False when W_r > min(Lx, Ly)/3: the map holds fewer than three roll-off wavelengths,
        the spectrum may simply rise to its lowest frequencies (whose few modes scatter
        strongly), and ``Wr`` is only a lower bound of the order of the map size.

    Notes
    -----
    The paper estimates W_r as the average distance between asperities. Here that distance is
    read from the spectrum: the variance carried per unit of log f rises as f² below the
    roll-off (flat PSD) and falls as f^−2H above it, so its maximum marks the roll-off, the
    wavelength of the dominant (largest) asperities; for a Weierstrass–Mandelbrot surface it is
    the n = 0 line at f = 1/W_r. The density is a kernel estimate: every Fourier mode adds its
    power at log₁₀|f| (radial frequency, up to 1/(4·max(dx, dy))), smoothed with a Gaussian of
    width ``smoothing``; each WM line is then counted once however narrow it is, and lines
    γ = 1.5 apart (0.18 decade) stay separate.

    Accuracy, measured on 256² maps: within 1 % for WM surfaces with W_r ≤ L/8 and within
    −20 % for random-phase surfaces with a roll-off at W_r ≤ L/8; when the map holds only a few
    roll-off wavelengths (W_r ≈ L/3) the window's main lobe biases W_r low by up to 40 %.
    """
    sig = check_range("smoothing", smoothing, 0.0, 1.0, unit="decades")
    c, fx, fy = _periodogram(surface, window)
    xp = np if isinstance(c, np.ndarray) else _cupy()
    f = xp.hypot(fx, fy).ravel()
    p = c.ravel()
    f0 = min(1.0 / surface.lx, 1.0 / surface.ly)
    fmax = 1.0 / (4.0 * max(surface.dx, surface.dy))
    keep = (f > 0) & (f <= fmax)
    res = 200  # histogram bins per decade before smoothing
    x = xp.log10(f[keep] / f0)
    nb = max(1, math.ceil(math.log10(max(fmax / f0, 1.0)) * res) + 1)
    idx = xp.minimum((x * res + 0.5).astype(xp.int64), nb - 1)
    hist = _to_host(xp.bincount(idx, weights=p[keep], minlength=nb))
    half = int(4 * sig * res)
    k = np.arange(-half, half + 1)
    kernel = np.exp(-0.5 * (k / (sig * res)) ** 2)
    dens = np.convolve(np.pad(hist, (half, half)), kernel, mode="valid")
    wr = 1.0 / (f0 * 10 ** (int(np.argmax(dens)) / res))
    return float(wr), bool(wr <= min(surface.lx, surface.ly) / 3.0)
