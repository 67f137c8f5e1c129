# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""How many cases go into each task of the Dask engine: :class:`ShardPlanner`.

Pure bookkeeping, no Dask and no Warp, so that its dynamics can be driven by a simulation
(``tests/test_sweep_sharding.py``). :func:`~warptrunc.sweep.cluster.run_dask` asks it for the
size of each shard it submits and tells it how long each finished shard took on its worker.

The size aims at ``target_s`` of work per task from the throughput measured so far: the
seconds of finished tasks over their cases, leaving out each worker's first task (its CUDA
context and kernel loads are not the cases' cost). While no such task has finished the size
starts at 1 and doubles with every round of finished tasks (as many as there are workers;
TCP's slow start), so slow first tasks never keep the shards at one case, and heavy cases
are not sent many at a time before their time is known. Whatever the estimate, a shard holds at most
⌈total/(k·n_workers)⌉ cases (k = ``tasks_per_worker``, 4): many homogeneous cases become about
k equal tasks per worker, so that the last task of a worker is a small part of its work.
Near the end the size shrinks so that ≥ 2 tasks per worker remain, but not below
``tail_fraction · target_s`` of work per task (tiny tasks cost more in scheduling and part
writes than they balance).
"""

from __future__ import annotations

import math
from collections import deque
from typing import Any

__all__ = ["ShardPlanner"]


class ShardPlanner:
    """Shard sizes for one run of the Dask engine.

    Parameters
    ----------
    total : int
        Cases to run (count).
    target_s : float
        Work per task to aim for (s).
    max_size : int
        Largest shard (cases).
    tasks_per_worker : int
        k: no shard holds more than ⌈total/(k·n_workers)⌉ cases (count).
    window : int
        Finished tasks (not first on their worker) whose times give the throughput (count).
    tail_fraction : float
        Shards shrink near the end, but not below this fraction of ``target_s`` of work.

    Notes
    -----
    A task's time is its duration on the worker (:func:`~warptrunc.sweep.engines.compute_shard`
    returns it, with the worker's process id); rows without it are timed by the sum of their
    cases' ``seconds`` (NaN and missing values left out). A task whose time is unknown
    counts for nothing.
    """

    def __init__(
        self,
        total: int,
        *,
        target_s: float = 1.0,
        max_size: int = 4096,
        tasks_per_worker: int = 4,
        window: int = 16,
        tail_fraction: float = 0.125,
    ) -> None:
        self.total = max(1, int(total))
        self.target_s = float(target_s)
        self.max_size = max(1, int(max_size))
        self.k = max(1, int(tasks_per_worker))
        self.tail_fraction = float(tail_fraction)
        self._recent: deque[tuple[int, float]] = deque(maxlen=max(1, int(window)))
        self._seen: set[Any] = set()
        self._done = 0

    def case_seconds(self) -> float | None:
        """Seconds per case from the recent finished tasks.

        Returns
        -------
        float or None
            Their seconds over their cases (s), or None while no task counts.
        """
        n = sum(c for c, _ in self._recent)
        s = sum(t for _, t in self._recent)
        return s / n if n > 0 and s > 0 else None

    def size(self, remaining: int, n_workers: int) -> int:
        """Cases for the next task.

        Parameters
        ----------
        remaining : int
            Cases not yet submitted (count).
        n_workers : int
            Workers of the cluster (count); values below 1 count as 1.

        Returns
        -------
        int
            ≥ 1 and ≤ max(1, remaining): ⌈target_s/case_seconds⌉, or the slow-start size while
            no time is known (2 to the number of rounds of ``n_workers`` finished tasks), clipped to [1, ``max_size``] and to
            ⌈total/(k·n_workers)⌉; then, near the end, to ⌈remaining/(2·n_workers)⌉ but not
            below ⌈tail_fraction·target_s/case_seconds⌉.
        """
        w = max(1, int(n_workers))
        remaining = max(0, int(remaining))
        cap = min(self.max_size, -(-self.total // (self.k * w)))
        per_case = self.case_seconds()
        if per_case is None:
            size = min(2 ** min(self._done // w, 30), cap)
        else:
            size = min(cap, math.ceil(self.target_s / per_case))
            floor = math.ceil(self.tail_fraction * self.target_s / per_case)
            size = min(size, max(floor, -(-remaining // (2 * w))))
        return max(1, min(size, max(1, remaining)))

    def finished(self, n_cases: int, seconds: float | None, worker: Any = None) -> None:
        """Record a finished task.

        Parameters
        ----------
        n_cases : int
            Cases of the task (count).
        seconds : float or None
            Its duration (s); None or NaN: unknown, not counted.
        worker : hashable, optional
            The worker that ran it; its first task is left out (warm-up). None: counted.
        """
        self._done += 1
        if worker is not None and worker not in self._seen:
            self._seen.add(worker)
            return
        if n_cases > 0 and seconds is not None and seconds == seconds and seconds > 0:
            self._recent.append((int(n_cases), float(seconds)))

    @staticmethod
    def task_seconds(out: dict[str, Any]) -> float | None:
        """The duration of a finished task from its result (s), or None.

        Parameters
        ----------
        out : dict
            :func:`~warptrunc.sweep.engines.compute_shard`'s result: ``seconds`` (the task's
            time on its worker), else the sum of its rows' ``seconds`` (per case, the first
            fit range's row; NaN and non-numbers left out).

        Returns
        -------
        float or None
            Seconds, or None when nothing is known.
        """
        s = out.get("seconds")
        if isinstance(s, (int, float)) and s == s:
            return float(s)
        vals = [rs[0].get("seconds") for rs in out.get("rows") or () if rs]
        vals = [float(v) for v in vals if isinstance(v, (int, float)) and v == v]
        return sum(vals) if vals else None
