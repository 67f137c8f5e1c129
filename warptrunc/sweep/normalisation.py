# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Reading stores written before the one normalisation with their meaning.

Since the one normalisation (changelog: "one E_c/E"), a sweep's ``beta`` and its curves'
``Ec_over_E`` are those of E_c/E with E the Young's modulus of the rough body (the paper's
Figs. 6 and 9), and the contact-modulus forms are stored beside them as
``beta_contact_modulus`` and ``Ec_over_Estar``. A store written before holds E_c/E* under the
first two names and lacks the last two: that absence is the version key, row by row (a store
resumed across the change holds both kinds). :func:`upgrade_rows`, :func:`upgrade_cases` and
:func:`upgrade_curves` convert such data on reading, with the material of each case
(``E_Pa``, ``nu``, ``E_flat_Pa``, ``nu_flat``): E_c/E = (E*/E)·E_c/E*, β = β*·E*/E.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..material import Material

__all__ = ["NORMALISATION", "upgrade_cases", "upgrade_curves", "upgrade_rows", "young_factor"]

NORMALISATION = "E_c/E"
"""The ``normalisation`` key of ``sweep.json``: β and ``Ec_over_E`` are those of E_c/E with E the
Young's modulus (stores without the key may hold either kind of row; see the module)."""


def young_factor(row: dict[str, Any]) -> float:
    """E*/E of a case row (dimensionless): from E_c/E* to E_c/E.

    Parameters
    ----------
    row : dict
        A case row with ``E_Pa`` (Pa), ``nu``, ``E_flat_Pa`` (Pa; None or inf for a rigid flat)
        and ``nu_flat``.

    Returns
    -------
    float
        The contact modulus over the Young's modulus of the rough body.
    """
    e_i = row.get("E_flat_Pa")
    e_i = math.inf if e_i is None or (isinstance(e_i, float) and math.isnan(e_i)) else e_i
    m = Material(
        E=float(row["E_Pa"]),
        nu=float(row["nu"]),
        E_i=float(e_i),
        nu_i=float(row.get("nu_flat") or 0.0),
    )
    return m.contact_modulus / m.E


def upgrade_rows(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Case rows with ``beta`` of E_c/E and ``beta_contact_modulus`` of E_c/E*.

    Parameters
    ----------
    rows : list of dict
        Fit-range rows of one or more cases, of either kind.

    Returns
    -------
    list of dict
        The same rows (new dicts where converted): a row without ``beta_contact_modulus`` was
        written before the one normalisation; its ``beta`` moves to ``beta_contact_modulus``
        and ``beta`` becomes β·E*/E.
    """
    out = []
    for r in rows:
        if "beta_contact_modulus" not in r and "beta" in r:
            b = r["beta"]
            new = None if b is None else float(b) * young_factor(r)
            r = {**r, "beta": new, "beta_contact_modulus": b}
        out.append(r)
    return out


def upgrade_cases(df):
    """A cases table (``cases.parquet``) with the columns of the one normalisation.

    Parameters
    ----------
    df : pandas.DataFrame
        The table as read.

    Returns
    -------
    pandas.DataFrame
        ``df`` itself when it has ``beta_contact_modulus``; else a copy with that column (the
        old ``beta``) right after ``beta``, and ``beta`` of E_c/E.
    """
    if "beta_contact_modulus" in df.columns or "beta" not in df.columns:
        return df
    factor = np.array([young_factor(r) for r in df.to_dict("records")], dtype=np.float64)
    df = df.copy()
    df.insert(df.columns.get_loc("beta") + 1, "beta_contact_modulus", df["beta"].to_numpy())
    df["beta"] = df["beta"].to_numpy() * factor
    return df


def upgrade_curves(df, rows: list[list[dict[str, Any]]] | None):
    """Curve rows of a part with ``Ec_over_E`` of E_c/E and ``Ec_over_Estar`` beside it.

    Parameters
    ----------
    df : pandas.DataFrame
        ``case_id`` and the curve columns of one part, as read.
    rows : list of list of dict, or None
        The part's case rows (:func:`~warptrunc.sweep.curves.part_rows`), for each case's
        material.

    Returns
    -------
    pandas.DataFrame
        ``df`` itself when it has ``Ec_over_Estar``; else with ``Ec_over_Estar`` (the old
        ``Ec_over_E``) appended and ``Ec_over_E`` multiplied by each case's E*/E.
    """
    if "Ec_over_Estar" in df.columns or "Ec_over_E" not in df.columns:
        return df
    by_case = {rs[0]["case_id"]: young_factor(rs[0]) for rs in rows or []}
    factor = df["case_id"].map(by_case).to_numpy(dtype=np.float64)
    df = df.copy()
    df["Ec_over_Estar"] = df["Ec_over_E"].to_numpy()
    df["Ec_over_E"] = df["Ec_over_Estar"].to_numpy() * factor
    return df
