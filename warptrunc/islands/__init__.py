# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Contact islands: labelling, island statistics at every depth, slit-island analysis and the
applicable truncation depth (paper §4.3, Fig. 8, Table 2, Eq. 5).

Kernels: ``warptrunc.kernels.label`` (union-find labelling of one mask),
``warptrunc.kernels.islands`` (carried forest across depths, per-island statistics) and
``warptrunc.kernels.euler`` (total perimeter and Euler characteristic by histograms).

Conventions
-----------
*Contact* at depth ω: ``z >= z_top − ω`` compared in float32, exactly as
:func:`warptrunc.truncate`.

*Connectivity* 4 (default) or 8. Two contact pixels are in one island when they share an edge
(4) or an edge or a corner (8). The default is 4 because two pixels touching at a corner only
meet at a point of zero width: for contact they are separate spots, and the truncated area
between them does not carry load across. With 4-connectivity of the contact set, holes are
8-connected, and vice versa; the Euler characteristic below follows the same pairing.

*Labels* are 1..n in raster order (C order, x fastest) of each island's first pixel, 0 for
non-contact. They do not depend on the device or on thread scheduling, and equal
``scipy.ndimage.label`` with the matching structure.

*Perimeter* of an island: the total length of the pixel edges between one of its pixels and a
non-contact pixel, dy per edge crossed along x and dx per edge crossed along y; the shores of
enclosed holes count too. Outside a bounded domain counts as non-contact, so an island cut by
the border is closed along it; with ``periodic=True`` the map wraps around instead. This
"city-block" length overestimates an oblique boundary (by 4/π on average for isotropic
boundaries, up to √2), a factor that does not depend on island size, so it moves the
intercept of a slit-island fit, not its exponent.

*Euler characteristic* χ of the contact set: islands minus enclosed holes (non-contact
components not touching the border, connectivity 8 for contact connectivity 4 and vice
versa). With ``periodic=True``, χ is that of the set on the torus (χ = islands − holes only for
sets that do not wrap around).

Every public name is importable from ``warptrunc.islands`` (imported on first use, so that the
parameters of ``settings`` load no Warp).
"""

from .._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "ISLANDS_TRUNCATION": ".settings",
        "MIN_ISLANDS": ".settings",
        "MIN_PIXELS": ".settings",
        "IndicatorSettings": ".settings",
        "Indicators": ".results",
        "IslandCurve": ".results",
        "IslandSettings": ".settings",
        "IslandSizes": ".results",
        "Islands": ".results",
        "SlitIslandFit": ".results",
        "TopologyCurve": ".results",
        "applicable_depth": ".fits",
        "island_counts_device": ".depths",
        "island_curve": ".depths",
        "islands_at_depths": ".depths",
        "label_islands": ".labelling",
        "slit_bootstrap": ".fits",
        "slit_island_fit": ".fits",
        "topology_curve": ".topology",
    },
)
__all__ = [n for n in __all__ if n != "island_counts_device"]  # the internal fast path
