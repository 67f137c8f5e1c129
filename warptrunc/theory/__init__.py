# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Contact theories from a surface's power spectrum: Persson, Greenwood–Williamson, Bush–Gibson–Thomas.

- :mod:`warptrunc.theory.psd`: the isotropic PSD C(q) (Persson's normalisation) from a
  self-affine description, a WM surface or a height map, and its moments;
- :mod:`warptrunc.theory.persson`: Persson's contact area, mean separation, stiffness and the
  distributions of pressure and gap;
- :mod:`warptrunc.theory.gw`: the asperity models, Greenwood–Williamson with Nayak's summit
  statistics and Bush–Gibson–Thomas.

Each returns a frozen result over an array of nominal pressures, with the quantities that say
whether it is inside its regime (h′_rms, the magnification) beside the curves.
"""

from .gw import (
    KAPPA_BGT,
    AsperityCurve,
    SummitStatistics,
    bgt_summit_weights,
    bush_gibson_thomas,
    greenwood_williamson,
    nayak_summits,
)
from .persson import (
    KAPPA_PERSSON,
    GapDistribution,
    PerssonCurve,
    PressureDistribution,
    persson_contact,
    persson_gap_distribution,
    persson_pressure_distribution,
)
from .psd import IsotropicPSD, self_affine_c0

__all__ = [
    "KAPPA_BGT",
    "KAPPA_PERSSON",
    "AsperityCurve",
    "GapDistribution",
    "IsotropicPSD",
    "PerssonCurve",
    "PressureDistribution",
    "SummitStatistics",
    "bgt_summit_weights",
    "bush_gibson_thomas",
    "greenwood_williamson",
    "nayak_summits",
    "persson_contact",
    "persson_gap_distribution",
    "persson_pressure_distribution",
    "self_affine_c0",
]
