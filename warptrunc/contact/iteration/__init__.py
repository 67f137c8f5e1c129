# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The iterations of :class:`~warptrunc.contact.ContactSolver`, one module each.

``loop``: what the solve loops share (which iteration runs, the warm start, the stopping test,
the records a solve returns); ``pk``: Polonsky & Keer's constrained CG (``algorithm="pk"``);
``bccg``: the preconditioned bound-constrained CG with a read-back after each reduction
(``algorithm="bccg"``, ``loop="host"``, the defaults); ``bccg_device``: the same with its
scalar steps folded on the device (``loop="device"``) and replayed from a CUDA graph
(``loop="graph"``); ``plastic``: the capped solves, load control by the approach and the
plastic flow (a finite hardness); ``punch``: Barber's punch, the stiffness of the current
contact. Each holds a base class of the solver (the solver's class docstring says why).
"""
