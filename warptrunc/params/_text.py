# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Documentation generated from parameter classes: the Markdown tables of the guide
(:func:`markdown_table`) and the numpydoc parameter lists (:func:`numpydoc_fields`). Part of
:mod:`warptrunc.params`."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

from ._cli import _default_text, _option
from ._fields import param_info

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
