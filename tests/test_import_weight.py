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

ROOT = Path(__file__).resolve().parents[1]
HEAVY = (
    "matplotlib", "pyvista", "vtk", "vtkmodules", "pandas", "pyarrow", "dask", "distributed",
    "cupy", "SurfaceTopography", "tqdm",
)  # fmt: skip
REPORT = f"import sys; print(sorted({{m.split('.')[0] for m in sys.modules}} & set({HEAVY!r})))"


def _loaded(code: str, cwd: Path) -> str:
    r = subprocess.run(
        [sys.executable, "-c", f"{code}\n{REPORT}"], cwd=cwd, capture_output=True, text=True,
        timeout=300,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    return r.stdout.strip().splitlines()[-1]


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
