# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Error messages name the thing that failed: the file a write could not finish (under a
file-size limit), and a ``.npy``/``.npz`` that is no NumPy file at all."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from cli_helpers import sweep_cli

from warptrunc.io import read_height_map

ROOT = Path(__file__).resolve().parents[1]

LIMITED = """
import resource, signal, sys
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails with EFBIG
resource.setrlimit(resource.RLIMIT_FSIZE, (4000, 4000))
from warptrunc.cli import main
sys.exit(main(sys.argv[1:]))
"""


def _limited(
    argv: list[str], cwd: Path, *, warm: bool = True, env: dict | None = None
) -> subprocess.CompletedProcess:
    """``argv`` under a 4000-byte file-size limit; ``warm``: run once without it first (in a
    folder of its own), so that Warp's kernels of the command are compiled and cached and the
    limit meets the command's outputs, not the kernel cache."""
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)
    env = {
        **os.environ,
        "PYTHONPATH": path,
        "WARPTRUNC_DEVICE": "cpu",
        "MPLBACKEND": "Agg",
        **(env or {}),
    }
    if warm:
        (cwd / "warm").mkdir()
        subprocess.run(
            [sys.executable, "-m", "warptrunc", *argv],
            capture_output=True,
            env=env,
            cwd=cwd / "warm",
            timeout=300,
        )
    return subprocess.run(
        [sys.executable, "-c", LIMITED, *argv],
        capture_output=True,
        text=True,
        env=env,
        cwd=cwd,
        timeout=300,
    )


def _error_line(r: subprocess.CompletedProcess) -> str:
    lines = [ln for ln in r.stderr.strip().splitlines() if not ln.startswith("warning:")]
    assert r.returncode == 2 and len(lines) == 1, r.stderr[-2000:]
    return lines[0]


@pytest.mark.parametrize(
    ("argv", "named"),
    [
        (["generate", "--n", "256", "-o", "uf_s.npz"], "'uf_s.npz'"),
        (
            [
                "analyze",
                "--n",
                "64",
                "--Rt",
                "1e-6",
                "--Wr",
                "20e-6",
                "--L",
                "1e-4",
                "--min-pixels",
                "1",
                "--out",
                "res",
            ],
            "'res/curve.csv'",
        ),
    ],
    ids=["generate", "analyze"],
)
def test_a_file_size_limit_names_the_file(argv, named, tmp_path):
    line = _error_line(_limited(argv, tmp_path))
    assert "File too large" in line and "ulimit -f" in line, line
    assert line.endswith(f": {named}"), line


def test_a_kernel_cache_under_a_file_size_limit_is_named(tmp_path):
    # an empty kernel cache: the command's first act under the limit is to compile a kernel
    cache = tmp_path / "kernels"
    argv = ["generate", "--n", "64", "-o", "s.npz"]
    r = _limited(argv, tmp_path, warm=False, env={"WARP_CACHE_PATH": str(cache)})
    line = _error_line(r)
    assert "File too large" in line and "writing Warp's kernel cache under" in line, line
    assert str(cache.name) in line, line
    assert not (tmp_path / "s.npz").exists()


def test_a_sweep_under_a_file_size_limit_names_its_part(tmp_path):
    pytest.importorskip("pyarrow")
    argv = [
        *sweep_cli("2.3", "2.5"),
        "--out",
        "sw",
    ]
    line = _error_line(_limited(argv, tmp_path))
    assert "File too large" in line, line
    assert "'sw/curves/part-" in line and line.endswith(".parquet'"), line


@pytest.mark.parametrize("suffix", [".npz", ".npy"])
def test_a_text_file_with_a_numpy_name_is_not_a_numpy_archive(suffix, tmp_path):
    fake = tmp_path / f"fake{suffix}"
    fake.write_text("0.1 0.2 0.3\n0.4 0.5 0.6\n")
    with pytest.raises(ValueError) as err:
        read_height_map(fake, dx=1e-6)
    msg = str(err.value)
    assert msg.startswith(f"{fake}: not a numpy archive"), msg
    assert "holds text ('0.1 0.2 0.3' …)" in msg and ".csv, .txt or .tsv" in msg, msg
    assert "allow_pickle" not in msg


def test_other_bytes_and_pickled_objects_are_named_as_such(tmp_path):
    other = tmp_path / "other.npz"
    other.write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(100))
    with pytest.raises(
        ValueError,
        match=r"other\.npz: not a numpy archive: .*starts with the "
        r"bytes b'\\x89PNG",
    ):
        read_height_map(other, dx=1e-6)
    objects = tmp_path / "objects.npy"
    np.save(objects, np.array([{"z": 1.0}], dtype=object), allow_pickle=True)
    with pytest.raises(ValueError) as err:
        read_height_map(objects, dx=1e-6)
    assert "holds Python objects (pickled)" in str(err.value)
    assert "allow_pickle" not in str(err.value)
