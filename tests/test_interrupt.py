# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""A stop signal swallowed in a destructor is raised again at the next safe point
(``warptrunc._support.interrupt``): CPython drops an exception raised inside ``__del__``."""

import os
import signal
import subprocess
import sys

from warptrunc._support.interrupt import check_interrupt, latched_signals


class _Stop(KeyboardInterrupt):
    pass


SCRIPT = """
import os, signal, sys
from warptrunc._support.interrupt import check_interrupt, latched_signals

class Stop(KeyboardInterrupt):
    pass

class SignalInDel:
    def __del__(self):
        os.kill(os.getpid(), signal.SIGUSR1)  # delivered while this destructor runs

with latched_signals({signal.SIGUSR1: Stop}):
    obj = SignalInDel()
    del obj  # the handler's exception is "ignored" inside __del__ ...
    print("went on", flush=True)
    try:
        check_interrupt()  # ... and raised again here
    except Stop:
        print("raised at the check", flush=True)
    check_interrupt()  # once only
    print("once", flush=True)
"""


def test_signal_swallowed_in_a_destructor_is_raised_at_the_check():
    """In a plain interpreter (pytest's own hook would re-raise the ignored exception)."""
    out = subprocess.run(
        [sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:3] == ["went on", "raised at the check", "once"], out
    assert "Exception ignored" in out.stderr  # the destructor did swallow it


def test_nothing_pending_without_a_signal_and_handlers_restored():
    before = signal.getsignal(signal.SIGUSR1)
    with latched_signals({signal.SIGUSR1: _Stop}):
        check_interrupt()
    assert signal.getsignal(signal.SIGUSR1) is before


def test_an_ignored_signal_stays_ignored():
    old = signal.signal(signal.SIGUSR1, signal.SIG_IGN)
    try:
        with latched_signals({signal.SIGUSR1: _Stop}):
            assert signal.getsignal(signal.SIGUSR1) is signal.SIG_IGN
            os.kill(os.getpid(), signal.SIGUSR1)
            check_interrupt()
    finally:
        signal.signal(signal.SIGUSR1, old)
