# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Figures drawn in a helper process while the job computes.

``warptrunc analyze`` spends most of what it adds to a Warp program's start on matplotlib: its
import (about 0.3 s) and two figures (0.1–0.3 s each). In the job's own process both run under
the GIL beside Warp's import and the launches, so a thread overlaps them little. A
:class:`FigureWorker` starts a helper Python process first thing, which imports matplotlib and
the figure modules (no Warp) and, if the job has sent nothing yet, draws a small figure to warm
matplotlib's caches (its mathtext parser, fonts, glyphs), while the job imports Warp and
computes; the job sends it each figure's data as soon as that is final (the area
fraction before the island pass, the stiffness figure after it) and gets the PNG bytes back,
which it writes into its staged output folder itself (all or nothing, as before).

The figure is the same call (:mod:`warptrunc.plot`, same data, same DPI) as in the job's own
process, so the files are the same pixels. An error raised by the drawing is raised again in
the job (its type and message, the helper's traceback chained); a helper that cannot start or
dies is replaced by drawing in the job's process. The helper is used when matplotlib is not
loaded yet (a fresh ``warptrunc`` command); where it is (a notebook, a test session) drawing
in-process is cheaper. ``WARPTRUNC_FIGURE_PROCESS=0`` always draws in-process.
"""

from __future__ import annotations

import os
import pickle
import queue
import signal
import subprocess
import sys
import threading
import traceback
from pathlib import Path
from types import SimpleNamespace
from typing import Any

ENV = "WARPTRUNC_FIGURE_PROCESS"
"""Environment variable: ``0`` draws every figure in the job's own process."""


class FigureProcessError(RuntimeError):
    """The helper's traceback, chained to a drawing error raised again in the job (or the error
    itself, when it cannot be pickled)."""


def plain(obj: Any, *names: str) -> SimpleNamespace:
    """The attributes ``names`` of a result object in a plain namespace (NumPy arrays and
    floats), which the helper unpickles without importing the module (and Warp) that defines
    the object's class.

    Parameters
    ----------
    obj : object
        A result object (a curve, a fit).
    *names : str
        The attributes that the figure reads.

    Returns
    -------
    types.SimpleNamespace
    """
    return SimpleNamespace(**{n: getattr(obj, n) for n in names})


def png_bytes(name: str, args: tuple, kwargs: dict) -> bytes:
    """Draw ``warptrunc.plot.<name>(*args, **kwargs)`` and return it as PNG bytes, saved as
    :func:`warptrunc.plot._style.finish_figure` saves it (the same DPI)."""
    from io import BytesIO

    from .. import plot
    from ._style import DPI

    fig = getattr(plot, name)(*args, **kwargs)
    buf = BytesIO()
    fig.savefig(buf, format="png", dpi=DPI)
    return buf.getvalue()


class FigureWorker:
    """Draws figures to PNG bytes, in a helper process started at construction or in this
    process.

    Parameters
    ----------
    process : bool, optional
        Use a helper process; None: unless matplotlib is loaded already or
        ``WARPTRUNC_FIGURE_PROCESS=0``.

    Notes
    -----
    :meth:`submit` sends a figure's data at once and returns a ticket; :meth:`result` waits
    for its bytes (raising the drawing's error). Use as a context manager: leaving it ends the
    helper (at once when an exception leaves it).
    """

    def __init__(self, process: bool | None = None) -> None:
        if process is None:
            process = os.environ.get(ENV, "1") != "0" and "matplotlib.figure" not in sys.modules
        self._sent: list[tuple[str, tuple, dict]] = []
        self._done: dict[int, bytes] = {}
        self._proc: subprocess.Popen | None = None
        self._replies: queue.Queue = queue.Queue()
        self._reader: threading.Thread | None = None
        if process:
            root = str(Path(__file__).resolve().parents[2])
            code = (
                f"import sys; sys.path.insert(0, {root!r}); "
                "from warptrunc.plot._worker import serve; serve()"
            )
            try:
                self._proc = subprocess.Popen(
                    [sys.executable, "-c", code], stdin=subprocess.PIPE, stdout=subprocess.PIPE
                )
            except OSError:  # no helper: draw here
                self._proc = None
            else:
                self._reader = threading.Thread(
                    target=self._read, name="warptrunc-figures", daemon=True
                )
                self._reader.start()

    @property
    def in_process(self) -> bool:
        """Whether the figures are drawn in this process (no helper, or it is gone)."""
        return self._proc is None

    def _read(self) -> None:
        out = self._proc.stdout
        try:
            while True:
                self._replies.put(pickle.load(out))
        except Exception:  # end of the stream: the helper is gone
            self._replies.put(None)

    def submit(self, name: str, *args: Any, **kwargs: Any) -> int:
        """Send ``warptrunc.plot.<name>(*args, **kwargs)`` (no ``path``) to be drawn; returns
        the ticket of :meth:`result`. In-process, the drawing waits for :meth:`result`."""
        req = (name, args, kwargs)
        self._sent.append(req)
        if self._proc is not None:
            try:
                pickle.dump(req, self._proc.stdin, protocol=pickle.HIGHEST_PROTOCOL)
                self._proc.stdin.flush()
            except OSError:  # the helper is gone: result() draws it here
                pass
        return len(self._sent) - 1

    def result(self, ticket: int) -> bytes:
        """The PNG bytes of a submitted figure.

        Raises
        ------
        Exception
            The drawing's own error (from the helper: the same type and message, its traceback
            chained as :class:`FigureProcessError`).
        """
        while ticket not in self._done:
            i = len(self._done)  # the helper answers in order
            reply = None if self._proc is None else self._replies.get()
            if reply is None:  # no helper, or it is gone: draw here
                self._end(kill=True)
                self._done[i] = png_bytes(*self._sent[i])
            elif reply[0] == "ok":
                self._done[i] = reply[1]
            else:
                self._done[i] = b""
                raise reply[1] from FigureProcessError(f"in the figure process:\n{reply[2]}")
        return self._done[ticket]

    def _end(self, kill: bool = False) -> None:
        proc, self._proc = self._proc, None
        if proc is None:
            return
        if kill:
            proc.kill()
        try:
            proc.stdin.close()  # end of input: the helper exits
        except OSError:
            pass
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        if self._reader is not None:
            self._reader.join(timeout=5)
        proc.stdout.close()

    def close(self) -> None:
        """End the helper (after its last answer)."""
        self._end()

    def __enter__(self) -> FigureWorker:
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        self._end(kill=exc_type is not None)


def _warm_up() -> None:
    """Draw a small figure with the pieces of the job's (log axes, mathtext, legend,
    constrained layout) so that the first real one finds matplotlib's parser, fonts and glyph
    caches ready."""
    from io import BytesIO

    from ._style import new_figure

    fig, axes = new_figure(figsize=(2.0, 1.6))
    ax = axes[0, 0]
    ax.loglog([1e-8, 1e-5], [1e-3, 1e-1], "-", label="fit α = 0.7, β = 96 (E$_c$/E)")
    ax.loglog([1e-8, 1e-5], [1e-3, 1e-1], "--", lw=1.6)
    ax.set_xlabel("F/(E·A)")
    ax.set_ylabel("E$_c$/E, A$_c$/A (%)")
    ax.set_title("R$_t$ = 10 µm, E$_i$ = 1 GPa")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.savefig(BytesIO(), format="png", dpi=40)


def _waiting(stream: Any) -> bool:
    """Whether a request waits on ``stream`` already (True where that cannot be told)."""
    import select

    try:
        return bool(select.select([stream], [], [], 0)[0])
    except (OSError, ValueError):  # no select() on a pipe (Windows)
        return True


def serve() -> None:
    """The helper process: import matplotlib and the job's figure modules, warm up if no
    request waits yet, then draw each request of stdin (a pickled ``(name, args, kwargs)``) and answer on stdout with
    ``("ok", png)`` or ``("error", exception, traceback)``, in order, until stdin ends."""
    inp, out = sys.stdin.buffer, sys.stdout.buffer
    sys.stdout = sys.stderr  # a print never lands among the answers
    # Ctrl-C reaches the whole process group: the job reports it, and ends this helper
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    import matplotlib.backends.backend_agg
    import matplotlib.figure  # noqa: F401

    from . import maps, stiffness  # noqa: F401  (the job's two figures)

    if not _waiting(inp):  # idle (the job still starts Warp): warm up
        try:
            _warm_up()
        except Exception:  # a cold cache costs time, never the job
            pass
    while True:
        try:
            req = pickle.load(inp)
        except EOFError:
            break
        try:
            reply: tuple = ("ok", png_bytes(*req))
        except Exception as exc:
            tb = traceback.format_exc()
            try:
                reply = ("error", pickle.loads(pickle.dumps(exc)), tb)
            except Exception:
                reply = ("error", FigureProcessError(f"{type(exc).__name__}: {exc}"), tb)
        pickle.dump(reply, out, protocol=pickle.HIGHEST_PROTOCOL)
        out.flush()
    out.flush()
    os._exit(0)  # nothing to tear down: matplotlib's exit is not the job's time
