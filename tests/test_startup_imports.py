# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The main job pays for no import it does not use (issue 40, item 4): ``import warptrunc``, the
import of the ``analyze`` path and a whole ``warptrunc analyze`` run with its two figures load
none of pyvista/VTK, SurfaceTopography, pandas/pyarrow or Dask (each in a fresh process, so
nothing imported by other tests counts); matplotlib only when figures are drawn."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
UNUSED = ("pyvista", "vtk", "vtkmodules", "SurfaceTopography", "pandas", "pyarrow", "dask",
          "distributed")  # fmt: skip


def _loaded(code: str, cwd: Path) -> set[str]:
    report = "import sys, json; print(json.dumps(sorted({m.split('.')[0] for m in sys.modules})))"
    r = subprocess.run([sys.executable, "-c", f"{code}\n{report}"], cwd=cwd, capture_output=True,
                       text=True, timeout=300)  # fmt: skip
    assert r.returncode == 0, r.stderr
    return set(json.loads(r.stdout.strip().splitlines()[-1]))


@pytest.mark.parametrize(
    "code",
    [
        "import warptrunc",
        "import warptrunc.cli.analyze, warptrunc.analysis, warptrunc.plot, warptrunc.stiffness",
    ],
    ids=["package", "analyze-path"],
)
def test_import_loads_nothing_unused(code):
    loaded = _loaded(code, ROOT)
    assert not loaded & set(UNUSED), sorted(loaded & set(UNUSED))
    assert "matplotlib" not in loaded


def test_analyze_with_figures_loads_nothing_unused(tmp_path):
    code = (
        "from warptrunc.cli import main\n"
        f"assert main(['analyze', '--n', '128', '--out', {str(tmp_path / 'o')!r},"
        " '--device', 'cpu']) == 0"
    )
    loaded = _loaded(code, tmp_path)
    assert not loaded & set(UNUSED), sorted(loaded & set(UNUSED))
    assert "matplotlib" in loaded  # the figures were drawn
    assert (tmp_path / "o" / "stiffness.png").exists()
