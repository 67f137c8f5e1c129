# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Islands of a WM surface labelled by row bands (border merge by union-find), timed.

What it shows
    ``streamed_islands`` on an n × n WM surface at a few depths (fractions of R_t): island
    counts and the largest island, with the wall time (after one warm-up run). Below the
    in-memory labelling limit (2³⁰ pixels) it also runs ``islands_at_depths`` on the in-memory
    surface and checks that counts and areas are equal.

Run
    python examples/stream_islands.py --n 2048 --device cpu
    python examples/stream_islands.py --n 16384 --band-rows 1024 --device cuda:0
    python examples/stream_islands.py --n 46400 --device cuda:0 --json out.json
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np
import warp as wp

import warptrunc
from warptrunc.islands.streamed import streamed_islands
from warptrunc.wm import wm_spec


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--n", type=int, default=1024, help="pixels per side")
    ap.add_argument("--fractions", type=float, nargs="+", default=[0.05, 0.2],
                    help="depths as fractions of R_t")  # fmt: skip
    ap.add_argument("--band-rows", type=int, default=None, help="rows per band")
    ap.add_argument("--device", default=None)
    ap.add_argument("--json", default=None)
    args = ap.parse_args()
    device = warptrunc.resolve_device(args.device)
    spec = wm_spec(n=args.n)
    depths = np.asarray(args.fractions) * spec.Rt  # R_t is exact after the scaling

    def run():
        if device.is_cuda:
            wp.synchronize_device(device)
        t0 = time.perf_counter()
        r = streamed_islands(spec, depths, band_rows=args.band_rows, device=device, progress=False)
        return r, time.perf_counter() - t0

    run()
    res, seconds = run()
    out = {
        "device": str(device), "n": args.n, "depths_m": depths.tolist(), "seconds": seconds,
        "n_islands": [r.n_islands for r in res],
        "largest_island_pixels": [int(r.area_pixels.max(initial=0)) for r in res],
        "n_border_merges": [r.n_border_merges for r in res],
    }  # fmt: skip
    if device.is_cuda:
        out["mempool_high_GiB"] = wp.get_mempool_used_mem_high(device) / 2**30
    if args.n**2 < 2**30:
        from warptrunc.islands import islands_at_depths
        from warptrunc.wm import wm_surface

        s = wm_surface(n=args.n, device=device)
        ref = islands_at_depths(s, depths, device=device)
        out["equal_to_in_memory"] = all(
            np.array_equal(a.area_pixels, b.area_pixels) for a, b in zip(res, ref, strict=True)
        )
    print(json.dumps(out))
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=2)
    if out.get("equal_to_in_memory") is False:
        raise SystemExit("streamed islands differ from the in-memory labelling")


if __name__ == "__main__":
    main()
