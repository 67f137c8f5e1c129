# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Reading a sweep store: the columns of ``cases.parquet``, :func:`load` and :func:`load_curves`.

The layout and its rules are described in :mod:`warptrunc.sweep.store`; a part holding a case
already held by an earlier part (in name order) is skipped here.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from .._support.outputs import read_json
from .curves import CURVE_COLUMNS, part_files, part_rows, read_part_curves
from .grid import STORE_FORMAT
from .normalisation import upgrade_cases

__all__ = [
    "BEM_QUANTITIES",
    "CASE_COLUMNS",
    "RUN_COLUMNS",
    "bem_long",
    "format_refusal",
    "load",
    "load_curves",
]

_ORIGIN = (
    "device",
    "device_name",
    "host",
    "finished_utc",
    "warptrunc_version",
    "git_commit",
)
"""The columns that say where, when and by which version a case ran (strings)."""

CASE_COLUMNS = (
    "case_id",
    "case_index",
    "D_in",
    "delta",
    "seed",
    "Rt_m",
    "Wr_m",
    "Lx_m",
    "Ly_m",
    "nx",
    "ny",
    "M",
    "gamma",
    "Wc_m",
    "cutoff",
    "increments",
    "max_depth_fraction",
    "max_depth_m",
    "E_Pa",
    "nu",
    "E_flat_Pa",
    "nu_flat",
    "beta_prime",
    "min_pixels",
    "min_pixels_fraction",
    "depth_window_lo_m",
    "depth_window_hi_m",
    "alpha",
    "beta",
    "beta_contact_modulus",
    "r2",
    "n_points",
    "fit_depth_min_m",
    "fit_depth_max_m",
    "final_contact_pixels",
    "final_area_fraction",
    "Rt_measured_m",
    "slope_rms",
    "curvature_rms_per_m",
    "slope_rms_spectrum",
    "D_tri",
    "D_tri_r2",
    "D_box",
    "D_box_r2",
    "D_vs",
    "D_vs_r2",
    "D_sp",
    "D_sp_r2",
    "fractal_options",
    "fractal_seconds",
    "fit_error",
    "warnings",
    "error",
    "seconds",
    *_ORIGIN,
)
"""Columns of ``cases.parquet``, in order; units in the names (SI).

``alpha`` and ``beta`` are those of E_c/E = β·[F/(E·A)]^α with E the Young's modulus (the
paper's Figs. 6 and 9), ``beta_contact_modulus`` the β of E_c/E*, E* the contact modulus (a
store written before the one normalisation is read with its meaning:
:mod:`warptrunc.sweep.normalisation`).

``E_flat_Pa`` and ``nu_flat`` are the options' ``E_i`` and ``nu_i``, in the store's spelling
(:data:`~warptrunc.sweep.grid.STORED_NAMES`). ``min_pixels_fraction`` is NaN for a
``min_pixels`` fit range and f for a ``min_pixels_fraction`` one (``min_pixels`` then holds
the count it resolved to, 0 when the case failed). ``D_<method>``, ``D_<method>_r2``, ``fractal_options`` (JSON) and
``fractal_seconds`` (s) are NaN/null unless the sweep ran with ``fractal_methods``.
``fit_error`` is set when the fit failed (α NaN) and when it is not worth reading
(:func:`warptrunc.plausibility.check_fit`: α, β, r² kept); ``warnings`` is then a JSON list of
``{code, message, details}`` (also for a measured D outside (2, 3)), else null. With
``bem_fractions`` the columns of ``bem_columns`` follow."""

RUN_COLUMNS = (
    "seconds",
    "fractal_seconds",
    "device",
    "device_name",
    "host",
    "finished_utc",
    "git_commit",
)
"""Columns that describe how and where a case ran rather than its result."""

BEM_QUANTITIES = (
    "bem_depth_m",
    "F_bem_N",
    "A_bem_m2",
    "k_bem_N_per_m",
    "F_trunc_N",
    "A_trunc_m2",
    "k_trunc_N_per_m",
    "F_ratio",
    "A_ratio",
    "k_ratio",
    "bem_converged",
    "bem_iterations",
)
"""Elastic columns per approach fraction f, named ``<quantity>_<f>`` (``F_bem_N_0.1``).

δ = f·R_t (m, measured R_t) is the approach; ``*_bem_*`` are the elastic solver's load (N), real
contact area (m²) and stiffness (N/m, Barber's punch of the contact set), ``*_trunc_*`` Eq. 2's
truncation values at the same depth, ``*_ratio`` = elastic / truncation (dimensionless);
``bem_converged`` (boolean) is False for a solve that hit its iteration limit (kept, not
dropped), ``bem_iterations`` its CG iterations. Per case: ``bem_seconds`` (s) and ``bem_error``
(the solver raised; the truncation results are kept)."""


def bem_columns(fractions) -> tuple[str, ...]:
    """The elastic columns of a sweep with these ``bem_fractions`` (empty for none)."""
    out = tuple(f"{q}_{f:g}" for f in fractions for q in BEM_QUANTITIES)
    return (*out, "bem_seconds", "bem_error") if out else ()


_INT = ("case_index", "seed", "nx", "ny", "M", "increments", "min_pixels")
_NULLABLE_INT = ("n_points", "final_contact_pixels")
_STR = (
    "case_id",
    "cutoff",
    "fractal_options",
    "fit_error",
    "warnings",
    "error",
    *_ORIGIN,
    "bem_error",
)
MANIFEST_KEY = b"warptrunc.parts"


def require_extra() -> None:
    """Import pandas and pyarrow, or raise ImportError naming what to install."""
    try:
        import pandas  # noqa: F401
        import pyarrow  # noqa: F401
    except ImportError as exc:
        raise ImportError(
            f"sweeps need pandas and pyarrow, dependencies of warptrunc that this environment "
            f"lacks ({exc.name} is missing): pip install pandas pyarrow"
        ) from None


RENAMED_COLUMNS = {"rt_measured_m": "Rt_measured_m"}
"""Columns of stores written before R_t was spelled ``Rt`` everywhere, read under the new name."""


def rows_frame(rows: list[dict[str, Any]], columns: tuple[str, ...] | None = None):
    """The rows as a DataFrame with the columns and dtypes of ``cases.parquet``.

    ``columns`` defaults to CASE_COLUMNS and the elastic columns the rows hold.
    """
    import pandas as pd

    if rows and any(k in rows[0] for k in RENAMED_COLUMNS):
        rows = [{RENAMED_COLUMNS.get(k, k): v for k, v in r.items()} for r in rows]
    if columns is None:
        extra = [k for k in (rows[0] if rows else {}) if k not in CASE_COLUMNS]
        columns = (*CASE_COLUMNS, *extra)
    data = {}
    for c in columns:
        values = [r.get(c) for r in rows]
        if c in _INT:
            data[c] = pd.array(values, dtype="int64")
        elif c in _NULLABLE_INT or c.startswith("bem_iterations_"):
            data[c] = pd.array(values, dtype="Int64")
        elif c in _STR:
            data[c] = pd.array(values, dtype="string")
        elif c.startswith("bem_converged_"):
            data[c] = pd.array(values, dtype="boolean")
        else:
            data[c] = np.array([np.nan if v is None else v for v in values], dtype=np.float64)
    return pd.DataFrame(data, columns=list(columns))


def sort_cases(df):
    if "min_pixels_fraction" not in df:  # a store written before that column existed
        df = df.assign(min_pixels_fraction=np.nan)
    keys = ["case_index", "min_pixels_fraction", "min_pixels"]
    return df.sort_values(keys, kind="stable", na_position="first").reset_index(drop=True)


def manifest_parts(path: Path) -> set[str] | None:
    import pyarrow.parquet as pq

    try:
        meta = pq.read_schema(path / "cases.parquet").metadata or {}
    except (OSError, ValueError):
        return None
    return set(json.loads(meta[MANIFEST_KEY])) if MANIFEST_KEY in meta else None


def _open_spec(path: Path) -> dict[str, Any]:
    meta = path / "sweep.json"
    if not meta.exists():
        raise FileNotFoundError(f"{path} is not a sweep store (no sweep.json)")
    spec = read_json(meta)
    if spec.get("format") != STORE_FORMAT:
        raise ValueError(format_refusal(path, spec.get("format")))
    return spec


def format_refusal(path: Path, found: Any) -> str:
    """Why the store at ``path``, whose ``sweep.json`` has the format tag ``found``, is not read.

    Parameters
    ----------
    path : Path
        The store folder.
    found : object
        The format tag its ``sweep.json`` holds.

    Returns
    -------
    str
        The message: what the store is and what to do (a new ``--out`` or ``--overwrite``).
    """
    if found == "warptrunc-sweep/1":
        return (
            f"{path} is a sweep store of the layout before {STORE_FORMAT} (one curve file per "
            "case), written only by development versions before 0.1; warptrunc no longer reads "
            "it: run the sweep again into a new --out (or with --overwrite)"
        )
    return f"{path} is a store of format {found!r}, not {STORE_FORMAT!r}; use --overwrite or a new --out"


def _unique_parts(path: Path) -> list[tuple[Path, list[list[dict[str, Any]]]]]:
    """(part, its cases' rows) in name order, each case kept in its first part only."""
    seen: set[str] = set()
    out = []
    for f in part_files(path / "curves"):
        held = part_rows(f)
        if held is None:
            continue
        held = [rs for rs in held if rs[0]["case_id"] not in seen]
        seen.update(rs[0]["case_id"] for rs in held)
        if held:
            out.append((f, held))
    return out


def load(path: str | Path):
    """The cases table of the store at ``path``, in grid order.

    Parameters
    ----------
    path : path
        The store folder.

    Returns
    -------
    pandas.DataFrame
        ``cases.parquet`` when it holds every part present; otherwise (a sweep killed before
        its last flush, or still running) the table rebuilt from the parts, so nothing that
        finished is missing and no case appears twice.

    Raises
    ------
    FileNotFoundError
        If ``path`` holds no ``sweep.json``.
    ValueError
        If the store has another format tag than ``warptrunc-sweep/2`` (the layout before it
        included: :func:`format_refusal` says why).
    """
    require_extra()
    import pyarrow.parquet as pq

    path = Path(path)
    spec = _open_spec(path)
    columns = (*CASE_COLUMNS, *bem_columns(spec.get("options", {}).get("bem_fractions", ())))
    parts = _unique_parts(path)
    f = path / "cases.parquet"
    if f.exists() and manifest_parts(path) == {p.name for p, _ in parts}:
        df = pq.read_table(f).to_pandas().rename(columns=RENAMED_COLUMNS)
        return sort_cases(upgrade_cases(df))
    rows = [r for _, held in parts for rs in held for r in rs]
    return sort_cases(rows_frame(rows, columns))


def load_curves(path: str | Path, case_id: str | None = None):
    """Curves of the store at ``path``: one case's, or all (long format with ``case_id``).

    Parameters
    ----------
    path : path
        The store folder.
    case_id : str, optional
        One case (ValueError if no part holds its curve).

    Returns
    -------
    pandas.DataFrame
        ``case_id`` and CURVE_COLUMNS (SI units in the names), rows in part order (grid
        order), each case from its first part only. Failed cases have no rows.
    """
    require_extra()
    import pandas as pd

    path = Path(path)
    _open_spec(path)
    frames = []
    for f, held in _unique_parts(path):
        ids = [rs[0]["case_id"] for rs in held]
        if case_id is not None:
            if case_id not in ids:
                continue
            ids = [case_id]
        frames.append(read_part_curves(f, ids))
    if case_id is not None and not frames:
        raise ValueError(f"case_id {case_id!r} has no curve in {path}")
    if not frames:
        return pd.DataFrame(
            {
                "case_id": pd.Series(dtype=object),
                **{k: pd.Series(dtype=float) for k in CURVE_COLUMNS},
            }
        )
    return pd.concat(frames, ignore_index=True)


def bem_long(df):
    """The elastic columns of a cases table in long format: one row per case × fit range × f.

    Parameters
    ----------
    df : pandas.DataFrame
        A cases table (:func:`load`) of a sweep with ``bem_fractions``.

    Returns
    -------
    pandas.DataFrame
        ``case_id``, ``min_pixels``, ``min_pixels_fraction``, ``D_in``, ``delta``, ``seed``,
        ``alpha``, ``bem_fraction`` (f, dimensionless) and one column per quantity of
        :data:`BEM_QUANTITIES` without the suffix (``F_bem_N``, ``k_ratio``, ...).
    """
    import pandas as pd

    keys = ["case_id", "min_pixels", "min_pixels_fraction", "D_in", "delta", "seed", "alpha"]
    fracs = sorted(
        {c[len("F_bem_N_") :] for c in df.columns if c.startswith("F_bem_N_")}, key=float
    )
    parts = []
    for f in fracs:
        part = df[keys].copy()
        part["bem_fraction"] = float(f)
        for q in BEM_QUANTITIES:
            part[q] = df[f"{q}_{f}"]
        parts.append(part)
    if not parts:
        return pd.DataFrame(columns=[*keys, "bem_fraction", *BEM_QUANTITIES])
    return pd.concat(parts, ignore_index=True)
