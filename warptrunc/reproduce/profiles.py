# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Profiles of ``warptrunc reproduce``: resolutions, seed counts and increments per stage.

``paper`` follows the paper (§3.3, §4.4: 10240² over 1 mm², five surfaces per case, 200
increments, ω_max = 0.1·R_t; islands of Figs. 7–8 and Table 2 on 30720² over 3 mm; Fig. 5 with
10 seeds per resolution; Table 1 calibrated on 1024² over 1 mm) except where noted in
:data:`PAPER_DEPARTURES`: Fig. 5 goes to 10240² (the paper: 32760²) and the island analysis
uses 4 seeds per surface; the elastic comparison (not in the paper) goes to 7680² (L/W_r = 30
at 256 pixels per W_r) and 5120² (L/W_r = 10, pixel size halved). The indentation stage (Fig. 6
in silico, not in the paper's simulations; :class:`~warptrunc.reproduce.indentation.design.IndentationStage`)
runs with the paper's punches and loads on 1 mm maps of 1280² (781 nm, the surfaces' content
W_c = 1.95 µm at 2.5 pixels) whose punch windows are generated again at every punch down to
the paper's 97.7 nm (``refine_max`` 8) until K has converged over two halvings; two
placements per punch, which the 502.6 µm punch's hold apart on 1 mm (``overlap = "error"``:
three overlap), traded for six realisations in the statistics. Two designs: a hardness sweep
(H of ``indentation.hardness`` from 0.2 GPa, one realisation × ``indentation.protocol.placements``
placements per punch) and statistics (``indentation.seeds`` × ``indentation.stats_placements``
indents per punch) for the models of ``indentation.stats``: H = ∞ and the one H of the sweep
whose largest threshold depth at 500 mN over every surface best matches the paper's ≈ 5 µm. ``quick`` and ``tiny`` coarsen its pixels
(512² and 256² over 1 mm), use fewer H, seeds and placements (``tiny``: the last four loads,
every cell with a contact pixel judged resolved: a smoke run). ``quick`` fits a 2-core CPU in
minutes and ``tiny`` is the CI check.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

from ..indent.protocol import PAPER_PEAK_LOADS, PAPER_PUNCH_DIAMETERS
from ..truncation.settings import TruncationSettings
from .indentation.design import IndentationStage

__all__ = ["PAPER_DEPARTURES", "PROFILES", "Profile", "get_profile"]

GROUP1_DELTA = (0.000625, 0.00125, 0.0025, 0.005, 0.01, 0.02, 0.04, 0.08, 0.16)
GROUP2_D = (2.1, 2.3, 2.5, 2.7, 2.9)


@dataclass(frozen=True)
class Profile:
    """Sizes of one reproduction run. Lengths in m."""

    name: str
    """Profile name (``"tiny"``, ``"quick"``, ``"paper"``)."""
    n: int
    """Pixels per side of the group-1/2 surfaces (over L)."""
    seeds: int
    """Surfaces per (D_in, δ) case."""
    L: float = 1e-3
    """Side of the group surfaces (m)."""
    Wr: float = 100e-6
    """Roll-off wavelength of the group surfaces (m)."""
    truncation: TruncationSettings = field(default=TruncationSettings())
    """Truncation of the group surfaces (:class:`~warptrunc.truncation.settings.TruncationSettings`:
    200 increments to ω_max = 0.1·R_t, §4.4; its ``increments``, ``max_depth_fraction``,
    ``max_depth`` and ``beta_prime`` are the sweep's)."""
    group1_delta: tuple[float, ...] = GROUP1_DELTA
    """Relative roughness values δ = R_t/W_r of group 1 (dimensionless)."""
    group2_D: tuple[float, ...] = GROUP2_D
    """Input fractal dimensions D_in of group 2 (dimensionless)."""
    fractal_on_group1: bool = False
    """Also measure the four D on group-1 surfaces (only group 2 enters Fig. 10a–e)."""
    late_fit_fraction: float = 0.05
    """Second fit range: increments with ≥ this fraction of each surface's final contact pixels
    (the first is the package default, ≥ 10 contact pixels)."""
    fig5_sizes: tuple[int, ...] = (512, 1024, 2048)
    """Pixels per side of the Fig. 5 convergence surfaces."""
    fig5_seeds: int = 3
    """Surfaces per Fig. 5 case (count)."""
    fig5_increments: tuple[int, ...] = (200, 1000)
    """Truncation increments of Fig. 5: the first at every size, the others at the largest."""
    table1_n: int = 256
    """Pixels per side of the calibration surfaces (1 µm pixels, as the paper's 1024² scans)."""
    table1_seeds: int = 1
    """Seeds per calibration surface (count)."""
    table1_methods: tuple[str, ...] = ("vs",)
    """Methods whose Table 1 value is the calibration target (Fig. 6 uses D_vs)."""
    table1_rtol: float = 0.05
    """Relative tolerance abs(D_out − D)/D of the calibration (dimensionless)."""
    islands_n: int = 1024
    """Pixels per side of the island-analysis surfaces."""
    islands_L: float = 1e-3
    """Side of the island-analysis surfaces (m)."""
    islands_seeds: int = 2
    """Island-analysis surfaces per case (count)."""
    islands_increments: int = 200
    """Truncation increments of the island analysis."""
    asperity_n: int = 1024
    """Pixels per side of the pixelated sphere of Fig. 2."""
    asperity_increments: int = 1000
    """Truncation increments of Fig. 2."""
    elastic_D: tuple[float, ...] = (2.1, 2.5, 2.9)
    """Input fractal dimensions of the ``elastic`` stage (dimensionless)."""
    elastic_size_ratios: tuple[float, ...] = (1, 3, 10, 30)
    """Map sizes L/W_r of the ``elastic`` stage, at a fixed pixel size (dimensionless)."""
    elastic_pixels_per_Wr: int = 256
    """Pixels per W_r of the ``elastic`` stage's base grid (n = L/W_r × this)."""
    elastic_refine_ratio: float | None = 10
    """L/W_r at which the ``elastic`` stage halves the pixel size once (None: never)."""
    elastic_seeds: int = 3
    """Surfaces per (D, grid) of the ``elastic`` stage (count)."""
    elastic_fractions: tuple[float, ...] = (0.02, 0.05, 0.1, 0.2, 0.3, 0.4)
    """Approaches δ/R_t of the ``elastic`` stage (dimensionless)."""
    elastic_dtype: str = "float64"
    """Precision of the elastic solver in the ``elastic`` stage."""
    indentation: IndentationStage = field(default=IndentationStage())
    """The ``indentation`` stage (:class:`~warptrunc.reproduce.indentation.design.IndentationStage`:
    its maps, hardness sweep, statistics, punch faces, resolution check, and the
    :class:`~warptrunc.indent.IndentProtocol`, solver settings and material of its pieces)."""
    extra: dict[str, Any] = field(default_factory=dict)
    """Free-form additions, recorded with the profile (no stage reads them)."""

    def to_dict(self) -> dict[str, Any]:
        """Plain dict (JSON-serialisable).

        Returns
        -------
        dict of str to Any
            One entry per field (lengths in m); ``truncation`` and ``indentation`` as the dicts
            of their own ``to_dict``.
        """
        return {
            **asdict(self),
            "truncation": self.truncation.to_dict(),
            "indentation": self.indentation.to_dict(),
        }


def _indentation(
    protocol: dict[str, Any] | None = None, solver: dict[str, Any] | None = None, **kw: Any
) -> IndentationStage:
    """The stage's parameters: ``IndentationStage()`` with ``kw`` changed, its protocol (refined
    at most once by default, ``refine_max`` 1) and solver settings with ``protocol`` and
    ``solver`` changed."""
    base = IndentationStage()
    return base.replace(
        protocol=base.protocol.replace(**(protocol or {})),
        solver=base.solver.replace(**(solver or {})),
        **kw,
    )


PROFILES = {
    "tiny": Profile(
        name="tiny",
        n=256,
        seeds=2,
        group1_delta=(0.0025, 0.01, 0.04),
        group2_D=(2.2, 2.5, 2.8),
        fig5_sizes=(64, 128),
        fig5_seeds=1,
        fig5_increments=(50, 200),
        table1_n=64,
        table1_methods=("vs",),
        islands_n=128,
        islands_seeds=1,
        islands_increments=50,
        asperity_n=256,
        asperity_increments=200,
        elastic_D=(2.1, 2.9),
        elastic_size_ratios=(1, 3),
        elastic_pixels_per_Wr=16,
        elastic_refine_ratio=3,
        elastic_seeds=1,
        elastic_fractions=(0.02, 0.05, 0.1, 0.2, 0.4),
        indentation=_indentation(
            n=256,
            hardness=(math.inf, 0.5e9, 2e9, 8e9),
            seeds=(0, 1),
            stats_placements=1,
            refine_punches=PAPER_PUNCH_DIAMETERS[:1],
            face_tilts_deg=(0.1,),
            face_hardness=2e9,
            protocol={
                "peak_loads": PAPER_PEAK_LOADS[-4:],
                "placements": 1,
                "truncation_increments": 200,
                "min_contact_pixels": 1,
                "refine_max": 2,
            },
            solver={"maxiter": 200},
        ),
    ),
    "quick": Profile(
        name="quick",
        n=1024,
        seeds=3,
        fig5_sizes=(256, 512, 1024, 2048),
        fig5_seeds=3,
        table1_n=256,
        table1_seeds=1,
        islands_n=1024,
        islands_seeds=2,
        asperity_n=1024,
        elastic_pixels_per_Wr=16,
        indentation=_indentation(
            n=512,
            seeds=(0, 1),
            stats_placements=2,
            refine_punches=PAPER_PUNCH_DIAMETERS[:1],
            protocol={"placements": 1, "min_contact_pixels": 10, "refine_max": 2},
        ),
    ),
    "paper": Profile(
        name="paper",
        n=10240,
        seeds=5,
        fig5_sizes=(1024, 2048, 4096, 8192, 10240),
        fig5_seeds=10,
        table1_n=1024,
        table1_seeds=3,
        table1_methods=("tri", "box", "vs", "sp"),
        islands_n=30720,
        islands_L=3e-3,
        islands_seeds=4,
        asperity_n=4096,
        indentation=_indentation(
            n=1280,
            seeds=(0, 1, 2, 3, 4, 5),
            stats_placements=2,
            refine_punches=None,
            protocol={"refine_max": 8, "placements": 2, "overlap": "error"},
            solver={"dtype": "float32"},
        ),
    ),
}

#: Where a profile's parameters differ from the paper: (item, what the paper did, what the
#: profile does), per profile field; the report's header table prints the rows that apply.
# fmt: off
PAPER_DEPARTURES = (
    ("fig5_sizes", "Fig. 5a resolutions", "1024² to 32760² over 1 mm", "{fig5_min}² to {fig5_max}² over 1 mm"),
    ("fig5_increments", "Fig. 5b increments", "200 to 5000", "{fig5_increments[0]} to {fig5_max_inc} (at {fig5_max}²)"),
    ("fig5_seeds", "Fig. 5 seeds per resolution", "10", "{fig5_seeds}"),
    ("n", "Groups 1–2 (Table 3) surfaces", "10240² over 1 mm, 5 per case", "{n}² over {L_mm:g} mm, {seeds} per case"),
    ("table1_n", "Table 1 calibration surfaces", "1024² scans, 1 µm pixels", "{table1_n}² scans, 1 µm pixels, {table1_seeds} seed(s)"),
    ("islands_n", "Islands (Figs. 7–8, Table 2)", "30720² over 3 mm", "{islands_n}² over {islands_L_mm:g} mm, {islands_seeds} seed(s) per surface"),
    ("asperity_n", "Fig. 2 sphere", "1000 increments", "{asperity_increments} increments, {asperity_n}² pixel sphere (the paper states no size)"),
    ("group_fit", "Fit range of α, β (Table 3)", "not stated", "≥ 10 contact pixels (`default`) and ≥ {late_fit_fraction:g} × final contact pixels (`late`); the fit-range map shows the rest"),
    ("indentation_n", "Indentation (Fig. 6) maps", "1 mm over 10240 pixels (97.7 nm)", "{indentation_L_mm:g} mm over {indentation_n} pixels ({indentation_dx_nm:.1f} nm)"),
    ("indentation_punches", "Indentation punches", "54.1, 108.7, 502.6 µm", "{indentation_punches_um}"),
    ("indentation_loads", "Indentation cycles", "10 peaks, each twice the previous, to 500 mN", "{indentation_n_loads} peaks, each twice the previous, to {indentation_max_mN:g} mN"),
    ("indentation_placements", "Indents per punch and surface", "not stated", "{indentation_indents_text}"),
    ("indentation_hardness", "Hardness H of the alloy", "not stated", "swept: {indentation_hardness_text}"),
)
# fmt: on


def get_profile(name: str) -> Profile:
    """The named profile; raises with the allowed names.

    Parameters
    ----------
    name : str
        ``"tiny"``, ``"quick"`` or ``"paper"`` (the keys of :data:`PROFILES`).

    Returns
    -------
    Profile
        The profile.

    Raises
    ------
    ValueError
        If ``name`` is not a profile; the message lists the allowed names.
    """
    if name not in PROFILES:
        raise ValueError(f"profile must be one of {sorted(PROFILES)}, got {name!r}")
    return PROFILES[name]
