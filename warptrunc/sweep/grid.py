# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The sweep grid (D × δ × seeds and extra axes) and case identity.

The options shared by every case, and which parameters may be axes, are
:mod:`warptrunc.sweep.options`.

A case is one surface: (D_in, δ, seed) with the options. Its id is a hash of exactly these
values, so a store can tell finished cases from missing ones whatever order they ran in.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .._support.docs import fill_doc
from .._support.messages import show
from .._support.validate import MAX_SEEDS, check_int, check_range
from ..params import check_value, param_info
from ..wm_params import WMSpec
from .options import AXIS_SPECS, SweepOptions, axis_names

__all__ = [
    "Case",
    "SweepGrid",
    "parse_seeds",
]

GRID_DOCS = {"{returns_grid}": "Returns\n-------\nSweepGrid\n    The grid.\n\nRaises\n------\nValueError"}
"""The end of every grid constructor's docstring, written once (:func:`fill_doc`)."""

FORMAT = "warptrunc-sweep/1"
"""Format tag of the case ids (part of every id; unchanged by the store layout of format 2)."""

STORE_FORMAT = "warptrunc-sweep/2"
"""Layout tag in ``sweep.json``: ``curves/part-*.parquet`` (one part per shard of cases).
``FORMAT`` in a ``sweep.json`` marks the layout before it (one curve file per case), which
:func:`warptrunc.sweep.migration.migrate` converts."""


def parse_seeds(spec: str | int | Iterable[int | str]) -> tuple[int, ...]:
    """Seeds from ``"0-4"``, ``"0,2,7"``, ``"0-2,9"``, an int or a list of those.

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
        empty, a seed is outside [0, 2³² − 1], seeds repeat, or there are more than
        :data:`~warptrunc._support.validate.MAX_SEEDS` (10⁶) of them.

    Examples
    --------
    >>> parse_seeds("0-2,9")
    (0, 1, 2, 9)
    """
    if isinstance(spec, bool):
        raise ValueError(f"seeds must be integers or ranges like '0-4', got {show(spec)}")
    if isinstance(spec, int):
        items: list = [spec]
    elif isinstance(spec, str):
        items = [s for s in spec.replace(" ", "").split(",") if s]
    else:
        items = list(spec)
    out: list[int] = []
    for it in items:
        m = re.fullmatch(r"(\d+)-(\d+)", it) if isinstance(it, str) else None
        if m:
            lo, hi = int(m[1]), int(m[2])
            if hi < lo:
                raise ValueError(f"seed range must have lo ≤ hi, got {show(it)}")
            if len(out) + (hi - lo + 1) > MAX_SEEDS:  # refused before building the list
                raise ValueError(
                    f"seeds {show(it)} name {hi - lo + 1 + len(out)} seeds, more than the "
                    f"{MAX_SEEDS} one sweep takes; split the grid into several sweeps"
                )
            out.extend(range(lo, hi + 1))
            continue
        try:
            v = int(it) if isinstance(it, str) else it
        except ValueError:
            raise ValueError(f"seeds must be integers or ranges like '0-4', got {show(it)}") from None
        out.append(v)
        if len(out) > MAX_SEEDS:
            raise ValueError(f"seeds name more than the {MAX_SEEDS} one sweep takes")
    for s in out:
        check_int("seed", s, 0, 2**32 - 1)
    if not out:
        raise ValueError(f"seeds must name at least one seed, got {show(spec)}")
    if len(set(out)) != len(out):
        raise ValueError(f"seeds must not repeat, got {show(spec)}")
    return tuple(out)


def _floats(name: str, values: Any, lo: float, hi: float | None) -> tuple[float, ...]:
    return _values(name, values, lambda v: check_range(name, v, lo, hi))


def _values(name: str, values: Any, check) -> tuple:
    if isinstance(values, (int, float, str)):
        values = [values]
    out = tuple(check(v) for v in values)
    if not out:
        raise ValueError(f"{name} must hold at least one value, got {values!r}")
    if len(set(out)) != len(out):
        raise ValueError(f"{name} values must not repeat, got {values!r}")
    return out


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
    """The cases of a sweep: every (D_in, δ, seed) combination.

    Build it from values, from the CLI's ``--D ... --delta ... --seeds 0-4`` with
    :meth:`from_values`, or from a TOML file with :meth:`from_toml`::

        D = [2.1, 2.3, 2.5]      # input fractal dimensions (dimensionless)
        delta = [0.005, 0.01]    # δ = R_t/W_r (dimensionless)
        seeds = "0-4"            # or [0, 1, 2, 3, 4]

        [axes]                   # optional: more axes, outermost (slowest) first
        M = [8, 10]              # any sweepable field of WMSpec or Material (SI units)

    The values are checked against the declarations of the fields
    (:func:`warptrunc.params.check_value`): ``D`` against :class:`~warptrunc.WMSpec`'s, an extra axis against that of
    the parameter class declaring it (``specs``). A grid without extra axes has the case ids
    it always had; a case of a grid with extra axes has the id of the same case run with
    those values as options.
    """

    D: tuple[float, ...]
    """Input fractal dimensions D_in, each in (2, 3) (dimensionless)."""
    delta: tuple[float, ...]
    """Relative roughness values δ = R_t/W_r > 0 (dimensionless)."""
    seeds: tuple[int, ...]
    """Phase seeds."""
    axes: tuple[tuple[str, tuple], ...] = ()
    """More axes, ``((name, values), ...)`` (a dict is accepted): sweepable fields of
    ``specs`` other than D and R_t, outermost first."""
    specs: tuple[type, ...] = field(default=AXIS_SPECS, repr=False, compare=False)
    """Parameter classes declaring the axes (default :data:`AXIS_SPECS`)."""

    def __post_init__(self) -> None:
        s = object.__setattr__
        specs = tuple(self.specs)
        s(self, "specs", specs)
        home = next((c for c in specs if "D" in param_info(c)), WMSpec)
        s(self, "D", _values("D", self.D, lambda v: check_value(home, "D", v)))
        s(self, "delta", _floats("delta", self.delta, 0, None))
        s(self, "seeds", parse_seeds(self.seeds))
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
            out.append((name, _values(name, values, lambda v, c=spec, k=name: check_value(c, k, v))))
        s(self, "axes", tuple(out))
        if len(self) > MAX_SEEDS:
            raise ValueError(
                f"the grid has {len(self.D)} D × {len(self.delta)} δ × {len(self.seeds)} seeds = "
                f"{len(self)} cases, more than the {MAX_SEEDS} one store takes; split it into "
                "several sweeps"
            )

    @classmethod
    @fill_doc(GRID_DOCS)
    def from_values(
        cls, D: Sequence[float] | float, delta: Sequence[float] | float, seeds: Any,
        axes: dict[str, Sequence] | None = None,
    ) -> SweepGrid:
        """From values; ``seeds`` may be ``"0-4"``, ``"0,3"``, an int or a list.

        Parameters
        ----------
        D : float or sequence of float
            Input fractal dimensions D_in in (2, 3) (dimensionless).
        delta : float or sequence of float
            Relative roughness δ = R_t/W_r > 0 (dimensionless).
        seeds : str, int or sequence
            Seeds, as for :func:`parse_seeds`.
        axes : dict of str to sequence, optional
            More axes: field name → values (see the class docstring).

        {returns_grid}
            If a value is out of range or a seed cannot be parsed.
        """
        axes = tuple((axes or {}).items())
        return cls(D=D, delta=delta, seeds=seeds, axes=axes)  # type: ignore[arg-type]

    @classmethod
    @fill_doc(GRID_DOCS)
    def from_dict(cls, d: dict[str, Any], specs: Sequence[type] = AXIS_SPECS) -> SweepGrid:
        """From {"D": [...], "delta": [...], "seeds": ..., "axes": {...}}; other keys raise ValueError.

        Parameters
        ----------
        d : dict of str to Any
            The keys ``D``, ``delta`` and ``seeds`` (as for :meth:`from_values`), and
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
        return cls(D=d["D"], delta=d["delta"], seeds=d["seeds"], axes=tuple(axes.items()),
                   specs=tuple(specs))  # fmt: skip

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
        d: dict[str, Any] = {"D": list(self.D), "delta": list(self.delta), "seeds": list(self.seeds)}
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
            opts = options.with_axes(over).to_dict()
            params = tuple(over.items())
            for D in self.D:
                for delta in self.delta:
                    for seed in self.seeds:
                        cid = case_id(D, delta, seed, opts)
                        out.append(Case(len(out), D, delta, seed, cid, params))
        return out


def case_id(D: float, delta: float, seed: int, options: dict[str, Any]) -> str:
    """16 hex digits of SHA-256 over the format tag, the case values and the options.

    Parameters
    ----------
    D : float
        Input fractal dimension D_in (dimensionless).
    delta : float
        Relative roughness δ = R_t/W_r (dimensionless).
    seed : int
        Phase seed.
    options : dict of str to Any
        :meth:`SweepOptions.to_dict` of the sweep.

    Returns
    -------
    str
        The case id.
    """
    key = {"format": FORMAT, "D": float(D), "delta": float(delta), "seed": int(seed)}
    key["options"] = options
    blob = json.dumps(key, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(blob.encode()).hexdigest()[:16]
