# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Error messages that stay short: one line, at most :data:`MAX_MESSAGE_CHARS` characters.

Every error the command line prints goes through :func:`one_line`; readers that wrap the
message of a third-party library (which may hold a whole file's bytes) go through it too, and
a value quoted in a message (a path, an option's text) through :func:`show`.
"""

from __future__ import annotations

__all__ = ["MAX_MESSAGE_CHARS", "MAX_VALUE_CHARS", "one_line", "show"]

MAX_MESSAGE_CHARS = 400
"""Longest error line (characters): a longer one keeps its start and its end, joined by " … "."""

MAX_VALUE_CHARS = 80
"""Longest value quoted in a message (characters)."""


def _clip(text: str, limit: int) -> str:
    if len(text) <= limit:
        return text
    tail = limit // 4
    head = limit - tail - 3
    return f"{text[:head]} … {text[-tail:]}"


def one_line(text: object, limit: int = MAX_MESSAGE_CHARS) -> str:
    """``text`` as one line of at most ``limit`` characters.

    Parameters
    ----------
    text : object
        The message (``str()`` of it; an exception gives its message).
    limit : int
        Largest length (characters).

    Returns
    -------
    str
        Runs of whitespace (newlines included) become one blank and control characters are
        dropped; a longer text keeps its first three quarters and its last quarter, joined by
        " … ".
    """
    s = "".join(c if c.isprintable() or c.isspace() else " " for c in str(text))
    return _clip(" ".join(s.split()), limit)


def show(value: object, limit: int = MAX_VALUE_CHARS) -> str:
    """``repr(value)`` shortened to ``limit`` characters, for quoting a value in a message.

    Parameters
    ----------
    value : object
        The value (a path, an option's text, ...).
    limit : int
        Largest length (characters).

    Returns
    -------
    str
        The repr, or its start and end joined by " … " when longer than ``limit``.
    """
    return _clip(repr(str(value) if hasattr(value, "__fspath__") else value), limit)
