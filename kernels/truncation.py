# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Truncation histograms: for every pixel, the first truncation increment at which it touches.

Launched by ``warptrunc.truncation``. Thresholds ``t[k] = z_top − ω_k`` (float32, metres,
non-increasing in k, k = 0..n) are computed on the host. A pixel with height z is in contact at
increment k when ``z >= t[k]``; its *contact index* is the smallest such k, or n + 1 when it
never touches. The guess ``k ≈ ceil((z_top − z)/Δω)`` is corrected with exact float32
comparisons against ``t``, so counts equal ``numpy.count_nonzero(z >= t[k])`` bit for bit.

Grid: one thread per pixel (flattened, C order). Counting uses integer atomics only, so results
are identical on the CPU and the GPU. Pixels that never touch are not counted (no atomic), which
keeps contention low at shallow depths.
"""

import warp as wp

wp.set_module_options({"enable_backward": False})


@wp.func
def contact_index(v: wp.float32, t: wp.array[wp.float32], z_top: float, inv_step: float) -> int:
    """Smallest k with v >= t[k]; len(t) when there is none."""
    n1 = t.shape[0]
    g = wp.ceil((z_top - v) * inv_step)
    k = int(0)
    if g > float(n1):
        k = n1
    elif g > 0.0:
        k = int(g)
    # exact corrections: t is non-increasing
    while k > 0 and v >= t[k - 1]:
        k -= 1
    while k < n1 and v < t[k]:
        k += 1
    return k


@wp.kernel
def contact_histogram_kernel(
    z: wp.array[wp.float32],
    t: wp.array[wp.float32],
    z_top: float,
    inv_step: float,
    hist: wp.array[wp.int64],
):
    """One thread per pixel; ``hist[k]`` += 1 for the pixel's contact index k ≤ n."""
    i = wp.tid()
    k = contact_index(z[i], t, z_top, inv_step)
    if k < t.shape[0]:
        wp.atomic_add(hist, k, wp.int64(1))


@wp.kernel
def contact_index_kernel(
    z: wp.array[wp.float32],
    t: wp.array[wp.float32],
    z_top: float,
    inv_step: float,
    index: wp.array[wp.int32],
):
    """One thread per pixel; writes the pixel's contact index (n + 1 = never in contact)."""
    i = wp.tid()
    index[i] = contact_index(z[i], t, z_top, inv_step)
