# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Self-affine random surfaces from a power spectrum (Fourier synthesis), beside WM.

:class:`SelfAffineSpec` declares the surface: Hurst exponent H, the roll-off, long and short
cut-off wavelengths (m), the side L (m), the pixels n, and the normalisation (rms height or rms
slope); :func:`self_affine_surface` generates it as a periodic :class:`~warptrunc.Surface`. The
isotropic power spectral density is

    C(q) = C₀                      for q_L ≤ q < q_r,
    C(q) = C₀ (q/q_r)^(−2(1+H))    for q_r ≤ q ≤ q_s,   and 0 otherwise,

with q = 2π/λ for each wavelength, in the convention ⟨h²⟩ = ∫ C(q) d²q (Persson's). On the grid
the modes are q = 2π(mx/Lx, my/Ly); each has the deterministic amplitude √(C(q))·2π/√(Lx·Ly)
and a random phase, so the map's discrete power spectrum equals C(q) at every mode and its rms
height and rms slope equal the discrete sums Σ C(q)Δq² and Σ q²C(q)Δq² to round-off. C₀ is
fixed by those sums: the requested rms height (or rms slope) is the map's, exactly.

Phases are drawn by Warp's counter-based generator (PCG) from the seed and each mode's integer
wavenumbers (``warptrunc.kernels.selfaffine``), not from a host array: the same seed gives the
same phases on every device, and a grid with more pixels over the same L draws the same phase
for every mode the coarser grid holds. With the short cut-off given as a length, the content of
the surface is fixed and a finer grid samples the same surface (to the FFT's round-off); with
``short_cutoff=None`` the content runs to 2 pixels of whatever grid is used, and grows with it.
The map is generated whole on the device (the inverse FFT: scipy on the CPU, CuPy's cuFFT on a
CUDA device, else scipy on the host), float64 there, float32 heights in the result.

References
----------
Persson, B. N. J., Albohr, O., Tartaglino, U., Volokitin, A. I. & Tosatti, E. (2005). On the
nature of surface roughness with application to contact mechanics, sealing, rubber friction
and adhesion. J. Phys.: Condens. Matter 17, R1. doi:10.1088/0953-8984/17/1/R01.
Jacobs, T. D. B., Junge, T. & Pastewka, L. (2017). Quantitative characterization of surface
topography using spectral analysis. Surf. Topogr.: Metrol. Prop. 5, 013001.
doi:10.1088/2051-672X/aa51f8.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .params import Parameters, check_fields, param

__all__ = ["SelfAffineSpec", "self_affine_surface"]


@dataclass(frozen=True)
class SelfAffineSpec(Parameters):
    """The parameters of a self-affine, isotropic, periodic random surface (SI units).

    Exactly one of ``rms_height`` and ``rms_slope`` sets the vertical scale; with neither,
    ``rms_height`` is 1 µm.

    Raises
    ------
    ValueError
        A field out of its range, both normalisations given, or cut-offs out of order
        (long > roll-off > short, the short one at least 2 pixels).

    Examples
    --------
    >>> SelfAffineSpec(hurst=0.8, L=100e-6, n=512, short_cutoff=4 * 100e-6 / 512, rms_slope=1.0).hurst
    0.8
    """

    hurst: float = param(0.8, "Hurst exponent H (D = 3 − H)", gt=0.0, le=1.0)
    L: float | tuple[float, float] = param(
        1e-3, "side length L, or Lx Ly (the period)", unit="m", gt=0.0, pair=True, sweep=False
    )
    n: int | tuple[int, int] = param(
        1024, "pixels per side, or nx ny", kind="int", ge=8, le=1 << 20, pair=True, sweep=False
    )
    rolloff: float | None = param(
        None,
        "roll-off wavelength λ_r: C(q) flat above it; none = no roll-off",
        unit="m",
        gt=0.0,
        optional=True,
    )
    long_cutoff: float | None = param(
        None,
        "long cut-off wavelength λ_L: no content above it; none = the side L",
        unit="m",
        gt=0.0,
        optional=True,
    )
    short_cutoff: float | None = param(
        None,
        "short cut-off wavelength λ_s: no content below it; none = 2 pixels of the grid",
        unit="m",
        gt=0.0,
        optional=True,
    )
    rms_height: float | None = param(
        None,
        "rms height h_rms the map has; none = 1 µm unless rms_slope is given",
        unit="m",
        gt=0.0,
        optional=True,
    )
    rms_slope: float | None = param(
        None, "rms slope h′_rms the map has (instead of rms_height)", gt=0.0, optional=True
    )
    seed: int = param(0, "seed of the random phases", kind="int", ge=0, le=2**32 - 1, sweep=False)

    def __post_init__(self) -> None:
        check_fields(self)
        if self.rms_height is not None and self.rms_slope is not None:
            raise ValueError("give rms_height or rms_slope, not both")
        g = self.grid()
        if not g["q_long"] < g["q_short"]:
            raise ValueError(
                f"long_cutoff ({2 * math.pi / g['q_long']:g} m) must exceed short_cutoff "
                f"({2 * math.pi / g['q_short']:g} m)"
            )
        if self.rolloff is not None and not g["q_long"] <= g["q_roll"] <= g["q_short"]:
            raise ValueError(
                f"rolloff = {self.rolloff:g} m must lie between the cut-offs "
                f"({2 * math.pi / g['q_short']:g} m and {2 * math.pi / g['q_long']:g} m)"
            )
        nyquist = 2.0 * max(g["dx"], g["dy"])
        if self.short_cutoff is not None and self.short_cutoff < nyquist * (1 - 1e-12):
            raise ValueError(
                f"short_cutoff = {self.short_cutoff:g} m is below 2 pixels ({nyquist:g} m): the "
                "grid cannot hold that content; use more pixels or a longer short_cutoff"
            )

    def grid(self) -> dict[str, Any]:
        """The grid and the cut-offs as wavevectors.

        Returns
        -------
        dict
            ``Lx``, ``Ly``, ``dx``, ``dy`` (m), ``nx``, ``ny``, and ``q_long``, ``q_roll``,
            ``q_short`` (rad/m): the roll-off at ``q_long`` when there is none.
        """
        lx, ly = self.L if isinstance(self.L, tuple) else (self.L, self.L)
        nx, ny = self.n if isinstance(self.n, tuple) else (self.n, self.n)
        dx, dy = lx / nx, ly / ny
        short = self.short_cutoff if self.short_cutoff is not None else 2.0 * max(dx, dy)
        long_ = self.long_cutoff if self.long_cutoff is not None else max(lx, ly)
        q_long, q_short = 2 * math.pi / long_, 2 * math.pi / short
        q_roll = 2 * math.pi / self.rolloff if self.rolloff is not None else q_long
        return {
            "Lx": lx,
            "Ly": ly,
            "nx": nx,
            "ny": ny,
            "dx": dx,
            "dy": dy,
            "q_long": q_long,
            "q_roll": q_roll,
            "q_short": q_short,
        }

    def psd(self, q: Any, c0: float) -> np.ndarray:
        """C(q) (m⁴) at wavevectors ``q`` (rad/m) for the prefactor ``c0`` (m⁴).

        Parameters
        ----------
        q : array_like
            Wavevector magnitudes (rad/m).
        c0 : float
            C₀, the plateau below the roll-off (m⁴): ``Surface.params["C0_m4"]`` of a map.

        Returns
        -------
        ndarray
            C(q) (m⁴), 0 outside [q_L, q_s] (a q on a cut-off to 10⁻⁹, relative, is inside, as
            the generator has it).
        """
        g = self.grid()
        q = np.asarray(q, dtype=np.float64)
        with np.errstate(divide="ignore"):  # q = 0 lies outside the band
            power = (q / g["q_roll"]) ** (-2.0 * (1.0 + self.hurst))
        c = np.where(q < g["q_roll"], 1.0, power)
        inside = (q >= g["q_long"] * (1 - 1e-9)) & (q <= g["q_short"] * (1 + 1e-9)) & (q > 0)
        return np.where(inside, c0 * c, 0.0)


def self_affine_surface(spec: SelfAffineSpec | None = None, *, device: Any = None) -> Any:
    """Generate a self-affine periodic surface (:class:`SelfAffineSpec`) on ``device``.

    Parameters
    ----------
    spec : SelfAffineSpec, optional
        The parameters; ``SelfAffineSpec()`` when None.
    device : str or warp.context.Device, optional
        Warp device; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    Surface
        The (ny, nx) map (m), float32 heights with zero mean, device-resident; ``params`` hold
        ``generator="self-affine"``, the spec's fields, ``C0_m4`` (C₀, m⁴), ``h_rms_m``,
        ``slope_rms`` and ``curvature_rms_per_m`` (the discrete sums of the spectrum, which the map
        has to round-off; the last the rms Laplacian, 1/m) and
        ``q_long``, ``q_roll``, ``q_short`` (rad/m).

    Raises
    ------
    ValueError
        A spectrum with no mode between the cut-offs on this grid.
    MemoryError
        The map and its spectrum would not fit the device.
    """
    import warp as wp

    from ._support.device import resolve_device
    from .kernels import selfaffine as _k
    from .surface import Surface

    spec = SelfAffineSpec() if spec is None else spec
    dev = resolve_device(device)
    g = spec.grid()
    nx, ny = g["nx"], g["ny"]
    geo = [
        nx,
        ny,
        float(g["Lx"]),
        float(g["Ly"]),
        float(spec.hurst),
        float(g["q_roll"]),
        float(g["q_long"]),
        float(g["q_short"]),
    ]
    sums = wp.zeros((ny, 3), dtype=wp.float64, device=dev)
    wp.launch(_k.mode_sums_kernel, dim=ny, inputs=geo, outputs=[sums], device=dev)
    s0, s2, s4 = (float(v) for v in sums.numpy().sum(axis=0))  # sync point
    if not s0 > 0:
        raise ValueError(
            f"no mode of the {nx}×{ny} grid lies between the cut-offs "
            f"({2 * math.pi / g['q_short']:g} m to {2 * math.pi / g['q_long']:g} m)"
        )
    if spec.rms_slope is not None:
        s = spec.rms_slope / math.sqrt(s2)
    else:
        s = (1e-6 if spec.rms_height is None else spec.rms_height) / math.sqrt(s0)
    spectrum = wp.empty((ny, nx // 2 + 1), dtype=wp.vec2d, device=dev)
    key = int(np.random.SeedSequence(spec.seed).generate_state(1, dtype=np.uint32)[0] >> 1)
    wp.launch(
        _k.fill_spectrum_kernel,
        dim=spectrum.shape,
        inputs=[*geo, float(nx * ny * s), key],
        outputs=[spectrum],
        device=dev,
    )
    z = wp.empty((ny, nx), dtype=wp.float32, device=dev)
    h = _inverse_real_fft(spectrum, (ny, nx), dev)
    wp.launch(_k.to_float32_kernel, dim=z.shape, inputs=[h], outputs=[z], device=dev)
    del spectrum, h
    c0 = s**2 * g["Lx"] * g["Ly"] / (2 * math.pi) ** 2
    params = {
        "generator": "self-affine",
        **spec.to_dict(),
        "C0_m4": c0,
        "h_rms_m": s * math.sqrt(s0),
        "slope_rms": s * math.sqrt(s2),
        "curvature_rms_per_m": s * math.sqrt(s4),
        **{k: g[k] for k in ("q_long", "q_roll", "q_short")},
    }
    return Surface(z, g["dx"], g["dy"], params)


def _inverse_real_fft(spectrum: Any, shape: tuple[int, int], dev: Any) -> Any:
    """The (ny, nx) float64 Warp array irfft2 of the half spectrum, on ``dev``."""
    import warp as wp

    if dev.is_cuda:
        try:
            import cupy as cp
        except ImportError:
            cp = None
        if cp is not None:
            wp.synchronize_device(dev)
            with cp.cuda.Device(dev.ordinal):
                c = cp.asarray(spectrum).view(cp.complex128)[..., 0]
                h = cp.fft.irfft2(c, s=shape)
                cp.cuda.get_current_stream().synchronize()
                out = wp.array(h, dtype=wp.float64, device=dev)  # copies from CuPy's memory
            return out
    from scipy import fft

    c = spectrum.numpy().view(np.complex128)[..., 0]  # sync point
    return wp.array(fft.irfft2(c, s=shape, workers=-1), dtype=wp.float64, device=dev)
