# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The ``indentation`` stage's design: its parameters (:class:`IndentationStage`, a profile's
``indentation``) and what they imply — the maps, the material at a hardness, the sweep's H
order, the realisations and placements of each design, the refinement of a punch and the punch
faces. Loads no Warp (the profiles read it).

Two designs: ``sweep`` — one realisation (the first of ``seeds``) × ``protocol.placements``
placements per punch, for every H of ``hardness``; ``stats`` — every realisation of ``seeds`` ×
``stats_placements`` placements per punch, for the models of ``stats``. A third, ``face``,
repeats the sweep's indents of ``face_surface`` at ``face_hardness`` with a tilted or a rough
punch face (:func:`face_variants`). Punch k draws its placements with seed
``protocol.placement_seed + k`` (one :func:`~warptrunc.indent.indent` call per punch, so that
each punch has its own refinement: ``refine_punches``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ...contact.settings import SolverSettings
from ...indent.face import MAX_FACE_GRID, PunchFaceSpec
from ...indent.protocol import PAPER_PROTOCOL, IndentProtocol, default_material
from ...material import Material
from ...params import Parameters, check_fields, param
from ...presets import TABLE1

__all__ = [
    "DESIGNS",
    "STATS_MODELS",
    "IndentationStage",
    "design_of",
    "face_fields",
    "face_spec",
    "face_variants",
    "material",
    "model_name",
    "refine_of",
    "spec",
    "sweep_order",
]

DESIGNS = ("sweep", "stats")
"""The two designs of the stage's main pieces: the hardness sweep and the statistics (the
``face`` pieces are summarised apart)."""
STATS_MODELS = ("elastic", "depth-match")
"""What :attr:`IndentationStage.stats` may name."""
INDENT_SURFACES = ("Ps", "SMATs", "GB300s", "GB50s")
"""The four Table 1 surfaces of Fig. 6."""
INDENT_HARDNESS = (math.inf, 0.2e9, 0.5e9, 1e9, 2e9, 4e9, 8e9)
"""The H values of the sweep (Pa; inf = elastic): from 0.2 GPa, where the handbook range of
aluminium alloys starts (below about 0.22 GPa the mean pressure of 500 mN under the 54.1 µm
punch reaches the cap's bulk-yield pressure: those cells are flagged ``bulk_yield``)."""


@dataclass(frozen=True)
class IndentationStage(Parameters):
    """What the ``indentation`` stage computes: the paper's experiment (§ 4.1, Fig. 6) in silico.

    The :attr:`protocol` (:class:`~warptrunc.indent.IndentProtocol`: punches, loads,
    placements of the sweep and their seed, unloading, truncation increments, the refinement
    rule) is the one every piece runs; its ``elastic`` and ``face`` are set per piece (H = ∞
    runs the elastic model, the ``face`` pieces their face). The :attr:`solver` settings and the
    :attr:`material`'s elastic constants are those of every piece, its hardness each piece's H.

    Raises
    ------
    ValueError
        A field out of its range (the message names it), a face surface that is not one of
        ``surfaces``, a face hardness that is not one of :attr:`hardness`, a depth band
        that does not bracket its target, or a protocol without punches or placements.
    """

    surfaces: tuple[str, ...] = param(
        INDENT_SURFACES,
        "Table 1 presets indented (warptrunc.presets.TABLE1)",
        choices=tuple(TABLE1),
        many=True,
        sweep=False,
    )
    n: int = param(10240, "pixels per side of the maps (over L)", kind="int", ge=8, sweep=False)
    L: float = param(1e-3, "side of the maps", unit="m", gt=0.0, sweep=False)
    hardness: tuple[float, ...] = param(
        INDENT_HARDNESS,
        "hardness values H of the sweep; inf = elastic (the paper states no "
        "hardness: H is swept, not assumed; aluminium alloys span about 0.2–1.7 GPa by "
        "handbook Vickers values, more at shallow nanoindentation depths and after work "
        "hardening; docs/guide/indentation.md)",
        unit="Pa",
        gt=0.0,
        allow_inf=True,
        many=True,
        sweep=False,
    )
    seeds: tuple[int, ...] = param(
        (0, 1, 2),
        "phase seeds of the realisations of the statistics pieces; the hardness "
        "sweep runs on the first",
        kind="seeds",
        sweep=False,
    )
    stats_placements: int = param(
        5,
        "random punch placements per diameter and realisation of the statistics pieces",
        kind="int",
        ge=1,
        le=10_000,
        sweep=False,
    )
    stats: tuple[str, ...] = field(default=STATS_MODELS)
    """Models of the statistics pieces: ``"elastic"`` (H = ∞) and ``"depth-match"`` (one H for
    every surface: the H of the sweep whose largest threshold depth at the largest load, over
    every surface, punch and placement, is nearest ``depth_target``, when the sweep reaches
    ``depth_band``; none otherwise — the paper's ≈ 5 µm is its maximum over all tests).
    Empty: no statistics pieces."""
    depth_target: float = param(
        5e-6,
        'the paper\'s maximal indentation depth at 500 mN, "around 5 µm" (§ 4.1)',
        unit="m",
        gt=0.0,
        sweep=False,
    )
    depth_band: tuple[float, float] = param(
        (4e-6, 6e-6),
        'threshold depths at the largest load taken as consistent with "around 5 µm" (the '
        "largest over every surface, punch and placement)",
        unit="m",
        gt=0.0,
        length=2,
        increasing=True,
        sweep=False,
    )
    face_surface: str | None = param(
        "Ps",
        "surface of the punch-face runs (none: none): the aligned smooth flat of the "
        "sweep against tilted and rough faces (§ 4.2 names misalignment and the tip's roughness "
        "among the causes of Ps's divergence beyond 15 % R_t')",
        choices=tuple(TABLE1),
        optional=True,
        sweep=False,
    )
    face_tilts_deg: tuple[float, ...] = param(
        (0.02, 0.05, 0.1),
        "tilts of the punch face in those runs (degrees; PunchFaceSpec.tilt_deg), relative "
        "to face_tilt_reference; with 'local' a face at 0° (aligned with the surface under "
        "each placement) runs too and is the reference of the comparison, with 'map' the "
        "sweep's aligned flat is",
        ge=0.0,
        le=5.0,
        many=True,
        sweep=False,
    )
    face_tilt_reference: str = param(
        "local",
        "what those tilts are measured against (PunchFaceSpec.tilt_reference): 'local', the "
        "sample's plane under each placement (the relative tilt of punch and surface; a long "
        "wave already tilts the sample under a punch: Ps's by about 0.02° rms), or 'map'",
        choices=("local", "map"),
        sweep=False,
    )
    face_roughness: float = param(
        0.05e-6,
        "rms roughness of a generated punch face in those runs (0: none): the paper's "
        'tip, "measured to have an RMS roughness of around 0.05 µm" (§ 4.2)',
        unit="m",
        ge=0.0,
        sweep=False,
    )
    face_hardness: float = param(
        1e9,
        "H of the punch-face runs (one of hardness; inf = elastic): the paper states none; "
        "1 GPa is warptrunc.indent's default, inside the handbook range",
        unit="Pa",
        gt=0.0,
        allow_inf=True,
        sweep=False,
    )
    refine: bool = param(
        True,
        "resolution check: the smallest punch at the map centre at dx and dx/2",
        kind="bool",
        sweep=False,
    )
    refine_punches: tuple[float, ...] | None = param(
        None,
        "punch diameters whose cells are refined up to protocol.refine_max (none: every "
        "punch); every cell of a refined punch is solved at least once at half the pixel, so "
        "refining the 502.6 µm punch at the paper's pixel costs about four times its solves",
        unit="m",
        gt=0.0,
        many=True,
        optional=True,
        sweep=False,
    )
    protocol: IndentProtocol = field(default=PAPER_PROTOCOL)
    """The experiment (:class:`~warptrunc.indent.IndentProtocol`): the paper's punches and ten
    loads, 3 placements per punch in the sweep (seed 0 + punch index), 10 % unloading, 1000
    truncation increments, the cells judged by their contact pixels (``refine_max`` 1: above
    1 the windows of ``refine_punches`` are generated again at pixel/2 … pixel/refine_max
    until resolved; the fits, the agreement depths and the tracking rule use the cells
    ``in_fit`` either way)."""
    solver: SolverSettings = field(default=SolverSettings(maxiter=1000))
    """Contact-solver settings of every solve (float64; at most 1000 iterations: a solve that
    does not converge — complete contact under a small punch on the smooth Ps stalls load
    control — is bounded, flagged, counted in the report and left out of the fits)."""
    material: Material = field(default=default_material())
    """Elastic constants of the alloy and of the diamond punch
    (:func:`~warptrunc.indent.default_material`, assumptions: ``docs/guide/indentation.md``);
    its hardness is each piece's H."""

    def __post_init__(self) -> None:
        check_fields(self)
        kinds = {"protocol": IndentProtocol, "solver": SolverSettings, "material": Material}
        for name, cls in kinds.items():
            if not isinstance(getattr(self, name), cls):
                raise ValueError(f"{name} must be a {cls.__name__}, got {getattr(self, name)!r}")
        object.__setattr__(self, "stats", tuple(self.stats))
        bad = [m for m in self.stats if m not in STATS_MODELS]
        if bad:
            raise ValueError(f"stats must name models among {STATS_MODELS}, got {bad!r}")
        lo, hi = self.depth_band
        if not lo <= self.depth_target <= hi:
            raise ValueError(
                f"depth_band must bracket depth_target, low ≤ target ≤ high (m), got "
                f"{list(self.depth_band)!r} around {self.depth_target!r}"
            )
        if self.face_surface is not None and face_variants(self):
            if self.face_surface not in self.surfaces:
                raise ValueError(
                    f"face_surface must be one of surfaces {self.surfaces!r} or None, got "
                    f"{self.face_surface!r}"
                )
            if self.face_hardness not in self.hardness:
                raise ValueError(
                    f"face_hardness must be one of hardness {self.hardness!r} (Pa), got "
                    f"{self.face_hardness!r}"
                )
        pr = self.protocol
        if pr.punch_diameters is None or pr.placements is None:
            raise ValueError(
                f"protocol needs punch diameters and placements (the stage places punches at "
                f"random), got punch_diameters={pr.punch_diameters!r}, placements={pr.placements!r}"
            )

    def to_dict(self) -> dict[str, Any]:
        """The fields as a JSON-ready dict, the protocol, solver and material as dicts of their own.

        Returns
        -------
        dict
        """
        return {
            **super().to_dict(),
            "protocol": self.protocol.to_dict(),
            "solver": self.solver.to_dict(),
            "material": self.material.to_dict(),
        }

    @property
    def pixel_size(self) -> float:
        """Pixel side L/n of the maps (m)."""
        return self.L / self.n


def model_name(hardness: float | None) -> str:
    """Model key of a hardness: ``elastic`` (inf or None) or ``elastic_plastic_<H in GPa>GPa``.

    Parameters
    ----------
    hardness : float or None
        H (Pa); inf or None = elastic.

    Returns
    -------
    str
        ``"elastic"``, ``"elastic_plastic_0.5GPa"``, ``"elastic_plastic_2GPa"``, …
    """
    if hardness is None or math.isinf(hardness):
        return "elastic"
    return f"elastic_plastic_{hardness / 1e9:g}GPa"


def material(st: IndentationStage, hardness: float) -> Material:
    """The stage's material at hardness H (Pa; inf = elastic).

    Parameters
    ----------
    st : IndentationStage
        The stage (its :attr:`~IndentationStage.material`).
    hardness : float
        H (Pa).

    Returns
    -------
    Material
    """
    return st.material.replace(hardness=hardness)


def spec(st: IndentationStage, name: str, seed: int | None = None):
    """The Table 1 preset ``name`` on the stage's map (and phase seed).

    Parameters
    ----------
    st : IndentationStage
        The stage (``n``, ``L``).
    name : str
        Table 1 name.
    seed : int, optional
        Phase seed (default the preset's).

    Returns
    -------
    WMSpec
    """
    s = TABLE1[name].replace(n=st.n, L=st.L)
    return s if seed is None else s.replace(seed=int(seed))


def sweep_order(st: IndentationStage) -> list[float]:
    """The sweep's H values, H = ∞ first (its cycles are the others' unyielded ones).

    Parameters
    ----------
    st : IndentationStage
        The stage (``hardness``).

    Returns
    -------
    list of float
        H (Pa): inf, then the finite values increasing.
    """
    hs = sorted(set(st.hardness), key=lambda h: (math.isfinite(h), h))
    return hs if math.isinf(hs[0]) else [math.inf, *hs]


def face_variants(st: IndentationStage) -> list[tuple[str, dict[str, float]]]:
    """The punch faces of the ``face`` pieces: (label, :class:`~warptrunc.indent.PunchFaceSpec`
    fields).

    Parameters
    ----------
    st : IndentationStage
        The stage (``face_surface``, ``face_tilts_deg``, ``face_roughness``).

    Returns
    -------
    list of (str, dict)
        With ``face_tilt_reference`` ``"local"``: ``("tilt 0° local", {"tilt_deg": 0.0,
        "tilt_reference": "local"})``, ``("tilt 0.02° local", …)``, …; with ``"map"``:
        ``("tilt 0.1°", {"tilt_deg": 0.1})``, …; then ``("rough 0.05 µm rms",
        {"roughness": 5e-08})``; empty without a face surface. Tilts turn their azimuth from
        one placement to the next (:func:`face_fields`).
    """
    if st.face_surface is None:
        return []
    if st.face_tilt_reference == "local":
        tilts = sorted({0.0, *(float(t) for t in st.face_tilts_deg)})
        out = [(f"tilt {t:g}° local", {"tilt_deg": t, "tilt_reference": "local"}) for t in tilts]
    else:
        out = [(f"tilt {t:g}°", {"tilt_deg": float(t)}) for t in st.face_tilts_deg if t > 0]
    if st.face_roughness > 0:
        out.append(
            (f"rough {st.face_roughness * 1e6:g} µm rms", {"roughness": float(st.face_roughness)})
        )
    return out


def face_fields(st: IndentationStage, face: dict[str, float], k: int, d: float) -> dict[str, Any]:
    """The face fields of punch k: its own face seed and, for a rough face, the shortest
    wavelength 2 map pixels or, when the punch's face grid cannot hold that, the shortest it can.

    Parameters
    ----------
    st : IndentationStage
        The stage (its pixel).
    face : dict
        The fields of a :func:`face_variants` entry.
    k : int
        Index of the punch.
    d : float
        Its diameter (m).

    Returns
    -------
    dict
        :class:`~warptrunc.indent.PunchFaceSpec` fields (``seed`` = k; a tilt's
        ``tilt_azimuths`` = the placements, so that they average over azimuth; ``cutoff_short``
        (m) of a rough face).
    """
    kw: dict[str, Any] = {**face, "seed": k}
    if "tilt_deg" in face:  # averaged over azimuth: one azimuth per placement of the design
        kw["tilt_azimuths"] = max(1, int(st.protocol.placements))
    if face.get("roughness", 0) > 0:
        kw["cutoff_short"] = max(2 * st.pixel_size, 2 * d / (MAX_FACE_GRID / 2 - 1) * (1 + 1e-6))
    return kw


def face_spec(
    st: IndentationStage, face: tuple[str, dict[str, float]] | None, k: int, d: float
) -> PunchFaceSpec:
    """The punch face of punch k in a piece: an aligned smooth flat, or the variant ``face``.

    Parameters
    ----------
    st : IndentationStage
        The stage.
    face : (str, dict) or None
        A :func:`face_variants` entry (``face`` pieces) or None.
    k : int
        Index of the punch.
    d : float
        Its diameter (m).

    Returns
    -------
    PunchFaceSpec
    """
    return PunchFaceSpec() if face is None else PunchFaceSpec(**face_fields(st, face[1], k, d))


def design_of(st: IndentationStage, design: str) -> tuple[tuple[int, ...], int]:
    """(phase seeds, placements per punch) of a design (``face``: the sweep's).

    Parameters
    ----------
    st : IndentationStage
        The stage.
    design : str
        ``"sweep"``, ``"stats"`` or ``"face"``.

    Returns
    -------
    tuple
        The phase seeds of its realisations and its placements per punch.
    """
    if design in ("sweep", "face"):
        return (st.seeds[0],), st.protocol.placements
    return tuple(st.seeds), st.stats_placements


def refine_of(st: IndentationStage, d: float) -> int:
    """The refinement of punch ``d``'s cells (1: none).

    Parameters
    ----------
    st : IndentationStage
        The stage (``refine_punches``, ``protocol.refine_max``).
    d : float
        Punch diameter (m).

    Returns
    -------
    int
    """
    sel = st.refine_punches
    if sel is None or any(math.isclose(d, x, rel_tol=1e-9) for x in sel):
        return st.protocol.refine_max
    return 1
