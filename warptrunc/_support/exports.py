# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""A package's public names, written once: imported from their modules on first use (PEP 562).

A package's ``__init__`` names each public name with the module that defines it, and nothing
else; ``__all__``, ``dir()`` and attribute access all come from that one mapping::

    __all__, __getattr__, __dir__ = lazy_exports(__name__, {"truncate": ".api", ...})

A package exported this way can hold Warp-free modules (parameter objects) that the command-line
parsers import without loading the package's kernels.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["lazy_exports"]


def lazy_exports(
    package: str, exports: Mapping[str, str]
) -> tuple[list[str], Callable[[str], Any], Callable[[], list[str]]]:
    """``__all__``, ``__getattr__`` and ``__dir__`` of a package from its export mapping.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    exports : mapping of str to str
        Public name → module that defines it, relative to ``package`` (``".api"``).

    Returns
    -------
    tuple
        ``(__all__, __getattr__, __dir__)``: the sorted public names, a module ``__getattr__``
        that imports a name on first access (and caches it in the package), and a ``__dir__``
        listing the public names beside the loaded attributes.
    """
    names = dict(exports)

    def __getattr__(name: str) -> Any:
        if name not in names:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(names[name], package), name)
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        return sorted(set(names) | set(vars(sys.modules[package])))

    return sorted(names), __getattr__, __dir__
