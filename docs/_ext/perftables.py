# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Render the measured tables of the site from the run records in ``benchmarks/records/``.

conf.py calls :func:`write_tables` before the build: every table of :data:`TABLES` is written to
``docs/_generated/<table>.md`` (not committed), which a guide includes::

    ```{include} ../_generated/solver_scaling.md
    ```

so a number on a page is the number in its record, and each table ends with the record it was
built from and the machine and commit of that run. :data:`TABLES` is the one place that says
which record a table reads: a new run is a new record file and a changed name here.

Kinds of record read here:

- *Transcribed tables* (``{"title", "source", "notes", "columns", "records"}``): one entry per
  measured figure with ``device``, ``date``, ``commit``, ``row`` (the row's label columns),
  ``figure`` (the column), ``value`` and, where one was measured in the same run,
  ``reference`` (:func:`records_table`).
- The JSON written by a benchmark script of ``examples/benchmarks/`` (the solver's scaling, the
  peers, the start-up, the Dask workers) or its JSON lines (the spread solver), each with its
  own renderer below.
- ``bem_table_*.json`` of ``examples/benchmarks/bem_table.py``: the BEM/truncation ratios of
  every case, summarised per D and per approach (:func:`bem_tables`).
"""

from __future__ import annotations

import json
import re
from collections import OrderedDict
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RECORDS = ROOT / "benchmarks" / "records"
LINK_PREFIX = "../../benchmarks/records/"  # from docs/guide/*.md, the pages that include tables


def _esc(v: object) -> str:
    return str(v).replace("|", "\\|")


def _md_table(header: list[str], rows: list[list[str]]) -> str:
    out = ["| " + " | ".join(_esc(h) for h in header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(_esc(c) for c in r) + " |" for r in rows]
    return "\n".join(out) + "\n"


def load(name: str) -> dict | list:
    """A record of ``benchmarks/records/`` by file name: JSON, or JSON lines as a list."""
    path = RECORDS / name
    text = path.read_text()
    if path.suffix == ".jsonl":
        return [json.loads(x) for x in text.splitlines() if x.strip()]
    return json.loads(text)


def _link(name: str) -> str:
    return f"[`{name}`]({LINK_PREFIX}{name})"


def _short(commit: str | None) -> str:
    return (commit or "")[:7]


def _commit(commit: str | None, name: str) -> str:
    """The record's commit, or the one its file name gives, marked †, where it holds none."""
    if commit:
        return f"`{commit[:7]}`"
    m = re.search(r"_([0-9a-f]{7})\.[a-z]+$", name)
    return f"`{m.group(1)}`†" if m else "not recorded"


UNRECORDED = (
    "† not in the record: the commit its file name gives (see benchmarks/records/README.md)."
)


def _gpu_model(name: str | None) -> str:
    """``NVIDIA H100 80GB HBM3`` → ``H100``; other names as they are."""
    m = re.search(r"\b([A-Z]{1,2}\d{2,4})\b", name or "")
    return m.group(1) if m else (name or "?")


def _source(names: list[str], machine: str) -> str:
    return (
        f"\n*Record{'s' if len(names) > 1 else ''}:* {', '.join(map(_link, names))} ({machine}).\n"
    )


def _s(x: float) -> str:
    """Seconds to three significant figures."""
    return f"{x:.3g}" if x < 100 else f"{x:.0f}"


def _ratio(x: float) -> str:
    return f"{x:.1f}×" if x < 100 else f"{x:.0f}×"


# -- transcribed tables ----------------------------------------------------------------------


def records_table(
    doc: dict, name: str, columns: dict[str, str] | None = None, drop_rows: tuple[str, ...] = ()
) -> str:
    """Markdown of one transcribed table: the table and a line naming its record and runs.

    ``columns`` keeps only these columns, renamed (old name → header), and leaves out the
    record's notes; default all. ``drop_rows``: rows whose first label starts with one of these
    are left out (another table shows them).
    """
    cols = doc["columns"]
    by_device = any(c["kind"] == "device" for c in cols)
    rows: OrderedDict[tuple, dict] = OrderedDict()
    for rec in doc["records"]:
        if str(next(iter(rec["row"].values()), "")).startswith(drop_rows or ("\0",)):
            continue
        key = ((rec["device"],) if by_device else ()) + tuple(rec["row"].values())
        row = rows.setdefault(key, {"_row": rec["row"], "_device": rec["device"]})
        row[rec["figure"]] = rec["value"]
        if "reference" in rec:
            row[rec.get("reference_column", "reference")] = rec["reference"]
    if columns is not None:
        cols = [c for c in cols if c["name"] in columns]
    header = [columns.get(c["name"], c["name"]) if columns else c["name"] for c in cols]
    body = []
    for row in rows.values():
        line = []
        for c in cols:
            if c["kind"] == "label":
                line.append(row["_row"].get(c["name"], ""))
            elif c["kind"] == "device":
                line.append(row["_device"])
            else:
                line.append(row.get(c["name"], ""))
        body.append(line)
    devices = sorted({r["device"] for r in doc["records"]})
    commits = sorted({(r["date"] or "", r["commit"] or "") for r in doc["records"]})
    prov = ", ".join(f"`{c}` ({d})" for d, c in commits if c)
    text = _md_table(header, body)
    text += f"\n*Record:* {_link(name)}"
    text += f", written by `{doc['source']}`. " if doc.get("source") else ". "
    if not any(c["kind"] == "device" for c in cols):
        text += f"*Machine:* {', '.join(devices)}. "
    text += f"*Commit:* {prov}. " if prov else ""
    if columns is None:
        text += doc.get("notes", "")
    return text + "\n"


def _rng(vals) -> str:
    return f"{min(vals):.2f}–{max(vals):.2f}"


def _mean_rng(vals) -> str:
    return f"{sum(vals) / len(vals):.2f} ({min(vals):.2f}–{max(vals):.2f})"


def bem_tables(doc: dict, name: str) -> tuple[str, str]:
    """The per-D summary and the per-approach table of a ``bem_table`` record."""
    by_d: OrderedDict[float, list[dict]] = OrderedDict()
    for case in doc["cases"]:
        by_d.setdefault(case["D"], []).append(case)
    summary, per = [], []
    for d, cases in by_d.items():
        cols = [c["columns"] for c in cases]
        lr = [v for c in cols for v in c["load_ratio"]]
        kr = [v for c in cols for v in c["stiffness_ratio"]]
        ar = [v for c in cols for v in c["area_ratio"]]
        conv = sum(bool(c["all_converged"]) for c in cases)
        tps = sum(c["time_per_solve_s"] for c in cases) / len(cases)
        wall = sum(c["wall_s"] for c in cases) / len(cases)
        summary.append(
            [
                f"{d}",
                _rng(lr),
                _rng(kr),
                _rng(ar),
                f"{conv}/{len(cases)}",
                f"{tps:.1f}",
                f"{wall:.0f}",
            ]
        )
        for i, frac in enumerate(cols[0]["depth_fraction_of_Rt"]):
            area = [c["bem_area_m2"][i] / c.get("apparent_area_m2", 1e-6) for c in cols]
            frac_pct = 100 * sum(area) / len(area)
            per.append(
                [
                    f"{d}",
                    f"{frac:.2f}",
                    _mean_rng([c["load_ratio"][i] for c in cols]),
                    _mean_rng([c["stiffness_ratio"][i] for c in cols]),
                    _mean_rng([c["area_ratio"][i] for c in cols]),
                    f"{frac_pct:.2g} %",
                ]
            )
    t1 = _md_table(
        ["D", "F'/F_BEM", "k'/k_BEM", "A'/A_BEM", "converged", "s per solve", "s per case"], summary
    )
    t2 = _md_table(["D", "δ/R_t", "F'/F_BEM", "k'/k_BEM", "A'/A_BEM", "A_BEM/A"], per)
    note = _source([name], doc.get("machine", "") + ", commit not recorded")
    return t1 + note, t2 + note


# -- the contact solver on one GPU ----------------------------------------------------------


def solver_scaling(name: str) -> str:
    """``benchmark_solver_scaling.py``'s rows: cold and warm solves, per convolution, memory."""
    doc = load(name)
    body = []
    for r in doc["rows"]:
        if r.get("error") or "warm_s" not in r:
            continue
        it_w, conv_w = r["warm_iterations"], r["warm_convolutions"]
        peak = r.get("peak_bytes") or r.get("mempool_high_water_bytes")
        body.append(
            [
                f"{r['n']}²",
                r["dtype"],
                f"{r['cold_s']:.3f} ({r['cold_iterations']})",
                f"{r['warm_s']:.3f} ({it_w})",
                f"{conv_w / it_w:.2f}",
                f"{1e3 * r['warm_per_convolution_s']:.2f}",
                f"{r['per_convolution_over_floor']:.2f}",
                f"{peak / 1e9:.2f}" if peak else "–",
                f"{peak / r['memory_model_bytes']:.3f}"
                if peak and r.get("memory_model_bytes")
                else "–",
            ]
        )
    header = [
        "N",
        "dtype",
        "cold solve (s, iterations)",
        "warm solve (s, iterations)",
        "convolutions per iteration",
        "ms per convolution",
        "÷ FFT floor",
        "peak memory (GB)",
        "peak ÷ model",
    ]
    machine = f"{doc.get('device_name', '?')}, `{_short(doc.get('commit'))}`"
    return _md_table(header, body) + _source([name], machine)


# -- against the peers ------------------------------------------------------------------------


def _peer_cell(r: dict | None) -> str:
    if r is None:
        return "–"
    if r.get("timed_out"):
        return f"stopped at {r['time_s']:.0f} s"
    if not r.get("matched"):
        return "no match"
    tol = f"{r['tol']:.0e}, " if r.get("tol") is not None else ""
    return f"{_s(r['time_s'])} s ({tol}{r.get('iterations', '?')} it)"


def peers(names: list[str]) -> str:
    """``benchmark_peers.py``: time at matched accuracy per solver, and each peer ÷ warptrunc."""
    docs = [(n, load(n)) for n in names]
    solvers: list[str] = []
    for _, d in docs:
        for r in d["rows"]:
            if r["solver"] != "reference" and r["solver"] not in solvers:
                solvers.append(r["solver"])
    # one column per solver, whatever its substrate; warptrunc's float64 is the unit of the ratios
    label = lambda s: s.replace(" periodic", "").replace(" free", "")  # noqa: E731
    cols = list(OrderedDict.fromkeys(label(s) for s in solvers))
    peers_ = [c for c in cols if not c.startswith("warptrunc")]
    many = len(docs) > 1
    header = (["machine", "commit"] if many else []) + ["surface, substrate", "N"]
    header += cols + [f"{p} ÷ warptrunc float64" for p in peers_]
    body = []
    for _, d in docs:
        groups: OrderedDict[tuple, dict] = OrderedDict()
        for r in d["rows"]:
            if r["solver"] == "reference":
                continue
            groups.setdefault((r["surface"], r["substrate"], r["n"]), {})[label(r["solver"])] = r
        for (surface, substrate, n), by in groups.items():
            wt = by.get("warptrunc float64")
            wt_s = wt["time_s"] if wt and wt.get("matched") else None
            line = (
                [
                    f"{_gpu_model(d['device_name'])} ({d['cpu_cores']} cores)",
                    f"`{_short(d['commit'])}`",
                ]
                if many
                else []
            )
            what = "tamaas' H = 0.8" if surface == "tamaas" else "WM D = 2.5"
            line += [f"{what}, {substrate}", f"{n}²"] + [_peer_cell(by.get(c)) for c in cols]
            for p in peers_:
                r = by.get(p)
                if r is None or wt_s is None:
                    line.append("–")
                elif r.get("timed_out"):
                    line.append(f"> {_ratio(r['time_s'] / wt_s)}")
                elif r.get("matched"):
                    line.append(_ratio(r["time_s"] / wt_s))
                else:
                    line.append("–")
            body.append(line)
    d0 = docs[0][1]
    machine = "; ".join(
        f"{d['device_name']}, {d['cpu']} ({d['cpu_cores']} cores), "
        f"`{_short(d['commit'])}`, {d['date'][:10]}"
        for _, d in docs
    )
    note = (
        f"\nEach cell: the time of one cold solve at the loosest tolerance that matches "
        f"(tolerance, iterations); {d0['rule']}.\n"
    )
    return _md_table(header, body) + note + _source([n for n, _ in docs], machine)


# -- start-up ---------------------------------------------------------------------------------


def startup(names: list[str]) -> str:
    """``startup.py``: ``warptrunc analyze`` as a whole process against the floor of Warp."""
    body = []
    for name in names:
        d = load(name)
        med = d["median_s"]
        dev = "CPU" if d["device"] == "cpu" else "one GPU"
        body.append(
            [
                f"{d['device_name']} ({dev}; {d['cpu_cores']}-core host)",
                f"`{_short(d['commit'])}`",
                f"{d['n']}²",
                f"{med['job']:.2f}",
                f"{med['floor']:.2f}",
                f"**{d['excess_s']:.2f}**",
            ]
        )
    header = [
        "machine",
        "commit",
        "`--n`",
        "`warptrunc analyze` (s, median of 5)",
        "floor: `import warp; warp.init()` (s)",
        "job − floor (s)",
    ]
    return _md_table(header, body) + _source(names, "fresh processes, warm kernel cache")


# -- several GPUs -----------------------------------------------------------------------------


def _gb(x: float | None) -> str:
    return f"{x / 1e9:.2f}" if x else "–"


def sharded(names: list[str]) -> str:
    """``benchmark_sharded.py solve``: one contact problem spread over the GPUs of one host."""
    body, marked = [], False
    for name in names:
        solves = [r for r in load(name) if r.get("step") == "solve" and "error" not in r]
        for r in sorted(solves, key=lambda r: (r["n"], r["dtype"], r["ndev"])):
            w = r["warm"]
            peak = max(r["peak_bytes"]) if r.get("peak_bytes") else r.get("peak_GB", 0) * 1e9
            model = r.get("model_bytes_per_device") or r.get("model_GB", 0) * 1e9
            conv = w.get("converged")
            capped = w["iterations"] >= r.get("maxiter", 1 << 30)
            its = f"{w['iterations']}" + (
                " (not converged)"
                if conv is False
                else " (maxiter)"
                if conv is None and capped
                else ""
            )
            commit = _commit(r.get("commit"), name)
            marked |= commit.endswith("†")
            kind = "WM D = 2.5" if r.get("map") == "wm" else "self-affine"
            body.append(
                [
                    f"{_gpu_model(r['devices'][0])} × {r['ndev']}",
                    commit,
                    f"{r['n']}², {r['dtype']}, {kind}",
                    f"{r['floor_ms']:.1f}",
                    f"{w['s']:.2f}",
                    its,
                    f"{w['ms_per_iteration']:.1f}",
                    f"{r['warm_over_floor']:.2f}",
                    _gb(peak),
                    _gb(model),
                ]
            )
    header = [
        "GPUs",
        "commit",
        "map",
        "FFT floor (ms)",
        "warm solve (s)",
        "iterations",
        "ms per iteration",
        "per convolution ÷ floor",
        "peak GB per GPU",
        "model GB per GPU (at that commit)",
    ]
    note = f"\n{UNRECORDED}\n" if marked else ""
    return _md_table(header, body) + note + _source(names, "free boundary, one host each")


def sharded_bem_check(name: str) -> str:
    """The ``warptrunc bem-check`` line of a spread-solver log: a whole command on several GPUs."""
    body = []
    for r in load(name):
        if r.get("step") != "bem_check" or not r.get("valid"):
            continue
        ratios = [
            t / b
            for t, b in zip(
                r.get("trunc_stiffness_N_per_m", []), r["bem_stiffness_N_per_m"], strict=False
            )
        ]
        body.append(
            [
                f"`{r['command']}`",
                f"`{_short(r['commit'])}`",
                ", ".join(f"{x:.2g}" for x in r["depth_fraction_of_Rt"]),
                ", ".join(map(str, r["n_iterations"])),
                ", ".join(f"{x:.1f}" for x in r["solve_time_s"]),
                f"{r['seconds_per_solve']:.1f}",
                r.get("wall", "–"),
                _gb(r["model_bytes_per_device"]),
            ]
            + ([_rng(ratios)] if ratios else [])
        )
    header = [
        "command",
        "commit",
        "δ/R_t",
        "iterations",
        "s per solve",
        "mean s per solve",
        "whole command (m:s)",
        "model GB per GPU",
    ]
    return _md_table(header, body) + _source([name], "4 × NVIDIA H200, one host")


def _workload(run: dict) -> str:
    m = re.search(r"--n (\d+)", run.get("command", ""))
    kind = "elastic" if "--bem-fractions" in run.get("command", "") else "light"
    return f"{run.get('cases', '?')} {kind} cases at {m.group(1) if m else '?'}²"


def _wall(r: dict | None) -> str:
    if r is None:
        return "–"
    if r.get("status"):
        return r["status"].split(" (")[0]
    sp = r.get("speedup")
    return f"{r['wall_s']:.1f}" + (f" ({sp:.2f}×)" if sp and r["run"] != "inproc" else "")


def workers(names: list[str]) -> str:
    """``benchmark_workers.py``: whole ``warptrunc sweep`` commands in process and on N workers."""
    body = []
    counts = sorted(
        {
            int(r["run"].split("_")[1])
            for n in names
            for r in load(n)["runs"]
            if r["run"].startswith("workers_")
        }
    )
    for name in names:
        d = load(name)
        model = _gpu_model(
            d.get("warp_devices", ["", "?"])[1] if len(d.get("warp_devices", [])) > 1 else "?"
        )
        by: OrderedDict[str, dict] = OrderedDict()
        for r in d["runs"]:
            by.setdefault(r["workload"], {})[r["run"]] = r
        for runs in by.values():
            inproc = runs.get("inproc")
            body.append(
                [
                    f"{model} × {len(d.get('warp_devices', [])) - 1}",
                    f"`{_short(d['commit'])}`",
                    _workload(inproc or next(iter(runs.values()))),
                    _wall(inproc),
                ]
                + [_wall(runs.get(f"workers_{c}")) for c in counts]
            )
    header = ["GPUs", "commit", "sweep", "in process on cuda:0 (s)"]
    header += [f"{c} worker{'s' if c > 1 else ''} (s, speed-up)" for c in counts]
    return _md_table(header, body) + _source(names, "whole commands, one worker per GPU")


def indentation_workers(names: list[str]) -> str:
    """``benchmark_indentation_workers.py``: the reproduce indentation stage on N workers."""
    body = []
    counts = sorted(
        {
            int(r["run"].split("_")[1])
            for n in names
            for r in load(n)["runs"]
            if r["run"].startswith("workers_")
        }
    )
    for name in names:
        d = load(name)
        gpus = d.get("machine", {}).get("gpus") or d.get("gpus_csv") or []
        model = _gpu_model(gpus[0] if gpus else "?")
        by = {r["run"]: r for r in d["runs"]}
        prof = d["profile"]
        inproc = by.get("inproc")
        body.append(
            [
                f"{model} × {len(gpus)}",
                f"`{_short(d['commit'])}`",
                f"{prof['indentation_n']}² over {prof['indentation_L_m'] * 1e3:g} mm",
                f"{inproc['pieces']} pieces, {inproc['pieces_s']:.0f} s" if inproc else "–",
                _wall(inproc),
            ]
            + [_wall(by.get(f"workers_{c}")) for c in counts]
        )
    header = [
        "GPUs",
        "commit",
        "indentation map",
        "work (sum of the pieces' seconds)",
        "in process (s)",
    ] + [f"{c} worker{'s' if c > 1 else ''} (s, speed-up)" for c in counts]
    return _md_table(header, body) + _source(names, "whole processes, `--profile paper`")


# -- the registry -----------------------------------------------------------------------------

TRANSCRIBED: dict[str, tuple[str, dict[str, str] | None, tuple[str, ...]]] = {
    "kernels": ("kernels_cpu_h200_0943db8_12ef4a7.json", None, ()),
    "islands": ("islands_cpu_h200_0943db8_faabd2b.json", None, ()),
    "fractal": ("fractal_methods_cpu_h200_0943db8.json", None, ()),
    "pipeline": (
        "pipeline_before_after_h100_e4e7e82.json",
        {
            "target": "what",
            "after": "time",
            "reference in the same run": "reference in the same run",
        },
        ("`island_curve`", "`warptrunc analyze --n 10240`", "label one mask"),
    ),
    "contact_cpu": ("contact_solver_cpu_5e9d35d.json", None, ()),
    "contact_h100": (
        "contact_solver_h100_7b6aa4a.json",
        {
            **{
                c: c
                for c in (
                    "N",
                    "dtype",
                    "warm solve",
                    "iterations (conv.)",
                    "per iteration",
                    "CuPy convolution floor",
                    "memory estimate / held",
                )
            },
            "× floor (target ≤ 1.3)": "× floor",
        },
        (),
    ),
    "sweep_throughput": ("sweep_throughput_cpu_h200x2_28b7361_34c794c.json", None, ()),
    "table1_presets": ("table1_presets_cpu_79581b0.json", None, ()),
}
"""Tables transcribed into records: table name → (record, the columns kept or None for all,
the rows left out)."""

BEM_TABLE = "bem_table_cpu_2026-11-23.json"


def preset_slopes() -> str:
    """The D_vs presets' content and h′_rms (``warptrunc.presets.CALIBRATION``)."""
    from warptrunc.presets import CALIBRATION, TABLE1

    rows = []
    for name in TABLE1:
        c = CALIBRATION[name]
        sl = c["slope_rms"]
        rows.append(
            [
                name,
                f"{c['D_in']:.3f}",
                f"{c['Wc_m'] * 1e6:.3g}",
                f"{c['Rt_pixel_m'] * 1e9:.4g}",
                f"{sl['calibration_pixel']:.3g}",
                f"{sl['paper_pixel']:.3g}",
                f"{sl['spectrum']:.3g}",
                "yes" if sl["paper_pixel"] <= sl["small_slope_limit"] else "**no**",
            ]
        )
    header = ["preset", "D_in", "W_c (µm)", "R_t′ measured at (nm)", "h′_rms at 977 nm",
              "h′_rms at 97.7 nm", "h′_rms of the terms", "small slope (≤ 0.5)"]  # fmt: skip
    return _md_table(header, rows) + (
        "\nSeed 0, finite differences at the pixel (`warptrunc.slope.slope_statistics`); the "
        "terms' value is the content's own, the same on every grid (`wm_slope_statistics`). "
        "Source: `warptrunc.presets.CALIBRATION`, measured again by "
        "`examples/benchmarks/content_sensitivity.py`.\n"
    )


# -- the contact-mechanics challenge ---------------------------------------------------------


def _g(x: float | None, fmt: str = ".3g") -> str:
    return "–" if x is None else format(x, fmt)


def challenge_study(records: list[str]) -> str:
    """``warptrunc challenge``: per grid, the grid study, κ and the slope of K(p); each record a
    ``challenge.json``."""
    header = [
        "grid (N → 2N)",
        "λ_s (µm)",
        "h′_rms",
        "a_r moves (N → 2N)",
        "ū moves",
        "κ BEM",
        "κ Persson",
        "κ GW",
        "κ BGT",
        "d ln K/d ln p: BEM",
        "Persson",
        "GW",
        "truncation",
    ]
    body, names, machine = [], [], []
    for name in records:
        d = load(name)
        g, k, sl = d["grid_study"], d["kappa"], d["stiffness_slope"]
        grid = f"{g['n'][0]}² → {g['n'][1]}²" if g else f"{d['surface']['grid'][0]}²"
        lam = d["surface"]["params"].get("short_cutoff")
        body.append(
            [
                grid,
                _g(None if lam is None else lam * 1e6),
                _g(d["slope_rms"]),
                "–" if not g else f"{100 * g['max_change_area_fraction']:.1f} %",
                "–" if not g else f"{100 * g['max_change_mean_gap']:.2f} %",
                _g(k.get("bem")),
                _g(k.get("persson")),
                _g(k.get("gw")),
                _g(k.get("bgt")),
                _g(sl.get("bem")),
                _g(sl.get("persson")),
                _g(sl.get("gw")),
                _g(sl.get("truncation")),
            ]
        )
        names.append(name)
        prov = d.get("provenance", {})
        machine.append(f"{prov.get('device') or 'cpu'}, `{_short(prov.get('git_commit'))}`")
    k0 = load(names[0])["kappa"]
    note = (
        f"\nκ = a_r E* h′_rms/p, the mean over the loads with a_r ≤ {k0['max_area_fraction']:g} "
        f"and ≥ {k0['min_contact_pixels']} contact pixels on the finer grid, h′_rms of the map's "
        f"spectrum; the limits are √(8/π) = {k0['persson_limit']:.3f} (Persson) and "
        f"√(2π) = {k0['bgt_limit']:.3f} (BGT). The slopes are fitted over the same loads; "
        '"moves" is the largest relative change of a_r and of ū over those loads when the '
        "pixel is halved on the same content.\n"
    )
    return _md_table(header, body) + note + _source(names, "; ".join(machine))


def challenge_curves(name: str) -> str:
    """``warptrunc challenge``: a_r, ū and K against p/E* on the finer grid, every model (a
    ``challenge.json`` record)."""
    d = load(name)
    c = d["columns"]
    header = [
        "p/E*",
        "a_r BEM",
        "Persson",
        "GW",
        "BGT",
        "truncation",
        "ū BEM (µm)",
        "Persson",
        "K BEM (MPa/µm)",
        "Persson",
        "GW",
    ]
    body = []
    for i, x in enumerate(c["pressure_over_contact_modulus"]):
        tr = c["truncation_area_fraction"][i]
        body.append(
            [
                f"{x:.3g}",
                _g(c["bem_area_fraction"][i], ".4g"),
                _g(c["persson_area_fraction"][i], ".4g"),
                _g(c["gw_area_fraction"][i], ".4g"),
                _g(c["bgt_area_fraction"][i], ".4g"),
                "–" if tr is None or not c["truncation_resolved"][i] else f"{tr:.4g}",
                _g(c["bem_mean_gap_m"][i] * 1e6, ".4g"),
                _g(c["persson_mean_gap_m"][i] * 1e6, ".4g"),
                _g(c["bem_stiffness_Pa_per_m"][i] * 1e-12, ".3g"),
                _g(c["persson_stiffness_Pa_per_m"][i] * 1e-12, ".3g"),
                _g(c["gw_stiffness_Pa_per_m"][i] * 1e-12, ".3g"),
            ]
        )
    prov = d.get("provenance", {})
    g = d["grid_study"]
    grid = f"{g['n'][1]}²" if g else f"{d['surface']['grid'][0]}²"
    note = (
        f"\nThe finer grid ({grid}); truncation's a_r where resolved (at least 10 truncated "
        'pixels), "–" where Eq. 2 reaches the whole map before the load.\n'
    )
    return (
        _md_table(header, body)
        + note
        + _source([name], f"{prov.get('device') or 'cpu'}, `{_short(prov.get('git_commit'))}`")
    )


def challenge_peers(name: str) -> str:
    """``challenge_peers.py``: a_r and ū of each solver at each load, against warptrunc's."""
    d = load(name)
    header = [
        "p/E*",
        "solver",
        "a_r",
        "ū (µm)",
        "a_r vs warptrunc",
        "ū vs warptrunc",
        "vs own tight: a_r, ū",
        "time (s)",
    ]
    body = []
    for row in d["loads"]:
        for key, res in row["solves"].items():
            a = row["agreement"][key]
            if res.get("timed_out"):
                body.append(
                    [
                        f"{row['pressure_over_E_star']:g}",
                        key,
                        "timed out",
                        "",
                        "",
                        "",
                        "",
                        _s(res["time_s"]),
                    ]
                )
                continue
            body.append(
                [
                    f"{row['pressure_over_E_star']:g}",
                    key,
                    f"{res['area_fraction']:.6g}",
                    f"{res['mean_gap_m'] * 1e6:.7g}",
                    f"{a['area_vs_warptrunc']:.1e}",
                    f"{a['gap_vs_warptrunc']:.1e}",
                    f"{a['area_vs_own_tight']:.1e}, {a['gap_vs_own_tight']:.1e}",
                    _s(res["time_s"]),
                ]
            )
    s = d["surface"]
    note = (
        f"\n{d['n']}² ({s['pixel_m'] * 1e9:.3g} nm pixels, λ_s = {s['short_cutoff_pixels']:.3g} "
        f"pixels, h′_rms = {s['slope_rms']:.3g}), periodic; {d['rule']} ({d['match']:g}). "
        '"vs warptrunc": relative to warptrunc\'s tight solve. Times on a shared machine, '
        "with other work running: not a benchmark.\n"
    )
    return (
        _md_table(header, body)
        + note
        + _source(
            [name],
            f"{d['cpu']} ({d['cpu_cores']} cores), {_commit(d.get('commit'), name)}, {d['date'][:10]}",
        )
    )


def content_sensitivity(name: str) -> str:
    """The reported numbers of the D_vs presets against the content cut-off W_c (one record)."""
    doc = load(name)
    rows = []
    for r in doc["rows"]:
        rows.append(
            [
                r["preset"],
                f"{r['Wc_m'] * 1e6:.3g}",
                f"{r['slope_rms']:.3g}",
                f"{r['alpha']:.3f}",
                f"{r['beta']:.3g}",
                f"{r['K_N_per_m'] / 1e6:.3g}",
                f"{r['contact_area_m2'] * 1e12:.4g}",
                f"{r['depth_m'] * 1e6:.3g}",
                f"{r['elastic_K_N_per_m'] / 1e6:.3g}",
            ]
        )
    header = ["preset", "W_c (µm)", "h′_rms at 97.7 nm", "α", "β", "K (MN/m)",
              "A (µm²)", "depth (µm)", "K elastic (MN/m)"]  # fmt: skip
    return _md_table(header, rows) + (
        f"\n{doc['notes']} {_source([name], doc.get('device_name', ''))}\n"
    )


def adhesion(name: str) -> str:
    """``benchmark_adhesion.py``: the adhesive and the non-adhesive solve of one surface."""
    d = load(name)
    header = ["N", "law", "set-up (s)", "cold (s)", "warm (s)", "iterations", "converged",
              "a_r", "attractive a_r", "p/E*", "peak pool (GB)", "memory_bytes (GB)"]  # fmt: skip
    body = []
    for r in d["rows"]:
        peak = r.get("peak_pool_bytes")
        body.append(
            [
                f"{r['n']}²",
                r["law"],
                _s(r["setup_s"]),
                _s(r["cold_s"]),
                _s(r["warm_s"]),
                str(r["n_iterations"]),
                "yes" if r["converged"] else "no",
                f"{r['area_fraction']:.4g}",
                f"{r['attractive_area_fraction']:.4g}",
                f"{r['pressure_over_E_star']:.3g}",
                "–" if peak is None else f"{peak / 1e9:.2f}",
                f"{r['memory_bytes'] / 1e9:.2f}",
            ]
        )
    note = f"\n{d['notes']}\n" if d.get("notes") else "\n"
    machine = f"{d.get('device_name', d.get('device'))}, {_commit(d.get('commit'), name)}"
    return _md_table(header, body) + note + _source([name], machine)


TABLES: dict[str, Callable[[], str]] = {
    "adhesion": lambda: adhesion("adhesion_h200_12026d7_partial.json"),
    "challenge_study": lambda: challenge_study(["challenge_4096_h200_73a5742.json"]),
    "challenge_curves": lambda: challenge_curves("challenge_4096_h200_73a5742.json"),
    "challenge_peers": lambda: challenge_peers("challenge_peers_cpu_0b47f80.json"),
    "preset_slopes": preset_slopes,
    "content_sensitivity": lambda: content_sensitivity("content_sensitivity_h200_73a5742.json"),
    "solver_scaling": lambda: solver_scaling("solver_scaling_h200x4_6af94f0.json"),
    "peers_cpu": lambda: peers(["peers_cpu_e2af04c.json"]),
    "peers_gpu": lambda: peers(["peers_h100x4_ec597f6.json", "peers_h200x4_6af94f0.json"]),
    "startup": lambda: startup(
        ["startup_cpu_4d0cc1f.json", "startup_h100x4_ec597f6.json", "startup_h200x4_6af94f0.json"]
    ),
    "sharded": lambda: sharded(
        [
            "sharded_h100x2_789c425.jsonl",
            "sharded_h200x4_6af94f0.jsonl",
            "sharded_h200x4_fab6f70.jsonl",
            "sharded_h200x4_34cbf1b.jsonl",
        ]
    ),
    "sharded_bem_check": lambda: sharded_bem_check("sharded_h200x4_34cbf1b.jsonl"),
    "workers": lambda: workers(["workers_h100x4_1b64d9c.json", "workers_h200x4_34cbf1b.json"]),
    "indentation_workers": lambda: indentation_workers(["indentation_workers_h100x4_1b64d9c.json"]),
    **{
        k: (lambda f=f, c=c, d=d: records_table(load(f), f, c, d))
        for k, (f, c, d) in TRANSCRIBED.items()
    },
    "bem_table_by_D": lambda: bem_tables(load(BEM_TABLE), BEM_TABLE)[0],
    "bem_table_by_depth": lambda: bem_tables(load(BEM_TABLE), BEM_TABLE)[1],
}
"""Every table of the site built from records: name (``docs/_generated/<name>.md``) → renderer."""


def write_tables(docs: Path) -> list[str]:
    """Write ``docs/_generated/<name>.md`` for every table of :data:`TABLES`; their names."""
    out = docs / "_generated"
    out.mkdir(exist_ok=True)
    for name, render in TABLES.items():
        text = render()
        dest = out / f"{name}.md"
        if not dest.is_file() or dest.read_text() != text:
            dest.write_text(text)
    return list(TABLES)
