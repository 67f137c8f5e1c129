# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""``pip install .`` brings what the uses need (issue 41, item 2).

The reference is the source itself: every third-party module that warptrunc imports (at the
top of a module or inside a function, found with :mod:`ast`) must come with the base install
(a dependency in pyproject.toml, or a dependency of one) unless it is one of the few optional
ones, each of which belongs to an extra or is named by the error that asks for it. The
sweep's libraries and the instrument readers are base dependencies; ``all`` holds every
extra that runs on any machine. That importing them stays lazy is tests/test_import_weight.py.
"""

from __future__ import annotations

import ast
import importlib.metadata as md
import re
import sys
from pathlib import Path

import pytest

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10: tomli, a base dependency there
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]

OPTIONAL = {
    "ContactMechanics": "bem",  # bem-check --solver contactmechanics
    "cupy": "gpu",
    "cupyx": "gpu",
    "dask_cuda": None,  # --workers: dask-cuda's LocalCUDACluster where installed, else LocalCluster
    "imageio": None,  # MP4 animations only; the error names pip install imageio imageio-ffmpeg
    "jax": "distributed",  # contact_solver(..., devices=n): one problem over several devices
    "tomli": None,  # Python 3.10 only: a base dependency with a marker
}
"""Third-party modules that the base install may lack, and the extra that brings each."""


def _norm(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def _name(req: str) -> str:
    return _norm(re.split(r"[\s\[<>=!~;]", req, maxsplit=1)[0])


def _imported_modules() -> set[str]:
    mods: set[str] = set()
    for p in [*(ROOT / "warptrunc").rglob("*.py"), *(ROOT / "kernels").rglob("*.py")]:
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                mods.update(a.name.split(".")[0] for a in node.names)
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                mods.add(node.module.split(".")[0])
    return {
        m
        for m in mods
        if m not in sys.stdlib_module_names and m not in ("warptrunc", "kernels", "__future__")
    }


def _extras(req: str) -> set[str]:
    m = re.match(r"\s*[\w.-]+\s*\[([^\]]*)\]", req)
    return {e.strip() for e in m.group(1).split(",")} if m else set()


def _closure(reqs: list[str]) -> set[str]:
    """The distributions that the requirements ``reqs`` bring, themselves included, with the
    extras they name (``dask[distributed]``); requirements of other extras left out."""
    seen: set[tuple[str, str]] = set()
    todo = [(_name(r), e) for r in reqs for e in ("", *_extras(r))]
    while todo:
        n, extra = todo.pop()
        if (n, extra) in seen:
            continue
        seen.add((n, extra))
        try:
            sub = md.requires(n) or []
        except md.PackageNotFoundError:
            continue
        for r in sub:
            want = re.search(r"extra\s*==\s*['\"]([\w-]+)['\"]", r)
            if (want.group(1) if want else "") == extra:
                todo += [(_name(r), e) for e in ("", *_extras(r))]
    return {n for n, _ in seen}


def test_every_imported_library_comes_with_the_base_install_or_an_extra():
    installed = _closure(PROJECT["dependencies"])
    where = md.packages_distributions()
    missing = []
    for m in sorted(_imported_modules()):
        if m in OPTIONAL:
            extra = OPTIONAL[m]
            assert extra is None or extra in PROJECT["optional-dependencies"], (m, extra)
            continue
        dists = {_norm(d) for d in where.get(m, [])}
        assert dists, f"{m} is imported but not installed here; add it to pyproject.toml"
        if not dists & installed:
            missing.append((m, sorted(dists)))
    assert not missing, f"imported, but not brought by `pip install .`: {missing}"


@pytest.mark.parametrize(
    "dist",
    ["pandas", "pyarrow", "dask", "SurfaceTopography"],
    ids=["sweep-store", "sweep-parquet", "sweep-dask", "instrument-readers"],
)
def test_sweeps_and_instrument_readers_are_base_dependencies(dist):
    reqs = {_name(r): r for r in PROJECT["dependencies"]}
    assert _norm(dist) in reqs
    if dist == "dask":
        assert "distributed" in reqs["dask"]  # the Dask engine (--workers, --scheduler)


def test_all_extra_holds_every_extra_that_runs_anywhere():
    extras = PROJECT["optional-dependencies"]
    inside = {m.group(1) for r in extras["all"] for m in re.finditer(r"warptrunc\[([\w,-]+)\]", r)}
    inside = {e for group in inside for e in group.split(",")}
    # gpu needs a CUDA device; test and docs are for developers
    runtime = set(extras) - {"all", "gpu", "test", "docs"}
    assert runtime and inside == runtime
    assert "sweep" not in extras and "scans" not in extras  # both are in the base install


def test_readme_first_section_says_what_the_install_brings():
    intro = (ROOT / "README.md").read_text().split("\n## ", 1)[0]
    for word in (
        "`pip install .`",
        "SurfaceTopography",
        "`warptrunc sweep`",
        "`all`",
        'pip install ".[all]"',
    ):
        assert word in intro, word
