# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""How good is truncation? Eq. 2, island-resolved truncation and elastic contact on one map.

Three routes to the load F, the stiffness k and the contact area A of a rough surface pressed
by a rigid flat to an approach d (measured from first touch at the highest pixel):

``eq2``
    The paper's Eq. (2): the whole truncated set at ω = d is one flat punch,
    k' = β'(2/√π)E*·√A', F' = ∫₀^d k' dω (:func:`warptrunc.stiffness.stiffness_curve`).
``islands``
    Island-resolved truncation: each island of the truncated set is a punch of its own,
    k_isl = β'(2/√π)E*·Σ_i √A_i, F_isl = ∫₀^d k_isl dω
    (:func:`warptrunc.stiffness.island_stiffness_curve`).
``bem``
    The elastic boundary-element solution of the same map on a free (zero-padded) half-space,
    :func:`warptrunc.contact.solve_contact`; k_BEM by Barber's theorem (the stiffness of a rigid
    flat punch shaped like the real contact area).

:func:`compare_models` does it for one surface (yours, or a generated one) and returns a
:class:`ModelComparison`. :func:`compare_study` runs a study over WM surfaces
(:class:`StudyDesign`: the fractal dimension D, the map size L/W_r at a fixed pixel size (size
effect), the pixel size at a fixed L (grid convergence), seeds, the approaches) or over your map
(:class:`MapStudy`); every case is stored as one Parquet file of one row per approach
(SI unit suffixes in the column names) under ``OUT/cases/``, written atomically, and a rerun
skips the cases already stored. :func:`load_comparison` reads the rows back into a pandas
DataFrame and :func:`summarize` turns them into the tables (ratios to BEM, mean and range over
seeds; the exponent α of k ∝ F^α by the three routes, fitted over the approaches).

Store layout::

    OUT/study.json              format tag, the study's parameters (strict JSON)
    OUT/cases/<case_id>.parquet one row per approach (columns: CASE_COLUMNS)

Scaling: in the half-space (small-slope) approximation all three routes are linear in the
height scale at a fixed d/R_t (A unchanged, F ∝ R_t, k unchanged), so the ratios and α do not
depend on R_t; the study fixes R_t = ``StudyDesign.Rt_over_Wr``·W_r.

References
----------
R. Pohrt, V.L. Popov, Normal contact stiffness of elastic solids with fractal rough surfaces,
Phys. Rev. Lett. 108, 104301 (2012). doi:10.1103/PhysRevLett.108.104301

L. Pastewka, N. Prodanov, B. Lorenz, M.H. Müser, M.O. Robbins, B.N.J. Persson, Finite-size
scaling in the interfacial stiffness of rough elastic contacts, Phys. Rev. E 87, 062809 (2013).
doi:10.1103/PhysRevE.87.062809

J.R. Barber, Bounds on the electrical resistance between contacting elastic rough bodies,
Proc. R. Soc. A 459, 53 (2003). doi:10.1098/rspa.2002.1038

Every public name is importable from ``warptrunc.compare`` (imported on first use; the study's
design, ``design``, loads no Warp).
"""

from .._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "APPROACH_FRACTIONS": ".design",
        "CASE_COLUMNS": ".study",
        "FORMAT": ".study",
        "GOOD": ".models",
        "LOW_FRACTION": ".models",
        "MapStudy": ".design",
        "ModelComparison": ".models",
        "ROUTES": ".models",
        "STUDY_D": ".design",
        "StudyDesign": ".design",
        "compare_models": ".models",
        "compare_study": ".study",
        "load_comparison": ".study",
        "study_cases": ".study",
        "summarize": ".study",
    },
)
