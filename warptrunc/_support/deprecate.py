# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Deprecated names that keep working with a :class:`DeprecationWarning`.

- :func:`deprecated_function`: a renamed or folded function under its old name;
- :func:`module_getattr`: a module ``__getattr__`` (PEP 562) that serves renamed module
  attributes (constants, functions) under their old names.

Every rename is also listed in ``CHANGELOG.md``.
"""

from __future__ import annotations

import functools
import warnings
from collections.abc import Callable
from typing import Any

__all__ = ["deprecated_function", "module_getattr"]


def _warn(old: str, new: str, stacklevel: int) -> None:
    warnings.warn(f"{old} is deprecated; use {new}", DeprecationWarning, stacklevel=stacklevel)


def deprecated_function(func: Callable, old: str, new: str) -> Callable:
    """``func`` under its old name ``old`` (dotted), warning that ``new`` replaces it."""

    @functools.wraps(func)
    def alias(*args: Any, **kwargs: Any) -> Any:
        _warn(old, new, 3)
        return func(*args, **kwargs)

    alias.__name__ = alias.__qualname__ = old.rsplit(".", 1)[-1]
    alias.__doc__ = f"Deprecated: use {new}."
    return alias


def module_getattr(module: str, namespace: dict[str, Any], renames: dict[str, str]) -> Callable:
    """A module ``__getattr__`` serving ``renames`` (old name → new name in ``namespace``)."""

    def __getattr__(name: str) -> Any:
        if name in renames:
            new = renames[name]
            _warn(f"{module}.{name}", f"{module}.{new}" if "." not in new else new, 2)
            return namespace[new.rsplit(".", 1)[-1]]
        raise AttributeError(f"module {module!r} has no attribute {name!r}")

    return __getattr__
