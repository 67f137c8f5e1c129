# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Documentation generated from parameter classes: the Markdown tables of the guide
(:func:`markdown_table`), the numpydoc lines of a class's fields (:func:`numpydoc_fields`) and
the numpydoc parameter blocks of functions that take a field as a parameter of their own
(:func:`field_doc`, :func:`field_docs`, filled in by :func:`warptrunc._support.docs.fill_doc`).
A field's description is written once, in its declaration. Part of :mod:`warptrunc.params`."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any, get_args

from ._cli import _default_text, _option
from ._fields import Param, param_info

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
    rows = [
        "| field | option | default | unit | allowed | description |",
        "|---|---|---|---|---|---|",
    ]
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


def _describe(meta: Param, *, choices: bool = True) -> str:
    """A field's description as a sentence: its text, then its allowed range and unit (not for
    a flag, whose range says nothing, nor for choices the type shows already)."""
    text = f"{meta.doc[:1].upper()}{meta.doc[1:]}"
    if meta.kind == "bool" or (meta.kind == "choice" and not choices):
        return f"{text}."
    unit = " (dimensionless)" if meta.kind == "float" and not meta.unit else ""
    return f"{text}; {meta.interval()}{unit}."


def _type_text(spec_cls: Any, name: str, meta: Param) -> str:
    """The numpydoc type of a field: its choices, else its annotation without ``None``, and
    ``optional`` when None is allowed."""
    if meta.kind == "choice":
        return "{" + ", ".join(repr(c) for c in meta.choices) + "}"
    typ = {f.name: f for f in dataclasses.fields(spec_cls)}[name].type
    if not isinstance(typ, str):
        typ = " | ".join(getattr(a, "__name__", str(a)) for a in get_args(typ) or (typ,))
    parts = [s.strip() for s in typ.split("|") if s.strip() != "None"]
    return " or ".join(parts) + (", optional" if meta.optional else "")


def field_doc(spec_cls: Any, field: str, *, name: str | None = None) -> str:
    """The numpydoc parameter block of a function parameter that is a field of ``spec_cls``.

    Parameters
    ----------
    spec_cls : type
        The parameter class that declares the field.
    field : str
        The field.
    name : str, optional
        The parameter's name in the function, when it differs from the field's
        (``n_increments`` for ``TruncationSettings.increments``).

    Returns
    -------
    str
        ``name : type`` and, indented by 4, the declaration's description, allowed range and
        unit.

    Examples
    --------
    >>> from warptrunc.truncation.settings import TruncationSettings
    >>> print(field_doc(TruncationSettings, "max_depth_fraction"))
    max_depth_fraction : float
        Largest depth ω_max as a fraction of R_t; (0, 1] (dimensionless).
    """
    meta = param_info(spec_cls)[field]
    typ = _type_text(spec_cls, field, meta)
    return f"{name or field} : {typ}\n    {_describe(meta, choices=False)}"


def field_docs(spec_cls: Any, *fields: str, **renamed: str) -> dict[str, str]:
    """Docstring blocks of fields of ``spec_cls`` for :func:`~warptrunc._support.docs.fill_doc`.

    Parameters
    ----------
    spec_cls : type
        The parameter class that declares the fields.
    *fields : str
        Fields documented under their own name.
    **renamed : str
        Parameter name → field, for parameters named otherwise than their field.

    Returns
    -------
    dict of str to str
        ``"{name}"`` → :func:`field_doc` of each field.
    """
    pairs = [(f, f) for f in fields] + list(renamed.items())
    return {"{" + n + "}": field_doc(spec_cls, f, name=n) for n, f in pairs}


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
        out.append(f"{pad}    {_describe(meta)}")
    return "\n".join(out)
