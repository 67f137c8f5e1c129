# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One progress report for every long loop (bands, depths, sweep cases, calibration steps,
contact solves, animation frames, reproduction parts).

:func:`progress_bar` gives, on stderr:

- a tqdm bar with its total when stderr is a terminal;
- otherwise (a log file, a pipe, a batch job) plain lines, never ``\\r`` or cursor moves:
  one when the loop starts, one per finished piece at most every :func:`line_seconds` (5 s),
  one as often while a piece runs long (so a log shows the job is alive), and one at the end;
- nothing when ``enabled`` is false (the commands' ``--no-progress``).

A line reads ``indentation cycles: 12/90 cycles (13 %), 41 s, about 4.5 min left``.
"""

from __future__ import annotations

import os
import sys
import threading
import time
import weakref
from collections.abc import Iterable, Iterator
from typing import Any

__all__ = ["LINE_SECONDS", "LineProgress", "line_seconds", "progress_bar", "silence_progress"]

LINE_SECONDS = 5.0
"""Seconds between two progress lines when stderr is not a terminal (s), unless the
environment variable ``WARPTRUNC_PROGRESS_SECONDS`` gives another (a batch job's log may want
one a minute)."""


def line_seconds() -> float:
    """Seconds between two progress lines: ``$WARPTRUNC_PROGRESS_SECONDS`` when it is a positive
    number, else :data:`LINE_SECONDS` (s)."""
    try:
        v = float(os.environ.get("WARPTRUNC_PROGRESS_SECONDS", ""))
    except ValueError:
        return LINE_SECONDS
    return v if v > 0 and v == v and v != float("inf") else LINE_SECONDS


_silenced = False


def silence_progress(silent: bool = True) -> None:
    """Silence every progress report of this process (``--no-progress`` of a command: the
    loops it runs deep inside the package included), or let them speak again.

    Parameters
    ----------
    silent : bool
        True: :func:`progress_bar` reports nothing until called with False.
    """
    global _silenced
    _silenced = bool(silent)


def _terminal(stream: Any) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):  # closed or replaced streams
        return False


def _duration(s: float) -> str:
    if s < 90:
        return f"{s:.0f} s"
    if s < 5400:
        return f"{s / 60:.1f} min"
    return f"{s / 3600:.1f} h"


class LineProgress:
    """A progress report in plain lines on stderr (no ``\\r``): the tqdm methods warptrunc
    uses (``update``, ``set_postfix``, ``set_postfix_str``, ``set_description``, ``close``,
    iteration, the context manager, ``n`` and ``total``).

    Parameters
    ----------
    iterable : iterable, optional
        Items to iterate over, each counted as one piece when done.
    total : int, optional
        Pieces in all (``len(iterable)`` when it has one); None: counts without a total.
    desc : str
        What is counted, first on every line.
    unit : str
        The piece's name (``"case"``, ``"cycle"``).
    initial : int
        Pieces already done (a resumed run).
    every : float, optional
        Seconds between lines (s; default :func:`line_seconds`).
    stream : file, optional
        Where the lines go (default: ``sys.stderr`` at each write).
    """

    def __init__(
        self,
        iterable: Iterable | None = None,
        *,
        total: int | None = None,
        desc: str = "",
        unit: str = "it",
        initial: int = 0,
        every: float | None = None,
        stream: Any = None,
    ) -> None:
        every = line_seconds() if every is None else every
        if total is None and iterable is not None and hasattr(iterable, "__len__"):
            total = len(iterable)  # type: ignore[arg-type]
        self.iterable = iterable
        self.total = total
        self.desc = desc
        self.unit = unit
        self.n = initial
        self._initial = initial
        self._every = every
        self._stream = stream
        self._postfix = ""
        self._t0 = time.monotonic()
        self._last = self._t0  # the last line written
        self._piece = self._t0  # the last piece finished
        self._lock = threading.Lock()
        self._closed = False
        self._stop = threading.Event()
        self._line("started")
        # the thread holds the report weakly: a report dropped without close() stops it
        self._beat = threading.Thread(
            target=_heartbeat, args=(weakref.ref(self), self._stop, every), daemon=True
        )
        self._beat.start()

    # --- tqdm's interface ---------------------------------------------------------------------

    def update(self, n: int = 1) -> None:
        """Count ``n`` more pieces done; a line when the last one is ``every`` seconds old."""
        with self._lock:
            self.n += n
            self._piece = time.monotonic()
            due = self._piece - self._last >= self._every
        if due:
            self._line()

    def set_postfix(self, ordered_dict: Any = None, refresh: bool = True, **kw: Any) -> None:
        """Add ``key=value`` pairs to the next lines."""
        items = dict(ordered_dict or {}, **kw)
        self._postfix = ", ".join(f"{k}={v}" for k, v in items.items())

    def set_postfix_str(self, s: str = "", refresh: bool = True) -> None:
        """Add ``s`` to the next lines."""
        self._postfix = str(s)

    def set_description(self, desc: str | None = None, refresh: bool = True) -> None:
        """Change what the lines name."""
        self.desc = desc or ""

    def refresh(self) -> None:
        """Write a line now."""
        self._line()

    def write(self, s: str) -> None:
        """Write ``s`` as a line of its own."""
        self._write(s)

    def close(self) -> None:
        """The last line (pieces done, time taken); stops the heartbeat."""
        if self._closed:
            return
        self._closed = True
        self._stop.set()
        self._line("done" if self.total is None or self.n >= self.total else "stopped")

    def __iter__(self) -> Iterator:
        if self.iterable is None:
            raise TypeError("LineProgress without an iterable is not iterable")
        try:
            for item in self.iterable:
                yield item
                self.update()
        finally:
            self.close()

    def __enter__(self) -> LineProgress:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __len__(self) -> int:
        return 0 if self.total is None else int(self.total)

    # --- the lines ----------------------------------------------------------------------------

    def _text(self, state: str | None) -> str:
        now = time.monotonic()
        dt = now - self._t0
        head = f"{self.desc}: " if self.desc else ""
        units = self.unit + ("s" if self.unit and not self.unit.endswith("s") else "")
        if self.total:
            count = f"{self.n}/{self.total} {units} ({100.0 * self.n / self.total:.0f} %)"
        else:
            count = f"{self.n} {units}"
        parts = [count, _duration(dt)]
        done = self.n - self._initial
        if state in (None, "running") and self.total and 0 < done and self.n < self.total:
            parts.append(f"about {_duration(dt / done * (self.total - self.n))} left")
        if state == "running":
            parts.append(f"this {self.unit} running for {_duration(now - self._piece)}")
        elif state in ("started", "done", "stopped"):
            parts.append(state)
        text = head + ", ".join(parts)
        return text + (f" [{self._postfix}]" if self._postfix else "")

    def _line(self, state: str | None = None) -> None:
        with self._lock:
            text = self._text(state)
            self._last = time.monotonic()
        self._write(text)

    def _write(self, text: str) -> None:
        stream = self._stream if self._stream is not None else sys.stderr
        try:
            stream.write(text + "\n")
            stream.flush()
        except (OSError, ValueError):  # a closed stream: the job goes on without its report
            pass


def _heartbeat(ref: Any, stop: threading.Event, every: float) -> None:
    """A line every ``every`` seconds without one (a piece running long), until ``stop``."""
    while not stop.wait(every / 2):
        bar = ref()
        if bar is None:
            return
        now = time.monotonic()
        if now - bar._last >= every:
            bar._line("running" if now - bar._piece >= every else None)
        del bar


class _Silent:
    """No report: the tqdm methods as no-ops (``enabled=False``)."""

    def __init__(self, iterable: Iterable | None, total: int | None, initial: int) -> None:
        self.iterable, self.total, self.n = iterable, total, initial

    def update(self, n: int = 1) -> None:
        self.n += n

    def set_postfix(self, *a: Any, **kw: Any) -> None:
        pass

    set_postfix_str = set_description = refresh = write = close = set_postfix

    def __iter__(self) -> Iterator:
        return iter(self.iterable if self.iterable is not None else ())

    def __enter__(self) -> _Silent:
        return self

    def __exit__(self, *exc: Any) -> None:
        pass


def progress_bar(
    iterable: Iterable | None = None,
    *,
    total: int | None = None,
    desc: str,
    unit: str,
    enabled: bool = True,
    initial: int = 0,
    leave: bool = True,
    every: float | None = None,
) -> Any:
    """The progress report of a long loop on stderr: a tqdm bar on a terminal, plain lines
    otherwise (:class:`LineProgress`), nothing when ``enabled`` is false.

    Parameters
    ----------
    iterable : iterable, optional
        Items to iterate over (each one piece).
    total : int, optional
        Pieces in all; give it whenever it is known (the bar and the lines show it).
    desc : str
        What is counted.
    unit : str
        The piece's name, singular.
    enabled : bool
        Report at all (false, or :func:`silence_progress`: nothing).
    initial : int
        Pieces already done (a resumed run).
    leave : bool
        Keep the terminal bar when it ends.
    every : float, optional
        Seconds between lines off a terminal (s; default :func:`line_seconds`).

    Returns
    -------
    tqdm.tqdm or LineProgress
        Usable as a context manager and an iterator, with ``update`` and ``set_postfix``.
    """
    if not enabled or _silenced:
        return _Silent(iterable, total, initial)
    if not _terminal(sys.stderr):
        return LineProgress(
            iterable, total=total, desc=desc, unit=unit, initial=initial, every=every
        )
    from tqdm.auto import tqdm  # here, not at the top: tqdm.auto costs ~65 ms of start-up

    return tqdm(iterable, total=total, desc=desc, unit=unit, initial=initial, leave=leave)
