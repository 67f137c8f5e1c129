# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Measured height maps as input: NumPy and text matrices built in, instrument files optional.

Built-in formats (no extra dependency):

``.npz`` / ``.npy`` written by :func:`warptrunc.write_height_map`
    Pixel sizes and parameters come from the file (``.npy`` from its ``.json`` sidecar).
plain ``.npy`` / ``.npz`` arrays
    A 2-D array ``z[iy, ix]``; an ``.npz`` must hold one array or one named ``heights`` or ``z``.
    The pixel spacing must be given (``dx=``, ``dy=``) and heights are multiplied by
    ``height_unit`` to get metres.
``.csv`` / ``.txt`` / ``.tsv`` matrices
    One row of the map per line (row ``iy``, columns ``ix``), separated by commas, semicolons,
    tabs or blanks. Leading header lines are read as ``key=value`` (or ``key: value``, an
    optional ``#`` in front); the keys ``dx``, ``dy``, ``pixel size``, ``height unit``,
    ``height conversion factor (-> m)``, ``nx``/``w`` and ``ny``/``h`` are understood (lengths
    may carry a unit: m, mm, µm/um, nm, pm). :func:`write_height_map` writes this format.
    ``nan`` and empty fields are missing points.

Instrument formats (``.sur``, ``.x3p``, ``.datx``, ``.plu``, ``.opd``, ``.vk4``, ``.gwy``,
``.di``, ``.top``, ``.asc``, ... over forty: :data:`INSTRUMENT_SUFFIXES`) are read through
SurfaceTopography (MIT licence), a dependency of warptrunc imported only when such a file is
read. A file that no reader recognises is refused with the formats that are read. Units and pixel sizes come from the file's metadata; SurfaceTopography indexes heights
as ``h[ix, iy]``, which is transposed here to ``z[iy, ix]``.

Missing points (NaN) are never ignored: :func:`read_scan` returns them with a validity mask,
and :func:`read_height_map` either raises (``missing="error"``, the default, with the count
and the options) or fills them (``missing="fill"``) and records the count in
``Surface.params["n_missing"]``.

Layout: :class:`Scan` and the known suffixes in ``scan``; :func:`fill_missing` and
:func:`level_plane` in ``repair``; the NumPy and text readers in ``builtin``; the
SurfaceTopography reader in ``instrument``; :func:`read_scan`, :func:`read_height_map` and
:func:`write_height_map` in ``read``; the reading options as a parameter object
(:class:`ReadOptions`, no Warp) in ``options``. Every name is importable from ``warptrunc.io``
(imported on first use).
"""

from .._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "FILL_METHODS": ".repair",
        "ENGINES": ".options",
        "INSTRUMENT_SUFFIXES": ".scan",
        "MissingExtraError": ".scan",
        "NUMPY_SUFFIXES": ".scan",
        "ReadOptions": ".options",
        "Scan": ".scan",
        "TEXT_SUFFIXES": ".scan",
        "fill_missing": ".repair",
        "level_plane": ".repair",
        "read_height_map": ".read",
        "read_scan": ".read",
        "write_height_map": ".read",
    },
)
