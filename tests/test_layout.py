# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The package's layout follows its concerns: every module says in its docstring which concern it
holds; no folder holds more than 15 modules (a larger family is a sub-package); no folder holds a
family of more than three modules whose names share a prefix (``indentation_parts``,
``indentation_pieces``, ... belong in a sub-package ``indentation/``). A module's length is not a
rule: one concern stays in one module."""

from __future__ import annotations

import ast
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = (ROOT / "warptrunc", ROOT / "kernels")
MAX_MODULES = 15
MAX_FAMILY = 3


def _folders() -> list[Path]:
    return sorted({p.parent for top in PACKAGES for p in top.rglob("*.py")})


def _modules(folder: Path) -> list[Path]:
    return sorted(p for p in folder.glob("*.py") if p.name != "__init__.py")


def test_every_module_says_its_concern():
    missing = []
    for top in PACKAGES:
        for p in sorted(top.rglob("*.py")):
            doc = ast.get_docstring(ast.parse(p.read_text(encoding="utf-8")))
            if not doc or len(doc.split()) < 4:
                missing.append(str(p.relative_to(ROOT)))
    assert missing == []


def test_no_folder_holds_more_than_fifteen_modules():
    big = {str(f.relative_to(ROOT)): len(_modules(f)) for f in _folders()}
    assert len(big) > 10  # the walk found the package
    assert {f: n for f, n in big.items() if n > MAX_MODULES} == {}


def test_no_family_of_prefixed_module_names():
    families = {}
    for f in _folders():
        prefixes = Counter(
            p.stem.lstrip("_").split("_")[0] for p in _modules(f) if "_" in p.stem.lstrip("_")
        )
        many = {k: n for k, n in prefixes.items() if n > MAX_FAMILY}
        if many:
            families[str(f.relative_to(ROOT))] = many
    assert families == {}
