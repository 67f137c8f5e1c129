# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Benchmark: ``warptrunc analyze`` as a whole process, against the floor of any Warp program.

What it shows
    * **job**: ``--runs`` fresh processes of ``warptrunc analyze --n N --device D`` (both
      default figures written), wall time from spawn to exit, after one warm-up run (the
      kernel cache filled);
    * **floor**: as many fresh processes of
      ``python -c "import warp; warp.init(); warp.get_device(D)"``, interleaved with the job's
      runs (so both see the same machine load), and of ``python -c pass`` (the interpreter);
    * **excess** = median(job) − median(floor): what warptrunc adds to a Warp program's start
      (at 10240² on one GPU it is about 1 s: ``benchmarks/records/startup_*.json``);
    * **breakdown**: one more fresh process runs the job in-process (``warptrunc.cli.main``)
      with timers around its phases — the imports (Warp, warptrunc's analysis path), ``wp.init``,
      the device (CUDA context), generation, truncation, the island pass, the fit, fit.json's
      provenance, the wait for the two figures (drawn by the job's figure process,
      ``warptrunc.plot._worker``, which imports matplotlib while the job computes) and the rest
      (CSV, JSON, the staged move) — each phase synchronising the device at its end.
      The job then runs a second time in the same process: the difference of a phase between
      the two runs is its one-time cost (loading the Warp modules from the kernel cache, lazy
      imports), the second run its steady cost;
    * **imports**: ``python -X importtime`` of the job, the largest top-level imports.

    A JSON record (``startup_<device>.json``; kept as ``benchmarks/records/startup_<machine>_<commit>.json``)
    goes under ``--out``; a table is printed last.

Run
    python examples/benchmarks/startup.py --n 1024 --device cpu --out bench
    python examples/benchmarks/startup.py --n 10240 --device cuda:0 --out $OUT
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PHASES = (
    "import warp",
    "wp.init",
    "device",
    "import analysis path",
    "generation",
    "truncation",
    "island pass",
    "fit",
    "provenance",
    "wait for the figures",
    "rest (CSV, JSON, move)",
)


def job_cmd(n: int, device: str, out: Path) -> list[str]:
    """The job's command line: the ``warptrunc`` console script beside this interpreter (or
    ``python -m warptrunc``)."""
    exe = Path(sys.executable).with_name("warptrunc")
    head = [str(exe)] if exe.exists() else [sys.executable, "-m", "warptrunc"]
    return [*head, "analyze", "--n", str(n), "--device", device, "--out", str(out)]


def wall(cmd: list[str], env: dict | None = None) -> float:
    """Wall time (s) of a fresh process from spawn to exit; raises if it fails."""
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    t = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError(f"{cmd} failed: {r.stderr[-2000:]}")
    return t


class Phases:
    """Exclusive wall time per phase: a phase called inside another (the island pass's fit)
    counts for itself only; every phase synchronises ``dev`` at its end."""

    def __init__(self, sync) -> None:
        self.acc: dict[str, float] = {}
        self.stack: list[list] = []
        self.sync = sync

    def wrap(self, name: str, fn):
        def timed(*a, **k):
            self.stack.append([name, 0.0])
            t0 = time.perf_counter()
            try:
                return fn(*a, **k)
            finally:
                self.sync()
                dt = time.perf_counter() - t0
                _, inner = self.stack.pop()
                self.acc[name] = self.acc.get(name, 0.0) + dt - inner
                if self.stack:
                    self.stack[-1][1] += dt

        return timed


def driver(n: int, device: str, out: Path) -> dict:
    """The job in this (fresh) process with timers around its phases, twice (cold, warm).

    Parameters
    ----------
    n : int
        Pixels per side.
    device : str
        Warp device.
    out : pathlib.Path
        Output folder of the job (replaced).

    Returns
    -------
    dict
        ``{"start": {phase: s}, "cold": {phase: s}, "warm": {phase: s}}``.
    """
    start = {}
    t0 = time.perf_counter()
    import warp as wp

    start["import warp"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    wp.init()
    start["wp.init"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    dev = wp.get_device(device)
    wp.synchronize_device(dev)
    start["device"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    import warptrunc.analysis as an
    import warptrunc.cli as cli
    import warptrunc.cli.analyze as ca

    start["import analysis path"] = time.perf_counter() - t0
    targets = [
        (an, "surface_from_spec", "generation"),
        (an, "truncate", "truncation"),
        (an, "_validity", "island pass"),
        (an, "_islands", "island pass"),
        (an, "stiffness_curve", "fit"),
        (an, "fit_power_law", "fit"),
        (ca, "provenance", "provenance"),
        (ca.FigureWorker, "result", "wait for the figures"),
    ]
    result = {"start": start}
    for run in ("cold", "warm"):
        ph = Phases(lambda: wp.synchronize_device(dev))
        saved = [(mod, attr, getattr(mod, attr)) for mod, attr, _ in targets]
        for mod, attr, name in targets:
            setattr(mod, attr, ph.wrap(name, getattr(mod, attr)))
        shutil.rmtree(out, ignore_errors=True)
        t0 = time.perf_counter()
        code = cli.main(["analyze", "--n", str(n), "--device", device, "--out", str(out)])
        total = time.perf_counter() - t0
        for mod, attr, fn in saved:
            setattr(mod, attr, fn)
        if code != 0:
            raise RuntimeError(f"warptrunc analyze exited {code}")
        ph.acc["rest (CSV, JSON, move)"] = total - sum(ph.acc.values())
        result[run] = {**ph.acc, "total": total}
    return result


def import_times(n: int, device: str, out: Path, top: int = 12) -> dict:
    """``python -X importtime`` of the job: the largest top-level imports (cumulative s) and
    which heavy libraries it loaded."""
    code = (
        f"from warptrunc.cli import main; raise SystemExit(main(['analyze', '--n', '{n}', "
        f"'--device', '{device}', '--out', {str(out)!r}]))"
    )
    r = subprocess.run(
        [sys.executable, "-X", "importtime", "-c", code], capture_output=True, text=True
    )
    rows = []
    for line in r.stderr.splitlines():
        if not line.startswith("import time:") or "cumulative" in line:
            continue
        _, cum, name = line[len("import time:") :].split("|")
        rows.append((name.rstrip(), int(cum) * 1e-6))
    level0 = sorted(((nm, c) for nm, c in rows if not nm.startswith("  ")), key=lambda x: -x[1])
    heavy = (
        "pyvista",
        "vtk",
        "vtkmodules",
        "SurfaceTopography",
        "pandas",
        "pyarrow",
        "dask",
        "distributed",
        "cupy",
        "scipy",
        "matplotlib",
    )
    names = {nm.strip().split(".")[0] for nm, _ in rows}
    return {
        "top_level_cumulative_s": {nm.strip(): round(c, 4) for nm, c in level0[:top]},
        "heavy_loaded": sorted(names & set(heavy)),
    }


def main(argv: list[str] | None = None) -> dict:
    """Run the benchmark; returns the JSON record."""
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--driver"]:
        res = driver(int(argv[1]), argv[2], Path(argv[3]))
        print("RESULT " + json.dumps(res), flush=True)
        return res
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.ArgumentDefaultsHelpFormatter
    )
    ap.add_argument("--n", type=int, default=1024, help="pixels per side of the job's surface")
    ap.add_argument("--device", default="cpu", help="cpu, cuda:0, ...")
    ap.add_argument("--runs", type=int, default=5, help="fresh processes of each kind")
    ap.add_argument("--out", type=Path, default=Path("bench"), help="folder for the JSON")
    ap.add_argument("--name", default=None, help="JSON name (default startup_<device>.json)")
    args = ap.parse_args(argv)
    floor = [sys.executable, "-c", f"import warp; warp.init(); warp.get_device({args.device!r})"]
    interp = [sys.executable, "-c", "pass"]
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "job"
        wall(job_cmd(args.n, args.device, out))  # warm-up: the kernel cache filled
        wall(floor)
        times: dict[str, list[float]] = {"job": [], "floor": [], "interpreter": []}
        for _ in range(args.runs):
            shutil.rmtree(out, ignore_errors=True)
            times["floor"].append(wall(floor))
            times["job"].append(wall(job_cmd(args.n, args.device, out)))
            times["interpreter"].append(wall(interp))
        r = subprocess.run(
            [
                sys.executable,
                __file__,
                "--driver",
                str(args.n),
                args.device,
                str(Path(tmp) / "drv"),
            ],
            capture_output=True,
            text=True,
        )
        lines = [ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")]
        breakdown = json.loads(lines[-1][7:]) if lines else {"failed": r.stderr[-2000:]}
        imports = import_times(args.n, args.device, Path(tmp) / "imp")
    import warp as wp

    wp.config.quiet = True
    dev = wp.get_device(args.device)
    from _common import cpu_name

    from warptrunc._support.provenance import git_commit

    med = {k: statistics.median(v) for k, v in times.items()}
    rec = {
        "benchmark": "startup",
        "date": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()),
        "commit": git_commit(),
        "device": args.device,
        "device_name": dev.name if dev.is_cuda else cpu_name(),
        "cpu_cores": os.cpu_count(),
        "warp": wp.config.version,
        "n": args.n,
        "runs": args.runs,
        "job": " ".join(job_cmd(args.n, args.device, Path("OUT"))),
        "floor": floor[-1],
        "times_s": times,
        "median_s": med,
        "excess_s": med["job"] - med["floor"],
        "breakdown_s": breakdown,
        "imports": imports,
    }
    args.out.mkdir(parents=True, exist_ok=True)
    name = args.name or f"startup_{args.device.replace(':', '')}.json"
    (args.out / name).write_text(json.dumps(rec, indent=1))
    print(table(rec))
    return rec


def table(rec: dict) -> str:
    """The printed summary: medians, excess, and the breakdown (cold / warm run)."""
    med, ts = rec["median_s"], rec["times_s"]
    lines = [
        f"startup, {rec['device']} ({rec['device_name']}), --n {rec['n']}, "
        f"{rec['runs']} fresh processes each",
        "| process | median (s) | runs (s) |",
        "|---|---|---|",
    ]
    for k in ("job", "floor", "interpreter"):
        lines.append(f"| {k} | {med[k]:.2f} | {', '.join(f'{t:.2f}' for t in ts[k])} |")
    lines.append(f"excess of the job over the floor: {rec['excess_s']:.2f} s")
    b = rec["breakdown_s"]
    if "cold" in b:
        lines += ["", "| phase | cold run (s) | warm run (s) |", "|---|---|---|"]
        for k, v in b["start"].items():
            lines.append(f"| {k} | {v:.3f} | |")
        for k in PHASES[4:]:
            lines.append(f"| {k} | {b['cold'].get(k, 0.0):.3f} | {b['warm'].get(k, 0.0):.3f} |")
        lines.append(
            f"| total of the job in-process | {b['cold']['total']:.3f} | {b['warm']['total']:.3f} |"
        )
        inside = sum(b["start"].values()) + b["cold"]["total"]
        lines.append(
            f"| outside (interpreter, entry point, exit): median job − {inside:.3f} | "
            f"{med['job'] - inside:.3f} | |"
        )
    imp = rec["imports"]
    lines.append(f"heavy libraries the job imports: {', '.join(imp['heavy_loaded']) or 'none'}")
    return "\n".join(lines)


if __name__ == "__main__":
    main()
