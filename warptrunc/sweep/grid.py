# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The sweep grid (D × δ × seeds and extra axes) and case identity.

The options shared by every case, and which parameters may be axes, are
:mod:`warptrunc.sweep.options`.

A case is one surface: (D_in, δ, seed) with the options. Its id is a hash of exactly these
values, so a store can tell finished cases from missing ones whatever order they ran in. The
options enter the id, and ``sweep.json``, in the store's own spelling
(:func:`stored_options`), fixed with the store's format so that a store resumes whatever the
options are called in the API.
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .._support.docs import fill_doc
from .._support.validate import MAX_SEEDS
from ..params import check_fields, check_value, param, param_info, param_like
from ..wm_params import WMSpec
from .options import AXIS_SPECS, SweepOptions, axis_names

__all__ = [
    "CASE_ID_FORMAT",
    "OMITTED_WHEN_OFF",
    "STORED_NAMES",
    "STORE_FORMAT",
    "Case",
    "SweepGrid",
    "case_id",
    "parse_seeds",
    "stored_options",
]

GRID_DOCS = {
    "{returns_grid}": "Returns\n-------\nSweepGrid\n    The grid.\n\nRaises\n------\nValueError"
}
"""The end of every grid constructor's docstring, written once (:func:`fill_doc`)."""

CASE_ID_FORMAT = "warptrunc-sweep/1"
"""Format tag hashed into every case id (:func:`case_id`); fixed, so that the ids of every
store stay valid."""

STORE_FORMAT = "warptrunc-sweep/2"
"""Layout tag in ``sweep.json``: ``curves/part-*.parquet`` (one part per shard of cases). A
``sweep.json`` tagged ``warptrunc-sweep/1`` is a store of the layout before it (one curve file
per case), written only by development versions before 0.1 and no longer read."""

STORED_NAMES = {"E_i": "E_flat", "nu_i": "nu_flat"}
"""Fields of :class:`~warptrunc.sweep.options.SweepOptions` that the store spells otherwise:
field → name in ``sweep.json`` and in every case id (the store's format)."""

OMITTED_WHEN_OFF = ("min_pixels_fraction", "fractal_methods", "bem_fractions")
"""Fields left out of the stored options (and so of the case ids) when they are None (off): the
ids of a sweep without them are those of a store made before they existed."""


def stored_options(options: SweepOptions) -> dict[str, Any]:
    """The options in the store's format: the ``options`` of ``sweep.json``, hashed into every
    case id.

    Parameters
    ----------
    options : SweepOptions
        The options.

    Returns
    -------
    dict of str to Any
        One entry per field, in field order, tuples as lists; ``E_i``, ``nu_i`` under the names
        of :data:`STORED_NAMES` (``E_flat``, ``nu_flat``); the fields of
        :data:`OMITTED_WHEN_OFF` only when set.
    """
    out = {}
    for f in dataclasses.fields(options):
        v = getattr(options, f.name)
        if f.name in OMITTED_WHEN_OFF and v is None:
            continue
        out[STORED_NAMES.get(f.name, f.name)] = list(v) if isinstance(v, tuple) else v
    return out


def parse_seeds(spec: Any) -> tuple[int, ...]:
    """Seeds from ``"0-4"``, ``"0,2,7"``, ``"0-2,9"``, an int or a list of those: the check of
    ``SweepGrid.seeds``.

    Ranges are inclusive: ``"0-4"`` is 0, 1, 2, 3, 4.

    Parameters
    ----------
    spec : str, int or iterable of int or str
        Comma-separated seeds and ``lo-hi`` ranges, one seed, or a list of either.

    Returns
    -------
    tuple of int
        The seeds in the order given (not sorted).

    Raises
    ------
    ValueError
        If an item is not an integer or a range, a range has hi < lo, ``spec`` is a bool or
        empty, a seed is outside [0, 2³² − 1], seeds repeat, or there are more than 10⁶ of
        them.

    Examples
    --------
    >>> parse_seeds("0-2,9")
    (0, 1, 2, 9)
    """
    return param_info(SweepGrid)["seeds"].check("seeds", spec)


def _values(name: str, values: Any, check) -> tuple:
    if isinstance(values, (int, float, str)):
        values = [values]
    out = tuple(check(v) for v in values)
    if not out:
        raise ValueError(f"{name} must hold at least one value, got {values!r}")
    if len(set(out)) != len(out):
        raise ValueError(f"{name} values must not repeat, got {values!r}")
    return out


def _required(f: dataclasses.Field) -> Any:
    """The field ``f`` (of :func:`param` or :func:`param_like`) without a default."""
    return dataclasses.field(metadata=f.metadata)


@dataclass(frozen=True)
class Case:
    """One surface of the sweep."""

    index: int
    """Position in the grid's order (D slowest, then δ, then seed)."""
    D: float
    """Input fractal dimension D_in (dimensionless)."""
    delta: float
    """Relative roughness δ = R_t/W_r (dimensionless)."""
    seed: int
    """Phase seed."""
    case_id: str
    """Stable hash of (D, δ, seed) and the options (those of the case: its extra axis values
    in place of the sweep's)."""
    params: tuple[tuple[str, Any], ...] = ()
    """The case's values of the grid's extra axes, ``((name, value), ...)`` (empty for a
    D × δ × seeds grid)."""


@dataclass(frozen=True)
class SweepGrid:
    """The cases of a sweep: every (D_in, δ, seed) combination, and optional extra axes.

    Build it from values (``SweepGrid([2.1, 2.5], [0.01], "0-4")``, the CLI's
    ``--D ... --delta ... --seeds 0-4``) or from a TOML file with :meth:`from_toml`::

        D = [2.1, 2.3, 2.5]      # input fractal dimensions (dimensionless)
        delta = [0.005, 0.01]    # δ = R_t/W_r (dimensionless)
        seeds = "0-4"            # or [0, 1, 2, 3, 4]

        [axes]                   # optional: more axes, outermost (slowest) first
        M = [8, 10]              # any sweepable field of WMSpec or Material (SI units)

    ``D``, ``delta`` and ``seeds`` are declared fields (:func:`warptrunc.params.param`; ``D`` as
    :class:`~warptrunc.WMSpec` declares it): a single value is a 1-tuple, a value that
    repeats is refused. An extra axis is checked against the declaration of the parameter class
    declaring it (``specs``; :func:`warptrunc.params.check_value`). A grid without extra axes
    has the case ids it always had; a case of a grid with extra axes has the id of the same
    case run with those values as options.

    Raises
    ------
    ValueError
        A value out of its range or repeated, an axis that is no sweepable parameter, or more
        than 10⁶ cases.
    """

    D: tuple[float, ...] = _required(
        param_like(WMSpec, "D", many=True, doc="input fractal dimensions D_in")
    )
    delta: tuple[float, ...] = _required(
        param(None, "relative roughness values δ = R_t/W_r; R_t = δ·W_r", gt=0.0, many=True)
    )
    seeds: tuple[int, ...] = param((0,), "phase seeds: 0-4, 0,3,7 or 0-2,9", kind="seeds")
    axes: tuple[tuple[str, tuple], ...] = ()
    """More axes, ``((name, values), ...)`` (a dict is accepted): sweepable fields of
    ``specs`` other than D and R_t, outermost first."""
    specs: tuple[type, ...] = field(default=AXIS_SPECS, repr=False, compare=False)
    """Parameter classes declaring the axes (default :data:`AXIS_SPECS`)."""

    def __post_init__(self) -> None:
        s = object.__setattr__
        check_fields(self)
        for name in ("D", "delta"):
            v = getattr(self, name)
            if len(set(v)) != len(v):
                raise ValueError(f"{name} values must not repeat, got {v!r}")
        specs = tuple(self.specs)
        s(self, "specs", specs)
        axes = self.axes.items() if isinstance(self.axes, dict) else self.axes
        allowed = axis_names(specs)
        out = []
        for name, values in axes:
            if name not in allowed:
                raise ValueError(
                    f"a sweep axis must be a sweepable parameter of "
                    f"{', '.join(c.__name__ for c in specs)} other than D and Rt "
                    f"({', '.join(allowed)}), got {name!r}"
                )
            if name in (a for a, _ in out):
                raise ValueError(f"axis {name!r} is given twice")
            spec = next(c for c in specs if name in param_info(c))
            check = lambda v, c=spec, k=name: check_value(c, k, v)  # noqa: E731
            out.append((name, _values(name, values, check)))
        s(self, "axes", tuple(out))
        if len(self) > MAX_SEEDS:
            raise ValueError(
                f"the grid has {len(self.D)} D × {len(self.delta)} δ × {len(self.seeds)} seeds = "
                f"{len(self)} cases, more than the {MAX_SEEDS} one store takes; split it into "
                "several sweeps"
            )

    @classmethod
    @fill_doc(GRID_DOCS)
    def from_dict(cls, d: dict[str, Any], specs: Sequence[type] = AXIS_SPECS) -> SweepGrid:
        """From {"D": [...], "delta": [...], "seeds": ..., "axes": {...}}; other keys raise ValueError.

        Parameters
        ----------
        d : dict of str to Any
            The keys ``D``, ``delta`` and ``seeds`` (as the fields take them), and
            optionally ``axes`` (field name → values).
        specs : sequence of type
            Parameter classes declaring the axes.

        {returns_grid}
            If a key is unknown or missing, or a value is out of range.
        """
        bad = sorted(set(d) - {"D", "delta", "seeds", "axes"})
        missing = sorted({"D", "delta", "seeds"} - set(d))
        if bad or missing:
            raise ValueError(
                f"a sweep grid has the keys D, delta, seeds (and optionally a table axes); "
                f"unknown {bad}, missing {missing}"
            )
        axes = d.get("axes", {})
        if not isinstance(axes, dict):
            raise ValueError(f"axes must be a table of field = [values], got {axes!r}")
        return cls(
            D=d["D"],
            delta=d["delta"],
            seeds=d["seeds"],
            axes=tuple(axes.items()),
            specs=tuple(specs),
        )

    @classmethod
    @fill_doc(GRID_DOCS)
    def from_toml(cls, path: str | Path) -> SweepGrid:
        """From a TOML file with the keys D, delta and seeds.

        Parameters
        ----------
        path : str or Path
            TOML file (see the class docstring).

        {returns_grid}
            If the file is not valid TOML or its keys or values are wrong; the message starts
            with the path.
        """
        try:
            import tomllib
        except ImportError:  # Python 3.10: warptrunc's dependencies include tomli
            import tomli as tomllib

        path = Path(path)
        try:
            d = tomllib.loads(path.read_text())
        except tomllib.TOMLDecodeError as exc:
            raise ValueError(f"{path}: not valid TOML: {exc}") from None
        try:
            return cls.from_dict(d)
        except ValueError as exc:
            raise ValueError(f"{path}: {exc}") from None

    def to_dict(self) -> dict[str, Any]:
        """The grid as lists, the input of :meth:`from_dict`.

        Returns
        -------
        dict of str to list
            ``{"D": [...], "delta": [...], "seeds": [...]}``, and ``"axes": {name: [...]}``
            when the grid has extra axes (so that the ``sweep.json`` of a D × δ × seeds grid
            is what it always was).
        """
        d: dict[str, Any] = {
            "D": list(self.D),
            "delta": list(self.delta),
            "seeds": list(self.seeds),
        }
        if self.axes:
            d["axes"] = {k: list(v) for k, v in self.axes}
        return d

    def __len__(self) -> int:
        n = len(self.D) * len(self.delta) * len(self.seeds)
        for _, v in self.axes:
            n *= len(v)
        return n

    def cases(self, options: SweepOptions) -> list[Case]:
        """Every case in grid order (extra axes slowest, then D, then δ, then seed).

        Parameters
        ----------
        options : SweepOptions
            Options of the sweep; they enter each case id.

        Returns
        -------
        list of Case
            ``len(self)`` cases, ``index`` 0, 1, ...
        """
        names = [k for k, _ in self.axes]
        out: list[Case] = []
        for combo in itertools.product(*(v for _, v in self.axes)):
            over = dict(zip(names, combo, strict=True))
            stored = stored_options(options.with_axes(over))
            params = tuple(over.items())
            for D in self.D:
                for delta in self.delta:
                    for seed in self.seeds:
                        cid = _hash(D, delta, seed, stored)
                        out.append(Case(len(out), D, delta, seed, cid, params))
        return out


def case_id(D: float, delta: float, seed: int, options: SweepOptions) -> str:
    """16 hex digits of SHA-256 over the format tag, the case values and the options.

    Parameters
    ----------
    D : float
        Input fractal dimension D_in (dimensionless).
    delta : float
        Relative roughness δ = R_t/W_r (dimensionless).
    seed : int
        Phase seed.
    options : SweepOptions
        The case's options (its extra-axis values in place).

    Returns
    -------
    str
        The case id.

    Notes
    -----
    The hash is over the JSON text (keys sorted, no spaces) of ``{"format":``
    :data:`CASE_ID_FORMAT` ``, "D", "delta", "seed", "options":`` :func:`stored_options` ``}``:
    the store's format, in which ``E_i`` and ``nu_i`` are ``E_flat`` and ``nu_flat`` and the
    fields of :data:`OMITTED_WHEN_OFF` are left out when off (a rigid flat is ``Infinity``).
    """
    return _hash(D, delta, seed, stored_options(options))


def _hash(D: float, delta: float, seed: int, stored: dict[str, Any]) -> str:
    """:func:`case_id` of the stored options ``stored`` (computed once per set of options)."""
    key = {"format": CASE_ID_FORMAT, "D": float(D), "delta": float(delta), "seed": int(seed)}
    key["options"] = stored
    blob = json.dumps(key, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(blob.encode()).hexdigest()[:16]
