# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Parameter sweeps over D and δ = R_t/W_r (paper §4.4, Fig. 9, Table 3).

Each case generates a WM surface, truncates it, and fits the power law for one or more fit
ranges. Rows are appended to a CSV as they finish, so an interrupted sweep keeps its results.
"""

from __future__ import annotations

import csv
import itertools
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import warp as wp

from .stiffness import DEFAULT_MIN_PIXELS, Material, fit_power_law, stiffness_curve
from .truncation import truncate
from .wm import wm_surface

__all__ = ["SweepTable", "linear_fit", "sweep"]


@dataclass(frozen=True, eq=False)
class SweepTable:
    """One row per (D, δ, seed, fit range); columns as 1-D arrays."""

    columns: dict[str, np.ndarray]
    """Column name → (n_rows,) array. Lengths in m."""

    def to_dict(self) -> dict[str, np.ndarray]:
        """The columns."""
        return dict(self.columns)

    def group_stats(self, by: Sequence[str], value: str) -> list[dict[str, Any]]:
        """Mean and sample standard deviation of ``value`` grouped by the columns ``by``."""
        keys = list(zip(*(self.columns[b] for b in by), strict=True))
        out = []
        for key in sorted(set(keys), key=lambda k: tuple(str(v) for v in k)):
            sel = np.array([k == key for k in keys])
            v = np.asarray(self.columns[value][sel], dtype=float)
            v = v[np.isfinite(v)]
            out.append(
                {
                    **dict(zip(by, key, strict=True)),
                    f"{value}_mean": float(v.mean()) if v.size else float("nan"),
                    f"{value}_sd": float(v.std(ddof=1)) if v.size > 1 else float("nan"),
                    "n": int(v.size),
                }
            )
        return out


def linear_fit(x: Iterable[float], y: Iterable[float]) -> dict[str, float]:
    """Least-squares line y = slope·x + intercept with Pearson r (as in the paper's Table 3)."""
    x = np.asarray(list(x), dtype=float)
    y = np.asarray(list(y), dtype=float)
    slope, intercept = np.polyfit(x, y, 1)
    r = float(np.corrcoef(x, y)[0, 1])
    return {"slope": float(slope), "intercept": float(intercept), "r": r}


def sweep(
    D_values: Sequence[float],
    delta_values: Sequence[float],
    seeds: Sequence[int],
    *,
    Wr: float = 100e-6,
    L: float = 1e-3,
    n: int = 1024,
    n_increments: int = 200,
    max_depth_fraction: float = 0.1,
    min_pixels: Sequence[int] = (DEFAULT_MIN_PIXELS,),
    material: Material | None = None,
    csv_path: str | Path | None = None,
    progress: bool = True,
    device: wp.DeviceLike = None,
    **wm_kwargs: Any,
) -> SweepTable:
    """Run truncation analyses over D × δ × seeds.

    Parameters
    ----------
    D_values : sequence of float
        Input fractal dimensions D_in (dimensionless).
    delta_values : sequence of float
        Relative roughness δ = R_t/W_r (dimensionless); R_t = δ·W_r (m).
    seeds : sequence of int
        Phase seeds; one surface per seed.
    Wr, L : float
        Roll-off wavelength and side length (m).
    n : int
        Pixels per side.
    n_increments, max_depth_fraction
        Truncation depths ω_k = k·ω_max/n, ω_max = max_depth_fraction·R_t.
    min_pixels : sequence of int
        Fit ranges to evaluate (one row each); 1 = every increment with non-zero load.
    csv_path : path, optional
        Append each row to this CSV as soon as it is computed.
    progress : bool
        Show a tqdm progress bar.
    **wm_kwargs
        Passed to :func:`warptrunc.wm.wm_surface` (M, gamma, Wc, cutoff).
    """
    from tqdm.auto import tqdm

    cases = list(itertools.product(D_values, delta_values, seeds))
    rows: list[dict[str, Any]] = []
    writer = fh = None
    if csv_path is not None:
        csv_path = Path(csv_path)
        csv_path.parent.mkdir(parents=True, exist_ok=True)
        fh = csv_path.open("w", newline="")
    try:
        for D, delta, seed in tqdm(cases, disable=not progress, desc="sweep", unit="surface"):
            s = wm_surface(D, Wr, L=L, n=n, Rt=delta * Wr, seed=seed, device=device, **wm_kwargs)
            sc = stiffness_curve(
                truncate(s, n_increments, max_depth_fraction=max_depth_fraction, device=device),
                material,
            )
            for mp in min_pixels:
                row: dict[str, Any] = {"D_in": D, "delta": delta, "Rt_m": delta * Wr, "seed": seed}
                row.update(n=n, L_m=L, Wr_m=Wr, min_pixels=mp)
                row["final_contact_pixels"] = int(sc.n_contact_pixels[-1])
                try:
                    f = fit_power_law(sc, min_pixels=mp)
                    row.update(alpha=f.alpha, beta=f.beta, r2=f.r2, n_points=f.n_points)
                except ValueError:  # too few increments in this range: recorded, not dropped
                    row.update(alpha=np.nan, beta=np.nan, r2=np.nan, n_points=0)
                rows.append(row)
                if fh is not None:
                    if writer is None:
                        writer = csv.DictWriter(fh, fieldnames=list(row))
                        writer.writeheader()
                    writer.writerow(row)
                    fh.flush()
    finally:
        if fh is not None:
            fh.close()
    cols = {k: np.array([r[k] for r in rows]) for k in (rows[0] if rows else {})}
    return SweepTable(cols)
