# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Survey of instrument files: read, analysed on the defaults, refused clearly, misread
====================================================================================

Reads every file of the given folders with :func:`warptrunc.io.read_height_map` as
``warptrunc analyze --input FILE --missing fill`` does (missing points filled, the map as
measured; ``dx = 1 µm`` only when the file has no spacing and the reader asks for one), runs
:func:`warptrunc.analysis.analyze` on the ``analyze`` defaults (200 increments to 0.1·R_t,
``min_pixels = 10``, and the automatic rule of :mod:`warptrunc.robust` for maps read from
files), and sorts each file into

* **analysed** — read, and its fit is worth reading (the rule's decisions named);
* **flagged** — read and fitted, but the fit is not worth reading (``fit_error``);
* **read, advice** — read, no range gives a fit worth reading, and the message names option
  values that do for this map (each checked on the map), or what on the map keeps every range
  from one;
* **refused** — not read or not analysed (a map under 32 pixels a side), with a one-line
  ValueError naming the problem;
* **misread** — read into a map that disagrees with SurfaceTopography's reading of the same
  file (other shape, a 1-D scan read as a map, heights not proportional); must be 0;
* **crashed** — any other exception (a traceback for the user); must be 0.

SurfaceTopography is the independent reference: where it opens a file, our shape must be its
``nb_grid_pts`` transposed and our heights proportional to its heights (a plain ``.npy`` is
compared untransposed: SurfaceTopography takes the array as h[ix, iy], warptrunc as z[iy, ix],
the convention its documentation states).

Writes ``scan_survey.md`` (the table), ``scan_survey.json`` (one row per file) and
``survey.png`` (files per category) to ``--out``.

Folders: the measured scans in ``../shared/data/scans`` and SurfaceTopography's
``test/file_format_examples`` (set ``WARPTRUNC_ST_EXAMPLES`` or pass folders)::

    python examples/scan_survey.py --out survey /work/shared/data/scans /tmp/st_examples
"""

# The docs build does not run this example (the scans are not part of the repository); its
# gallery card shows survey.png of a run on ../shared/data/scans:
# sphinx_gallery_thumbnail_path = "_static/scan_survey.png"

from __future__ import annotations

import argparse
import gc
import json
import os
import sys
import warnings
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parents[2]  # the folder that holds the checkout and shared/
DEFAULT_DIRS = [HERE / "shared" / "data" / "scans"]
if os.environ.get("WARPTRUNC_ST_EXAMPLES"):
    DEFAULT_DIRS.append(Path(os.environ["WARPTRUNC_ST_EXAMPLES"]))


def _reference(f: Path):
    """(nb_grid_pts, heights h[ix, iy]) from SurfaceTopography, or None if it cannot read."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            from SurfaceTopography import open_topography

            r = open_topography(str(f))
            ch = r.default_channel
            n = tuple(int(v) for v in ch.nb_grid_pts)
            h = None
            if len(n) == 2:
                kw = {}
                if ch.physical_sizes is None:
                    kw["physical_sizes"] = tuple(float(v) for v in n)
                if ch.unit is None and ch.physical_sizes is None:
                    kw["unit"] = "m"
                h = np.ma.filled(np.ma.asarray(r.topography(**kw).heights(), float), np.nan)
            getattr(r, "close", lambda: None)()
            del r
            gc.collect()  # some readers leave their file open
            return n, h
    except Exception:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            gc.collect()
        return None


def _proportional(a: np.ndarray, b: np.ndarray) -> bool:
    ok = np.isfinite(a) & np.isfinite(b)
    if ok.sum() < 2 or np.ptp(a[ok]) == 0 or np.ptp(b[ok]) == 0:
        return True  # constant maps: nothing to compare beyond the shape
    return abs(np.corrcoef(a[ok], b[ok])[0, 1]) > 0.999


def survey_file(f: Path, device: str) -> dict:
    """The category of one file and what decided it."""
    from warptrunc.analysis import analyze
    from warptrunc.truncation import TruncationSettings
    from warptrunc.io import read_height_map
    from warptrunc.robust import AutoRangeError, fit_range_advice

    row = {"file": f.name, "options": "", "category": "", "detail": ""}
    ref = _reference(f)
    kw = {"missing": "fill"}
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                s = read_height_map(f, **kw)
            except ValueError as exc:
                if "give dx" not in str(exc):
                    raise
                s = read_height_map(f, dx=1e-6, **kw)
                row["options"] = "--dx 1e-6"
    except ValueError as exc:
        row["category"], row["detail"] = "refused", str(exc).replace(str(f), f.name)[:160]
        return row
    except Exception as exc:
        row["category"], row["detail"] = "crashed", f"{type(exc).__name__}: {exc}"[:160]
        return row
    if ref is not None:
        n, h = ref
        # SurfaceTopography takes a plain .npy array as h[ix, iy]; warptrunc as z[iy, ix]
        same = f.suffix.lower() == ".npy"
        if len(n) != 2 or (s.ny, s.nx) != (n if same else (n[1], n[0])):
            row["category"] = "misread"
            row["detail"] = f"read {s.nx}×{s.ny}, SurfaceTopography: {n}"
            return row
        raw = read_height_map(f, dx=1e-6 if row["options"] else None, missing="fill")
        if h is not None and not _proportional(np.asarray(raw.heights, float), h if same else h.T):
            row["category"], row["detail"] = "misread", "heights differ from SurfaceTopography's"
            return row
    try:
        a = analyze(
            s, truncation=TruncationSettings(islands=False), device=device
        )  # analyze's defaults and its rule
    except AutoRangeError as exc:  # no fit worth reading: what to change, checked on the map
        row["category"] = "read, advice"
        row["detail"] = str(exc).replace(str(f), f"{f.name} ({s.nx}×{s.ny})")
        return row
    except ValueError as exc:
        advice = fit_range_advice(
            s.heights,
            increments=200,
            max_depth_fraction=0.1,
            max_depth=None,
            min_pixels=10,
            depth_window=None,
        )
        if "fit range" in str(exc) and advice:
            row["category"] = "read, advice"
            row["detail"] = "; ".join(a.split(" (")[0] for a in advice)
        else:
            row["category"], row["detail"] = "refused", str(exc)[:160]
        return row
    fit, rule = a.fit, a.fit_range
    keys = ("levelled", "spikes_masked", "depth_extended", "depth_cut")
    done = [k for k in keys if rule.get(k)]
    row["category"] = "analysed" if a.fit_error is None else "flagged"
    row["detail"] = f"{s.nx}×{s.ny}, α = {fit.alpha:.3f}, r² = {fit.r2:.3f}" + (
        f"; automatic: {', '.join(done)}" if done else ""
    )
    return row


CATEGORIES = ("analysed", "flagged", "read, advice", "refused", "misread", "crashed")


def survey(dirs: list[Path], device: str = "cpu", quick: bool = False) -> list[dict]:
    """One row per file of ``dirs`` (README files skipped)."""
    files = []
    for d in dirs:
        if d.is_dir():
            files += sorted(p for p in d.iterdir() if p.is_file() and p.suffix != ".md")
    if quick:
        files = files[:4]
    return [survey_file(f, device) for f in files]


def table(rows: list[dict]) -> str:
    """Markdown: one line per file, then the counts."""
    lines = ["| file | read options | category | detail |", "|---|---|---|---|"]
    lines += [f"| {r['file']} | {r['options']} | {r['category']} | {r['detail']} |" for r in rows]
    counts = {c: sum(r["category"] == c for r in rows) for c in CATEGORIES}
    rule = "|" + "---|" * (len(CATEGORIES) + 1)
    lines += ["", "| " + " | ".join(CATEGORIES) + " | total |", rule]
    lines.append("| " + " | ".join(str(counts[c]) for c in CATEGORIES) + f" | {len(rows)} |")
    return "\n".join(lines) + "\n"


def figure(rows: list[dict], path: Path) -> None:
    """Bar chart of the files per category (survey.png)."""
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    counts = [sum(r["category"] == c for r in rows) for c in CATEGORIES]
    colors = ["tab:green", "tab:orange", "tab:olive", "tab:gray", "tab:red", "k"]
    fig = Figure(figsize=(5.0, 3.0), dpi=150, layout="constrained")
    ax = fig.subplots()
    y = np.arange(len(CATEGORIES))[::-1]
    ax.barh(y, counts, color=colors)
    for yi, c in zip(y, counts, strict=True):
        ax.text(c, yi, f" {c}", va="center", fontsize=8)
    ax.set_yticks(y, CATEGORIES)
    ax.set_xlim(0, max([*counts, 1]) * 1.15)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("instrument files")
    ax.set_title(f"{len(rows)} files read and analysed on the analyze defaults", fontsize=9)
    fig.savefig(path)


def main(argv: list[str] | None = None) -> int:
    """Survey the folders, print the table, write it (and JSON) to --out."""
    p = argparse.ArgumentParser(
        description=__doc__.splitlines()[0],
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    p.add_argument("dirs", nargs="*", type=Path, default=DEFAULT_DIRS, help="folders to survey")
    p.add_argument("--device", default="cpu", help="Warp device")
    p.add_argument("--out", type=Path, default=Path("survey"), help="output folder")
    p.add_argument("--quick", action="store_true", help="the first four files only")
    p.add_argument("--no-show", action="store_true", help="no effect (survey.png is saved)")
    args = p.parse_args(argv)
    rows = survey(args.dirs, args.device, args.quick)
    text = table(rows)
    print(text)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "scan_survey.md").write_text(text)
    (args.out / "scan_survey.json").write_text(json.dumps(rows, indent=1) + "\n")
    figure(rows, args.out / "survey.png")
    bad = sum(r["category"] in ("misread", "crashed") for r in rows)
    return 1 if bad else 0


if __name__ == "__main__":
    if (status := main()) != 0:
        sys.exit(status)
