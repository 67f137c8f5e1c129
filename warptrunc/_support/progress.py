# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One progress bar for every long loop (bands, depths, sweep cases, calibration steps)."""

from __future__ import annotations

from collections.abc import Iterable

__all__ = ["progress_bar"]


def progress_bar(
    iterable: Iterable | None = None,
    *,
    total: int | None = None,
    desc: str,
    unit: str,
    enabled: bool = True,
    initial: int = 0,
    leave: bool = True,
):
    """A ``tqdm.auto`` bar (hidden when ``enabled`` is false), usable as a context manager."""
    from tqdm.auto import tqdm  # here, not at the top: tqdm.auto costs ~65 ms of start-up

    return tqdm(
        iterable,
        total=total,
        desc=desc,
        unit=unit,
        disable=not enabled,
        initial=initial,
        leave=leave,
    )
