# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Messages in the user's terms (issue 41, item 5): errors name the option and the values as
typed with the rule; a file that is no height map is called so, with the formats that are
read; a sweep says why its fits were left out, and draws no line through fewer than three
values of D.

References: the values typed on the command line, SurfaceTopography's own list of readers,
and hand-made cases tables whose reasons and means are known.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest

from warptrunc.cli import main


def _cli(argv, capsys) -> tuple[int, str, str]:
    try:
        code = main([*argv, "--device", "cpu"])
    except SystemExit as exc:
        code = exc.code
    r = capsys.readouterr()
    return code, r.out, r.err


# --- bem-check: approaches ----------------------------------------------------------------------


@pytest.mark.parametrize(
    "opt, vals, want",
    [
        ("--fractions", ["0.5", "0.2"], "got 0.5 0.2"),
        ("--fractions", ["0.2", "0.2"], "got 0.2 0.2"),
        ("--depths", ["5e-6", "2e-6"], "got 5e-06 2e-06"),
    ],
)
def test_bem_check_order_error_names_the_option_and_the_values_typed(
    opt, vals, want, capsys, tmp_path
):
    out = tmp_path / "b"
    code, _, err = _cli(["bem-check", "--n", "32", opt, *vals, "--out", str(out)], capsys)
    assert code == 2 and not out.exists()
    line = err.strip()
    assert "\n" not in line and "Traceback" not in line
    assert f"{opt} must increase strictly" in line and want in line
    assert "e-06," not in line and "0000" not in line  # no metres of float noise for fractions


def test_bem_check_depth_above_rt_names_the_range_in_metres(capsys, tmp_path):
    code, _, err = _cli(
        [
            "bem-check",
            "--n",
            "32",
            "--Rt",
            "1e-5",
            "--depths",
            "5e-6",
            "2e-5",
            "--out",
            str(tmp_path / "b"),
        ],
        capsys,
    )
    assert code == 2
    assert "--depths must be in (0, R_t) = (0, 1e-05) m" in err and "got 5e-06 2e-05" in err


def test_bem_check_api_names_the_parameter():
    from warptrunc.contact import BemCheckSettings

    with pytest.raises(ValueError, match=r"fractions must increase strictly .* got 0\.3 0\.2$"):
        BemCheckSettings(fractions=[0.3, 0.2])


# --- describe: a file that is no height map ----------------------------------------------------


def _text_file(tmp_path):
    p = tmp_path / "notes.md"
    p.write_text("# Notes\n\nNot a height map: words, not numbers.\n")
    return p


def test_describe_text_file_is_not_a_height_map_format(capsys, tmp_path):
    pytest.importorskip("SurfaceTopography")
    code, _, err = _cli(["describe", "--input", str(_text_file(tmp_path))], capsys)
    assert code == 2
    assert "notes.md: not a recognised height-map format (.md" in err
    assert ".npz .npy .csv .txt .tsv built in" in err and ".sur .x3p .datx" in err
    assert "needs SurfaceTopography" not in err and "no reader recognises" not in err


def test_describe_text_file_without_surfacetopography(capsys, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)  # as if it were not installed
    code, _, err = _cli(["describe", "--input", str(_text_file(tmp_path))], capsys)
    assert code == 2
    assert "notes.md: not a recognised height-map format (.md)" in err
    assert ".npz .npy .csv .txt .tsv built in" in err and ".sur" in err
    assert "pip install SurfaceTopography" in err
    # an instrument suffix without SurfaceTopography: what to install, not "unrecognised"
    p = tmp_path / "scan.sur"
    p.write_bytes(b"\0" * 64)
    code, _, err = _cli(["describe", "--input", str(p)], capsys)
    assert code == 2 and "reading .sur files needs SurfaceTopography" in err


def test_instrument_suffixes_are_those_surfacetopography_reads():
    pytest.importorskip("SurfaceTopography")
    import warnings

    from warptrunc.io import INSTRUMENT_SUFFIXES, NUMPY_SUFFIXES, TEXT_SUFFIXES

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        from SurfaceTopography.IO import readers
    theirs = {
        f".{e.lower()}" for r in readers for e in (getattr(r, "_file_extensions", None) or [])
    }
    assert set(INSTRUMENT_SUFFIXES) == theirs - set(NUMPY_SUFFIXES + TEXT_SUFFIXES)
    assert len(INSTRUMENT_SUFFIXES) == len(set(INSTRUMENT_SUFFIXES))


# --- sweep: why fits were left out, no line through two values of D ----------------------------


def _table(rows):
    pd = pytest.importorskip("pandas")
    cols = ["D_in", "min_pixels", "alpha", "fit_error", "error"]
    df = pd.DataFrame(rows, columns=cols)
    df["min_pixels_fraction"] = np.nan
    for c in ("fit_error", "error"):
        df[c] = df[c].astype("string")
    return df


STAIRS = (
    "not worth reading: fit: only {} contact pixels at the deepest fitted increment "
    "(< 50): A_c moves by whole pixels, the fit reads the pixel staircase"
)
SHORT = "not worth reading: fit: the fit spans 0.3 decades of load (< 0.5)"
FEW = (
    "only 0 increments in the fit range (min_pixels=10, depth_window=None); need at least 3: "
    "lower min_pixels or widen the window"
)


def test_sweep_summary_all_flagged_prints_the_reasons_counted(capsys):
    from warptrunc.cli.sweep import _print_summary

    df = _table(
        [
            (
                2.3,
                10,
                0.84,
                STAIRS.format(31) + "; fit: the fit spans 0.332 decades of load (< 0.5)",
                None,
            ),
            (2.5, 10, 0.80, STAIRS.format(12), None),
            (2.7, 10, np.nan, FEW, None),
        ]
    )
    _print_summary(df)
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("min_pixels=10: α — no fit worth reading; 3 fits left out")
    # the staircase twice (31 and 12 pixels: one reason), the short load range once, FEW once
    assert out[1] == "  2× " + STAIRS.format(31).removeprefix("not worth reading: ")
    assert sorted(out[2:]) == sorted(
        ["  1× fit: the fit spans 0.332 decades of load (< 0.5)", "  1× " + FEW]
    )


def test_sweep_summary_two_values_of_d_draw_no_line(capsys):
    from warptrunc.cli.sweep import _print_summary
    from warptrunc.sweep import alpha_summary

    rows = [(2.3, 10, 0.61, None, None), (2.3, 10, 0.63, None, None),
            (2.7, 10, 0.50, None, None), (2.7, 10, 0.52, SHORT, None)]  # fmt: skip
    df = _table(rows)
    assert alpha_summary(df)["fit_ranges"]["10"]["alpha_vs_D"] == []
    _print_summary(df)
    out = capsys.readouterr().out.splitlines()
    assert "D=2.3: 0.6200±0.0141 (n=2 seeds), D=2.7: 0.5000 (n=1 seed)" in out[0]  # flagged out
    assert "α = " not in out[0]  # no line
    assert "no line α(D): α worth reading at 2 values of D, a line needs 3" in out[0]
    assert out[1] == "  1× fit: the fit spans 0.3 decades of load (< 0.5)"


def test_sweep_summary_three_values_of_d_give_the_least_squares_line(capsys):
    from warptrunc.cli.sweep import _print_summary

    d, a = np.array([2.1, 2.5, 2.9]), np.array([0.551, 0.603, 0.688])  # slope 0.17125
    _print_summary(_table([(x, 1, y, None, None) for x, y in zip(d, a, strict=True)]))
    out = capsys.readouterr().out
    slope = np.sum((d - d.mean()) * (a - a.mean())) / np.sum((d - d.mean()) ** 2)
    icpt = a.mean() - slope * d.mean()
    r = np.corrcoef(d, a)[0, 1]
    assert f"α = {slope:.3f}·D {'+' if icpt >= 0 else '−'} {abs(icpt):.3f} (r = {r:.3f})" in out


def test_sweep_cli_prints_why_no_fit_is_worth_reading(capsys, tmp_path):
    pytest.importorskip("pyarrow")
    # 64² maps of D 2.3 and 2.7: no increment has 10 contact pixels within 0.1·R_t
    code, out, _ = _cli(
        [
            "sweep",
            "--D",
            "2.3",
            "2.7",
            "--delta",
            "0.1",
            "--n",
            "64",
            "--no-progress",
            "--out",
            str(tmp_path / "s"),
        ],
        capsys,
    )
    assert code == 0
    lines = out.splitlines()
    i = next(k for k, s in enumerate(lines) if "no fit worth reading" in s)
    assert "2 fits left out (fit_error in cases.parquet)" in lines[i]
    assert lines[i + 1].startswith("  2× ")
