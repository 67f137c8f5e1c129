# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The whole truncation analysis of one surface, as ``warptrunc analyze`` runs it.

:func:`analyze` truncates a surface (a map in memory, or a WM surface generated whole or by
row bands), turns the curve into stiffness and load by Eq. 2, fits the power law k ∝ F^α over
the fit range and, for a map in memory, repeats the fit with the island-resolved model (one
flat punch per island, :func:`warptrunc.stiffness.island_stiffness_curve`). The result,
:class:`Analysis`, holds every curve and fit and the record that ``analyze`` writes as
``fit.json`` (:meth:`Analysis.summary`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import warp as wp

from ._support.device import resolve_device
from .material import Material
from .plausibility import PlausibilityWarning, check_fit, check_fit_depth, fit_error_text
from .robust import auto_fit_range, clip_to_percentiles
from .stiffness import (
    DEFAULT_MIN_PIXELS,
    PowerLawFit,
    StiffnessCurve,
    fit_power_law,
    island_stiffness_curve,
    stiffness_curve,
)
from .surface import Surface
from .truncation.api import truncate
from .truncation.curve import TruncationCurve
from .truncation.stream import as_wm_spec, banded_truncation, fits_in_memory
from .wm import surface_from_spec
from .wm_params import WMSpec, WMTerms

__all__ = ["ISLAND_MODEL", "TOO_BIG", "Analysis", "FitRangeError", "analyze"]

ISLAND_MODEL = "k = β'(2/√π)E*·Σ_i √A_i, one flat punch per island"
"""How ``fit.json`` names the island-resolved model."""
TOO_BIG = "the map needs more than half of the free memory"
"""Why a WM surface was streamed when streaming was not asked for."""
STREAM_GIVEN = "--stream given"
"""Why a WM surface was streamed when ``stream=True`` (``warptrunc analyze --stream``)."""


class FitRangeError(ValueError):
    """The fit range of Eq. 2's fit holds fewer than 3 increments.

    Parameters
    ----------
    message : str
        The fit's error message.
    surface : Surface or None
        The surface that was truncated (after clipping), to advise a fit range that works on
        it; None for a streamed surface.
    """

    def __init__(self, message: str, surface: Surface | None):
        super().__init__(message)
        self.surface = surface


@dataclass(frozen=True)
class Analysis:
    """Truncation curve, Eq. 2's stiffness and its power-law fit, optionally island-resolved."""

    curve: TruncationCurve
    """Truncated area A_c(ω) at every depth."""
    stiffness: StiffnessCurve
    """Stiffness k (N/m) and load F (N) of Eq. 2 at every depth."""
    fit: PowerLawFit
    """Power-law fit of E_c/E against F/(E·A) over the fit range."""
    islands: StiffnessCurve | None
    """The island-resolved model on the same depths; None when off or streamed."""
    islands_fit: PowerLawFit | None
    """Its fit over the same range; None when off, streamed or empty."""
    material: Material
    """Elastic constants of the rough body and the counter-body."""
    surface: dict[str, Any]
    """Scalar metadata of the surface (:meth:`warptrunc.Surface.to_dict`): grid (pixels, m),
    ``Rt_m`` (m), generation and reading parameters."""
    path: dict[str, Any]
    """``{"path": "in-memory"}``, or ``{"path": "streamed", "streaming": {"band_rows",
    "n_bands", "reason"}}`` (rows, count, text)."""
    connectivity: int
    """Island neighbourhood of the island-resolved model (4 or 8)."""
    warnings: tuple[PlausibilityWarning, ...] = ()
    """Plausibility warnings of the fits (:mod:`warptrunc.plausibility`): a fit not worth
    reading, a fit range past § 4.3's validity depth."""
    fit_range: dict[str, Any] | None = None
    """The fit-range rule used: ``{"rule": "legacy"}`` or the automatic rule's record
    (:func:`warptrunc.robust.auto_fit_range`)."""
    indicators: Any = None
    """§ 4.3's indicators (:class:`warptrunc.Indicators`) of the map when computed, else None."""
    fit_error: str | None = None
    """Why Eq. 2's fit is not worth reading, or None."""
    islands_fit_error: str | None = None
    """Why the island-resolved fit is not worth reading, or None."""

    def to_dict(self) -> dict[str, np.ndarray]:
        """The curve's columns, one row per depth, as ``analyze`` writes ``curve.csv``.

        Returns
        -------
        dict of str to (n+1,) ndarray
            :meth:`StiffnessCurve.to_dict` of :attr:`stiffness`, then (with the island model)
            ``stiffness_islands_N_per_m`` (N/m), ``load_islands_N`` (N), ``Ec_over_E_islands``
            (E_c/E, E the Young's modulus) and ``Ec_over_Estar_islands`` (E_c/E*), dimensionless.
        """
        cols = self.stiffness.to_dict()
        if self.islands is not None:
            cols["stiffness_islands_N_per_m"] = self.islands.stiffness
            cols["load_islands_N"] = self.islands.load
            cols["Ec_over_E_islands"] = self.islands.Ec_over_E
            cols["Ec_over_Estar_islands"] = self.islands.Ec_over_Estar
        return cols

    def summary(self) -> dict[str, Any]:
        """The fit and its provenance, as ``analyze`` writes ``fit.json``.

        Returns
        -------
        dict
            :meth:`PowerLawFit.to_dict` of :attr:`fit`, ``surface``, ``material`` (its
            fields; ``E_i`` inf is a rigid flat), the :attr:`path` entries and ``islands``:
            the island-resolved fit with ``model``, ``connectivity`` and ``fit_error``, or
            None; ``fit_range`` (the rule), ``fit_error``, ``applicable_depth`` (§ 4.3's
            indicators or None) and ``warnings`` (list of dicts).
        """
        info = {**self.fit.to_dict(), "surface": self.surface,
                "material": self.material.__dict__, **self.path}  # fmt: skip
        info["fit_range"] = self.fit_range or {"rule": "legacy"}
        info["fit_error"] = self.fit_error
        info["islands"] = None if self.islands_fit is None else {
            **self.islands_fit.to_dict(), "model": ISLAND_MODEL,
            "connectivity": self.connectivity, "fit_error": self.islands_fit_error,
        }  # fmt: skip
        info["applicable_depth"] = None if self.indicators is None else self.indicators.to_dict()
        info["warnings"] = [w.to_dict() for w in self.warnings]
        return info


def analyze(
    source: Surface | WMSpec | WMTerms | Mapping,
    n_increments: int = 200,
    *,
    max_depth: float | None = None,
    max_depth_fraction: float = 0.1,
    material: Material | None = None,
    beta_prime: float = 1.0,
    min_pixels: int = DEFAULT_MIN_PIXELS,
    depth_window: tuple[float, float] | None = None,
    rt_percentile: tuple[float, float] | None = None,
    islands: bool | None = None,
    connectivity: int = 4,
    stream: bool | Literal["auto"] = "auto",
    band_rows: int | None = None,
    fit_range: Literal["auto", "legacy"] = "auto",
    progress: bool = True,
    device: wp.DeviceLike = None,
) -> Analysis:
    """Truncate a surface, compute Eq. 2's stiffness and load, and fit k ∝ F^α.

    Parameters
    ----------
    source : Surface, WMSpec, WMTerms or mapping
        The height map (m), or a WM surface to generate (as :func:`warptrunc.truncate`
        takes it).
    n_increments : int
        Number of depth increments n.
    max_depth : float, optional
        Largest depth ω_max (m); overrides ``max_depth_fraction``.
    max_depth_fraction : float
        ω_max as a fraction of R_t (dimensionless).
    material : Material, optional
        Elastic constants; ``Material()`` (the default alloy on a rigid flat) when None.
    beta_prime : float
        Geometric factor β′ of Eq. 2 (dimensionless).
    min_pixels : int
        Fit only increments with at least this many contact pixels (pixels).
    depth_window : (float, float), optional
        Fit only depths LO ≤ ω ≤ HI (m).
    rt_percentile : (float, float), optional
        Clip the heights to these percentiles first (%, :func:`warptrunc.robust.clip_to_percentiles`);
        the map must be in memory.
    islands : bool, optional
        Also the island-resolved model; None: on for a map in memory, off when streamed.
    connectivity : {4, 8}
        Island neighbourhood of the island-resolved model.
    stream : {"auto", True, False}
        For a WM surface: generate it by row bands (True), whole (False), or by bands only
        when the map needs more than half of the free memory ("auto"). A :class:`Surface` is
        always in memory (True raises).
    band_rows : int, optional
        Rows per band when streaming.
    fit_range : {"auto", "legacy"}
        ``"legacy"``: increments to ω_max with ≥ ``min_pixels`` contact pixels. ``"auto"``: the
        same, and for a :class:`Surface` (a map read from a file) whose legacy fit is not worth
        reading (:func:`warptrunc.plausibility.check_fit`) with no range of the caller's own
        (``max_depth``, ``depth_window``, ``rt_percentile``), the range stated in contact
        pixels of :func:`warptrunc.robust.auto_fit_range`, kept when its fit is worth reading.
    progress : bool
        Show a progress bar over the bands of each streamed pass.
    device : str, optional
        Warp device; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    Analysis
        The curves, the fits and the surface's metadata.

    Raises
    ------
    FitRangeError
        The fit range of Eq. 2's fit holds fewer than 3 increments.
    ValueError
        ``stream=True`` with a :class:`Surface`, ``islands`` or ``rt_percentile`` with a
        streamed surface, or parameters out of range.
    """
    material = Material() if material is None else material
    if fit_range not in ("auto", "legacy"):
        raise ValueError(f"fit_range must be 'auto' or 'legacy', got {fit_range!r}")
    curve, surface, meta, path = _truncation(
        source, n_increments, max_depth=max_depth, max_depth_fraction=max_depth_fraction,
        rt_percentile=rt_percentile, islands=islands, stream=stream, band_rows=band_rows,
        progress=progress, device=device,
    )  # fmt: skip
    read_map = isinstance(source, Surface)
    sc = stiffness_curve(curve, material, beta_prime=beta_prime)
    found: list = []
    try:
        fit = fit_power_law(sc, min_pixels=min_pixels, depth_window=depth_window)
        found = check_fit(fit, sc)
    except ValueError as exc:
        fit, error = None, exc
    want_islands = surface is not None and islands is not False
    indicators = _validity(surface, read_map, connectivity, device) if want_islands else None
    if fit is not None and indicators is not None:
        found += check_fit_depth(fit, indicators)
    rule: dict[str, Any] = {"rule": "legacy"}
    auto_ok = (fit_range == "auto" and read_map and surface is not None and depth_window is None
               and max_depth is None and rt_percentile is None)  # fmt: skip
    if (fit is None or found) and auto_ok:
        auto = _auto_range(surface, material, n_increments, beta_prime, min_pixels, read_map,
                           connectivity, want_islands, device)  # fmt: skip
        if auto is not None:
            surface, max_depth, curve, sc, fit, found, indicators, rule = auto
            meta = surface.to_dict()
    if fit is None:
        raise FitRangeError(str(error), surface) from None
    isl = isl_fit = None
    isl_found: list = []
    if want_islands:
        isl, isl_fit = _islands(
            surface, curve, material, n_increments, max_depth=max_depth,
            max_depth_fraction=max_depth_fraction, beta_prime=beta_prime,
            min_pixels=min_pixels, depth_window=depth_window, connectivity=connectivity,
            device=device,
        )  # fmt: skip
        if isl_fit is not None:
            isl_found = check_fit(isl_fit, isl, label="islands fit")
            if indicators is not None:
                isl_found += check_fit_depth(isl_fit, indicators, label="islands fit")
    return Analysis(
        curve, sc, fit, isl, isl_fit, material, meta, path, connectivity,
        warnings=tuple(found + isl_found), fit_range=rule, indicators=indicators,
        fit_error=fit_error_text(found), islands_fit_error=fit_error_text(isl_found),
    )  # fmt: skip


#: Depth grid of the island counts that locate the maximum growth rate (§ 4.3, Table 2).
VALIDITY_INCREMENTS, VALIDITY_DEPTH_FRACTION = 100, 0.5


def _validity(surface: Surface, read_map: bool, connectivity: int, device):
    """§ 4.3's indicators (maximum growth rate of the island count) of the map: island counts
    at 100 depths to 0.5·R_t for a generated surface, to the median height (half of the
    pixels in contact) for a map read from a file, whose R_t a spike or a pit can set; None
    when that depth is not positive."""
    from .islands.depths import island_curve
    from .islands.fits import applicable_depth

    max_depth = None
    if read_map:
        z = np.asarray(surface.heights)
        max_depth = float(z.max()) - float(np.median(z))
        if not max_depth > 0:
            return None
    ic = island_curve(
        surface, VALIDITY_INCREMENTS, max_depth=max_depth,
        max_depth_fraction=VALIDITY_DEPTH_FRACTION, connectivity=connectivity,
        statistics=False, device=device,
    )  # fmt: skip
    return applicable_depth(ic)


def _auto_range(surface, material, n_increments, beta_prime, min_pixels, read_map, connectivity,
                want_islands, device):  # fmt: skip
    """(surface, ω_max, curve, stiffness curve, fit, warnings, indicators, rule) on the
    automatic fit range, or None when its fit is not worth reading either (the legacy result
    is then kept)."""
    try:
        s, max_depth, rule = auto_fit_range(surface)
        curve = truncate(s, n_increments, max_depth=max_depth, device=device)
        sc = stiffness_curve(curve, material, beta_prime=beta_prime)
        fit = fit_power_law(sc, min_pixels=min_pixels)
    except ValueError:
        return None
    found = check_fit(fit, sc)
    indicators = _validity(s, read_map, connectivity, device) if want_islands else None
    if indicators is not None:
        found += check_fit_depth(fit, indicators)
    if found:
        return None
    rule = {**rule, "reason": "the legacy fit range gave no fit worth reading"}
    return s, max_depth, curve, sc, fit, found, indicators, rule


def _truncation(source, n_increments: int, *, max_depth, max_depth_fraction, rt_percentile,
                islands, stream, band_rows, progress, device):  # fmt: skip
    """(curve, the Surface truncated or None when streamed, its metadata, the path record)."""
    if stream not in ("auto", True, False):
        raise ValueError(f"stream must be 'auto', True or False, got {stream!r}")
    opts = {"max_depth": max_depth, "max_depth_fraction": max_depth_fraction}
    spec = None if isinstance(source, Surface) else as_wm_spec(source)
    streamed = spec is not None and (
        stream is True or (stream == "auto" and not fits_in_memory(spec, device))
    )  # fmt: skip
    if not streamed:
        if isinstance(source, Surface) and stream is True:
            raise ValueError("stream=True applies to generated surfaces, not to a Surface")
        s = source if spec is None else surface_from_spec(spec, resolve_device(device))
        if rt_percentile is not None:
            s = clip_to_percentiles(s, *rt_percentile)
        curve = truncate(s, n_increments, **opts, device=device)
        return curve, s, s.to_dict(), {"path": "in-memory"}
    if rt_percentile is not None:
        raise ValueError("rt_percentile needs the map in memory; it cannot be streamed")
    if islands:
        raise ValueError("islands=True needs the map in memory; a streamed map has no island pass")
    st = banded_truncation(
        spec, n_increments, **opts, band_rows=band_rows, device=resolve_device(device),
        progress=progress,
    )  # fmt: skip
    reason = STREAM_GIVEN if stream is True else TOO_BIG
    info = {"band_rows": st.band_rows, "n_bands": st.n_bands, "reason": reason}
    return st.curve, None, st.surface, {"path": "streamed", "streaming": info}


def _islands(surface: Surface, curve: TruncationCurve, material: Material, n_increments: int,
             *, max_depth, max_depth_fraction, beta_prime, min_pixels, depth_window,
             connectivity, device):  # fmt: skip
    """(island-resolved StiffnessCurve, its fit or None) on the depths of ``curve``."""
    from .islands.depths import island_curve

    ic = island_curve(
        surface, n_increments, max_depth=max_depth, max_depth_fraction=max_depth_fraction,
        connectivity=connectivity, statistics=True, device=device,
    )  # fmt: skip
    if not (np.array_equal(ic.depth, curve.depth)
            and np.array_equal(ic.n_contact_pixels, curve.n_contact_pixels)):  # fmt: skip
        raise RuntimeError("internal error: island pass and truncation disagree on the depths")
    isl = island_stiffness_curve(ic, material, beta_prime=beta_prime)
    try:
        fit = fit_power_law(isl, min_pixels=min_pixels, depth_window=depth_window)
    except ValueError:  # same range as Eq. 2's fit, which succeeded: cannot happen
        fit = None
    return isl, fit
