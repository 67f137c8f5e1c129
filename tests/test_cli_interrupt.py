# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Ctrl-C: every command stops with one line on stderr (what was kept, how to go on) and exit
status 130 (``warptrunc.cli.main``).

The commands run in a child process of their own session; SIGINT goes to the whole process
group about 1 s after the child reaches the command line, as a terminal's Ctrl-C does (so the
figure helper of ``analyze`` gets it too). The sizes are small CPU runs that take several
seconds here, so the signal comes while they compute; ``--no-progress`` where a command has
it, so that the lines counted are the command's own.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from cli_helpers import INDENT_CLI, compare_cli

from warptrunc._support.outputs import kept_stores, store_rollback
from warptrunc.cli import _interrupted_text

ROOT = Path(__file__).resolve().parents[1]

COMMANDS = {
    "analyze": ["analyze", "--n", "4096"],
    "bem-check": ["bem-check", "--n", "128", "--no-progress"],
    "islands": ["islands", "--n", "256", "--no-progress"],
    "compare": compare_cli("2.3", "32", "0-3"),
    "indent": INDENT_CLI,
}

# Python's own SIGINT handler in the child: a shell's background job (`bash .ci/run &`) starts
# it with SIGINT ignored, and then no KeyboardInterrupt ever comes
CHILD = (
    "import runpy, signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
    "print('ready', flush=True); sys.argv[0] = 'warptrunc'; "
    "runpy.run_module('warptrunc', run_name='__main__', alter_sys=True)"
)


@pytest.mark.timeout(300)
@pytest.mark.parametrize("name", list(COMMANDS))
def test_ctrl_c_is_one_line_and_exit_130(name, tmp_path):
    out = tmp_path / "out"
    env = {
        **os.environ,
        "WARPTRUNC_DEVICE": "cpu",
        "MPLBACKEND": "Agg",
        "PYTHONPATH": os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p),
    }
    p = subprocess.Popen(
        [sys.executable, "-c", CHILD, *COMMANDS[name], "--out", str(out)],
        cwd=tmp_path,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        assert p.stdout.readline().strip() == "ready"
        time.sleep(1.0)
        os.killpg(p.pid, signal.SIGINT)  # the terminal's Ctrl-C: the whole process group
        stdout, stderr = p.communicate(timeout=120)
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.communicate()
    lines = stderr.strip().splitlines()
    assert p.returncode == 130, (p.returncode, stdout, stderr)
    assert 1 <= len(lines) <= 3, stderr
    assert lines[-1].startswith(f"warptrunc {name}: interrupted; "), stderr
    if name == "compare" and out.exists():  # a finished case stays in its store
        assert any((out / "cases").glob("*.parquet"))
        assert f"the finished cases stay in '{out}'" in lines[-1], stderr
    else:
        assert "nothing was written" in lines[-1] and not out.exists(), stderr


def test_the_message_names_the_store_kept_and_how_to_go_on(tmp_path):
    store = tmp_path / "store"
    before = len(kept_stores())
    with pytest.raises(KeyboardInterrupt), store_rollback(store, keep=lambda: True):
        (store / "cases").mkdir(parents=True)
        raise KeyboardInterrupt
    kept = kept_stores()[before:]
    assert kept == [store]
    text = _interrupted_text("compare", kept)
    assert text == (
        f"warptrunc compare: interrupted; the finished cases stay in '{store}': "
        "run the same command again to finish the rest"
    )
    assert "start over" in _interrupted_text("analyze", [])


SWALLOWED = """
import os, signal, sys
from warptrunc.cli import _interrupt_in_destructor

sys.unraisablehook = _interrupt_in_destructor(sys.unraisablehook)

class SignalInDel:
    def __del__(self):
        os.kill(os.getpid(), signal.SIGINT)  # Ctrl-C while a destructor runs

try:
    obj = SignalInDel()
    del obj
    for _ in range(10**7):  # the program goes on ...
        pass
    print("went on to the end", flush=True)
except KeyboardInterrupt:
    print("raised where the program went on", flush=True)
"""


def test_ctrl_c_in_a_destructor_is_raised_where_the_program_goes_on():
    """In a plain interpreter: CPython drops an exception raised inside ``__del__``."""
    r = subprocess.run(
        [sys.executable, "-c", SWALLOWED], capture_output=True, text=True, timeout=120, cwd=ROOT
    )
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "raised where the program went on", r
    assert "Exception ignored" not in r.stderr
