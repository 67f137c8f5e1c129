# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The public modules of warptrunc: the API reference (``docs/_ext/apigen.py``) documents
them and ``tests/test_docstrings.py`` validates their docstrings, from this one list."""

from __future__ import annotations

import pkgutil

__all__ = ["SKIP_PREFIXES", "public_modules"]

SKIP_PREFIXES = ("warptrunc.kernels", "warptrunc.cli")
"""Packages left out: device code, and the command line (documented by its ``--help``)."""


def public_modules() -> list[str]:
    """Names of the public modules of warptrunc, sorted: every module below the package whose
    dotted name has no part starting with ``_``, except those under ``SKIP_PREFIXES``."""
    import warptrunc

    names = ["warptrunc"]
    for info in pkgutil.walk_packages(warptrunc.__path__, "warptrunc."):
        name = info.name
        if name.startswith(SKIP_PREFIXES):
            continue
        if any(part.startswith("_") for part in name.split(".")[1:]):
            continue
        names.append(name)
    return sorted(names)
