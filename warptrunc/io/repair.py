# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Missing points and levelling: fill NaN points, subtract the least-squares plane."""

from __future__ import annotations

import numpy as np

FILL_METHODS = ("nearest", "harmonic", "mean")
"""Fill methods of :func:`fill_missing` (``method=``)."""


def fill_missing(z: np.ndarray, valid: np.ndarray, *, method: str = "nearest") -> np.ndarray:
    """Fill the points where ``valid`` is False.

    Parameters
    ----------
    z : (ny, nx) ndarray
        Heights (m); values where ``valid`` is False are ignored.
    valid : (ny, nx) bool ndarray
        True where a height was measured.
    method : {"nearest", "harmonic", "mean"}
        ``"nearest"``: the height of the nearest measured pixel (Euclidean distance in pixel
        units, ties broken by ``scipy.ndimage.distance_transform_edt``). ``"harmonic"``: the
        solution of Laplace's equation ∇²z = 0 on the missing points with the measured points as
        Dirichlet data (5-point stencil, reflecting edges), the smoothest fill; a component of
        missing points with no measured neighbour anywhere falls back to the mean.
        ``"mean"``: the mean of the measured heights.

    Returns
    -------
    (ny, nx) float64 ndarray
        Filled heights (m); measured points are unchanged.
    """
    z = np.array(z, dtype=np.float64)
    valid = np.asarray(valid, dtype=bool)
    if valid.shape != z.shape:
        raise ValueError(f"valid must have the shape of z {z.shape}, got {valid.shape}")
    if method not in FILL_METHODS:
        raise ValueError(f"method must be one of {FILL_METHODS}, got {method!r}")
    bad = ~valid
    if not bad.any():
        return z
    if not valid.any():
        raise ValueError("cannot fill: every point is missing")
    if method == "mean":
        z[bad] = z[valid].mean()
        return z
    from scipy import ndimage

    if method == "nearest":
        idx = ndimage.distance_transform_edt(bad, return_distances=False, return_indices=True)
        return z[tuple(idx)]
    # harmonic: sparse Laplace solve on the missing pixels only
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve

    ny, nx = z.shape
    unknown = np.flatnonzero(bad.ravel())
    index = -np.ones(z.size, dtype=np.int64)
    index[unknown] = np.arange(unknown.size)
    iy, ix = np.divmod(unknown, nx)
    rows, cols, vals = [], [], []
    rhs = np.zeros(unknown.size)
    diag = np.zeros(unknown.size)
    zf = np.where(valid, z, 0.0).ravel()
    for dy_, dx_ in ((-1, 0), (1, 0), (0, -1), (0, 1)):
        jy, jx = iy + dy_, ix + dx_
        inside = (jy >= 0) & (jy < ny) & (jx >= 0) & (jx < nx)
        k = np.flatnonzero(inside)
        nb = jy[k] * nx + jx[k]
        diag[k] += 1.0
        nb_unknown = index[nb] >= 0
        rows.append(k[nb_unknown])
        cols.append(index[nb][nb_unknown])
        vals.append(-np.ones(int(nb_unknown.sum())))
        np.add.at(rhs, k[~nb_unknown], zf[nb[~nb_unknown]])
    # a tiny diagonal shift keeps components without measured neighbours solvable; they are
    # then set to the mean below
    a = coo_matrix(
        (
            np.concatenate([diag + 1e-12, *vals]),
            (
                np.concatenate([np.arange(unknown.size), *rows]),
                np.concatenate([np.arange(unknown.size), *cols]),
            ),
        ),
        shape=(unknown.size, unknown.size),
    ).tocsr()
    sol = spsolve(a, rhs)
    labels, _ = ndimage.label(bad)
    touching = np.unique(labels[ndimage.binary_dilation(valid) & bad])
    isolated = ~np.isin(labels.ravel()[unknown], touching)
    sol[isolated] = z[valid].mean()
    out = z.ravel()
    out[unknown] = sol
    return out.reshape(ny, nx)


def level_plane(
    z: np.ndarray, dx: float = 1.0, dy: float = 1.0, *, mask: np.ndarray | None = None
) -> np.ndarray:
    """Subtract the least-squares plane a + b·x + c·y fitted on the points of ``mask``.

    Parameters
    ----------
    z : (ny, nx) ndarray
        Heights (m); may hold NaN outside ``mask``.
    dx, dy : float
        Pixel spacings (m); they do not change the result, only the fitted slopes' units.
    mask : (ny, nx) bool ndarray, optional
        Points used in the fit; default: the finite points.

    Returns
    -------
    (ny, nx) float64 ndarray
        ``z`` minus the plane (NaN stays NaN); the mean over ``mask`` is zero.
    """
    z = np.asarray(z, dtype=np.float64)
    if mask is None:
        mask = np.isfinite(z)
    ny, nx = z.shape
    yy, xx = np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")
    a = np.stack([np.ones(int(mask.sum())), xx[mask], yy[mask]], axis=1)
    coef, *_ = np.linalg.lstsq(a, z[mask], rcond=None)
    return z - (coef[0] + coef[1] * xx + coef[2] * yy)
