# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The public modules of warptrunc: the API reference (``docs/_ext/apigen.py``) documents
them and ``tests/test_docstrings.py`` validates their docstrings, from this one list."""

from __future__ import annotations

from pathlib import Path

__all__ = ["SKIP_PREFIXES", "public_modules"]

SKIP_PREFIXES = ("warptrunc.kernels", "warptrunc.cli")
"""Packages left out: device code, and the command line (documented by its ``--help``)."""

PACKAGE = Path(__file__).resolve().parents[1]
"""The folder of the package ``warptrunc``."""


def _walk(folder: Path, name: str) -> list[str]:
    """Dotted names of the modules and packages below ``folder`` (the package ``name``),
    read from the file tree: nothing is imported."""
    names = []
    for p in sorted(folder.iterdir()):
        if p.is_dir() and (p / "__init__.py").is_file():
            names += [f"{name}.{p.name}", *_walk(p, f"{name}.{p.name}")]
        elif p.suffix == ".py" and p.stem != "__init__":
            names.append(f"{name}.{p.stem}")
    return names


def public_modules() -> list[str]:
    """Names of the public modules of warptrunc, sorted: every module below the package whose
    dotted name has no part starting with ``_``, except those under ``SKIP_PREFIXES``."""
    names = ["warptrunc"]
    for name in _walk(PACKAGE, "warptrunc"):
        if name.startswith(SKIP_PREFIXES):
            continue
        if any(part.startswith("_") for part in name.split(".")[1:]):
            continue
        names.append(name)
    return sorted(names)
