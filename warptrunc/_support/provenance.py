# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Provenance of results: the commit of the code that made them."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path


def git_commit(root: str | Path | None = None) -> str | None:
    """The commit of the checkout at ``root`` (default: this package's), or None.

    ``$WARPTRUNC_GIT_COMMIT``, when set, is returned as it is.
    """
    env = os.environ.get("WARPTRUNC_GIT_COMMIT")
    if env:  # a copy without .git (e.g. a tree shipped to a GPU machine) can say its commit
        return env.strip()
    root = Path(root) if root is not None else Path(__file__).resolve().parents[1]
    try:
        out = subprocess.run(
            ["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True
        )
        return out.stdout.strip() or None
    except OSError:
        return None
