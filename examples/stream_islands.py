# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Contact islands of a map labelled band by band, for maps larger than memory
===========================================================================

What it shows
    ``streamed_islands`` on an n × n WM surface (D = 2.5, W_r = 100 µm, L = 1 mm, R_t = 10 µm)
    at a few depths (fractions of R_t): island counts and the largest island, with the wall
    time (after one warm-up run). Below the in-memory labelling limit (2³⁰ pixels) it also
    runs ``islands_at_depths`` on the in-memory surface and checks that counts and areas are
    equal.

Key steps
    ``wm_spec`` describes the surface without generating it; ``streamed_islands`` generates it
    in row bands, labels each band and merges the labels across band borders by union-find, so
    the whole map is never held in memory.

Outputs (in ``--out``)
    stream_islands.json (device, depths, time, island counts, largest island, border merges,
    equality with the in-memory labelling); island_sizes.png: the cumulative island-size
    distribution N(≥ a) against the island area a (µm²), one line per depth.

Run::

    python examples/stream_islands.py --n 2048 --device cpu --out results/stream_islands
    python examples/stream_islands.py --n 16384 --band-rows 1024 --device cuda:0
    python examples/stream_islands.py --n 46400 --device cuda:0 --json out.json
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np
import warp as wp

import warptrunc
from warptrunc.islands.streamed import streamed_islands
from warptrunc.wm import wm_spec


def _island_sizes(res, spec, path: Path) -> None:
    """Cumulative island-size distribution N(≥ a) against a (µm²), log–log, per depth."""
    from matplotlib.figure import Figure
    from matplotlib.ticker import FormatStrFormatter, LogLocator, NullFormatter

    fig = Figure(figsize=(5.0, 4.0), dpi=150, layout="constrained")
    ax = fig.subplots()
    pixel_um2 = spec.dx * spec.dy * 1e12
    for r in res:
        if r.n_islands == 0:
            continue
        a, count = np.unique(r.area_pixels, return_counts=True)
        n_ge = np.cumsum(count[::-1])[::-1]  # islands with area ≥ a
        word = "island" if r.n_islands == 1 else "islands"
        ax.loglog(
            a * pixel_um2,
            n_ge,
            "o-",
            ms=3,
            label=f"ω = {r.depth / spec.Rt:.2f}·R$_t$: {r.n_islands} {word}",
        )
    ax.set_xlabel("island area a (µm²)")
    ax.set_ylabel("islands with area ≥ a")
    ax.set_title(f"streamed labelling, {spec.nx}×{spec.ny} WM surface, D = {spec.D}", fontsize=9)
    ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))  # 1–2–5: a few labels
    ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
    ax.xaxis.set_minor_formatter(NullFormatter())  # no minor labels: no overlapping text
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.savefig(path)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--n", type=int, default=1024, help="pixels per side")
    ap.add_argument("--seed", type=int, default=0, help="phase seed")
    ap.add_argument(
        "--fractions", type=float, nargs="+", default=[0.05, 0.2], help="depths as fractions of R_t"
    )
    ap.add_argument("--band-rows", type=int, default=None, help="rows per band")
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ... (default: CUDA if present)")
    ap.add_argument(
        "--out", type=Path, default=None, help="folder for stream_islands.json and island_sizes.png"
    )
    ap.add_argument("--json", default=None, help="also write the JSON to this file")
    ap.add_argument("--quick", action="store_true", help="256², bands of 32 rows")
    ap.add_argument("--no-show", action="store_true", help="(no figures; accepted for symmetry)")
    args = ap.parse_args(argv)
    if args.quick:
        args.n, args.band_rows = 256, 32
    device = warptrunc.resolve_device(args.device)
    spec = wm_spec(n=args.n, seed=args.seed)
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
        "device": str(device),
        "n": args.n,
        "depths_m": depths.tolist(),
        "seconds": seconds,
        "n_islands": [r.n_islands for r in res],
        "largest_island_pixels": [int(r.area_pixels.max(initial=0)) for r in res],
        "n_border_merges": [r.n_border_merges for r in res],
    }
    if device.is_cuda:
        out["mempool_high_GiB"] = wp.get_mempool_used_mem_high(device) / 2**30
    if args.n**2 < 2**30:
        from warptrunc.islands import islands_at_depths
        from warptrunc.wm import wm_surface

        s = wm_surface(n=args.n, seed=args.seed, device=device)
        ref = islands_at_depths(s, depths, device=device)
        out["equal_to_in_memory"] = all(
            np.array_equal(a.area_pixels, b.area_pixels) for a, b in zip(res, ref, strict=True)
        )
    print(json.dumps(out))
    paths = [args.json] if args.json else []
    if args.out is not None:
        args.out.mkdir(parents=True, exist_ok=True)
        paths.append(args.out / "stream_islands.json")
    for path in paths:
        with open(path, "w") as fh:
            json.dump(out, fh, indent=2)
    if args.out is not None:
        _island_sizes(res, spec, args.out / "island_sizes.png")
        print(f"wrote {args.out}/stream_islands.json, island_sizes.png")
    if out.get("equal_to_in_memory") is False:
        raise SystemExit("streamed islands differ from the in-memory labelling")
    return 0


if __name__ == "__main__":
    if (status := main()) != 0:
        raise SystemExit(status)
