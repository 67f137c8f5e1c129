# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stage-level result store of ``warptrunc reproduce``: one JSON file per stage, reused on rerun.

Each stage's file holds its parameters and its results. A rerun with the same parameters
loads the results instead of recomputing; a rerun with different parameters refuses (the
earlier results are never replaced silently) unless ``overwrite=True``. Files are written
atomically (temporary file + ``os.replace``), so an interrupted run leaves either the old
file or the new one.

Why a store apart from ``warptrunc.sweep.store``: a stage is one JSON document (parameters and
results of a fixed study step) reused or refused as a whole, where the sweep store holds Parquet
rows of many cases written by workers and resumed case by case. Both write through
:func:`warptrunc._support.outputs.write_atomic` and convert values with :func:`warptrunc._support.outputs.jsonable`.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from .._support.docs import fill_doc
from .._support.outputs import jsonable, write_atomic

__all__ = ["StageConflict", "StageStore"]

_NAME = "Parameters\n----------\nname : str\n    Stage name."
STAGE_DOCS = {
    "{name}": _NAME,
    "{name_params}": _NAME
    + "\nparams : dict\n    Parameters that identify the stage, compared after ``jsonable``.",
}
STAGE_DOCS["{profile}"] = "Parameters\n----------\np : Profile\n    The reproduction profile."
STAGE_DOCS["{elastic_profile}"] = STAGE_DOCS["{profile}"][:-1] + " (its ``elastic_*`` fields)."
STAGE_DOCS["{indentation_stage}"] = (
    "Parameters\n----------\nst : IndentationStage\n    The stage's parameters (a profile's "
    "``indentation``, :class:`~warptrunc.reproduce.indentation.design.IndentationStage`)."
)
STAGE_DOCS["{stage_params_returns}"] = (
    "Returns\n-------\ndict\n"
    "    JSON-able parameters (compared by :class:`~warptrunc.reproduce.store.StageStore`)."
)
STAGE_DOCS["{report_extras}"] = (
    "seconds : float or None\n    Compute time of the stage (s), if known.\n"
    "figure_names : list of str, optional\n    Figures to embed.\n\nReturns\n-------\nlist of str"
)
"""Docstring text of the stage store and of the reproduction stages, written once
(:func:`~warptrunc._support.docs.fill_doc`)."""


class StageConflict(ValueError):
    """A stage file exists with different parameters and ``overwrite`` is off."""


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

    @fill_doc(STAGE_DOCS)
    def path(self, name: str) -> Path:
        """The stage's file.

        {name}

        Returns
        -------
        Path
            ``<out>/stages/<name>.json`` (it may not exist yet).
        """
        return self.dir / f"{name}.json"

    @fill_doc(STAGE_DOCS)
    def load(self, name: str) -> dict[str, Any] | None:
        """The stored ``{"params", "result", "seconds"}`` of a stage, or None.

        {name}

        Returns
        -------
        dict or None
            The parsed stage file, or None when it does not exist.
        """
        p = self.path(name)
        if not p.exists():
            return None
        return json.loads(p.read_text())

    @fill_doc(STAGE_DOCS)
    def check(self, name: str, params: dict[str, Any]) -> bool:
        """True when the stage is stored with ``params``; raises on a conflict (no overwrite).

        {name_params}

        Returns
        -------
        bool
            True when the stored parameters equal ``params``; False when nothing is stored,
            or when they differ and ``overwrite`` is on.

        Raises
        ------
        StageConflict
            The stored parameters differ and ``overwrite`` is off; the message names the
            differing keys.
        """
        old = self.load(name)
        if old is None:
            return False
        params = jsonable(params)
        if old.get("params") == params:
            return True
        if self.overwrite:
            return False
        diff = sorted(
            k
            for k in set(params) | set(old.get("params", {}))
            if params.get(k) != old.get("params", {}).get(k)
        )
        why = (
            (
                "; it was written before β and E_c/E were normalised by the Young's modulus "
                "(E_c/E*, see the changelog)"
            )
            if diff == ["normalisation"]
            else ""
        )
        raise StageConflict(
            f"stage {name!r} in {self.out} was computed with other parameters (differing: "
            f"{', '.join(diff)}{why}); use another --out, or --overwrite to replace it"
        )

    @fill_doc(STAGE_DOCS)
    def matches(self, name: str, params: dict[str, Any]) -> bool:
        """True when the stage is stored with ``params`` (never raises).

        {name_params}

        Returns
        -------
        bool
            Whether a stored stage has exactly these parameters.
        """
        old = self.load(name)
        return old is not None and old.get("params") == jsonable(params)

    @fill_doc(STAGE_DOCS)
    def run(
        self, name: str, params: dict[str, Any], fn: Callable[[], dict[str, Any]]
    ) -> dict[str, Any]:
        """The stage's result: stored when the parameters match, else ``fn()`` (then stored).

        The stage name goes to ``reused`` or ``computed``. A computed result is
        written atomically with its parameters and its compute time.

        {name}
        params : dict
            Parameters that identify the stage (JSON-able after ``jsonable``).
        fn : callable
            Computes the result, called with no arguments; returns a dict, stored after
            ``jsonable`` (non-finite floats become null).


        Returns
        -------
        dict
            The result, as stored (after ``jsonable``).

        Raises
        ------
        StageConflict
            Stored with other parameters and ``overwrite`` is off.
        """

        if self.check(name, params):
            self.reused.append(name)
            return self.load(name)["result"]
        t0 = time.perf_counter()
        result = jsonable(fn())
        rec = {"params": jsonable(params), "result": result, "seconds": time.perf_counter() - t0}
        write_atomic(self.path(name), json.dumps(rec, indent=1, allow_nan=False) + "\n")
        self.computed.append(name)
        return result

    @fill_doc(STAGE_DOCS)
    def seconds(self, name: str) -> float | None:
        """Compute time of a stored stage (s).

        {name}

        Returns
        -------
        float or None
            The stored ``seconds`` (s), or None when the stage or the entry is missing.
        """

        rec = self.load(name)
        return None if rec is None else rec.get("seconds")
