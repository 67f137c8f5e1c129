# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Device selection: explicit, WARPTRUNC_DEVICE, and a clear error for unknown devices."""

import subprocess
import sys

import pytest

import warptrunc


def test_explicit_cpu():
    assert str(warptrunc.resolve_device("cpu")) == "cpu"


def test_environment_variable_sets_the_default(monkeypatch):
    monkeypatch.setenv("WARPTRUNC_DEVICE", "cpu")
    assert str(warptrunc.resolve_device(None)) == "cpu"
    monkeypatch.setenv("WARPTRUNC_DEVICE", "cuda:7")
    with pytest.raises(ValueError, match=r"device must be one of .* got 'cuda:7'"):
        warptrunc.resolve_device(None)


def test_import_is_light():
    code = "import sys, warptrunc; print(any(m.split('.')[0] in ('matplotlib', 'pyvista', 'vtk') for m in sys.modules))"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "False"
