# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Shard sizes of the Dask engine (warptrunc.sweep.sharding.ShardPlanner), driven by a
simulation of the client's loop: workers whose first task pays a warm-up, light cases that
cost a per-batch overhead plus a per-case time, heavy cases of seconds; the task counts and
the finishing times are checked against what an ideal split of the same work gives."""

from __future__ import annotations

import heapq
import math

import pytest

from warptrunc.sweep.sharding import ShardPlanner


def simulate(total, n_workers, *, per_case, per_task, warm, latency=2e-3, planner=None):
    """Event simulation of ``cluster._run_on``'s loop: at most 2 tasks in flight per worker,
    a task goes to the worker with the fewest tasks (running or queued), runs for
    ``warm`` (its worker's first task only) + ``per_task`` + n·``per_case`` (s), and its
    result reaches the client ``latency`` (s) later, which then submits the next one.
    Returns (task sizes in submission order, finishing time of the last task (s), planner).
    """
    plan = planner or ShardPlanner(total)
    left, sizes, inflight, events = total, [], 0, []
    queues = [[] for _ in range(n_workers)]
    started = [False] * n_workers

    def start(w, t):
        n = queues[w][0]
        d = (0.0 if started[w] else warm) + per_task + n * per_case
        started[w] = True
        heapq.heappush(events, (t + d + latency, t + d, w, n, d))

    def top_up(t):
        nonlocal left, inflight
        while left and inflight < 2 * n_workers:
            n = plan.size(left, n_workers)
            assert 1 <= n <= left
            sizes.append(n)
            left -= n
            inflight += 1
            w = min(range(n_workers), key=lambda i: (len(queues[i]), i))
            queues[w].append(n)
            if len(queues[w]) == 1:
                start(w, t)

    top_up(0.0)
    end = 0.0
    while events:
        t, done, w, n, d = heapq.heappop(events)
        queues[w].pop(0)
        inflight -= 1
        if queues[w]:
            start(w, done)
        plan.finished(n, d, worker=w)
        end = max(end, done)
        top_up(t)
    assert sum(sizes) == total
    return sizes, end, plan


# The light sweep of issue 39 on a GPU: 0.4 ms a case and 3 ms a task, 2 s of warm-up in the
# first task of each worker (CUDA context, kernel loads).
LIGHT = dict(per_case=4e-4, per_task=3e-3, warm=2.0)


@pytest.mark.parametrize("n_workers", [1, 2, 4, 8])
def test_light_cases_few_tasks_despite_a_slow_first_task(n_workers):
    total = 2000
    sizes, end, _ = simulate(total, n_workers, **LIGHT)
    # the work spread evenly, one task per worker at a time, plus the warm-up
    ideal = LIGHT["warm"] + total * LIGHT["per_case"] / n_workers
    # about k = 4 tasks per worker, plus the first 2 per worker (1 case each) and a short tail
    assert len(sizes) <= 4 * n_workers + 2 * n_workers + 8, sizes
    assert max(sizes) == math.ceil(total / (4 * n_workers))  # the static plan's bound
    assert end <= ideal + 0.2 * (ideal - LIGHT["warm"]) + 0.05, (end, ideal)


def test_many_light_cases_keep_the_static_bound():
    total, w = 20000, 4
    sizes, end, _ = simulate(total, w, **LIGHT)
    # the shards grow to the bound, then shrink near the end, not below 1/8 s of work each
    assert max(sizes) == total // (4 * w) and len(sizes) <= 12 * w
    assert min(sizes[3 * w : -1]) >= math.ceil(0.125 / LIGHT["per_case"]) * 0.9
    assert end <= LIGHT["warm"] + 1.2 * total * LIGHT["per_case"] / w + 0.05


def test_heavy_cases_one_per_task_and_balanced():
    """Elastic cases of 1.5 s: about one case per task (1 s aimed at), every worker busy to
    the end."""
    total, w = 96, 4
    heavy = dict(per_case=1.5, per_task=0.01, warm=2.0)
    sizes, end, _ = simulate(total, w, **heavy)
    assert max(sizes) <= 2  # never many heavy cases in one task before their time is known
    ideal = heavy["warm"] + total * heavy["per_case"] / w
    assert end <= ideal + 2 * heavy["per_case"] + 0.1, (end, ideal)


def test_medium_cases_aim_at_the_target_seconds():
    """20 ms cases, 10 000 of them on 2 workers: tasks of about 1 s (50 cases), not the static
    bound (1250)."""
    sizes, _, plan = simulate(10000, 2, per_case=0.02, per_task=0.0, warm=1.0)
    assert plan.case_seconds() == pytest.approx(0.02)
    big = [s for s in sizes if s > 1]
    assert len(sizes) < 215 and max(sizes) == 51  # 50·0.02 s rounds to just above 1 s
    assert sum(s in (50, 51) for s in big) >= len(big) - 12  # all but the start and the tail
    assert min(sizes[-10:-1]) >= math.ceil(0.125 / 0.02)  # the tail: ≥ 1/8 s a task but the last


def test_first_task_per_worker_left_out_and_unknown_times_ignored():
    p = ShardPlanner(1000, target_s=1.0)
    assert p.case_seconds() is None
    assert p.size(1000, 2) == 1  # nothing known yet: slow start
    p.finished(1, 5.0, worker="a")  # a's first task: warm-up, not counted
    assert p.case_seconds() is None and p.size(999, 2) == 1
    p.finished(1, 5.0, worker="b")  # a round of 2 workers: doubled
    assert p.case_seconds() is None and p.size(998, 2) == 2
    p.finished(3, float("nan"), worker="a")
    p.finished(3, None, worker="a")
    assert p.case_seconds() is None and p.size(990, 2) == 4 and p.size(990, 1) == 16
    p.finished(10, 0.05, worker="a")
    assert p.case_seconds() == pytest.approx(0.005)
    # 200 cases make 1 s; the bound is 1000/(4·2) = 125
    assert p.size(900, 2) == 125
    # near the end: ≥ 2 tasks per worker, but not below 1/8 s of work (25 cases)
    assert p.size(400, 2) == 100 and p.size(40, 2) == 25 and p.size(10, 2) == 10


def test_task_seconds_from_the_result():
    rows = [
        [{"seconds": 0.5}, {"seconds": 0.5}],
        [{"seconds": float("nan")}],
        [{"x": 1}],
        [{"seconds": 0.25}],
    ]
    assert ShardPlanner.task_seconds({"seconds": 2.0, "rows": rows}) == 2.0
    assert ShardPlanner.task_seconds({"seconds": None, "rows": rows}) == 0.75
    assert ShardPlanner.task_seconds({"rows": [[{"seconds": float("nan")}]]}) is None
