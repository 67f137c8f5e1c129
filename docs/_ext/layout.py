# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The module list of the code-layout page, generated from the package tree (run by conf.py).

Walks ``warptrunc/`` and ``kernels/`` and writes ``docs/_generated/layout.md``: one row per
sub-package and module with the first sentence of its docstring, read with :mod:`ast` (nothing
is imported), so the page follows every module that is added, moved or removed.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
ABBREVIATIONS = {"fig", "figs", "eq", "eqs", "e.g", "i.e", "cf", "vs", "no", "al", "approx"}
"""Words after which a full stop does not end the first sentence (``Fig. 4``, ``e.g.``)."""


def summary(path: Path) -> str:
    """The first sentence of a module's docstring (its first paragraph, up to a full stop)."""
    try:
        doc = ast.get_docstring(ast.parse(path.read_text()), clean=True) or ""
    except (SyntaxError, UnicodeDecodeError):
        return ""
    para = " ".join(doc.strip().split("\n\n", 1)[0].split())
    end = len(para)
    for m in re.finditer(r"\.(?=\s|$)", para):
        word = re.search(r"(\S+)$", para[: m.start()])
        if not word or word.group(1).lower().strip("([").rstrip(".") not in ABBREVIATIONS:
            end = m.start() + 1
            break
    text = re.sub(r":[\w:]+:`~?\.?([^`]+)`", r"`\1`", para[:end])  # a Sphinx role: its target
    return text.replace("|", "\\|")


def rows(package: Path, prefix: str, depth: int = 0) -> list[tuple[str, str]]:
    """(path shown, summary) of a package's modules and sub-packages, depth first."""
    out = []
    entries = sorted(
        p
        for p in package.iterdir()
        if (p.suffix == ".py" and not p.name.startswith("__"))
        or (p.is_dir() and (p / "__init__.py").is_file())
    )
    for p in entries:
        if p.is_dir():
            out.append((f"{prefix}{p.name}/", summary(p / "__init__.py")))
            out += rows(p, f"{prefix}{p.name}/", depth + 1)
        else:
            out.append((f"{prefix}{p.name}", summary(p)))
    return out


def layout_table(root: Path = ROOT) -> str:
    """Markdown tables of ``warptrunc/`` and ``kernels/``: every module and what it holds."""
    text = []
    for name in ("warptrunc", "kernels"):
        pkg = root / name
        if not pkg.is_dir():
            continue
        lines = [f"| `{name}/` | what it holds |", "|---|---|"]
        lines += [f"| `{path}` | {what} |" for path, what in rows(pkg, "")]
        text.append("\n".join(lines) + "\n")
    return "\n".join(text)


def write_page(docs: Path) -> Path:
    """Write ``docs/_generated/layout.md``; returns its path."""
    out = docs / "_generated"
    out.mkdir(exist_ok=True)
    dest = out / "layout.md"
    text = layout_table(docs.parent)
    if not dest.is_file() or dest.read_text() != text:
        dest.write_text(text)
    return dest
