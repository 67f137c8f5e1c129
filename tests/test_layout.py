# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The package's layout follows its concerns: every module says in its docstring which concern it
holds; no folder holds more than 15 modules (a larger family is a sub-package); no folder holds a
family of more than three modules whose names share a prefix (``indentation_parts``,
``indentation_pieces``, ... belong in a sub-package ``indentation/``). A module's length is not a
rule: one concern stays in one module.

Imports point down four floors, commands → studies → core → support (:data:`FLOORS`), never
up, and no import circle joins two packages or two modules (every import counts, those inside
functions too; the source is read with :mod:`ast`, nothing is imported)."""

from __future__ import annotations

import ast
import functools
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = (ROOT / "warptrunc", ROOT / "kernels")
MAX_MODULES = 15
MAX_FAMILY = 3

FLOORS = {
    0: {"_support", "params", "kernels"},
    1: {
        "material",
        "wm_params",
        "surface",
        "wm",
        "selfaffine",
        "truncation",
        "stiffness",
        "islands",
        "descriptors",
        "spectra",
        "fractal",
        "slope",
        "plausibility",
        "robust",
        "io",
        "contact",
        "presets",
        "theory",
    },
    2: {"analysis", "calibrate", "compare", "indent", "sweep", "reproduce", "plot", "render"},
    3: {"cli", "__main__", "warptrunc"},
}
"""Floor of each top-level package or module of ``warptrunc`` (``warptrunc``: the package's
face, ``__init__.py``): 0 support (helpers, parameter declarations, kernels), 1 core (surfaces,
their analysis, the contact solver), 2 studies (commands' computations, their figures), 3
commands. A new top-level package or module names its floor here."""

CIRCLES: set[frozenset[str]] = set()
"""Module circles kept on purpose: none."""


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


def _module_name(p: Path) -> str:
    parts = list(p.relative_to(ROOT).with_suffix("").parts)
    if parts[0] == "kernels":
        parts.insert(0, "warptrunc")
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@functools.cache
def _imports() -> dict[str, set[str]]:
    """Module → the warptrunc modules it imports (every import but ``if TYPE_CHECKING:``)."""
    files = {_module_name(p): p for top in PACKAGES for p in top.rglob("*.py")}
    graph = {}
    for name, p in files.items():
        tree = ast.parse(p.read_text(encoding="utf-8"))
        skip = {
            id(n)
            for node in ast.walk(tree)
            if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)
            for n in ast.walk(node)
        }
        package = name if p.name == "__init__.py" else name.rpartition(".")[0]
        found = set()
        for node in ast.walk(tree):
            if id(node) in skip:
                continue
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[: len(package.split(".")) - node.level + 1]
                    target = ".".join([*base, node.module] if node.module else base)
                else:
                    target = node.module or ""
                for alias in node.names:
                    full = f"{target}.{alias.name}"
                    found.add(full if full in files else target)
            elif isinstance(node, ast.Import):
                found |= {a.name for a in node.names}
        graph[name] = {m for m in found if m in files and m != name}
    return graph


def _top(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "warptrunc"


def _circles(graph: dict[str, set[str]]) -> list[frozenset[str]]:
    """The strongly connected components of more than one node (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = set()
            while True:
                w = stack.pop()
                on.discard(w)
                comp.add(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(frozenset(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_every_top_level_package_has_a_floor():
    floor = {p for ps in FLOORS.values() for p in ps}
    tops = {_top(m) for m in _imports()}
    assert tops - floor == set(), "name the floor of each new package in FLOORS"


def test_imports_point_down_the_floors():
    floor = {p: f for f, ps in FLOORS.items() for p in ps}
    up = sorted(
        f"{a} imports {b}"
        for a, targets in _imports().items()
        for b in targets
        if _top(a) in floor and _top(b) in floor and floor[_top(b)] > floor[_top(a)]
    )
    assert up == []


def test_no_import_circle():
    graph = _imports()
    packages = {}
    for a, targets in graph.items():
        for b in targets:
            if _top(a) != _top(b):
                packages.setdefault(_top(a), set()).add(_top(b))
    assert _circles(packages) == []
    # a module's own package __init__ runs first anyway: that edge is no circle
    modules = {a: {b for b in t if not a.startswith(b + ".")} for a, t in graph.items()}
    assert set(_circles(modules)) <= CIRCLES
