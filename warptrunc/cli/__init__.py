# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Command-line interface ``warptrunc`` (also ``python -m warptrunc``).

Each sub-command is a module of this package defining ``NAME``, ``HELP``,
``add_arguments(parser)`` and ``run(args) -> int``; modules are discovered in name order,
so adding a command needs no edit here. Every sub-command gets ``--verbose`` (show the
notices of Warp and VTK that are hidden by default on CPU-only machines), one-line errors with
exit status 2 (:class:`warptrunc.cli._common.Parser`) and the help formatter of
:mod:`warptrunc.cli._common`, whose ``type=`` validators new commands should use.
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys

from .._device import set_verbose
from ._common import HelpFormatter, Parser

_VERBOSE_HELP = (
    "show the notices of Warp and VTK that are hidden otherwise (e.g. no CUDA driver on a "
    "CPU-only machine, no X server for off-screen rendering)"
)


def build_parser() -> argparse.ArgumentParser:
    """The top-level parser with every discovered sub-command."""

    parser = Parser(
        prog="warptrunc",
        description="Contact stiffness of rough multiscale surfaces by truncation analysis.",
    )
    parser.add_argument("--verbose", "-v", action="store_true", help=_VERBOSE_HELP)
    sub = parser.add_subparsers(
        dest="command", required=True, metavar="COMMAND", parser_class=Parser
    )
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if info.name.startswith("_"):
            continue
        mod = importlib.import_module(f"{__name__}.{info.name}")
        p = sub.add_parser(
            mod.NAME,
            help=mod.HELP,
            description=mod.__doc__,
            formatter_class=HelpFormatter,
        )
        mod.add_arguments(p)
        p.add_argument(
            "--verbose", "-v", action="store_true", default=argparse.SUPPRESS, help=_VERBOSE_HELP
        )
        p.set_defaults(_run=mod.run)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    args = build_parser().parse_args(argv)

    if getattr(args, "verbose", False):
        set_verbose(True)  # otherwise $WARPTRUNC_VERBOSE decides
    try:
        return int(args._run(args) or 0)
    except (ValueError, MemoryError, OSError) as exc:
        msg = " ".join(str(exc).split())  # one line
        print(f"warptrunc {args.command}: error: {msg}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
