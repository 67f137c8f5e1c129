# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Parameters declared once: fields with default, unit, allowed range and description.

A parameter of warptrunc has one home: a field of a frozen parameter object
(:class:`~warptrunc.WMSpec`, :class:`~warptrunc.Material`,
:class:`~warptrunc.contact.SolverSettings`). The field is declared with :func:`param`, which
keeps its unit, its allowed range and a one-line description as field metadata. Everything
else is generated from that metadata:

- validation (:func:`check_fields`, called by each object's ``__post_init__``), with an error
  that names the field, its value and the allowed range;
- command-line options (:func:`add_options`: ``--D``, ``--Wr`` … with unit and range in the
  help) and the object made back from the parsed arguments (:func:`from_args`);
- sweep axes (:func:`sweep_fields`) and their validation (:func:`check_value`);
- the parameter tables of the documentation (:func:`markdown_table`);
- the JSON provenance of results (:func:`to_dict`).

So adding a field to a parameter object makes it appear in the CLI, the sweep grid and the docs
with no other edit.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
from collections.abc import Iterable, Sequence
from typing import Any

__all__ = [
    "Param",
    "Parameters",
    "add_options",
    "check_fields",
    "check_value",
    "from_args",
    "markdown_table",
    "numpydoc_fields",
    "param",
    "param_info",
    "param_like",
    "sweep_fields",
    "to_dict",
]

_KEY = "warptrunc"


@dataclasses.dataclass(frozen=True)
class Param:
    """Metadata of one parameter field (made by :func:`param`)."""

    doc: str
    """One-line description (the paper's symbol first where it has one)."""
    unit: str = ""
    """SI unit ("m", "Pa", "N") or "" for dimensionless and counts."""
    gt: float | None = None
    """Exclusive lower bound."""
    ge: float | None = None
    """Inclusive lower bound."""
    lt: float | None = None
    """Exclusive upper bound."""
    le: float | None = None
    """Inclusive upper bound."""
    kind: str = "float"
    """``"float"``, ``"int"`` or ``"choice"``."""
    choices: tuple = ()
    """Allowed values of a ``"choice"`` field."""
    optional: bool = False
    """``None`` is allowed (meaning: derived, see the description)."""
    pair: bool = False
    """A scalar or an (x, y) pair is allowed (CLI: one or two values)."""
    many: bool = False
    """A tuple of one or more values, each in the range (a scalar becomes a 1-tuple; CLI: one
    or more values)."""
    allow_inf: bool = False
    """+inf is allowed (e.g. the modulus of a rigid body, the hardness of an elastic one)."""
    cli: str | None = None
    """Option name without the dashes (default: the field name)."""
    aliases: tuple = ()
    """Further option names (without dashes) that users already call."""
    sweep: bool = True
    """The field can be a sweep axis."""

    def interval(self) -> str:
        """The allowed range as text, e.g. ``(2, 3)``, ``(0, inf] Pa``, ``{'free', 'periodic'}``.

        Returns
        -------
        str
            The interval (or set of choices) followed by the unit.
        """
        if self.kind == "choice":
            return "{" + ", ".join(repr(c) for c in self.choices) + "}"
        lo, lo_open = (self.gt, True) if self.gt is not None else (self.ge, False)
        hi, hi_open = (self.lt, True) if self.lt is not None else (self.le, False)
        if hi is None and self.allow_inf:
            hi, hi_open = math.inf, False
        num = (lambda v: f"{v:g}") if self.kind == "float" else (lambda v: f"{int(v)}")
        lo_s = "-inf" if lo is None else num(lo)
        hi_s = "inf" if hi is None or math.isinf(hi) else num(hi)
        left = "(" if lo is None or lo_open else "["
        right = ")" if hi is None or hi_open else "]"
        text = f"{left}{lo_s}, {hi_s}{right}"
        if self.kind == "int":
            text = "integer in " + text
        return f"{text} {self.unit}".rstrip()

    def check(self, name: str, value: Any) -> Any:
        """Convert and check one value.

        Parameters
        ----------
        name : str
            Field name, for the message.
        value : object
            The value (a pair for a ``pair`` field).

        Returns
        -------
        object
            The value as int, float or choice (a pair of equal values becomes a scalar).

        Raises
        ------
        ValueError
            Naming ``name``, the value and the allowed range.
        """
        if value is None:
            if self.optional:
                return None
            raise ValueError(f"{name} must be given ({self.interval()}), got None")
        if self.pair and not isinstance(value, (str, bytes)) and isinstance(value, Iterable):
            v = tuple(value)
            if len(v) != 2:
                raise ValueError(f"{name} must be a scalar or an (x, y) pair, got {value!r}")
            checked = (self._one(f"{name} (x)", v[0]), self._one(f"{name} (y)", v[1]))
            return checked[0] if checked[0] == checked[1] else checked
        if self.many:
            if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
                value = (value,)
            v = tuple(value)
            if self.optional and v == (None,):
                return None
            if not v:
                raise ValueError(f"{name} needs at least one value in {self.interval()}, got none")
            return tuple(self._one(f"{name}[{i}]", x) for i, x in enumerate(v))
        return self._one(name, value)

    def _one(self, name: str, value: Any) -> Any:
        if self.kind == "choice":
            if value not in self.choices:
                raise ValueError(f"{name} must be one of {self.interval()}, got {value!r}")
            return value
        if self.kind == "int":
            try:
                ok = not isinstance(value, bool) and float(value).is_integer()
            except (TypeError, ValueError, OverflowError):
                ok = False
            if not ok:
                raise ValueError(f"{name} must be an {self.interval()}, got {value!r}")
            v = int(value)
        else:
            try:
                v = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"{name} must be a number in {self.interval()}, got {value!r}") from None
        bad = math.isnan(v) or (math.isinf(v) and not (self.allow_inf and v > 0))
        bad |= self.gt is not None and not v > self.gt
        bad |= self.ge is not None and not v >= self.ge
        bad |= self.lt is not None and not v < self.lt
        bad |= self.le is not None and not v <= self.le
        if bad:
            what = "an " if self.kind == "int" else "in "
            raise ValueError(f"{name} must be {what}{self.interval()}, got {value!r}")
        return v


class Parameters:
    """Base of the parameter objects (:class:`~warptrunc.WMSpec`, :class:`~warptrunc.Material`,
    :class:`~warptrunc.SolverSettings`): ``replace`` and ``to_dict``, written once."""

    def replace(self, **kw: Any) -> Any:
        """A copy with some fields changed (validated by the copy's ``__post_init__``).

        Parameters
        ----------
        **kw
            Fields to change.

        Returns
        -------
        object
            A new instance of the same class.
        """
        return dataclasses.replace(self, **kw)

    def to_dict(self) -> dict[str, Any]:
        """The fields as a JSON-ready dict (SI; pairs as lists, ``inf`` kept as float).

        Returns
        -------
        dict
            One entry per field.
        """
        return to_dict(self)


def param(default: Any, doc: str, *, unit: str = "", **kw: Any) -> Any:
    """A dataclass field carrying its unit, range and description (see :class:`Param`).

    Parameters
    ----------
    default : object
        Default value (immutable).
    doc : str
        One-line description.
    unit : str
        SI unit, "" for dimensionless quantities and counts.
    **kw
        Further :class:`Param` attributes: ``gt``, ``ge``, ``lt``, ``le``, ``kind``,
        ``choices``, ``optional``, ``pair``, ``many``, ``allow_inf``, ``cli``, ``aliases``,
        ``sweep``.

    Returns
    -------
    dataclasses.Field
    """
    if "choices" in kw:
        kw.setdefault("kind", "choice")
        kw["choices"] = tuple(kw["choices"])
    meta = Param(doc=doc, unit=unit, **kw)
    return dataclasses.field(default=default, metadata={_KEY: meta})


def param_like(source: Any, name: str, *, default: Any = dataclasses.MISSING, **changes: Any) -> Any:
    """A field declared like field ``name`` of ``cls``: same default, unit, range, description.

    For an object that holds a parameter of another one under its own name (the sweep's
    options hold W_r, E, ...), so that the declaration stays in one place.

    Parameters
    ----------
    source : type
        The parameter class that declares the field.
    name : str
        Its field name.
    default : object, optional
        Another default (default: the same).
    **changes
        :class:`Param` attributes that differ (e.g. a narrower range ``ge=8``).

    Returns
    -------
    dataclasses.Field
    """
    f = {f.name: f for f in dataclasses.fields(source)}.get(name)
    if f is None or _KEY not in f.metadata:
        raise ValueError(f"{source.__name__} has no parameter {name!r}")
    meta = dataclasses.replace(f.metadata[_KEY], **changes)
    d = f.default if default is dataclasses.MISSING else default
    return dataclasses.field(default=d, metadata={_KEY: meta})


def param_info(cls_or_obj: Any) -> dict[str, Param]:
    """Field name → :class:`Param` of a parameter object, in field order.

    Parameters
    ----------
    cls_or_obj : type or object
        A parameter class or instance.

    Returns
    -------
    dict of str to Param
    """
    return {
        f.name: f.metadata[_KEY]
        for f in dataclasses.fields(cls_or_obj)
        if _KEY in f.metadata
    }


def check_value(cls_or_obj: Any, name: str, value: Any) -> Any:
    """Check one value of field ``name`` against its declared range (see :meth:`Param.check`).

    Parameters
    ----------
    cls_or_obj : type or object
        A parameter class or instance.
    name : str
        Field name.
    value : object
        Value to check.

    Returns
    -------
    object
        The converted value.
    """
    info = param_info(cls_or_obj)
    if name not in info:
        raise ValueError(
            f"{type(cls_or_obj).__name__ if not isinstance(cls_or_obj, type) else cls_or_obj.__name__}"
            f" has no parameter {name!r}; known: {', '.join(info)}"
        )
    return info[name].check(name, value)


def check_fields(obj: Any, *, keep_pairs: bool = False) -> None:
    """Validate (and normalise: ints, floats) every declared field of a frozen dataclass.

    Called from ``__post_init__``.

    Parameters
    ----------
    obj : object
        A parameter object.
    keep_pairs : bool
        Keep a pair of equal values as a pair (a tuple) rather than making it a scalar (for
        objects whose ``to_dict`` enters a hash, e.g. the sweep's case ids).

    Raises
    ------
    ValueError
        Naming the field, its value and the range.
    """
    for name, meta in param_info(obj).items():
        raw = getattr(obj, name)
        v = meta.check(name, raw)
        if keep_pairs and meta.pair and isinstance(raw, (tuple, list)) and not isinstance(v, tuple):
            v = (v, v)
        object.__setattr__(obj, name, v)


def to_dict(obj: Any) -> dict[str, Any]:
    """The fields as a JSON-ready dict (pairs as lists, ``inf`` kept as float).

    Parameters
    ----------
    obj : object
        A parameter object.

    Returns
    -------
    dict
    """
    out: dict[str, Any] = {}
    for f in dataclasses.fields(obj):
        v = getattr(obj, f.name)
        out[f.name] = list(v) if isinstance(v, tuple) else v
    return out


def sweep_fields(spec_cls: Any) -> dict[str, Param]:
    """The fields of ``spec_cls`` that can be sweep axes.

    Parameters
    ----------
    spec_cls : type
        A parameter class.

    Returns
    -------
    dict of str to Param
    """
    return {k: v for k, v in param_info(spec_cls).items() if v.sweep}


# --- command line -----------------------------------------------------------------------------


def _option(name: str, meta: Param, prefix: str) -> list[str]:
    names = [meta.cli or name, *meta.aliases]
    return [f"--{prefix}{n}" for n in names]


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
    Options are stored under ``{prefix}{field}`` with dashes as underscores; every option's
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
        unit = f" ({meta.unit})" if meta.unit else ""
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
        if meta.kind == "choice":
            kw["choices"] = list(meta.choices)
        else:
            kw["type"] = _arg_type(name, meta)
            kw["metavar"] = name.upper() if meta.kind == "int" else name
        if meta.pair or meta.many or name in many:
            kw["nargs"] = "+"
        g.add_argument(*_option(name, meta, prefix), **kw)
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
        if meta.pair:
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
    return spec_cls(**kw)


# --- documentation ----------------------------------------------------------------------------


def markdown_table(spec_cls: Any, *, prefix: str = "") -> str:
    """The parameters of ``spec_cls`` as a Markdown table: option, default, unit, range, description.

    Parameters
    ----------
    spec_cls : type
        A parameter class.
    prefix : str
        Prefix of the option names.

    Returns
    -------
    str
        The table (Markdown).
    """
    fields = {f.name: f for f in dataclasses.fields(spec_cls)}
    rows = ["| field | option | default | unit | allowed | description |",
            "|---|---|---|---|---|---|"]  # fmt: skip
    for name, meta in param_info(spec_cls).items():
        opt = " ".join(f"`{o}`" for o in _option(name, meta, prefix))
        default = fields[name].default
        rng = meta.interval()
        if meta.unit and rng.endswith(meta.unit):
            rng = rng[: -len(meta.unit)].rstrip()
        rows.append(
            f"| `{name}` | {opt} | `{_default_text(default)}` | {meta.unit or '–'} | "
            f"{rng} | {meta.doc} |"
        )
    return "\n".join(rows)


def numpydoc_fields(spec_cls: Any, *, indent: int = 4, exclude: Sequence[str] = ()) -> str:
    """The fields of ``spec_cls`` as numpydoc-style lines, to fill into a docstring.

    One line per field, ``name : type, default value`` followed by its description, unit and
    allowed range (indented by 4 more), so a function that takes the fields as ``**params``
    documents them from the declaration instead of repeating it (pyvista-style docstring
    templating: the function's docstring holds a placeholder that this text replaces).

    Parameters
    ----------
    spec_cls : type
        A parameter class.
    indent : int
        Spaces before each ``name :`` line.
    exclude : sequence of str
        Fields left out.

    Returns
    -------
    str
        The lines, joined by newlines (no trailing newline).
    """
    fields = {f.name: f for f in dataclasses.fields(spec_cls)}
    pad, out = " " * indent, []
    for name, meta in param_info(spec_cls).items():
        if name in exclude:
            continue
        typ = fields[name].type
        typ = typ if isinstance(typ, str) else getattr(typ, "__name__", str(typ))
        default = _default_text(fields[name].default)
        out.append(f"{pad}``{name}`` : {typ}, default {default}")
        text = f"{meta.doc[:1].upper()}{meta.doc[1:]}; {meta.interval()}."
        out.append(f"{pad}    {text}")
    return "\n".join(out)