# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The design of a comparison study (see :mod:`warptrunc.compare`): which WM surfaces and which
approaches (:class:`StudyDesign`), or one height map at its approaches (:class:`MapStudy`).

Declared once with :func:`warptrunc.params.param`: the defaults, units and ranges make the
options of ``warptrunc compare``, their validation and the study's record. No Warp here: the
command-line parser imports this module.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..params import Parameters, check_fields, param, param_like
from ..wm_params import WMSpec

if TYPE_CHECKING:
    from ..surface import Surface

__all__ = ["APPROACH_FRACTIONS", "STUDY_D", "MapStudy", "StudyDesign"]

APPROACH_FRACTIONS = (0.02, 0.05, 0.1, 0.2, 0.3, 0.4)
"""Default approaches d/R_t of a comparison (dimensionless): from first islands to large
contact."""

STUDY_D = (2.1, 2.5, 2.9)
"""Default fractal dimensions D of the WM study (dimensionless)."""


def _check_increasing(obj: Any) -> None:
    v = obj.fractions
    if any(b <= a for a, b in itertools.pairwise(v)):
        raise ValueError(
            f"fractions must increase strictly (approaches δ/R_t), got "
            f"{' '.join(f'{x:g}' for x in v)}"
        )


@dataclass(frozen=True)
class StudyDesign(Parameters):
    """The WM surfaces of a comparison study and its approaches: D × (L/W_r at a fixed pixel
    size, plus one halved pixel size) × seeds, each at the approaches d/R_t ``fractions``.

    Every case has n = L/W_r × ``pixels_per_Wr`` pixels a side, so the pixel size
    dx = W_r/``pixels_per_Wr`` is the same in every size (size effect); at L/W_r =
    ``refine_ratio``, one of ``size_ratios``, the same surface (same phases, same cut-off
    W_c) is sampled once more with half that pixel (grid convergence: the change measures each route's discretisation
    error, not added roughness). The cut-off W_c is the Nyquist wavelength of the base grid,
    2·W_r/``pixels_per_Wr``, in every case; R_t = ``Rt_over_Wr``·W_r.

    Examples
    --------
    >>> StudyDesign(D=(2.5,), seeds="0-4").seeds
    (0, 1, 2, 3, 4)
    """

    D: tuple[float, ...] = param_like(
        WMSpec, "D", default=STUDY_D, many=True, doc="fractal dimensions D of the WM study"
    )
    size_ratios: tuple[float, ...] = param(
        (1.0, 3.0, 10.0),
        "map sizes L/W_r, at a fixed pixel size W_r/pixels_per_Wr",
        gt=0.0,
        many=True,
        sweep=False,
    )
    pixels_per_Wr: int = param(
        32,
        "pixels per roll-off wavelength W_r of the base grid (n = L/W_r × this)",
        kind="int",
        ge=2,
        cli="pixels-per-wr",
        sweep=False,
    )
    refine_ratio: float | None = param(
        10.0,
        "one of the size ratios, at which the pixel size is halved once more (grid "
        "convergence on the same surface: one more grid of that size); none = never",
        gt=0.0,
        optional=True,
        sweep=False,
    )
    seeds: tuple[int, ...] = param((0, 1, 2), "seeds of the surfaces per (D, grid)", kind="seeds")
    Wr: float = param_like(WMSpec, "Wr")
    Rt_over_Wr: float = param(
        0.01,
        "R_t/W_r, the paper's relative roughness δ; the ratios and α do not depend on it",
        gt=0.0,
        cli="rt-over-wr",
    )
    M: int = param_like(WMSpec, "M")
    gamma: float = param_like(WMSpec, "gamma")
    fractions: tuple[float, ...] = param(
        APPROACH_FRACTIONS,
        "approaches δ/R_t, strictly increasing",
        gt=0.0,
        lt=1.0,
        many=True,
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self)
        _check_increasing(self)
        r = self.refine_ratio
        if r is not None and not any(math.isclose(r, x, rel_tol=1e-9) for x in self.size_ratios):
            sizes = " ".join(f"{x:g}" for x in self.size_ratios)
            raise ValueError(
                f"refine_ratio {r:g} is not one of the size ratios ({sizes}): the pixel is "
                f"halved once more at one of the sizes the study runs; give one of them, none "
                f"(no refined grid), or add {r:g} to the size ratios"
            )


@dataclass(frozen=True)
class MapStudy:
    """A comparison study of one height map (your own, not a WM family) at its approaches.

    Examples
    --------
    >>> MapStudy(surface, fractions=(0.05, 0.1, 0.2))  # doctest: +SKIP
    """

    surface: Surface
    """The height map (m)."""
    fractions: tuple[float, ...] = param_like(StudyDesign, "fractions")
    """Approaches δ/R_t, strictly increasing, in (0, 1) (dimensionless)."""

    def __post_init__(self) -> None:
        check_fields(self)
        _check_increasing(self)
