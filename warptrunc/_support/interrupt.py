# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stop signals that are not lost in a destructor.

Python raises a signal handler's exception wherever the main thread happens to be; when that is
inside a ``__del__`` (Warp frees an array there) the exception is printed as "Exception ignored
in …" and dropped, and a long command carries on as if the signal never came. A command that
must stop on Ctrl-C or SIGTERM installs :func:`latched_signals`: its handlers record the signal
before raising, and :func:`check_interrupt`, called between units of work, raises it again if it
was swallowed.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["check_interrupt", "latched_signals"]

_pending: list[type[BaseException]] = []


def check_interrupt() -> None:
    """Raise the stop signal's exception if one was recorded and not yet raised to the end.

    Raises
    ------
    KeyboardInterrupt
        A signal of :func:`latched_signals` came (its exception class, e.g. a
        ``KeyboardInterrupt`` subclass for SIGTERM).
    """
    if _pending:
        raise _pending.pop()()


@contextmanager
def latched_signals(handlers: dict[int, type[BaseException]]) -> Iterator[None]:
    """Within the block, each signal in ``handlers`` records its exception class and raises it.

    Parameters
    ----------
    handlers : dict
        Signal number → the exception class to raise (``KeyboardInterrupt`` or a subclass).
        A signal whose present handler is ``SIG_IGN`` (a shell's background job ignores
        SIGINT) stays ignored. Off the main thread nothing is installed.

    Yields
    ------
    None
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = {}
    for sig, exc in handlers.items():
        if signal.getsignal(sig) is signal.SIG_IGN:
            continue

        def handler(signum, frame, exc=exc):
            _pending[:] = [exc]
            raise exc()

        old[sig] = signal.signal(sig, handler)
    _pending.clear()
    try:
        yield
    finally:
        for sig, h in old.items():
            signal.signal(sig, h)
        _pending.clear()
