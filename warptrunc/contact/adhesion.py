# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The interaction law of adhesive contact, a parameter object (:class:`Adhesion`).

A law gives the traction σ(g) (Pa, tensile) between the surfaces at a gap g ≥ 0 (m) and its
energy per unit area φ(g) = −∫_g^∞ σ (J/m²), whose depth at contact is the work of adhesion
w = −φ(0):

- ``"maugis"``: Maugis–Dugdale's cohesive zone, σ = σ₀ = w/h₀ for g < h₀ and 0 beyond
  (φ = −w·(1 − g/h₀) below h₀); the law of Maugis (1992) [1]_ and of tamaas'
  ``MaugisAdhesionFunctional``;
- ``"exponential"``: σ = (w/ρ)·exp(−g/ρ) (φ = −w·exp(−g/ρ)); the law of the
  contact-mechanics challenge (Müser et al. 2017) [2]_ and of tamaas'
  ``ExponentialAdhesionFunctional``;
- ``"none"`` (default): non-adhesive contact, the solver of :mod:`warptrunc.contact.solver`
  unchanged.

The solver (:mod:`warptrunc.contact.iteration.adhesive`) samples the law at each pixel's gap,
``range`` is h₀ or ρ. No Warp here: the command-line parsers import this module (``--adhesion
maugis --work 0.05 --range 2e-9``, generated from the fields).

References
----------
.. [1] D. Maugis, Adhesion of spheres: the JKR-DMT transition using a Dugdale model,
   J. Colloid Interface Sci. 150, 243 (1992). doi:10.1016/0021-9797(92)90285-T
.. [2] M.H. Müser et al., Meeting the contact-mechanics challenge, Tribol. Lett. 65, 118
   (2017). doi:10.1007/s11249-017-0900-2
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..params import Parameters, check_fields, param

__all__ = ["ADHESION_LAWS", "Adhesion"]

ADHESION_LAWS = ("none", "maugis", "exponential")
"""The interaction laws of :class:`Adhesion` (``"none"``: non-adhesive contact)."""

_LAW_CODES = {"none": 0, "maugis": 1, "exponential": 2}  # kernels/contact/adhesion.py's


@dataclass(frozen=True)
class Adhesion(Parameters):
    """The interaction law of adhesive contact: its kind, work of adhesion w and range.

    Raises
    ------
    ValueError
        A field out of its range; the message names the field, its value and the range.

    Examples
    --------
    >>> law = Adhesion("maugis", work=0.05, range=2e-9)
    >>> law.peak_stress  # σ₀ = w/h₀ (Pa)
    25000000.0
    >>> Adhesion().active
    False
    """

    law: str = param(
        "none",
        "interaction law: 'maugis' Maugis–Dugdale's constant cohesive stress w/h₀ for gaps "
        "below h₀, 'exponential' the stress (w/ρ)·exp(−g/ρ), 'none' non-adhesive",
        choices=ADHESION_LAWS,
        cli="adhesion",
        sweep=False,
    )
    work: float = param(
        0.0, "work of adhesion w, the law's energy per unit area at contact", unit="J/m²", ge=0.0
    )
    range: float = param(
        2e-9, "range of the law: h₀ (Maugis–Dugdale) or ρ (exponential)", unit="m", gt=0.0
    )

    def __post_init__(self) -> None:
        check_fields(self)

    @property
    def active(self) -> bool:
        """True for an adhesive law (``law`` is not ``"none"``), whatever the work."""
        return self.law != "none"

    @property
    def code(self) -> int:
        """The law's number in ``warptrunc.kernels.contact.adhesion`` (0 none, 1 Maugis–Dugdale,
        2 exponential)."""
        return _LAW_CODES[self.law]

    @property
    def peak_stress(self) -> float:
        """The largest tensile stress of the law, w/range (Pa): σ₀ of Maugis–Dugdale, the
        stress at contact of the exponential law; 0 without adhesion."""
        return self.work / self.range if self.active else 0.0

    def stress(self, gap: Any) -> np.ndarray:
        """The law's traction at the gaps ``gap`` (m), compressive positive (so ≤ 0).

        Parameters
        ----------
        gap : array_like
            Gaps g (m); values below 0 count as 0 (closed).

        Returns
        -------
        ndarray of float64
            −σ(g) (Pa).
        """
        g = np.maximum(np.asarray(gap, dtype=np.float64), 0.0)
        if self.law == "maugis":
            return np.where(g < self.range, -self.peak_stress, 0.0)
        if self.law == "exponential":
            return -self.peak_stress * np.exp(-g / self.range)
        return np.zeros_like(g)

    def energy(self, gap: Any) -> np.ndarray:
        """The law's energy per unit area at the gaps ``gap`` (m).

        Parameters
        ----------
        gap : array_like
            Gaps g (m); values below 0 count as 0 (closed).

        Returns
        -------
        ndarray of float64
            φ(g) (J/m²): −w at contact, 0 far apart.
        """
        g = np.maximum(np.asarray(gap, dtype=np.float64), 0.0)
        if self.law == "maugis":
            return np.where(g < self.range, -self.work * (1.0 - g / self.range), 0.0)
        if self.law == "exponential":
            return -self.work * np.exp(-g / self.range)
        return np.zeros_like(g)

    def maugis_parameter(self, radius: float, contact_modulus: float) -> float:
        """Maugis' transition parameter λ = 2σ₀·[R/(π·w·K²)]^(1/3), K = 4E*/3, of a sphere.

        λ → ∞ is the JKR limit (pull-off 1.5πwR), λ → 0 the DMT limit (2πwR). σ₀ is
        :attr:`peak_stress` (for the exponential law the stress at contact, the Maugis–Dugdale
        law of the same w and peak stress).

        Parameters
        ----------
        radius : float
            Radius R of the sphere (m).
        contact_modulus : float
            E* (Pa).

        Returns
        -------
        float
            λ (dimensionless); 0 when w = 0.
        """
        if self.work == 0.0:
            return 0.0
        k = 4.0 * contact_modulus / 3.0
        return 2.0 * self.peak_stress * (radius / (math.pi * self.work * k**2)) ** (1.0 / 3.0)

    def tabor_parameter(self, radius: float, contact_modulus: float) -> float:
        """Tabor's parameter μ = [R·w²/(E*²·z₀³)]^(1/3) of a sphere, with z₀ = ``range``.

        Parameters
        ----------
        radius : float
            Radius R of the sphere (m).
        contact_modulus : float
            E* (Pa).

        Returns
        -------
        float
            μ (dimensionless): the elastic deformation at pull-off over the law's range.
        """
        return (radius * self.work**2 / (contact_modulus**2 * self.range**3)) ** (1.0 / 3.0)
