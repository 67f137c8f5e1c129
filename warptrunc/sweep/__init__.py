# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Parameter sweeps over D and δ = R_t/W_r (paper §4.4, Fig. 9, Table 3), with a result store.

>>> from warptrunc.sweep import SweepGrid, run_sweep, load
>>> grid = SweepGrid.from_values(D=[2.1, 2.5], delta=[0.01], seeds="0-4")
>>> df = run_sweep(grid, "runs/g2", n=1024, min_pixels=[1, 100])   # doctest: +SKIP
>>> load("runs/g2").groupby(["min_pixels", "D_in"]).alpha.agg(["mean", "std"])  # doctest: +SKIP

Modules: ``grid`` (SweepGrid, SweepOptions, case ids), ``store`` (the Parquet store:
sweep.json, ``curves/part-*.parquet``, cases.parquet), ``read`` (the columns of cases.parquet;
:func:`load`, :func:`load_curves`), ``migration`` (:func:`migrate`, the previous layout), ``curves`` (writing and
reading one part), ``engines`` (one case, one shard; in-process execution), ``batch`` (several light
surfaces per launch on a GPU), ``rows`` and ``elastic`` (a case's columns), ``cluster`` (Dask), ``sharding`` (its shard sizes),
``run`` (:func:`run_sweep`), ``stats`` (pandas summaries, :func:`linear_fit`, and the older
in-memory :func:`sweep`/:class:`SweepTable`). pandas, pyarrow and dask (dependencies of
warptrunc) are imported only inside these functions, so ``import warptrunc`` stays light.
"""

from .curves import CURVE_COLUMNS
from .grid import Case, SweepGrid, parse_seeds
from .migration import migrate
from .options import SweepOptions
from .read import BEM_QUANTITIES, CASE_COLUMNS, RUN_COLUMNS, bem_long, load, load_curves
from .run import run_sweep
from .stats import SweepTable, alpha_summary, linear_fit, sweep
from .store import Store

__all__ = [
    "BEM_QUANTITIES",
    "CASE_COLUMNS",
    "CURVE_COLUMNS",
    "RUN_COLUMNS",
    "Case",
    "Store",
    "SweepGrid",
    "SweepOptions",
    "SweepTable",
    "alpha_summary",
    "bem_long",
    "linear_fit",
    "load",
    "load_curves",
    "migrate",
    "parse_seeds",
    "run_sweep",
    "sweep",
]
