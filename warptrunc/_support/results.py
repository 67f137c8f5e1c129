# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Helpers of the result dataclasses: their fields as a dict of columns, and ``all_converged``.

- :func:`fields_to_dict`: a result dataclass's fields as ``{column: value}``, in field order,
  with the column names (unit suffixes such as ``depth_m``) given once per type.
- :func:`all_converged_property`: the ``all_converged`` property of a result with a
  ``converged`` column.

Their JSON and CSV writers go through :mod:`warptrunc._support.outputs`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

__all__ = ["all_converged_property", "fields_to_dict"]


def all_converged_property() -> property:
    """The ``all_converged`` property of a result with a ``converged`` column (assign it in the
    class body, where the API reference documents it with the class's own members)."""

    def all_converged(self: Any) -> bool:
        """True when every entry of ``converged`` is true (every solve converged)."""
        return bool(np.all(self.converged))

    return property(all_converged)


def fields_to_dict(
    obj: Any, columns: Mapping[str, str] | None = None, *, skip: Iterable[str] = ()
) -> dict[str, Any]:
    """The dataclass ``obj``'s fields as ``{column: value}`` in field order.

    ``columns`` maps a field name to its column name (``{"depth": "depth_m"}``); fields not in
    it keep their name; fields in ``skip`` are left out. Values are not copied or converted.
    """
    columns = columns or {}
    skip = set(skip)
    return {
        columns.get(f.name, f.name): getattr(obj, f.name)
        for f in dataclasses.fields(obj)
        if f.name not in skip
    }
