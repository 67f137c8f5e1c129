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
    exit status 2 (argparse's default also prints the usage, a dozen lines here). Unknown
    options are reported by the sub-command's parser (``warptrunc indent: error: unrecognized
    arguments: --x (see warptrunc indent --help)``), not by the top-level one.

    An abbreviated option (``--pressure``) matching an option and its hidden old spelling
    (``--pressure-tol``, ``--pressure_tol``, same destination) is the option, not ambiguous.

    Values such as ``-1e-6``, ``-inf`` and ``-nan`` are read as (negative) numbers, so that the
    validators can name the allowed range, rather than as unknown options.
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(
            r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE
        )

    def parse_args(self, args=None, namespace=None):  # type: ignore[override]
        ns, extras = self.parse_known_args(args, namespace)
        if extras:
            self._innermost(ns).error(f"unrecognized arguments: {' '.join(extras)}")
        return ns

    def _innermost(self, ns: argparse.Namespace) -> argparse.ArgumentParser:
        """The parser of the (sub-)sub-command that ``ns`` ran, else this one."""
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction):
                sub = action.choices.get(getattr(ns, action.dest, None) or "")
                if sub is not None:
                    return sub._innermost(ns) if isinstance(sub, Parser) else sub
        return self

    def _get_option_tuples(self, option_string):
        found = super()._get_option_tuples(option_string)
        shown = {t[0].dest for t in found if t[0].help != argparse.SUPPRESS}
        return [t for t in found if t[0].help != argparse.SUPPRESS or t[0].dest not in shown]

    def error(self, message: str):  # type: ignore[override]
        from .._support.messages import one_line

        self.exit(2, one_line(f"{self.prog}: error: {message} (see {self.prog} --help)") + "\n")
