# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Command-line interface ``warptrunc`` (also ``python -m warptrunc``).

Each sub-command is a module of this package defining ``NAME``, ``HELP``,
``add_arguments(parser)`` and ``run(args) -> int``; modules are discovered in name order,
so adding a command needs no edit here. Every sub-command gets ``--verbose`` (show the
notices of Warp and VTK that are hidden by default on CPU-only machines), one-line errors with
exit status 2 (:class:`warptrunc.cli._parser.Parser`) and the help formatter of
:mod:`warptrunc.cli._parser`; the ``type=`` validators of :mod:`warptrunc.cli._common` are the
ones new commands should use.

Ctrl-C: every sub-command stops with one line on stderr that says what was kept and how to go
on, and exit status 130 (:func:`main`; ``--verbose`` shows the traceback). ``sweep`` says it
itself, with the count of the cases in its store.

Start-up: only the sub-command that runs is imported. ``NAME``, ``HELP`` and the module
docstring of the others are read from their source (:mod:`ast`), so ``warptrunc --help``
imports neither Warp nor NumPy.
"""

from __future__ import annotations

import argparse
import ast
import errno
import importlib
import os
import pkgutil
import signal
import sys
import threading
from dataclasses import dataclass
from pathlib import Path

from ._parser import HelpFormatter, Parser

__all__ = ["build_parser", "main"]

_VERBOSE_HELP = (
    "show the notices of Warp and VTK that are hidden otherwise (e.g. no CUDA driver on a "
    "CPU-only machine, no X server for off-screen rendering)"
)


@dataclass(frozen=True)
class _Command:
    """A sub-command module as read from its source: module name, ``NAME``, ``HELP``, doc."""

    module: str
    name: str
    help: str
    doc: str | None


def _commands() -> list[_Command]:
    """The sub-command modules of this package, in module-name order, without importing them."""
    out = []
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if info.name.startswith("_"):
            continue
        tree = ast.parse((Path(__path__[0]) / f"{info.name}.py").read_text(encoding="utf-8"))
        consts = {
            t.id: node.value.value
            for node in tree.body
            if isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant)
            for t in node.targets
            if isinstance(t, ast.Name)
        }
        out.append(_Command(info.name, consts["NAME"], consts["HELP"], ast.get_docstring(tree)))
    return out


def _command_in(argv: list[str]) -> str | None:
    """The sub-command named on the command line (the first argument that is no option)."""
    for a in argv:
        if not a.startswith("-"):
            return a
    return None


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The top-level parser: every sub-command, with the full options of the one in ``argv``.

    Parameters
    ----------
    argv : list of str, optional
        The command line (without the program name). The sub-command it names is imported and
        gets its options; the others are listed with their help only. ``None``: every
        sub-command is imported and complete (for documentation and tests).

    Returns
    -------
    argparse.ArgumentParser
        The parser; a parsed namespace carries the sub-command's ``run`` as ``_run``.
    """
    parser = Parser(
        prog="warptrunc",
        description="Contact stiffness of rough multiscale surfaces by truncation analysis.",
    )
    parser.add_argument("--verbose", "-v", action="store_true", help=_VERBOSE_HELP)
    sub = parser.add_subparsers(
        dest="command", required=True, metavar="COMMAND", parser_class=Parser
    )
    wanted = _command_in(argv) if argv is not None else None
    for cmd in _commands():
        p = sub.add_parser(cmd.name, help=cmd.help, description=cmd.doc,
                           formatter_class=HelpFormatter)  # fmt: skip
        if argv is not None and cmd.name != wanted:
            continue  # listed in the top-level help; its options load only when it runs
        mod = importlib.import_module(f"{__name__}.{cmd.module}")
        mod.add_arguments(p)
        p.add_argument(
            "--verbose", "-v", action="store_true", default=argparse.SUPPRESS, help=_VERBOSE_HELP
        )
        p.set_defaults(_run=mod.run)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``warptrunc``.

    Parameters
    ----------
    argv : list of str, optional
        The command line without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status: 0 on success, 2 for bad input (one line on stderr), 130 after Ctrl-C
        (SIGINT; one line saying what was kept), or the sub-command's own documented status.
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    hook = sys.unraisablehook
    sys.unraisablehook = _interrupt_in_destructor(hook)
    before = len(_kept_stores())
    try:
        return _main(argv)
    except KeyboardInterrupt:
        if "--verbose" in argv or "-v" in argv:
            raise
        kept = _kept_stores()[before:]
        print(_interrupted_text(_command_in(argv) or "", kept), file=sys.stderr)
        return EXIT_INTERRUPTED
    finally:
        sys.unraisablehook = hook


EXIT_INTERRUPTED = 130
"""Exit status after Ctrl-C (SIGINT), as a shell reports a job that SIGINT ended (128 + 2)."""


def _kept_stores() -> list:
    """:func:`warptrunc._support.outputs.kept_stores` once a command has imported it (every
    command that writes does), else none."""
    atomic = sys.modules.get("warptrunc._support.outputs")
    return atomic.kept_stores() if atomic is not None else []


def _interrupted_text(command: str, kept: list) -> str:
    """The one line after Ctrl-C: what was kept (``kept``: the resumable stores of finished
    cases that the command kept; else nothing, as every other output is written whole or not
    at all) and how to go on."""
    from .._support.messages import show

    head = f"warptrunc {command}: interrupted"
    if kept:
        return (f"{head}; the finished cases stay in {show(kept[-1])}: run the same command "
                "again to finish the rest")  # fmt: skip
    return (f"{head}; nothing was written (each output is written whole or not at all): run "
            "the same command again to start over")  # fmt: skip


def _interrupt_in_destructor(hook):
    """An ``unraisablehook`` that does not drop Ctrl-C: a ``KeyboardInterrupt`` raised while a
    destructor ran (Warp frees its arrays in ``__del__``; CPython prints it as "Exception
    ignored in …" and goes on) is delivered again as SIGINT, so that it is raised where the
    program goes on. Its subclasses (``sweep``'s SIGTERM) are left to the latch that raised
    them (:mod:`warptrunc._support.interrupt`); every other unraisable exception goes to
    ``hook``."""

    def unraisable(info) -> None:
        handled = signal.getsignal(signal.SIGINT) not in (signal.SIG_IGN, signal.SIG_DFL, None)
        if not isinstance(info.exc_value, KeyboardInterrupt):
            hook(info)
        elif type(info.exc_value) is KeyboardInterrupt and handled:
            # sent from another thread, a moment later: a signal sent here would be handled
            # at once, inside this hook, and dropped again
            again = threading.Timer(0.01, os.kill, (os.getpid(), signal.SIGINT))
            again.daemon = True
            again.start()

    return unraisable


def _main(argv: list[str]) -> int:
    """:func:`main` without its Ctrl-C handling."""
    parser = build_parser(argv)
    try:
        args = parser.parse_args(argv)
    except OSError as exc:  # a ``type=`` validator met the file system (all are caught there)
        print(f"warptrunc {_command_in(argv)}: error: {_error_text(exc)}", file=sys.stderr)
        return 2

    verbose_before = os.environ.get("WARPTRUNC_VERBOSE")
    if getattr(args, "verbose", False):
        # read by warptrunc._support.device.is_verbose, here and in the command's child processes
        os.environ["WARPTRUNC_VERBOSE"] = "1"
    from .._support.progress import silence_progress
    from .._support.provenance import set_command

    set_command(["warptrunc", *argv])  # the command line in every output's provenance
    silence_progress(getattr(args, "no_progress", False))  # every report of the command
    try:
        return int(args._run(args) or 0)
    except (ValueError, MemoryError, OSError, OverflowError, RecursionError) as exc:
        text = _error_text(exc, getattr(args, "out", None))
        print(f"warptrunc {args.command}: error: {text}", file=sys.stderr)
        return 2
    except Exception as exc:  # a bug: still one line, the traceback with --verbose
        oom = _xla_out_of_memory(exc)
        if oom is not None:  # XLA's out-of-memory status: bad input (too large), not a bug
            print(f"warptrunc {args.command}: error: {_error_text(oom)}", file=sys.stderr)
            return _end_spread(2, exc)
        if getattr(args, "verbose", False):
            raise
        print(
            f"warptrunc {args.command}: internal error: {_error_text(exc)} (a bug: please "
            "report it with the command line; --verbose shows the traceback)",
            file=sys.stderr,
        )
        return _end_spread(EXIT_INTERNAL_ERROR, exc)
    finally:
        set_command(None)
        silence_progress(False)
        if verbose_before is None:  # the caller's process as it was (main() called in-process)
            os.environ.pop("WARPTRUNC_VERBOSE", None)
        else:
            os.environ["WARPTRUNC_VERBOSE"] = verbose_before


def _xla_out_of_memory(exc: BaseException) -> MemoryError | None:
    """XLA's out-of-memory error as a MemoryError, when a solve was spread (else None)."""
    if "warptrunc.contact.sharded.devices" not in sys.modules:
        return None
    from ..contact.sharded.devices import out_of_memory

    return out_of_memory(exc)


def _end_spread(status: int, exc: BaseException) -> int:
    """``status``; but after an error of the XLA runtime in a process that spread a solve over
    several devices, end the process here (``os._exit``, streams flushed): the other devices
    may wait in a collective forever, and the JAX runtime for them at exit (a 65536² run on
    4 × H200 hung after its out-of-memory error until its time limit)."""
    mod = sys.modules.get("warptrunc.contact.sharded.devices")
    if mod is not None and type(exc).__name__ in mod.XLA_ERRORS and mod.spread_in_use():
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(status)
    return status


EXIT_INTERNAL_ERROR = 1
"""Exit status of an unexpected exception (a bug); bad input exits with 2."""


def _error_text(exc: BaseException, out: object = None) -> str:
    """The exception's message as one short line; its type when the message is empty.

    An error of the file system names its file (``File too large: 'out/fit.json'``); one
    that carries no file name names the command's output ``out`` when there is one
    (``File too large, writing under 'sweep'``), or Warp's kernel cache when the error came
    from compiling a kernel there (``$WARP_CACHE_PATH``). A file-size limit (EFBIG) says where
    such a limit comes from.
    """
    from .._support.messages import one_line, show

    msg = one_line(exc)
    if isinstance(exc, MemoryError):
        return f"out of memory{': ' + msg if msg else ''}"
    if isinstance(exc, OSError) and exc.strerror:
        why = exc.strerror
        if exc.errno == errno.EFBIG:
            why += " (over a file-size limit: the shell's ulimit -f, or the file system's)"
        if exc.filename is not None:
            return one_line(f"{why}: {show(exc.filename)}")
        cache = _warp_cache_dir(exc)
        if cache is not None:
            return one_line(f"{why}, writing Warp's kernel cache under {show(cache)}")
        if out is not None:
            return one_line(f"{why}, writing under {show(out)}")
        return one_line(why)
    return msg or type(exc).__name__


def _warp_cache_dir(exc: BaseException) -> str | None:
    """Warp's kernel cache folder when ``exc`` was raised inside Warp's module loading (a
    kernel compiled and written there), else None."""
    tb = exc.__traceback__
    last = None
    while tb is not None:
        last = tb.tb_frame.f_code.co_filename
        tb = tb.tb_next
    if last is None or f"{os.sep}warp{os.sep}" not in last:
        return None
    try:
        import warp as wp

        return str(wp.config.kernel_cache_dir or "") or None
    except Exception:
        return None


if __name__ == "__main__":
    sys.exit(main())
