# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The public functions take parameter objects, not their unpacked fields: none outside the
kernels takes more than 10 parameters (a walk of the package's source)."""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "warptrunc"
MAX_PARAMETERS = 10


def _wide(path: Path) -> list[str]:
    out = []
    tree = ast.parse(path.read_text())

    def walk(node, owner: str | None) -> None:
        for n in ast.iter_child_nodes(node):
            if isinstance(n, ast.ClassDef):
                if not n.name.startswith("_"):
                    walk(n, n.name)
            elif isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)):
                if n.name.startswith("_") and n.name != "__init__":
                    continue
                a = n.args
                names = [x.arg for x in (*a.posonlyargs, *a.args, *a.kwonlyargs)]
                if owner is not None and names[:1] in (["self"], ["cls"]):
                    names = names[1:]
                count = len(names) + (a.vararg is not None) + (a.kwarg is not None)
                if count > MAX_PARAMETERS:
                    out.append(
                        f"{path.relative_to(PACKAGE.parent)}:{n.lineno} "
                        f"{owner + '.' if owner else ''}{n.name} ({count})"
                    )

    walk(tree, None)
    return out


def test_no_public_function_takes_more_than_ten_parameters():
    wide = []
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE).parts
        if any(part.startswith("_") and part != "__init__.py" for part in rel):
            continue  # private modules and packages
        wide += _wide(path)
    assert wide == [], "\n".join(wide)
