# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""``import warptrunc`` from the repository root, whichever way the package was installed.

From the root, Python finds the source folder ``warptrunc/`` first (the current folder leads
``sys.path``), which has no ``kernels/`` inside: the kernels live in the top-level
``kernels/`` and are installed as ``warptrunc.kernels``. These tests start Python from the
root with ``-S`` (no ``.pth`` files, so no editable-install finder) and the dependencies'
site-packages on the path, and check three layouts: an installed copy built the way
setuptools' ``package-dir`` lays it out (``pip install .``), no install at all, and the
editable install this venv has. A top-level ``kernels`` package must never appear.
"""

import shutil
import subprocess
import sys
from pathlib import Path

import numpy
import pytest

ROOT = Path(__file__).resolve().parents[1]
DEPS = str(Path(numpy.__file__).resolve().parents[1])  # site-packages holding the dependencies

PROBE = (
    "import sys, warptrunc, warptrunc.kernels, warptrunc.truncation.stream, warptrunc.io.vtk;"
    "import warptrunc.islands.streamed, warptrunc.plot.pooling;"
    "from warptrunc.kernels import truncation as _k;"
    "from warptrunc.kernels.contact import bccg as _kb;"
    "assert 'kernels' not in sys.modules, 'top-level kernels package';"
    "s = warptrunc.from_heights([[0.0, 1.0], [2.0, 3.0]], 1e-6);"
    "c = warptrunc.truncate(s, 3, max_depth_fraction=1.0, device='cpu');"
    "print(warptrunc.__file__); print(_kb.__file__); print(_k.__file__);"
    "print([int(v) for v in c.n_contact_pixels])"
)


def _run(extra_path: list[str], code: str = PROBE):
    boot = f"import sys; sys.path[1:1] = {[*extra_path, DEPS]!r}; "
    return subprocess.run(
        [sys.executable, "-S", "-c", boot + code],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=120,
    )


def _fake_install(dest: Path) -> Path:
    """The tree ``pip install .`` writes: warptrunc/ with kernels/ copied inside it."""
    site = dest / "site"
    ignore = shutil.ignore_patterns("__pycache__")
    shutil.copytree(ROOT / "warptrunc", site / "warptrunc", ignore=ignore)
    shutil.copytree(ROOT / "kernels", site / "warptrunc" / "kernels", ignore=ignore)
    return site


def test_root_import_with_a_non_editable_install_shadowed_by_the_source(tmp_path):
    site = _fake_install(tmp_path)
    r = _run([str(site)])
    assert r.returncode == 0, r.stderr
    pkg, sub, kern, counts = r.stdout.strip().splitlines()[-4:]
    assert Path(pkg).parent == ROOT / "warptrunc"  # the source folder wins the lookup
    assert Path(kern) == ROOT / "kernels" / "truncation.py"  # and finds its kernels
    assert Path(sub) == ROOT / "kernels" / "contact" / "bccg.py"  # their sub-packages too
    assert counts == "[1, 2, 3, 4]"  # z ≥ 3 − ω at ω = 0, 1, 2, 3 (z = 0, 1, 2, 3)


def test_installed_copy_keeps_its_own_kernels(tmp_path):
    """Away from the root, the installed copy is used with its own kernels folder."""
    site = _fake_install(tmp_path)
    code = PROBE
    r = subprocess.run(
        [sys.executable, "-S", "-c", f"import sys; sys.path[:0] = {[str(site), DEPS]!r}; " + code],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 0, r.stderr
    pkg, sub, kern, _ = r.stdout.strip().splitlines()[-4:]
    assert Path(pkg).parent == site / "warptrunc"
    assert Path(kern) == site / "warptrunc" / "kernels" / "truncation.py"
    assert Path(sub) == site / "warptrunc" / "kernels" / "contact" / "bccg.py"


def test_root_import_from_an_uninstalled_checkout():
    r = _run([])
    assert r.returncode == 0, r.stderr
    sub, kern = r.stdout.strip().splitlines()[-3:-1]
    assert Path(kern) == ROOT / "kernels" / "truncation.py"
    assert Path(sub) == ROOT / "kernels" / "contact" / "bccg.py"


def test_root_import_with_this_venv_as_installed():
    """Whatever this venv holds (editable in CI): plain ``python -c`` from the root works."""
    r = subprocess.run(
        [sys.executable, "-c", PROBE], cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    assert r.returncode == 0, r.stderr


@pytest.mark.parametrize(
    "mod", ["warptrunc.kernels.wm", "warptrunc.kernels.label", "warptrunc.kernels.contact.cg"]
)
def test_kernel_modules_are_submodules_of_the_package(mod):
    import importlib

    m = importlib.import_module(mod)
    assert m.__name__ == mod and m.__package__ == mod.rpartition(".")[0]


def test_pyproject_lists_every_package_of_the_tree():
    """``packages`` in pyproject.toml = the folders of ``warptrunc/`` and ``kernels/`` (installed
    as ``warptrunc.kernels``) with an ``__init__.py``, and ``package-dir`` maps the kernels."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib
    cfg = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    tree = {
        ".".join(p.parent.relative_to(ROOT).parts)
        for p in (ROOT / "warptrunc").rglob("__init__.py")
        if "__pycache__" not in p.parts
    }
    kernels = {
        ".".join(("warptrunc", *p.parent.relative_to(ROOT).parts))
        for p in (ROOT / "kernels").rglob("__init__.py")
        if "__pycache__" not in p.parts
    }
    assert "warptrunc.kernels.contact" in kernels
    assert set(cfg["packages"]) == tree | kernels
    assert cfg["package-dir"]["warptrunc.kernels"] == "kernels"


@pytest.mark.parametrize(
    "old", ["warptrunc.stream", "warptrunc.stream_islands", "warptrunc.vtk_io", "warptrunc._blocks"]
)
def test_old_module_paths_are_gone(old):
    """One place per concern: the modules moved into ``truncation/``, ``islands/``, ``io/`` and
    ``plot/`` leave no second import path behind."""
    import importlib

    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(old)
