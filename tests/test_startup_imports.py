# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The main job pays for no import it does not use (issue 40, item 4): ``import warptrunc``, the
import of the ``analyze`` path and a whole ``warptrunc analyze`` run with its two figures load
none of pyvista/VTK, SurfaceTopography, pandas/pyarrow or Dask (each in a fresh process, so
nothing imported by other tests counts); matplotlib only when figures are drawn, and then in the
figure process (``warptrunc.plot._worker``), which loads no Warp either; the parser of
``analyze`` loads no Warp, so that process starts before Warp's import."""

from pathlib import Path

import pytest
from import_helpers import modules_after

ROOT = Path(__file__).resolve().parents[1]
UNUSED = (
    "pyvista",
    "vtk",
    "vtkmodules",
    "SurfaceTopography",
    "pandas",
    "pyarrow",
    "dask",
    "distributed",
)


@pytest.mark.parametrize(
    "code",
    [
        "import warptrunc",
        "import warptrunc.cli.analyze, warptrunc.analysis, warptrunc.plot, warptrunc.stiffness",
        "from warptrunc.plot import area_fraction, stiffness_load",
    ],
    ids=["package", "analyze-path", "figure-modules"],
)
def test_import_loads_nothing_unused(code):
    loaded = modules_after(code, ROOT)
    assert not loaded & set(UNUSED), sorted(loaded & set(UNUSED))
    assert "matplotlib" not in loaded


def test_analyze_with_figures_loads_nothing_unused(tmp_path):
    code = (
        "from warptrunc.cli import main\n"
        f"assert main(['analyze', '--n', '128', '--out', {str(tmp_path / 'o')!r},"
        " '--device', 'cpu']) == 0"
    )
    loaded = modules_after(code, tmp_path)
    assert not loaded & set(UNUSED), sorted(loaded & set(UNUSED))
    assert "matplotlib" not in loaded  # the figures were drawn by the figure process
    assert (tmp_path / "o" / "stiffness.png").exists()


def test_analyze_parser_loads_no_warp():
    code = "import warptrunc.cli.analyze as a, argparse\na.add_arguments(argparse.ArgumentParser())"
    assert "warp" not in modules_after(code, ROOT)


def test_figure_process_loads_nothing_unused(tmp_path):
    """What the figure process imports and draws (both of the job's figures) loads no Warp and
    nothing unused."""
    code = (
        "import numpy as np\n"
        "from types import SimpleNamespace as N\n"
        "import matplotlib.backends.backend_agg, matplotlib.figure\n"
        "from warptrunc.plot import maps, stiffness\n"
        "from warptrunc.plot._worker import _warm_up, png_bytes\n"
        "_warm_up()\n"
        "d = np.linspace(0, 1e-6, 50)\n"
        "c = N(depth=d, Rt=1e-5, area_fraction=np.linspace(1e-4, 1e-2, 50))\n"
        "png_bytes('area_fraction', (c,), {'log': True})\n"
        "s = N(load=d + 1e-9, F_over_EA=d + 1e-9, Ec_over_E=np.sqrt(d + 1e-9))\n"
        "f = N(alpha=0.5, beta=1.0, r2=1.0, F_over_EA_min=1e-8, F_over_EA_max=1e-6)\n"
        "assert png_bytes('stiffness_load', (s, f), {'title': 'R$_t$'})[:4] == b'\\x89PNG'\n"
    )
    loaded = modules_after(code, tmp_path)
    assert "matplotlib" in loaded
    assert not loaded & {"warp", *UNUSED}, sorted(loaded & {"warp", *UNUSED})
