# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Shared by the theory results: their ``to_dict`` columns (scalars repeated to the length of
the curve) and the checks of a pressure array and of a material."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np


def columns(obj: Any, names: Mapping[str, str], *, skip: Iterable[str] = ()) -> dict[str, Any]:
    """The fields of the dataclass ``obj`` as 1-D columns of one length.

    Array fields are kept as they are; scalar fields (floats, strings) are repeated to the
    length of the first array field, so ``pandas.DataFrame(obj.to_dict())`` needs no other
    code. ``names`` maps a field to its column name (a unit suffix); ``skip`` leaves fields out.
    """
    skip = set(skip)
    fields = [f.name for f in dataclasses.fields(obj) if f.name not in skip]
    arrays = [getattr(obj, k) for k in fields if isinstance(getattr(obj, k), np.ndarray)]
    n = arrays[0].shape[0] if arrays else 1
    out: dict[str, Any] = {}
    for k in fields:
        v = getattr(obj, k)
        out[names.get(k, k)] = v if isinstance(v, np.ndarray) else np.full(n, v)
    return out


def check_pressure(pressure: Any) -> np.ndarray:
    """A (n,) float64 array of nominal pressures, each finite and > 0 (Pa)."""
    p = np.atleast_1d(np.asarray(pressure, dtype=np.float64))
    if p.ndim != 1 or p.size == 0:
        raise ValueError(f"pressure must be a scalar or a 1-D array, got shape {p.shape}")
    if not np.all(np.isfinite(p) & (p > 0)):
        bad = p[~(np.isfinite(p) & (p > 0))][0]
        raise ValueError(f"every pressure must be finite and > 0 Pa, got {bad!r}")
    return p


def modulus_of(material: Any) -> float:
    """E* (Pa) of a :class:`~warptrunc.Material` (its ``contact_modulus``)."""
    e = getattr(material, "contact_modulus", None)
    if e is None:
        raise TypeError(f"material must be a warptrunc.Material, got {type(material).__name__}")
    return float(e)
