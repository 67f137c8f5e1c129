# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Compare two output trees of warptrunc bit for bit: every CSV, Parquet and JSON value.

Used to show that a refactoring changes no number: run the same commands with the old and the
new code (e.g. ``analyze --n 512``, ``sweep --D 2.3 2.5 --delta 0.01 --seeds 0-1 --n 256``,
``reproduce --profile quick``, each into its own folder of one tree), then::

    python examples/gpu_checks/compare_outputs.py BASELINE_TREE NEW_TREE

Every file of BASELINE_TREE with the suffix .csv, .json or .parquet is compared with the file
of the same relative path in NEW_TREE; the Parquet parts of a dataset folder
(``curves/part-*.parquet``, whose names hold a random suffix) are read as one table, sorted by
``case_id``. Numbers are compared bit for bit (floats by their IEEE bits, so −0.0 ≠ 0.0 and
NaN = NaN of the same payload); strings and booleans exactly. Provenance values are skipped:
version, commit, times and durations, command lines, device and host names, paths (``SKIP``).
Keys and columns renamed on purpose are mapped with ``RENAMED`` (baseline name → new name), and
keys moved into another object with ``--moves FILE`` (regular expressions on the new key path),
before the comparison; keys only in NEW_TREE are listed as additions (new columns beside the
old ones are allowed), keys missing from NEW_TREE are failures.

Exit status 0 when every compared value is identical, 1 otherwise. CPU only; reads files.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import struct
import sys
from pathlib import Path

import numpy as np
import pandas as pd

RENAMED: dict[str, str] = {}
"""Key or column renamed between the baseline and the new code: baseline name → new name."""

SKIP = re.compile(
    r"^(version|warptrunc_version|commit|git_commit|date|time|created|finished_utc|started_utc|"
    r"command|command_line|argv|cmd|device|device_name|devices|host|hostname|out|path|paths|"
    r"store|python|platform|numpy|warp|wall_time|wall_s|duration|elapsed|cwd|file|files|cost)$"
    r"|seconds|_time$|^time_|_s$|_utc$|_path$|_dir$"
)
"""Provenance keys (matched against the last component of a key path or a column name)."""


def _leaves(v, prefix: str = ""):
    """(path, value) of every leaf of a JSON value."""
    if isinstance(v, dict):
        for k, x in v.items():
            yield from _leaves(
                x, f"{prefix}.{RENAMED_INV.get(k, k)}" if prefix else RENAMED_INV.get(k, k)
            )
    elif isinstance(v, list):
        for i, x in enumerate(v):
            yield from _leaves(x, f"{prefix}[{i}]")
    else:
        yield prefix, v


RENAMED_INV = {new: old for old, new in RENAMED.items()}


def _last(path: str) -> str:
    return re.sub(r"\[\d+\]$", "", path.rsplit(".", 1)[-1])


def _skipped(path: str) -> bool:
    parts = [re.sub(r"\[\d+\]", "", p) for p in path.split(".")]
    return any(SKIP.search(p) for p in parts if p)


def _same(a, b) -> bool:
    if isinstance(a, bool) or isinstance(b, bool) or a is None or b is None:
        return a is b or a == b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if isinstance(a, int) and isinstance(b, int):
            return a == b
        return struct.pack("<d", float(a)) == struct.pack("<d", float(b))
    return a == b


MOVED: list[tuple[str, str]] = []
"""(regex on a new key path, replacement giving the baseline path): keys moved on purpose into
another object (``--moves FILE``: one ``REGEX => REPLACEMENT`` per line, ``#`` comments)."""


def _moved(path: str) -> str:
    for pat, rep in MOVED:
        new = re.sub(pat, rep, path)
        if new != path:
            return new
    return path


def compare_json(a: Path, b: Path, report: list[str]) -> int:
    """Compare two JSON files leaf by leaf; returns the number of values compared."""
    la = dict(_leaves(json.loads(a.read_text())))
    lb = {_moved(k): v for k, v in _leaves(json.loads(b.read_text()))}
    n = 0
    for k, v in la.items():
        if _skipped(k):
            continue
        if k not in lb:
            report.append(f"{b}: missing key {k}")
            continue
        n += 1
        if not _same(v, lb[k]):
            report.append(f"{b}: {k}: {v!r} → {lb[k]!r}")
    extra = sorted(k for k in lb if k not in la and not _skipped(k))
    if extra:
        report.append(f"(addition) {b}: {len(extra)} new keys, e.g. {extra[:3]}")
    return n


def _read_table(p: Path) -> pd.DataFrame:
    if p.is_dir():  # a dataset of parts with random names: one table, sorted by case
        parts = sorted(p.glob("*.parquet"))
        df = pd.concat([pd.read_parquet(x) for x in parts], ignore_index=True)
        if "case_id" in df.columns:
            df = df.sort_values("case_id", kind="stable", ignore_index=True)
        return df
    if p.suffix == ".csv":  # Python's float() of each cell: correctly rounded
        df = pd.read_csv(p, dtype=str, keep_default_na=False)
        for c in df.columns:
            try:
                df[c] = df[c].map(float)
            except ValueError:
                pass
        return df
    return pd.read_parquet(p)


def _bits(s: pd.Series) -> np.ndarray:
    x = s.to_numpy()
    if x.dtype.kind == "f":
        return x.astype(np.float64).view(np.int64)
    return x


def compare_table(a: Path, b: Path, report: list[str]) -> int:
    """Compare two tables column by column; returns the number of values compared."""
    ta, tb = _read_table(a), _read_table(b).rename(columns=RENAMED_INV)
    if len(ta) != len(tb):
        report.append(f"{b}: {len(ta)} rows → {len(tb)}")
        return 0
    n = 0
    for c in ta.columns:
        if _skipped(c):
            continue
        if c not in tb.columns:
            report.append(f"{b}: missing column {c}")
            continue
        sa, sb = ta[c], tb[c]
        n += len(sa)
        if sa.dtype.kind in "fiub" and sb.dtype.kind in "fiub":
            if sa.dtype.kind != sb.dtype.kind:
                report.append(f"{b}: column {c}: dtype {sa.dtype} → {sb.dtype}")
            elif not np.array_equal(_bits(sa), _bits(sb)):
                i = int(np.flatnonzero(_bits(sa) != _bits(sb))[0])
                report.append(
                    f"{b}: column {c} differs (first at row {i}: {sa.iloc[i]!r} → {sb.iloc[i]!r})"
                )
        else:
            va = [
                None if (v is pd.NA or (isinstance(v, float) and math.isnan(v))) else v
                for v in sa.tolist()
            ]
            vb = [
                None if (v is pd.NA or (isinstance(v, float) and math.isnan(v))) else v
                for v in sb.tolist()
            ]
            if va != vb:
                i = next(i for i, (x, y) in enumerate(zip(va, vb)) if x != y)
                report.append(f"{b}: column {c} differs (first at row {i}: {va[i]!r} → {vb[i]!r})")
    extra = [c for c in tb.columns if c not in ta.columns and not _skipped(c)]
    if extra:
        report.append(f"(addition) {b}: new columns {extra}")
    return n


def _load_moves(path):
    for line in Path(path).read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            pat, rep = line.split(" => ")
            MOVED.append((pat.strip(), rep.strip()))


def main(argv: list[str] | None = None) -> int:
    """Compare the trees; print a summary and the differences."""
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("baseline", type=Path)
    p.add_argument("new", type=Path)
    p.add_argument(
        "--moves",
        default=None,
        metavar="FILE",
        help="keys moved on purpose: lines 'REGEX => REPLACEMENT' that map a new key "
        "path to the baseline's",
    )
    args = p.parse_args(argv)
    if args.moves:
        _load_moves(args.moves)
    report: list[str] = []
    n_files = n_values = 0
    done_dirs: set[Path] = set()
    for f in sorted(args.baseline.rglob("*")):
        if not f.is_file() or f.suffix not in (".csv", ".json", ".parquet"):
            continue
        rel = f.relative_to(args.baseline)
        if f.suffix == ".parquet" and f.parent.name == "curves":  # a dataset of parts
            if f.parent in done_dirs:
                continue
            done_dirs.add(f.parent)
            f, rel = f.parent, rel.parent
        g = args.new / rel
        if not g.exists():
            report.append(f"missing in new tree: {rel}")
            continue
        n_files += 1
        n_values += (compare_json if f.suffix == ".json" else compare_table)(f, g, report)
    fails = [r for r in report if not r.startswith("(addition)")]
    print(
        f"compared {n_values} values in {n_files} files/datasets "
        f"({args.baseline} → {args.new}); renamed keys: {RENAMED or 'none'}"
    )
    for r in report:
        print("  " + r)
    print("IDENTICAL" if not fails else f"{len(fails)} DIFFERENCES")
    return 0 if not fails else 1


if __name__ == "__main__":
    sys.exit(main())
