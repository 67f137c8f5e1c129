# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic and elastic–perfectly-plastic contact of rough surfaces on Warp: a constrained
conjugate-gradient (Polonsky–Keer) boundary-element solver on a free (zero-padded) or periodic
half-space, with an optional pressure cap (the hardness), and the cross-check of truncation
analysis against it (:func:`bem_check`)."""

from . import sharded as _sharded  # noqa: F401 - registers ShardedContactSolver (no JAX import)
from .curve import STIFFNESS_METHODS, solve_contact
from .halfspace import ElasticHalfSpace
from .influence import SUBSTRATES, influence_spectrum, influence_table
from .results import ContactCurve, ContactState
from .settings import SolverSettings
from .solver import ContactSolver, default_pentol

__all__ = [
    "STIFFNESS_METHODS",
    "SUBSTRATES",
    "ContactCurve",
    "ContactSolver",
    "ContactState",
    "ElasticHalfSpace",
    "SolverSettings",
    "default_pentol",
    "influence_spectrum",
    "influence_table",
    "solve_contact",
]
