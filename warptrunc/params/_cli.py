# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Command-line options generated from parameter classes (:func:`add_options`) and the objects
made back from the parsed arguments (:func:`from_args`). Part of :mod:`warptrunc.params`."""

from __future__ import annotations

import argparse
import dataclasses
import math
from collections.abc import Sequence
from typing import Any

from ._fields import Param, param_info, sweep_fields

# --- command line -----------------------------------------------------------------------------


def _option(name: str, meta: Param, prefix: str) -> list[str]:
    """The option string of a field: hyphenated (``--pressure-tol`` for ``pressure_tol``)."""
    return [f"--{prefix}{meta.cli or name}".replace("_", "-")]


FIELD = "warptrunc_field"
"""Attribute set on every argparse action made by :func:`add_options`: ``"Class.field"``, the
parameter the option sets (``tests/test_cli_fields.py`` checks every option against it)."""


class _NoneGiven:
    """The value of an optional option given as ``none`` on the command line (argparse's own
    ``None`` means "not given"); :func:`from_args` turns it into ``None``."""

    def __repr__(self) -> str:
        return "none"


NONE_GIVEN = _NoneGiven()


def _arg_type(name: str, meta: Param):
    def parse(text: str):
        if meta.optional and text.lower() == "none":
            return NONE_GIVEN
        v: Any = text
        if meta.kind == "str":
            return text
        if meta.kind == "seeds":
            try:
                return meta.check(name, text)
            except ValueError as exc:
                raise argparse.ArgumentTypeError(str(exc).removeprefix(f"{name}: ")) from None
        if meta.kind == "choice":
            by_text = {str(c): c for c in meta.choices}
            if text not in by_text:
                raise argparse.ArgumentTypeError(
                    f"must be one of {', '.join(by_text)}, got {text!r}"
                )
            return by_text[text]
        if meta.kind != "choice":
            try:
                v = float(text)
            except ValueError:
                v = None
            if v is None or (meta.kind == "int" and not (math.isfinite(v) and v.is_integer())):
                what = "an " if meta.kind == "int" else "a number in "
                raise argparse.ArgumentTypeError(f"must be {what}{meta.interval()}, got {text!r}")
            if meta.kind == "int":
                v = int(v)
        try:
            return meta._one(name, v)
        except ValueError:
            what = "an " if meta.kind == "int" else "in "
            raise argparse.ArgumentTypeError(
                f"must be {what}{meta.interval()}, got {text!r}"
            ) from None

    parse.__name__ = meta.kind
    return parse


def _default_text(v: Any) -> str:
    if v is None:
        return "none"
    if isinstance(v, float):
        return f"{v:g}"
    if isinstance(v, tuple):
        return " ".join(_default_text(x) for x in v)
    return str(v)


def add_options(
    parser: argparse._ActionsContainer,
    spec_cls: Any,
    *,
    prefix: str = "",
    title: str | None = None,
    exclude: Sequence[str] = (),
    only: Sequence[str] | None = None,
    defaults: dict[str, Any] | None = None,
    many: bool | Sequence[str] = False,
    docs: dict[str, str] | None = None,
) -> argparse._ActionsContainer:
    """Add one option per declared field of ``spec_cls``, help text from the metadata.

    Parameters
    ----------
    parser : argparse.ArgumentParser or argument group
        Where the options go.
    spec_cls : type
        A parameter class (frozen dataclass whose fields come from :func:`param`).
    prefix : str
        Prefix of the option names (``"punch-"`` gives ``--punch-diameter``).
    title : str, optional
        Put the options in a new argument group with this title.
    exclude : sequence of str
        Fields left out.
    only : sequence of str, optional
        Only these fields (in the class's order).
    defaults : dict, optional
        Defaults that differ from the class's (for a command whose own default differs), as
        shown in the help; the command passes the same dict to :func:`from_args`.
    many : bool or sequence of str
        These fields (``True``: every sweepable one, see :func:`sweep_fields`) take one or
        more values (``--D 2.1 2.3``, ``nargs="+"``), each checked against the range: a list
        of values for a sweep. Pair fields keep their one-or-two values.
    docs : dict of str to str, optional
        Another description for some fields, where the command gives the parameter another
        role (e.g. the *target* D of a calibration); unit and range stay those declared.

    Returns
    -------
    argparse group or parser
        The container the options were added to.

    Notes
    -----
    Options are spelled with hyphens (``--pressure-tol`` for field ``pressure_tol``) and stored
    under ``{prefix}{field}`` with dashes as underscores; every option's
    default is ``None`` (= "not given"), so :func:`from_args` takes the class's default for
    options not given and a subclass's new field needs no other edit. The help shows the
    default, the unit and the allowed range.
    """
    g = parser.add_argument_group(title) if title else parser
    defaults = dict(defaults or {})
    docs = dict(docs or {})
    fields = {f.name: f for f in dataclasses.fields(spec_cls)}
    info = param_info(spec_cls)
    unknown = sorted(set(exclude) | set(only or ()) | set(docs) | set(defaults))
    unknown = [k for k in unknown if k not in info]
    if unknown:
        raise ValueError(f"{spec_cls.__name__} has no parameters {unknown}")
    if many is True:
        many = tuple(sweep_fields(spec_cls))
    many = set(many or ())
    for name, meta in info.items():
        if name in exclude or (only is not None and name not in only):
            continue
        default = defaults.get(name, fields[name].default)
        unit = f" ({meta.unit})" if meta.unit else " (dimensionless)" if meta.kind == "float" else ""
        rng = meta.interval() if meta.kind != "choice" else ""
        if meta.unit and rng.endswith(" " + meta.unit):
            rng = rng[: -len(meta.unit) - 1]  # the unit is named once, after the description
        help_ = f"{docs.get(name, meta.doc)}{unit}"
        if rng:
            help_ += f"; {rng}"
        help_ += f"; default {_default_text(default)}"
        if name in many and not meta.pair:
            help_ += "; several values: one sweep axis"
        kw: dict[str, Any] = {
            "dest": f"{prefix}{name}".replace("-", "_"),
            "default": None,
            "help": help_.replace("%", "%%"),
        }
        if meta.kind == "bool":
            kw["action"] = argparse.BooleanOptionalAction
        else:
            kw["type"] = _arg_type(name, meta)
            if meta.kind == "choice":
                kw["choices"] = list(meta.choices)
                kw["metavar"] = "{" + ",".join(str(c) for c in meta.choices) + "}"
            else:
                kw["metavar"] = meta.metavar or (name.upper() if meta.kind in ("int", "seeds") else name)
        if meta.length is not None:
            kw["nargs"] = meta.length
            if meta.metavar is None:
                kw["metavar"] = tuple(f"{name.upper()}{i}" for i in range(meta.length))
        elif meta.pair or meta.many or meta.kind == "seeds" or name in many:
            kw["nargs"] = "+"
        action = g.add_argument(*_option(name, meta, prefix), **kw)
        setattr(action, FIELD, f"{spec_cls.__name__}.{name}")
    return g


def from_args(
    spec_cls: Any,
    args: argparse.Namespace,
    *,
    prefix: str = "",
    defaults: dict[str, Any] | None = None,
    **overrides: Any,
) -> Any:
    """The parameter object of the parsed options (see :func:`add_options`).

    Parameters
    ----------
    spec_cls : type
        The parameter class.
    args : argparse.Namespace
        Parsed arguments.
    prefix : str
        The prefix given to :func:`add_options`.
    defaults : dict, optional
        The command's own defaults, for options not given (else the class's).
    **overrides
        Values that win over the options.

    Returns
    -------
    object
        An instance of ``spec_cls`` (validated).
    """
    kw: dict[str, Any] = dict(defaults or {})
    for name, meta in param_info(spec_cls).items():
        dest = f"{prefix}{name}".replace("-", "_")
        v = getattr(args, dest, None)
        if v is None:
            continue
        if isinstance(v, list) and any(x is NONE_GIVEN for x in v):
            if len(v) > 1:
                raise ValueError(
                    f"{_option(name, meta, prefix)[0]} takes 'none' alone, got {' '.join(map(str, v))}"
                )
            v = NONE_GIVEN
        if v is NONE_GIVEN:
            kw[name] = None
            continue
        if meta.kind == "seeds":
            v = tuple(x for part in v for x in (part if isinstance(part, tuple) else (part,)))
        elif meta.length is not None:
            v = tuple(v)
        elif meta.pair:
            if len(v) > 2:
                raise ValueError(
                    f"{_option(name, meta, prefix)[0]} takes one or two values, got {len(v)}: {v!r}"
                )
            v = v[0] if len(v) == 1 else (v[0], v[1])
        elif meta.many:
            v = tuple(v)
        elif isinstance(v, list):  # an option of add_options(..., many=...)
            if len(v) != 1:
                raise ValueError(
                    f"{_option(name, meta, prefix)[0]} takes one value here, got {len(v)}: {v!r}"
                )
            v = v[0]
        kw[name] = v
    kw.update(overrides)
    try:
        return spec_cls(**kw)
    except ValueError as exc:  # named by the option, as argparse names its own errors
        msg = str(exc)
        for name in sorted(param_info(spec_cls), key=len, reverse=True):
            if msg.startswith(name) and msg[len(name): len(name) + 1] in (" ", "[", ":", ""):
                meta = param_info(spec_cls)[name]
                msg = _option(name, meta, prefix)[0] + msg[len(name):]
                break
        raise ValueError(msg) from None
