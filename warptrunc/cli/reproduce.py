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
import sys
from pathlib import Path

from ..reproduce import reproduce
from ..reproduce.profiles import PROFILES
from ..reproduce.study import STAGES
from ..sweep.read import require_extra
from ._common import add_device, add_workers, output_dir

NAME = "reproduce"
HELP = "reproduce the paper's figures and tables with a report"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of ``warptrunc reproduce``."""

    p.add_argument("--profile", choices=sorted(PROFILES), default="quick", help="sizes of the run")
    p.add_argument(
        "--out", type=output_dir, default=Path("reproduction"), help="output folder"
    )
    p.add_argument("--overwrite", action="store_true",
                   help="recompute stages stored with other parameters (replacing them)")  # fmt: skip
    p.add_argument("--commit", metavar="SHA", default=None,
                   help="commit recorded in the report (default: $WARPTRUNC_GIT_COMMIT, else "
                        "git rev-parse HEAD of the checkout, else 'unknown')")  # fmt: skip
    p.add_argument("--stages", metavar="NAME[,NAME...]", default=None,
                   help=f"compute only these stages (of {', '.join(STAGES)}); the others are "
                        "reused when stored with the same parameters, else left out")  # fmt: skip
    p.add_argument("--time-budget", metavar="SECONDS", type=float, default=None,
                   help="stop the indentation stage between pieces after this many seconds; "
                        "its finished pieces are kept and a rerun continues (default: no limit)")  # fmt: skip
    add_workers(p, "the indentation stage's parts (one punch × one realisation of a piece each) "
                "and the elastic stage's maps (the other stages in this process)",
                "the same tasks (workers one per GPU, on a filesystem shared with --out)")
    add_device(p)


def run(args: argparse.Namespace) -> int:
    """Run the study and print where the report is."""

    try:  # the Table 3 groups run on the sweep store
        require_extra()
    except ImportError as exc:
        raise ValueError(str(exc)) from None
    doc = reproduce(args.profile, args.out, overwrite=args.overwrite, device=args.device,
                    commit=args.commit, command="warptrunc " + " ".join(sys.argv[1:]),
                    stages=args.stages, time_budget=args.time_budget, workers=args.workers,
                    scheduler=args.scheduler)  # fmt: skip
    m = doc["meta"]
    print(f"wrote {args.out}/report.md, results.json and {len(m['figures'])} figures "
          f"in {m['wall_s']:.1f} s on {m['device']} (reused: {', '.join(m['reused']) or 'none'})")  # fmt: skip
    for msg in m.get("incomplete", {}).values():
        print(f"incomplete: {msg}")
    return 0
