# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The WM maps an indentation generates: their side and their realisations (:class:`IndentMaps`,
the parameters of ``warptrunc indent``'s generated surfaces). Loads no Warp."""

from __future__ import annotations

from dataclasses import dataclass

from ..params import Parameters, check_fields, param
from ..wm_params import WMSpec

__all__ = ["MAP_SIDE", "IndentMaps"]

MAP_SIDE = 1e-3
"""Side of a generated indentation map (m): the paper's simulated maps (1 mm; Table 1's 10240²
at 97.7 nm), which hold the default two placements of the 502.6 µm punch apart (three overlap
there: ``map_side`` 3e-3, the paper's island maps of § 4.3, holds them)."""


@dataclass(frozen=True)
class IndentMaps(Parameters):
    """The WM surfaces indented: one map side for all, and the phase seeds of the realisations.

    Raises
    ------
    ValueError
        A field out of its range (the message names it, its value and the range).

    Examples
    --------
    >>> from warptrunc.presets import TABLE1
    >>> [s.n for s in IndentMaps().specs(TABLE1["GB300s"])]  # 1 mm at the preset's 97.7 nm
    [10240]
    """

    map_side: float | None = param(
        MAP_SIDE,
        "side of a generated map, at the pixel of its preset or of the defaults unless "
        "--n is given (1 mm: the paper's simulated maps, which hold two placements of the "
        "502.6 µm punch apart; 3e-3, its island maps, hold three); none = the surface's own --L",
        unit="m",
        gt=0.0,
        optional=True,
        sweep=False,
    )
    seeds: tuple[int, ...] | None = param(
        None,
        "WM surface realisations: the phase seeds of the surfaces indented (the same "
        "punches and placements on each; the fits' intervals resample their indents); none = "
        "the one surface of --seed",
        kind="seeds",
        optional=True,
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self)

    def specs(self, spec: WMSpec, *, keep_n: bool = False) -> list[WMSpec]:
        """The WM surfaces of ``spec`` on these maps, one per realisation.

        Parameters
        ----------
        spec : WMSpec
            The surface (a preset, or the generation parameters).
        keep_n : bool
            Keep ``spec.n`` on the map of side ``map_side`` (else the pixel of ``spec`` is
            kept and ``n`` scaled with the side).

        Returns
        -------
        list of WMSpec
            One per seed of ``seeds`` (``spec.seed`` alone when None), each of side
            ``map_side`` (``spec.L`` when None). E.g. the preset GB300s: 1 mm over 10240
            pixels (its 97.7 nm); ``WMSpec()``: 1 mm over 1024 (its 0.977 µm).
        """
        side = self.map_side
        if side is not None:
            lx, ly = spec.L if isinstance(spec.L, tuple) else (spec.L, spec.L)
            nx, ny = spec.n if isinstance(spec.n, tuple) else (spec.n, spec.n)
            if not keep_n:  # the pixel of the preset or the defaults, on a larger map
                nx, ny = round(nx * side / lx), round(ny * side / ly)
            spec = spec.replace(L=side, n=(nx, ny) if nx != ny else nx)
        seeds = (spec.seed,) if self.seeds is None else self.seeds
        return [spec.replace(seed=k) for k in seeds]
