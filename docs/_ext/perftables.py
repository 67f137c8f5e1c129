# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Render the tables of the site from the JSON files in ``docs/benchmarks/`` (run by conf.py).

Two kinds of file:

- *Records* (``{"title", "source", "notes", "columns", "records"}``): one record per measured
  figure with the fields ``device``, ``date``, ``commit``, ``row`` (the row's label columns),
  ``figure`` (the column), ``value`` and, where one was measured in the same run,
  ``reference``. Tables that were only in the README were transcribed once into such files;
  new measurements are added as records, never typed into a page.
- ``bem_table.json``, written by ``examples/benchmarks/bem_table.py``: the BEM/truncation
  ratios of every case, summarised here per D and per approach.

Each table is written to ``docs/_generated/<name>.md`` (not committed), which the pages
include with ``{include}``.
"""

from __future__ import annotations

import json
from collections import OrderedDict
from pathlib import Path


def _esc(v: str) -> str:
    return str(v).replace("|", "\\|")


def _md_table(header: list[str], rows: list[list[str]]) -> str:
    out = ["| " + " | ".join(_esc(h) for h in header) + " |",
           "|" + "---|" * len(header)]
    out += ["| " + " | ".join(_esc(c) for c in r) + " |" for r in rows]
    return "\n".join(out) + "\n"


def records_table(doc: dict) -> str:
    """Markdown of one records file: the table and a line naming its provenance."""
    cols = doc["columns"]
    rows: OrderedDict[tuple, dict] = OrderedDict()
    for rec in doc["records"]:
        key = tuple(rec["row"].values())
        row = rows.setdefault(key, {"_row": rec["row"], "_device": rec["device"]})
        row[rec["figure"]] = rec["value"]
        if "reference" in rec:
            row[rec.get("reference_column", "reference")] = rec["reference"]
    header = [c["name"] for c in cols]
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
    text += f"\n*Source:* `{doc['source']}`. " if doc.get("source") else "\n"
    if not any(c["kind"] == "device" for c in cols):
        text += f"*Device:* {', '.join(devices)}. "
    text += f"*Recorded at:* {prov}. " if prov else ""
    text += doc.get("notes", "")
    return text + "\n"


def _rng(vals) -> str:
    return f"{min(vals):.2f}–{max(vals):.2f}"


def _mean_rng(vals) -> str:
    return f"{sum(vals) / len(vals):.2f} ({min(vals):.2f}–{max(vals):.2f})"


def bem_tables(doc: dict) -> tuple[str, str]:
    """The per-D summary and the per-approach table of ``bem_table.json``."""
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
        summary.append([f"{d}", _rng(lr), _rng(kr), _rng(ar), f"{conv}/{len(cases)}",
                        f"{tps:.1f}", f"{wall:.0f}"])
        for i, frac in enumerate(cols[0]["depth_fraction_of_Rt"]):
            area = [c["bem_area_m2"][i] / c.get("apparent_area_m2", 1e-6) for c in cols]
            frac_pct = 100 * sum(area) / len(area)
            per.append([f"{d}", f"{frac:.2f}",
                        _mean_rng([c["load_ratio"][i] for c in cols]),
                        _mean_rng([c["stiffness_ratio"][i] for c in cols]),
                        _mean_rng([c["area_ratio"][i] for c in cols]),
                        f"{frac_pct:.2g} %"])
    t1 = _md_table(["D", "F'/F_BEM", "k'/k_BEM", "A'/A_BEM", "converged", "s per solve",
                    "s per case"], summary)
    t2 = _md_table(["D", "δ/R_t", "F'/F_BEM", "k'/k_BEM", "A'/A_BEM", "A_BEM/A"], per)
    machine = doc.get("machine", "")
    note = f"\n*Source:* `docs/benchmarks/bem_table.json` ({machine}).\n"
    return t1 + note, t2 + note


def write_tables(docs: Path) -> list[str]:
    """Write ``docs/_generated/<name>.md`` for every JSON file in ``docs/benchmarks/``."""
    out = docs / "_generated"
    out.mkdir(exist_ok=True)
    names = []
    for path in sorted((docs / "benchmarks").glob("*.json")):
        doc = json.loads(path.read_text())
        if "records" in doc:
            pieces = {path.stem: records_table(doc)}
        elif path.stem == "bem_table":
            t1, t2 = bem_tables(doc)
            pieces = {"bem_table_by_D": t1, "bem_table_by_depth": t2}
        else:
            continue
        for name, text in pieces.items():
            dest = out / f"{name}.md"
            if not dest.is_file() or dest.read_text() != text:
                dest.write_text(text)
            names.append(name)
    return names
