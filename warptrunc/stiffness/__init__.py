# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stiffness and load from truncated areas (paper Eqs. 1–3) and the power-law fit (§4.4).

Host-side float64 arithmetic on a :class:`~warptrunc.truncation.TruncationCurve`. The one home
of Eq. 2 (:func:`flat_punch_stiffness`) and of power-law fits (:func:`fit_power_law` →
:class:`PowerLawFit`).

One normalisation of the contact modulus E_c = (√π/2)·k/√A (§4.1) is *the* one: E_c/E with E
the Young's modulus of the rough body, E_c/E = (E*/E)·β′·√(A_c/A) (``Ec_over_E``), as the
paper's Figs. 6 and 9 and Table 3 plot and fit it; ``alpha`` and ``beta`` of every fit are
those of E_c/E = β·[F/(E·A)]^α. The contact-modulus form E_c/E* = β′·√(A_c/A) (Eq. 3) stays
under explicit names (``Ec_over_Estar``, ``beta_contact_modulus``). The two differ by the
constant E*/E (1/(1 − ν²) = 1.12 against a rigid flat): the same α, β* = β·E/E*. Outputs
written before this one normalisation held the E* ones under ``Ec_over_E`` and ``beta``; they
are read with that meaning (see the changelog).
"""

from __future__ import annotations

from ..material import Material
from .curve import (
    STIFFNESS_MODELS,
    StiffnessCurve,
    flat_punch_stiffness,
    island_stiffness_curve,
    stiffness_curve,
)
from .fit import (
    DEFAULT_MIN_PIXELS,
    NORMALISATION_E,
    NORMALISATION_ESTAR,
    NORMALISATION_NONE,
    PowerLawFit,
    fit_power_law,
)

__all__ = [
    "DEFAULT_MIN_PIXELS",
    "NORMALISATION_E",
    "NORMALISATION_ESTAR",
    "NORMALISATION_NONE",
    "STIFFNESS_MODELS",
    "Material",
    "PowerLawFit",
    "StiffnessCurve",
    "fit_power_law",
    "flat_punch_stiffness",
    "island_stiffness_curve",
    "stiffness_curve",
]
