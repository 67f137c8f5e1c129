# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One name per quantity, one home per operation: the public face of the package, and no old
name beside it (0.1 is unreleased: a rename leaves no alias)."""

import importlib
import math

import numpy as np
import pytest

import warptrunc
from warptrunc._support.public import public_modules


def test_dir_is_the_public_api():
    """dir(warptrunc) = __all__ ∪ the public top-level modules: no Any, sys, importlib …"""
    top = {m.split(".")[1] for m in public_modules() if m.count(".") >= 1}
    top |= {"cli"}  # cli: public, documented by --help
    assert set(dir(warptrunc)) == set(warptrunc.__all__) | top
    for leaked in ("Any", "TYPE_CHECKING", "importlib", "sys", "types", "annotations", "kernels"):
        assert leaked not in dir(warptrunc)
    for name in top:  # each listed module is reachable as an attribute
        assert getattr(warptrunc, name) is not None
    with pytest.raises(AttributeError, match="no attribute '_support'"):
        warptrunc.__getattr__("_support")  # an internal package is not served as a name


def test_public_names_are_written_once():
    """``__all__`` is the export mapping's keys: the package names each public name once."""
    assert warptrunc.__all__ == sorted(warptrunc._EXPORTS)
    assert "TYPE_CHECKING" not in vars(warptrunc)


@pytest.mark.parametrize(
    "name, module",
    [
        ("wm_surface", "warptrunc.wm"),
        ("truncate", "warptrunc.truncation"),
        ("label_islands", "warptrunc.islands"),
        ("fit_power_law", "warptrunc.stiffness"),
        ("solve_contact", "warptrunc.contact"),
    ],
)
def test_one_public_function_per_operation_at_the_top(name, module):
    assert name in warptrunc.__all__
    assert getattr(warptrunc, name) is getattr(importlib.import_module(module), name)


@pytest.mark.parametrize(
    "module, old",
    [
        ("warptrunc.reproduce.analysis", "line_fit"),  # warptrunc.sweep.linear_fit
        ("warptrunc.reproduce.analysis", "power_fit"),  # warptrunc.fit_power_law
        ("warptrunc.stiffness", "MODELS"),  # STIFFNESS_MODELS
        ("warptrunc._support", "deprecate"),  # the alias machinery itself
    ],
)
def test_renamed_names_leave_no_alias(module, old):
    mod = importlib.import_module(module)
    assert not hasattr(mod, old)
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(f"{module}.{old}")


def test_reproduce_fits_are_the_one_fit():
    """The report's fits are :func:`warptrunc.fit_power_law` and the sweep's ``linear_fit``:
    y = 0.0386·x^−1.122 (the paper's Table 3 β(δ)) and a line of slope 0.125 come back."""
    import warptrunc.reproduce.analysis as a

    x = np.array([0.01, 0.02, 0.04, 0.08])
    f = a._power(x, 0.0386 * x**-1.122)
    assert f["p"] == pytest.approx(-1.122, rel=1e-12) and f["b"] == pytest.approx(0.0386)
    g = a._line([2.1, 2.5, 2.9], [0.40, 0.45, 0.50])
    assert g["slope"] == pytest.approx(0.125) and g["n"] == 3


def test_contact_modulus_has_one_name():
    """``contact_modulus`` on both materials; the old property names are gone."""
    from warptrunc.reproduce.asperity import AsperityMaterial

    m = AsperityMaterial(E=70e9, nu=0.33)
    assert m.contact_modulus == pytest.approx(70e9 / (1 - 0.33**2), rel=1e-15)
    assert not hasattr(m, "E_r")
    assert not hasattr(warptrunc.Material(), "reduced_modulus")


def test_no_other_name_for_the_contact_modulus():
    """E* is called contact_modulus in the code: no reduced_modulus/e_star/E_r identifiers."""
    import ast
    import pathlib

    bad = {"reduced_modulus", "e_star", "estar", "E_star", "Estar", "E_r", "Er", "E_red"}
    root = pathlib.Path(warptrunc.__file__).parent
    hits = []
    for path in root.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            name = (
                getattr(node, "id", None)
                or getattr(node, "attr", None)
                or getattr(node, "arg", None)
            )
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
                name = node.name
            if name in bad:
                hits.append(f"{path.relative_to(root)}:{node.lineno}: {name}")
    assert hits == []
    assert math.isfinite(warptrunc.Material().contact_modulus)
