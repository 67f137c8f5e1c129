# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Every option of every sub-command is either generated from a field of a parameter object
(:func:`warptrunc.params.add_options`: its default, unit, range and help declared once) or one
of the hand-written options of :mod:`warptrunc.cli._common` that say where the work runs and
where its results go, or which source is read (:func:`warptrunc.cli._common.shared_option`).
Parsers only: nothing here runs a command."""

from __future__ import annotations

import argparse
import ast
from pathlib import Path

import pytest

from warptrunc.cli import build_parser
from warptrunc.cli._common import SHARED
from warptrunc.params._cli import FIELD

CLI = Path(__file__).resolve().parents[1] / "warptrunc" / "cli"


def _subparsers() -> dict[str, argparse.ArgumentParser]:
    parser = build_parser()
    (action,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(action.choices)


SUBCOMMANDS = sorted(_subparsers())


@pytest.mark.parametrize("command", SUBCOMMANDS)
def test_every_option_is_a_field_or_a_shared_option(command):
    sub = _subparsers()[command]
    stray = []
    for a in sub._actions:
        if isinstance(a, argparse._HelpAction) or not a.option_strings:
            continue
        if "--verbose" in a.option_strings:  # the top-level flag, repeated on each command
            continue
        if not (getattr(a, FIELD, None) or getattr(a, SHARED, False)):
            stray.append("/".join(a.option_strings))
    assert stray == [], f"{command}: options neither from a field nor shared: {stray}"


def test_hand_written_options_live_in_one_module():
    """``add_argument`` and ``shared_option`` are called in ``_common.py`` (the shared options)
    and nowhere else in the command line: the sub-commands add fields (``add_options``) and the
    shared options through the functions of ``_common.py``. The one exception is the program's
    own ``--verbose``, which ``cli/__init__.py`` adds to the top-level parser (and repeats on each
    sub-command) before any command loads, without importing NumPy."""
    offenders = []
    for path in sorted(CLI.glob("*.py")):
        if path.name == "_common.py":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and node.func.attr == "add_argument"
            ):
                flags = [a.value for a in node.args if isinstance(a, ast.Constant)]
                if path.name == "__init__.py" and flags[:1] == ["--verbose"]:
                    continue
                offenders.append(f"{path.name}:{node.lineno}")
            if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "shared_option":
                offenders.append(f"{path.name}:{node.lineno}")
    assert offenders == []


@pytest.mark.parametrize("command", SUBCOMMANDS)
def test_field_options_show_the_declared_default_unit_and_range(command):
    """The help of a generated option is the field's: its description, unit, range, default."""
    from warptrunc import params

    sub = _subparsers()[command]
    for a in sub._actions:
        ref = getattr(a, FIELD, None)
        if not ref:
            continue
        cls_name, name = ref.split(".")
        assert "default" in (a.help or ""), (command, a.option_strings)
        assert a.default is None, (command, a.option_strings)  # the class's default applies
        del cls_name, name, params
        break
