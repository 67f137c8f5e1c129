# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Parameters declared once (issue 27): a field of WMSpec or Material reaches the CLI, the
sweep grid, the docs table and the docstrings from its declaration alone."""

from __future__ import annotations

import argparse
import math
from dataclasses import dataclass

import numpy as np
import pytest

from warptrunc import TABLE1, Material, WMSpec, preset, wm_surface
from warptrunc.cli import main
from warptrunc.params import add_options, from_args, markdown_table, numpydoc_fields, param
from warptrunc.sweep import SweepGrid, SweepOptions


@dataclass(frozen=True)
class SkewedSpec(WMSpec):
    """A WMSpec with one more field, declared here only."""

    skew: float = param(0.0, "test-only skewness s of the heights", ge=-1.0, le=1.0)


def test_new_field_reaches_cli_sweep_grid_and_docs_with_no_other_edit(capsys):
    # CLI: the generic machinery builds the option, its help (range) and the object back
    p = argparse.ArgumentParser(prog="t")
    add_options(p, SkewedSpec, title="surface")
    helptext = p.format_help()
    assert "--skew" in helptext and "[-1, 1]" in helptext and "test-only skewness" in helptext
    spec = from_args(SkewedSpec, p.parse_args(["--skew", "0.25", "--D", "2.2", "--n", "64"]))
    assert isinstance(spec, SkewedSpec) and spec.skew == 0.25 and spec.D == 2.2 and spec.n == 64
    with pytest.raises(SystemExit) as e:
        p.parse_args(["--skew", "3"])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert "--skew" in err and "'3'" in err and "[-1, 1]" in err
    # sweep grid: the field is an axis, its values checked against the declaration
    grid = SweepGrid.from_dict(
        {"D": [2.3], "delta": [0.01], "seeds": "0", "axes": {"skew": [0.5, -0.5]}},
        specs=(SkewedSpec, Material),
    )
    assert len(grid) == 2 and grid.to_dict()["axes"] == {"skew": [0.5, -0.5]}
    with pytest.raises(ValueError, match=r"skew must be in \[-1, 1\], got 2"):
        SweepGrid.from_dict(
            {"D": [2.3], "delta": [0.01], "seeds": "0", "axes": {"skew": [2]}},
            specs=(SkewedSpec, Material),
        )
    # docs: the parameter table and the numpydoc lines
    table = markdown_table(SkewedSpec)
    row = next(r for r in table.splitlines() if r.startswith("| `skew`"))
    assert "`--skew`" in row and "[-1, 1]" in row and "test-only skewness" in row
    assert "``skew`` : float, default 0" in numpydoc_fields(SkewedSpec)
    # and the object validates it
    with pytest.raises(ValueError, match="skew"):
        SkewedSpec(skew=1.5)


def test_out_of_range_fields_raise_naming_the_field():
    with pytest.raises(ValueError, match=r"^D must be in \(2, 3\), got 3.5"):
        WMSpec(D=3.5)
    with pytest.raises(ValueError, match=r"^hardness must be in \(0, inf\] Pa, got -1"):
        Material(hardness=-1)
    with pytest.raises(ValueError, match="hardness"):
        Material(hardness=0.0)
    with pytest.raises(ValueError, match="hardness"):
        Material(hardness=math.nan)


def test_contact_modulus_against_closed_forms():
    m = Material()
    assert m.contact_modulus == pytest.approx(m.E / (1.0 - m.nu**2), rel=1e-15)
    assert m.contact_modulus == pytest.approx(70e9 / (1.0 - 0.33**2), rel=1e-15)
    # diamond counter-body (Oliver & Pharr 1992): E_i = 1141 GPa, ν_i = 0.07
    want = 1.0 / ((1.0 - 0.33**2) / 70e9 + (1.0 - 0.07**2) / 1141e9)
    d = Material.against_diamond()
    assert d.contact_modulus == pytest.approx(want, rel=1e-15)
    assert round(want / 1e9, 2) == 73.52


@pytest.mark.parametrize(
    "argv, want",
    [
        (["analyze", "--D", "3.5"], ["--D", "'3.5'", "(2, 3)"]),
        (["generate", "--Wr", "-1"], ["--Wr", "'-1'", "(0, inf)"]),
        (["bem-check", "--nu", "0.7"], ["--nu", "'0.7'", "(-1, 0.5]"]),
        (["analyze", "--E-i", "0"], ["--E-i", "'0'", "(0, inf] Pa"]),
        (["sweep", "--D", "2.1", "3.5", "--delta", "0.01"], ["--D", "'3.5'", "(2, 3)"]),
        (["compare", "--D", "1.5"], ["--D", "'1.5'", "(2, 3)"]),
        (["calibrate", "--Rt", "0"], ["--Rt", "'0'", "(0, 1e+37] m"]),
    ],
)
def test_cli_parse_errors_exit_2_naming_option_value_range(argv, want, capsys):
    with pytest.raises(SystemExit) as e:
        main(argv)
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    for w in want:
        assert w in err, (w, err)


def test_cli_option_names_of_today_parse_to_the_same_objects():
    from warptrunc.cli import _common

    p = argparse.ArgumentParser()
    _common.add_surface_source(p)
    _common.add_material(p)
    a = p.parse_args(
        "--D 2.3 --Wr 5e-5 --L 1e-3 2e-3 --n 128 64 --M 8 --gamma 1.4 --Wc 3e-5 "
        "--cutoff pixel --seed 7 --E 2e11 --nu 0.3 --E-i 1141e9 "
        "--nu-i 0.07".split()
    )
    spec = _common.wm_spec_from_args(a)
    assert spec == WMSpec(
        D=2.3, Wr=5e-5, L=(1e-3, 2e-3), n=(128, 64), M=8, gamma=1.4, Wc=3e-5, cutoff="pixel", seed=7
    )
    assert _common.material_from_args(a) == Material(E=2e11, nu=0.3, E_i=1141e9, nu_i=0.07)
    # --G given: the heights are not rescaled (Rt None), as before
    g = _common.wm_spec_from_args(p.parse_args(["--G", "1e-9", "--Rt", "5e-6"]))
    assert g.G == 1e-9 and g.Rt is None
    # a preset, with options winning over its fields
    pr = _common.wm_spec_from_args(p.parse_args(["--preset", "GB300s", "--n", "64"]))
    assert pr == TABLE1["GB300s"].replace(n=64)


def test_presets_are_wmspecs_with_the_paper_wr():
    from warptrunc.presets import PRESETS, TABLE1_TRI

    assert set(TABLE1) == set(TABLE1_TRI) == {"Ps", "SMATs", "GB300s", "GB50s"}
    assert set(PRESETS) == set(TABLE1) | {f"{k}-tri" for k in TABLE1}
    assert all(isinstance(s, WMSpec) for s in PRESETS.values())
    # W_r from the paper's Table 1 (µm), Ps's "≫ 1024 µm" taken as 2·L of the calibration map
    # (1 mm for the D_vs presets, 1.024 mm for the D_tri ones)
    table = {"SMATs": 120, "GB300s": 60, "GB50s": 25}
    assert {k: round(s.Wr * 1e6, 9) for k, s in TABLE1.items()} == {"Ps": 2000, **table}
    assert {k: round(s.Wr * 1e6, 9) for k, s in TABLE1_TRI.items()} == {"Ps": 2048, **table}
    assert all(s.L == 1e-3 and s.n == 10240 and s.M == 10 for s in PRESETS.values())
    assert preset("GB50s") is TABLE1["GB50s"]
    assert preset("GB50s-tri") is TABLE1_TRI["GB50s"]
    with pytest.raises(ValueError, match=r"preset must be one of Ps, SMATs, .*, GB50s-tri, got"):
        preset("GB100s")


def test_wm_surface_takes_a_spec_or_the_legacy_arguments():
    spec = WMSpec(D=2.3, Wr=50e-6, n=64, Rt=2e-6, M=6, seed=3)
    a = wm_surface(spec, device="cpu").heights
    b = wm_surface(2.3, 50e-6, n=64, Rt=2e-6, M=6, seed=3, device="cpu").heights
    c = wm_surface(D=2.3, Wr=50e-6, n=64, Rt=2e-6, M=6, seed=3, device="cpu").heights
    d = wm_surface(spec.replace(seed=0), seed=3, device="cpu").heights  # keywords override
    for z in (b, c, d):
        np.testing.assert_array_equal(a, z)
    with pytest.raises(TypeError, match="multiple values"):
        wm_surface(2.3, D=2.4)
    with pytest.raises(TypeError, match="at most 2 positional"):
        wm_surface(2.3, 50e-6, 1e-3)


def test_sweep_options_follow_the_declarations():
    with pytest.raises(ValueError, match=r"^gamma must be in \(1, inf\)"):
        SweepOptions(gamma=1.0)
    with pytest.raises(ValueError, match=r"^E_i must be in \(0, inf\] Pa"):
        SweepOptions(E_i=-1.0)
    with pytest.raises(ValueError, match=r"^increments must be an integer in \[1, 1000000\]"):
        SweepOptions(increments=0)  # as TruncationSettings declares it
    o = SweepOptions(n=(256, 256), L=1e-3)
    assert o.n == (256, 256)  # a pair stays a pair: it enters the case ids
    assert o.wm_spec(2.4, 1e-6, 5) == WMSpec(D=2.4, Rt=1e-6, seed=5, n=256)


def test_sweep_cli_several_values_make_an_axis():
    from warptrunc.cli import sweep as cli_sweep

    p = argparse.ArgumentParser()
    cli_sweep.add_arguments(p)
    a = p.parse_args("--D 2.2 2.4 --delta 0.01 --M 8 10 --gamma 1.4 --E-i 1141e9".split())
    grid = cli_sweep.grid_from_args(a)
    opts = cli_sweep.options_from_args(a)
    assert grid.axes == (("M", (8, 10)),) and len(grid) == 4
    assert opts.gamma == 1.4 and opts.E_i == 1141e9 and opts.M == SweepOptions().M
    cases = grid.cases(opts)
    # a case of an axis is the case run with that value as an option
    one = SweepGrid([2.2], [0.01], "0").cases(opts.replace(M=8))
    assert cases[0].case_id == one[0].case_id and cases[0].params == (("M", 8),)
    with pytest.raises(ValueError, match="cannot vary 'hardness'"):
        SweepGrid.from_dict(
            {"D": [2.3], "delta": [0.01], "seeds": "0", "axes": {"hardness": [1e9]}}
        ).cases(SweepOptions())
