# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Summaries of a sweep's cases table with pandas, the α(D) line, and the in-memory table
(:func:`sweep`, :class:`SweepTable`).

:func:`alpha_summary` gives, per fit range and δ, the mean and standard deviation of α over the
seeds at each D_in and the least-squares line α(D_in) (the paper's Table 3), from the fits
:func:`worth_reading` keeps: the one filter of the sweep's summary, of ``summary.json`` and of
:func:`warptrunc.plot.alpha_vs_D`.
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

__all__ = [
    "MIN_TREND_D",
    "SweepTable",
    "alpha_summary",
    "group_stats",
    "linear_fit",
    "sweep",
    "worth_reading",
]

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


def worth_reading(df) -> Any:
    """Which rows of a cases table hold a fit worth reading: the one filter of every summary
    and figure of α.

    A row is kept when its case ran (``error`` null), its fit is not flagged (``fit_error``
    null: :func:`warptrunc.plausibility.check_fit` found nothing, or the fit range had enough
    increments) and α is finite. A column that is absent flags nothing.

    Parameters
    ----------
    df : pandas.DataFrame
        Cases table (:func:`warptrunc.sweep.load`), or any frame with an ``alpha`` column.

    Returns
    -------
    pandas.Series of bool
        True for the rows worth reading, indexed as ``df``.
    """
    alpha = df["alpha"].astype(float)
    keep = alpha.notna() & np.isfinite(alpha.fillna(0.0))
    for col in ("error", "fit_error"):
        if col in df:
            keep &= df[col].isna()
    return keep


def _fit_range_parts(df) -> list[tuple[str, Any]]:
    """(key, rows) per fit range: ``"10"`` for ``min_pixels``, ``"fraction=f"`` for
    ``min_pixels_fraction``."""
    if "min_pixels_fraction" in df and df["min_pixels_fraction"].notna().any():
        frac = df["min_pixels_fraction"].astype(float)
        parts = [(str(int(mp)), p) for mp, p in df[frac.isna()].groupby("min_pixels", sort=True)]
        parts += [(f"fraction={f:g}", p) for f, p in df[frac.notna()].groupby(frac[frac.notna()])]
        return parts
    return [(str(int(mp)), p) for mp, p in df.groupby("min_pixels", sort=True)]


def alpha_summary(df) -> dict[str, Any]:
    """α per fit range, δ and D_in over the seeds, and the line α(D_in) per δ (Table 3).

    Only the fits :func:`worth_reading` keeps enter the statistics and the lines; the others
    are listed under ``flagged`` with their reason. The statistics are over independent
    surfaces: the seeds of one (D_in, δ), each seed counted once. δ (= R_t/W_r) is its own
    axis, never pooled: the maps of one seed at two δ are one surface scaled in height, so
    pooling them would count one surface twice.

    Fit ranges relative to each case (``min_pixels_fraction`` f) are keyed ``"fraction=f"``.

    Parameters
    ----------
    df : pandas.DataFrame or SweepTable
        Cases table (:func:`warptrunc.sweep.load`) with the columns ``min_pixels``, ``D_in``
        and ``alpha`` (and where present ``delta``, ``seed``, ``error``, ``fit_error``,
        ``min_pixels_fraction``).

    Returns
    -------
    dict
        ``{"fit_ranges": {key: {"per_D": [...], "alpha_vs_D": [...], "flagged": [...]}}}``.
        ``per_D``: one row per (D_in, δ) with ``D_in``, ``delta`` (None without the column),
        ``alpha_mean``, ``alpha_sd`` (sample sd over the seeds, dimensionless), ``n`` (seeds
        whose fit is worth reading) and ``n_flagged`` (seeds whose fit is left out).
        ``alpha_vs_D``: per δ with at least ``MIN_TREND_D`` (3) values of D holding a mean,
        ``{"delta", "slope", "intercept", "r"}`` (:func:`linear_fit` of the means against
        D_in). ``flagged``: ``{"D_in", "delta", "seed", "alpha", "fit_error"}`` of each fit
        left out that has a finite α (for figures that draw them hollow).
    """
    import pandas as pd

    if isinstance(df, SweepTable):
        df = pd.DataFrame(df.columns)
    df = df.assign(_keep=worth_reading(df))
    if "delta" not in df:
        df = df.assign(delta=np.nan)
    if "seed" not in df:
        df = df.assign(seed=np.arange(len(df)))
    if "fit_error" not in df:
        df = df.assign(fit_error=None)

    def opt(v: Any) -> float | None:
        return None if pd.isna(v) else float(v)

    out = {}
    for key, part in _fit_range_parts(df):
        per_d = []
        for (d_in, delta), g in part.groupby(["D_in", "delta"], sort=True, dropna=False):
            good = g[g["_keep"]].drop_duplicates("seed")  # one value per surface
            a = good["alpha"].astype(float).to_numpy()
            per_d.append(
                {
                    "D_in": float(d_in),
                    "delta": opt(delta),
                    "alpha_mean": float(a.mean()) if a.size else float("nan"),
                    "alpha_sd": float(a.std(ddof=1)) if a.size > 1 else float("nan"),
                    "n": int(a.size),
                    "n_flagged": int(g.loc[~g["_keep"], "seed"].nunique()),
                }
            )
        lines = []
        for delta in dict.fromkeys(r["delta"] for r in per_d):
            ok = [r for r in per_d if r["delta"] == delta and r["n"] > 0]
            if len(ok) >= MIN_TREND_D:
                line = linear_fit([r["D_in"] for r in ok], [r["alpha_mean"] for r in ok])
                lines.append({"delta": delta, **line})
        bad = part[~part["_keep"] & np.isfinite(part["alpha"].astype(float))]
        flagged = [
            {
                "D_in": float(r.D_in),
                "delta": opt(r.delta),
                "seed": int(r.seed),
                "alpha": float(r.alpha),
                "fit_error": None if pd.isna(r.fit_error) else str(r.fit_error),
            }
            for r in bad.itertuples()
        ]
        out[key] = {"per_D": per_d, "alpha_vs_D": lines, "flagged": flagged}
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
