# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Every long command talks on a redirected stderr in plain lines (no ``\\r``, no cursor
moves), with its total, and ``--no-progress`` silences it. References: the lines a
subprocess writes into a pipe as they arrive, and the counts the loop was given."""

from __future__ import annotations

import io
import itertools
import os
import subprocess
import sys
import threading
import time

import pytest

from warptrunc._support.progress import LineProgress, line_seconds, progress_bar


def test_lines_carry_the_total_and_no_carriage_return():
    buf = io.StringIO()
    with LineProgress(total=4, desc="cases", unit="case", every=3600, stream=buf) as bar:
        for _ in range(4):
            bar.update()
    lines = buf.getvalue().splitlines()
    assert lines[0] == "cases: 0/4 cases (0 %), 0 s, started"
    assert lines[-1].startswith("cases: 4/4 cases (100 %)") and lines[-1].endswith("done")
    assert "\r" not in buf.getvalue() and "\x1b" not in buf.getvalue()


def test_a_piece_that_runs_long_still_gives_lines():
    buf = io.StringIO()
    bar = LineProgress(total=2, desc="solves", unit="solve", every=0.1, stream=buf)
    time.sleep(0.6)  # one piece, six intervals: the heartbeat writes meanwhile
    bar.close()
    running = [ln for ln in buf.getvalue().splitlines() if "this solve running for" in ln]
    assert running and all(ln.startswith("solves: 0/2 solves (0 %)") for ln in running)


def test_off_a_terminal_the_report_is_lines_and_silenced_on_request(monkeypatch):
    from warptrunc._support.progress import silence_progress

    monkeypatch.setattr(sys, "stderr", io.StringIO())  # not a terminal
    bar = progress_bar(total=3, desc="x", unit="frame")
    assert isinstance(bar, LineProgress)
    bar.close()
    silence_progress(True)
    try:
        assert not isinstance(progress_bar(total=3, desc="x", unit="frame"), LineProgress)
    finally:
        silence_progress(False)
    monkeypatch.setenv("WARPTRUNC_PROGRESS_SECONDS", "60")
    assert line_seconds() == 60.0
    monkeypatch.setenv("WARPTRUNC_PROGRESS_SECONDS", "soon")
    assert line_seconds() == 5.0


def _stderr_lines(argv, cwd, timeout=300):
    """Run ``python -m warptrunc ARGV`` with stderr in a pipe: (exit status, [(seconds since
    the start, line)], the raw bytes of stderr)."""
    env = {**os.environ, "WARPTRUNC_DEVICE": "cpu", "WARPTRUNC_PROGRESS_SECONDS": "1"}
    t0 = time.monotonic()
    p = subprocess.Popen(
        [sys.executable, "-m", "warptrunc", *argv],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        cwd=cwd,
        env=env,
    )
    raw: list[bytes] = []
    seen: list[tuple[float, str]] = []

    def read() -> None:
        for line in p.stderr:
            raw.append(line)
            seen.append((time.monotonic() - t0, line.decode("utf-8", "replace").rstrip("\n")))

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    code = p.wait(timeout=timeout)
    reader.join(timeout=10)
    p.stderr.close()
    return code, seen, b"".join(raw), time.monotonic() - t0


def _check_report(seen, raw, wall, what):
    lines = [(t, s) for t, s in seen if s.startswith(what)]
    assert len(lines) >= 2, f"no progress lines of {what!r} in {[s for _, s in seen]}"
    assert b"\r" not in raw and b"\x1b" not in raw
    assert "started" in lines[0][1] and "done" in lines[-1][1]
    assert "/" in lines[0][1]  # the total is shown
    # within 10 s of the start, and never 10 s without a line while the loop runs
    times = [t for t, _ in lines]
    assert times[0] <= 10.0, f"first progress line after {times[0]:.1f} s"
    assert max(b - a for a, b in itertools.pairwise(times)) <= 10.0


def test_indent_reports_in_lines_on_a_redirected_stderr(tmp_path):
    argv = ["indent", "--n", "128", "--map-side", "0.5e-3", "--punch-diameters", "1e-4",
            "--peak-loads", "0.05", "0.1", "--no-plot", "--out", str(tmp_path / "ind")]  # fmt: skip
    code, seen, raw, wall = _stderr_lines(argv, tmp_path)
    assert code in (0, 3), raw.decode()
    _check_report(seen, raw, wall, "indentation cycles")
    code, seen, raw, _ = _stderr_lines(
        [*argv[:-1], str(tmp_path / "quiet"), "--no-progress"], tmp_path
    )
    assert code in (0, 3) and not [s for _, s in seen if s.startswith("indentation cycles")]


def test_render_animate_reports_in_lines_on_a_redirected_stderr(tmp_path):
    pytest.importorskip("pyvista")
    argv = ["render", "--n", "64", "--size", "300", "200", "--animate", "--frames", "4",
            "--out", str(tmp_path / "r")]  # fmt: skip
    # once before, so that the lines timed are the loop's, not a cold kernel cache's compiles
    # and pyvista's first import (which precede the loop and its first line)
    _stderr_lines([*argv[:-1], str(tmp_path / "warm")], tmp_path)
    code, seen, raw, wall = _stderr_lines(argv, tmp_path)
    assert code == 0, raw.decode()
    _check_report(seen, raw, wall, "animation")
    assert any("4/5 frames" in s or "5/5 frames" in s for _, s in seen)
