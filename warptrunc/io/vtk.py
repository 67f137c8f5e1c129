# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""VTK export of a height map for ParaView: heights and the depth at which each point touches.

Written with NumPy only (no VTK or pyvista needed), as image data: XML ``.vti`` (raw appended
binary) or legacy ``.vtk`` (binary STRUCTURED_POINTS). Point ``(ix, iy)`` sits at
``(ix·dx, iy·dy, 0)`` (m) and VTK orders points with x fastest, so the point data arrays are
C-order ``ravel()`` of the ``(ny, nx)`` maps.

Point data (SI units):

``height`` (float32, m)
    z[iy, ix].
``first_contact_depth`` (float64, m)
    The smallest analysed depth ω_k at which the point is in contact (z ≥ z_top − ω_k), NaN
    when it never touches up to ω_max; threshold in ParaView to see the contact set at ω.
``contact_index`` (int32)
    That k (n + 1 when never in contact), as :func:`warptrunc.contact_index_map` returns it.

In ParaView: open the file, apply *Warp By Scalar* on ``height`` (with a scale factor for
vertical exaggeration) and colour by ``first_contact_depth``, or *Threshold* it at ω.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import warp as wp

from .._support.docs import fill_doc
from ..surface import Surface
from ..truncation.curve import contact_index_map, depth_grid
from ..truncation.settings import TRUNCATION_DOCS

__all__ = ["export_vtk"]

_ROWS = 512  # rows per write, so large maps are not copied whole


@fill_doc(TRUNCATION_DOCS)
def export_vtk(
    surface: Surface,
    path: str | Path,
    *,
    n_increments: int = 200,
    max_depth: float | None = None,
    max_depth_fraction: float = 1.0,
    device: wp.DeviceLike = None,
) -> Path:
    """Write ``surface`` with its first-contact depths as VTK image data.

    Parameters
    ----------
    {surface}
    path : path
        ``.vti`` (VTK XML image data) or ``.vtk`` (legacy structured points).
    {n_increments}
        The depths are ω_k = k·ω_max/n, k = 0..n, as in :func:`warptrunc.truncate`.
    {max_depth}
    {max_depth_fraction}
        1 by default, not :func:`truncate`'s 0.1: the exported contact index covers the whole
        height range, so every point gets the depth at which it touches.
    device : str, optional
        Warp device for the contact index; see :func:`warptrunc.resolve_device`.

    Returns
    -------
    Path
        The file written.

    Notes
    -----
    The file holds 4 + 8 + 4 = 16 bytes per pixel (1.6 GB for 10240²).
    """

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".vti", ".vtk"):
        raise ValueError(f"path must end in .vti or .vtk, got {str(path)!r}")
    depth = depth_grid(
        surface.Rt, n_increments, max_depth=max_depth, max_depth_fraction=max_depth_fraction
    )
    index = contact_index_map(surface, depth, device=device)
    lookup = np.append(depth, np.nan)  # index n + 1 → never in contact
    z = surface.heights
    arrays = [
        ("height", "Float32", "float", np.dtype("<f4"), lambda a, b: z[a:b]),
        (
            "first_contact_depth",
            "Float64",
            "double",
            np.dtype("<f8"),
            lambda a, b: lookup[index[a:b]],
        ),
        ("contact_index", "Int32", "int", np.dtype("<i4"), lambda a, b: index[a:b]),
    ]
    path.parent.mkdir(parents=True, exist_ok=True)
    if suffix == ".vti":
        _write_vti(path, surface, arrays)
    else:
        _write_legacy(path, surface, arrays)
    return path


def _chunks(ny: int, get, dtype: np.dtype):
    for a in range(0, ny, _ROWS):
        yield np.ascontiguousarray(get(a, min(ny, a + _ROWS)), dtype=dtype)


def _write_vti(path: Path, s: Surface, arrays) -> None:
    nx, ny = s.nx, s.ny
    n = nx * ny
    extent = f"0 {nx - 1} 0 {ny - 1} 0 0"
    lines = [
        '<?xml version="1.0"?>',
        '<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">',
        f'  <ImageData WholeExtent="{extent}" Origin="0 0 0" Spacing="{s.dx!r} {s.dy!r} {s.dx!r}">',
        f'    <Piece Extent="{extent}">',
        '      <PointData Scalars="height">',
    ]
    offset = 0
    for name, vtype, _, dt, _ in arrays:
        lines.append(
            f'        <DataArray type="{vtype}" Name="{name}" format="appended" offset="{offset}"/>'
        )
        offset += 8 + n * dt.itemsize
    lines += [
        "      </PointData>",
        "    </Piece>",
        "  </ImageData>",
        '  <AppendedData encoding="raw">',
    ]
    with path.open("wb") as fh:
        fh.write(("\n".join(lines) + "\n   _").encode())
        for _, _, _, dt, get in arrays:
            fh.write(np.uint64(n * dt.itemsize).astype("<u8").tobytes())
            for c in _chunks(ny, get, dt):
                fh.write(c.tobytes())
        fh.write(b"\n  </AppendedData>\n</VTKFile>\n")


def _write_legacy(path: Path, s: Surface, arrays) -> None:
    nx, ny = s.nx, s.ny
    head = (
        "# vtk DataFile Version 3.0\n"
        f"warptrunc surface {nx}x{ny}, dx = {s.dx!r} m, dy = {s.dy!r} m (SI units)\n"
        "BINARY\n"
        "DATASET STRUCTURED_POINTS\n"
        f"DIMENSIONS {nx} {ny} 1\n"
        "ORIGIN 0 0 0\n"
        f"SPACING {s.dx!r} {s.dy!r} {s.dx!r}\n"
        f"POINT_DATA {nx * ny}\n"
    )
    with path.open("wb") as fh:
        fh.write(head.encode())
        for name, _, ltype, dt, get in arrays:
            fh.write(f"SCALARS {name} {ltype} 1\nLOOKUP_TABLE default\n".encode())
            for c in _chunks(ny, get, dt.newbyteorder(">")):  # legacy binary is big-endian
                fh.write(c.tobytes())
            fh.write(b"\n")
