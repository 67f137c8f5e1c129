# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Issue 30: every command, every path fails cleanly — exit 2 and one short line naming the
parameter, the value and what is allowed; no traceback, no warning, nothing written.

Each case of the issue's list has a test here: an ``--out`` the file system refuses (a name
too long, a folder one may not enter: simulated, since root enters every folder), bounded work
(``--increments`` above the cap, a huge ``--seeds`` range), ``--Rt 1e300``, a damaged
``sweep.json``, an unreadable ``.lock``, a half-cut ``.opd``, an empty instrument file, an XYZ
list with an ``inf`` coordinate, and the message of an unexpected error.
"""

from __future__ import annotations

import errno
import json
import os
import pathlib
import struct
from pathlib import Path

import numpy as np
import pytest
from cli_helpers import sweep_cli

from warptrunc._support.messages import MAX_MESSAGE_CHARS
from warptrunc._support.validate import MAX_INCREMENTS, MAX_SEEDS
from warptrunc.cli import main

COMMANDS = [
    "analyze",
    "bem-check",
    "calibrate",
    "compare",
    "describe",
    "generate",
    "islands",
    "render",
    "reproduce",
    "sweep",
]


def cli(argv, capsys) -> tuple[int, str]:
    """(exit status, stderr) of ``warptrunc ARGV`` run in-process."""
    try:
        code = main([str(a) for a in argv])
    except SystemExit as exc:
        code = exc.code
    return code, capsys.readouterr().err


def one_clean_line(code: int, err: str, *want: str, status: int = 2) -> str:
    """Assert exit ``status`` and exactly one short stderr line holding every ``want``."""
    assert code == status, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, f"not one line: {err[:2000]!r}"
    line = lines[0]
    assert "Traceback" not in err and len(line) <= MAX_MESSAGE_CHARS + 120, line  # + prefix
    for w in want:
        assert w in line, (w, line)
    return line


def out_argv(cmd: str, out: str, scan: Path) -> list[str]:
    """A command line of ``cmd`` whose output goes to ``out``."""
    if cmd == "generate":
        return [cmd, "-o", f"{out}/s.npz"]
    if cmd == "describe":
        return [cmd, scan, "--out", out]
    return [cmd, "--out", out]


@pytest.fixture
def scan(tmp_path) -> Path:
    f = tmp_path / "scan.npy"
    np.save(f, np.random.default_rng(0).normal(size=(16, 16)))
    return f


# --- --out the file system refuses -----------------------------------------------------------


@pytest.mark.parametrize("cmd", COMMANDS)
def test_out_with_a_name_too_long_is_one_line(cmd, scan, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    out = f"{tmp_path}/{'a' * 300}/x"  # ENAMETOOLONG from stat(): a real OSError, even as root
    code, err = cli(out_argv(cmd, out, scan), capsys)
    line = one_clean_line(code, err, "File name too long", " … ")
    assert "--out" in line or "--output" in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scan.npy"]


@pytest.mark.parametrize("cmd", COMMANDS)
def test_out_inside_a_folder_one_cannot_enter_is_one_line(cmd, scan, tmp_path, capsys, monkeypatch):
    """``stat()`` under a folder without x permission raises PermissionError (root is never
    refused, so the refusal is simulated at ``Path.stat``, which ``exists``/``is_dir`` use)."""
    locked = tmp_path / "locked"
    locked.mkdir()
    real_stat = pathlib.Path.stat

    def stat(self, *a, **k):
        if str(self.absolute()).startswith(str(locked) + os.sep):
            raise PermissionError(errno.EACCES, "Permission denied", str(self))
        return real_stat(self, *a, **k)

    monkeypatch.setattr(pathlib.Path, "stat", stat)
    code, err = cli(out_argv(cmd, str(locked / "sub"), scan), capsys)
    one_clean_line(
        code, err, "Permission denied", "locked/sub"
    )  # long paths are shortened in the middle
    assert not any(locked.iterdir())


def test_input_that_cannot_be_read_is_one_line(scan, capsys, monkeypatch):
    real_access = os.access
    monkeypatch.setattr(
        os, "access", lambda p, m, **k: False if str(p) == str(scan) else real_access(p, m, **k)
    )
    code, err = cli(["analyze", "-i", scan, "--dx", "1e-6"], capsys)
    one_clean_line(code, err, "--input", "not readable", str(scan))


# --- bounded work ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "argv, option",
    [
        (["analyze"], "--increments"),
        (["islands"], "--increments"),
        (["bem-check"], "--increments"),
        (["compare"], "--increments"),
        (["sweep", "--D", "2.3", "--delta", "0.01"], "--increments"),
        (["render"], "--vtk-increments"),
    ],
    ids=["analyze", "islands", "bem-check", "compare", "sweep", "render"],
)
def test_increments_above_the_cap_are_refused_at_once(argv, option, tmp_path, capsys):
    code, err = cli([*argv, option, 10_000_000, "--out", tmp_path / "o"], capsys)
    one_clean_line(code, err, f"{option}: must be an integer in [1, {MAX_INCREMENTS}]", "10000000")
    assert not (tmp_path / "o").exists()


def test_library_refuses_increments_above_the_cap():
    from warptrunc import from_heights, truncate

    s = from_heights(np.arange(16.0).reshape(4, 4), 1e-6)
    with pytest.raises(
        ValueError, match=rf"n_increments must be an integer in \[1, {MAX_INCREMENTS}\]"
    ):
        truncate(s, MAX_INCREMENTS + 1, device="cpu")


@pytest.mark.parametrize("seeds", ["0-100000000000", "0-600000,700000-1100000"])
def test_a_huge_seed_range_names_the_count_and_the_cap(seeds, tmp_path, capsys):
    code, err = cli(
        ["sweep", "--D", "2.3", "--delta", "0.01", "--seeds", seeds, "--out", tmp_path / "s"],
        capsys,
    )
    one_clean_line(code, err, "--seeds", f"more than {MAX_SEEDS} seeds")
    assert not (tmp_path / "s").exists()


def test_a_grid_with_too_many_cases_is_refused():
    from warptrunc.sweep import SweepGrid

    with pytest.raises(ValueError, match=r"2 D × 1 δ × 600000 seeds = 1200000 cases"):
        SweepGrid([2.3, 2.5], [0.01], "0-599999")


@pytest.mark.parametrize("cmd", ["analyze", "generate", "islands"])
def test_rt_beyond_float32_heights_is_a_range_error_not_an_overflow(cmd, tmp_path, capsys):
    # filterwarnings=error: an overflow warning would fail the test
    out = ["-o", tmp_path / "s.npz"] if cmd == "generate" else ["--out", tmp_path / "o"]
    code, err = cli([cmd, "--n", 64, "--Rt", "1e300", *out], capsys)
    one_clean_line(code, err, "--Rt: must be in (0, 1e+37] m", "1e300")
    assert not any(tmp_path.iterdir())


def test_a_topothesy_that_makes_heights_overflow_is_refused(tmp_path, capsys):
    code, err = cli(["generate", "--n", 64, "--G", "1e-300", "-o", tmp_path / "s.npz"], capsys)
    one_clean_line(code, err, "G = 1e-300 m gives heights of R_t", "float32")


# --- damaged store files -----------------------------------------------------------------------

SWEEP = sweep_cli("2.3", n="32")


@pytest.fixture
def store(tmp_path, capsys) -> Path:
    pytest.importorskip("pyarrow")
    out = tmp_path / "s"
    assert main([*SWEEP, "--out", str(out)]) == 0
    capsys.readouterr()
    return out


def test_a_truncated_sweep_json_is_named(store, capsys):
    meta = store / "sweep.json"
    meta.write_bytes(meta.read_bytes()[:100])
    code, err = cli([*SWEEP, "--out", store], capsys)
    one_clean_line(code, err, str(meta), "not valid JSON", "--overwrite")


@pytest.mark.parametrize(
    "lock",
    [b'{"pid":', b"\xff\xfe garbage", b'{"host": "x"}', "folder"],
    ids=["half-written", "binary", "no-pid", "a-folder"],
)
def test_an_unreadable_lock_says_so_not_pid_none(store, capsys, lock):
    f = store / ".lock"
    if lock == "folder":
        f.mkdir()
    else:
        f.write_bytes(lock)
    code, err = cli([*SWEEP, "--out", store], capsys)
    line = one_clean_line(code, err, "cannot be read", f"remove {f}")
    assert "pid None" not in line


# --- readers -----------------------------------------------------------------------------------


def opd_bytes(nx: int = 64, ny: int = 48) -> bytes:
    """A small Wyko OPD file (the layout of SurfaceTopography's OPD reader): a directory of
    blocks, a float32 raster, the wavelength and the pixel size."""
    z = np.random.default_rng(0).normal(size=(nx, ny)).astype("<f4")
    blocks = [
        ("RAW_DATA", 3, struct.pack("<HHH", nx, ny, 4) + z.tobytes()),
        ("Wavelength", 7, struct.pack("<f", 632.8)),
        ("Mult", 6, struct.pack("<h", 1)),
        ("Pixel_size", 7, struct.pack("<f", 0.001)),
    ]

    def head(name: str, typ: int, length: int) -> bytes:
        return struct.pack("<16shlH", name.encode().ljust(16, b"\0"), typ, length, 0)

    out = b"\x01\x00" + head("Directory", 3, 24 * (len(blocks) + 1))
    out += b"".join(head(n, t, len(d)) for n, t, d in blocks)
    return out + b"".join(d for _, _, d in blocks)


def test_a_half_cut_opd_gives_one_short_line(tmp_path, capsys):
    pytest.importorskip("SurfaceTopography")
    whole = tmp_path / "whole.opd"
    whole.write_bytes(opd_bytes())
    assert main(["describe", str(whole), "--methods", "box"]) == 0  # the file is valid
    capsys.readouterr()
    half = tmp_path / "half.opd"
    half.write_bytes(opd_bytes()[: len(opd_bytes()) // 2])
    code, err = cli(["describe", half], capsys)
    one_clean_line(code, err, str(half), "damaged or cut short", "OPDReader")


@pytest.mark.parametrize("suffix", [".opd", ".sur", ".x3p", ".npy", ".npz", ".csv", ".txt"])
def test_an_empty_file_is_called_empty(suffix, tmp_path, capsys):
    f = tmp_path / f"empty{suffix}"
    f.write_bytes(b"")
    code, err = cli(["describe", f], capsys)
    line = one_clean_line(code, err, str(f), "empty file (0 bytes)")
    assert "pixel spacing" not in line


@pytest.mark.parametrize(
    "where",
    [(3, 0, np.inf), (5, 1, -np.inf), (7, 0, np.nan)],
    ids=["x-inf", "y-minus-inf", "x-nan"],
)
def test_an_xyz_list_with_a_non_finite_coordinate_is_refused(where, tmp_path):
    from warptrunc.io import read_scan

    iy, ix = np.mgrid[0:4, 0:5]
    pts = np.column_stack([ix.ravel() * 1.0, iy.ravel() * 1.0, np.arange(20.0)])
    row, col, value = where
    pts[row, col] = value
    np.savetxt(tmp_path / "p.txt", pts)
    with pytest.raises(
        ValueError,
        match=rf"XYZ point list with a coordinate that is not finite \(data row {row + 1}",
    ):
        read_scan(tmp_path / "p.txt", dx=1e-6)  # no RuntimeWarning (warnings are errors)


def test_a_line_scan_with_infinite_x_is_still_a_line_scan(tmp_path):
    from warptrunc.io import read_scan

    np.savetxt(tmp_path / "xz.txt", np.column_stack([[0, np.inf, np.inf, 3, 4.0], np.arange(5.0)]))
    with pytest.raises(ValueError, match=r"line scan \(x, z\) of 5 points"):
        read_scan(tmp_path / "xz.txt", dx=1e-6)


# --- every other error ---------------------------------------------------------------------------


def test_a_long_option_value_is_shortened(capsys):
    code, err = cli(["generate", "--D", "9" * 5000], capsys)
    one_clean_line(code, err, "--D", " … ")


def test_an_out_of_memory_error_says_so(monkeypatch, tmp_path, capsys):
    import warptrunc.cli.generate as gen

    monkeypatch.setattr(gen, "surface_from_args", lambda args: (_ for _ in ()).throw(MemoryError()))
    code, err = cli(["generate", "-o", tmp_path / "s.npz"], capsys)
    one_clean_line(code, err, "warptrunc generate: error: out of memory")


def test_an_unexpected_error_is_one_line_with_exit_1(monkeypatch, tmp_path, capsys):
    import warptrunc.cli.generate as gen

    monkeypatch.setattr(gen, "surface_from_args", lambda args: {}["bug"])
    code, err = cli(["generate", "-o", tmp_path / "s.npz"], capsys)
    one_clean_line(code, err, "internal error: 'bug'", "--verbose", status=1)
    with pytest.raises(KeyError):  # --verbose shows the traceback
        main(["generate", "-o", str(tmp_path / "s.npz"), "--verbose"])


def test_an_error_line_is_capped():
    from warptrunc._support.messages import one_line

    text = "start " + "x\n" * 10**6 + " end"
    line = one_line(text)
    assert len(line) <= MAX_MESSAGE_CHARS and line.startswith("start") and line.endswith("end")
    assert "\n" not in line
    assert json.dumps(one_line("a\x00b\x1bc")) == '"a b c"'
