# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic contact of rough surfaces on Warp: a constrained conjugate-gradient (Polonsky–Keer)
boundary-element solver on a free (zero-padded) or periodic half-space, and the cross-check of
truncation analysis against it (:func:`bem_check`)."""

from .curve import STIFFNESS_METHODS, solve_contact
from .halfspace import ElasticHalfSpace
from .influence import SUBSTRATES, influence_spectrum, influence_table
from .results import ContactCurve
from .solver import ContactSolver, default_pentol

__all__ = [
    "STIFFNESS_METHODS",
    "SUBSTRATES",
    "ContactCurve",
    "ContactSolver",
    "ElasticHalfSpace",
    "default_pentol",
    "influence_spectrum",
    "influence_table",
    "solve_contact",
]
