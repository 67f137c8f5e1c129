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
part holds); `--migrate OUT` converts a store of the previous layout (one curve file per case); another grid or option set on the same OUT is refused unless
--overwrite. SIGINT/SIGTERM stop after writing what has finished (exit 130/143). One sweep per store at a
time: OUT/.lock holds the running sweep's pid and host, and a second sweep on the same OUT is
refused at once (a lock left by a dead process on this host is taken over, with a message).
sweep.json is strict JSON: "E_flat": null means a rigid flat (E_flat = inf).
Example: warptrunc sweep --D 2.1 2.3 2.5 --delta 0.005 0.01 --seeds 0-4 --n 2048 --out runs/g2
"""

from __future__ import annotations

import argparse
import re
import signal
import sys
from collections import Counter

from .._support.interrupt import check_interrupt, latched_signals
from .._support.validate import DEFAULT_MIN_PIXELS
from ..material import Material
from ..params import add_options, param_info
from ..sweep.grid import SweepGrid
from ..sweep.options import option_name
from ..sweep.read import load, require_extra
from ..sweep.run import run_sweep
from ..sweep.stats import MIN_TREND_D, alpha_summary
from ..wm_params import WMSpec
from ._common import (
    add_device,
    add_devices,
    add_material,
    add_out,
    add_truncation,
    add_wm_shape,
    add_workers,
    input_file,
    integer,
    positive,
    prepare_devices,
    real,
    truncation_from_args,
)

NAME = "sweep"
HELP = "sweep D × δ × seeds into a resumable Parquet store (in-process or on Dask)"


class Terminated(KeyboardInterrupt):
    """Raised by the SIGTERM handler so that the store is flushed on the way out."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc sweep``."""
    g = p.add_argument_group("grid (values on the command line, or --grid FILE)")
    add_options(g, WMSpec, only=("D",), many=("D",), defaults={"D": None},
                docs={"D": "input fractal dimensions D_in"})  # fmt: skip
    g.add_argument("--delta", type=positive(), nargs="+", default=None,
                   help="relative roughness values δ = R_t/W_r (dimensionless); R_t = δ·W_r")  # fmt: skip
    g.add_argument("--seeds", default=None, help="seeds: '0-4', '0,3,7' or '0-2,9' (default 0)")
    g.add_argument("--grid", type=input_file, default=None,
                   help="TOML file with D = [...], delta = [...], seeds = '0-4' and optionally "
                   "a table [axes] of more axes (e.g. M = [8, 10])")  # fmt: skip
    s = p.add_argument_group(
        "surface generation (SI; several values of --Wr, --M, --gamma, --Wc: more grid axes)"
    )
    add_wm_shape(s, many=True)
    g = p.add_argument_group("truncation and material")
    add_truncation(g, only=("increments", "max_depth_fraction", "max_depth", "beta_prime"))
    add_material(g, many=True)
    f = p.add_argument_group("fit range")
    f.add_argument(
        "--min-pixels", type=integer(1), nargs="+", default=[DEFAULT_MIN_PIXELS],
        help="fit only increments with at least this many contact pixels (1 = all with load > 0)"
        "; several values: one fit (row) each",
    )  # fmt: skip
    f.add_argument(
        "--depth-window", type=real(0.0, lo_open=False, unit="m"), nargs=2, default=None,
        metavar=("LO", "HI"), help="fit only depths LO ≤ ω ≤ HI (m)",
    )  # fmt: skip
    m = p.add_argument_group("extra measurements and fit ranges")
    m.add_argument("--min-pixels-fraction", type=float, nargs="+", default=[],
                   help="more fit ranges relative to each case: increments with ≥ f × its final "
                   "contact pixels (at least 10), f in (0, 1]")  # fmt: skip
    m.add_argument("--fractal", nargs="+", default=[], choices=("tri", "box", "vs", "sp"),
                   metavar="METHOD",
                   help="measure D of each generated surface by these methods (tri box vs sp; "
                   "fractal_dimensions' default options): columns D_<method>, D_<method>_r2, "
                   "fractal_options")  # fmt: skip
    m.add_argument("--bem-fractions", type=real(0.0, 1.0), nargs="+", default=[], metavar="F",
                   help="elastic solves per case (free half-space, warptrunc.contact) at "
                   "approaches δ = f·R_t, f in (0, 1): columns F_bem_N_<f>, A_bem_m2_<f>, "
                   "k_bem_N_per_m_<f>, the truncation values F_trunc_N_<f>, ..., the ratios "
                   "F_ratio_<f>, A_ratio_<f>, k_ratio_<f> and bem_converged_<f>")  # fmt: skip
    e = p.add_argument_group("execution")
    add_device(e)
    add_devices(e, "--bem-fractions (with --workers N: each worker takes that many devices of its "
                "own, and --workers auto is the GPUs divided by it)")
    add_workers(e, "the cases", "the cases (its workers write into --out: a shared filesystem)")
    e.add_argument("--shard-size", type=integer(1, 10**6), default=None,
                   help="with --workers/--scheduler: cases per Dask task, each written by its "
                   "worker as one part (default: adaptive, about --shard-seconds of work)")  # fmt: skip
    e.add_argument("--shard-seconds", type=real(0.0, None, lo_open=False), default=1.0,
                   help="work per part of the store (s); a hard kill loses at most about this "
                   "much per worker")  # fmt: skip
    e.add_argument("--migrate", action="store_true",
                   help="only convert the store at --out from the previous layout (one curve "
                   "file per case) to parts, and exit")  # fmt: skip
    e.add_argument("--overwrite", action="store_true",
                   help="replace the results in an existing store made by another grid/options")  # fmt: skip
    e.add_argument("--retry-failed", action="store_true",
                   help="run again the cases recorded with an error")  # fmt: skip
    e.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_out(p, default="sweep")


def _wm_material(args: argparse.Namespace) -> tuple[dict, dict]:
    """(single-valued options, extra axes) of the WMSpec and Material options given."""
    opts: dict = {}
    axes: dict = {}
    for cls in (WMSpec, Material):
        for name, meta in param_info(cls).items():
            v = getattr(args, name, None)
            if name == "D" or v is None:
                continue
            if meta.pair:
                if len(v) > 2:
                    raise ValueError(f"--{meta.cli or name} takes one or two values, got {v}")
                v = v[0] if len(v) == 1 else tuple(v)
            elif isinstance(v, list) and len(v) > 1:
                axes[name] = v
                continue
            elif isinstance(v, list):
                v = v[0]
            opts[option_name(name)] = v
    return opts, axes


def grid_from_args(args: argparse.Namespace):
    """The :class:`SweepGrid` of ``--grid`` or of ``--D/--delta/--seeds``, with the extra
    axes of the options given several values."""

    _, axes = _wm_material(args)
    if args.grid is not None:
        if args.D is not None or args.delta is not None or args.seeds is not None:
            raise ValueError("give --grid FILE or --D/--delta/--seeds, not both")
        g = SweepGrid.from_toml(args.grid)
        return SweepGrid(D=g.D, delta=g.delta, seeds=g.seeds, axes=(*g.axes, *axes.items()))
    if args.D is None or args.delta is None:
        raise ValueError("the grid needs --D and --delta (and --seeds), or --grid FILE")
    seeds = args.seeds if args.seeds is not None else "0"
    return SweepGrid.from_values(args.D, args.delta, seeds, axes=axes)


def options_from_args(args: argparse.Namespace) -> dict:
    """Keyword options of :func:`warptrunc.sweep.run_sweep` from the parsed arguments."""

    wm_material, _ = _wm_material(args)
    t = truncation_from_args(args)
    return dict(
        **wm_material, increments=t.increments,
        max_depth_fraction=t.max_depth_fraction, max_depth=t.max_depth,
        beta_prime=t.beta_prime, min_pixels=tuple(args.min_pixels),
        min_pixels_fraction=tuple(args.min_pixels_fraction),
        fractal_methods=tuple(args.fractal), bem_fractions=tuple(args.bem_fractions),
        depth_window=None if args.depth_window is None else tuple(args.depth_window),
    )  # fmt: skip


def run(args: argparse.Namespace) -> int:
    """Run the sweep; print a summary."""
    try:
        require_extra()
    except ImportError as exc:
        raise ValueError(str(exc)) from None
    if args.migrate:
        return _migrate(args.out)
    if args.devices not in (None, 1):
        if args.devices == "auto" and (args.workers is not None or args.scheduler is not None):
            raise ValueError("--devices auto with --workers/--scheduler: give a count (each "
                             "worker takes that many devices of its own)")  # fmt: skip
        if not args.bem_fractions:
            raise ValueError(f"--devices {args.devices} spreads the elastic solves of "
                             "--bem-fractions, and none are asked for")  # fmt: skip
        prepare_devices(args.devices)
    grid = grid_from_args(args)
    stops = latched_signals({signal.SIGINT: KeyboardInterrupt, signal.SIGTERM: Terminated})
    try:
        with stops:
            df = run_sweep(
                grid, args.out, workers=args.workers, scheduler=args.scheduler,
                overwrite=args.overwrite, retry_failed=args.retry_failed,
                shard_size=args.shard_size, shard_seconds=args.shard_seconds,
                progress=not args.no_progress, device=args.device, devices=args.devices,
                **options_from_args(args),
            )  # fmt: skip
            check_interrupt()  # a signal swallowed in a destructor after the last case
    except KeyboardInterrupt as exc:
        n = load(args.out)["case_id"].nunique() if (args.out / "sweep.json").exists() else 0
        what = "SIGTERM" if isinstance(exc, Terminated) else "interrupted"
        print(f"\n{what}: {n} of {len(grid)} cases are in {args.out}; run the same command "
              "again to finish the rest", file=sys.stderr)  # fmt: skip
        return 143 if isinstance(exc, Terminated) else 130
    except ImportError as exc:
        raise ValueError(str(exc)) from None
    failed = df.loc[df["error"].notna(), "case_id"].nunique()
    print(f"{len(grid)} cases ({failed} failed) in {args.out}: sweep.json, cases.parquet, "
          "curves/part-*.parquet")
    _print_summary(df)
    return 0


def _migrate(out) -> int:
    from ..sweep.lock import store_lock
    from ..sweep.migration import migrate

    if not (out / "sweep.json").exists():
        raise ValueError(f"{out} is not a sweep store (no sweep.json)")
    with store_lock(out, notify=lambda m: print(m, file=sys.stderr)):
        n = migrate(out, notify=print)
    if n == 0:
        print(f"{out} has the current layout already; nothing to convert")
    return 0


def _print_summary(df) -> None:
    """Per fit range: α per D_in (mean ± sd over seeds and δ), the line α(D_in) through at
    least MIN_TREND_D values of D or why there is none, and why fits were left out (each
    reason of ``fit_error``, counted)."""
    ok = df["error"].isna()
    flagged = int((ok & df["fit_error"].notna() & df["alpha"].notna()).sum())
    if flagged:
        print(f"warning: {flagged} fits not worth reading (fit_error in cases.parquet) are left "
              "out of the α summary", file=sys.stderr)  # fmt: skip
    ranges = alpha_summary(df[ok])["fit_ranges"]
    good = alpha_summary(df[ok & df["fit_error"].isna()])["fit_ranges"]
    keys = _range_keys(df)
    for mp in ranges:
        label = mp if mp.startswith("fraction") else f"min_pixels={mp}"
        left = df.loc[ok & (keys == mp) & df["fit_error"].notna(), "fit_error"].tolist()
        why = f"{len(left)} fit{'s' if len(left) != 1 else ''} left out (fit_error in cases.parquet)"
        if mp not in good:
            print(f"{label}: α — no fit worth reading; {why}:")
        else:
            rows = [r for r in good[mp]["per_D"] if r["n"] > 0]
            per_d = ", ".join(
                f"D={r['D_in']:g}: {r['alpha_mean']:.4f}"
                + (f"±{r['alpha_sd']:.4f}" if r["n"] > 1 else "") + f" (n={r['n']})"
                for r in rows
            )
            line = good[mp]["alpha_vs_D"]
            trend = (
                f"α = {line['slope']:.3f}·D {'−' if line['intercept'] < 0 else '+'} "
                f"{abs(line['intercept']):.3f} (r = {line['r']:.3f})" if line
                else f"no line α(D): α worth reading at {len(rows)} value"
                f"{'s' if len(rows) != 1 else ''} of D, a line needs {MIN_TREND_D}"
                + (" (through 2 it is exact, r = ±1)" if len(rows) == 2 else "")
            )  # fmt: skip
            print(f"{label}: α {per_d}; {trend}" + (f"; {why}:" if left else ""))
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
