# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Power spectra of a height map: periodogram, radial and profile PSD, band variances, roll-off W_r.

Moved verbatim from :mod:`warptrunc.descriptors` (conventions there); every name is still
importable from ``warptrunc.descriptors``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import warp as wp

from ._support.results import fields_to_dict
from ._support.validate import check_int, check_range
from .surface import Surface

__all__ = [
    "PSD",
    "WINDOWS",
    "band_variance",
    "periodogram",
    "profile_psd",
    "radial_psd",
    "roll_off_wavelength",
]


WINDOWS = ("hann", "none")


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
        """Columns ``frequency_per_m``, ``psd``, ``n_modes`` and the ``kind``.

        Returns
        -------
        dict
            ``frequency_per_m`` (k,) (1/m), ``psd`` (k,) (m⁴ radial, m³ profile), ``n_modes``
            (k,) and ``kind`` (str).
        """
        return fields_to_dict(self, {"frequency": "frequency_per_m"})


def _array_module(surface: Surface):
    """(xp, z): the array module and the (ny, nx) heights to run the spectra with (module
    docstring: CuPy on the surface's CUDA device when available, else NumPy on a host view)."""
    dev = surface.device
    if dev is None:
        return np, surface.heights

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


def _window(n: int, kind: str, xp=np) -> np.ndarray:
    if kind == "none" or n < 3:  # fewer than 3 samples cannot be tapered (Hann of 1 is [0])
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

    Parameters
    ----------
    surface : Surface
        Height map (m); its mean is subtracted. A surface on a CUDA device is transformed
        there with CuPy when it is available.
    window : {"hann", "none"}
        2-D window (outer product of 1-D windows) applied before the FFT; the PSD is divided
        by its mean square.

    Returns
    -------
    PSD
        ``kind="radial"``: bin centres k·Δf, Δf = min(1/Lx, 1/Ly) (1/m), for the bins that hold
        at least one mode, C(f) (m⁴) and the number of modes per bin.

    Raises
    ------
    ValueError
        ``window`` is not one of :data:`WINDOWS`.
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
