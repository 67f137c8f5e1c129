# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The parameter fields: :class:`Param` metadata, its declaration (:func:`param`), validation
and the views of a parameter class (info, sweep axes, JSON). Part of :mod:`warptrunc.params`."""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Iterable
from typing import Any

_KEY = "warptrunc"

SEED_MAX = 2**32 - 1
"""Largest seed (NumPy's ``SeedSequence`` entropy of one 32-bit word)."""

MAX_SEEDS = 1_000_000
"""Most seeds one field may hold."""


def _seeds(name: str, spec: Any) -> tuple[int, ...]:
    """Seeds from ``"0-4"``, ``"0,2,7"``, ``"0-2,9"``, an int or a list of those (ranges
    inclusive, order kept, no repeats)."""
    import re

    if isinstance(spec, bool):
        raise ValueError(f"{name} must be seeds like 0, '0-4' or '0,3,7', got {spec!r}")
    if isinstance(spec, str):
        items: list = [s for s in spec.replace(" ", "").split(",") if s]
    elif isinstance(spec, Iterable):
        items = []
        for it in spec:
            items += [s for s in it.replace(" ", "").split(",") if s] if isinstance(it, str) else [it]
    else:
        items = [spec]
    out: list[int] = []
    for it in items:
        m = re.fullmatch(r"(\d+)-(\d+)", it) if isinstance(it, str) else None
        if m:
            lo, hi = int(m[1]), int(m[2])
            if hi < lo:
                raise ValueError(f"{name}: a seed range needs lo ≤ hi, got {it!r}")
            if len(out) + hi - lo + 1 > MAX_SEEDS:
                raise ValueError(f"{name}: more than {MAX_SEEDS} seeds")
            out.extend(range(lo, hi + 1))
            continue
        try:
            ok = not isinstance(it, bool) and float(it).is_integer()
        except (TypeError, ValueError, OverflowError):
            ok = False
        if not ok:
            raise ValueError(f"{name} must be seeds like 0, '0-4' or '0,3,7', got {it!r}")
        out.append(int(float(it)))
    if not out:
        raise ValueError(f"{name} needs at least one seed, got none")
    bad = [k for k in out if not 0 <= k <= SEED_MAX]
    if bad:
        raise ValueError(f"{name}: seeds must be in [0, {SEED_MAX}], got {bad[0]}")
    if len(set(out)) != len(out):
        dup = next(k for i, k in enumerate(out) if k in out[:i])
        raise ValueError(f"{name}: seed {dup} is given twice")
    return tuple(out)


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
    """``"float"``, ``"int"``, ``"choice"``, ``"bool"``, ``"str"`` or ``"seeds"`` (a tuple of
    seeds in [0, 2³² − 1], written ``0-4``, ``0,3,7`` or ``0-2,9`` on the command line)."""
    choices: tuple = ()
    """Allowed values of a ``"choice"`` field."""
    optional: bool = False
    """``None`` is allowed (meaning: derived, see the description)."""
    pair: bool = False
    """A scalar or an (x, y) pair is allowed (CLI: one or two values)."""
    many: bool = False
    """A tuple of one or more values, each in the range (a scalar becomes a 1-tuple; CLI: one
    or more values)."""
    length: int | None = None
    """A tuple of exactly this many values, each in the range (e.g. 2 for a window LO, HI; CLI:
    that many values)."""
    increasing: bool = False
    """The values of a ``many`` or ``length`` field must increase strictly (a window LO < HI)."""
    allow_inf: bool = False
    """+inf is allowed (e.g. the modulus of a rigid body, the hardness of an elastic one)."""
    cli: str | None = None
    """Option name without the dashes (default: the field name)."""
    metavar: str | tuple | None = None
    """Name(s) of the value(s) in the command-line help (default: from the field)."""
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
        if self.kind == "bool":
            return "{True, False}"
        if self.kind == "str":
            return "text"
        if self.kind == "seeds":
            return "seeds in [0, 4294967295]"
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
        if self.kind == "seeds":
            return _seeds(name, value)
        if self.length is not None:
            if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
                raise ValueError(
                    f"{name} needs {self.length} values in {self.interval()}, got {value!r}"
                )
            v = tuple(value)
            if len(v) != self.length:
                raise ValueError(
                    f"{name} needs {self.length} values in {self.interval()}, got {len(v)}: {value!r}"
                )
            return self._ordered(name, tuple(self._one(f"{name}[{i}]", x) for i, x in enumerate(v)))
        if self.many:
            if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
                value = (value,)
            v = tuple(value)
            if self.optional and v == (None,):
                return None
            if not v:
                raise ValueError(f"{name} needs at least one value in {self.interval()}, got none")
            return self._ordered(name, tuple(self._one(f"{name}[{i}]", x) for i, x in enumerate(v)))
        return self._one(name, value)

    def _ordered(self, name: str, v: tuple) -> tuple:
        if self.increasing and any(not a < b for a, b in itertools.pairwise(v)):
            unit = f" ({self.unit})" if self.unit else ""
            if len(v) == 2:
                raise ValueError(f"{name} needs LO < HI{unit}, got {v[0]!r} {v[1]!r}")
            raise ValueError(f"{name} must increase strictly{unit}, got {v!r}")
        return v

    def _one(self, name: str, value: Any) -> Any:
        if self.kind == "choice":
            if value not in self.choices or isinstance(value, bool):
                raise ValueError(f"{name} must be one of {self.interval()}, got {value!r}")
            return value
        if self.kind == "bool":
            if not (isinstance(value, bool) or type(value).__name__ == "bool_"):  # numpy's too
                raise ValueError(f"{name} must be True or False, got {value!r}")
            return bool(value)
        if self.kind == "str":
            if not isinstance(value, str):
                raise ValueError(f"{name} must be text, got {value!r}")
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
        ``choices``, ``optional``, ``pair``, ``many``, ``length``, ``increasing``,
        ``allow_inf``, ``cli``, ``metavar``, ``sweep``.

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
