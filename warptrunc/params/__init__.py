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
- the parameter tables of the documentation (:func:`markdown_table`), and the parameter text of
  every docstring that documents a field (:func:`numpydoc_fields`, :func:`field_doc`,
  :func:`field_docs`);
- the JSON provenance of results (:func:`to_dict`).

So adding a field to a parameter object makes it appear in the CLI, the sweep grid and the docs
with no other edit.
"""
from ._cli import add_options, from_args
from ._fields import (
    Param,
    Parameters,
    check_fields,
    check_value,
    param,
    param_info,
    param_like,
    sweep_fields,
    to_dict,
)
from ._text import field_doc, field_docs, markdown_table, numpydoc_fields

__all__ = [
    "Param",
    "Parameters",
    "add_options",
    "check_fields",
    "check_value",
    "field_doc",
    "field_docs",
    "from_args",
    "markdown_table",
    "numpydoc_fields",
    "param",
    "param_info",
    "param_like",
    "sweep_fields",
    "to_dict",
]
