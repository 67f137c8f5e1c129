# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Sphinx configuration of the warptrunc documentation site.

Build (CPU only, offline, warnings are errors, nitpicky cross-references)::

    pip install -e ".[docs]"
    sphinx-build -W --keep-going -n -b html docs docs/_build/html

Environment:

- ``WARPTRUNC_DOCS_INTERSPHINX=1`` links numpy, scipy, warp, matplotlib, pyvista and pandas
  names to their own documentation through intersphinx. It needs the internet to fetch the
  inventories, so it is off by default: the CI machine is offline, and an inventory that
  cannot be fetched is a warning (an error under ``-W``). Offline, references into those
  packages are plain text (``nitpick_ignore_regex`` below names them).
- ``WARPTRUNC_DOCS_GALLERY=0`` skips running the example gallery (a quick text-only build).
- The site needs no network to read: MathJax is copied into ``_static/mathjax`` from the
  ``sphinx-mathjax-offline`` package (``docs`` extra), and ``docs/check_links.py`` fails when a
  page loads a script, stylesheet or image from the network.
- The gallery runs every example in ``examples/*.py`` at its ``--quick`` size on the CPU
  (``WARPTRUNC_DEVICE=cpu``), so every picture on the site is made by the code shown beside it.

Theme: pydata-sphinx-theme, the theme of numpy, scipy, pandas, pyvista and scikit-image —
the pages our users read next to ours look and navigate the same way (top bar of sections,
left sidebar per section, "on this page" on the right, dark mode), and it renders
sphinx-gallery's thumbnails and numpydoc's tables without extra CSS.
"""

from __future__ import annotations

import inspect
import os
import shutil
import subprocess
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS / "_ext"))

# the docs never need a GPU: autodoc imports and the gallery run on the CPU
os.environ.setdefault("WARPTRUNC_DEVICE", "cpu")
os.environ.setdefault("MPLBACKEND", "Agg")
os.environ.pop("DISPLAY", None)

import warptrunc  # noqa: E402

import apigen  # noqa: E402
import layout  # noqa: E402
import paramtables  # noqa: E402
import perftables  # noqa: E402
import xref  # noqa: E402

project = "warptrunc"
author = "warptrunc developers"
copyright = "2026, warptrunc developers"
release = warptrunc.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "sphinx.ext.linkcode",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_parser",
    "sphinx_copybutton",
    "sphinx_gallery.gen_gallery",
    "xref",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_generated", "Thumbs.db", ".DS_Store"]
templates_path = ["_templates"]
nitpicky = True

# -- MyST ------------------------------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
suppress_warnings = [
    # README-style relative links to repository files outside docs/ (e.g. ../examples/x.py)
    # are written as plain links to GitHub below; MyST would otherwise try them as documents
]

# -- API reference ---------------------------------------------------------------------------
shutil.rmtree(DOCS / "api" / "generated", ignore_errors=True)  # stubs of renamed objects
API_PAGES = apigen.write_pages(DOCS)
xref.set_aliases(*apigen.collect())
autosummary_generate = True
autosummary_imported_members = False
autodoc_typehints = "none"  # numpydoc docstrings give types, shapes and units
autodoc_default_options = {"member-order": "bysource"}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks = set()  # tests/test_docstrings.py validates

# -- measured tables from the run records of benchmarks/records/ ---------------------------
perftables.write_tables(DOCS)

# -- the module list of guide/layout.md, from the package tree ------------------------------
layout.write_page(DOCS)

# -- parameter tables from the declarations of WMSpec and Material (warptrunc.params) --------
paramtables.write_tables(DOCS)

# -- guide pages added by other work (e.g. guide/elastic_comparison.md) join the guide's toctree
GUIDE_ORDER = ["index", "getting_started", "method", "islands", "fractal", "scans", "large_maps",
               "sweeps", "elastic", "pictures", "command_line", "parameters", "reproduce",
               "performance", "layout"]


def _guide_toctree() -> set[str]:
    """Pages named in the toctree of guide/index.md (not listed again under "More guides")."""
    text = (DOCS / "guide" / "index.md").read_text()
    names: set[str] = set()
    for block in text.split("```{toctree}")[1:]:
        names |= {ln.strip() for ln in block.split("```")[0].splitlines()
                  if ln.strip() and not ln.strip().startswith(":")}
    return names


def _guide_extra() -> None:
    listed = set(GUIDE_ORDER) | _guide_toctree()
    extra = sorted(p.stem for p in (DOCS / "guide").glob("*.md") if p.stem not in listed)
    text = ("```{toctree}\n:maxdepth: 2\n:caption: More guides\n\n" + "\n".join(extra)
            + "\n```\n") if extra else ""
    dest = DOCS / "_generated" / "guide_extra.md"
    if not dest.is_file() or dest.read_text() != text:
        dest.write_text(text)


_guide_extra()

# -- intersphinx (optional: needs the internet) ----------------------------------------------
INTERSPHINX = os.environ.get("WARPTRUNC_DOCS_INTERSPHINX", "0") == "1"
intersphinx_mapping = {}
if INTERSPHINX:
    intersphinx_mapping = {
        "python": ("https://docs.python.org/3", None),
        "numpy": ("https://numpy.org/doc/stable/", None),
        "scipy": ("https://docs.scipy.org/doc/scipy/", None),
        "matplotlib": ("https://matplotlib.org/stable/", None),
        "pandas": ("https://pandas.pydata.org/docs/", None),
        "pyvista": ("https://docs.pyvista.org/", None),
        "warp": ("https://nvidia.github.io/warp/", None),
    }
    nitpick_ignore_regex = []
else:
    # Offline build: names in these packages would resolve through intersphinx; they are
    # the only targets left unresolved on purpose.
    nitpick_ignore_regex = [
        (r"py:.*", r"(numpy|np|scipy|matplotlib|pandas|pd|pyvista|pv|warp|wp|dask|"
                   r"distributed|pyarrow|cupy|SurfaceTopography|ContactMechanics|tqdm|"
                   r"pathlib|os|json|concurrent|typing|collections|dataclasses|argparse|"
                   r"contextlib|threading|multiprocessing|zlib|hashlib)(\..*)?"),
        # private modules (warptrunc._support.results, ...) are not part of the API reference
        (r"py:.*", r"warptrunc\._.*"),
        # Python builtins, which intersphinx to the Python docs links when online
        (r"py:.*", r"(int|float|str|bool|bytes|dict|list|tuple|set|frozenset|object|None|"
                   r"callable|iterable|hash|Path|ValueError|TypeError|RuntimeError|OSError|"
                   r"MemoryError|KeyError|Exception|BaseException|FileNotFoundError|"
                   r"KeyboardInterrupt|NotImplementedError|ImportError)"),
    ]

# -- sphinx-gallery --------------------------------------------------------------------------
import gallery  # noqa: E402

GALLERY = os.environ.get("WARPTRUNC_DOCS_GALLERY", "1") != "0"
sphinx_gallery_conf = {
    "examples_dirs": str(gallery.stage_sources().relative_to(DOCS)),
    "gallery_dirs": "gallery",
    "filename_pattern": gallery.filename_pattern(),  # which examples are executed
    "ignore_pattern": gallery.ignore_pattern(),      # examples whose extras are missing
    "plot_gallery": "True" if GALLERY else "False",
    "reset_argv": "gallery.reset_argv",
    "image_scrapers": ("gallery.png_scraper",),
    "within_subsection_order": "FileNameSortKey",
    "doc_module": ("warptrunc",),
    "backreferences_dir": "api/backreferences",
    "reference_url": {"warptrunc": None},
    "remove_config_comments": True,
    "download_all_examples": False,
    "show_memory": False,
    "capture_repr": (),
    "min_reported_time": 1,
    # no sg_execution_times pages: they load jQuery and DataTables from CDNs (the site must
    # work offline, docs/check_links.py checks), and the timings of a CPU build say little
    "write_computation_times": False,  # (the stale pages of an earlier build are removed below)
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "copyfile_regex": "",
}

for _stale in (DOCS / "sg_execution_times.rst", DOCS / "gallery" / "sg_execution_times.rst"):
    _stale.unlink(missing_ok=True)

# -- linkcode: "[source]" links to the repository, as pyvista does ---------------------------
GITHUB = "https://github.com/warptrunc/warptrunc"


def _commit() -> str:
    try:
        return subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True,
                              text=True, check=True).stdout.strip() or "main"
    except (OSError, subprocess.CalledProcessError):
        return "main"


COMMIT = _commit()


def linkcode_resolve(domain: str, info: dict) -> str | None:
    """URL of the source lines of a documented Python object (``sphinx.ext.linkcode``)."""
    if domain != "py" or not info.get("module"):
        return None
    obj = sys.modules.get(info["module"])
    for part in info["fullname"].split("."):
        obj = getattr(obj, part, None)
        if obj is None:
            return None
    obj = inspect.unwrap(obj)
    if isinstance(obj, property):
        obj = obj.fget
    try:
        fn = inspect.getsourcefile(obj)
        src, start = inspect.getsourcelines(obj)
    except (TypeError, OSError):
        return None
    if fn is None:
        return None
    try:
        rel = Path(fn).resolve().relative_to(ROOT)
    except ValueError:
        return None
    return f"{GITHUB}/blob/{COMMIT}/{rel.as_posix()}#L{start}-L{start + len(src) - 1}"


# -- maths: MathJax bundled with the site, so "The method" reads right offline --------------
# sphinx-mathjax-offline (PyPI, in the `docs` extra) ships MathJax 3's files; we copy only what
# the TeX→CommonHTML renderer loads (tex-chtml.js, its fonts, the TeX extensions it may
# autoload) into _static/mathjax, and point sphinx.ext.mathjax there instead of a CDN.
# docs/check_links.py fails the build when any page loads a script from the network.
MATHJAX_FILES = ("tex-chtml.js", "output/chtml", "input/tex/extensions", "a11y", "ui",
                 "sre")


def _mathjax_source() -> Path:
    import importlib.util

    spec = importlib.util.find_spec("sphinx-mathjax-offline")
    if spec is None or not spec.submodule_search_locations:
        raise RuntimeError("the docs bundle MathJax from the sphinx-mathjax-offline package: "
                           'pip install -e ".[docs]"')
    return Path(next(iter(spec.submodule_search_locations))) / "static" / "mathjax"


def _bundle_mathjax() -> None:
    src, dest = _mathjax_source(), DOCS / "_generated" / "static" / "mathjax"
    for name in MATHJAX_FILES:
        if not (src / name).exists():
            continue
        if (src / name).is_dir():
            shutil.copytree(src / name, dest / name, dirs_exist_ok=True)
        else:
            dest.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src / name, dest / name)


_bundle_mathjax()
mathjax_path = "mathjax/tex-chtml.js"  # relative: under _static of the built site

# -- HTML ------------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"warptrunc {release}"
html_static_path = ["_static", "_generated/static"]
html_css_files = ["warptrunc.css"]
html_js_files = ["wide_tables.js"]  # the note above a table wider than the column
html_logo = None
html_show_sourcelink = False
html_theme_options = {
    "github_url": GITHUB,
    "navbar_align": "left",
    "show_toc_level": 2,
    "navigation_with_keys": False,
    "header_links_before_dropdown": 8,
    # the parameters page gives its width to the presets table (12 columns) instead of a
    # page outline on the right
    "secondary_sidebar_items": {"**": ["page-toc"], "guide/parameters": []},
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_context = {"default_mode": "light"}
html_sidebars = {"index": [], "changelog": [], "reproduction": []}
copybutton_prompt_text = r">>> |\.\.\. |\$ "
copybutton_prompt_is_regexp = True
copybutton_exclude = ".linenos, .gp, .go"


def _copy_repo_files(app):
    """Nothing to copy: Sphinx finds the images of benchmarks/records/ by their relative paths."""
    return None


def setup(app):
    app.connect("builder-inited", _copy_repo_files)
