# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The result of :func:`warptrunc.indent`: one row per punch × placement × peak load, three
models side by side (elastic–plastic, elastic, Eq. 2 truncation), and their power-law fits."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._support.docs import SHARED_DOCS, fill_doc
from .._support.outputs import strict_json, write_columns_csv
from .._support.results import all_converged_property
from ..material import Material
from .depth import threshold_depth
from .fits import IndentFit, ModelFits, fit_model
from .protocol import IndentProtocol

__all__ = ["MODELS", "IndentationResult", "modulus_from_stiffness"]

MODELS = {
    "elastic_plastic": ("E_c_over_E", "in_fit", "area_resolved"),
    "elastic_plastic_partial": ("E_c_partial_over_E", "in_fit", "area_resolved"),
    "elastic": ("elastic_E_c_over_E", "elastic_in_fit", "elastic_area_resolved"),
    "elastic_partial": ("elastic_E_c_partial_over_E", "elastic_in_fit", "elastic_area_resolved"),
    "truncation": ("truncation_E_c_over_E", "in_fit", "area_resolved"),
}
"""Model name → (E_c/E column, column of the cells it may use, column of the cells whose
contact area converged too) of the fits E_c/E = β·[F/(E·A)]^α: the elastic–plastic unloading
stiffness (Barber's initial slope; ``_partial``: the secant of the partial unloading), the same
for the elastic solution (H = ∞), and Eq. 2 truncation (on the elastic–plastic cells' disks and
pixels, so their cells)."""


def modulus_from_stiffness(stiffness: Any, area: Any) -> np.ndarray:
    """E_c = √π·K/(2√A) (Pa), § 4.1.

    Parameters
    ----------
    stiffness : array_like
        Unloading stiffness K (N/m).
    area : array_like
        Punch area A (m²).

    Returns
    -------
    ndarray of float64
        E_c (Pa).
    """
    k = np.asarray(stiffness, dtype=np.float64)
    return math.sqrt(math.pi) * k / (2.0 * np.sqrt(np.asarray(area, dtype=np.float64)))


@dataclass(frozen=True, eq=False)
class IndentationResult:
    """Flat-punch indentation of a rough surface, in silico (paper § 4.1, Fig. 6).

    One row per punch diameter × placement × peak load, in that nesting order. Columns are
    (m,) host arrays; the unloading stiffnesses are measured with the plastic state of the peak
    frozen (:mod:`warptrunc.indent.protocol`).
    """

    punch_diameter: np.ndarray
    """(m,) float64 punch diameter d (m); NaN for a flat larger than the map."""
    placement: np.ndarray
    """(m,) int64 index of the punch position (0, 1, …) for this diameter."""
    centre_x: np.ndarray
    """(m,) float64 x of the punch centre (m), from the map's corner."""
    centre_y: np.ndarray
    """(m,) float64 y of the punch centre (m)."""
    overlap_fraction: np.ndarray
    """(m,) float64 largest fraction of this punch's area that another placement of the same
    diameter covers (dimensionless); 0 when they are apart."""
    punch_area: np.ndarray
    """(m,) float64 punch area A = πd²/4 (m²), or Lx·Ly for a flat larger than the map."""
    n_punch_pixels: np.ndarray
    """(m,) int64 pixels the punch can touch (pixel centre inside the disk)."""
    peak_load: np.ndarray
    """(m,) float64 peak load F of the cycle (N)."""
    displacement: np.ndarray
    """(m,) float64 approach δ of the punch at the peak, from first touch at the highest pixel
    inside the disk (m)."""
    n_contact: np.ndarray
    """(m,) int64 contact pixels at the peak (p > 0)."""
    contact_area: np.ndarray
    """(m,) float64 real contact area at the peak (m²)."""
    plastic_area: np.ndarray
    """(m,) float64 area of the pixels at the hardness at the peak (m²); 0 when elastic."""
    plastic_volume: np.ndarray
    """(m,) float64 plastic (permanent) volume removed up to the peak (m³)."""
    max_pressure: np.ndarray
    """(m,) float64 largest contact pressure at the peak (Pa); at most H, and below H where no
    pixel yields."""
    unloading_stiffness: np.ndarray
    """(m,) float64 Barber's initial unloading stiffness K (N/m): a rigid punch shaped like the
    whole contact set at the peak."""
    partial_unloading_stiffness: np.ndarray
    """(m,) float64 the paper's secant K = f·F/Δδ over the partial unloading (N/m)."""
    E_c: np.ndarray
    """(m,) float64 E_c = √π·K/(2√A) from :attr:`unloading_stiffness` (Pa)."""
    E_c_partial: np.ndarray
    """(m,) float64 E_c from :attr:`partial_unloading_stiffness` (Pa)."""
    converged: np.ndarray
    """(m,) bool: every solve of the cycle (peak, punch stiffness, partial unloading) converged."""
    realisation: np.ndarray
    """(m,) int64 index of the surface realisation (0 for one surface)."""
    pixel_size: np.ndarray
    """(m,) float64 pixel side dx the cell was finally solved at (m): the map's, or a WM map's
    divided by 2, 4, … (:mod:`warptrunc.indent.refine`)."""
    resolution_change: np.ndarray
    """(m,) float64 abs(K(p)/K(2p) − 1) of Barber's stiffness at the last halving of the pixel;
    NaN if the cell was not refined."""
    area_change: np.ndarray
    """(m,) float64 abs(A(p)/A(2p) − 1) of the contact area at the last halving; NaN if not
    refined."""
    stiffness_extrapolated: np.ndarray
    """(m,) float64 Barber's K extrapolated to a zero pixel over the last two halvings
    (Richardson, :func:`warptrunc.indent.refine.richardson`) (N/m); NaN if not refined."""
    stiffness_error: np.ndarray
    """(m,) float64 error estimate of K at the final pixel (N/m); NaN if not refined."""
    contact_area_extrapolated: np.ndarray
    """(m,) float64 contact area extrapolated likewise (m²); NaN if not refined."""
    contact_area_error: np.ndarray
    """(m,) float64 discretisation error estimate of the contact area at the final pixel (m²);
    NaN if not refined."""
    resolved: np.ndarray
    """(m,) bool: the one rule: K's error estimate over at least two halvings within
    ``protocol.resolution_tol`` of the extrapolated K, with at least
    ``protocol.min_contact_pixels`` contact pixels (a map that is not refined: the pixel count
    alone, ``resolution_note`` says so)."""
    area_resolved: np.ndarray
    """(m,) bool: resolved, and the contact area's error estimate within the tolerance too
    (the second rule of the fits' systematic)."""
    saturated: np.ndarray
    """(m,) bool: complete contact, every pixel of the punch face touches (or K at the
    complete-contact plateau)."""
    sub_window: np.ndarray
    """(m,) bool: the cell's final solve ran on a sub-window that holds its contact."""
    bulk_yield: np.ndarray
    """(m,) bool: the mean punch pressure F/A reaches the bulk-yield pressure of the cap model,
    (2.84/3)·H (:mod:`warptrunc.indent.depth`): left out of the fits."""
    in_fit: np.ndarray
    """(m,) bool: resolved, not saturated, converged and not bulk-yielding: used by the fits."""
    detection_displacement: np.ndarray
    """(m,) float64 approach at the detection load F_s (``protocol.detection_load``) on the
    cell's window and pixel (m); NaN without one."""
    resolution_note: np.ndarray
    """(m,) str: why the refinement stopped (:data:`warptrunc.indent.refine.NOTES`)."""
    elastic_displacement: np.ndarray
    """(m,) float64 approach at the peak of the elastic solution, H = ∞ (m); NaN when not run."""
    elastic_contact_area: np.ndarray
    """(m,) float64 contact area of the elastic solution at the peak (m²)."""
    elastic_unloading_stiffness: np.ndarray
    """(m,) float64 Barber's stiffness of the elastic solution at the peak (N/m)."""
    elastic_partial_unloading_stiffness: np.ndarray
    """(m,) float64 the partial-unloading secant of the elastic solution (N/m)."""
    elastic_converged: np.ndarray
    """(m,) bool: every solve of the elastic cycle converged (False when not run)."""
    elastic_pixel_size: np.ndarray
    """(m,) float64 pixel side the elastic cell was finally solved at (m); NaN when not run."""
    elastic_n_contact: np.ndarray
    """(m,) int64 contact pixels of the elastic solution at the peak (0 when not run)."""
    elastic_resolution_change: np.ndarray
    """(m,) float64 :attr:`resolution_change` of the elastic solution."""
    elastic_stiffness_extrapolated: np.ndarray
    """(m,) float64 :attr:`stiffness_extrapolated` of the elastic solution (N/m)."""
    elastic_stiffness_error: np.ndarray
    """(m,) float64 :attr:`stiffness_error` of the elastic solution (N/m)."""
    elastic_contact_area_error: np.ndarray
    """(m,) float64 :attr:`contact_area_error` of the elastic solution (m²)."""
    elastic_resolved: np.ndarray
    """(m,) bool :attr:`resolved` of the elastic solution (False when not run)."""
    elastic_area_resolved: np.ndarray
    """(m,) bool :attr:`area_resolved` of the elastic solution (False when not run)."""
    elastic_detection_displacement: np.ndarray
    """(m,) float64 :attr:`detection_displacement` of the elastic solution (m)."""
    elastic_saturated: np.ndarray
    """(m,) bool :attr:`saturated` of the elastic solution."""
    elastic_in_fit: np.ndarray
    """(m,) bool :attr:`in_fit` of the elastic solution (False when not run)."""
    truncation_depth: np.ndarray
    """(m,) float64 truncation depth ω under the punch where Eq. 2's F(ω) = F (m)."""
    truncation_contact_area: np.ndarray
    """(m,) float64 truncated area A_c of the disk at that depth (m²)."""
    truncation_stiffness: np.ndarray
    """(m,) float64 k = (2/√π)·E*·√A_c, Eq. 2 (N/m)."""
    truncation_pixel_size: np.ndarray
    """(m,) float64 pixel side of the disk truncation read (m): the finest whole window at or
    above the cell's final pixel."""
    material: Material
    """Material: E (Pa) normalises E_c/E and F/(E·A); E* and the hardness H (Pa) of the solves."""
    protocol: IndentProtocol
    """The protocol that was run."""
    settings: dict[str, Any] = field(default_factory=dict)
    """Surface, solver settings, device, the pixel counts of each punch and its punch face
    (``punch_face``: tilt and roughness per diameter, None for aligned smooth flats) (JSON-able)."""

    # --- derived columns -------------------------------------------------------------------

    def _over_E(self, stiffness: np.ndarray) -> np.ndarray:
        return modulus_from_stiffness(stiffness, self.punch_area) / self.material.E

    @property
    def E_c_over_E(self) -> np.ndarray:
        """(m,) float64 E_c/E of Barber's unloading stiffness (dimensionless)."""
        return self.E_c / self.material.E

    @property
    def E_c_partial_over_E(self) -> np.ndarray:
        """(m,) float64 E_c/E of the partial-unloading secant (dimensionless)."""
        return self.E_c_partial / self.material.E

    @property
    def threshold_depth(self) -> np.ndarray:
        """(m,) float64 depth from surface detection, δ(F) − δ(F_s) (m;
        :mod:`warptrunc.indent.depth`): at most :attr:`displacement`."""
        return threshold_depth(self.displacement, self.detection_displacement)

    @property
    def elastic_threshold_depth(self) -> np.ndarray:
        """(m,) float64 :attr:`threshold_depth` of the elastic solution (m)."""
        return threshold_depth(self.elastic_displacement, self.elastic_detection_displacement)

    @property
    def mean_pressure(self) -> np.ndarray:
        """(m,) float64 mean punch pressure F/A (Pa)."""
        return self.peak_load / self.punch_area

    @property
    def F_over_EA(self) -> np.ndarray:
        """(m,) float64 F/(E·A) (dimensionless)."""
        return self.peak_load / (self.material.E * self.punch_area)

    @property
    def elastic_E_c_over_E(self) -> np.ndarray:
        """(m,) float64 E_c/E of the elastic solution's Barber stiffness (dimensionless)."""
        return self._over_E(self.elastic_unloading_stiffness)

    @property
    def elastic_E_c_partial_over_E(self) -> np.ndarray:
        """(m,) float64 E_c/E of the elastic solution's partial-unloading secant."""
        return self._over_E(self.elastic_partial_unloading_stiffness)

    @property
    def truncation_E_c_over_E(self) -> np.ndarray:
        """(m,) float64 E_c/E of Eq. 2 truncation, E*/E·√(A_c/A) (dimensionless)."""
        return self._over_E(self.truncation_stiffness)

    all_converged = all_converged_property()

    # --- tables ------------------------------------------------------------------------------

    def to_dict(self) -> dict[str, np.ndarray]:
        """1-D columns, SI units in the names: the rows of ``indent.csv``.

        Returns
        -------
        dict of str to (m,) ndarray
            ``punch_diameter_m, placement, peak_load_N, displacement_m, contact_area_m2,
            plastic_area_m2, unloading_stiffness_N_per_m, partial_unloading_stiffness_N_per_m,
            E_c_Pa, E_c_over_E, F_over_EA, converged`` (the elastic–plastic model), its
            resolution ``pixel_size_m, n_contact_pixels, resolution_change, area_change,
            resolved, saturated, in_fit, resolution_note``, ``realisation``, then
            ``E_c_partial_Pa, E_c_partial_over_E, centre_x_m, centre_y_m, overlap_fraction,
            punch_area_m2, n_punch_pixels`` (at ``pixel_size_m``), ``plastic_volume_m3,
            max_pressure_Pa``, the elastic solution's ``elastic_*`` columns
            (``displacement_m``, ``contact_area_m2``, ``unloading_stiffness_N_per_m``,
            ``partial_unloading_stiffness_N_per_m``, ``E_c_over_E``, ``E_c_partial_over_E``,
            ``converged``, ``pixel_size_m``, ``n_contact_pixels``, ``resolution_change``,
            ``resolved``, ``saturated``, ``in_fit``) and Eq. 2 truncation's
            ``truncation_depth_m``, ``truncation_contact_area_m2``,
            ``truncation_stiffness_N_per_m``, ``truncation_E_c_over_E`` (on the disk at
            ``pixel_size_m``).
        """
        return {
            "punch_diameter_m": self.punch_diameter,
            "placement": self.placement,
            "peak_load_N": self.peak_load,
            "displacement_m": self.displacement,
            "contact_area_m2": self.contact_area,
            "plastic_area_m2": self.plastic_area,
            "unloading_stiffness_N_per_m": self.unloading_stiffness,
            "partial_unloading_stiffness_N_per_m": self.partial_unloading_stiffness,
            "E_c_Pa": self.E_c,
            "E_c_over_E": self.E_c_over_E,
            "F_over_EA": self.F_over_EA,
            "converged": self.converged,
            "pixel_size_m": self.pixel_size,
            "n_contact_pixels": self.n_contact,
            "resolution_change": self.resolution_change,
            "area_change": self.area_change,
            "stiffness_extrapolated_N_per_m": self.stiffness_extrapolated,
            "stiffness_error_N_per_m": self.stiffness_error,
            "contact_area_extrapolated_m2": self.contact_area_extrapolated,
            "contact_area_error_m2": self.contact_area_error,
            "resolved": self.resolved,
            "area_resolved": self.area_resolved,
            "saturated": self.saturated,
            "sub_window": self.sub_window,
            "bulk_yield": self.bulk_yield,
            "in_fit": self.in_fit,
            "resolution_note": self.resolution_note,
            "realisation": self.realisation,
            "detection_displacement_m": self.detection_displacement,
            "threshold_depth_m": self.threshold_depth,
            "mean_pressure_Pa": self.mean_pressure,
            "E_c_partial_Pa": self.E_c_partial,
            "E_c_partial_over_E": self.E_c_partial_over_E,
            "centre_x_m": self.centre_x,
            "centre_y_m": self.centre_y,
            "overlap_fraction": self.overlap_fraction,
            "punch_area_m2": self.punch_area,
            "n_punch_pixels": self.n_punch_pixels,
            "plastic_volume_m3": self.plastic_volume,
            "max_pressure_Pa": self.max_pressure,
            "elastic_displacement_m": self.elastic_displacement,
            "elastic_contact_area_m2": self.elastic_contact_area,
            "elastic_unloading_stiffness_N_per_m": self.elastic_unloading_stiffness,
            "elastic_partial_unloading_stiffness_N_per_m": self.elastic_partial_unloading_stiffness,
            "elastic_E_c_over_E": self.elastic_E_c_over_E,
            "elastic_E_c_partial_over_E": self.elastic_E_c_partial_over_E,
            "elastic_converged": self.elastic_converged,
            "elastic_pixel_size_m": self.elastic_pixel_size,
            "elastic_n_contact_pixels": self.elastic_n_contact,
            "elastic_resolution_change": self.elastic_resolution_change,
            "elastic_stiffness_extrapolated_N_per_m": self.elastic_stiffness_extrapolated,
            "elastic_stiffness_error_N_per_m": self.elastic_stiffness_error,
            "elastic_contact_area_error_m2": self.elastic_contact_area_error,
            "elastic_resolved": self.elastic_resolved,
            "elastic_area_resolved": self.elastic_area_resolved,
            "elastic_detection_displacement_m": self.elastic_detection_displacement,
            "elastic_threshold_depth_m": self.elastic_threshold_depth,
            "elastic_saturated": self.elastic_saturated,
            "elastic_in_fit": self.elastic_in_fit,
            "truncation_depth_m": self.truncation_depth,
            "truncation_contact_area_m2": self.truncation_contact_area,
            "truncation_stiffness_N_per_m": self.truncation_stiffness,
            "truncation_E_c_over_E": self.truncation_E_c_over_E,
            "truncation_pixel_size_m": self.truncation_pixel_size,
        }

    def fit_cells(self, name: str) -> dict[str, np.ndarray]:
        """The cells a model's fits may use: ``in_fit`` for that model, E_c/E and F/(E·A) > 0.

        Parameters
        ----------
        name : str
            A :data:`MODELS` name.

        Returns
        -------
        dict of str to ndarray
            ``x`` (F/(E·A)), ``y`` (E_c/E), ``depth`` (m: the approach δ, truncation's ω),
            ``load`` (N), ``punch`` (m, NaN for a flat larger than the map), ``realisation``,
            ``placement``, ``indent`` ((k, 3) realisation, punch diameter, placement) and
            ``rules`` (rule → (k,) bool: ``stiffness``, every cell; ``stiffness_and_area``, those
            whose contact area converged too) of the cells, and ``mask`` ((m,) bool over the
            rows).
        """
        y_col, ok_col, area_col = MODELS[name]
        cols = self.to_dict()
        y = np.asarray(cols[y_col], dtype=np.float64)
        x = self.F_over_EA
        ok = np.isfinite(y) & (y > 0) & np.isfinite(x) & (x > 0) & np.asarray(cols[ok_col], bool)
        depth = {
            "truncation": self.truncation_depth,
            "elastic": self.elastic_displacement,
            "elastic_partial": self.elastic_displacement,
        }.get(name, self.displacement)
        d = np.nan_to_num(self.punch_diameter, nan=0.0)
        ind = np.stack(
            [self.realisation.astype(np.float64), d, self.placement.astype(np.float64)], 1
        )
        return {
            "x": x[ok],
            "y": y[ok],
            "depth": depth[ok],
            "load": self.peak_load[ok],
            "punch": self.punch_diameter[ok],
            "realisation": self.realisation[ok],
            "placement": self.placement[ok],
            "indent": ind[ok],
            "rules": {
                "stiffness": np.ones(int(ok.sum()), bool),
                "stiffness_and_area": np.asarray(cols[area_col], bool)[ok],
            },
            "mask": ok,
        }

    def model_fits(self) -> dict[str, ModelFits]:
        """Per model, the fits over loads of each punch and the pooled one beside them.

        Returns
        -------
        dict of str to ModelFits
            One entry per :data:`MODELS` name (:func:`warptrunc.indent.fits.fit_model`): per
            punch diameter a fit over at least three distinct peak loads with cells in_fit,
            else the reason; the pooled fit only where the per-punch α intervals agree; the
            intervals by a hierarchical bootstrap over realisations and placements, spanning
            both cell rules.
        """
        cache = self.__dict__.get("_model_fits")
        if cache is None:
            punches = [None if not math.isfinite(d) else d for d in np.unique(self.punch_diameter)]
            cache = {
                name: fit_model(self.fit_cells(name), self.material, punches=punches)
                for name in MODELS
            }
            object.__setattr__(self, "_model_fits", cache)
        return cache

    def punch_fits(self) -> dict[str, dict[float, IndentFit | None]]:
        """Per model, punch diameter (m; NaN for a flat larger than the map) → its fit over
        loads, or None where it is not made (:meth:`model_fits` has the reasons).

        Returns
        -------
        dict of str to dict of float to IndentFit or None
        """
        return {name: mf.per_punch for name, mf in self.model_fits().items()}

    def fits(self) -> dict[str, IndentFit | None]:
        """Per model, the pooled fit over the punches: made only beside at least two per-punch
        fits over loads whose α intervals agree (:meth:`model_fits`).

        Returns
        -------
        dict of str to IndentFit or None
            One entry per :data:`MODELS` name; None where the pooled fit is not made.
            ``alpha_ci95``/``beta_ci95`` by a hierarchical bootstrap over realisations and
            placements, spanning both cell rules (:mod:`warptrunc.indent.fits`);
            ``depth_min``/``depth_max`` are the range of the punch approach δ (m) of the cells
            used (truncation: ω).
        """
        return {name: mf.pooled for name, mf in self.model_fits().items()}

    def fit_summary(self) -> dict[str, dict[str, Any]]:
        """The fits as ``indent.json`` holds them.

        Returns
        -------
        dict of str to dict
            Model → :meth:`ModelFits.to_dict`: ``per_punch`` (per diameter ``n_loads`` and
            the fit, or ``made`` False with the ``reason``), ``pooled`` and ``agreement``.
        """
        return {name: mf.to_dict() for name, mf in self.model_fits().items()}

    def resolution_counts(self) -> dict[str, Any]:
        """How many cells are resolved, saturated and in the fits, per contact model.

        Returns
        -------
        dict
            ``n_cells`` and, for ``elastic_plastic`` and ``elastic`` (when run), the counts
            ``resolved``, ``saturated``, ``in_fit``, ``not_converged`` and per
            ``resolution_note``.
        """
        out: dict[str, Any] = {"n_cells": int(self.peak_load.size)}
        pairs = [("elastic_plastic", "")]
        if self.protocol.elastic:
            pairs.append(("elastic", "elastic_"))
        cols = self.to_dict()
        for name, pre in pairs:
            conv = np.asarray(cols[f"{pre}converged"], bool)
            out[name] = {
                k: int(np.sum(cols[f"{pre}{k}"]))
                for k in ("resolved", "area_resolved", "saturated", "in_fit")
            }
            out[name]["not_converged"] = int((~conv).sum())
        notes, counts = np.unique(self.resolution_note.astype(str), return_counts=True)
        out["elastic_plastic"]["notes"] = {
            str(k): int(v) for k, v in zip(notes, counts, strict=True)
        }
        px = np.asarray(self.pixel_size, np.float64)
        base = float(np.nanmax(px)) if px.size else math.nan
        out["elastic_plastic"].update(
            sub_window=int(np.sum(self.sub_window)),
            bulk_yield=int(np.sum(self.bulk_yield)),
            largest_refinement=round(base / float(np.nanmin(px))) if px.size else 1,
        )
        return out

    def depth_summary(self) -> dict[str, Any]:
        """How depth is read and where the cap model stops: what ``indent.json`` states.

        Returns
        -------
        dict
            ``detection_load_N`` and ``detection`` (the threshold depth's definition,
            :mod:`warptrunc.indent.depth`), ``bulk_yield`` (the criterion, its pressure
            (Pa) and the cells flagged) and, per punch diameter at the largest peak load,
            ``threshold_depth_m`` and ``depth_m`` (from the highest point) as median, min and
            max over the indents.
        """
        from .depth import BULK_YIELD_FRACTION, BULK_YIELD_SOURCE, DETECTION_SOURCE

        h = self.material.hardness
        top = self.peak_load == self.peak_load.max() if self.peak_load.size else self.peak_load
        per = []
        for d in np.unique(self.punch_diameter[top]):
            sel = top & (np.isnan(self.punch_diameter) if np.isnan(d) else self.punch_diameter == d)
            row: dict[str, Any] = {"punch_diameter_m": None if np.isnan(d) else float(d)}
            for key, v in (
                ("threshold_depth_m", self.threshold_depth),
                ("depth_m", self.displacement),
            ):
                v = v[sel & self.converged]
                v = v[np.isfinite(v)]
                row[key] = (
                    {"median": float(np.median(v)), "min": float(v.min()), "max": float(v.max())}
                    if v.size
                    else None
                )
            per.append(row)
        return {
            "detection_load_N": self.protocol.detection_load,
            "detection": DETECTION_SOURCE,
            "bulk_yield": {
                "criterion": BULK_YIELD_SOURCE,
                "pressure_Pa": None if not math.isfinite(h) else BULK_YIELD_FRACTION * h,
                "n_cells": int(np.sum(self.bulk_yield)),
            },
            "at_largest_load": {
                "load_N": float(self.peak_load.max()) if self.peak_load.size else None,
                "per_punch": per,
            },
        }

    def summary(self) -> dict[str, Any]:
        """Settings, material, protocol and the fits: what ``indent.json`` holds besides its
        provenance.

        Returns
        -------
        dict
            ``protocol``, ``material`` (SI, with ``contact_modulus``), ``settings``, ``fits``
            (:meth:`fit_summary`), ``resolution`` (:meth:`resolution_counts`), ``depth``
            (:meth:`depth_summary`), ``n_rows``, ``all_converged``.
        """
        return {
            "protocol": self.protocol.to_dict(),
            "material": self.material.to_dict(),
            "settings": self.settings,
            "fits": self.fit_summary(),
            "resolution": self.resolution_counts(),
            "depth": self.depth_summary(),
            "fit_form": "E_c/E = beta * (F/(E*A))**alpha, E Young's modulus, A punch area",
            "n_rows": int(self.peak_load.size),
            "all_converged": self.all_converged,
        }

    @fill_doc(SHARED_DOCS)
    def to_csv(self, path: str | Path) -> Path:
        """Write :meth:`to_dict` as CSV (full float64 precision).

        {write_path}

        {returns_path}
            ``path``.
        """
        return write_columns_csv(path, self.to_dict())

    @fill_doc(SHARED_DOCS)
    def to_json(self, path: str | Path, **extra: Any) -> Path:
        """Write :meth:`summary` (and ``extra`` keys) as strict JSON (NaN/inf as null).

        {write_path}
        **extra
            Further top-level keys (e.g. provenance).

        {returns_path}
            ``path``.
        """
        path = Path(path)
        path.write_text(strict_json({**self.summary(), **extra}))
        return path
