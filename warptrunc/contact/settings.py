# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The parameters of the contact solver and of what is computed with it, declared once
(:mod:`warptrunc.params`).

:class:`SolverSettings` holds the precision, the substrate, the tolerances and the iteration
limits of :class:`~warptrunc.contact.ContactSolver`; :class:`CurveSettings` what each row of
:func:`~warptrunc.contact.solve_contact` holds beside the solve (the stiffness method, the
maps); :class:`BemCheckSettings` the approaches of :func:`~warptrunc.bem_check` and how its
elastic side is solved. Validation, command-line options (:func:`warptrunc.params.add_options`)
and the docs tables (:func:`warptrunc.params.markdown_table`) are generated from their fields.
No Warp here: the command-line parsers import this module.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import Any

from ..params import Parameters, check_fields, param, param_like
from ..slope import SMALL_SLOPE_LIMIT
from ..truncation.settings import TruncationSettings
from .adhesion import Adhesion

__all__ = [
    "BEM_SOLVERS",
    "CHECK_FRACTIONS",
    "ELASTIC_TRUNCATION",
    "STIFFNESS_METHODS",
    "BemCheckSettings",
    "CurveSettings",
    "SolverSettings",
]

STIFFNESS_METHODS = ("barber", "central", "none")
"""How the stiffness k = dF/dδ of a contact curve's row is found (:class:`CurveSettings`)."""

BEM_SOLVERS = ("warptrunc", "contactmechanics")
"""The elastic solvers of a bem-check: warptrunc's own and ContactMechanics' (the reference)."""

CHECK_FRACTIONS = (0.05, 0.1, 0.15, 0.2, 0.3, 0.4)
"""Approaches δ/R_t of a bem-check when none are given (dimensionless)."""

ELASTIC_TRUNCATION = TruncationSettings(increments=400)
"""The truncation of the elastic cross-checks (:func:`~warptrunc.bem_check`,
:func:`~warptrunc.compare.compare_models`): 400 depth increments from 0 to the largest approach
for the load integrals, β' = 1, 4-connected islands."""


@dataclass(frozen=True)
class SolverSettings(Parameters):
    """Precision, substrate, tolerances and iteration limits of the contact solver.

    Raises
    ------
    ValueError
        A field out of its range; the message names the field, its value and the range.

    Notes
    -----
    ``direct_max`` is an integer or None (``"auto"`` is accepted and stored as None): None
    chooses 24 on a CUDA device and 4 on the CPU, where Warp runs a kernel on one core.
    ``precondition_above`` likewise: None (or ``"auto"``) applies the preconditioner always on a
    map of at least 1024² pixels (the iterations then hardly grow with the grid) and while the
    free set covers more than 2 % of a smaller map; the solvers of a punch's window
    (:mod:`warptrunc.indent`) take 2 % at every size, where always preconditioning costs more
    convolutions than it saves (``warptrunc.contact.iteration.bccg.PRECONDITION_LARGE``; the
    measurements behind the rule: ``guide/performance.md``).

    ``adhesion`` is the interaction law the solver solves with, a parameter object of its own
    (:class:`~warptrunc.contact.adhesion.Adhesion`, the command-line options ``--adhesion``,
    ``--work``, ``--range``), as the substrate is the half-space it solves on; the default
    ``Adhesion()`` is non-adhesive, and :meth:`to_dict` lists it only when it is adhesive.

    Examples
    --------
    >>> SolverSettings(dtype="float32").substrate
    'free'
    """

    dtype: str = param(
        "float64",
        "precision of the maps and FFTs (reductions are float64 in both)",
        choices=("float64", "float32"),
    )
    substrate: str = param(
        "free",
        "half-space: isolated zero-padded patch or periodic map",
        choices=("free", "periodic"),
    )
    pressure_tol: float = param(
        1e-5,
        "tolerance on tensile (and above-hardness) pixel pressure relative to E*; "
        "forcetol = pressure_tol·E*·dx·dy",
        gt=0.0,
    )
    pentol: float | None = param(
        None,
        "tolerance on penetration; None = rms height/(10·mean(nx, ny)) (ContactMechanics), "
        "lowered near full contact to 1 % of the mean open gap (contact.iteration.loop.OPEN_GAP_FRACTION)",
        unit="m",
        gt=0.0,
        optional=True,
    )
    thermotol: float = param(1e-6, "relative tolerance on the total force", gt=0.0)
    load_control: str = param(
        "offset",
        "how a solve at a given load finds its approach: 'offset' moves the rigid "
        "offset inside the CG (ContactMechanics'; with a hardness, an elastic trial that is "
        "kept when no pixel exceeds H, else the secant from it), 'secant' runs a safeguarded "
        "secant on the approach over displacement-controlled solves",
        choices=("offset", "secant"),
    )
    algorithm: str = param(
        "bccg",
        "iteration: 'pk' Polonsky & Keer's constrained CG (ContactMechanics'), 'bccg' "
        "Vollebregt's bound-constrained CG with the FFT preconditioner K⁻¹ (one more convolution "
        "per iteration, far fewer iterations on large contacts)",
        choices=("pk", "bccg"),
    )
    fft_plan: str = param(
        "auto",
        "cuFFT plans of the free half-space on a CUDA device (ignored elsewhere): "
        "'pruned' transforms only the map's rows and the columns in slabs (least memory), "
        "'full' one 2-D plan each way over the padded grid (about 2× faster per convolution at "
        "16384², with cuFFT's work area as large as the work spectrum: +16 bytes per map pixel "
        "in float32), 'auto' full when the solver then fits in the free device memory, else "
        "pruned",
        choices=("auto", "pruned", "full"),
    )
    loop: str = param(
        "host",
        "where the BCCG iteration's scalar steps run: 'host' reads back after each "
        "reduction (4-5 times per iteration); 'device' folds the offset of load control, the "
        "CG's beta and the projection's count on the device and reads back once per iteration; "
        "'graph' the same, its steady iterations replayed from a CUDA graph (as 'device' off "
        "CUDA). Equal to round-off; on an H200 'graph' was 8 % faster at 2048² and 1-3 % slower "
        "from 8192² (guide/performance.md)",
        choices=("host", "device", "graph"),
    )
    precondition_above: float | None = param(
        None,
        "BCCG applies its FFT preconditioner c·K⁻¹·c (one more convolution per iteration) "
        "while the free set covers more than this fraction of the map (dimensionless; 0 = "
        "always, 1 = never; Barber's punch solve likewise on its contact set); None = auto: "
        "0 on maps of at least 1024² pixels, else 0.02; 0.02 under a punch and in Barber's solve",
        ge=0.0,
        le=1.0,
        optional=True,
    )
    maxiter: int = param(10000, "largest number of iterations per solve", kind="int", ge=1)
    refresh: int = param(
        50, "transform the forces afresh at least every this many iterations", kind="int", ge=1
    )
    direct_max: int | None = param(
        None,
        "largest number of changed forces corrected by direct summation (algorithm "
        "'pk'); None = auto "
        "(24 on CUDA, 4 on the CPU)",
        kind="int",
        ge=0,
        optional=True,
    )
    slope_limit: float = param(
        SMALL_SLOPE_LIMIT,
        "the largest rms slope h′_rms of the surface at the pixel solved that counts as inside the "
        "small-slope range of the half-space solution: a warning above it (it changes no number)",
        gt=0.0,
        sweep=False,
    )
    adhesion: Adhesion = field(default=Adhesion())
    """The interaction law between the surfaces (:class:`~warptrunc.contact.adhesion.Adhesion`;
    a dict of its fields is accepted); default non-adhesive."""

    def __post_init__(self) -> None:
        for name in ("direct_max", "precondition_above"):
            if isinstance(getattr(self, name), str) and getattr(self, name) == "auto":
                object.__setattr__(self, name, None)
        if isinstance(self.adhesion, dict):
            object.__setattr__(self, "adhesion", Adhesion(**self.adhesion))
        if not isinstance(self.adhesion, Adhesion):
            raise ValueError(f"adhesion must be an Adhesion, got {type(self.adhesion).__name__}")
        check_fields(self)

    def to_dict(self) -> dict[str, Any]:
        """The fields (SI), the adhesion law as a dict of its own when it is adhesive.

        Returns
        -------
        dict
            One entry per field; ``adhesion`` only with an adhesive law (so that the records
            of non-adhesive solves stay as they were).
        """
        out = super().to_dict()
        law = out.pop("adhesion")
        if law.active:
            out["adhesion"] = law.to_dict()
        return out


@dataclass(frozen=True)
class CurveSettings(Parameters):
    """What each row of a contact curve holds beside its solve (:func:`~warptrunc.contact.solve_contact`).

    Examples
    --------
    >>> CurveSettings(stiffness="central", fd_step=0.01).fd_step
    0.01
    """

    stiffness: str = param(
        "barber",
        "k = dF/dδ by Barber's flat punch of the contact set (one linear CG solve; "
        "with a finite hardness the unloading stiffness of the deformed surface), by the central "
        "difference over δ(1 ± fd_step) (two more contact solves; elastic only), or none (NaN)",
        choices=STIFFNESS_METHODS,
        sweep=False,
    )
    fd_step: float = param(
        0.02,
        "relative step h of the central difference k = [F(δ(1 + h)) − F(δ(1 − h))]/(2hδ)",
        gt=0.0,
        lt=0.5,
    )
    maps: bool = param(
        False,
        "keep the pressure (Pa) and gap (m) maps of every row (host memory: 16 bytes per "
        "pixel per row)",
        kind="bool",
        sweep=False,
    )

    def __post_init__(self) -> None:
        check_fields(self)


@dataclass(frozen=True)
class BemCheckSettings(Parameters):
    """The approaches δ of a bem-check (:func:`~warptrunc.bem_check`) and how its elastic side is
    solved and differentiated.

    The approaches are ``fractions`` of R_t or ``depths`` (m), one or the other; neither:
    :data:`CHECK_FRACTIONS`.

    Examples
    --------
    >>> BemCheckSettings(fractions=(0.1, 0.2), stiffness="barber").fractions
    (0.1, 0.2)
    """

    fractions: tuple[float, ...] | None = param(
        None,
        "approaches δ as fractions of R_t, strictly increasing; none = 0.05 0.1 0.15 0.2 "
        "0.3 0.4, unless depths are given",
        gt=0.0,
        lt=1.0,
        many=True,
        optional=True,
        sweep=False,
    )
    depths: tuple[float, ...] | None = param(
        None,
        "approaches δ, strictly increasing, below R_t of the map; instead of the fractions",
        unit="m",
        gt=0.0,
        many=True,
        optional=True,
        sweep=False,
    )
    solver: str = param(
        "warptrunc",
        "the elastic solver: warptrunc's constrained CG on the device, or "
        'ContactMechanics\' on the CPU, the reference (pip install "warptrunc[bem]")',
        choices=BEM_SOLVERS,
        sweep=False,
    )
    stiffness: str = param_like(
        CurveSettings,
        "stiffness",
        default="central",
        choices=("central", "barber"),
        doc="k = dF/dδ by the central difference over δ(1 ± fd_step), or by Barber's flat punch "
        "of the contact set (solver warptrunc only)",
    )
    fd_step: float = param_like(CurveSettings, "fd_step")

    def __post_init__(self) -> None:
        check_fields(self)
        for name, what in (("fractions", "fractions of R_t"), ("depths", "m")):
            v = getattr(self, name)
            if v is not None and any(b <= a for a, b in itertools.pairwise(v)):
                raise ValueError(
                    f"{name} must increase strictly (approaches δ, {what}), got "
                    f"{' '.join(f'{x:g}' for x in v)}"
                )
        if self.fractions is not None and self.depths is not None:
            raise ValueError("fractions and depths both give the approaches: give one")
        if self.stiffness == "barber" and self.solver != "warptrunc":
            raise ValueError(f"stiffness barber needs solver warptrunc, got {self.solver}")

    def approaches(self, Rt: float) -> Any:
        """The approaches δ (m) on a map of height range ``Rt``.

        Parameters
        ----------
        Rt : float
            R_t of the map (m).

        Returns
        -------
        (m,) ndarray of float64
            ``fractions``·R_t, or ``depths`` (m).

        Raises
        ------
        ValueError
            A depth not below R_t, naming the range in metres.
        """
        import numpy as np

        if self.depths is None:
            return np.asarray(self.fractions or CHECK_FRACTIONS, dtype=np.float64) * Rt
        if max(self.depths) >= Rt:
            raise ValueError(
                f"depths must be in (0, R_t) = (0, {Rt:.6g}) m for this surface, got "
                f"{' '.join(f'{v:g}' for v in self.depths)} (metres; fractions are of R_t)"
            )
        return np.asarray(self.depths, dtype=np.float64)
