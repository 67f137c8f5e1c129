# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stage-level result store of ``warptrunc reproduce``: one JSON file per stage, reused on rerun.

Each stage's file holds its parameters and its results. A rerun with the same parameters
loads the results instead of recomputing; a rerun with different parameters refuses (the
earlier results are never replaced silently) unless ``overwrite=True``. Files are written
atomically (temporary file + ``os.replace``), so an interrupted run leaves either the old
file or the new one.
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["StageConflict", "StageStore", "jsonable", "write_atomic"]


class StageConflict(ValueError):
    """A stage file exists with different parameters and ``overwrite`` is off."""


def jsonable(v: Any) -> Any:
    """Nested dicts/lists/NumPy values → JSON types; non-finite floats → None."""
    if isinstance(v, dict):
        return {str(k): jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [jsonable(x) for x in v]
    if isinstance(v, np.ndarray):
        return jsonable(v.tolist())
    if isinstance(v, np.generic):
        return jsonable(v.item())
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def write_atomic(path: Path, text: str | bytes) -> Path:
    """Write ``text`` to ``path`` through a temporary file in the same folder and a rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(text.encode() if isinstance(text, str) else text)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


class StageStore:
    """Stage files ``<out>/stages/<name>.json`` with parameter checks.

    Parameters
    ----------
    out : path
        Output folder of the study.
    overwrite : bool
        Recompute and replace a stage whose stored parameters differ.
    """

    def __init__(self, out: str | Path, *, overwrite: bool = False):
        self.out = Path(out)
        self.dir = self.out / "stages"
        self.overwrite = bool(overwrite)
        self.reused: list[str] = []
        self.computed: list[str] = []

    def path(self, name: str) -> Path:
        """The stage's file."""
        return self.dir / f"{name}.json"

    def load(self, name: str) -> dict[str, Any] | None:
        """The stored ``{"params", "result", "seconds"}`` of a stage, or None."""
        p = self.path(name)
        if not p.exists():
            return None
        return json.loads(p.read_text())

    def check(self, name: str, params: dict[str, Any]) -> bool:
        """True when the stage is stored with ``params``; raises on a conflict (no overwrite)."""
        old = self.load(name)
        if old is None:
            return False
        params = jsonable(params)
        if old.get("params") == params:
            return True
        if self.overwrite:
            return False
        diff = sorted(
            k for k in set(params) | set(old.get("params", {}))
            if params.get(k) != old.get("params", {}).get(k)
        )  # fmt: skip
        raise StageConflict(
            f"stage {name!r} in {self.out} was computed with other parameters (differing: "
            f"{', '.join(diff)}); use another --out, or --overwrite to replace it"
        )

    def run(
        self, name: str, params: dict[str, Any], fn: Callable[[], dict[str, Any]]
    ) -> dict[str, Any]:
        """The stage's result: stored when the parameters match, else ``fn()`` (then stored)."""
        import time

        if self.check(name, params):
            self.reused.append(name)
            return self.load(name)["result"]
        t0 = time.perf_counter()
        result = jsonable(fn())
        rec = {"params": jsonable(params), "result": result, "seconds": time.perf_counter() - t0}
        write_atomic(self.path(name), json.dumps(rec, indent=1, allow_nan=False) + "\n")
        self.computed.append(name)
        return result

    def seconds(self, name: str) -> float | None:
        """Compute time of a stored stage (s)."""
        rec = self.load(name)
        return None if rec is None else rec.get("seconds")
