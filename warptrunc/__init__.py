# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""warptrunc: normal contact stiffness of rough multiscale surfaces by truncation analysis.

Symbols (paper notation → code name, SI unit); the full mapping, with the names that collide
between the paper and the code, is the glossary (``docs/guide/glossary.md``):

======  ========================  ==========================================
D       ``D``                     fractal dimension D_in (dimensionless, 2 < D < 3)
W_r     ``Wr``                    roll-off wavelength (m)
W_c     ``Wc``                    cut-off wavelength (m)
γ       ``gamma``                 WM frequency density (dimensionless, > 1)
M       ``M``                     number of superposed ridges
G       ``G``                     topothesy (m)
R_t     ``Rt``                    peak-to-valley height (m)
δ       ``delta``                 relative roughness R_t/W_r (dimensionless)
ω       ``depth``                 truncation depth from the top (m)
A_c     ``contact_area``          truncated (contact) area A′ (m²)
A       ``apparent_area``         apparent area Lx·Ly (m²)
k       ``stiffness``             normal contact stiffness, Eq. 2 (N/m)
F       ``load``                  normal load (N)
E, ν    ``E``, ``nu``             Young's modulus (Pa), Poisson's ratio of the rough body
E_r′    ``contact_modulus``       contact modulus E* = [(1−ν²)/E + (1−ν_i²)/E_i]⁻¹ (Pa)
β′      ``beta_prime``            geometric factor of Eq. 2 (dimensionless)
E_c/E   ``Ec_over_E``             (E*/E)·β′·√(A_c/A), E the Young's modulus (dimensionless)
E_c/E*  ``Ec_over_Estar``         β′·√(A_c/A), Eq. 3, E* the contact modulus (dimensionless)
α, β    ``alpha``, ``beta``       exponent and amplitude of E_c/E = β[F/(E·A)]^α (the paper's)
β*      ``beta_contact_modulus``  amplitude of E_c/E* = β*[F/(E·A)]^α, β·E/E*
======  ========================  ==========================================

One public function per operation: generate :func:`wm_surface`, truncate :func:`truncate`,
label :func:`label_islands`, fit :func:`fit_power_law`, solve a contact :func:`solve_contact`.

``import warptrunc`` is light: every public name (and subpackage) is imported on first use
(PEP 562), so ``import warptrunc`` and ``warptrunc --help`` load neither Warp nor NumPy; the
first computing call loads Warp, plotting and rendering load matplotlib and pyvista.

The public names are written once, in ``_EXPORTS`` (name → the module that defines it):
``__all__``, ``dir()`` and attribute access all come from it
(:func:`warptrunc._support.exports.lazy_exports`); the public subpackages and modules are
those of the package's folder. Type checkers see the names through the module
``__getattr__`` (typed ``Any``); import from the defining module for precise types.
"""

import sys as _sys
import types as _types
from typing import Any as _Any

from ._support.checkout import map_source_kernels as _map_source_kernels

_map_source_kernels(__name__, __path__)

from ._support.exports import lazy_exports as _lazy_exports
from ._support.provenance import __version__  # noqa: F401 (re-exported)

_EXPORTS = {
    "Analysis": ".analysis",
    "BemCheck": ".contact.check",
    "Calibration": ".calibrate",
    "CalibrationError": ".calibrate",
    "CalibrationTarget": ".calibrate",
    "Descriptors": ".descriptors",
    "FractalFit": ".fractal",
    "IndentProtocol": ".indent",
    "IndentationResult": ".indent",
    "Indicators": ".islands",
    "IslandCurve": ".islands",
    "Islands": ".islands",
    "Material": ".material",
    "PowerLawFit": ".stiffness",
    "SolverSettings": ".contact.settings",
    "StiffnessCurve": ".stiffness",
    "TABLE1": ".presets",
    "Surface": ".surface",
    "TruncationCurve": ".truncation",
    "WMSpec": ".wm_params",
    "analyze": ".analysis",
    "applicable_depth": ".islands",
    "bem_check": ".contact.check",
    "calibrate": ".calibrate",
    "contact_index_map": ".truncation",
    "depth_grid": ".truncation",
    "describe": ".descriptors",
    "export_vtk": ".io.vtk",
    "fit_power_law": ".stiffness",
    "fractal_dimension": ".fractal",
    "fractal_dimensions": ".fractal",
    "from_heights": ".surface",
    "indent": ".indent",
    "island_curve": ".islands",
    "label_islands": ".islands",
    "preset": ".presets",
    "read_height_map": ".io",
    "resolve_device": "._support.device",
    "solve_contact": ".contact.curve",
    "stiffness_curve": ".stiffness",
    "truncate": ".truncation",
    "wm_surface": ".wm",
    "write_height_map": ".io",
}
"""Public name → the module that defines it (imported on first access, PEP 562): the one list
of the package's face."""

__all__, __getattr__, __dir__ = _lazy_exports(__name__, _EXPORTS, submodules=True, hide={"kernels"})


class _Package(_types.ModuleType):
    """The package module: keeps a public function that shares its subpackage's name.

    The import system binds every imported submodule as an attribute of its package; for
    ``calibrate`` and ``indent`` (functions of the packages ``warptrunc.calibrate`` and
    ``warptrunc.indent``) the function must stay bound.
    """

    def __setattr__(self, name: str, value: _Any) -> None:
        if isinstance(value, _types.ModuleType) and _EXPORTS.get(name) == f".{name}":
            if name not in vars(value):  # a package exporting lazily: bound on first access
                return
            value = getattr(value, name)
        super().__setattr__(name, value)


_sys.modules[__name__].__class__ = _Package
