# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""warptrunc: normal contact stiffness of rough multiscale surfaces by truncation analysis.

Symbols (paper notation → code name, SI unit):

======  =====================  ==========================================
D       ``D``                  fractal dimension (dimensionless, 2 < D < 3)
W_r     ``Wr``                 roll-off wavelength (m)
W_c     ``Wc``                 cut-off wavelength (m)
γ       ``gamma``              WM frequency density (dimensionless, > 1)
M       ``M``                  number of superposed ridges
G       ``G``                  topothesy (m)
R_t     ``Rt``                 peak-to-valley height (m)
ω       ``depth``              truncation depth from the top (m)
A_c     ``contact_area``       truncated (contact) area (m²)
A       ``apparent_area``      apparent area Lx·Ly (m²)
k       ``stiffness``          normal contact stiffness (N/m)
F       ``load``               normal load (N)
E, ν    ``E``, ``nu``          Young's modulus (Pa), Poisson's ratio of the rough body
α, β    ``alpha``, ``beta``    power-law exponent and amplitude of E_c/E = β[F/(EA)]^α
======  =====================  ==========================================

``import warptrunc`` is light: every public name (and subpackage) is imported on first use
(PEP 562), so ``import warptrunc`` and ``warptrunc --help`` load neither Warp nor NumPy; the
first computing call loads Warp, plotting and rendering load matplotlib and pyvista.
"""

import importlib
import sys
import types
from typing import TYPE_CHECKING, Any

from ._source import map_source_kernels as _map_source_kernels

_map_source_kernels(__name__, __path__)

_EXPORTS = {
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
    "stiffness_curve": ".stiffness",
    "truncate": ".truncation",
    "wm_surface": ".wm",
    "write_height_map": ".io",
}
"""Public name → the module that defines it (imported on first access, PEP 562)."""

_SUBMODULES = frozenset({
    "calibrate", "cli", "contact", "descriptors", "fractal", "indent", "io", "islands",
    "material", "params", "plot", "presets", "render", "reproduce", "robust", "spectra",
    "stiffness", "surface", "sweep", "truncation", "wm", "wm_params",
})  # fmt: skip


def __getattr__(name: str) -> Any:
    """Import a public name (or a subpackage) on first access."""
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name], __name__), name)
    elif name in _SUBMODULES:
        value = importlib.import_module(f".{name}", __name__)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


class _Package(types.ModuleType):
    """The package module: keeps a public function that shares its module's name.

    The import system binds every imported submodule as an attribute of its package; for
    ``calibrate`` (function of module ``warptrunc.calibrate``) the function must stay bound.
    """

    def __setattr__(self, name: str, value: Any) -> None:
        if isinstance(value, types.ModuleType) and _EXPORTS.get(name) == f".{name}":
            value = getattr(value, name)
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__) | _SUBMODULES)


if TYPE_CHECKING:  # for type checkers and IDEs: the same names, imported eagerly
    from ._support.device import resolve_device  # after the kernels mapping above
    from .calibrate import Calibration, CalibrationError, CalibrationTarget, calibrate
    from .contact.check import BemCheck, bem_check
    from .contact.settings import SolverSettings
    from .descriptors import Descriptors, describe
    from .fractal import FractalFit, fractal_dimension, fractal_dimensions
    from .indent import IndentationResult, IndentProtocol, indent
    from .io import read_height_map, write_height_map
    from .io.vtk import export_vtk
    from .islands import (
        Indicators,
        IslandCurve,
        Islands,
        applicable_depth,
        island_curve,
        label_islands,
    )
    from .material import Material
    from .presets import TABLE1, preset
    from .stiffness import PowerLawFit, StiffnessCurve, fit_power_law, stiffness_curve
    from .surface import Surface, from_heights
    from .truncation import TruncationCurve, contact_index_map, depth_grid, truncate
    from .wm import wm_surface
    from .wm_params import WMSpec

__version__ = "0.1.0"

__all__ = [
    "BemCheck",
    "Calibration",
    "CalibrationError",
    "CalibrationTarget",
    "Descriptors",
    "FractalFit",
    "IndentProtocol",
    "IndentationResult",
    "Indicators",
    "IslandCurve",
    "Islands",
    "Material",
    "PowerLawFit",
    "SolverSettings",
    "StiffnessCurve",
    "Surface",
    "TABLE1",
    "TruncationCurve",
    "WMSpec",
    "applicable_depth",
    "bem_check",
    "calibrate",
    "contact_index_map",
    "depth_grid",
    "describe",
    "export_vtk",
    "fit_power_law",
    "fractal_dimension",
    "fractal_dimensions",
    "from_heights",
    "indent",
    "island_curve",
    "label_islands",
    "preset",
    "read_height_map",
    "resolve_device",
    "stiffness_curve",
    "truncate",
    "wm_surface",
    "write_height_map",
]
