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

``import warptrunc`` loads NumPy and Warp only; plotting and rendering import matplotlib and
pyvista when first used.
"""

from ._source import map_source_kernels as _map_source_kernels

_map_source_kernels(__name__, __path__)

from ._device import resolve_device  # after the kernels mapping above
from .calibrate import Calibration, CalibrationError, CalibrationTarget, calibrate
from .contact.check import BemCheck, bem_check
from .descriptors import Descriptors, describe
from .fractal import FractalFit, fractal_dimension, fractal_dimensions
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
from .stiffness import Material, PowerLawFit, StiffnessCurve, fit_power_law, stiffness_curve
from .surface import Surface, from_heights
from .truncation import TruncationCurve, contact_index_map, depth_grid, truncate
from .wm import wm_surface

__version__ = "0.1.0"

__all__ = [
    "BemCheck",
    "Calibration",
    "CalibrationError",
    "CalibrationTarget",
    "Descriptors",
    "FractalFit",
    "Indicators",
    "IslandCurve",
    "Islands",
    "Material",
    "PowerLawFit",
    "StiffnessCurve",
    "Surface",
    "TruncationCurve",
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
    "island_curve",
    "label_islands",
    "read_height_map",
    "resolve_device",
    "stiffness_curve",
    "truncate",
    "wm_surface",
    "write_height_map",
]
