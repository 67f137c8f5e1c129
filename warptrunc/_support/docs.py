# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Shared docstring text that is not a field's: parameter blocks that sibling functions share
(the device, the surface, a written file) are written once, and :func:`fill_doc` fills them in.

A parameter that is a field of a parameter object (``max_depth_fraction``, ``periodic``, ...)
is documented from the field's declaration (:func:`warptrunc.params.field_docs`), through the
same :func:`fill_doc`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any


def fill_doc(blocks: Mapping[str, str]) -> Callable[[Any], Any]:
    """A decorator that replaces each docstring line holding only a key of ``blocks`` (such as
    ``{surface}``) by its block, at that line's indentation, and returns the object."""

    def fill(obj: Any) -> Any:
        lines = []
        for line in obj.__doc__.split("\n"):
            block = blocks.get(line.strip())
            if block is None:
                lines.append(line)
                continue
            indent = line[: len(line) - len(line.lstrip())]
            lines += [indent + b if b else b for b in block.split("\n")]
        obj.__doc__ = "\n".join(lines)
        return obj

    return fill


SHARED_DOCS = {
    "{device}": (
        "device : str, optional\n    Warp device; default: where a device-resident surface lives,"
        " else\n    :func:`warptrunc.resolve_device`'s choice."
    ),
    "{warp_device}": "device : str, optional\n    Warp device.",
    "{warp_device_obj}": "device : str or warp Device, optional\n    Warp device.",
    "{surface}": "surface : Surface\n    The height map (m).",
    "{write_path}": "Parameters\n----------\npath : str or Path\n    File to write (overwritten).",
    "{returns_path}": "Returns\n-------\nPath",
}
"""Parameter text that functions of several packages share and that is no field of a parameter
object, written once: a docstring line holding only a key is replaced by its block
(:func:`fill_doc`). A parameter that is a field documents itself from its declaration
(:func:`warptrunc.params.field_docs`, e.g. ``TRUNCATION_DOCS`` of
:mod:`warptrunc.truncation.settings`)."""
