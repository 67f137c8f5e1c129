# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The identity check of benchmark_indentation_workers.py: what a reproduction
stores for the indentation stage, compared bit for bit between runs (floats by their IEEE bits,
NaN equal to NaN), the keys that say where, when and how fast a piece ran left out; the values
kept as gzipped JSON so that runs of separate processes or device calls can be compared
(``benchmark_indentation_workers.py compare REF OTHER ...``)."""

from __future__ import annotations

import argparse
import gzip
import json
import math
import struct
import sys
from pathlib import Path

EXCLUDED = frozenset({"seconds", "device", "devices", "cost", "worker", "host", "pid"})
"""Keys left out of the identity check, with every key ending ``_s`` (seconds): where, when and
how fast a piece ran (``cost`` is the analysis's table of seconds per design and level)."""


def _load(path: Path):
    return json.loads(path.read_text())


def stored_values(store: Path) -> dict:
    """What the identity check reads: {file or section: JSON value}."""
    docs = {
        f"indentation/{f.name}": _load(f) for f in sorted((store / "indentation").glob("*.json"))
    }
    st = _load(store / "stages" / "indentation.json")
    docs["stages/indentation.json"] = {k: st.get(k) for k in ("params", "result")}
    docs["results.json:analysis"] = _load(store / "results.json").get("analysis")
    return docs


def _number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _same(a, b) -> bool:
    """Equal bit for bit: floats by their IEEE bits (NaN = NaN), the rest exactly."""
    if _number(a) and _number(b):
        if isinstance(a, int) and isinstance(b, int):
            return a == b
        x, y = float(a), float(b)
        return struct.pack("<d", x) == struct.pack("<d", y) or (math.isnan(x) and math.isnan(y))
    return type(a) is type(b) and a == b


def _note(out: dict, path: str, a, b, what: str | None = None) -> None:
    e = out.setdefault(path, {"count": 0, "max_abs": 0.0, "max_rel": 0.0, "example": None})
    e["count"] += 1
    if e["example"] is None:
        e["example"] = what or f"{a!r} → {b!r}"
    if _number(a) and _number(b) and math.isfinite(a) and math.isfinite(b):
        d = abs(float(a) - float(b))
        e["max_abs"] = max(e["max_abs"], d)
        e["max_rel"] = max(e["max_rel"], d / max(abs(float(a)), sys.float_info.min))


def differences(a, b, path: str = "", out: dict | None = None, seen: list | None = None) -> dict:
    """{field path (indices as ``[]``): count, max_abs, max_rel, example} of the values of
    ``b`` that differ from ``a``, :data:`EXCLUDED` and ``*_s`` keys left out; ``seen[0]``
    counts the values compared."""
    out = {} if out is None else out
    seen = [0] if seen is None else seen
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b), key=str):
            if k in EXCLUDED or str(k).endswith("_s"):
                continue
            p = f"{path}{k}" if not path or path.endswith(":") else f"{path}.{k}"
            if k not in a or k not in b:
                _note(
                    out, p, None, None, "only in " + ("the worker run" if k in b else "in process")
                )
            else:
                differences(a[k], b[k], p + (":" if not path else ""), out, seen)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            _note(out, path + "[]", None, None, f"length {len(a)} → {len(b)}")
        else:
            for x, y in zip(a, b, strict=True):
                differences(x, y, path + "[]", out, seen)
    else:
        seen[0] += 1
        if not _same(a, b):
            _note(out, path, a, b)
    return out


def identity(ref, other) -> dict:
    """The identity check of ``other`` against ``ref``: stores (paths), or what
    :func:`stored_values` read from them (dicts, e.g. a ``values_<run>.json.gz`` of an earlier
    call)."""
    seen = [0]
    a = ref if isinstance(ref, dict) else stored_values(ref)
    b = other if isinstance(other, dict) else stored_values(other)
    d = differences(a, b, seen=seen)
    top = sorted(d.items(), key=lambda kv: (-kv[1]["max_rel"], -kv[1]["count"]))
    return {
        "identical": not d,
        "files": len(a),
        "values_compared": seen[0],
        "n_fields": len(d),
        "fields": dict(top[:40]),
    }


def write_values(path: Path, values: dict) -> None:
    """What :func:`stored_values` read, as gzipped JSON (floats exactly: ``repr`` round-trips)."""
    with gzip.open(path, "wt", encoding="utf-8") as f:
        json.dump(values, f)


def read_values(path: Path) -> dict:
    """The values written by :func:`write_values`."""
    with gzip.open(path, "rt", encoding="utf-8") as f:
        return json.load(f)


def piece_seconds(ref: dict, other: dict) -> dict:
    """The pieces' own seconds (each piece file's top-level ``seconds``: ``total_s``,
    ``elastic_plastic_s``, ``refinement_s`` …) summed over the pieces both runs stored, and each
    sum of ``other`` over that of ``ref``: whether a piece costs the same wherever it ran."""
    sums: dict[str, list[float]] = {}
    n = 0
    for f in sorted(set(ref) & set(other)):
        a, b = ref[f], other[f]
        if not (isinstance(a, dict) and isinstance(b, dict)):
            continue
        sa, sb = a.get("seconds"), b.get("seconds")
        if not (isinstance(sa, dict) and isinstance(sb, dict)):
            continue
        n += 1
        for k in sorted(set(sa) & set(sb)):
            if _number(sa[k]) and _number(sb[k]):
                t = sums.setdefault(k, [0.0, 0.0])
                t[0] += float(sa[k])
                t[1] += float(sb[k])
    return {
        "pieces": n,
        "reference_s": {k: v[0] for k, v in sums.items()},
        "run_s": {k: v[1] for k, v in sums.items()},
        "ratio": {k: (v[1] / v[0] if v[0] > 0 else None) for k, v in sums.items()},
    }


def compare(argv: list[str], prog: str = "compare") -> int:
    """``compare REF OTHER ... [--json OUT]``: the identity check of runs written by
    :func:`write_values` (e.g. runs made at the same time on different GPUs of one host, each by
    its own benchmark process) against the reference; exit 1 if any differs."""
    ap = argparse.ArgumentParser(
        prog=prog, description="compare values_<run>.json.gz files bit for bit"
    )
    ap.add_argument("reference", type=Path, help="values_inproc.json.gz of the reference run")
    ap.add_argument("others", type=Path, nargs="+", help="values_<run>.json.gz to compare")
    ap.add_argument("--json", type=Path, default=None, help="write the checks here")
    args = ap.parse_args(argv)
    ref = read_values(args.reference)
    checks, seconds = {}, {}
    for o in args.others:
        values = read_values(o)
        checks[str(o)] = identity(ref, values)
        seconds[str(o)] = piece_seconds(ref, values)
    for name, c in checks.items():
        same = "identical" if c["identical"] else f"DIFFERENT in {c['n_fields']} fields"
        print(f"{name}: {same} ({c['values_compared']} values, {c['files']} files)")
        r = seconds[name]["ratio"]
        print(
            "  pieces' seconds ÷ reference: "
            + ", ".join(f"{k} {v:.2f}" for k, v in r.items() if v is not None and k != "surface_s")
        )
    if args.json:
        args.json.write_text(
            json.dumps(
                dict(reference=str(args.reference), checks=checks, piece_seconds=seconds),
                indent=1,
                default=str,
            )
            + "\n"
        )
    return 0 if all(c["identical"] for c in checks.values()) else 1
