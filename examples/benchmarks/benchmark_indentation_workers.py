# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: the ``warptrunc reproduce`` indentation stage in
process and on 1, 2, 4 … Dask workers (one GPU each), side by side, as whole fresh processes,
and whether the workers store what in process stores, bit for bit.

What it runs
    ``reproduce(profile, OUT, stages="indentation", workers=W, device=D)`` — the CLI's
    ``warptrunc reproduce --profile paper --stages indentation --workers W`` — as a child process
    of this script (its ``run`` subcommand), each time into a fresh folder under ``--timeout-s``:
    first in process (W none, D = ``--device``), then once per count of ``--workers`` (written
    ``auto`` where it is the number of visible GPUs; by default the largest count first, so a
    budget cuts the 1-worker run, ≈ in process, first). Before them an untimed warm-up child
    (the profile at ``--warmup-n`` pixels, one surface, H = ∞ and the faces' H, one placement)
    compiles Warp's kernels into the kernel cache the workers share, so no timed process
    compiles.

The profile: a departure from the paper
    At the paper's map (``indentation.n`` = 10240: 97.7 nm pixels over 1 mm) the stage costs
    about 2250 GPU-seconds (``benchmarks/records/reproduce_paper_indentation_h100x4_ad12c18/indentation_paper_h100x4.json``), too much for one
    10-minute GPU call. The runs use the paper profile with ``indentation.n`` = N
    (``--n`` N = 2048 by default): 488 nm pixels over ``indentation.L`` =
    1 mm, every other field the paper profile's (surfaces, punches, loads, the H sweep, the
    statistics, the punch faces, the refinement). The JSON records every field that differs
    from ``PROFILES["paper"]`` (``profile.departures``).

Per run
    ``wall_s``: the whole child process (imports, Warp's start, the cluster's start and stop,
    the stage, the figures and results.json); ``speedup``: in process's wall / this one's. From
    the store (``OUT/indentation/*.json``, one file per piece, its parts merged): ``pieces``,
    ``parts``, ``pieces_s`` (the pieces' own seconds, ``seconds.piece_s``: each part's solves,
    device time), ``surfaces_s`` (the realisations' generation), ``resolution_s`` (the
    resolution check), ``stage_s`` (the stage's wall time, ``stages/indentation.json``).
    ``busiest_device_s``: in process, pieces + surfaces + resolution; on workers, the busiest
    device's sum of its tasks' compute times (Dask's task stream, taken by the child around the
    cluster ``reproduce`` opens: a piece merged from parts records only its devices). In process
    also ``fixed_s``: the same child again on its finished store (nothing to compute).

Identity (item 4)
    Each worker run's store against the in-process one, value by value: every piece file and
    the resolution check (``OUT/indentation/*.json``), ``stages/indentation.json`` (parameters
    and result) and ``results.json``'s ``analysis`` (the fits α, β and their intervals, depths,
    the resolution table). Numbers by their IEEE bits (NaN equal to itself), strings and
    booleans exactly; left out: the keys that say where, when or how fast something ran
    (``_indentation_identity.EXCLUDED``, keys ending ``_s``), results.json's ``meta`` and the figures. Per run
    ``identical`` and, per differing field, the count and the largest differences.

Output
    ``<out>/benchmark_indentation_workers.json``, rewritten after every run: the machine, the
    commit, the profile and its departures, every command and its measures; ``commands.log``;
    ``values_<run>.json.gz`` (what the identity check reads, per run: a later call compares
    against it with ``--reference``); a table at the end.

Run
    # CPU dry run (the tiny profile at 128², 2 local CPU workers): about 30 s on 2 cores
    python examples/benchmarks/benchmark_indentation_workers.py --profile tiny --n 128 \\
        --device cpu --workers 2 --out /tmp/biw
    # a GPU node: the paper profile at 2048², in process, then N, 2, 1 workers; or in two
    # device calls: in process alone (--workers with no count), then the workers against it
    # (--no-inprocess --reference A/values_inproc.json.gz --reference-wall S)
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import math
import os
import platform
import re
import shutil
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

HERE = Path(__file__).resolve()
sys.path.insert(0, str(HERE.parent))
from _indentation_identity import (  # noqa: E402  (beside this script)
    _load,
    compare,
    identity,
    read_values,
    stored_values,
    write_values,
)

PART_FILE = re.compile(r"__p\d+r\d+$")
"""Stem of a part file (``<piece>__p<k>r<r>``): a piece not yet merged."""


# --- the child: one reproduce call ------------------------------------------------------------


def build_profile(name: str, n: int | None, warmup: bool = False):
    """The run's profile: ``PROFILES[name]`` with ``indentation.n = n``; for the warm-up also
    one surface (the faces'), one realisation, one placement, H = ∞ and the faces' H."""
    from warptrunc.reproduce import PROFILES

    p = PROFILES[name]
    st = p.indentation
    if n:
        st = st.replace(n=int(n))
    if warmup:
        s = st.face_surface or st.surfaces[0]
        finite = [h for h in st.hardness if math.isfinite(h)]
        h = st.face_hardness if st.face_surface else (finite or [math.inf])[0]
        st = st.replace(
            surfaces=(s,),
            seeds=st.seeds[:1],
            stats_placements=1,
            hardness=tuple(sorted({math.inf, h})),
            protocol=st.protocol.replace(placements=1),
        )
    return dataclasses.replace(p, indentation=st)


def departures(p) -> dict:
    """The fields of ``p`` that the indentation stage reads (``name``, ``indentation``: its own,
    then ``protocol.*``, ``solver.*``, ``material.*``) and that differ from ``PROFILES["paper"]``:
    {field: {paper, here}} (lengths in m)."""
    from warptrunc.reproduce import PROFILES

    def flat(prof) -> dict:
        st = prof.indentation.to_dict()
        out = {"name": prof.name}
        for k, v in st.items():
            if isinstance(v, dict):
                out.update({f"indentation.{k}.{kk}": vv for kk, vv in v.items()})
            else:
                out[f"indentation.{k}"] = v
        return out

    ref, mine = flat(PROFILES["paper"]), flat(p)
    out = {k: {"paper": ref.get(k), "here": v} for k, v in mine.items() if ref.get(k) != v}
    out = json.loads(json.dumps(out).replace("Infinity", '"inf"'))  # H = ∞ as "inf": plain JSON
    if "indentation.n" in out or "indentation.L" in out:
        out["indentation.dx_nm"] = {
            "paper": PROFILES["paper"].indentation.pixel_size * 1e9,
            "here": p.indentation.pixel_size * 1e9,
        }
    return out


def _worker_device() -> str:
    """A worker's device: its pinned ``$WARPTRUNC_DEVICE``, else its first visible GPU."""
    env = os.environ
    if env.get("WARPTRUNC_DEVICE"):
        return env["WARPTRUNC_DEVICE"]
    vis = env.get("CUDA_VISIBLE_DEVICES", "")
    return f"CUDA_VISIBLE_DEVICES={vis.split(',')[0]}" if vis else "default"


def record_tasks(rec: dict, cpu: bool) -> None:
    """Wrap :func:`warptrunc.sweep.cluster.open_client` (``reproduce`` imports it when it opens
    its cluster) so that the cluster's task stream and every worker's device land in ``rec``."""
    from distributed import get_task_stream

    import warptrunc.sweep.cluster as cl

    opened = cl.open_client

    @contextlib.contextmanager
    def recording(*a, **kw):
        with opened(*a, **kw) as (client, cluster, own), get_task_stream(client=client) as ts:
            try:
                yield client, cluster, own
            finally:
                devs = client.run(_worker_device)
                rec["worker_devices"] = {w: "cpu" if cpu else d for w, d in devs.items()}
        rec["tasks"] = []
        for t in ts.data:
            ss = [s for s in t.get("startstops", ()) if s.get("action") == "compute"]
            if ss:
                rec["tasks"].append(
                    dict(
                        key=str(t.get("key")),
                        worker=t.get("worker"),
                        status=t.get("status"),
                        start=min(s["start"] for s in ss),
                        stop=max(s["stop"] for s in ss),
                        compute_s=sum(s["stop"] - s["start"] for s in ss),
                    )
                )

    cl.open_client = recording


def child(args: argparse.Namespace) -> int:
    """The ``run`` subcommand: one ``reproduce`` call; its record goes to ``--record``."""
    from warptrunc.reproduce import reproduce

    t0 = time.perf_counter()
    p = build_profile(args.profile, args.n, args.warmup)
    w = (
        None
        if args.workers == "none"
        else (args.workers if args.workers == "auto" else int(args.workers))
    )
    rec: dict = {"tasks": [], "worker_devices": {}}
    if w is not None:
        record_tasks(rec, args.device == "cpu")
    cmd = (
        f"warptrunc reproduce --profile {args.profile} (indentation.n={p.indentation.n}) "
        f"--stages indentation --device {args.device} --out {args.out}"
        + ("" if w is None else f" --workers {w}")
    )
    doc = reproduce(
        p,
        args.out,
        stages="indentation",
        workers=w,
        device=args.device,
        commit=os.environ.get("WARPTRUNC_GIT_COMMIT") or None,
    )
    m = doc["meta"]
    rec.update(
        command=cmd,
        child_wall_s=time.perf_counter() - t0,
        reproduce_wall_s=m["wall_s"],
        stage_wall_s=m["stage_wall_s"],
        computed=m["computed"],
        reused=m["reused"],
        incomplete=m.get("incomplete"),
        device=f"{m['provenance']['device']} ({m['provenance']['device_name'] or ''})",
    )
    if args.record:
        Path(args.record).write_text(json.dumps(rec, indent=1, default=str) + "\n")
    return 3 if m.get("incomplete") else 0


# --- the parent: measures from the store ------------------------------------------------------


def store_measures(store: Path, rec: dict | None, in_process: bool) -> dict:
    """Pieces, parts and seconds from the store; the busiest device (see the module's doc)."""
    folder = store / "indentation"
    pieces = [
        _load(f)
        for f in sorted(folder.glob("*.json"))
        if f.name != "resolution.json" and not PART_FILE.search(f.stem)
    ]
    res = folder / "resolution.json"
    stage = store / "stages" / "indentation.json"
    devs = set()
    for d in pieces:
        devs.update(d["device"] if isinstance(d.get("device"), list) else [str(d.get("device"))])
    out = dict(
        pieces=len(pieces),
        parts=sum(int(d.get("n_parts", 1)) for d in pieces),
        pieces_s=sum(d["seconds"].get("piece_s", 0.0) for d in pieces),
        surfaces_s=sum(d["seconds"].get("surface_s", 0.0) for d in pieces),
        resolution_s=_load(res).get("seconds", 0.0) if res.exists() else 0.0,
        stage_s=_load(stage).get("seconds") if stage.exists() else None,
        store_devices=sorted(devs),
    )
    if in_process or not rec or not rec.get("tasks"):
        total = out["pieces_s"] + out["surfaces_s"] + out["resolution_s"]
        out.update(
            per_device={",".join(out["store_devices"]): total},
            busiest_device_s=total,
            busiest_from="store",
        )
        return out
    per_worker: dict[str, float] = {}
    for t in rec["tasks"]:
        per_worker[t["worker"]] = per_worker.get(t["worker"], 0.0) + t["compute_s"]
    per_dev: dict[str, float] = {}
    for w, s in per_worker.items():
        dev = rec["worker_devices"].get(w, w)
        per_dev[dev] = per_dev.get(dev, 0.0) + s
    out.update(
        tasks=len(rec["tasks"]),
        per_worker=per_worker,
        per_device=per_dev,
        busiest_device_s=max(per_dev.values()),
        busiest_worker_s=max(per_worker.values()),
        busiest_from="task stream",
    )
    return out


# --- the parent -------------------------------------------------------------------------------


def default_workers(n_gpus: int) -> list[int]:
    """1, 2 and the visible GPUs' count, deduplicated, largest first ([2, 1] without a GPU)."""
    return sorted({1, 2, *([n_gpus] if n_gpus > 0 else [])}, reverse=True)


def child_cmd(args, store: Path, record: Path, workers, warmup: bool = False) -> list[str]:
    """The command line of one child."""
    cmd = [
        sys.executable,
        str(HERE),
        "run",
        "--profile",
        args.profile,
        "--n",
        str(min(args.n, args.warmup_n) if warmup else args.n),
        "--device",
        args.device,
        "--workers",
        "none" if workers is None else str(workers),
        "--out",
        str(store),
        "--record",
        str(record),
    ]
    return [*cmd, "--warmup"] if warmup else cmd


def _same_text(r: dict) -> str:
    """The identity column of a run."""
    ident = r.get("identity")
    if ident is None:
        return "(reference)" if r["run"] == "inproc" else "-"
    if ident.get("error"):
        return f"not compared: {ident['error']}"
    if ident["identical"]:
        return f"yes ({ident['values_compared']} values)"
    field, worst = next(iter(ident["fields"].items()))
    return f"no: {ident['n_fields']} fields, e.g. {field} (max rel {worst['max_rel']:.2g})"


def table(results: dict) -> str:
    """The runs as a plain-text table."""
    head = (
        f"{'run':11} {'wall s':>8} {'×':>6} {'pieces':>6} {'parts':>6} {'Σpiece s':>9} "
        f"{'busiest s':>9} {'fixed s':>7}  identical"
    )
    lines = [head, "-" * (len(head) + 8)]
    order = lambda r: 0 if r["run"].startswith("inproc") else int(r["run"].split("_")[1])  # noqa: E731
    num = lambda v, w: f"{v:{w}.{2 if w == 6 else 1}f}" if isinstance(v, float) else f"{'-':>{w}}"  # noqa: E731
    for r in sorted(results["runs"], key=order):
        if r.get("status"):
            lines.append(
                f"{r['run']:11} {r['status']}"
                + (f" after {r['wall_s']:.1f} s" if "wall_s" in r else "")
            )
            continue
        lines.append(
            f"{r['run']:11} {r['wall_s']:8.1f} {num(r.get('speedup'), 6)} "
            f"{r['pieces']:6d} {r['parts']:6d} {r['pieces_s']:9.1f} "
            f"{r['busiest_device_s']:9.1f} {num(r.get('fixed_s'), 7)}  {_same_text(r)}"
        )
    return "\n".join(lines)


def parser() -> argparse.ArgumentParser:
    """The parent's options (the child's: ``run --help``)."""
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0] + " Subcommand `run`: one "
        "child (see `run --help`); `compare REF OTHER ...`: the identity "
        "check of values files of separate benchmark processes.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    ap.add_argument(
        "--out",
        type=Path,
        default=Path("bench_indentation_workers"),
        help="output folder (the JSON, commands.log, the stores while they run)",
    )
    ap.add_argument(
        "--profile",
        default="paper",
        choices=("paper", "quick", "tiny"),
        help="reproduce profile, its indentation map replaced by --n",
    )
    ap.add_argument(
        "--n",
        type=int,
        default=2048,
        help="pixels per side of the indentation maps over indentation.L (1 mm): "
        "2048 gives 488 nm pixels (the paper: 10240, 97.7 nm)",
    )
    ap.add_argument(
        "--workers",
        type=int,
        nargs="*",
        default=None,
        help="worker counts, run in this order (default: the visible GPUs' count, "
        "2 and 1; 2 1 without a GPU)",
    )
    ap.add_argument(
        "--device",
        default=None,
        help="device of the in-process run and of the driver (cpu: also of every "
        "worker); default cuda:0 where CUDA is visible, else cpu",
    )
    ap.add_argument(
        "--warmup-n",
        type=int,
        default=256,
        help="pixels per side of the untimed warm-up run (capped at --n; 0: none)",
    )
    ap.add_argument(
        "--budget-s",
        type=float,
        default=None,
        help="start no timed run after this many seconds (s) from the start, nor one "
        "expected to end past it; they are listed as 'skipped: budget'",
    )
    ap.add_argument(
        "--grace-s",
        type=float,
        default=30.0,
        help="with --budget-s: a child is stopped this long after the budget (s)",
    )
    ap.add_argument("--timeout-s", type=float, default=None, help="limit of one child (s)")
    ap.add_argument(
        "--keep-stores",
        action="store_true",
        help="keep every run's reproduction folder under --out",
    )
    ap.add_argument(
        "--no-inprocess",
        action="store_true",
        help="skip the in-process run (its figures from --reference and "
        "--reference-wall, e.g. of an earlier device call)",
    )
    ap.add_argument(
        "--reference",
        type=Path,
        default=None,
        help="values_inproc.json.gz of an earlier in-process run: the worker runs' "
        "identity check against it (every run writes its values_<run>.json.gz)",
    )
    ap.add_argument(
        "--reference-wall",
        type=float,
        default=None,
        help="that run's wall (s): the speed-ups against it",
    )
    return ap


def child_parser() -> argparse.ArgumentParser:
    """The ``run`` subcommand's options."""
    ap = argparse.ArgumentParser(
        prog=f"{HERE.name} run", description="one reproduce call of the benchmark (a child)"
    )
    ap.add_argument("--profile", default="paper", choices=("paper", "quick", "tiny"))
    ap.add_argument("--n", type=int, default=2048, help="pixels per side of the indentation maps")
    ap.add_argument("--device", default="cpu", help="Warp device of the driver (cpu: also tasks)")
    ap.add_argument("--workers", default="none", help="none (in process), a count or auto")
    ap.add_argument("--out", type=Path, required=True, help="fresh reproduction folder")
    ap.add_argument("--record", type=Path, default=None, help="JSON of the child's measures")
    ap.add_argument("--warmup", action="store_true", help="the small warm-up profile")
    return ap


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] == "run":
        return child(child_parser().parse_args(argv[1:]))
    if argv and argv[0] == "compare":
        return compare(argv[1:], prog=f"{HERE.name} compare")
    args = parser().parse_args(argv)
    sys.path.insert(0, str(HERE.parent))
    from _common import ROOT, git_commit
    from benchmark_workers import expected_s, gpus, timed

    from warptrunc.sweep.cluster import resolve_workers

    gpu_lines = gpus()
    n_gpus = resolve_workers("auto") if gpu_lines else 0  # CUDA_VISIBLE_DEVICES respected
    args.device = args.device or ("cuda:0" if n_gpus else "cpu")
    counts = args.workers
    if counts is None:  # (an empty --workers: in process only)
        counts = default_workers(n_gpus if args.device != "cpu" else 0)
    commit = git_commit()
    if commit:  # every child records the same commit
        os.environ["WARPTRUNC_GIT_COMMIT"] = commit
    out = args.out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    log, path = out / "commands.log", out / "benchmark_indentation_workers.json"
    try:
        from importlib.metadata import version

        warp_version = version("warp-lang")
    except Exception:
        warp_version = "unknown"
    p = build_profile(args.profile, args.n)
    results = dict(
        benchmark="benchmark_indentation_workers",
        commit=commit,
        host=platform.node(),
        started_utc=datetime.now(timezone.utc).isoformat(timespec="seconds"),
        machine=dict(
            gpus=gpu_lines or "cpu",
            visible_gpus=n_gpus,
            cpus=os.cpu_count(),
            cuda_visible_devices=os.environ.get("CUDA_VISIBLE_DEVICES"),
            warp=warp_version,
            python=platform.python_version(),
        ),
        profile=dict(
            name=args.profile,
            indentation_n=p.indentation.n,
            indentation_L_m=p.indentation.L,
            departures=departures(p),
        ),
        device=args.device,
        workers=counts,
        budget_s=args.budget_s,
        timeout_s=args.timeout_s,
        runs=[],
    )

    def save():
        path.write_text(json.dumps(results, indent=1, default=str) + "\n")

    t_begin = time.perf_counter()
    spent = lambda: time.perf_counter() - t_begin  # noqa: E731

    def limit() -> float | None:
        if args.budget_s is None:
            return args.timeout_s
        left = max(1.0, args.budget_s + args.grace_s - spent())
        return left if args.timeout_s is None else min(args.timeout_s, left)

    def shown(cmd: list[str]) -> str:  # the command as recorded: paths relative
        text = " ".join(cmd[1:]).replace(f"{out}/", "<out>/")
        return text.replace(
            str(HERE), str(HERE.relative_to(ROOT)) if HERE.is_relative_to(ROOT) else str(HERE)
        )

    def run(name: str, workers, warmup: bool = False) -> tuple[dict, Path]:
        store, record = out / f"store_{name}", out / f"record_{name}.json"
        shutil.rmtree(store, ignore_errors=True)
        record.unlink(missing_ok=True)
        cmd = child_cmd(args, store, record, workers, warmup)
        wall, rc = timed(cmd, log, limit())
        rec = dict(run=name, command=shown(cmd), wall_s=wall, rc=rc)
        if rc != 0:
            rec["status"] = f"failed (rc {rc}, see commands.log)"
        elif record.exists():
            rec["child"] = _load(record)
        record.unlink(missing_ok=True)
        return rec, store

    if args.warmup_n > 0:
        w, store = run("warmup", None, warmup=True)
        results["warmup"] = w
        save()
        shutil.rmtree(store, ignore_errors=True)
    base, fixed = args.reference_wall, None
    ref_store = read_values(args.reference) if args.reference else None
    for n in ([] if args.no_inprocess else [None]) + list(counts):
        name = "inproc" if n is None else f"workers_{n}"
        guess = expected_s(base, fixed or 0.0, n, n_gpus, {})
        left = None if args.budget_s is None else args.budget_s - spent()
        if left is not None and (left <= 0 or (guess is not None and guess > left)):
            results["runs"].append(
                dict(
                    run=name,
                    status="skipped: budget"
                    + ("" if guess is None else f" (≈ {guess:.0f} s, {max(left, 0):.0f} s left)"),
                )
            )
            save()
            continue
        w = None if n is None else ("auto" if n == n_gpus and args.device != "cpu" else n)
        rec, store = run(name, w)
        results["runs"].append(rec)
        if "status" not in rec:
            try:
                rec.update(store_measures(store, rec.get("child"), n is None))
            except (OSError, KeyError, ValueError) as exc:  # a store the child left unfinished
                rec["status"] = f"failed: store unreadable ({exc!r})"
        if "status" not in rec:
            try:  # kept (small), so that a later call can compare against this run
                write_values(out / f"values_{name}.json.gz", stored_values(store))
            except (OSError, KeyError, ValueError) as exc:
                rec["values_error"] = repr(exc)
            if n is None:
                base, ref_store = rec["wall_s"], store
                again = child_cmd(args, store, out / "record_fixed.json", None)
                rec["fixed_s"], frc = timed(again, log, limit())  # a finished store: no work
                rec["fixed_command"] = shown(again)
                (out / "record_fixed.json").unlink(missing_ok=True)
                if frc != 0:
                    rec["fixed_s"] = f"failed (rc {frc})"
                fixed = rec["fixed_s"] if isinstance(rec["fixed_s"], float) else None
            elif ref_store is not None:
                try:
                    rec["identity"] = identity(ref_store, store)
                except (OSError, KeyError, ValueError) as exc:
                    rec["identity"] = {"identical": None, "error": repr(exc)}
            rec["speedup"] = base / rec["wall_s"] if base else None
        save()
        if n is not None and not args.keep_stores:
            shutil.rmtree(store, ignore_errors=True)
    if isinstance(ref_store, Path) and not args.keep_stores:
        shutil.rmtree(ref_store, ignore_errors=True)
    results["total_s"] = spent()
    save()
    print(
        f"commit {commit}; {len(gpu_lines)} GPU(s): {'; '.join(gpu_lines) or 'none'}; profile "
        f"{args.profile} at indentation.n={p.indentation.n} on {args.device}; results in {path}"
    )
    print(table(results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
