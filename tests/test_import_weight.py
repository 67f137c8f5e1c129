# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Start-up stays light: ``import warptrunc``, its subpackages (plotting and rendering modules
included: they import matplotlib/pyvista inside their functions), the CLI's parser and
``analyze --no-plot`` load none of the plotting, rendering, data-frame, cluster, scan-reader or
progress-bar libraries (each in a fresh process, so nothing imported by other tests counts)."""

import subprocess
import sys
from pathlib import Path

import pytest
from import_helpers import modules_after

ROOT = Path(__file__).resolve().parents[1]
HEAVY = (
    "matplotlib",
    "pyvista",
    "vtk",
    "vtkmodules",
    "pandas",
    "pyarrow",
    "dask",
    "distributed",
    "cupy",
    "SurfaceTopography",
    "tqdm",
)


def _loaded(code: str, cwd: Path) -> str:
    return str(sorted(modules_after(code, cwd) & set(HEAVY)))


@pytest.mark.parametrize(
    "code",
    [
        "import warptrunc",
        "import warptrunc.truncation, warptrunc.islands, warptrunc.io, warptrunc.io.vtk, "
        "warptrunc.fractal, warptrunc.descriptors, warptrunc.calibrate, warptrunc.render, "
        "warptrunc.plot, warptrunc.sweep, warptrunc.cli.sweep",
        "from warptrunc.cli import build_parser; build_parser()",  # what `warptrunc --help` runs
    ],
    ids=["package", "subpackages", "cli-parser"],
)
def test_import_loads_no_heavy_library(code):
    assert _loaded(code, ROOT) == "[]"


def test_analyze_without_plots_loads_no_matplotlib(tmp_path):
    # 128² and 200 increments to 10 % R_t: enough contact pixels for the power-law fit
    code = (
        "from warptrunc.cli import main\n"
        f"assert main(['analyze', '--n', '128', '--out', {str(tmp_path / 'o')!r}, '--no-plot',"
        " '--device', 'cpu']) == 0"
    )
    assert _loaded(code, tmp_path) == "[]"
    assert (tmp_path / "o" / "fit.json").exists()


@pytest.mark.parametrize(
    "code",
    [
        "import warptrunc",
        "from warptrunc.cli import build_parser; build_parser(['--help'])",
        "from warptrunc.cli import build_parser; build_parser(['generate', '--help'])",
    ],
    ids=["package", "top-level-help", "generate-parser"],
)
def test_help_and_import_load_no_warp(code):
    """``import warptrunc`` and ``warptrunc --help`` import neither Warp nor NumPy (public
    names load on first use), so the help answers at once; building one sub-command's parser
    loads only what that sub-command's module imports (Warp, for ``generate``)."""
    loaded = str(sorted(modules_after(code, ROOT) & {"warp", "numpy"}))
    expect = "['numpy', 'warp']" if "generate" in code else "[]"
    assert loaded == expect


def test_lazy_names_resolve_to_their_objects():
    """Every name of ``warptrunc.__all__`` resolves (lazily) to the object its module defines;
    ``warptrunc.calibrate`` stays the function after its module is imported."""
    code = (
        "import importlib, sys, warptrunc\n"
        "import warptrunc.calibrate\n"
        "m = sys.modules['warptrunc.calibrate']\n"
        "assert warptrunc.calibrate is m.calibrate, warptrunc.calibrate\n"
        "for n in warptrunc.__all__:\n"
        "    obj = getattr(warptrunc, n)\n"
        "    mod = importlib.import_module(warptrunc._EXPORTS[n], 'warptrunc')\n"
        "    assert obj is getattr(mod, n), n\n"
        "print('ok')"
    )
    r = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300
    )
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr
