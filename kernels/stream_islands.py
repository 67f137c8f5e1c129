# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Per-band pieces of the banded island labelling: contact mask and island areas.

Launched by ``warptrunc.stream_islands``. Grid: one thread per pixel of one row band,
flattened (a band holds fewer than 2³¹ pixels). Heights in metres (float32); labels int32
(1..n within the band, 0 = no contact); areas are int64 pixel counts (integer atomics:
identical on every device).
"""

import warp as wp

wp.set_module_options({"enable_backward": False})


@wp.kernel
def contact_mask_kernel(z: wp.array[wp.float32], threshold: wp.float32, mask: wp.array[wp.uint8]):
    """One thread per pixel: mask = 1 where z ≥ threshold (the truncation's comparison)."""
    i = wp.tid()
    mask[i] = wp.uint8(0)
    if z[i] >= threshold:
        mask[i] = wp.uint8(1)


@wp.kernel
def label_area_kernel(labels: wp.array[wp.int32], area: wp.array[wp.int64]):
    """One thread per pixel: area[label] += 1 for labelled pixels (area[0] is unused)."""
    i = wp.tid()
    lab = labels[i]
    if lab > 0:
        wp.atomic_add(area, lab, wp.int64(1))
