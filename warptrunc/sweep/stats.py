# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Summaries of a sweep's cases table with pandas, the α(D) line, and the in-memory table
(:func:`sweep`, :class:`SweepTable`).

:func:`alpha_summary` gives, per fit range, the mean and standard deviation of α over the
seeds at each D_in and the least-squares line α(D_in) (the paper's Table 3).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .._support.docs import SHARED_DOCS, fill_doc
from .read import require_extra
from .run import run_sweep

__all__ = ["MIN_TREND_D", "SweepTable", "alpha_summary", "group_stats", "linear_fit", "sweep"]

MIN_TREND_D = 3
"""Fewest values of D (each with a finite mean α) that the line α(D_in) is fitted through: a
line through two points fits them exactly (r = ±1) and says nothing about a trend."""


def linear_fit(x: Iterable[float], y: Iterable[float]) -> dict[str, float]:
    """Least-squares line y = slope·x + intercept with Pearson r (as in the paper's Table 3).

    Parameters
    ----------
    x, y : iterable of float
        Abscissae and ordinates, same length (≥ 2), in any units.

    Returns
    -------
    dict of str to float
        ``slope`` (unit of y per unit of x), ``intercept`` (unit of y) and Pearson ``r``
        (dimensionless; NaN when y is constant). The one straight-line fit of warptrunc (power
        laws: :func:`warptrunc.fit_power_law`).

    Examples
    --------
    >>> linear_fit([2.1, 2.5, 2.9], [0.40, 0.45, 0.50])["slope"]
    0.125...
    """
    x = np.asarray(list(x), dtype=float)
    y = np.asarray(list(y), dtype=float)
    slope, intercept = np.polyfit(x, y, 1)
    r = float(np.corrcoef(x, y)[0, 1]) if np.ptp(y) > 0 else float("nan")
    return {"slope": float(slope), "intercept": float(intercept), "r": r}


def group_stats(df, by: Sequence[str], value: str) -> list[dict[str, Any]]:
    """Mean and sample standard deviation (ddof=1) of the finite ``value`` per group of ``by``.

    Groups whose values are all NaN are kept with n = 0 and NaN statistics.

    Parameters
    ----------
    df : pandas.DataFrame
        Cases table (:func:`warptrunc.sweep.load`).
    by : sequence of str
        Columns to group by; groups sorted, NaN keys kept.
    value : str
        Column to summarise.

    Returns
    -------
    list of dict
        One dict per group: the ``by`` values, ``<value>_mean``, ``<value>_sd`` (unit of the
        column) and ``n`` (finite values, count).

    Raises
    ------
    ImportError
        If pandas or pyarrow (dependencies of warptrunc) is missing from the environment.
    """

    require_extra()
    v = df[value].astype(float)
    d = df.assign(_v=v.where(np.isfinite(v)))
    g = d.groupby(list(by), sort=True, dropna=False)["_v"].agg(["mean", "std", "count"])
    return [
        {
            **dict(zip(by, key if isinstance(key, tuple) else (key,), strict=True)),
            f"{value}_mean": float(r["mean"]),
            f"{value}_sd": float(r["std"]),
            "n": int(r["count"]),
        }
        for key, r in g.iterrows()
    ]


def alpha_summary(df) -> dict[str, Any]:
    """{"fit_ranges": {min_pixels: {"per_D": [...], "alpha_vs_D": line or None}}} of a table.

    Fit ranges relative to each case (``min_pixels_fraction`` f) are keyed ``"fraction=f"``.

    ``df`` is a cases table (:func:`warptrunc.sweep.load`) or a :class:`SweepTable`.
    ``per_D`` holds ``D_in``, ``alpha_mean``, ``alpha_sd`` (over seeds and δ) and ``n``;
    ``alpha_vs_D`` is :func:`linear_fit` of the means against D_in, or None with fewer than
    ``MIN_TREND_D`` (3) values of D that have a finite mean.

    Parameters
    ----------
    df : pandas.DataFrame or SweepTable
        Cases table with the columns ``min_pixels``, ``D_in`` and ``alpha`` (and optionally
        ``min_pixels_fraction``).

    Returns
    -------
    dict
        ``{"fit_ranges": {key: {"per_D": [...], "alpha_vs_D": dict or None}}}``.
    """
    import pandas as pd

    if isinstance(df, SweepTable):
        df = pd.DataFrame(df.columns)
    out = {}
    if "min_pixels_fraction" in df and df["min_pixels_fraction"].notna().any():
        frac = df["min_pixels_fraction"].astype(float)
        parts = [(str(int(mp)), p) for mp, p in df[frac.isna()].groupby("min_pixels", sort=True)]
        parts += [(f"fraction={f:g}", p) for f, p in df[frac.notna()].groupby(frac[frac.notna()])]
    else:
        parts = [(str(int(mp)), p) for mp, p in df.groupby("min_pixels", sort=True)]
    for key, part in parts:
        stats = group_stats(part, ["D_in"], "alpha")
        ok = [r for r in stats if r["n"] > 0 and np.isfinite(r["alpha_mean"])]
        line = (
            linear_fit([r["D_in"] for r in ok], [r["alpha_mean"] for r in ok])
            if len(ok) >= MIN_TREND_D
            else None
        )
        out[key] = {"per_D": stats, "alpha_vs_D": line}
    return {"fit_ranges": out}


@dataclass(frozen=True, eq=False)
class SweepTable:
    """One row per (D, δ, seed, fit range); columns as 1-D arrays (the in-memory API)."""

    columns: dict[str, np.ndarray]
    """Column name → (n_rows,) array. Lengths in m."""

    def to_dict(self) -> dict[str, np.ndarray]:
        """The columns.

        Returns
        -------
        dict of str to ndarray
            A new dict of the (n_rows,) column arrays (the arrays are not copied).
        """
        return dict(self.columns)

    def group_stats(self, by: Sequence[str], value: str) -> list[dict[str, Any]]:
        """Mean and sample standard deviation of ``value`` grouped by the columns ``by``.

        Parameters
        ----------
        by : sequence of str
            Columns to group by.
        value : str
            Column to summarise.

        Returns
        -------
        list of dict
            As :func:`group_stats`.
        """
        import pandas as pd

        return group_stats(pd.DataFrame(self.columns), by, value)


@fill_doc(SHARED_DOCS)
def sweep(
    grid: Any,
    store: str | Path | None = None,
    *,
    options: Any = None,
    progress: bool = True,
    device: Any = None,
) -> SweepTable:
    """Run truncation analyses over a grid in this process; the table as a :class:`SweepTable`.

    :func:`warptrunc.sweep.run_sweep` with its default execution, returning NumPy columns
    instead of a DataFrame.

    Parameters
    ----------
    grid : SweepGrid, dict or path
        D_in × δ × seeds (and extra axes), as :func:`~warptrunc.sweep.run_sweep` takes it.
    store : str or Path, optional
        Result store folder, resumed when it exists; None keeps the results in memory only.
    options : SweepOptions, optional
        What every case computes; default ``SweepOptions()`` (aluminium against a rigid flat).
    progress : bool
        Show a progress bar.
    {warp_device}

    Returns
    -------
    SweepTable
        One row per (D, δ, seed, fit range); lengths in m.

    Raises
    ------
    ValueError
        If a grid value or option is out of range.
    ImportError
        If pandas or pyarrow (dependencies of warptrunc) is missing from the environment.
    """
    df = run_sweep(grid, store, options=options, progress=progress, device=device)
    return SweepTable({c: df[c].to_numpy() for c in df.columns})
