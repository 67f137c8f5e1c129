# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The ``indentation`` stage's work plan: pieces, their parts, what each part waits for, and the
two ways to run them — in this process, in the canonical order, or on a Dask cluster, one part
per task.

The plan (:class:`Plan`) knows every piece of the stage as soon as it can: the hardness sweep
(H = ∞ first), the elastic statistics and the face pieces from the start, the ``depth-match``
statistics of every surface once every sweep is complete (one H for the alloy:
:func:`stats_hardness`). A part is ready
when its piece is planned and, for a finite-H sweep part that reuses elastic cycles, when the
elastic part of its punch is done. Finished parts are written by whoever ran them
(:func:`~.pieces.compute_part`); the plan merges a piece when its last part arrives,
writes the piece file and removes its part files. In-process the parts run one at a time in the
canonical order (surface by surface, the sweep, the statistics, the faces); on a cluster the
driver keeps one part in flight per worker, the most expensive ready part first (the elastic
sweep parts, which unlock others, before all), so that ``time_budget`` stops new parts within
one part's time and a worker lost mid-part loses that part only (it is submitted again; a part
file already written is read). The stored result is the same whichever way it ran: parts are
independent solves, merged in a fixed order.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from typing import Any

from ..._support.outputs import write_atomic
from .design import IndentationStage, design_of, face_variants, refine_of, sweep_order
from .pieces import (
    Part,
    compute_part,
    elastic_of,
    face_of,
    load_part,
    load_piece,
    merge_parts,
    part_file,
    part_params,
    parts_of,
    piece_file,
    piece_params,
    reuse_rows,
    reuses,
)
from .rules import depth_at_load, depth_match

__all__ = ["Plan", "run_in_process", "run_on_cluster", "stats_hardness"]

PieceKey = tuple[str, str, float, "str | None"]


def stats_hardness(
    st: IndentationStage, sweep_rows: dict[str, dict[float, dict[str, list]]]
) -> dict[str, Any]:
    """The H values of the statistics pieces, from the sweeps of every surface.

    The paper's "maximal indentation depth … around 5 µm" (§ 4.1) is its maximum over all its
    tests, not a per-surface target: the depth compared is, per H, the largest threshold depth
    (from surface detection, :mod:`warptrunc.indent.depth`) at the largest load over every
    surface, punch and placement of the sweep; one H (one alloy) is matched to it.

    Parameters
    ----------
    st : IndentationStage
        The stage.
    sweep_rows : dict
        Surface → H (Pa; inf = elastic) → the rows of that H's sweep piece.

    Returns
    -------
    dict
        ``hardness``: the H values (Pa, inf = elastic) in the order of
        ``IndentationStage.stats``; ``depths``: H → the largest threshold depth at the largest
        load over the surfaces (m); ``match``:
        :func:`~warptrunc.reproduce.indentation.rules.depth_match` over the finite H values.
    """
    at = max(st.protocol.peak_loads)
    depths: dict[float, float | None] = {}
    for rows in sweep_rows.values():
        for h, r in rows.items():
            col = r.get("threshold_depth_m") or r["displacement_m"]  # pieces before it: δ
            dd = depth_at_load(r["punch_diameter_m"], r["peak_load_N"], col, r["converged"], at)
            top = max((v["max"] for v in dd["per_punch"].values()), default=None)
            if top is not None and (depths.get(h) is None or top > depths[h]):
                depths[h] = top
            depths.setdefault(h, None)
    finite = sorted(h for h in depths if math.isfinite(h))
    match = depth_match(finite, [depths[h] for h in finite], st.depth_target, st.depth_band)
    out: list[float] = []
    for m in st.stats:
        h = math.inf if m == "elastic" else match["H_match"]
        if h is not None and h not in out:
            out.append(h)
    return {"hardness": out, "depths": depths, "match": match}


class Plan:
    """The stage's pieces and parts, what is stored, and what is ready to run.

    Parameters
    ----------
    st : IndentationStage
        The stage.
    store : Path
        The piece folder (``OUT/indentation``).
    overwrite : bool
        Recompute pieces stored with other parameters (else :class:`StageConflict`).
    """

    def __init__(self, st: IndentationStage, store: Path, overwrite: bool) -> None:
        self.st, self.store, self.overwrite = st, Path(store), overwrite
        self.sweep = sweep_order(st)
        self.stieces: dict[PieceKey, dict[str, Any] | None] = {}  # planned piece → record or None
        self.starts: dict[Part, dict[str, Any]] = {}  # finished parts of unfinished pieces
        self.stats_done: set[str] = set()
        self.extra_parts = 0  # runs outside the pieces (the resolution check), for the total
        for s in st.surfaces:
            for h in self.sweep:
                self._plan((s, "sweep", h, None))
            if "elastic" in st.stats:
                self._plan((s, "stats", math.inf, None))
            if s == st.face_surface:
                for label, _kw in face_variants(st):
                    self._plan((s, "face", st.face_hardness, label))
        for s in st.surfaces:
            self._stats(s)

    # --- what is stored -----------------------------------------------------------------------

    def _plan(self, key: PieceKey) -> None:
        if key in self.stieces:
            return
        s, design, h, face = key
        path = piece_file(self.store, s, design, h, face)
        rec = load_piece(
            path, piece_params(self.st, s, design, h, face_of(self.st, face)), self.overwrite
        )
        self.stieces[key] = rec
        if rec is None:
            for part in parts_of(self.st, s, design, h, face):
                got = load_part(part_file(self.store, part), part_params(self.st, part))
                if got is not None:
                    self.starts[part] = got
            self._merge(key)

    def _merge(self, key: PieceKey) -> None:
        """Write the piece when every part is done; then its part files go."""
        parts = parts_of(self.st, *key)
        if self.stieces.get(key) is not None or not all(q in self.starts for q in parts):
            return
        rec = merge_parts(self.st, key, {q: self.starts[q] for q in parts})
        write_atomic(
            piece_file(self.store, *key), json.dumps(rec, indent=None, allow_nan=False) + "\n"
        )
        self.stieces[key] = rec
        for q in parts:
            part_file(self.store, q).unlink(missing_ok=True)
            self.starts.pop(q, None)
        self._stats(key[0])

    def _stats(self, s: str) -> None:
        """Plan the depth-match statistics of every surface once every sweep is complete (one
        H for the alloy: :func:`stats_hardness`)."""
        if self.stats_done or "depth-match" not in self.st.stats:
            return
        rows = {
            ss: {h: self.stieces.get((ss, "sweep", h, None)) for h in self.sweep}
            for ss in self.st.surfaces
        }
        if any(r is None for v in rows.values() for r in v.values()):
            return
        self.stats_done.update(self.st.surfaces)
        found = stats_hardness(
            self.st, {ss: {h: r["rows"] for h, r in v.items()} for ss, v in rows.items()}
        )
        for ss in self.st.surfaces:
            for h in found["hardness"]:
                self._plan((ss, "stats", h, None))

    # --- what runs --------------------------------------------------------------------------

    def done(self, part: Part) -> bool:
        """Whether ``part`` is finished (alone, or inside its stored piece).

        Parameters
        ----------
        part : Part
            The part.

        Returns
        -------
        bool
            True when its record is held or its piece is stored.
        """
        return part in self.starts or self.stieces.get(part.piece) is not None

    def reuse_rows(self, part: Part) -> dict[str, list] | None:
        """The elastic rows ``part`` takes its unyielded cycles from.

        Parameters
        ----------
        part : Part
            The part.

        Returns
        -------
        dict or None
            The rows of the elastic part of its punch; None when it solves them itself.
        """
        if not reuses(self.st, part):
            return None
        el = elastic_of(part)
        if el in self.starts:
            return self.starts[el]["rows"]
        rec = self.stieces.get(el.piece)
        return (
            None
            if rec is None
            else reuse_rows(rec["rows"], self.st.protocol.punch_diameters[part.punch])
        )

    def ready(self, running: set[Part]) -> list[Part]:
        """Parts that can start now, in the canonical order.

        Parameters
        ----------
        running : set of Part
            Parts in flight (left out).

        Returns
        -------
        list of Part
            Parts of planned, unstored pieces, not done, whose elastic part (if any) is done.
        """
        out = []
        for key, rec in list(self.stieces.items()):
            if rec is not None:
                continue
            for q in parts_of(self.st, *key):
                if q in running or self.done(q):
                    continue
                if reuses(self.st, q) and not self.done(elastic_of(q)):
                    continue
                out.append(q)
        return out

    def finish(self, part: Part, rec: dict[str, Any]) -> None:
        """Record a finished part; merge its piece when it was the last.

        Parameters
        ----------
        part : Part
            The part.
        rec : dict
            Its record (:func:`~.pieces.run_part`).
        """
        if self.stieces.get(part.piece) is None:
            self.starts[part] = rec
            self._merge(part.piece)

    def complete(self) -> bool:
        """Whether every planned piece is stored.

        Returns
        -------
        bool
            True when nothing is left to run.
        """
        return all(r is not None for r in self.stieces.values())

    def n_pieces(self) -> tuple[int, int]:
        """Pieces stored and planned.

        Returns
        -------
        tuple of int
            (stored, planned).
        """
        return sum(r is not None for r in self.stieces.values()), len(self.stieces)

    def parts_left(self) -> int:
        """Parts of the planned pieces not done yet, and ``extra_parts``: the total of the
        progress report (it grows when a surface's sweep plans its depth-match pieces).

        Returns
        -------
        int
            Parts still to run.
        """
        left = sum(
            not self.done(q)
            for key, rec in self.stieces.items()
            if rec is None
            for q in parts_of(self.st, *key)
        )
        return left + self.extra_parts

    def count(self, bar: Any) -> None:
        """One part done on ``bar``, whose total follows :meth:`parts_left`.

        Parameters
        ----------
        bar : progress report
            :func:`warptrunc._support.progress.progress_bar`.
        """
        bar.update()
        bar.total = max(bar.total or 0, bar.n + self.parts_left())

    def records(self) -> list[tuple[tuple[str, str, float], dict[str, Any]]]:
        """The stored pieces in the canonical order, keyed as the summary reads them.

        Returns
        -------
        list of ((str, str, float), dict)
            ((surface, design or ``face:<label>``, H), piece record).
        """
        out = []
        for s in self.st.surfaces:
            keys = [k for k in self.stieces if k[0] == s]
            keys.sort(
                key=lambda k: (
                    ("sweep", "stats", "face").index(k[1]),
                    self.sweep.index(k[2]) if k[1] == "sweep" else 0,
                )
            )
            for k in keys:
                if self.stieces[k] is not None:
                    out.append(
                        ((s, k[1] if k[3] is None else f"face:{k[3]}", k[2]), self.stieces[k])
                    )
        return out

    def cost(self, part: Part) -> float:
        """A rough relative cost: placements × punch pixels × refinement × plasticity, and the
        elastic sweep parts (which unlock the finite-H ones) first.

        Parameters
        ----------
        part : Part
            The part.

        Returns
        -------
        float
            Larger runs first on a cluster.
        """
        st = self.st
        d = st.protocol.punch_diameters[part.punch]
        c = design_of(st, part.design)[1] * (d / st.pixel_size) ** 2 * refine_of(st, d) ** 2
        c *= 1.0 if math.isinf(part.hardness) else 2.0
        return c * (1e6 if part.design == "sweep" and math.isinf(part.hardness) else 1.0)


def run_in_process(plan: Plan, *, device, stop, bar) -> None:
    """Run the ready parts one at a time, in the canonical order, until the plan is complete.

    Parameters
    ----------
    plan : Plan
        The plan.
    device : str, optional
        Warp device.
    stop : callable
        ``stop(what)`` raises when the time budget is spent.
    bar : progress bar
        Updated once per part.
    """
    while True:
        ready = plan.ready(set())
        if not ready:
            return
        part = ready[0]
        stop(part.label())
        rec = compute_part(plan.st, part, str(plan.store), device, plan.reuse_rows(part))
        plan.finish(part, rec)
        plan.count(bar)


def run_on_cluster(
    plan: Plan, client, *, device, deadline: float | None, bar, max_attempts: int = 3
) -> bool:
    """Run the ready parts on a Dask cluster, one part in flight per worker.

    Parameters
    ----------
    plan : Plan
        The plan.
    client : distributed.Client
        The cluster's client.
    device : str, optional
        Warp device of the tasks (None: each worker's pinned ``$WARPTRUNC_DEVICE``).
    deadline : float, optional
        ``time.perf_counter()`` after which no part is submitted (those in flight finish).
    bar : progress bar
        Updated once per part.
    max_attempts : int
        Submissions of one part before its error is raised (a lost worker, a killed process).

    Returns
    -------
    bool
        False when the deadline stopped the run before the plan was complete.
    """
    from distributed import as_completed

    inflight: dict[Any, Part] = {}
    attempts: dict[Part, int] = {}
    pool = as_completed()
    n_workers = [1, 0.0]

    def capacity() -> int:
        if time.monotonic() - n_workers[1] > 5:
            n_workers[:] = [
                max(1, len(client.scheduler_info().get("workers", {}))),
                time.monotonic(),
            ]
        return n_workers[0]

    def submit() -> bool:
        late = deadline is not None and time.perf_counter() > deadline
        if late:
            return False
        running = set(inflight.values())
        ready = sorted(plan.ready(running), key=plan.cost, reverse=True)
        for part in ready[: max(0, capacity() - len(inflight))]:
            attempts[part] = attempts.get(part, 0) + 1
            fut = client.submit(
                compute_part,
                plan.st,
                part,
                str(plan.store.resolve()),
                device,
                plan.reuse_rows(part),
                key=f"indent-{part_file(plan.store, part).stem}-{attempts[part]}",
                pure=False,
            )
            inflight[fut] = part
            pool.add(fut)
        return True

    on_time = submit()
    while inflight:
        fut = next(pool)
        part = inflight.pop(fut)
        try:
            rec = fut.result()
        except Exception as exc:  # a lost worker or a failed solve: the file, else once more
            rec = load_part(part_file(plan.store, part), part_params(plan.st, part))
            if rec is None and attempts[part] >= max_attempts:
                raise RuntimeError(
                    f"indentation part {part.label()} failed {attempts[part]} times: {exc}"
                ) from exc
        if rec is not None:
            plan.finish(part, rec)
            plan.count(bar)
        on_time = submit() and on_time
    return on_time and plan.complete()
