# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Stage ``indentation`` of ``warptrunc reproduce``: the paper's experiment (§ 4.1, Fig. 6) in
silico, by concern:

- ``design``: what the stage computes (:class:`IndentationStage`, a profile's ``indentation``)
  and what it implies (the maps, the sweep's H order, the designs, the faces);
- ``pieces``: the stored units of work, pieces (surface × design × H) and their parts (one
  punch × one realisation), their parameters, files, run and merge;
- ``schedule``: the work plan and its two executors, in this process or on a Dask cluster;
- ``stage``: the stage (:func:`stage_indentation`, :func:`stage_params`) and its resolution
  check;
- ``summary``: the stage result from the stored pieces;
- ``rules``: the rules of the analysis on plain tables (depth at a load, depth match, hardness
  range, agreement depth);
- ``analysis``: the report's numbers from the stage result;
- ``tables`` and ``report``: the report section's tables, text and figures.

Every public name is importable from here (imported on first use), so that the profiles load
the design without the stage's solvers.
"""

from ..._support.exports import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "IndentationStage": ".design",
        "StageIncomplete": ".stage",
        "analyse_indentation": ".analysis",
        "model_name": ".design",
        "stage_indentation": ".stage",
        "stage_params": ".stage",
        "stats_hardness": ".schedule",
        "summary_from_pieces": ".summary",
        "tracking": ".analysis",
    },
)
