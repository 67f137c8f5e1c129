# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Sweep D × δ × seeds (and more axes) into a result store that a re-run resumes.

Several values of a sweepable surface or material option (--Wr, --M, --gamma, --Wc, --E,
--nu, --E-i, --nu-i) make it one more axis of the grid (outermost), as a table [axes] of the
--grid file does; one value is an option shared by every case.

Writes OUT/sweep.json (grid and options), OUT/curves/part-*.parquet (one Parquet part per
shard of about 1 s of work: its curves, and its rows in the metadata; a dataset that
pd.read_parquet("OUT/curves") reads) and OUT/cases.parquet (one row per case × fit range,
rebuilt from the parts). Running the same command again skips the finished cases (those some
part holds); another grid or option set on the same OUT is refused unless --overwrite.
SIGINT/SIGTERM stop after writing what has finished (exit 130/143). One sweep per store at a
time: OUT/.lock holds the running sweep's pid and host, and a second sweep on the same OUT is
refused at once (a lock left by a dead process on this host is taken over, with a message).
sweep.json is strict JSON and spells E_i, ν_i as the store always has: "E_flat": null means a
rigid flat (E_i = inf).
Example: warptrunc sweep --D 2.1 2.3 2.5 --delta 0.005 0.01 --seeds 0-4 --n 2048 --out runs/g2
"""

from __future__ import annotations

import argparse
import re
import signal
import sys
from collections import Counter

from .._support.interrupt import check_interrupt, latched_signals
from ..params import add_options, from_args
from ..sweep.grid import SweepGrid
from ..sweep.options import SweepExecution, SweepOptions, axis_names
from ..sweep.read import load, require_extra
from ..sweep.run import run_sweep
from ..sweep.stats import MIN_TREND_D, alpha_summary, worth_reading
from ._common import (
    add_device,
    add_devices,
    add_grid_file,
    add_no_progress,
    add_out,
    add_overwrite,
    add_retry_failed,
    add_shards,
    add_workers,
    prepare_devices,
)

NAME = "sweep"
HELP = "sweep D × δ × seeds into a resumable Parquet store (in-process or on Dask)"

AXES = tuple(axis_names(runnable=True))
"""Options that take several values, each value a case of one more grid axis."""

SURFACE = ("Wr", "L", "n", "M", "gamma", "Wc", "cutoff")
TRUNCATION_MATERIAL = (
    "increments",
    "max_depth_fraction",
    "max_depth",
    "beta_prime",
    "E",
    "nu",
    "E_i",
    "nu_i",
)
FIT_RANGE = ("min_pixels", "depth_window")
EXTRA = ("min_pixels_fraction", "fractal_methods", "bem_fractions")


class Terminated(KeyboardInterrupt):
    """Raised by the SIGTERM handler so that the store is flushed on the way out."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc sweep``: the fields of :class:`~warptrunc.sweep.SweepGrid` and
    :class:`~warptrunc.sweep.SweepOptions`, and where the cases run and the store goes."""
    g = p.add_argument_group("grid (values on the command line, or --grid FILE)")
    add_options(g, SweepGrid, only=("D", "delta", "seeds"), defaults={"D": None, "delta": None})
    add_grid_file(g)
    groups = (
        (
            "surface generation (SI; several values of --Wr, --M, --gamma, --Wc: more grid axes)",
            SURFACE,
        ),
        (
            "truncation and material (several values of --E, --nu, --E-i, --nu-i: more grid axes)",
            TRUNCATION_MATERIAL,
        ),
        ("fit range", FIT_RANGE),
        ("extra measurements and fit ranges", EXTRA),
    )
    for title, names in groups:
        add_options(
            p.add_argument_group(title),
            SweepOptions,
            only=names,
            many=[k for k in names if k in AXES],
        )
    e = p.add_argument_group("execution")
    add_device(e)
    add_devices(
        e,
        "--bem-fractions (with --workers N: each worker takes that many devices of its "
        "own, and --workers auto is the GPUs divided by it)",
    )
    add_workers(e, "the cases", "the cases (its workers write into --out: a shared filesystem)")
    add_shards(e)
    add_overwrite(e, "the results in an existing store made by another grid/options")
    add_retry_failed(e, "the cases recorded with an error")
    add_no_progress(e)
    add_out(p, default="sweep")


def _axes(args: argparse.Namespace) -> dict:
    """The options given several values: field → values (each an extra axis of the grid)."""
    return {k: v for k in AXES if isinstance(v := getattr(args, k, None), list) and len(v) > 1}


def grid_from_args(args: argparse.Namespace) -> SweepGrid:
    """The :class:`SweepGrid` of ``--grid`` or of ``--D/--delta/--seeds``, with the extra
    axes of the options given several values."""

    axes = _axes(args)
    if args.grid is not None:
        if args.D is not None or args.delta is not None or args.seeds is not None:
            raise ValueError("give --grid FILE or --D/--delta/--seeds, not both")
        g = SweepGrid.from_toml(args.grid)
        return SweepGrid(D=g.D, delta=g.delta, seeds=g.seeds, axes=(*g.axes, *axes.items()))
    if args.D is None or args.delta is None:
        raise ValueError("the grid needs --D and --delta (and --seeds), or --grid FILE")
    return from_args(SweepGrid, args, axes=tuple(axes.items()))


def options_from_args(args: argparse.Namespace) -> SweepOptions:
    """The :class:`SweepOptions` of the parsed arguments; an option given several values is an
    axis of the grid (:func:`grid_from_args`) and keeps its default here."""

    single = argparse.Namespace(**{**vars(args), **dict.fromkeys(_axes(args))})
    return from_args(SweepOptions, single)


def execution_from_args(args: argparse.Namespace) -> SweepExecution:
    """The :class:`SweepExecution` of ``--workers``, ``--scheduler``, ``--devices``,
    ``--shard-size`` and ``--shard-seconds`` (those not given: its defaults)."""

    return from_args(
        SweepExecution, args, workers=args.workers, scheduler=args.scheduler, devices=args.devices
    )


def run(args: argparse.Namespace) -> int:
    """Run the sweep; print a summary."""
    try:
        require_extra()
    except ImportError as exc:
        raise ValueError(str(exc)) from None
    options = options_from_args(args)
    execution = execution_from_args(args)
    if execution.spread:
        if args.devices == "auto" and execution.distributed:
            raise ValueError(
                "--devices auto with --workers/--scheduler: give a count (each "
                "worker takes that many devices of its own)"
            )
        if not options.bem_fractions:
            raise ValueError(
                f"--devices {args.devices} spreads the elastic solves of "
                "--bem-fractions, and none are asked for"
            )
        prepare_devices(args.devices)
    grid = grid_from_args(args)
    stops = latched_signals({signal.SIGINT: KeyboardInterrupt, signal.SIGTERM: Terminated})
    try:
        with stops:
            df = run_sweep(
                grid,
                args.out,
                options=options,
                execution=execution,
                overwrite=args.overwrite,
                retry_failed=args.retry_failed,
                progress=not args.no_progress,
                device=args.device,
            )
            check_interrupt()  # a signal swallowed in a destructor after the last case
    except KeyboardInterrupt as exc:
        n = load(args.out)["case_id"].nunique() if (args.out / "sweep.json").exists() else 0
        what = "SIGTERM" if isinstance(exc, Terminated) else "interrupted"
        print(
            f"\n{what}: {n} of {len(grid)} cases are in {args.out}; run the same command "
            "again to finish the rest",
            file=sys.stderr,
        )
        return 143 if isinstance(exc, Terminated) else 130
    except ImportError as exc:
        raise ValueError(str(exc)) from None
    failed = df.loc[df["error"].notna(), "case_id"].nunique()
    print(
        f"{len(grid)} cases ({failed} failed) in {args.out}: sweep.json, cases.parquet, "
        "curves/part-*.parquet"
    )
    _print_summary(df)
    return 0


def _print_summary(df) -> None:
    """Per fit range and δ: α per D_in (mean ± sd over the seeds, n seeds), the line α(D_in)
    through at least MIN_TREND_D values of D or why there is none, and why fits were left out
    (each reason of ``fit_error``, counted). The fits are those
    :func:`~warptrunc.sweep.worth_reading` keeps, as in ``summary.json`` and the figures."""
    ok = df["error"].isna()
    flagged = int((ok & ~worth_reading(df) & df["alpha"].notna()).sum())
    if flagged:
        print(
            f"warning: {flagged} fits not worth reading (fit_error in cases.parquet) are left "
            "out of the α summary",
            file=sys.stderr,
        )
    ranges = alpha_summary(df[ok])["fit_ranges"]
    keys = _range_keys(df)
    several = "delta" in df and df.loc[ok, "delta"].nunique() > 1
    for mp, summary in ranges.items():
        label = mp if mp.startswith("fraction") else f"min_pixels={mp}"
        left = df.loc[ok & (keys == mp) & df["fit_error"].notna(), "fit_error"].tolist()
        why = (
            f"{len(left)} fit{'s' if len(left) != 1 else ''} left out (fit_error in cases.parquet)"
        )
        lines = {line["delta"]: line for line in summary["alpha_vs_D"]}
        deltas = list(dict.fromkeys(r["delta"] for r in summary["per_D"]))
        for i, delta in enumerate(deltas):
            head = f"{label}, δ={delta:g}" if several and delta is not None else label
            tail = f"; {why}:" if left and i == len(deltas) - 1 else ""
            rows = [r for r in summary["per_D"] if r["delta"] == delta and r["n"] > 0]
            if not rows:
                print(f"{head}: α — no fit worth reading{tail}")
                continue
            per_d = ", ".join(
                f"D={r['D_in']:g}: {r['alpha_mean']:.4f}"
                + (f"±{r['alpha_sd']:.4f}" if r["n"] > 1 else "")
                + f" (n={r['n']} seed{'s' if r['n'] != 1 else ''})"
                for r in rows
            )
            line = lines.get(delta)
            trend = (
                f"α = {line['slope']:.3f}·D {'−' if line['intercept'] < 0 else '+'} "
                f"{abs(line['intercept']):.3f} (r = {line['r']:.3f})"
                if line
                else f"no line α(D): α worth reading at {len(rows)} value"
                f"{'s' if len(rows) != 1 else ''} of D, a line needs {MIN_TREND_D}"
                + (" (through 2 it is exact, r = ±1)" if len(rows) == 2 else "")
            )
            print(f"{head}: α {per_d}; {trend}{tail}")
        for text in _reasons(left):
            print(f"  {text}")


def _range_keys(df):
    """The fit-range key of each row, as :func:`~warptrunc.sweep.alpha_summary` names it."""
    keys = df["min_pixels"].map(lambda v: str(int(v)) if v == v else "")
    if "min_pixels_fraction" in df:
        frac = df["min_pixels_fraction"].astype(float)
        keys = keys.where(frac.isna(), frac.map(lambda f: f"fraction={f:g}"))
    return keys


_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def _reasons(errors: list[str], top: int = 3) -> list[str]:
    """The reasons in ``fit_error`` texts, most common first: "N× reason" (reasons that
    differ only in their numbers counted together, the first one shown)."""
    count: Counter = Counter()
    first: dict[str, str] = {}
    for e in errors:
        body = e.removeprefix("not worth reading: ")
        parts = re.split(r"; (?=(?:islands )?fit: )", body) if body != e else [e]
        for part in parts:
            key = _NUMBER.sub("#", part)
            count[key] += 1
            first.setdefault(key, part)
    out = [f"{n}× {first[k]}" for k, n in count.most_common(top)]
    if len(count) > top:
        out.append(f"… and {len(count) - top} other reasons")
    return out
