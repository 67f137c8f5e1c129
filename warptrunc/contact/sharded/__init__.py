# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One contact problem spread over several devices (JAX): :class:`ShardedContactSolver`, which
``contact_solver(..., devices=...)`` returns.

``solver``: the solver (a :class:`~warptrunc.contact.ContactSolver` whose map lies in row slabs
over the devices); ``devices``: which devices a solve runs on and the per-device memory check;
``grid``: the slab layout, the per-device memory model and JAX's import; ``fft``: the sharded
half-space (the FFT convolution over the slabs); ``spectrum``: its kernel spectrum, built in
pieces; ``steps``: the per-pixel steps of the iteration (``jax.numpy``). JAX is imported only
when a solve is spread. ``ShardedContactSolver`` is importable from here (on first use).
"""

from ..._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(__name__, {"ShardedContactSolver": ".solver"})
