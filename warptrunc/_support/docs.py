# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Shared docstring text: parameter blocks that sibling functions share are written once."""

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
