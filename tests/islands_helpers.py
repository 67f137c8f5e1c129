# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Independent references and test maps for the island tests (not a test module):
scipy.ndimage.label, scipy.sparse.csgraph for periodic maps, NumPy edge counting, and
hand-drawn masks and smooth surfaces."""

import numpy as np
import scipy.ndimage as ndi
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

import warptrunc

# --- references -------------------------------------------------------------------------------


def structure(connectivity):
    return ndi.generate_binary_structure(2, 1 if connectivity == 4 else 2)


def scipy_labels(mask, connectivity):
    return ndi.label(mask, structure(connectivity))


def graph_labels(mask, connectivity, periodic):
    """Components by scipy.sparse.csgraph on the pixel graph, numbered 1..n in raster order of
    first pixel (independent of ndimage and of our code; handles periodic maps)."""
    ny, nx = mask.shape
    ids = np.arange(ny * nx).reshape(ny, nx)
    offsets = [(0, 1), (1, 0)] + ([(1, 1), (1, -1)] if connectivity == 8 else [])
    rows, cols = [], []
    for dy, dx in offsets:
        if periodic:
            other = np.roll(ids, (-dy, -dx), axis=(0, 1))
            om = np.roll(mask, (-dy, -dx), axis=(0, 1))
            ok = mask & om
            rows.append(ids[ok])
            cols.append(other[ok])
        else:
            y0, y1 = max(0, -dy), ny - max(0, dy)
            x0, x1 = max(0, -dx), nx - max(0, dx)
            a = ids[y0:y1, x0:x1]
            b = ids[y0 + dy : y1 + dy, x0 + dx : x1 + dx]
            ok = mask[y0:y1, x0:x1] & mask[y0 + dy : y1 + dy, x0 + dx : x1 + dx]
            rows.append(a[ok])
            cols.append(b[ok])
    r, c = np.concatenate(rows), np.concatenate(cols)
    g = coo_matrix((np.ones(r.size), (r, c)), shape=(ny * nx, ny * nx))
    _, comp = connected_components(g, directed=False)
    comp = comp.reshape(ny, nx)
    out = np.zeros((ny, nx), np.int32)
    flat_c, flat_m = comp.ravel(), mask.ravel()
    seen = {}
    for i in np.flatnonzero(flat_m):
        seen.setdefault(flat_c[i], len(seen) + 1)
    lut = np.zeros(comp.max() + 1, np.int32)
    for cc, lab in seen.items():
        lut[cc] = lab
    out[mask] = lut[comp[mask]]
    return out, len(seen)


def edge_counts(labels, n, periodic):
    """Per-label (pixels, edges crossed along x, edges crossed along y) by NumPy."""
    fg = labels > 0
    if periodic:
        nb = {
            "x": [np.roll(fg, 1, axis=1), np.roll(fg, -1, axis=1)],
            "y": [np.roll(fg, 1, axis=0), np.roll(fg, -1, axis=0)],
        }
    else:
        p = np.pad(fg, 1)
        nb = {"x": [p[1:-1, :-2], p[1:-1, 2:]], "y": [p[:-2, 1:-1], p[2:, 1:-1]]}
    ex = sum((fg & ~q).astype(int) for q in nb["x"])
    ey = sum((fg & ~q).astype(int) for q in nb["y"])
    area = np.bincount(labels.ravel(), minlength=n + 1)[1:]
    ex = np.bincount(labels.ravel(), weights=ex.ravel(), minlength=n + 1)[1:]
    ey = np.bincount(labels.ravel(), weights=ey.ravel(), minlength=n + 1)[1:]
    return area, ex.astype(np.int64), ey.astype(np.int64)


def islands_minus_holes(mask, connectivity):
    _, n = scipy_labels(mask, connectivity)
    bg, nb = ndi.label(~mask, structure(12 - connectivity))
    border = np.unique(np.concatenate([bg[0], bg[-1], bg[:, 0], bg[:, -1]]))
    return n - (nb - np.count_nonzero(border))


def thresholds(surface, depth):
    return (np.float64(surface.heights.max()) - np.asarray(depth)).astype(np.float32)


# --- test masks and surfaces --------------------------------------------------------------------


def spiral(n):
    """A one-pixel-wide square spiral with one-pixel gaps (a single, very long island)."""
    m = np.zeros((n, n), bool)
    dirs = [(0, 1), (1, 0), (0, -1), (-1, 0)]
    y = x = d = 0
    m[0, 0] = True
    path = [(0, 0)]
    turns = 0
    while turns < 2:
        dy, dx = dirs[d]
        y1, x1, y2, x2 = y + dy, x + dx, y + 2 * dy, x + 2 * dx
        inside2 = 0 <= y2 < n and 0 <= x2 < n
        if 0 <= y1 < n and 0 <= x1 < n and not m[y1, x1] and not (inside2 and m[y2, x2]):
            y, x = y1, x1
            m[y, x] = True
            path.append((y, x))
            turns = 0
        else:
            d = (d + 1) % 4
            turns += 1
    return m, path


def rings(n=48):
    yy, xx = np.mgrid[:n, :n] - (n - 1) / 2
    r = np.hypot(yy, xx)
    return ((r.astype(int) % 6) < 2) & (r < n / 2 - 1)


def hand_masks():
    checker = (np.add.outer(np.arange(16), np.arange(20)) % 2).astype(bool)
    rect = np.zeros((20, 24), bool)
    rect[2:7, 3:11] = True
    rect[10:18, 15:22] = True
    rect[12:14, 0:24] = True
    diag = np.zeros((6, 6), bool)
    diag[[0, 1, 2, 3, 4, 5], [0, 1, 2, 3, 4, 5]] = True
    diag[0, 5] = diag[5, 0] = True
    return {
        "checkerboard": checker,
        "rings": rings(),
        "spiral": spiral(41)[0],
        "empty": np.zeros((9, 13), bool),
        "full": np.ones((9, 13), bool),
        "rectangles": rect,
        "diagonals": diag,
        "single": np.ones((1, 1), bool),
        "row": np.array([[1, 1, 0, 1, 0, 0, 1]], bool),
        "column": np.array([[1], [0], [1], [1]], bool),
    }


def smooth_surface(n=64, nx=None, sigma=2.5, seed=0, dx=1e-6):
    rng = np.random.default_rng(seed)
    z = ndi.gaussian_filter(rng.standard_normal((n, nx or n)), sigma, mode="wrap")
    return warptrunc.from_heights((z * 1e-6).astype(np.float32), dx)
