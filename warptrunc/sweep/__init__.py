# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Parameter sweeps over D and δ = R_t/W_r (paper §4.4, Fig. 9, Table 3), with a result store.

>>> from warptrunc.sweep import SweepExecution, SweepGrid, SweepOptions, run_sweep, load
>>> grid = SweepGrid(D=[2.1, 2.5], delta=[0.01], seeds="0-4")
>>> df = run_sweep(grid, "runs/g2", options=SweepOptions(n=1024, min_pixels=(1, 100)),
...                execution=SweepExecution(workers="auto"))   # doctest: +SKIP
>>> load("runs/g2").groupby(["min_pixels", "D_in"]).alpha.agg(["mean", "std"])  # doctest: +SKIP

Three objects say everything a sweep does: the grid (:class:`SweepGrid`: D × δ × seeds and
extra axes), what each case computes (:class:`SweepOptions`) and where the cases run
(:class:`SweepExecution`); :func:`run_sweep` takes them.

Modules: ``options`` (SweepOptions, SweepExecution, the axes a grid may vary), ``grid``
(SweepGrid, case ids, the store's spelling of the options), ``store`` (the Parquet store:
sweep.json, ``curves/part-*.parquet``, cases.parquet; its lock), ``read`` (the columns of
cases.parquet; :func:`load`, :func:`load_curves`), ``curves`` (writing and reading one part),
``normalisation`` (rows written before the one normalisation), ``engines`` (one case, one
shard; in-process execution), ``batch`` (several light surfaces per launch on a GPU), ``rows``
(a case's columns: fit ranges, fractal dimensions, elastic solves), ``cluster`` (the Dask
engine and its local cluster), ``_affinity`` (the CPUs near a GPU, where the cluster's pinned
workers bind), ``groups`` (devices per Dask worker), ``sharding`` (the Dask
engine's shard sizes), ``run`` (:func:`run_sweep`), ``stats`` (pandas summaries,
:func:`linear_fit`, the in-memory :func:`sweep`/:class:`SweepTable`). pandas, pyarrow and dask
(dependencies of warptrunc) are imported only inside these functions, so ``import warptrunc``
stays light.
"""

from .curves import CURVE_COLUMNS
from .grid import Case, SweepGrid, parse_seeds
from .options import SweepExecution, SweepOptions
from .read import BEM_QUANTITIES, CASE_COLUMNS, RUN_COLUMNS, bem_long, load, load_curves
from .run import run_sweep
from .stats import SweepTable, alpha_summary, linear_fit, sweep, worth_reading
from .store import Store

__all__ = [
    "BEM_QUANTITIES",
    "CASE_COLUMNS",
    "CURVE_COLUMNS",
    "RUN_COLUMNS",
    "Case",
    "Store",
    "SweepExecution",
    "SweepGrid",
    "SweepOptions",
    "SweepTable",
    "alpha_summary",
    "bem_long",
    "linear_fit",
    "load",
    "load_curves",
    "parse_seeds",
    "run_sweep",
    "sweep",
    "worth_reading",
]
