# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""A package's public names, written once: imported from their modules on first use (PEP 562).

A package's ``__init__`` names each public name with the module that defines it, and nothing
else; ``__all__``, ``dir()`` and attribute access all come from that one mapping::

    __all__, __getattr__, __dir__ = lazy_exports(__name__, {"truncate": ".api", ...})

A package exported this way can hold Warp-free modules (parameter objects) that the command-line
parsers import without loading the package's kernels. The top-level package also serves its
public subpackages and modules (``submodules=True``): those of its folder, found without
importing them.
"""

from __future__ import annotations

import functools
import importlib
import sys
from collections.abc import Callable, Collection, Mapping
from typing import Any

__all__ = ["lazy_exports"]


def lazy_exports(
    package: str,
    exports: Mapping[str, str],
    *,
    submodules: bool = False,
    hide: Collection[str] = (),
) -> tuple[list[str], Callable[[str], Any], Callable[[], list[str]]]:
    """``__all__``, ``__getattr__`` and ``__dir__`` of a package from its export mapping.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    exports : mapping of str to str
        Public name → module that defines it, relative to ``package`` (``".api"``).
    submodules : bool
        Also serve the package's public submodules (the modules and subpackages of its folder
        whose names do not start with ``_``) as attributes, imported on first access; ``dir()``
        then lists the public names and these submodules only.
    hide : collection of str
        Submodules left out of ``submodules`` (importable, not part of the face).

    Returns
    -------
    tuple
        ``(__all__, __getattr__, __dir__)``: the sorted public names, a module ``__getattr__``
        that imports a name on first access (and caches it in the package), and a ``__dir__``
        listing the public names beside the loaded attributes (or beside the public
        submodules, with ``submodules``).
    """
    names = dict(exports)

    @functools.cache
    def public_submodules() -> frozenset[str]:
        import pkgutil

        found = pkgutil.iter_modules(sys.modules[package].__path__)
        return frozenset(m.name for m in found if not m.name.startswith("_")) - set(hide)

    def __getattr__(name: str) -> Any:
        if name in names:
            value = getattr(importlib.import_module(names[name], package), name)
        elif submodules and name in public_submodules():
            value = importlib.import_module(f".{name}", package)
        else:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        if submodules:
            return sorted(set(names) | public_submodules())
        return sorted(set(names) | set(vars(sys.modules[package])))

    return sorted(names), __getattr__, __dir__
