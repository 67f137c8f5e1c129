# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One spelling of the command-line options: every option is hyphenated, the generated ones
included, and none is hidden (no underscore spellings, no aliases); an unknown option is reported
by its sub-command. Parsers only: nothing here runs a command."""

from __future__ import annotations

import argparse
import subprocess
import sys

import pytest

from warptrunc.cli import build_parser, main
from warptrunc.contact.settings import SolverSettings
from warptrunc.params import add_options, from_args

COMMANDS = {
    "analyze",
    "bem-check",
    "calibrate",
    "challenge",
    "compare",
    "describe",
    "generate",
    "indent",
    "islands",
    "render",
    "reproduce",
    "sweep",
}
GENERATED = {
    "--pressure-tol",
    "--load-control",
    "--fft-plan",
    "--precondition-above",
    "--direct-max",
}


def _subparsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    (action,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(action.choices)


def _visible(parser: argparse.ArgumentParser) -> list[str]:
    """The option strings of ``parser`` that its --help shows."""
    return [o for a in parser._actions if a.help != argparse.SUPPRESS for o in a.option_strings]


def _hidden(parser: argparse.ArgumentParser) -> dict[str, argparse.Action]:
    return {o: a for a in parser._actions if a.help == argparse.SUPPRESS for o in a.option_strings}


@pytest.fixture(scope="module")
def parser():
    return build_parser()  # every sub-command, complete


def test_every_visible_option_of_every_command_is_hyphenated(parser):
    subs = _subparsers(parser)
    assert set(subs) == COMMANDS
    bad = {o for o in _visible(parser) if "_" in o}
    for name, sub in subs.items():
        bad |= {f"{name} {o}" for o in _visible(sub) if "_" in o}
        for o in _visible(sub):  # and the help text shows exactly these
            assert o in sub.format_help()
    assert bad == set()
    indent = _visible(subs["indent"])
    assert GENERATED <= set(indent)  # the walk saw the generated options


def test_add_options_spells_fields_with_hyphens_and_keeps_the_dest():
    p = argparse.ArgumentParser(prog="t")
    add_options(p, SolverSettings)
    assert "--pressure-tol" in _visible(p) and "--pressure_tol" not in _visible(p)
    assert "--pressure-tol" in p.format_help() and "--pressure_tol" not in p.format_help()
    ns = p.parse_args(["--pressure-tol", "2e-6", "--direct-max", "7"])
    assert ns.pressure_tol == 2e-6 and ns.direct_max == 7
    s = from_args(SolverSettings, ns)
    assert s.pressure_tol == 2e-6 and s.direct_max == 7


def test_pressure_tol_hyphenated_parses_on_indent(capsys):
    p = build_parser(["indent"])
    ns = p.parse_args(
        [
            "indent",
            "--n",
            "64",
            "--pressure-tol",
            "1e-5",
            "--fft-plan",
            "full",
            "--load-control",
            "secant",
            "--precondition-above",
            "0.5",
        ]
    )
    assert (ns.pressure_tol, ns.fft_plan, ns.load_control) == (1e-5, "full", "secant")
    assert ns.precondition_above == 0.5
    s = from_args(SolverSettings, ns)
    assert (s.pressure_tol, s.fft_plan, s.load_control) == (1e-5, "full", "secant")
    assert capsys.readouterr().err == ""


def test_no_option_is_hidden(parser):
    for name, sub in _subparsers(parser).items():
        assert _hidden(sub) == {}, name
    p = build_parser(["indent"])
    with pytest.raises(SystemExit) as e:
        p.parse_args(["indent", "--pressure_tol", "1e-5"])
    assert e.value.code == 2


def test_abbreviation_is_the_option(capsys):
    ns = build_parser(["indent"]).parse_args(["indent", "--pressure", "4e-5"])
    assert ns.pressure_tol == 4e-5 and capsys.readouterr().err == ""


@pytest.mark.parametrize("cmd", ["indent", "generate", "bem-check"])
def test_unknown_option_names_the_command_and_its_help(capsys, cmd):
    with pytest.raises(SystemExit) as e:
        main([cmd, "--frobnicate", "3"])
    assert e.value.code == 2
    out = capsys.readouterr()
    assert out.err == (
        f"warptrunc {cmd}: error: unrecognized arguments: --frobnicate 3 "
        f"(see warptrunc {cmd} --help)\n"
    )
    assert out.out == ""


def test_unknown_option_as_a_user_sees_it():
    r = subprocess.run(
        [sys.executable, "-m", "warptrunc", "indent", "--n", "64", "--frobnicate", "3"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 2
    assert r.stderr == (
        "warptrunc indent: error: unrecognized arguments: --frobnicate 3 "
        "(see warptrunc indent --help)\n"
    )
