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

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import warp as wp

from ._support.device import resolve_device
from .material import Material
from .plausibility import (
    PlausibilityWarning,
    check_fit,
    check_fit_depth,
    check_spikes,
    fit_error_text,
)
from .robust import automatic_range, check_map_size, clip_to_percentiles
from .slope import slope_record
from .stiffness import (
    PowerLawFit,
    StiffnessCurve,
    fit_power_law,
    island_stiffness_curve,
    stiffness_curve,
)
from .surface import Surface
from .truncation.api import truncate
from .truncation.curve import TruncationCurve
from .truncation.settings import FitRange, TruncationSettings
from .truncation.stream import banded_truncation, stream_reason
from .wm import surface_from_spec
from .wm_params import WMSpec, WMTerms

__all__ = ["ISLAND_MODEL", "Analysis", "FitRangeError", "analyze"]

ISLAND_MODEL = "k = β'(2/√π)E*·Σ_i √A_i, one flat punch per island"
"""How ``fit.json`` names the island-resolved model."""


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
    """The fit-range rule: ``asked`` (``"auto"`` or ``"legacy"``), ``rule`` (the one used),
    ``reason`` (why), the automatic decisions ``spikes_masked`` (``count``, ``passes``,
    ``sets``, ``Rt_before_m``, ``Rt_after_m``), ``depth_extended`` and ``depth_cut``
    (:func:`warptrunc.robust.adjust_depth`), each None when not taken, and ``max_depth_m`` (m)
    when the rule is ``"auto"``."""
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
        info = {
            **self.fit.to_dict(),
            "surface": self.surface,
            "material": self.material.__dict__,
            **self.path,
        }
        info["fit_range"] = self.fit_range or {"rule": "legacy"}
        info["fit_error"] = self.fit_error
        info["islands"] = (
            None
            if self.islands_fit is None
            else {
                **self.islands_fit.to_dict(),
                "model": ISLAND_MODEL,
                "connectivity": self.connectivity,
                "fit_error": self.islands_fit_error,
            }
        )
        info["applicable_depth"] = None if self.indicators is None else self.indicators.to_dict()
        info["warnings"] = [w.to_dict() for w in self.warnings]
        return info


def analyze(
    source: Surface | WMSpec | WMTerms | Mapping,
    *,
    truncation: TruncationSettings | None = None,
    fit: FitRange | None = None,
    material: Material | None = None,
    stream: bool | Literal["auto"] = "auto",
    band_rows: int | None = None,
    progress: bool = True,
    device: wp.DeviceLike = None,
    on_curve: Callable[[TruncationCurve], Any] | None = None,
) -> Analysis:
    """Truncate a surface, compute Eq. 2's stiffness and load, and fit k ∝ F^α.

    Parameters
    ----------
    source : Surface, WMSpec, WMTerms or mapping
        The height map (m), or a WM surface to generate (as :func:`warptrunc.truncate`
        takes it).
    truncation : TruncationSettings, optional
        Depth increments, ω_max, β′ and the island-resolved model
        (:class:`~warptrunc.truncation.settings.TruncationSettings`; its defaults when None).
        ``islands=None`` runs the island-resolved model for a map in memory, not when streamed.
    fit : FitRange, optional
        The fit range (:class:`~warptrunc.truncation.settings.FitRange`; its defaults when
        None). ``rule="legacy"``: increments to ω_max with ≥ ``min_pixels`` contact pixels.
        ``rule="auto"``: the same, and for a :class:`Surface` (a map read from a file) with no
        range of the caller's own (``truncation.max_depth``, ``depth_window``,
        ``rt_percentile``) the automatic rule of :mod:`warptrunc.robust`: a map under 32 pixels
        a side is refused; a tilt that spans more than the roughness is levelled; spikes that
        set R_t are masked (``spikes=True``); ω_max extends until the deepest increment has 50
        contact pixels (or is cut to 5 % of A in contact), and deeper while the fit is not
        worth reading, when the default fit is empty or not worth reading; no fit worth reading
        is refused (:class:`~warptrunc.robust.AutoRangeError`). ``spikes=False`` leaves the
        spikes as given and reports nothing. ``rt_percentile`` clips the heights first
        (:func:`warptrunc.robust.clip_to_percentiles`); the map must be in memory.
    material : Material, optional
        Elastic constants; ``Material()`` (the default alloy on a rigid flat) when None.
    stream : {"auto", True, False}
        For a WM surface: generate it by row bands (True), whole (False), or by bands only
        when the map needs more than half of the free memory ("auto"). A :class:`Surface` is
        always in memory (True raises).
    band_rows : int, optional
        Rows per band when streaming.
    progress : bool
        Show a progress bar over the bands of each streamed pass.
    device : str, optional
        Warp device; see :func:`warptrunc.resolve_device`.
    on_curve : callable, optional
        Called once with the truncation curve of the result (:attr:`Analysis.curve`) as soon
        as it is final and its fit succeeded, before the island pass: ``warptrunc analyze``
        sends it to be drawn while the islands are counted.

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
        streamed surface, a :class:`Surface` under 32 pixels a side with ``rule="auto"``
        (:func:`warptrunc.robust.check_map_size`).
    AutoRangeError
        ``rule="auto"`` on a map read from a file: no range of the automatic rule gives a fit
        worth reading; the message names the settings that give one on this map.

    Examples
    --------
    >>> from warptrunc import WMSpec, analyze
    >>> from warptrunc.truncation import FitRange, TruncationSettings
    >>> a = analyze(WMSpec(n=128), truncation=TruncationSettings(increments=50),
    ...             fit=FitRange(min_pixels=5), device="cpu")  # doctest: +SKIP
    """
    truncation = TruncationSettings() if truncation is None else truncation
    fit = FitRange() if fit is None else fit
    material = Material() if material is None else material
    read_map = isinstance(source, Surface)
    if read_map and fit.rule == "auto":
        check_map_size(source)
    curve, surface, meta, path = _truncation(
        source, truncation, fit.rt_percentile, stream, band_rows, progress, device
    )
    sc = stiffness_curve(curve, material, beta_prime=truncation.beta_prime)
    found: list = []
    try:
        eq2 = fit_power_law(sc, min_pixels=fit.min_pixels, depth_window=fit.depth_window)
        found = check_fit(eq2, sc)
    except ValueError as exc:
        eq2, error = None, exc
    own = [
        name
        for name, v in (
            ("--max-depth", truncation.max_depth),
            ("--depth-window", fit.depth_window),
            ("--rt-percentile", fit.rt_percentile),
        )
        if v is not None
    ]
    rule = _rule_without_auto(fit.rule, read_map, own)
    if rule is not None and eq2 is not None and on_curve is not None:
        on_curve(curve)  # final: no automatic rule can change it
        on_curve = None
    connectivity = truncation.connectivity
    want_islands = surface is not None and truncation.islands is not False
    indicators = _validity(surface, read_map, connectivity, device) if want_islands else None
    if eq2 is not None and indicators is not None:
        found += check_fit_depth(eq2, indicators)
    decided: list = []
    if rule is not None and read_map and fit.spikes:  # no rule: the spikes are reported
        decided = check_spikes(source)
    if rule is None:
        legacy = eq2, found, None if eq2 is not None else error
        validity = (lambda s: _validity(s, True, connectivity, device)) if want_islands else None
        auto, rule, decided = automatic_range(
            surface,
            legacy,
            material=material,
            truncation=truncation,
            fit_range=fit,
            indicators=validity,
            device=device,
        )
        if auto is not None:
            surface, omega, curve, sc, eq2, found, indicators = auto
            truncation = truncation.replace(max_depth=omega)
            meta = surface.to_dict()
    if eq2 is None:
        raise FitRangeError(str(error), surface) from None
    if on_curve is not None:
        on_curve(curve)
    isl = isl_fit = None
    isl_found: list = []
    if want_islands:
        isl, isl_fit = _islands(surface, curve, material, truncation, fit, device)
        if isl_fit is not None:
            isl_found = check_fit(isl_fit, isl, label="islands fit")
            if indicators is not None:
                isl_found += check_fit_depth(isl_fit, indicators, label="islands fit")
    meta = {**meta, "slope": slope_record(surface, params=meta)}  # h′_rms at the pixel used
    return Analysis(
        curve,
        sc,
        eq2,
        isl,
        isl_fit,
        material,
        meta,
        path,
        connectivity,
        warnings=tuple(decided + found + isl_found),
        fit_range=rule,
        indicators=indicators,
        fit_error=fit_error_text(found),
        islands_fit_error=fit_error_text(isl_found),
    )


VALIDITY_TRUNCATION = TruncationSettings(increments=100, max_depth_fraction=0.5)
"""Depth grid of the island counts that locate the maximum growth rate (§ 4.3, Table 2)."""


def _validity(surface: Surface, read_map: bool, connectivity: int, device):
    """§ 4.3's indicators (maximum growth rate of the island count) of the map: island counts
    at 100 depths to 0.5·R_t for a generated surface, to the median height (half of the
    pixels in contact) for a map read from a file, whose R_t a spike or a pit can set; None
    when that depth is not positive."""
    from .islands.depths import island_curve
    from .islands.fits import applicable_depth
    from .islands.settings import IslandSettings

    max_depth = None
    if read_map:
        z = np.asarray(surface.heights)
        max_depth = float(z.max()) - float(np.median(z))
        if not max_depth > 0:
            return None
    depths = VALIDITY_TRUNCATION.replace(max_depth=max_depth, connectivity=connectivity)
    ic = island_curve(
        surface, truncation=depths, settings=IslandSettings(statistics=False), device=device
    )
    return applicable_depth(ic)


def _rule_without_auto(fit_range: str, read_map: bool, own: list[str]) -> dict | None:
    """The ``fit_range`` record when the automatic rule does not apply; None when it does."""
    base = {
        "asked": fit_range,
        "rule": "legacy",
        "levelled": None,
        "spikes_masked": None,
        "depth_extended": None,
        "depth_cut": None,
    }
    if fit_range == "legacy":
        return {**base, "reason": "--fit-range legacy asked"}
    if not read_map:
        return {
            **base,
            "reason": "a generated surface: the automatic rule is for maps read from files",
        }
    if own:
        return {**base, "reason": f"a range of the caller's own ({', '.join(own)})"}
    return None


def _truncation(
    source, truncation: TruncationSettings, rt_percentile, stream, band_rows, progress, device
):
    """(curve, the Surface truncated or None when streamed, its metadata, the path record)."""
    opts = {"max_depth": truncation.max_depth, "max_depth_fraction": truncation.max_depth_fraction}
    spec, reason = stream_reason(source, stream, device)
    if reason is None:
        s = source if spec is None else surface_from_spec(spec, resolve_device(device))
        if rt_percentile is not None:
            s = clip_to_percentiles(s, *rt_percentile)
        curve = truncate(s, truncation.increments, **opts, device=device)
        return curve, s, s.to_dict(), {"path": "in-memory"}
    if rt_percentile is not None:
        raise ValueError("rt_percentile needs the map in memory; it cannot be streamed")
    if truncation.islands:
        raise ValueError("islands=True needs the map in memory; a streamed map has no island pass")
    st = banded_truncation(
        spec,
        truncation.increments,
        **opts,
        band_rows=band_rows,
        device=resolve_device(device),
        progress=progress,
    )
    info = {"band_rows": st.band_rows, "n_bands": st.n_bands, "reason": reason}
    return st.curve, None, st.surface, {"path": "streamed", "streaming": info}


def _islands(
    surface: Surface,
    curve: TruncationCurve,
    material: Material,
    truncation: TruncationSettings,
    fit_range: FitRange,
    device,
):
    """(island-resolved StiffnessCurve, its fit or None) on the depths of ``curve``."""
    from .islands.depths import island_curve
    from .islands.settings import IslandSettings

    ic = island_curve(
        surface, truncation=truncation, settings=IslandSettings(snapshots=None), device=device
    )
    if not (
        np.array_equal(ic.depth, curve.depth)
        and np.array_equal(ic.n_contact_pixels, curve.n_contact_pixels)
    ):
        raise RuntimeError("internal error: island pass and truncation disagree on the depths")
    isl = island_stiffness_curve(ic, material, beta_prime=truncation.beta_prime)
    try:
        fit = fit_power_law(
            isl, min_pixels=fit_range.min_pixels, depth_window=fit_range.depth_window
        )
    except ValueError:  # same range as Eq. 2's fit, which succeeded: cannot happen
        fit = None
    return isl, fit
