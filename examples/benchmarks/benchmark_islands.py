# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: contact-island labelling on Warp against scipy / cupyx in the same process.

What it shows
    1. Labelling one contact mask of a WM surface (D = 2.5, W_r = 100 µm, L = 1 mm,
       R_t = 10 µm) at 10 %, 30 % and 50 % of R_t: ``label_device`` (4- and 8-connected, the
       island count read back) against ``cupyx.scipy.ndimage.label`` on a GPU or
       ``scipy.ndimage.label`` on the CPU. Labels are checked equal.
    2. Island counts at all 201 depths (200 increments to 0.5·R_t) from one carried union-find
       forest (``island_counts_device`` on a device-resident contact-index map), against
       labelling every depth separately with the reference. The reference is timed on
       ``--ref-depths`` evenly spaced depths and extrapolated to all depths (mean × 201); its
       counts are checked equal to ours at those depths. Our own from-scratch labelling per
       depth is extrapolated the same way.
    3. End-to-end drivers from a host height map: ``island_curve`` (counts only; with
       per-island statistics and slit-island fits at every depth) and the perimeter/Euler
       histograms.

Method
    Warm-up first (the first launch compiles), ``wp.synchronize_device()`` (or the CuPy
    equivalent) after each call, medians of ``--repeats`` runs. Writes OUT/benchmark_islands.json
    (device name, Warp/NumPy/SciPy/CuPy versions, grid, git commit, all timings) and prints a
    short table.

Run
    python examples/benchmarks/benchmark_islands.py --device cuda:0 --n 10240 --out results/bench
    python examples/benchmarks/benchmark_islands.py --device cpu --n 2048 4096 --out results/bench
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import sys
import time
import traceback
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]

try:
    import warptrunc
except ImportError:  # not installed: import the checkout, mapping kernels/ as warptrunc.kernels
    import importlib.util

    sys.path.insert(0, str(ROOT))
    spec = importlib.util.spec_from_file_location(
        "warptrunc.kernels",
        ROOT / "kernels" / "__init__.py",
        submodule_search_locations=[str(ROOT / "kernels")],
    )
    mod = importlib.util.module_from_spec(spec)
    sys.modules["warptrunc.kernels"] = mod
    spec.loader.exec_module(mod)
    import warptrunc

import warp as wp  # noqa: E402
from _common import git_commit, timeit  # noqa: E402

from warptrunc.islands import (  # noqa: E402
    IslandSettings,
    island_counts_device,
    island_curve,
    label_islands,
)
from warptrunc.islands.forest import Forest  # noqa: E402
from warptrunc.islands.topology import topology_hist  # noqa: E402
from warptrunc.islands.unionfind import label_device  # noqa: E402
from warptrunc.truncation import (  # noqa: E402
    TruncationSettings,
    contact_index_device,
    depth_grid,
)
from warptrunc.wm import wm_surface  # noqa: E402

FRACTIONS = (0.1, 0.3, 0.5)


def guarded(res: dict, key: str, fn):
    """Run ``fn``; record an error under ``key`` instead of stopping (runs unattended)."""
    try:
        return fn()
    except Exception as exc:  # report and go on
        res.setdefault("errors", {})[key] = f"{type(exc).__name__}: {exc}"
        traceback.print_exc()
        return None


def counts_breakdown(idx, n: int, n1: int, device, sync) -> dict:
    """Median split of ``island_counts_device``: sort + buckets, the union passes, the
    difference histogram."""
    flat = idx.reshape((n * n,))
    parts: dict[str, list[float]] = {"sort_and_buckets_s": [], "unions_s": [], "histogram_s": []}
    for _ in range(4):  # the first run warms up
        sync()
        t0 = time.perf_counter()
        forest = Forest(flat, (n, n), n1, 4, False, False, device)
        sync()
        t1 = time.perf_counter()
        for _ in range(n1):
            forest.step()
        sync()
        t2 = time.perf_counter()
        forest.island_counts()
        t3 = time.perf_counter()
        for key, v in zip(parts, (t1 - t0, t2 - t1, t3 - t2), strict=True):
            parts[key].append(v)
        del forest
    return {k: statistics.median(v[1:]) for k, v in parts.items()}


def run_case(n: int, device, args) -> dict:
    import scipy.ndimage as ndi

    cross = ndi.generate_binary_structure(2, 1)
    block = ndi.generate_binary_structure(2, 2)
    rep = args.repeats
    sync = lambda: wp.synchronize_device(device)  # noqa: E731
    res: dict = {"n": n, "pixels": n * n, "device": str(device), "device_name": device.name}
    t0 = time.perf_counter()
    s = wm_surface(2.5, 100e-6, L=1e-3, n=n, Rt=10e-6, seed=0, device=device)
    res["generate_s"] = time.perf_counter() - t0
    z = s.heights
    ztop = np.float64(z.max())

    cp = None
    if device.is_cuda:
        try:
            import cupy as cp
            import cupyx.scipy.ndimage as cndi

            res["cupy_version"] = cp.__version__
        except ImportError as exc:
            res["cupy_missing"] = str(exc)
            cp = None
    csync = (lambda: cp.cuda.Device().synchronize()) if cp is not None else (lambda: None)

    # 1. one mask at 10 %, 30 %, 50 % of R_t
    res["masks"] = []
    for f in FRACTIONS:
        thr = np.float32(ztop - f * s.Rt)
        m_np = z >= thr
        row: dict = {"fraction_of_Rt": f, "contact_fraction": float(m_np.mean())}
        m_wp = wp.array(m_np.view(np.uint8), dtype=wp.uint8, device=device)
        for conn in (4, 8):
            row[f"warp_label{conn}_s"] = guarded(
                row,
                f"warp{conn}",
                lambda c=conn, m=m_wp: timeit(lambda: label_device(m, c), rep, sync),
            )
            lab, nw = label_device(m_wp, conn)
            row[f"n_islands{conn}"] = nw
            st = cross if conn == 4 else block
            if cp is not None:
                m_cp = cp.asarray(m_np)
                st_cp = cp.asarray(st)
                row[f"cupyx_label{conn}_s"] = guarded(
                    row,
                    f"cupyx{conn}",
                    lambda m_cp=m_cp, st_cp=st_cp: timeit(
                        lambda: cndi.label(m_cp, st_cp), rep, csync
                    ),
                )
                ref, nr = cndi.label(m_cp, st_cp)
                row[f"labels_equal{conn}"] = bool(cp.array_equal(cp.asarray(lab), ref)) and (
                    int(nr) == nw
                )
                del m_cp, ref
            elif not device.is_cuda:
                row[f"scipy_label{conn}_s"] = timeit(
                    lambda st=st, m=m_np: ndi.label(m, st), rep, sync
                )
                ref, nr = ndi.label(m_np, st)
                row[f"labels_equal{conn}"] = bool(np.array_equal(lab.numpy(), ref)) and nr == nw
                del ref
            del lab
        row["warp_label_islands_with_stats_s"] = guarded(
            row,
            "label_islands",
            lambda m=m_np: timeit(
                lambda: label_islands(m, s.dx, s.dy, device=device), max(1, rep // 2), sync
            ),
        )
        # the same from the device mask: no host pass, labels left on the device
        row["warp_label_islands_device_mask_with_stats_s"] = guarded(
            row,
            "label_islands_device",
            lambda m=m_wp: timeit(lambda: label_islands(m, s.dx, s.dy), max(1, rep // 2), sync),
        )
        del m_wp
        res["masks"].append(row)
        print(
            f"  {n}² mask at {f:.0%} R_t: warp4 {1e3 * (row['warp_label4_s'] or np.nan):.2f} ms"
            f", ref4 {1e3 * row.get('cupyx_label4_s', row.get('scipy_label4_s')) or np.nan:.2f} ms"
            f", equal {row.get('labels_equal4')}",
            flush=True,
        )

    # 2. island counts at every depth from one carried forest
    depth = depth_grid(s.Rt, args.increments, max_depth_fraction=args.max_depth_fraction)
    n1 = depth.size
    res["increments"] = args.increments
    res["max_depth_fraction"] = args.max_depth_fraction
    res["contact_index_map_incl_h2d_s"] = timeit(
        lambda: contact_index_device(s, depth, warptrunc.resolve_device(device)), rep, sync
    )
    idx = contact_index_device(s, depth, warptrunc.resolve_device(device))
    for conn in (4, 8):
        res[f"warp_counts_all_depths{conn}_s"] = guarded(
            res,
            f"counts{conn}",
            lambda c=conn, i=idx: timeit(lambda: island_counts_device(i, n1, c), rep, sync),
        )
    counts = island_counts_device(idx, n1, 4)
    res["max_islands"] = int(counts.max())
    res["warp_counts_breakdown4"] = guarded(
        res, "breakdown", lambda: counts_breakdown(idx, n, n1, device, sync)
    )
    flat = idx.reshape((n * n,))
    res["warp_perimeter_euler_histograms_s"] = guarded(
        res,
        "topology",
        lambda f=flat: timeit(lambda: topology_hist(f, (n, n), n1, 4, False, device), rep, sync),
    )
    flat = idx = None  # free before the reference runs
    # reference: label each depth separately, timed on a subset and extrapolated
    ks = np.unique(np.linspace(0, n1 - 1, min(args.ref_depths, n1)).round().astype(int))
    thr = (ztop - depth).astype(np.float32)
    res["ref_depth_indices"] = ks.tolist()
    per_ref, per_ref_thr, per_warp, ok = [], [], [], True
    if cp is not None:
        zc = cp.asarray(z)
    for k in ks:
        m_np = z >= thr[k]
        m_wp = wp.array(m_np.view(np.uint8), dtype=wp.uint8, device=device)
        per_warp.append(timeit(lambda m_wp=m_wp: label_device(m_wp, 4), 1, sync))
        if cp is not None:
            tk = cp.float32(thr[k])
            per_ref_thr.append(timeit(lambda tk=tk: cndi.label(zc >= tk, cross), 1, csync))
            m_cp = cp.asarray(m_np)
            per_ref.append(timeit(lambda m_cp=m_cp: cndi.label(m_cp, cross), 1, csync))
            nr = int(cndi.label(m_cp, cross)[1])
        elif not device.is_cuda:
            per_ref.append(timeit(lambda m_np=m_np: ndi.label(m_np, cross), 1, sync))
            nr = ndi.label(m_np, cross)[1]
        else:
            nr = int(counts[k])
        ok &= nr == int(counts[k])
    res["ref_counts_equal"] = bool(ok)
    ref_name = "cupyx" if cp is not None else ("scipy" if not device.is_cuda else None)
    if ref_name:
        res[f"{ref_name}_label_per_depth_mean_s"] = float(np.mean(per_ref))
        res[f"{ref_name}_label_all_depths_extrapolated_s"] = float(np.mean(per_ref) * n1)
    if per_ref_thr:
        res["cupyx_threshold_and_label_all_depths_extrapolated_s"] = float(
            np.mean(per_ref_thr) * n1
        )
    res["warp_label_per_depth_all_depths_extrapolated_s"] = float(np.mean(per_warp) * n1)

    # 3. end-to-end drivers from the host height map
    depths = TruncationSettings(
        increments=args.increments, max_depth_fraction=args.max_depth_fraction
    )
    for what, settings, repeats in (
        ("counts", IslandSettings(statistics=False), rep),
        ("statistics", IslandSettings(snapshots=None), max(1, rep // 2)),
    ):
        res[f"warp_island_curve_{what}_s"] = guarded(
            res,
            f"curve_{what}",
            lambda st=settings, k=repeats: timeit(
                lambda: island_curve(s, truncation=depths, settings=st, device=device), k, sync
            ),
        )
    return res


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--device", default=None, help="cpu, cuda:0, ... (default: CUDA if present)")
    ap.add_argument("--n", type=int, nargs="+", default=[2048], help="pixels per side")
    ap.add_argument("--repeats", type=int, default=5, help="timed runs per measurement")
    ap.add_argument("--increments", type=int, default=200, help="depth increments")
    ap.add_argument("--max-depth-fraction", type=float, default=0.5, help="ω_max / R_t")
    ap.add_argument(
        "--ref-depths", type=int, default=20, help="depths at which the per-depth reference runs"
    )
    ap.add_argument("--out", type=Path, default=Path("results/benchmark"), help="output folder")
    ap.add_argument("--quick", action="store_true", help="256², 2 repeats, 5 reference depths")
    ap.add_argument("--no-show", action="store_true", help="accepted for symmetry; no figures")
    args = ap.parse_args(argv)
    if args.quick:
        args.n, args.repeats, args.ref_depths = [256], 2, 5
    device = warptrunc.resolve_device(args.device)
    import scipy

    info = {
        "device": str(device),
        "device_name": device.name,
        "warp_version": wp.config.version,
        "numpy_version": np.__version__,
        "scipy_version": scipy.__version__,
        "python": platform.python_version(),
        "machine": platform.machine(),
        "processor": platform.processor(),
        "git_commit": git_commit(),
        "dtype": "float32 heights, uint8 masks, int32 labels",
        "repeats": args.repeats,
        "cases": [],
    }
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / "benchmark_islands.json"
    for n in args.n:
        print(f"{n}² on {device} ({device.name})", flush=True)
        info["cases"].append(guarded(info, f"case{n}", lambda n=n: run_case(n, device, args)))
        path.write_text(json.dumps(info, indent=1) + "\n")  # after each case: partial results

    ms = lambda v: "-" if v is None else f"{1e3 * v:.2f}"  # noqa: E731
    print(f"\nmedians in ms on {device.name}; wrote {path}")
    for c in info["cases"]:
        if c is None:
            continue
        ref = "cupyx" if "cupy_version" in c else "scipy"
        print(f"{c['n']}²  label one mask (4-conn / 8-conn), warp vs {ref}:")
        for r in c["masks"]:
            print(
                f"   {r['fraction_of_Rt']:.0%} R_t ({r['contact_fraction']:.1%} contact, "
                f"{r['n_islands4']} islands): warp {ms(r.get('warp_label4_s'))} / "
                f"{ms(r.get('warp_label8_s'))}, {ref} {ms(r.get(ref + '_label4_s'))} / "
                f"{ms(r.get(ref + '_label8_s'))}, equal {r.get('labels_equal4')}/"
                f"{r.get('labels_equal8')}"
            )
        print(
            f"   all {c['increments'] + 1} depths: warp counts {ms(c.get('warp_counts_all_depths4_s'))}"
            f" (4) / {ms(c.get('warp_counts_all_depths8_s'))} (8) + index map "
            f"{ms(c.get('contact_index_map_incl_h2d_s'))} (incl. host→device), perimeter+χ "
            f"{ms(c.get('warp_perimeter_euler_histograms_s'))}; {ref} per depth × "
            f"{c['increments'] + 1} ≈ {ms(c.get(ref + '_label_all_depths_extrapolated_s'))}"
            f" (extrapolated from {len(c['ref_depth_indices'])} depths; counts equal "
            f"{c['ref_counts_equal']}); warp per depth ≈ "
            f"{ms(c.get('warp_label_per_depth_all_depths_extrapolated_s'))}"
        )
        print(
            f"   island_curve end to end: counts {ms(c.get('warp_island_curve_counts_s'))}, "
            f"with statistics {ms(c.get('warp_island_curve_statistics_s'))}"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
