# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Contact islands at every truncation depth from one carried union-find forest, and per-island
area and perimeter.

Launched by ``warptrunc.islands``. Union-find functions come from
``warptrunc.kernels.label`` (roots are the smallest flat index of their island).

Carried forest. Every pixel has a contact index ``idx[i]`` (first depth increment at which it
touches; ``n1 = len(depth)`` when never). The driver sorts the pixels by contact index (stable
radix sort, so each *bucket* of pixels sharing an index is in raster order) and, for
k = 0, 1, ..., launches ``hook_depth_kernel`` over bucket k only: each new pixel unites with
its already active neighbours. Islands only merge as the depth grows, so the forest is never
rebuilt. A root that gets hooked at increment k records ``link[root] = k``; a pixel is then an
island root for the increments ``idx[i] <= k < link[i]``, and ``island_count_diff_kernel``
turns that into a difference array whose cumulative sum is the island count at every depth.

Per-island statistics along the way (optional): integer accumulators ``area``,
``edges_x``, ``edges_y`` live on the roots. After the unions of increment k, the
accumulators of the roots hooked at k are added to their new roots
(``merge_linked_stride_kernel``), then each new pixel adds 1 to the area and its change of
boundary edges (``add_pixels_kernel``), then ``compact_roots_kernel`` keeps the surviving roots
and adds them to the per-depth area histogram, slit-island sums and Σ√(island area). The number of roots stays
on the device, so no increment waits for the host. ``edges_x`` counts pixel edges crossed along x (vertical
edges, length dy), ``edges_y`` edges crossed along y (length dx), between a contact pixel and a
non-contact pixel or the domain border (unless periodic). Integer atomics only: results are
identical on every device.

Grids: 1-D, one thread per listed pixel (a bucket, or candidate roots), or 2-D one thread per
(row, segment) for ``island_stats_kernel``.
"""

import warp as wp
from warptrunc.kernels.label import find_root, find_root_readonly, unite, wrap_index

wp.set_module_options({"enable_backward": False})


@wp.func
def offset_y(d: int) -> int:
    """Row offset of neighbour d: 0 right, 1 up, 2 left, 3 down, 4..7 diagonals."""
    r = int(0)
    if d == 1 or d == 4 or d == 5:
        r = 1
    elif d == 3 or d == 6 or d == 7:
        r = -1
    return r


@wp.func
def offset_x(d: int) -> int:
    """Column offset of neighbour d (see ``offset_y``)."""
    r = int(0)
    if d == 0 or d == 4 or d == 6:
        r = 1
    elif d == 2 or d == 5 or d == 7:
        r = -1
    return r


@wp.kernel
def init_forest_kernel(n1: int, parent: wp.array[wp.int32], link: wp.array[wp.int32]):
    """One thread per pixel: every pixel its own root, never hooked (``link = n1``)."""
    i = wp.tid()
    parent[i] = i
    link[i] = n1


@wp.kernel
def bucket_start_kernel(keys: wp.array[wp.int32], count: int, first: wp.array[wp.int32]):
    """One thread per sorted position t: ``first[k]`` = first position with key >= k, for
    k = 0..len(first) - 1 (``count`` when there is none)."""
    t = wp.tid()
    k = keys[t]
    lo = int(0)
    if t > 0:
        lo = keys[t - 1] + 1
    for kk in range(lo, wp.min(k, first.shape[0] - 1) + 1):
        first[kk] = t
    if t == count - 1:
        for kk in range(k + 1, first.shape[0]):
            first[kk] = count


@wp.kernel
def hook_depth_kernel(
    order: wp.array[wp.int32],
    start: int,
    idx: wp.array[wp.int32],
    k: int,
    ny: int,
    nx: int,
    connectivity: int,
    periodic: int,
    parent: wp.array[wp.int32],
    link: wp.array[wp.int32],
):
    """One thread per pixel of bucket k (``order[start + t]``): unite with every neighbour
    already in contact (index < k), and with new neighbours (index == k) of smaller flat index,
    so each edge is tried once; a root that gets hooked records ``link[root] = k``."""
    t = wp.tid()
    i = order[start + t]
    iy = i // nx
    ix = i - iy * nx
    for d in range(connectivity):
        j = wrap_index(iy + offset_y(d), ix + offset_x(d), ny, nx, periodic)
        if j >= 0 and j != i:
            kj = idx[j]
            if kj < k or (kj == k and j < i):
                hooked = unite(parent, i, j)
                if hooked >= 0:
                    link[hooked] = k


@wp.kernel
def island_count_diff_kernel(
    idx: wp.array[wp.int32],
    link: wp.array[wp.int32],
    n1: int,
    diff: wp.array[wp.int64],
):
    """One thread per pixel: a pixel is a root for ``idx <= k < link``: +1 at idx, -1 at link.
    Only the pixels that start an island (few) issue atomics."""
    i = wp.tid()
    a = idx[i]
    if a < n1:
        l = link[i]
        if l > a:
            wp.atomic_add(diff, a, wp.int64(1))
            if l < n1:
                wp.atomic_add(diff, l, wp.int64(-1))


@wp.func
def candidate(
    roots: wp.array[wp.int32], n_roots: int, order: wp.array[wp.int32], start: int, t: int
) -> int:
    """Candidate t: the previous roots first, then the pixels of the current bucket."""
    c = int(0)
    if t < n_roots:
        c = roots[t]
    else:
        c = order[start + t - n_roots]
    return c


@wp.func
def active_at(idx: wp.array[wp.int32], j: int, k: int) -> int:
    """1 when pixel j (-1: outside the domain) is in contact at increment k."""
    r = int(0)
    if j >= 0:
        if idx[j] <= k:
            r = 1
    return r


@wp.func
def active_before(idx: wp.array[wp.int32], j: int, k: int) -> int:
    """1 when pixel j (-1: outside the domain) was in contact before increment k."""
    r = int(0)
    if j >= 0:
        if idx[j] < k:
            r = 1
    return r


@wp.kernel
def add_pixels_kernel(
    order: wp.array[wp.int32],
    start: int,
    idx: wp.array[wp.int32],
    k: int,
    ny: int,
    nx: int,
    periodic: int,
    parent: wp.array[wp.int32],
    area: wp.array[wp.int32],
    edges_x: wp.array[wp.int32],
    edges_y: wp.array[wp.int32],
):
    """One thread per pixel of bucket k: area += 1 and the change of boundary edges,
    (2 − active neighbours − neighbours active before k) per axis, on the pixel's root."""
    t = wp.tid()
    i = order[start + t]
    iy = i // nx
    ix = i - iy * nx
    r = find_root(parent, i)
    jr = wrap_index(iy, ix + 1, ny, nx, periodic)
    jl = wrap_index(iy, ix - 1, ny, nx, periodic)
    ju = wrap_index(iy + 1, ix, ny, nx, periodic)
    jd = wrap_index(iy - 1, ix, ny, nx, periodic)
    dex = 2 - active_at(idx, jr, k) - active_at(idx, jl, k)
    dex -= active_before(idx, jr, k) + active_before(idx, jl, k)
    dey = 2 - active_at(idx, ju, k) - active_at(idx, jd, k)
    dey -= active_before(idx, ju, k) + active_before(idx, jd, k)
    wp.atomic_add(area, r, 1)
    if dex != 0:
        wp.atomic_add(edges_x, r, dex)
    if dey != 0:
        wp.atomic_add(edges_y, r, dey)


@wp.kernel
def merge_linked_stride_kernel(
    roots: wp.array[wp.int32],
    counts: wp.array[wp.int32],
    kprev: int,
    order: wp.array[wp.int32],
    start: int,
    count: int,
    link: wp.array[wp.int32],
    k: int,
    n_threads: int,
    parent: wp.array[wp.int32],
    area: wp.array[wp.int32],
    edges_x: wp.array[wp.int32],
    edges_y: wp.array[wp.int32],
):
    """``merge_linked_kernel`` without a host-known candidate count: ``n_threads`` threads
    stride over the ``counts[kprev]`` previous roots (read on the device; none when
    ``kprev < 0``) and the ``count`` pixels of bucket k."""
    g = wp.tid()
    nr = int(0)
    if kprev >= 0:
        nr = counts[kprev]
    for t in range(g, nr + count, n_threads):
        c = candidate(roots, nr, order, start, t)
        if link[c] == k:
            a = area[c]
            if a != 0:
                r = find_root(parent, c)
                wp.atomic_add(area, r, a)
                wp.atomic_add(edges_x, r, edges_x[c])
                wp.atomic_add(edges_y, r, edges_y[c])


SQRT_SCALE = wp.constant(wp.float64(1 << 30))
"""Fixed-point scale of the Σ√A_i accumulator (units of pixel^½): ≤ 2^31 pixels give
Σ√a ≤ 2^31, i.e. ≤ 2^61 in int64, and each term is rounded to 2^-31 pixel^½."""


@wp.func
def sqrt_fixed(a: int) -> wp.int64:
    """√a (a in pixels) in fixed point, rounded to the nearest 1/SQRT_SCALE."""
    return wp.int64(wp.sqrt(wp.float64(a)) * SQRT_SCALE + wp.float64(0.5))


@wp.kernel
def compact_roots_kernel(
    roots: wp.array[wp.int32],
    kprev: int,
    order: wp.array[wp.int32],
    start: int,
    count: int,
    parent: wp.array[wp.int32],
    area: wp.array[wp.int32],
    edges_x: wp.array[wp.int32],
    edges_y: wp.array[wp.int32],
    k: int,
    min_pixels: int,
    aspect: wp.float64,
    n_blocks: int,
    counts: wp.array[wp.int32],
    out_roots: wp.array[wp.int32],
    hist: wp.array2d[wp.int64],
    sums: wp.array2d[wp.float64],
    sqrt_sums: wp.array[wp.int64],
):
    """Tiled, ``n_blocks`` blocks striding over the candidates of increment k (previous roots,
    ``counts[kprev]`` of them, then bucket k). Each candidate still a root is appended to
    ``out_roots`` at ``atomic_add(counts, k, 1)`` (any order: every consumer is
    order-free), counted in row k of the log2 area histogram, and, when it has at least
    ``min_pixels`` pixels, added to the slit-island sums of row k:
    ``sums[k] = [n, Σx, Σy, Σx², Σxy, Σy²]`` with x = log10(area in pixels) and
    y = log10(edges_x·aspect + edges_y) (perimeter in units of dx; aspect = dy/dx), in
    float64, reduced per block (tile sum) before one atomic per block and column. Every
    surviving root also adds √(area in pixels) to ``sqrt_sums[k]`` (island-resolved stiffness,
    Σ√A_i): each √a is a float64 rounded to a fixed-point int64 in units of
    ``SQRT_SCALE``⁻¹ pixel^½, so the sum is exact and independent of the order of the roots
    (identical on every device and run)."""
    b, lane = wp.tid()
    bd = wp.block_dim()
    nr = int(0)
    if kprev >= 0:
        nr = counts[kprev]
    s0 = wp.float64(0.0)
    s1 = wp.float64(0.0)
    s2 = wp.float64(0.0)
    s3 = wp.float64(0.0)
    s4 = wp.float64(0.0)
    s5 = wp.float64(0.0)
    q = wp.int64(0)
    for t in range(b * bd + lane, nr + count, n_blocks * bd):
        c = candidate(roots, nr, order, start, t)
        if parent[c] == c:
            slot = wp.atomic_add(counts, k, 1)
            out_roots[slot] = c
            a = area[c]
            e = int(0)
            while (a >> (e + 1)) > 0:
                e += 1
            wp.atomic_add(hist, k, wp.min(e, hist.shape[1] - 1), wp.int64(1))
            q += sqrt_fixed(a)
            if a >= min_pixels:
                x = wp.log10(wp.float64(a))
                y = wp.log10(wp.float64(edges_x[c]) * aspect + wp.float64(edges_y[c]))
                s0 += wp.float64(1.0)
                s1 += x
                s2 += y
                s3 += x * x
                s4 += x * y
                s5 += y * y
    rq = wp.tile_extract(wp.tile_sum(wp.tile(q)), 0)
    if lane == 0 and rq != wp.int64(0):
        wp.atomic_add(sqrt_sums, k, rq)
    r0 = wp.tile_extract(wp.tile_sum(wp.tile(s0)), 0)
    if r0 > wp.float64(0.0):
        r1 = wp.tile_extract(wp.tile_sum(wp.tile(s1)), 0)
        r2 = wp.tile_extract(wp.tile_sum(wp.tile(s2)), 0)
        r3 = wp.tile_extract(wp.tile_sum(wp.tile(s3)), 0)
        r4 = wp.tile_extract(wp.tile_sum(wp.tile(s4)), 0)
        r5 = wp.tile_extract(wp.tile_sum(wp.tile(s5)), 0)
        if lane == 0:
            wp.atomic_add(sums, k, 0, r0)
            wp.atomic_add(sums, k, 1, r1)
            wp.atomic_add(sums, k, 2, r2)
            wp.atomic_add(sums, k, 3, r3)
            wp.atomic_add(sums, k, 4, r4)
            wp.atomic_add(sums, k, 5, r5)


@wp.kernel
def active_labels_flag_kernel(
    idx: wp.array[wp.int32],
    k: int,
    parent: wp.array[wp.int32],
    flag: wp.array[wp.int32],
):
    """One thread per pixel, after the unions of increment k: contact pixels (index <= k) get
    ``parent := root`` (path halving) and ``flag = 1`` for roots, 0 elsewhere (the count step
    of count → scan → write)."""
    i = wp.tid()
    f = int(0)
    if idx[i] <= k:
        r = find_root(parent, i)
        parent[i] = r
        if r == i:
            f = 1
    flag[i] = f


@wp.kernel
def active_labels_write_kernel(
    idx: wp.array[wp.int32],
    k: int,
    parent: wp.array[wp.int32],
    rank: wp.array[wp.int32],
    labels: wp.array[wp.int32],
):
    """One thread per pixel: ``labels = rank[root]`` for contact pixels, 0 elsewhere
    (``labels`` may alias ``rank``, as in ``label.write_labels_kernel``)."""
    i = wp.tid()
    lab = int(0)
    if idx[i] <= k:
        lab = rank[find_root_readonly(parent, i)]
    labels[i] = lab


@wp.kernel
def island_stats_kernel(
    labels: wp.array[wp.int32],
    ny: int,
    nx: int,
    periodic: int,
    segment: int,
    area: wp.array[wp.int64],
    edges_x: wp.array[wp.int64],
    edges_y: wp.array[wp.int64],
):
    """One thread per (row, segment of ``segment`` pixels): per-label pixel count and boundary
    edges, accumulated along runs of one label and flushed with one atomic per run (a large
    island is not hit by one atomic per pixel)."""
    iy, s = wp.tid()
    x0 = s * segment
    x1 = wp.min(x0 + segment, nx)
    cur = int(0)
    ca = int(0)
    cx = int(0)
    cy = int(0)
    for ix in range(x0, x1):
        i = iy * nx + ix
        lab = labels[i]
        if lab != cur:
            if cur > 0:
                wp.atomic_add(area, cur, wp.int64(ca))
                wp.atomic_add(edges_x, cur, wp.int64(cx))
                wp.atomic_add(edges_y, cur, wp.int64(cy))
            cur = lab
            ca = 0
            cx = 0
            cy = 0
        if lab > 0:
            ca += 1
            for d in range(4):
                j = wrap_index(iy + offset_y(d), ix + offset_x(d), ny, nx, periodic)
                outside = True
                if j >= 0:
                    outside = labels[j] == 0
                if outside:
                    if d == 0 or d == 2:
                        cx += 1
                    else:
                        cy += 1
    if cur > 0:
        wp.atomic_add(area, cur, wp.int64(ca))
        wp.atomic_add(edges_x, cur, wp.int64(cx))
        wp.atomic_add(edges_y, cur, wp.int64(cy))


@wp.kernel
def iota_kernel(out: wp.array[wp.int32]):
    """One thread per element: ``out[i] = i``."""
    i = wp.tid()
    out[i] = i


@wp.kernel
def contact_index_search_kernel(
    z: wp.array[wp.float32],
    t: wp.array[wp.float32],
    idx: wp.array[wp.int32],
):
    """One thread per pixel: the first k with ``z >= t[k]`` (thresholds non-increasing,
    float32, m) by binary search, or ``len(t)`` when there is none."""
    i = wp.tid()
    v = z[i]
    lo = int(0)
    hi = t.shape[0]
    while lo < hi:
        mid = (lo + hi) // 2
        if v >= t[mid]:
            hi = mid
        else:
            lo = mid + 1
    idx[i] = lo


@wp.kernel
def mask_to_index_kernel(mask: wp.array[wp.uint8], idx: wp.array[wp.int32]):
    """One thread per pixel: contact index 0 for contact pixels, 1 (never) elsewhere."""
    i = wp.tid()
    v = int(1)
    if mask[i] != wp.uint8(0):
        v = 0
    idx[i] = v
