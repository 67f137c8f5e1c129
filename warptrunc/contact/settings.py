# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Settings of the contact solver, declared once (:mod:`warptrunc.params`).

:class:`SolverSettings` holds the precision, the substrate, the tolerances and the iteration
limits of :class:`~warptrunc.contact.ContactSolver`; validation, command-line options
(:func:`warptrunc.params.add_options`) and the docs table (:func:`warptrunc.params.markdown_table`)
are generated from its fields.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..params import Parameters, check_fields, param

__all__ = ["SolverSettings"]


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
    convolutions than it saves (``warptrunc.contact.bccg.PRECONDITION_LARGE``; the
    measurements behind the rule: ``guide/performance.md``).

    Examples
    --------
    >>> SolverSettings(dtype="float32").substrate
    'free'
    """

    dtype: str = param(
        "float64", "precision of the maps and FFTs (reductions are float64 in both)",
        choices=("float64", "float32"),
    )  # fmt: skip
    substrate: str = param(
        "free", "half-space: isolated zero-padded patch or periodic map",
        choices=("free", "periodic"),
    )  # fmt: skip
    pressure_tol: float = param(
        1e-5, "tolerance on tensile (and above-hardness) pixel pressure relative to E*; "
        "forcetol = pressure_tol·E*·dx·dy", gt=0.0,
    )  # fmt: skip
    pentol: float | None = param(
        None, "tolerance on penetration; None = rms height/(10·mean(nx, ny)) (ContactMechanics), "
        "lowered near full contact to 1 % of the mean open gap (contact.loop.OPEN_GAP_FRACTION)",
        unit="m", gt=0.0, optional=True,
    )  # fmt: skip
    thermotol: float = param(1e-6, "relative tolerance on the total force", gt=0.0)
    load_control: str = param(
        "offset", "how a solve at a given load finds its approach: 'offset' moves the rigid "
        "offset inside the CG (ContactMechanics'; with a hardness, an elastic trial that is "
        "kept when no pixel exceeds H, else the secant from it), 'secant' runs a safeguarded "
        "secant on the approach over displacement-controlled solves",
        choices=("offset", "secant"),
    )  # fmt: skip
    algorithm: str = param(
        "bccg", "iteration: 'pk' Polonsky & Keer's constrained CG (ContactMechanics'), 'bccg' "
        "Vollebregt's bound-constrained CG with the FFT preconditioner K⁻¹ (one more convolution "
        "per iteration, far fewer iterations on large contacts)",
        choices=("pk", "bccg"),
    )  # fmt: skip
    fft_plan: str = param(
        "auto", "cuFFT plans of the free half-space on a CUDA device (ignored elsewhere): "
        "'pruned' transforms only the map's rows and the columns in slabs (least memory), "
        "'full' one 2-D plan each way over the padded grid (about 2× faster per convolution at "
        "16384², with cuFFT's work area as large as the work spectrum: +16 bytes per map pixel "
        "in float32), 'auto' full when the solver then fits in the free device memory, else "
        "pruned",
        choices=("auto", "pruned", "full"),
    )  # fmt: skip
    loop: str = param(
        "host", "where the BCCG iteration's scalar steps run: 'host' reads back after each "
        "reduction (4-5 times per iteration); 'device' folds the offset of load control, the "
        "CG's beta and the projection's count on the device and reads back once per iteration; "
        "'graph' the same, its steady iterations replayed from a CUDA graph (as 'device' off "
        "CUDA). Equal to round-off; on an H200 'graph' was 8 % faster at 2048² and 1-3 % slower "
        "from 8192² (guide/performance.md)",
        choices=("host", "device", "graph"),
    )  # fmt: skip
    precondition_above: float | None = param(
        None, "BCCG applies its FFT preconditioner c·K⁻¹·c (one more convolution per iteration) "
        "while the free set covers more than this fraction of the map (dimensionless; 0 = "
        "always, 1 = never; Barber's punch solve likewise on its contact set); None = auto: "
        "0 on maps of at least 1024² pixels, else 0.02; 0.02 under a punch and in Barber's solve",
        ge=0.0, le=1.0, optional=True,
    )  # fmt: skip
    maxiter: int = param(10000, "largest number of iterations per solve", kind="int", ge=1)
    refresh: int = param(
        50, "transform the forces afresh at least every this many iterations", kind="int", ge=1
    )
    direct_max: int | None = param(
        None, "largest number of changed forces corrected by direct summation (algorithm "
        "'pk'); None = auto "
        "(24 on CUDA, 4 on the CPU)", kind="int", ge=0, optional=True,
    )  # fmt: skip

    def __post_init__(self) -> None:
        for name in ("direct_max", "precondition_above"):
            if isinstance(getattr(self, name), str) and getattr(self, name) == "auto":
                object.__setattr__(self, name, None)
        check_fields(self)
