# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Issue 30: all-or-nothing outputs of every command, under a file-size limit and a full disk.

A command that cannot write its outputs exits 2 with one line, leaves the outputs of an
earlier run byte for byte, and leaves no new file (no staging folder, no ``.partial``/``.tmp``
file, no empty folder). The file-size limit is ``RLIMIT_FSIZE`` in a subprocess (SIGXFSZ
ignored, so a write past it fails with EFBIG); the full disk is a small tmpfs where one may
mount it (root; 16 KiB), else writes under the output folder fail with ENOSPC (injected).
"""

from __future__ import annotations

import errno
import io
import os
import subprocess
import sys
import uuid
from pathlib import Path

import numpy as np
import pytest
from cli_helpers import CALIBRATE_CLI, QUICK_CALIBRATION, RENDER_CLI, SMALL, compare_cli, sweep_cli

from warptrunc._support.outputs import staged_outputs, store_rollback
from warptrunc.cli import main

ROOT = Path(__file__).resolve().parents[1]


def _has(mod: str) -> bool:
    try:
        __import__(mod)
    except ImportError:
        return False
    return True


def commands(scan: Path, out: Path) -> dict[str, list[str]]:
    """Small command lines of the commands that write files, all into ``out``."""
    cmds = {
        "analyze": ["analyze", *SMALL, "--min-pixels", "1", "--out", out / "analyze"],
        "bem-check": [
            "bem-check",
            "--n",
            "32",
            "--maxiter",
            "200",
            "--accept-unconverged",
            "--no-progress",
            "--out",
            out / "bem",
        ],
        "describe": [
            "describe",
            scan,
            "--dx",
            "1e-6",
            "--methods",
            "box",
            "--json",
            out / "d.json",
            "--out",
            out / "describe",
        ],
        "islands": ["islands", *SMALL, "--increments", "50", "--no-progress", "--out", out / "islands"],
        "generate": ["generate", "--n", "256", "-o", out / "surface.npz"],
        "calibrate": [
            *CALIBRATE_CLI,
            "--n-out",
            "128",
            *QUICK_CALIBRATION,
            "--out",
            out / "cal",
        ],
    }
    if _has("pyarrow"):
        cmds["sweep"] = [
            *sweep_cli("2.3", "2.5"),
            "--out",
            out / "sweep",
        ]
        cmds["compare"] = [
            *compare_cli("2.3", "16", "0"),
            "--out",
            out / "compare",
        ]
    if _has("pyvista"):
        cmds["render"] = [
            *RENDER_CLI,
            "--size",
            "120",
            "100",
            "--out",
            out / "render",
        ]
    return {k: [str(a) for a in v] for k, v in cmds.items()}


def snapshot(root: Path) -> dict[str, bytes | None]:
    return {
        str(p.relative_to(root)): (None if p.is_dir() else p.read_bytes())
        for p in sorted(root.rglob("*"))
    }


@pytest.fixture
def scan(tmp_path_factory) -> Path:
    f = tmp_path_factory.mktemp("scan") / "scan.npy"
    np.save(f, np.random.default_rng(0).normal(size=(64, 64)))
    return f


# --- file-size limit -----------------------------------------------------------------------------

LIMITED = """
import resource, signal, sys
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, ({limit}, {limit}))
from warptrunc.cli import main
sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.parametrize(
    "name",
    [
        "analyze",
        "bem-check",
        "describe",
        "islands",
        "generate",
        "calibrate",
        "sweep",
        "compare",
        "render",
    ],
)
def test_a_file_size_limit_keeps_the_earlier_outputs_and_adds_nothing(name, scan, tmp_path, capsys):
    cmds = commands(scan, tmp_path / "out")
    if name not in cmds:
        pytest.skip(f"{name} needs an optional extra")
    argv = cmds[name]
    if name in ("sweep", "compare"):  # resumable stores: a finished case stays by design
        (tmp_path / "out").mkdir()
    else:
        assert main(argv) in (0, 3), capsys.readouterr().err  # the earlier run (3: unconverged)
    capsys.readouterr()
    before = snapshot(tmp_path / "out")
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)
    env = {**os.environ, "PYTHONPATH": path, "WARPTRUNC_DEVICE": "cpu", "MPLBACKEND": "Agg"}
    r = subprocess.run(
        [sys.executable, "-c", LIMITED.format(limit=4000), *argv],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=300,
    )
    # plausibility warnings (one "warning:" line each) may precede the error
    lines = [ln for ln in r.stderr.strip().splitlines() if not ln.startswith("warning:")]
    assert r.returncode == 2, r.stderr[-2000:]
    assert len(lines) == 1 and "File too large" in lines[0] and len(lines[0]) < 500, r.stderr
    assert snapshot(tmp_path / "out") == before


# --- full disk -----------------------------------------------------------------------------------


@pytest.fixture
def full_disk(tmp_path, monkeypatch):
    """A folder on a 16 KiB file system (tmpfs, when this process may mount one), else a folder
    under which every write past 2 KiB fails with ENOSPC."""
    d = tmp_path / "disk"
    d.mkdir()
    mounted = False
    if hasattr(os, "geteuid") and os.geteuid() == 0 and sys.platform.startswith("linux"):
        r = subprocess.run(
            ["mount", "-t", "tmpfs", "-o", "size=16k", "tmpfs", str(d)], capture_output=True
        )
        mounted = r.returncode == 0
    if not mounted:
        _inject_enospc(monkeypatch, d, 2048)
    try:
        yield d
    finally:
        if mounted:
            subprocess.run(["umount", str(d)], check=True)


class _Limited:
    """A file object whose writes fail with ENOSPC once ``limit`` bytes are written."""

    def __init__(self, f, limit: int) -> None:
        self._f, self._left = f, limit

    def write(self, b):
        self._left -= len(b)
        if self._left < 0:
            raise OSError(errno.ENOSPC, "No space left on device")
        return self._f.write(b)

    def __getattr__(self, name):
        return getattr(self._f, name)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._f.close()

    def __iter__(self):
        return iter(self._f)


def _inject_enospc(monkeypatch, root: Path, limit: int) -> None:
    """Every file opened for writing under ``root`` fails with ENOSPC past ``limit`` bytes."""
    import builtins

    real_open = io.open

    def fake_open(file, mode="r", *a, **k):
        f = real_open(file, mode, *a, **k)
        if isinstance(file, (str, os.PathLike)) and any(c in mode for c in "wax+"):
            if os.path.abspath(file).startswith(str(root)):
                return _Limited(f, limit)
        return f

    monkeypatch.setattr(builtins, "open", fake_open)
    monkeypatch.setattr(io, "open", fake_open)


@pytest.mark.parametrize(
    "name",
    ["analyze", "bem-check", "describe", "islands", "generate", "calibrate", "sweep", "compare"],
)
def test_a_full_disk_leaves_nothing_behind(name, scan, full_disk, capsys):
    cmds = commands(scan, full_disk / "out")
    if name not in cmds:
        pytest.skip(f"{name} needs an optional extra")
    code = main(cmds[name])
    err = capsys.readouterr().err
    lines = [ln for ln in err.strip().splitlines() if not ln.startswith("warning:")]
    assert code == 2, err
    assert len(lines) == 1 and "No space left on device" in lines[0], err
    left = [p for p in full_disk.rglob("*")]
    assert left == [], left


@pytest.mark.parametrize("name", ["analyze", "describe", "generate", "calibrate"])
def test_an_injected_enospc_leaves_nothing_behind(name, scan, tmp_path, monkeypatch, capsys):
    """The same without a mount: the writers themselves fail (Python's open)."""
    _inject_enospc(monkeypatch, tmp_path / "disk", 2048)
    code = main(commands(scan, tmp_path / "disk" / "out")[name])
    err = capsys.readouterr().err
    assert code == 2 and "No space left on device" in err, err
    assert not (tmp_path / "disk").exists()


# --- the scheduler that is not there -----------------------------------------------------------------


def test_an_unreachable_scheduler_leaves_nothing(tmp_path, capsys):
    pytest.importorskip("distributed")
    import dask

    out = tmp_path / "s"
    with dask.config.set({"distributed.comm.timeouts.connect": "1s"}):
        code = main(
            [
                "sweep",
                "--D",
                "2.3",
                "--delta",
                "0.01",
                "--n",
                "32",
                "--no-progress",
                "--scheduler",
                "tcp://127.0.0.1:1",
                "--out",
                str(out),
            ]
        )
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert not out.exists()


# --- the mechanism ---------------------------------------------------------------------------------


def test_staged_outputs_commits_folders_and_files_together(tmp_path):
    (tmp_path / "old").mkdir()
    (tmp_path / "old" / "a.txt").write_text("old a")
    with pytest.raises(RuntimeError), staged_outputs() as st:
        (st.folder(tmp_path / "old") / "a.txt").write_text("new a")
        st.file(tmp_path / "new" / "b.json").write_text("{}")
        raise RuntimeError
    assert snapshot(tmp_path) == {"old": None, "old/a.txt": b"old a"}
    with staged_outputs() as st:
        (st.folder(tmp_path / "old") / "a.txt").write_text("new a")
        st.file(tmp_path / "new" / "b.json").write_text("{}")
        assert not (tmp_path / "new" / "b.json").exists()  # nothing is in place before the end
    assert snapshot(tmp_path) == {
        "new": None,
        "new/b.json": b"{}",
        "old": None,
        "old/a.txt": b"new a",
    }
    assert oct((tmp_path / "new" / "b.json").stat().st_mode & 0o777) == "0o644"


def test_staged_outputs_names_the_output_of_an_anonymous_os_error(tmp_path):
    with pytest.raises(OSError) as e, staged_outputs() as st:
        st.folder(tmp_path / "x")
        raise OSError(errno.ENOSPC, "No space left on device")
    assert e.value.filename == str(tmp_path / "x") and not (tmp_path / "x").exists()


def test_store_rollback_removes_only_what_the_failed_run_made(tmp_path):
    out = tmp_path / "store"
    out.mkdir()
    (out / "kept.parquet").write_bytes(b"old")
    with pytest.raises(KeyboardInterrupt), store_rollback(out, keep=lambda: False):
        (out / "meta.json").write_text("{}")
        (out / "parts").mkdir()
        (out / "parts" / uuid.uuid4().hex).write_text("x")
        raise KeyboardInterrupt
    assert snapshot(out) == {"kept.parquet": b"old"}
    with pytest.raises(ValueError), store_rollback(tmp_path / "new" / "s", keep=lambda: True):
        (tmp_path / "new" / "s").mkdir(parents=True)
        (tmp_path / "new" / "s" / "part").write_text("done")
        raise ValueError
    assert (tmp_path / "new" / "s" / "part").read_text() == "done"  # finished work is kept
    with pytest.raises(ValueError), store_rollback(tmp_path / "n2" / "s", keep=lambda: False):
        (tmp_path / "n2" / "s").mkdir(parents=True)
        raise ValueError
    assert not (tmp_path / "n2").exists()
