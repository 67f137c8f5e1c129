# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Path validators for ``type=`` (``input_file``, ``output_file``, ``output_dir``), re-exported by
:mod:`warptrunc.cli._common` (their table is there): one-line ``argparse`` errors naming the
path and what is wrong with it."""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from .._support.messages import show
from .._support.outputs import probe_writable

__all__ = ["input_file", "output_dir", "output_file"]


def _nearest_existing(p: Path) -> Path:
    q = p.absolute()
    while not q.exists() and q != q.parent:
        q = q.parent
    return q


def _check_writable_parent(p: Path, text: str) -> None:
    anc = _nearest_existing(p.parent if p.name else p)
    if not anc.is_dir():
        raise argparse.ArgumentTypeError(f"{show(anc)} is not a folder, so {show(text)} cannot be written")
    if not os.access(anc, os.W_OK | os.X_OK):
        raise argparse.ArgumentTypeError(f"cannot write under {show(anc)} (no permission), got {show(text)}")
    why = probe_writable(anc)  # os.access is wrong for root and on /proc, /sys
    if why is not None:
        raise argparse.ArgumentTypeError(f"{why}, got {show(text)}")


def _path_check(what: str):
    """Turn an OSError met while looking at a path (no permission to enter a folder, a name too
    long, ...) into the one-line ``argparse`` error of the option."""

    def wrap(check):
        def parse(text: str) -> Path:
            try:
                return check(text)
            except OSError as exc:
                why = exc.strerror or type(exc).__name__
                raise argparse.ArgumentTypeError(
                    f"cannot use {show(text)} as {what} ({why}"
                    + (f": {show(exc.filename)}" if exc.filename not in (None, text) else "")
                    + ")"
                ) from None

        parse.__name__ = check.__name__
        parse.__doc__ = check.__doc__
        return parse

    return wrap


@_path_check("an input file")
def input_file(text: str) -> Path:
    """A ``type=`` for an existing regular file (not a folder)."""
    p = Path(text)
    if not text:
        raise argparse.ArgumentTypeError("must be a file name, got ''")
    if not p.exists():
        raise argparse.ArgumentTypeError(f"file not found: {show(text)}")
    if not p.is_file():
        raise argparse.ArgumentTypeError(f"must be a regular file, got a folder: {show(text)}")
    if not os.access(p, os.R_OK):
        raise argparse.ArgumentTypeError(f"file is not readable (no permission): {show(text)}")
    return p


@_path_check("an output file")
def output_file(text: str) -> Path:
    """A ``type=`` for a file to write: not an existing folder, in a writable folder."""
    p = Path(text)
    if not text:
        raise argparse.ArgumentTypeError("must be a file name, got ''")
    if p.is_dir():
        raise argparse.ArgumentTypeError(f"must be a file name, got an existing folder: {show(text)}")
    _check_writable_parent(p, text)
    return p


@_path_check("an output folder")
def output_dir(text: str) -> Path:
    """A ``type=`` for an output folder: an existing folder, or one that can be created."""
    p = Path(text)
    if not text:
        raise argparse.ArgumentTypeError("must be a folder name, got ''")
    if p.exists() and not p.is_dir():
        raise argparse.ArgumentTypeError(f"must be a folder, got an existing file: {show(text)}")
    if p.is_dir():
        if not os.access(p, os.W_OK | os.X_OK) or probe_writable(p) is not None:
            raise argparse.ArgumentTypeError(f"folder is not writable: {show(text)}")
        return p
    _check_writable_parent(p / "x", text)
    return p
