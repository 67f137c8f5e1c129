# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Bad command-line input: every sub-command refuses it with one line that names the option,
the value and the allowed range, and exit status 2 (no traceback, nothing computed).

Numeric options get 0, negative, NaN, inf and huge values where each is out of range; path
options get a missing file, a folder, an existing file and an unwritable place. Run in-process
through :func:`warptrunc.cli.main` (the entry point of the ``warptrunc`` script).
"""

from __future__ import annotations

import pytest

from warptrunc.cli import main

# (argv, substrings the one-line error must contain). {f} is an existing regular file, {d} an
# existing folder, {m} a missing file, {u} a place no one can write (a folder under /proc/1).
NUMERIC = [
    # generate / shared surface source
    (["generate", "--D", "3.5"], ["--D", "(2, 3)", "3.5"]),
    (["generate", "--D", "nan"], ["--D", "(2, 3)", "nan"]),
    (["generate", "--D", "2"], ["--D", "(2, 3)", "'2'"]),
    (["generate", "--Wr", "0"], ["--Wr", "(0, inf) m", "'0'"]),
    (["generate", "--Wr", "-1e-4"], ["--Wr", "(0, inf) m", "-1e-4"]),
    (["generate", "--Wr", "inf"], ["--Wr", "(0, inf) m", "inf"]),
    (["generate", "--L", "nan"], ["--L", "(0, inf) m", "nan"]),
    (["generate", "--L", "1e-3", "-1"], ["--L", "(0, inf) m", "-1"]),
    (["generate", "--L", "1e-3", "1e-3", "1e-3"], ["--L", "one or two values", "3"]),
    (["generate", "--n", "0"], ["--n", "[2, 1048576]", "'0'"]),
    (["generate", "--n", "-64"], ["--n", "[2, 1048576]", "-64"]),
    (["generate", "--n", "64.5"], ["--n", "integer", "64.5"]),
    (["generate", "--n", "nan"], ["--n", "integer", "nan"]),
    (["generate", "--Rt", "0"], ["--Rt", "(0, 1e+37] m", "'0'"]),
    (["generate", "--Rt=-inf"], ["--Rt", "(0, 1e+37] m", "-inf"]),
    (["generate", "--G", "-1"], ["--G", "(0, inf) m", "-1"]),
    (["generate", "--M", "0"], ["--M", "[1, 10000]", "'0'"]),
    (["generate", "--M", "1000000"], ["--M", "[1, 10000]", "1000000"]),
    (["generate", "--gamma", "1"], ["--gamma", "(1, inf)", "'1'"]),
    (["generate", "--gamma", "inf"], ["--gamma", "(1, inf)", "inf"]),
    (["generate", "--Wc", "0"], ["--Wc", "(0, inf) m", "'0'"]),
    (["generate", "--seed", "-1"], ["--seed", "[0, 4294967295]", "-1"]),
    (["generate", "--seed", "nan"], ["--seed", "integer", "nan"]),
    # reader options (any command with a file)
    (["analyze", "--dx", "0"], ["--dx", "(0, inf) m", "'0'"]),
    (["analyze", "--dy", "nan"], ["--dy", "(0, inf) m", "nan"]),
    (["analyze", "--height-unit", "-1e-6"], ["--height-unit", "(0, inf) m", "-1e-6"]),
    (["analyze", "--channel", "-1"], ["--channel", "[0, inf)", "-1"]),
    # analyze
    (["analyze", "--increments", "0"], ["--increments", "[1, 1000000]", "'0'"]),
    (["analyze", "--increments", "1e12"], ["--increments", "[1, 1000000]", "1e12"]),
    (["analyze", "--increments", "99999999999"], ["--increments", "[1, 1000000]", "99999999999"]),
    (["analyze", "--max-depth-fraction", "0"], ["--max-depth-fraction", "(0, 1]", "'0'"]),
    (["analyze", "--max-depth-fraction", "1.5"], ["--max-depth-fraction", "(0, 1]", "1.5"]),
    (["analyze", "--max-depth-fraction", "nan"], ["--max-depth-fraction", "(0, 1]", "nan"]),
    (["analyze", "--max-depth", "-1e-6"], ["--max-depth", "(0, inf) m", "-1e-6"]),
    (["analyze", "--E", "0"], ["--E", "(0, inf) Pa", "'0'"]),
    (["analyze", "--E", "inf"], ["--E", "(0, inf) Pa", "inf"]),
    (["analyze", "--nu", "0.6"], ["--nu", "(-1, 0.5]", "0.6"]),
    (["analyze", "--nu", "-1"], ["--nu", "(-1, 0.5]", "-1"]),
    (["analyze", "--E-i", "0"], ["--E-i", "(0, inf] Pa", "'0'"]),
    (["analyze", "--E-i", "nan"], ["--E-i", "(0, inf] Pa", "nan"]),
    (["analyze", "--nu-i", "nan"], ["--nu-i", "(-1, 0.5]", "nan"]),
    (["analyze", "--beta-prime", "0"], ["--beta-prime", "(0, inf)", "'0'"]),
    (["analyze", "--min-pixels", "0"], ["--min-pixels", "[1, inf)", "'0'"]),
    (["analyze", "--depth-window", "-1", "1"], ["--depth-window", "[0, inf) m", "-1"]),
    (["analyze", "--n", "32", "--depth-window", "2e-6", "1e-6"], ["--depth-window", "LO < HI"]),
    # render
    (["render", "--n", "64", "--depths", "2"], ["--depths", "(0, R_t]", "2 ", "metres"]),
    (["render", "--depths", "0"], ["--depths", "(0, inf) m", "'0'"]),
    (["render", "--depths", "-1e-6"], ["--depths", "(0, inf) m", "-1e-6"]),
    (["render", "--depth-fractions", "0"], ["--depth-fractions", "(0, 1]", "'0'"]),
    (["render", "--depth-fractions", "2"], ["--depth-fractions", "(0, 1]", "'2'"]),
    (["render", "--size", "0", "100"], ["--size", "[16, 16384]", "'0'"]),
    (["render", "--size", "100000", "100"], ["--size", "[16, 16384]", "100000"]),
    (["render", "--ncols", "0"], ["--ncols", "[1, inf)", "'0'"]),
    (["render", "--exaggeration", "0"], ["--exaggeration", "(0, inf)", "'0'"]),
    (["render", "--exaggeration", "inf"], ["--exaggeration", "(0, inf)", "inf"]),
    (["render", "--downsample", "0"], ["--downsample", "[1, inf)", "'0'"]),
    (["render", "--frames", "1"], ["--frames", "[2, 100000]", "'1'"]),
    (["render", "--fps", "0"], ["--fps", "(0, inf)", "'0'"]),
    (["render", "--fps", "nan"], ["--fps", "(0, inf)", "nan"]),
    (["render", "--max-depth-fraction", "-0.5"], ["--max-depth-fraction", "(0, 1]", "-0.5"]),
    (["render", "--vtk-increments", "0"], ["--vtk-increments", "[1, 1000000]", "'0'"]),
    (["render", "--pooling", "max"], ["--pooling", "'max'", "area, any"]),
    (["render", "--output", "a/b.png"], ["--output", "without folders", "a/b.png"]),
    # islands
    (["islands", "--increments", "-3"], ["--increments", "[1, 1000000]", "-3"]),
    (["islands", "--max-depth-fraction", "inf"], ["--max-depth-fraction", "(0, 1]", "inf"]),
    (["islands", "--max-depth", "0"], ["--max-depth", "(0, inf) m", "'0'"]),
    (["islands", "--connectivity", "6"], ["--connectivity", "6", "4, 8"]),
    (["islands", "--min-pixels", "0"], ["--min-pixels", "[1, inf)", "'0'"]),
    (["islands", "--snapshots", "1.5"], ["--snapshots", "(0, 1]", "1.5"]),
    (["islands", "--exponent-tolerance", "1"], ["--exponent-tolerance", "(0, 1)", "'1'"]),
    (["islands", "--min-islands", "1"], ["--min-islands", "[5, inf)", "'1'"]),
    (["islands", "--plateau-width", "0"], ["--plateau-width", "(0, 1]", "'0'"]),
    (["islands", "--persist", "-0.1"], ["--persist", "[0, 1]", "-0.1"]),
    (["islands", "--smooth", "4"], ["--smooth must be odd, got 4"]),
    (["islands", "--smooth", "0"], ["--smooth", "[1, inf)", "'0'"]),
    # calibrate (typed-in targets)
    (["calibrate", "--D", "3"], ["--D", "(2, 3)", "'3'"]),
    (["calibrate", "--Rrms", "0"], ["--Rrms", "(0, inf) m", "'0'"]),
    (["calibrate", "--Rt", "nan"], ["--Rt", "(0, 1e+37] m", "nan"]),
    (["calibrate", "--Wr", "-1"], ["--Wr", "(0, inf) m", "-1"]),
    (["calibrate", "--L", "0"], ["--L", "(0, inf) m", "'0'"]),
    (["calibrate", "--n", "1"], ["--n", "[8, 1048576]", "'1'"]),
    (["calibrate", "--seeds", "-1"], ["--seeds", "[0, 4294967295]", "-1"]),
    (["calibrate", "--rtol", "0"], ["--rtol", "(0, 1)", "'0'"]),
    (["calibrate", "--rtol", "inf"], ["--rtol", "(0, 1)", "inf"]),
    (["calibrate", "--max-iter", "0"], ["--max-iter", "[2, 1000]", "'0'"]),
    (["calibrate", "--n-out", "0"], ["--n-out", "[2, inf)", "'0'"]),
    (["calibrate", "--seed-out", "-2"], ["--seed-out", "[0, 4294967295]", "-2"]),
    # bem-check
    (["bem-check", "--fractions", "0.1", "1.2"], ["--fractions", "(0, 1)", "1.2"]),
    (["bem-check", "--depths", "-1e-6"], ["--depths", "(0, inf) m", "-1e-6"]),
    (["bem-check", "--E", "nan"], ["--E", "(0, inf) Pa", "nan"]),
    (["bem-check", "--fd-step", "0"], ["--fd-step", "(0, 0.5)", "'0'"]),
    (["bem-check", "--pressure-tol", "-1"], ["--pressure-tol", "(0, inf)", "-1"]),
    (["bem-check", "--maxiter", "0"], ["--maxiter", "[1, inf)", "'0'"]),
    (["analyze", "--band-rows", "0"], ["--band-rows", "[1, inf)", "'0'"]),
    # sweep
    (["sweep", "--D", "2.5", "3.1"], ["--D", "(2, 3)", "3.1"]),
    (["sweep", "--delta", "0"], ["--delta", "(0, inf)", "'0'"]),
    (["sweep", "--workers", "0"], ["--workers", "[1, 4096]", "'0'"]),
    (["sweep", "--min-pixels", "5", "0"], ["--min-pixels", "[1, inf)", "'0'"]),
    (["sweep", "--n", "nan"], ["--n", "integer", "nan"]),
]

PATHS = [
    (["analyze", "--n", "64", "--out", "{f}"], ["--out", "existing file", "{f}"]),
    (["analyze", "--out", "{f}/sub"], ["--out", "not a folder", "{f}"]),
    (["analyze", "--out", "{u}"], ["--out", "{u}"]),
    (["analyze", "--input", "{m}"], ["--input", "not found", "{m}"]),
    (["analyze", "--input", "{d}"], ["--input", "folder", "{d}"]),
    (["islands", "--out", "{f}"], ["--out", "existing file", "{f}"]),
    (["islands", "--input", "{m}"], ["--input", "not found", "{m}"]),
    (["render", "--out", "{f}"], ["--out", "existing file", "{f}"]),
    (["render", "--input", "{d}"], ["--input", "folder", "{d}"]),
    (["generate", "-o", "{d}"], ["--output", "existing folder", "{d}"]),
    (["generate", "-o", "{f}/s.npz"], ["--output", "not a folder", "{f}"]),
    (["generate", "-o", "{u}/s.npz"], ["--output", "{u}"]),
    (["describe", "{m}"], ["file", "not found", "{m}"]),
    (["describe", "{d}"], ["file", "folder", "{d}"]),
    (["describe", "{f}", "--out", "{f}"], ["--out", "existing file", "{f}"]),
    (["describe", "{f}", "--json", "{d}"], ["--json", "existing folder", "{d}"]),
    (["calibrate", "{m}"], ["file", "not found", "{m}"]),
    (["calibrate", "--out", "{f}", "--D", "2.5"], ["--out", "existing file", "{f}"]),
    (["reproduce", "--out", "{f}"], ["--out", "existing file", "{f}"]),
    (["sweep", "--grid", "{m}"], ["--grid", "not found", "{m}"]),
    (["bem-check", "--out", "{f}"], ["--out", "existing file", "{f}"]),
    (["sweep", "--out", "{f}"], ["--out", "existing file", "{f}"]),
    (["reproduce", "--out", "{u}"], ["--out", "{u}"]),
]


def _cli(argv, capsys) -> tuple[int, str]:
    try:
        code = main([*argv, "--device", "cpu"])
    except SystemExit as exc:
        code = exc.code
    return code, capsys.readouterr().err


def _unwritable() -> str:
    """A folder that cannot be created, even by root: /proc/1 is not writable."""
    return "/proc/1/warptrunc-out"


@pytest.fixture
def places(tmp_path):
    f = tmp_path / "file.txt"
    f.write_text("not a height map\n")
    d = tmp_path / "folder"
    d.mkdir()
    return {"f": str(f), "d": str(d), "m": str(tmp_path / "missing.npz"), "u": _unwritable()}


def _check(code, err, want, argv):
    assert code == 2, (argv, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1, f"not one line: {err!r}"
    assert "Traceback" not in err
    for w in want:
        assert w in lines[0], (w, lines[0])


@pytest.mark.parametrize("argv, want", NUMERIC, ids=[" ".join(a) for a, _ in NUMERIC])
def test_bad_number_is_one_line_exit_2(argv, want, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # nothing may be written; if it were, it lands here
    code, err = _cli(argv, capsys)
    _check(code, err, want, argv)
    assert not any(tmp_path.iterdir()), "an output was written before the error"


@pytest.mark.parametrize("argv, want", PATHS, ids=[" ".join(a) for a, _ in PATHS])
def test_bad_path_is_one_line_exit_2(argv, want, places, capsys, tmp_path, monkeypatch):
    if "{u}" in " ".join(argv) and not __import__("os").path.isdir("/proc/1"):
        pytest.skip("no /proc on this system")
    monkeypatch.chdir(tmp_path)
    argv = [a.format(**places) for a in argv]
    want = [w.format(**places) for w in want]
    code, err = _cli(argv, capsys)
    _check(code, err, want, argv)


def test_existing_file_as_out_leaves_it_untouched(places, capsys):
    from pathlib import Path

    before = Path(places["f"]).read_text()
    code, _ = _cli(["analyze", "--n", "64", "--out", places["f"]], capsys)
    assert code == 2 and Path(places["f"]).read_text() == before


def test_help_states_units_of_depths_and_fractions(capsys):
    with pytest.raises(SystemExit):
        main(["render", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "truncation depths ω in metres, each in (0, R_t]" in out
    assert "fractions of R_t, each in (0, 1]" in out


@pytest.mark.parametrize("cmd", ["generate", "analyze", "render", "islands", "describe"])
def test_device_help_states_its_default_once(cmd, capsys):
    with pytest.raises(SystemExit):
        main([cmd, "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "(default: (default:" not in out and "(default: None)" not in out
    assert out.count("$WARPTRUNC_DEVICE") == 1
