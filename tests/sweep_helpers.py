# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Helpers shared by the sweep tests (tests/test_sweep.py, tests/test_sweep_dask.py) and the
reproduce-on-workers tests."""

from warptrunc.sweep import RUN_COLUMNS, SweepOptions
from warptrunc.sweep.curves import part_files, part_rows

__all__ = ["OPTS", "OPTS_CLI", "case_ids_on_disk", "results_only", "two_worker_client"]

OPTS = SweepOptions(n=64, increments=60, max_depth_fraction=0.3, min_pixels=(1, 20))
"""The options of the small sweeps of the tests (64², 60 increments to 0.3·R_t, two fit ranges)."""

OPTS_CLI = [
    "--increments",
    "60",
    "--max-depth-fraction",
    "0.3",
    "--min-pixels",
    "1",
    "20",
    "--device",
    "cpu",
    "--no-progress",
]
"""OPTS's truncation and fit ranges as options of ``warptrunc sweep``, on the CPU without
progress bars (the grid size is the caller's: ``--n 64`` is OPTS's)."""


def results_only(df):
    """The cases table without the columns that describe where and when a case ran."""
    return df.drop(columns=list(RUN_COLUMNS)).reset_index(drop=True)


def case_ids_on_disk(out):
    """Case ids held by the parts of a store (a case in two parts counts twice)."""
    return [rs[0]["case_id"] for f in part_files(out / "curves") for rs in (part_rows(f) or [])]


def two_worker_client():
    """A Dask client of a local cluster of 2 worker processes, one thread each (a generator for
    a module-scoped fixture: yields the client, then closes it and the cluster)."""
    import logging

    import distributed

    cluster = distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        dashboard_address=":0",
        silence_logs=logging.ERROR,
    )
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()
