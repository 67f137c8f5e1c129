# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: whole ``warptrunc sweep`` commands in process and on
1, 2, 4 … Dask workers (one per GPU), side by side, and whether their rows are identical.

What it measures
    For each workload — ``light``: light cases (generate → truncate → fit), ``elastic``: the
    same plus an elastic solve per case (``--bem-fractions``) — the same ``warptrunc sweep``
    command is run as a child process, once in process (``--device`` as given, else the
    default device: cuda:0 on a GPU machine) and once per worker count of ``--workers``
    (``--workers N``; written ``--workers auto`` when N is the number of GPUs), each into a
    fresh store. Before them an untimed warm-up command (the workload's first seed only)
    compiles Warp's kernels into the shared kernel cache, so no timed command compiles.

    Per run: the command's wall time (the whole process: imports, Warp's start, the cluster's
    start and stop, the cases, the store's writes) and its speed-up against in process; where
    the time goes, as far as the store tells it: ``fixed_s`` (the in-process command again on
    its finished store: imports, Warp's start, reading the store; no cluster starts then),
    ``start_s`` (a local cluster of N workers started, every worker's Warp started and a 64²
    surface made there, the cluster closed; measured separately, in this process),
    ``compute_s`` (the busiest device's sum of the cases' own times, the ``seconds`` column,
    divided by the workers sharing it), ``tail_s`` (how long the first device to finish
    waited for the last one: an imbalanced last task), and ``other_s`` = wall − fixed − start
    − compute (the scheduler, host↔device copies outside a case, the store's writes and the
    client's reads; negative in process, where the cases' own times overlap: generation,
    fitting and writing run in threads side by side), with the parts (tasks of a cluster;
    store writes) and the bytes written.

    ``check`` (item 4): two small sweeps — light cases (several surfaces per launch on a GPU,
    where the batches of a worker's task differ from those in process) and cases with elastic
    solves and fractal dimensions — each run in process twice on the same device, then with
    ``--workers 2`` (``--check-workers``). Every stored row and curve is compared bit for bit
    (NaN equal to NaN) with the first run, leaving out the columns that say where, when and
    how fast a case ran (``RUN_COLUMNS``, ``bem_seconds``); the columns that differ are
    listed with the number of rows and the largest difference.

Output
    ``<out>/benchmark_workers.json`` (rewritten after every run, so a run cut short keeps what
    finished): the machine (GPUs from ``nvidia-smi -L`` and Warp), the commit, every command
    and its measures; a table on stdout at the end.

Run
    # CPU, small (the defaults: 64² grids, 2 workers): a minute
    python examples/benchmarks/benchmark_workers.py --device cpu --workers 2 --out bench_w
    # a GPU node, the full sizes (2000 light cases at 2048², 96 elastic at 4096²)
    python examples/benchmarks/benchmark_workers.py --full --out bench_w
    # 20000 light cases (seeds 0-4999 over the 4 D values): where the cluster's start stops
    # mattering
    python examples/benchmarks/benchmark_workers.py --full --runs light --light-cases 20000
    # see examples/gpu_checks/workers_bench.sh
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shlex
import shutil
import signal
import subprocess
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

#: The workloads: (grid and options for ``warptrunc sweep``) small (CPU, CI) and full (a GPU node).
SIZES = {
    "small": {
        "light": ["--n", "64", "--D", "2.3", "2.6", "--delta", "0.01", "--seeds", "0-7"],
        "elastic": [
            "--n",
            "64",
            "--D",
            "2.3",
            "2.6",
            "--delta",
            "0.01",
            "--seeds",
            "0-3",
            "--bem-fractions",
            "0.1",
        ],
        "check": {
            "light": dict(n=64, D=[2.3, 2.6], seeds="0-7"),
            "elastic": dict(
                n=64, D=[2.3, 2.6], seeds="0-3", bem=(0.1, 0.2), fractal=("tri", "box")
            ),
        },
    },
    "full": {  # 4 × 500 = 2000 light cases at 2048²; 2 × 48 = 96 elastic cases at 4096²
        "light": [
            "--n",
            "2048",
            "--D",
            "2.2",
            "2.4",
            "2.6",
            "2.8",
            "--delta",
            "0.01",
            "--seeds",
            "0-499",
        ],
        "elastic": [
            "--n",
            "4096",
            "--D",
            "2.3",
            "2.6",
            "--delta",
            "0.01",
            "--seeds",
            "0-47",
            "--bem-fractions",
            "0.1",
        ],
        "check": {
            "light": dict(n=2048, D=[2.3, 2.6], seeds="0-31"),  # batched on a GPU
            "elastic": dict(
                n=1024,
                D=[2.3, 2.6],
                seeds="0-7",
                bem=(0.1, 0.2),
                fractal=("tri", "box", "vs", "sp"),
            ),
        },
    },
}


def gpus() -> list[str]:
    """``nvidia-smi -L`` lines (empty without nvidia-smi or a GPU)."""
    try:
        r = subprocess.run(["nvidia-smi", "-L"], capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return []
    return [ln.strip() for ln in r.stdout.splitlines() if ln.strip().startswith("GPU")]


def warp_devices() -> list[str]:
    """``name (alias)`` of every Warp device."""
    import warp as wp

    from warptrunc._support.device import cuda_device_count

    cuda_device_count()  # quiet init
    return [f"{d.name} ({d.alias})" for d in wp.get_devices()]


def _seeds_first(args: list[str]) -> list[str]:
    """The workload's arguments with only its first seed (the warm-up)."""
    out = list(args)
    i = out.index("--seeds") + 1
    out[i] = out[i].split(",")[0].split("-")[0]
    return out


def with_cases(args: list[str], n_cases: int) -> list[str]:
    """The workload's arguments with ``--seeds 0-<k−1>``: ``n_cases`` cases over its ``--D``
    values (k = n_cases / their number, rounded up)."""
    out = list(args)
    i = out.index("--D") + 1
    n_d = next((j for j, a in enumerate(out[i:]) if a.startswith("--")), len(out) - i)
    k = max(1, -(-int(n_cases) // max(1, n_d)))
    out[out.index("--seeds") + 1] = f"0-{k - 1}"
    return out


def sweep_cmd(workload: list[str], store: Path, workers, device) -> list[str]:
    """The ``warptrunc sweep`` command of one run."""
    cmd = [
        sys.executable,
        "-m",
        "warptrunc",
        "sweep",
        *workload,
        "--out",
        str(store),
        "--no-progress",
    ]
    if device:
        cmd += ["--device", device]
    if workers is not None:
        cmd += ["--workers", str(workers)]
    return cmd


def timed(cmd: list[str], log: Path, timeout: float | None) -> tuple[float, int]:
    """(wall time in s, return code; 124 if stopped at ``timeout`` s) of ``cmd``, its output
    appended to ``log``. The command runs in a session of its own, so a stop (SIGTERM, then
    SIGKILL after 10 s) reaches its Dask workers too."""
    t0 = time.perf_counter()
    with log.open("a") as fh:
        fh.write(f"$ {' '.join(cmd)}\n")
        fh.flush()
        p = subprocess.Popen(cmd, stdout=fh, stderr=subprocess.STDOUT, start_new_session=True)
        try:
            rc = p.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            for sig, wait in ((signal.SIGTERM, 10), (signal.SIGKILL, 30)):
                try:
                    os.killpg(p.pid, sig)
                    p.wait(timeout=wait)
                    break
                except (ProcessLookupError, subprocess.TimeoutExpired):
                    continue
            rc = 124
    return time.perf_counter() - t0, rc


def cluster_start(n: int, device) -> dict:
    """Seconds to start a local cluster of ``n`` workers (``start_s``), to warm every worker
    (``warm_s``: Warp started, a 64² surface made on its device) and to close it (``stop_s``),
    measured here, not inside a command; ``start_total_s`` is their sum."""
    from warptrunc.sweep.cluster import open_client

    def warm():
        from warptrunc._support.device import resolve_device
        from warptrunc.wm import wm_surface

        dev = resolve_device(device)
        wm_surface(2.5, 1e-3, L=1e-3, n=64, Rt=1e-5, seed=0, device=dev)
        return str(dev)

    t0 = time.perf_counter()
    with open_client(n, None, device, False) as (client, cluster, _):
        client.wait_for_workers(n, timeout=300)
        t1 = time.perf_counter()
        devices = sorted(client.run(warm).values())
        t2 = time.perf_counter()
        kind = type(cluster).__name__
    t3 = time.perf_counter()
    return dict(
        start_s=t1 - t0,
        warm_s=t2 - t1,
        stop_s=t3 - t2,
        start_total_s=t3 - t0,
        cluster=kind,
        worker_devices=devices,
    )


def store_measures(store: Path, n_workers: int) -> dict:
    """Where the time went, from the store: per device, parts (tasks), bytes, imbalance."""
    from warptrunc.sweep import load
    from warptrunc.sweep.curves import part_files, part_rows

    df = load(store)
    cases = df.drop_duplicates("case_id")
    per_dev = {}
    for dev, g in cases.groupby(cases["device"].fillna("none")):
        stamps = pd_times(g["finished_utc"])
        per_dev[str(dev)] = dict(
            cases=len(g),
            compute_s=float(np.nansum(g["seconds"])),
            last_utc=str(max(g["finished_utc"])),
            _last=stamps.max(),
        )
    lasts = [v.pop("_last") for v in per_dev.values()]
    share = max(1.0, n_workers / max(1, len(per_dev)))  # workers per device (CPU: all on one)
    parts = part_files(store / "curves")
    sizes = [len(held or []) for held in (part_rows(p) for p in parts)]
    return dict(
        cases=len(cases),
        rows=len(df),
        failed=int(cases["error"].notna().sum()),
        per_device=per_dev,
        compute_s=max((v["compute_s"] / share for v in per_dev.values()), default=0.0),
        compute_sum_s=float(np.nansum(cases["seconds"])),
        tail_s=float(max(lasts) - min(lasts)) if lasts else 0.0,
        parts=len(parts),
        cases_per_part=float(np.mean(sizes)) if sizes else 0.0,
        store_bytes=sum(f.stat().st_size for f in store.rglob("*") if f.is_file()),
        workers=n_workers,
    )


def pd_times(col) -> np.ndarray:
    """ISO time stamps as seconds since the epoch."""
    import pandas as pd

    return pd.to_datetime(col, utc=True).astype("int64").to_numpy() / 1e9


def bitwise_diff(a, b, skip=()) -> dict:
    """Columns of frames ``a`` and ``b`` (same shape, same order) that are not identical bit
    for bit (NaN equal to NaN): {column: {"rows": count, "max_abs": …, "max_rel": …}}."""
    if a.shape != b.shape or list(a.columns) != list(b.columns):
        return {"<shape>": {"a": list(a.shape), "b": list(b.shape)}}
    out = {}
    for c in a.columns:
        if c in skip:
            continue
        x, y = a[c].to_numpy(), b[c].to_numpy()
        if x.dtype.kind == "f" and y.dtype.kind == "f":
            x, y = x.astype(np.float64), y.astype(np.float64)
            same = (x.view(np.int64) == y.view(np.int64)) | (np.isnan(x) & np.isnan(y))
            if not same.all():
                d = np.abs(x - y)[~same]
                rel = d / np.maximum(np.abs(x[~same]), np.finfo(float).tiny)
                out[c] = dict(
                    rows=int((~same).sum()),
                    max_abs=float(np.nanmax(d, initial=0)),
                    max_rel=float(np.nanmax(rel, initial=0)),
                )
        else:
            same = np.array([_same(u, v) for u, v in zip(x, y, strict=True)])
            if not same.all():
                out[c] = dict(rows=int((~same).sum()))
    return out


def _isna(u) -> bool:
    return u is None or (np.ndim(u) == 0 and bool(pd_isna(u)))


def pd_isna(u) -> bool:
    """pandas.isna of a scalar."""
    import pandas as pd

    return pd.isna(u)


def _same(u, v) -> bool:
    """Two cells of an object column equal (None/NA/NaN equal to each other)."""
    if _isna(u) or _isna(v):
        return _isna(u) and _isna(v)
    return bool(np.all(u == v))


def check(out: Path, spec: dict, device, workers: list[int]) -> dict:
    """Item 4: in process twice on one device, then on each count of ``workers``, compared
    bit for bit with the first in-process run."""
    from warptrunc.sweep import (
        RUN_COLUMNS,
        SweepExecution,
        SweepGrid,
        SweepOptions,
        load,
        load_curves,
        run_sweep,
    )

    grid = SweepGrid(spec["D"], [0.01], spec["seeds"])
    opts = dict(
        n=spec["n"],
        bem_fractions=tuple(spec.get("bem", ())),
        fractal_methods=tuple(spec.get("fractal", ())),
    )
    options = SweepOptions(**{k: v or None for k, v in opts.items()})  # () is off: None
    runs = {"inproc_a": {}, "inproc_b": {}, **{f"workers_{w}": dict(workers=w) for w in workers}}
    frames = {}
    times = {}
    for name, kw in runs.items():
        t0 = time.perf_counter()
        run_sweep(
            grid,
            out / f"check_{name}",
            options=options,
            execution=SweepExecution(**kw),
            overwrite=True,
            progress=False,
            device=device if not kw else (device if device == "cpu" else None),
        )
        times[name] = time.perf_counter() - t0
        df = load(out / f"check_{name}")
        frames[name] = (df, load_curves(out / f"check_{name}"), sorted(set(df["device"])))
    ref_rows, ref_curves, _ = frames["inproc_a"]
    res = dict(
        grid=dict(D=spec["D"], delta=[0.01], seeds=spec["seeds"]),
        options=opts,
        cases=len(grid),
        seconds=times,
        devices={k: v[2] for k, v in frames.items()},
    )
    for name in list(runs)[1:]:
        rows, curves, _ = frames[name]
        skip = {*RUN_COLUMNS, *(c for c in rows.columns if c.endswith("seconds"))}  # times
        res[name] = dict(
            rows_differ=bitwise_diff(ref_rows, rows, skip=skip),
            curves_differ=bitwise_diff(ref_curves, curves),
        )
        res[name]["identical"] = not res[name]["rows_differ"] and not res[name]["curves_differ"]
    for name in runs:
        shutil.rmtree(out / f"check_{name}", ignore_errors=True)
    return res


def expected_s(base, fixed: float, n, n_gpus: int, starts: dict) -> float | None:
    """A guess of a workers run's wall time (s), to skip one that would not finish in the
    budget: the in-process work shared by min(n, GPUs) workers, the fixed cost and a cluster
    start (measured, else 5 s). None for the in-process run or before it."""
    if n is None or not base:
        return None
    start = starts.get(n, {}).get("start_total_s", 5.0)
    return fixed + start + max(0.0, base - fixed) / max(1, min(n, n_gpus or 1))


def default_workers(n_gpus: int) -> list[int]:
    """1, 2, 4, … up to the GPUs present, and their count; [1, 2] without a GPU."""
    if n_gpus <= 0:
        return [1, 2]
    ws = [w for w in (1, 2, 4, 8, 16, 32) if w <= n_gpus]
    return ws if ws[-1] == n_gpus else [*ws, n_gpus]


def table(results: dict) -> str:
    """The runs as a plain-text table."""
    head = (
        f"{'workload':9} {'run':10} {'cases':>6} {'wall s':>8} {'×':>6} {'fixed':>6} "
        f"{'start':>6} {'compute':>8} {'tail':>6} {'other':>7} {'parts':>6}"
    )
    lines = [head, "-" * len(head)]

    def order(r):  # light before elastic; in process, then 1, 2, 4 … workers
        n = 0 if r["run"] == "inproc" else int(r["run"].split("_")[1])
        return (r["workload"] != "light", n)

    for r in sorted(results["runs"], key=order):
        if r.get("status"):  # skipped, failed or stopped
            wall = f" after {r['wall_s']:.1f} s" if "wall_s" in r else ""
            lines.append(f"{r['workload']:9} {r['run']:10} {r['status']}{wall}")
            continue
        f = lambda k, w=6, r=r: f"{r[k]:{w}.1f}" if isinstance(r.get(k), float) else f"{'-':>{w}}"  # noqa: E731
        lines.append(
            f"{r['workload']:9} {r['run']:10} {r.get('cases', 0):6d} {r['wall_s']:8.1f} "
            f"{r.get('speedup', float('nan')):6.2f} {f('fixed_s')} {f('start_s')} "
            f"{f('compute_s', 8)} {f('tail_s')} {f('other_s', 7)} "
            f"{r.get('parts', 0):6d}"
        )
    for kind, c in results.get("check", {}).items():
        for name in [k for k in c if k.startswith(("inproc_b", "workers_"))]:
            d = c[name]
            what = (
                "identical"
                if d["identical"]
                else "differ in "
                + ", ".join([*d["rows_differ"], *(f"curve:{k}" for k in d["curves_differ"])])
            )
            lines.append(
                f"check {kind} (n={c['options']['n']}, {c['cases']} cases): {name} vs "
                f"inproc_a: {what}"
            )
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--out", type=Path, default=Path("bench_workers"), help="output folder")
    ap.add_argument(
        "--full",
        action="store_true",
        help="the full sizes (2000 light cases at 2048², 96 elastic at 4096², "
        "check at 1024²) instead of the small CPU ones (64²)",
    )
    ap.add_argument(
        "--runs",
        nargs="+",
        default=["light", "elastic", "check"],
        choices=("light", "elastic", "check"),
    )
    ap.add_argument(
        "--workers",
        type=int,
        nargs="+",
        default=None,
        help="worker counts (default: 1, 2, 4, … up to the GPUs present; 1 2 without a GPU)",
    )
    ap.add_argument(
        "--check-workers", type=int, nargs="+", default=[2], help="worker counts of the check"
    )
    ap.add_argument(
        "--device",
        default=None,
        help="device of the in-process runs (and of every worker with cpu); "
        "default: cuda:0 on a GPU machine, the workers one GPU each",
    )
    ap.add_argument(
        "--light-args",
        default=None,
        help="replace the light workload's sweep arguments (one quoted string, "
        'e.g. "--n 512 --D 2.5 --delta 0.01 --seeds 0-99")',
    )
    ap.add_argument(
        "--light-cases",
        type=int,
        default=None,
        help="light cases (count) over the light workload's D values: its seeds "
        "become 0-(N/len(D)−1), e.g. 20000 with --full for seeds 0-4999 over 4 D "
        "values; default: the workload's own (2000 with --full)",
    )
    ap.add_argument(
        "--elastic-args",
        default=None,
        help="replace the elastic workload's sweep arguments (one quoted string)",
    )
    ap.add_argument(
        "--budget-s",
        type=float,
        default=None,
        help="start no timed run after this many seconds (s), nor one expected to "
        "end past budget + grace; they are listed as skipped (the check still "
        "runs)",
    )
    ap.add_argument(
        "--grace-s",
        type=float,
        default=60.0,
        help="with --budget-s: a timed command is stopped this long after the budget "
        "(s), and listed as failed (rc 124)",
    )
    ap.add_argument("--timeout-s", type=float, default=None, help="limit of one command (s)")
    args = ap.parse_args(argv)

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from _common import git_commit

    sizes = SIZES["full" if args.full else "small"]
    workloads = {
        "light": shlex.split(args.light_args) if args.light_args else sizes["light"],
        "elastic": shlex.split(args.elastic_args) if args.elastic_args else sizes["elastic"],
    }
    if args.light_cases is not None:
        workloads["light"] = with_cases(workloads["light"], args.light_cases)
    out = args.out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    log = out / "commands.log"
    gpu_lines = gpus()
    wdevs = warp_devices()
    n_gpus = sum(1 for d in wdevs if "(cuda:" in d)
    counts = args.workers or default_workers(n_gpus if args.device in (None, "") else 0)
    results = dict(
        benchmark="benchmark_workers",
        commit=git_commit(),
        host=platform.node(),
        started_utc=datetime.now(timezone.utc).isoformat(timespec="seconds"),
        gpus=gpu_lines,
        warp_devices=wdevs,
        cpus=os.cpu_count(),
        python=platform.python_version(),
        sizes="full" if args.full else "small",
        device=args.device,
        workers=counts,
        runs=[],
    )
    path = out / "benchmark_workers.json"

    def save():
        path.write_text(json.dumps(results, indent=1, default=str) + "\n")

    t_begin = time.perf_counter()
    over = lambda: args.budget_s is not None and time.perf_counter() - t_begin > args.budget_s  # noqa: E731

    def limit() -> float | None:
        """A command's time limit (s): --timeout-s, and no later than budget + grace."""
        if args.budget_s is None:
            return args.timeout_s
        left = max(1.0, args.budget_s + args.grace_s - (time.perf_counter() - t_begin))
        return left if args.timeout_s is None else min(args.timeout_s, left)

    starts: dict[int, dict] = {}
    for wl in [w for w in ("light", "elastic") if w in args.runs]:
        store = out / f"store_{wl}"
        shutil.rmtree(store, ignore_errors=True)
        spent, rc = timed(
            sweep_cmd(_seeds_first(workloads[wl]), store, None, args.device), log, args.timeout_s
        )
        results.setdefault("warmup_s", {})[wl] = spent
        base, fixed = None, 0.0
        for n in [None, *sorted(counts, reverse=True)]:  # past the budget, 1 worker goes first
            name = "inproc" if n is None else f"workers_{n}"
            rec = dict(workload=wl, run=name)
            results["runs"].append(rec)
            guess = expected_s(base, fixed, n, n_gpus, starts)
            if over() or (guess is not None and limit() is not None and guess > limit()):
                rec["status"] = "skipped (budget" + ("" if over() else f": ≈ {guess:.0f} s") + ")"
                save()
                continue
            w = None if n is None else ("auto" if n == n_gpus and not args.device else n)
            cmd = sweep_cmd(workloads[wl], store, w, args.device)
            shutil.rmtree(store, ignore_errors=True)
            wall, rc = timed(cmd, log, limit())
            rec.update(command=" ".join(cmd[1:]).replace(f"{out}/", "<out>/"), wall_s=wall, rc=rc)
            if rc != 0:
                rec["status"] = f"failed (rc {rc}, see commands.log)"
                save()
                continue
            rec.update(store_measures(store, n or 1))
            if n is None:
                base = wall
                rec["fixed_s"], _ = timed(cmd, log, args.timeout_s)  # a finished store: no work
                fixed = rec["fixed_s"]
                rec["start_s"] = 0.0
            else:
                if n not in starts:
                    starts[n] = cluster_start(n, args.device if args.device == "cpu" else None)
                rec.update(
                    start_s=starts[n]["start_total_s"],
                    cluster=starts[n]["cluster"],
                    worker_devices=starts[n]["worker_devices"],
                    fixed_s=fixed,
                )
            rec["other_s"] = wall - rec["fixed_s"] - rec["start_s"] - rec["compute_s"]
            rec["speedup"] = base / wall if base else float("nan")
            save()
        shutil.rmtree(store, ignore_errors=True)
    results["cluster_start"] = {str(k): v for k, v in starts.items()}
    save()
    if "check" in args.runs:  # after the timed runs (it uses this process's GPU); no budget
        results["check"] = {}
        for kind, spec in sizes["check"].items():
            results["check"][kind] = check(out, spec, args.device, args.check_workers)
            save()
    results["total_s"] = time.perf_counter() - t_begin
    save()
    print(
        f"commit {results['commit']}; {len(gpu_lines)} GPU(s): "
        f"{'; '.join(gpu_lines) or 'none'}; results in {path}"
    )
    print(table(results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
