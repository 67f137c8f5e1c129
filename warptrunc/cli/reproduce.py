# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Reproduce the paper's study (Fig. 2, Fig. 5, Tables 1–3, Figs. 7–10) and write a report.

Writes OUT/report.md, OUT/results.json, the figures (PNG) and OUT/stages/*.json. A rerun with
the same --out reuses finished stages; one whose parameters differ is refused unless
--overwrite. Profiles: tiny (CI, < 1 min on a CPU), quick (a few minutes on a 2-core CPU),
paper (the paper's sizes, for a GPU). --stages runs only some stages (the others are reused when
stored); the indentation stage stores its pieces as they finish, so a rerun continues it, and
--time-budget stops it cleanly between pieces.
"""

from __future__ import annotations

import argparse

from ..reproduce import reproduce
from ..reproduce.study import STAGES
from ..sweep.read import require_extra
from ._common import (
    add_commit,
    add_device,
    add_no_progress,
    add_out,
    add_overwrite,
    add_profile,
    add_stages,
    add_time_budget,
    add_workers,
)

NAME = "reproduce"
HELP = "reproduce the paper's figures and tables with a report"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc reproduce``: which profile, which stages, where and how it runs
    (what each stage computes is the profile's, :mod:`warptrunc.reproduce.profiles`)."""
    add_profile(p, "sizes of the run", "quick")
    add_out(p, "reproduction")
    add_overwrite(p, "stages stored with other parameters (recomputed)")
    add_commit(p)
    add_stages(p, STAGES)
    add_time_budget(p, "the indentation stage between pieces")
    add_workers(
        p,
        "the indentation stage's parts (one punch × one realisation of a piece each) "
        "and the elastic stage's maps (the other stages in this process)",
        "the same tasks (workers one per GPU, on a filesystem shared with --out)",
    )
    add_device(p)
    add_no_progress(p)


def run(args: argparse.Namespace) -> int:
    """Run the study and print where the report is."""
    try:  # the Table 3 groups run on the sweep store
        require_extra()
    except ImportError as exc:
        raise ValueError(str(exc)) from None
    doc = reproduce(
        args.profile,
        args.out,
        stages=args.stages,
        overwrite=args.overwrite,
        time_budget=args.time_budget,
        commit=args.commit,
        device=args.device,
        workers=args.workers,
        scheduler=args.scheduler,
    )
    m = doc["meta"]
    print(
        f"wrote {args.out}/report.md, results.json and {len(m['figures'])} figures "
        f"in {m['wall_s']:.1f} s on {m['device']} (reused: {', '.join(m['reused']) or 'none'})"
    )
    for msg in m.get("incomplete", {}).values():
        print(f"incomplete: {msg}")
    return 0
