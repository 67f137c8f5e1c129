# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""How sphinx-gallery runs ``examples/*.py`` for the site (used by ``docs/conf.py``).

Each example is a command-line script. sphinx-gallery executes it as ``__main__`` with
``sys.argv`` from :func:`reset_argv`: ``--quick --no-show --out out/<stem>``, the small CPU size
the tests also use (``tests/test_examples.py``). sphinx-gallery runs each example in its own
folder (``docs/_build/gallery-src``), so ``--out`` is relative and what an example prints
("wrote out/quickstart/curve.csv, ...") reads as it would for a user, with no path of the
build machine in it. The examples write their
figures as PNG files; :func:`png_scraper` puts the PNGs the example wrote into the page, so
every picture in the gallery is made by the code shown above it.

Examples whose optional packages are missing (``render_truncated_section``: pyvista;
``parametric_sweep``: pandas and pyarrow) are shown but not executed; ``scan_survey`` needs
the measured scans of ``../shared`` and is never executed by the build.
"""

from __future__ import annotations

import importlib.util
import re
import shutil
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1]
SRC = DOCS / "_build" / "gallery-src"  # the user examples only (not benchmarks/, gpu_checks/)
OUT = SRC / "out"  # the examples' outputs: sphinx-gallery ignores a folder without a header

HEADER = """\
Gallery of examples
===================

Runnable scripts, one per concern, in ``examples/`` of the repository. Each page below was
made by running the script shown on it at its ``--quick`` size on the CPU while the site was
built (``python examples/<name>.py --quick --no-show --out <folder>``); run it without
``--quick`` for the sizes its docstring names, and with ``--device cuda:0`` on a GPU.
The timing studies behind the :doc:`performance tables </guide/performance>` live in
``examples/benchmarks/`` and the GPU runs in ``examples/gpu_checks/``; they are not part of the
gallery.
"""

NEEDS = {
    "render_truncated_section": ("pyvista",),
    "parametric_sweep": ("pandas", "pyarrow"),
}
NEVER_RUN = ("scan_survey",)  # needs measured scans that are not part of the repository
# arguments instead of --quick where --quick is too small to show what the example is about
# (256² with a 3-pixel fit range draws a staircase); 1024² takes a second on 2 cores
ARGS = {"quickstart": ["--n", "1024"]}


def _missing(stem: str) -> bool:
    return any(importlib.util.find_spec(m) is None for m in NEEDS.get(stem, ()))


def stage_sources() -> Path:
    """Copy ``examples/*.py`` (changed files only) and the gallery header into :data:`SRC`.

    sphinx-gallery would take ``examples/benchmarks/`` and ``examples/gpu_checks/`` (which have a
    README) for subsections; the staged folder holds the user examples only.
    """
    SRC.mkdir(parents=True, exist_ok=True)
    wanted = {"GALLERY_HEADER.rst": HEADER}
    for p in sorted((DOCS.parent / "examples").glob("*.py")):
        wanted[p.name] = p.read_text()
    for name, text in wanted.items():
        dest = SRC / name
        if not dest.is_file() or dest.read_text() != text:
            dest.write_text(text)
    for stale in SRC.iterdir():
        if stale.name not in wanted and stale.is_file():
            stale.unlink()
    return SRC


def filename_pattern() -> str:
    """Regular expression of the example files the build executes."""
    examples = DOCS.parent / "examples"
    run = [p.stem for p in sorted(examples.glob("*.py"))
           if p.stem not in NEVER_RUN and not _missing(p.stem)]
    return "/(" + "|".join(re.escape(s) for s in run) + r")\.py$"


def ignore_pattern() -> str:
    """Regular expression of files sphinx-gallery must not show (private helpers)."""
    return r"(__init__|/_[^/]*)\.py$"


def reset_argv(gallery_conf, script_vars) -> list[str]:
    """Command-line arguments of an example in the gallery: its ``--quick`` size on the CPU."""
    stem = Path(script_vars["src_file"]).stem
    shutil.rmtree(OUT / stem, ignore_errors=True)
    # relative to the folder sphinx-gallery runs the example in (SRC): no absolute path in
    # what the example prints
    return [*ARGS.get(stem, ["--quick"]), "--no-show", "--out", f"{OUT.name}/{stem}"]


def png_scraper(block, block_vars, gallery_conf) -> str:
    """sphinx-gallery image scraper: the PNG files the example wrote into its ``--out``."""
    from sphinx_gallery.scrapers import figure_rst

    stem = Path(block_vars["src_file"]).stem
    out = OUT / stem
    pngs = sorted(out.rglob("*.png")) if out.is_dir() else []
    paths = []
    for png, dest in zip(pngs, block_vars["image_path_iterator"]):
        shutil.copyfile(png, dest)
        paths.append(dest)
    return figure_rst(paths, gallery_conf["src_dir"])
