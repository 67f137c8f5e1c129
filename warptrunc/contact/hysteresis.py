# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The force–approach cycle of an adhesive contact (:func:`force_approach`): its loading and
unloading branches, where the repulsive contact appears and vanishes (the jump-in and the
jump-out), the pull-off force and the work the cycle dissipates.

It reads a :class:`~warptrunc.contact.results.ContactCurve` whose approaches go in and out
(:func:`~warptrunc.contact.solve_contact` with an :class:`~warptrunc.contact.adhesion.Adhesion`
law and depths that rise, then fall): NumPy only, no Warp.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["JUMP_FACTOR", "ForceApproachCycle", "force_approach"]

JUMP_FACTOR = 3.0
"""A change of the load between two rows counts as a jump when it is more than this many times
the median change of the other steps of the same branch (dimensionless)."""


@dataclass(frozen=True)
class ForceApproachCycle:
    """The loading and unloading of one force–approach curve (SI units)."""

    pull_off_force: float
    """The most tensile load of the curve (N, ≤ 0; 0 when no row pulls). On an unloading
    branch under displacement control this is the pull-off force of load control: the
    minimum of F(δ), before the displacement-controlled jump-out."""
    pull_off_depth: float
    """Approach of that row (m)."""
    jump_in_depth: float
    """Approach of the first loading row in repulsive contact after a row without (m); NaN
    when there is none."""
    jump_in_load_change: float
    """The load change at that step (N; negative: the surfaces snapped together); NaN when
    there is none."""
    jump_in: bool
    """The contact appeared with a jump (its load change more than :data:`JUMP_FACTOR` times
    the loading branch's median step)."""
    jump_out_depth: float
    """Approach of the first unloading row without repulsive contact after a row with (m);
    NaN when there is none."""
    jump_out_load_change: float
    """The load change at that step (N; positive: the neck broke); NaN when there is none."""
    jump_out: bool
    """The contact vanished with a jump (as :attr:`jump_in`, on the unloading branch)."""
    dissipated_work: float
    """The work the cycle dissipates, ∮ F dδ over the rows in their order, closed from the
    last row back to the first (J; the trapezoidal rule; 0 for a reversible curve)."""
    loading: np.ndarray
    """(m,) bool: the row's approach is larger than the row before (the first row counts as
    loading)."""

    def to_dict(self) -> dict[str, Any]:
        """The scalars, SI units in the names (``loading`` left out).

        Returns
        -------
        dict of str to float or bool
            ``pull_off_force_N`` (N), ``pull_off_depth_m`` (m), ``jump_in_depth_m`` (m),
            ``jump_in_load_change_N`` (N), ``jump_in``, ``jump_out_depth_m`` (m),
            ``jump_out_load_change_N`` (N), ``jump_out``, ``dissipated_work_J`` (J).
        """
        return {
            "pull_off_force_N": self.pull_off_force,
            "pull_off_depth_m": self.pull_off_depth,
            "jump_in_depth_m": self.jump_in_depth,
            "jump_in_load_change_N": self.jump_in_load_change,
            "jump_in": self.jump_in,
            "jump_out_depth_m": self.jump_out_depth,
            "jump_out_load_change_N": self.jump_out_load_change,
            "jump_out": self.jump_out,
            "dissipated_work_J": self.dissipated_work,
        }


def _jump(load: np.ndarray, steps: np.ndarray, i: int) -> bool:
    """Whether the load change into row ``i`` stands out of the other ``steps`` (row indices
    of the same branch)."""
    others = [abs(load[j] - load[j - 1]) for j in steps if j != i]
    if not others:
        return True
    return bool(abs(load[i] - load[i - 1]) > JUMP_FACTOR * float(np.median(others)))


def force_approach(curve: Any) -> ForceApproachCycle:
    """The loading and unloading branches of a force–approach curve and their jumps.

    Parameters
    ----------
    curve : ContactCurve
        Rows in the order solved (:func:`~warptrunc.contact.solve_contact` with depths that go
        in and out); its ``depth`` (m), ``load`` (N) and ``n_contact`` are read.

    Returns
    -------
    ForceApproachCycle

    Raises
    ------
    ValueError
        Fewer than two rows.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> c = SimpleNamespace(depth=np.array([-1.0, 0.0, 1.0, 0.0, -1.0]),
    ...                     load=np.array([0.0, -1.0, 0.5, -1.5, 0.0]),
    ...                     n_contact=np.array([0, 3, 5, 4, 0]))
    >>> r = force_approach(c)
    >>> r.pull_off_force, r.jump_in_depth, r.jump_out_depth, r.dissipated_work
    (-1.5, 0.0, -1.0, 0.5)
    """
    d = np.asarray(curve.depth, dtype=np.float64)
    f = np.asarray(curve.load, dtype=np.float64)
    n = np.asarray(curve.n_contact)
    if d.size < 2:
        raise ValueError(f"a force–approach cycle needs at least two rows, got {d.size}")
    loading = np.concatenate([[True], np.diff(d) > 0])
    up = [i for i in range(1, d.size) if loading[i]]
    down = [i for i in range(1, d.size) if not loading[i]]
    nan = math.nan
    j_in = next((i for i in up if n[i - 1] == 0 and n[i] > 0), None)
    j_out = next((i for i in down if n[i - 1] > 0 and n[i] == 0), None)
    k = int(np.argmin(f))
    closed_d = np.concatenate([d, d[:1]])
    closed_f = np.concatenate([f, f[:1]])
    work = float(np.sum(0.5 * (closed_f[1:] + closed_f[:-1]) * np.diff(closed_d)))
    return ForceApproachCycle(
        pull_off_force=float(min(0.0, f[k])),
        pull_off_depth=float(d[k]) if f[k] < 0 else nan,
        jump_in_depth=nan if j_in is None else float(d[j_in]),
        jump_in_load_change=nan if j_in is None else float(f[j_in] - f[j_in - 1]),
        jump_in=j_in is not None and _jump(f, up, j_in),
        jump_out_depth=nan if j_out is None else float(d[j_out]),
        jump_out_load_change=nan if j_out is None else float(f[j_out] - f[j_out - 1]),
        jump_out=j_out is not None and _jump(f, down, j_out),
        dissipated_work=work,
        loading=loading,
    )
