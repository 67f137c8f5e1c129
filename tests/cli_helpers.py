# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Small command lines and checks of the command line shared by the tests (not a test
module)."""

import subprocess
import sys

from warptrunc.cli import main

__all__ = [
    "CALIBRATE_CLI",
    "INDENT_CLI",
    "QUICK_CALIBRATION",
    "RENDER_CLI",
    "SMALL",
    "assert_refused_in_one_line",
    "compare_cli",
    "run_cli",
    "sweep_cli",
]

SMALL = ["--n", "64", "--Rt", "1e-6", "--Wr", "20e-6", "--L", "1e-4"]
"""A small generated WM map: 64² over 0.1 mm, R_t = 1 µm, W_r = 20 µm."""

CALIBRATE_CLI = [
    "calibrate",
    "--D",
    "2.4",
    "--Rrms",
    "1e-7",
    "--Rt",
    "1e-6",
    "--Wr",
    "2e-5",
    "--L",
    "1e-4",
    "--n",
    "32",
]
"""``warptrunc calibrate`` to a small WM target (32² over 0.1 mm)."""

QUICK_CALIBRATION = ["--seeds", "0", "--max-iter", "2", "--rtol", "0.9", "--no-progress"]
"""A calibration that stops after two steps: one seed, a loose tolerance, no progress bars."""

INDENT_CLI = [
    "indent",
    "--n",
    "64",
    "--L",
    "0.4e-3",
    "--Rt",
    "2e-6",
    "--punch-diameters",
    "1.5e-4",
    "--peak-loads",
    "1e-3",
    "4e-3",
    "1.6e-2",
    "--placements",
    "2",
    "--no-progress",
    "--refine-max",
    "2",
]
"""A small ``warptrunc indent``: 64² over 0.4 mm, one punch, three loads, two placements."""

RENDER_CLI = ["render", "--n", "32", "--depth-fractions", "0.3"]
"""``warptrunc render`` of one section of a 32² map (the image size is the caller's)."""


def run_cli(*args, cwd=None, env=None) -> subprocess.CompletedProcess:
    """``python -m warptrunc ARGS`` as a user runs it: a subprocess in ``cwd`` with ``env``
    (default: this one's), its output captured as text, stopped after 300 s."""
    return subprocess.run(
        [sys.executable, "-m", "warptrunc", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=300,
        env=env,
    )


def sweep_cli(*D: str, n: str = "64") -> list[str]:
    """A small ``warptrunc sweep``: the D values ``D`` at δ = 0.01 on n² maps, fits from one
    contact pixel, no progress bars."""
    return ["sweep", "--D", *D, "--delta", "0.01", "--n", n, "--min-pixels", "1", "--no-progress"]


def compare_cli(D: str, pixels_per_wr: str, seeds: str) -> list[str]:
    """A small ``warptrunc compare``: one D at L = W_r, ``pixels_per_wr`` pixels, no
    refinement, the ``seeds``, approaches 0.1 and 0.2·R_t, no progress bars, no figures."""
    return [
        "compare",
        "--D",
        D,
        "--size-ratios",
        "1",
        "--pixels-per-wr",
        pixels_per_wr,
        "--refine-ratio",
        "none",
        "--seeds",
        seeds,
        "--fractions",
        "0.1",
        "0.2",
        "--no-progress",
        "--no-plot",
    ]


def assert_refused_in_one_line(args, out, capsys, needles) -> None:
    """``warptrunc ARGS --out OUT`` exits 2 with one stderr line holding every needle, and
    writes no OUT."""
    import pytest

    with pytest.raises(SystemExit) as e:
        raise SystemExit(main([*args, "--out", str(out)]))
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    for n in needles:
        assert n in err, (n, err)
    assert not out.exists()
