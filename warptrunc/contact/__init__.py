# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic and elastic–perfectly-plastic contact of rough surfaces on Warp: a boundary-element
solver (preconditioned bound-constrained CG, or Polonsky–Keer's constrained CG) on a free
(zero-padded) or periodic half-space, with an optional pressure cap (the hardness), and the
cross-check of truncation analysis against it (:func:`bem_check`).

What lives where:

- ``settings``: the parameter objects (:class:`SolverSettings`, :class:`CurveSettings`,
  :class:`BemCheckSettings`; no Warp, the command-line parsers import them); ``adhesion``:
  the interaction law of adhesive contact (:class:`Adhesion`, no Warp either);
- ``solver``: the solver object, :class:`ContactSolver` (its state and public methods);
  ``factory``: :func:`contact_solver`, the solver on one device or spread over several;
  ``iteration``: the iterations it runs (what the loops share, Polonsky–Keer, BCCG with its
  scalar steps on the host or on the device, the capped solves and the plastic flow, Barber's
  punch); ``memory``: its memory model and the check against the free memory;
- ``halfspace``, ``influence``, ``transforms``: the elastic half-space (kernel spectrum,
  influence table, padded transforms, lane reductions);
- ``sharded``: one contact problem spread over several devices (JAX), the same solver;
- ``curve``: contact curves, :func:`solve_contact`; ``results``: their result objects;
  ``hysteresis``: the force–approach cycle of an adhesive curve (:func:`force_approach`);
- ``check``, ``runs``: the bem-check and its two elastic solvers (warptrunc's, ContactMechanics').

Every public name is importable from ``warptrunc.contact`` (imported on first use).
"""

from .._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "ADHESION_LAWS": ".adhesion",
        "Adhesion": ".adhesion",
        "BemCheckSettings": ".settings",
        "ContactCurve": ".results",
        "ContactSolver": ".solver",
        "ContactState": ".results",
        "CurveSettings": ".settings",
        "ElasticHalfSpace": ".halfspace",
        "ForceApproachCycle": ".hysteresis",
        "STIFFNESS_METHODS": ".settings",
        "SUBSTRATES": ".influence",
        "SolverSettings": ".settings",
        "contact_solver": ".factory",
        "default_pentol": ".solver",
        "force_approach": ".hysteresis",
        "influence_spectrum": ".influence",
        "influence_table": ".influence",
        "solve_contact": ".curve",
    },
)
