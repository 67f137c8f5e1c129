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


SHARED_DOCS = {
    "{device}": (
        "device : str, optional\n    Warp device; default: where a device-resident surface lives,"
        " else\n    :func:`warptrunc.resolve_device`'s choice."
    ),
    "{warp_device}": "device : str, optional\n    Warp device.",
    "{warp_device_obj}": "device : str or warp Device, optional\n    Warp device.",
    "{surface}": "surface : Surface\n    The height map (m).",
    "{depth_range}": (
        "n_increments : int\n    Number of depth increments n (≥ 1).\n"
        "max_depth : float or None\n    Largest depth ω_max (m); None to use ``max_depth_fraction``.\n"
        "max_depth_fraction : float\n    ω_max as a fraction of R_t, in (0, 1] (dimensionless)."
    ),
    "{periodic}": "periodic : bool\n    Wrap the map around in x and y.",
    "{connectivity}": "connectivity : {4, 8}\n    Neighbourhood of an island.",
    "{path}": "Parameters\n----------\npath : str or Path\n    File to write (overwritten).",
    "{returns_path}": "Returns\n-------\nPath",
}
SHARED_DOCS["{label_options}"] = "\n".join(
    SHARED_DOCS[k] for k in ("{connectivity}", "{periodic}", "{device}")
)
"""Parameter text that functions of several packages share, written once: a docstring line
holding only a key is replaced by its block (:func:`fill_doc`)."""
