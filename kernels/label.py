# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Connected-component labelling of one binary mask by lock-free union-find.

Launched by ``warptrunc.islands`` (``label_device``, ``label_islands``); the union-find
functions ``find_root``, ``find_root_readonly`` and ``unite`` are also called by the carried
forest kernels in ``warptrunc.kernels.islands``.

Data layout: all arrays are flattened in C order, pixel ``i = iy·nx + ix``; the mask is
``uint8`` (non-zero = contact), ``parent`` is ``int32`` with ``parent[i] = -1`` for background
pixels. Invariant: ``parent[i] <= i``, and a pixel is a root when ``parent[i] == i``. Roots are
only ever hooked *onto a smaller index*, so every root is the smallest flat index of its tree;
after all unions, the root of a component is its first pixel in raster order, whatever the
order in which threads ran. That is what makes the final labels deterministic.

Union: both roots are found, and the larger one is hooked under the smaller by a
compare-and-swap that only succeeds while it is still a root (as ECL-CC, Jaiganesh & Burtscher
2018, doi:10.1145/3208040.3208041); a failed CAS returns the new parent and the loop climbs on.
Path halving in ``find_root`` uses plain stores: every store points a pixel at one of its
ancestors, which is in the same set and has a smaller index, so races between such stores are
benign (a stale store only leaves a longer path).

Pipeline (one thread per pixel, 2-D launches ``iy, ix = wp.tid()``): ``init_parent_kernel``
(runs of contact pixels in a row) → ``hook_kernel``
(union with the forward neighbours) → ``compress_flag_kernel`` (parent := root, flag roots) →
inclusive scan of the flags (``wp.utils.array_scan``) → ``write_labels_kernel``. On the CPU,
``label_sequential_kernel`` does the same union-find in raster order in one launch.
"""

import warp as wp

wp.set_module_options({"enable_backward": False})


@wp.func
def find_root(parent: wp.array[wp.int32], i: int) -> int:
    """Root of ``i``, halving the path on the way (benign races; see the module docstring)."""
    prev = i
    cur = parent[i]
    if cur != i:
        nxt = parent[cur]
        while cur > nxt:
            parent[prev] = nxt
            prev = cur
            cur = nxt
            nxt = parent[cur]
    return cur


@wp.func
def find_root_readonly(parent: wp.array[wp.int32], i: int) -> int:
    """Root of ``i`` without writing (used where ``parent[i] := root`` is written per thread)."""
    cur = i
    nxt = parent[cur]
    while cur != nxt:
        cur = nxt
        nxt = parent[cur]
    return cur


@wp.func
def unite(parent: wp.array[wp.int32], a: int, b: int) -> int:
    """Merge the sets of ``a`` and ``b``; return the root that was hooked, or -1 if none was.

    Exactly one call returns each root that stops being a root, so callers can record when
    islands merge.
    """
    ra = find_root(parent, a)
    rb = find_root(parent, b)
    hooked = int(-1)
    while ra != rb:
        if ra < rb:
            old = wp.atomic_cas(parent, rb, rb, ra)
            if old == rb:
                hooked = rb
                rb = ra
            else:
                rb = old
        else:
            old = wp.atomic_cas(parent, ra, ra, rb)
            if old == ra:
                hooked = ra
                ra = rb
            else:
                ra = old
    return hooked


@wp.func
def wrap_index(iy: int, ix: int, ny: int, nx: int, periodic: int) -> int:
    """Flat index of pixel (iy, ix), wrapped when ``periodic``; -1 outside a bounded domain."""
    j = int(-1)
    if periodic != 0:
        j = ((iy + ny) % ny) * nx + ((ix + nx) % nx)
    elif iy >= 0 and iy < ny and ix >= 0 and ix < nx:
        j = iy * nx + ix
    return j


@wp.func
def is_contact(mask: wp.array[wp.uint8], j: int) -> bool:
    """True for an in-domain contact pixel (``j >= 0`` and the mask is set)."""
    r = False
    if j >= 0:
        r = mask[j] != wp.uint8(0)
    return r


@wp.func
def init_parent_at(mask: wp.array[wp.uint8], nx: int, segment: int, iy: int, ix: int) -> int:
    """Initial parent of pixel (iy, ix): a contact pixel points at the first pixel of its run of
    contact pixels within its aligned row segment of ``segment`` pixels (found by scanning left,
    at most ``segment`` − 1 cached reads); that first pixel points at its left neighbour when
    the run continues from the previous segment (never across the periodic seam, which keeps
    ``parent[i] < i``), else at itself. Background pixels get -1. Paths along a row are then
    at most one hop per segment long."""
    row = iy * nx
    i = row + ix
    p = int(-1)
    if mask[i] != wp.uint8(0):
        x0 = (ix // segment) * segment
        s = ix
        while s > x0 and mask[row + s - 1] != wp.uint8(0):
            s -= 1
        p = row + s
        if s == ix and s == x0 and s > 0:
            if mask[i - 1] != wp.uint8(0):
                p = i - 1
    return p


@wp.func
def hook_at(
    mask: wp.array[wp.uint8],
    ny: int,
    nx: int,
    connectivity: int,
    periodic: int,
    parent: wp.array[wp.int32],
    iy: int,
    ix: int,
):
    """Contact pixel (iy, ix) unites with its forward neighbours (up; up-left and up-right for
    8-connectivity; right across the periodic seam), skipping links that the left neighbour
    already implies."""
    i = iy * nx + ix
    # the left neighbour (within the row) is already our parent or child after init
    left = False
    if ix > 0:
        left = mask[i - 1] != wp.uint8(0)
    if periodic != 0 and ix == nx - 1:
        j = wrap_index(iy, ix + 1, ny, nx, periodic)
        if is_contact(mask, j):
            unite(parent, i, j)
    up = wrap_index(iy + 1, ix, ny, nx, periodic)
    if connectivity == 4:
        # left and up-left both contact: up is already connected through them
        up_left = False
        if left:
            up_left = is_contact(mask, wrap_index(iy + 1, ix - 1, ny, nx, periodic))
        if not up_left and is_contact(mask, up):
            unite(parent, i, up)
    else:
        # 8-connectivity: a contact left neighbour is diagonal to up and up-left, so both
        # links are implied by the left neighbour's own up-right and up links
        if not left:
            if is_contact(mask, up):
                unite(parent, i, up)
            ul = wrap_index(iy + 1, ix - 1, ny, nx, periodic)
            if is_contact(mask, ul):
                unite(parent, i, ul)
        ur = wrap_index(iy + 1, ix + 1, ny, nx, periodic)
        if is_contact(mask, ur):
            unite(parent, i, ur)


@wp.func
def compress_at(parent: wp.array[wp.int32], i: int) -> int:
    """``parent[i] := root`` (path halving on the way); returns 1 for a root, else 0."""
    f = int(0)
    if parent[i] >= 0:
        r = find_root(parent, i)
        parent[i] = r
        if r == i:
            f = 1
    return f


@wp.func
def label_at(parent: wp.array[wp.int32], rank: wp.array[wp.int32], i: int) -> int:
    """``rank[root of i]`` for a contact pixel, 0 for background."""
    lab = int(0)
    if parent[i] >= 0:
        lab = rank[find_root_readonly(parent, i)]
    return lab


@wp.kernel
def init_parent_kernel(
    mask: wp.array[wp.uint8],
    nx: int,
    segment: int,
    parent: wp.array[wp.int32],
):
    """One thread per pixel: ``parent[i]`` = :func:`init_parent_at` (coalesced writes)."""
    iy, ix = wp.tid()
    parent[iy * nx + ix] = init_parent_at(mask, nx, segment, iy, ix)


@wp.kernel
def hook_kernel(
    mask: wp.array[wp.uint8],
    ny: int,
    nx: int,
    connectivity: int,
    periodic: int,
    parent: wp.array[wp.int32],
):
    """One thread per pixel: contact pixels run :func:`hook_at`."""
    iy, ix = wp.tid()
    if mask[iy * nx + ix] != wp.uint8(0):
        hook_at(mask, ny, nx, connectivity, periodic, parent, iy, ix)


@wp.kernel
def compress_flag_kernel(
    nx: int,
    parent: wp.array[wp.int32],
    flag: wp.array[wp.int32],
):
    """One thread per pixel: ``parent[i] := root`` and ``flag[i] = 1`` for roots, 0 elsewhere. A
    concurrent halving store may put an intermediate ancestor back into ``parent[i]``;
    ``write_labels_kernel`` therefore finds the root again (1–2 hops)."""
    iy, ix = wp.tid()
    i = iy * nx + ix
    flag[i] = compress_at(parent, i)


@wp.kernel
def write_labels_kernel(
    parent: wp.array[wp.int32],
    rank: wp.array[wp.int32],
    nx: int,
    labels: wp.array[wp.int32],
):
    """One thread per pixel: ``labels[i] = rank[root]`` (the inclusive scan of the root flags,
    so labels are 1..n in raster order of each island's first pixel), 0 for background.
    ``labels`` may be ``rank`` itself: a root rewrites its own value, and no thread reads the
    slot of a non-root."""
    iy, ix = wp.tid()
    i = iy * nx + ix
    labels[i] = label_at(parent, rank, i)


# --- four pixels per thread (GPU, rows of a multiple of 4 pixels) -----------------------------
# One thread per quad of 4 consecutive pixels of a row, read as one uint32 of mask bytes or
# one vec4i of parents: a quad of background (most of a map at shallow depths) costs one load
# and one store, and the per-thread overhead is paid once per 4 pixels.


@wp.kernel
def init_parent4_kernel(
    mask4: wp.array[wp.uint32],
    mask: wp.array[wp.uint8],
    nx: int,
    segment: int,
    parent4: wp.array[wp.vec4i],
):
    """One thread per quad: :func:`init_parent_at` for its 4 pixels."""
    t = wp.tid()
    if mask4[t] == wp.uint32(0):
        parent4[t] = wp.vec4i(-1, -1, -1, -1)
        return
    i0 = t * 4
    iy = i0 // nx
    ix = i0 - iy * nx
    parent4[t] = wp.vec4i(
        init_parent_at(mask, nx, segment, iy, ix),
        init_parent_at(mask, nx, segment, iy, ix + 1),
        init_parent_at(mask, nx, segment, iy, ix + 2),
        init_parent_at(mask, nx, segment, iy, ix + 3),
    )


@wp.kernel
def hook_flat_kernel(
    mask: wp.array[wp.uint8],
    ny: int,
    nx: int,
    connectivity: int,
    periodic: int,
    parent: wp.array[wp.int32],
):
    """One thread per pixel, 1-D launch: the row and column are only computed for contact
    pixels. (Unions stay one pixel per thread: four per thread serialised them and ran 1.5–2.3×
    slower on half-covered maps.)"""
    i = wp.tid()
    if mask[i] != wp.uint8(0):
        iy = i // nx
        hook_at(mask, ny, nx, connectivity, periodic, parent, iy, i - iy * nx)


@wp.kernel
def compress_flag4_kernel(
    parent4: wp.array[wp.vec4i],
    parent: wp.array[wp.int32],
    flag4: wp.array[wp.vec4i],
):
    """One thread per quad: :func:`compress_at` for its 4 pixels (``parent4`` aliases
    ``parent``)."""
    t = wp.tid()
    p = parent4[t]
    if wp.max(p) < 0:
        flag4[t] = wp.vec4i(0, 0, 0, 0)
        return
    i0 = t * 4
    flag4[t] = wp.vec4i(
        compress_at(parent, i0),
        compress_at(parent, i0 + 1),
        compress_at(parent, i0 + 2),
        compress_at(parent, i0 + 3),
    )


@wp.kernel
def write_labels4_kernel(
    parent4: wp.array[wp.vec4i],
    parent: wp.array[wp.int32],
    rank: wp.array[wp.int32],
    labels4: wp.array[wp.vec4i],
):
    """One thread per quad: :func:`label_at` for its 4 pixels; ``labels4`` may alias ``rank``
    (all 4 values are read before the store, and roots rewrite their own value)."""
    t = wp.tid()
    p = parent4[t]
    if wp.max(p) < 0:
        labels4[t] = wp.vec4i(0, 0, 0, 0)
        return
    i0 = t * 4
    labels4[t] = wp.vec4i(
        label_at(parent, rank, i0),
        label_at(parent, rank, i0 + 1),
        label_at(parent, rank, i0 + 2),
        label_at(parent, rank, i0 + 3),
    )


@wp.func
def unite_smaller_neighbours(
    mask: wp.array[wp.uint8],
    iy: int,
    ix: int,
    ny: int,
    nx: int,
    connectivity: int,
    periodic: int,
    labels: wp.array[wp.int32],
):
    """Unite pixel (iy, ix) with every contact neighbour of smaller flat index (general case:
    periodic seams)."""
    i = iy * nx + ix
    for d in range(connectivity):
        dy = int(0)
        dx = int(0)
        if d == 0:
            dx = -1
        elif d == 1:
            dy = -1
        elif d == 2:
            dx = 1
        elif d == 3:
            dy = 1
        elif d == 4:
            dy = -1
            dx = -1
        elif d == 5:
            dy = -1
            dx = 1
        elif d == 6:
            dy = 1
            dx = -1
        else:
            dy = 1
            dx = 1
        j = wrap_index(iy + dy, ix + dx, ny, nx, periodic)
        if j >= 0 and j < i:
            if mask[j] != wp.uint8(0):
                unite(labels, i, j)


@wp.kernel
def label_sequential_kernel(
    mask: wp.array[wp.uint8],
    ny: int,
    nx: int,
    connectivity: int,
    periodic: int,
    labels: wp.array[wp.int32],
    count: wp.array[wp.int32],
):
    """One thread: the whole map in raster order, for the CPU, where a Warp launch runs on one
    thread anyway. Pass 1 unites every contact pixel with its neighbours of smaller flat index
    (each edge once, periodic seams included) in ``labels`` used as the parent array; a pixel
    whose left neighbour is contact starts with that neighbour's parent, and links already
    implied through it are skipped. Pass 2 replaces parents by labels in place: a root takes
    the next label, any other pixel the label already written at its parent (parents have
    smaller indices). Same labels as the parallel pipeline."""
    zero = wp.uint8(0)
    for iy in range(ny):
        for ix in range(nx):
            i = iy * nx + ix
            if mask[i] == zero:
                labels[i] = -1
            elif periodic != 0 and (ix == 0 or iy == 0 or ix == nx - 1 or iy == ny - 1):
                labels[i] = i
                unite_smaller_neighbours(mask, iy, ix, ny, nx, connectivity, periodic, labels)
            else:
                left = False
                if ix > 0:
                    left = mask[i - 1] != zero
                labels[i] = i
                if left:
                    labels[i] = labels[i - 1]  # the left pixel's parent: a short path
                if iy > 0:
                    b = i - nx
                    down = mask[b] != zero
                    down_left = False
                    if ix > 0:
                        down_left = mask[b - 1] != zero
                    if connectivity == 4:
                        if down and not (left and down_left):
                            unite(labels, i, b)
                    else:
                        down_right = False
                        if ix < nx - 1:
                            down_right = mask[b + 1] != zero
                        # left is diagonal to down; down is beside down-left and down-right
                        if down and not left:
                            unite(labels, i, b)
                        if down_left and not left and not down:
                            unite(labels, i, b - 1)
                        if down_right and not down:
                            unite(labels, i, b + 1)
    n = int(0)
    for i in range(ny * nx):
        p = labels[i]
        lab = int(0)
        if p == i:
            n += 1
            lab = n
        elif p >= 0:
            lab = labels[p]
        labels[i] = lab
    count[0] = n
