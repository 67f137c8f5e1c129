# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The parser class and help formatter of the command line (standard library only).

Kept apart from :mod:`warptrunc.cli._common` so that ``warptrunc --help`` builds the top-level
parser without importing Warp or NumPy.
"""

from __future__ import annotations

import argparse
import re

__all__ = ["HelpFormatter", "Parser"]


class HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Appends "(default: X)" to an option's help, except when the help already states its
    default or the default is None (whose meaning the help text gives)."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = action.help or ""
        if action.default is None or "default" in text.lower():
            return text
        if isinstance(action, argparse._StoreTrueAction):  # "(default: False)" says nothing
            return text
        return super()._get_help_string(action)


class Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line: ``PROG: error: MESSAGE (see PROG --help)``,
    exit status 2 (argparse's default also prints the usage, a dozen lines here).

    Values such as ``-1e-6``, ``-inf`` and ``-nan`` are read as (negative) numbers, so that the
    validators can name the allowed range, rather than as unknown options.
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(
            r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE
        )

    def error(self, message: str):  # type: ignore[override]
        from .._support.messages import one_line

        self.exit(2, one_line(f"{self.prog}: error: {message} (see {self.prog} --help)") + "\n")
