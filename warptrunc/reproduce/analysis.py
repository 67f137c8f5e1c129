# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Numbers of the reproduction report, from the stage results (no computation on surfaces)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..stiffness import fit_power_law
from ..sweep.stats import linear_fit
from .paper import TABLE1, TABLE2, TABLE3

__all__ = ["analyse", "slit_band_summary"]

D_KEYS = ("in", "tri", "box", "vs", "sp")


def _line(x, y) -> dict[str, float] | None:
    """y = slope·x + intercept with Pearson r (NaN when y is constant) and ``n`` (points used),
    by :func:`warptrunc.sweep.linear_fit`; pairs with a non-finite value are
    dropped; None with fewer than 2 points or 2 distinct x."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    if x.size < 2 or np.ptp(x) == 0:
        return None
    return {**linear_fit(x, y), "n": int(x.size)}


def _power(x, y) -> dict[str, float] | None:
    """y = b·x^p by :func:`warptrunc.fit_power_law` of two arrays: ``b``, exponent ``p``,
    Pearson ``r`` of the logs and ``n``; pairs not positive and finite dropped; None with fewer
    than 2 pairs or 2 distinct x."""
    try:
        f = fit_power_law(x, y, min_points=2)
    except ValueError:
        return None
    return {"b": f.beta, "p": f.alpha, "r": f.r, "n": f.n_points}


def worth_reading(f: dict[str, Any]) -> bool:
    """A stage row's fit enters the lines, means and figures: it has an α and is not flagged
    not worth reading (``warning``, the sweep's ``fit_error``; as
    :func:`warptrunc.sweep.worth_reading`). Flagged fits stay in the rows and are drawn
    hollow."""
    return f.get("alpha") is not None and not f.get("warning")


def _points(rows, fit, key):
    xs, a = [], []
    for r in rows:
        f = r["fits"][fit]
        if not worth_reading(f):
            continue
        x = r["D_in"] if key == "in" else r.get("D", {}).get(key, {}).get("D")
        if x is None:
            continue
        xs.append(x)
        a.append(f["alpha"])
    return xs, a


def analyse(res: dict[str, Any]) -> dict[str, Any]:
    """Every number the report prints, with the paper's value beside it where there is one.

    Parameters
    ----------
    res : dict of str to Any
        The stage results of :func:`~warptrunc.reproduce.study.run_study` (``group1``,
        ``group2`` and the other stages).

    Returns
    -------
    dict of str to Any
        The derived numbers (Table 3 fits of α against D per fit range and D method, and the
        others :func:`~warptrunc.reproduce.report.markdown` prints), JSON-serialisable.
    """
    out: dict[str, Any] = {}
    if "group1" in res and "group2" in res:
        g1, g2 = res["group1"], res["group2"]
        # Table 3, α(D) per fit range and D method, one point per generated surface
        t3: dict[str, Any] = {}
        for fit in g2["fit_ranges"]:
            t3[fit] = {}
            for k in D_KEYS:
                f = _line(*_points(g2["rows"], fit, k))
                t3[fit][k] = {
                    "ours": f,
                    "paper": dict(
                        zip(("slope", "intercept", "r"), TABLE3["alpha"][k], strict=True)
                    ),
                }
        out["table3_alpha"] = t3
        # group 1: β(δ) and the scaling argument β ∝ δ^−α
        b1: dict[str, Any] = {}
        for fit in g1["fit_ranges"]:
            rows = [
                r
                for r in g1["rows"]
                if r["fits"][fit].get("beta") is not None and worth_reading(r["fits"][fit])
            ]
            pf = _power([r["delta"] for r in rows], [r["fits"][fit]["beta"] for r in rows])
            alphas = np.array([r["fits"][fit]["alpha"] for r in rows])
            b1[fit] = {
                "ours": pf,
                "alpha_mean": float(alphas.mean()) if alphas.size else None,
                "alpha_sd": float(alphas.std(ddof=1)) if alphas.size > 1 else None,
                "minus_alpha": -float(alphas.mean()) if alphas.size else None,
                "paper": {"b": TABLE3["beta"][0], "p": TABLE3["beta"][1], "r": TABLE3["beta"][2]},
                "n_surfaces": len(rows),
            }
        out["table3_beta"] = b1
        # α per D_in (group 2) and per δ (group 1), mean ± sd
        for name, g, key in (("group2_alpha", g2, "D_in"), ("group1_alpha", g1, "delta")):
            out[name] = {}
            for fit in g["fit_ranges"]:
                per = {}
                for r in g["rows"]:
                    if worth_reading(r["fits"][fit]):
                        per.setdefault(r[key], []).append(r["fits"][fit]["alpha"])
                out[name][fit] = {
                    str(k): {
                        "mean": float(np.mean(v)),
                        "sd": float(np.std(v, ddof=1)) if len(v) > 1 else None,
                        "n": len(v),
                    }
                    for k, v in sorted(per.items())
                }
        # D convention: the options each method ran with
        first = next((r for r in g2["rows"] if "D" in r), None)
        out["d_options"] = {k: v["options"] for k, v in first["D"].items()} if first else {}
    if "fig5" in res:
        # Fig. 5
        f5 = res["fig5"]
        conv: dict[str, Any] = {}
        for r in f5["rows"]:
            conv.setdefault(f"{r['n']}|{r['increments']}", []).append(r["Ec_over_E"])
        out["fig5"] = {
            k: [
                None
                if all(x[i] is None for x in v)
                else float(np.mean([x[i] for x in v if x[i] is not None]))
                for i in range(len(f5["loads"]))
            ]
            for k, v in conv.items()
        }
    if "table1" in res:
        # Table 1
        t1 = []
        for r in res["table1"]["rows"]:
            Rt, rrms, _wr, *d_paper = TABLE1[r["surface"]]
            row = {
                "surface": r["surface"],
                "matched": r["matched"],
                "status": r["status"],
                "paper": {
                    "Rt_um": Rt,
                    "Rrms_um": rrms,
                    "D": dict(zip(D_KEYS[1:], d_paper, strict=True)),
                },
            }
            if r["status"] == "ok":
                row.update(
                    D_in=r["D_in"],
                    Rt_um=r["Rt_m"] / 1e-6,
                    Rrms_um=r["Rrms_m"] / 1e-6,
                    D_out=r["D_out"],
                )
            else:
                row["message"] = r.get("message")
            t1.append(row)
        out["table1"] = t1
    if "islands" in res:
        # Table 2 and the slit exponent's depth trend
        t2 = {}
        for name, s in res["islands"]["surfaces"].items():
            inds = [x["indicators"] for x in s["seeds"]]

            def m(key, inds=inds):
                v = [i[key] for i in inds if i.get(key) is not None]
                return float(np.mean(v)) if v else None

            frac = np.asarray(s["seeds"][0]["depth_fraction"])
            ex = np.array(
                [[np.nan if v is None else v for v in x["slit_exponent"]] for x in s["seeds"]]
            )
            ok = np.isfinite(ex)
            cnt = ok.sum(axis=0)
            mean_ex = np.where(
                cnt > 0, np.where(ok, ex, 0.0).sum(axis=0) / np.maximum(cnt, 1), np.nan
            )
            trend = {
                f"{int(p)}": (None if not np.isfinite(v) else float(v))
                for p in (5, 10, 20, 30, 40, 50)
                for v in [mean_ex[int(np.argmin(np.abs(frac - p / 100)))]]
            }
            t2[name] = {
                "max_growth_rate_depth_percent_Rt": m("max_growth_rate_depth_percent_Rt"),
                "fractality_depth_percent_Rt": m("fractality_depth_percent_Rt"),
                "island_peak_depth_percent_Rt": m("island_peak_depth_percent_Rt"),
                "plateau_exponent": m("plateau_exponent"),
                "slit_exponent_at_percent_Rt": trend,
                "paper": dict(
                    zip(("applicable", "max_growth", "fractality"), TABLE2[name], strict=True)
                ),
            }
        out["table2"] = t2
        out["slit_band"] = slit_band_summary(res["islands"])
    if "asperity" in res:
        out["asperity"] = {
            k: v for k, v in res["asperity"]["bounds"].items() if not isinstance(v, list)
        }
        out["asperity"]["pixel_bound_holds"] = res["asperity"]["pixel_bound_holds"]
        out["asperity"]["max_rel_area_error_last_half"] = res["asperity"][
            "max_rel_area_error_last_half"
        ]
    if "elastic" in res:
        from .elastic import analyse_elastic

        out["elastic"] = analyse_elastic(res["elastic"])
    if "indentation" in res:
        from .indentation.analysis import analyse_indentation

        out["indentation"] = analyse_indentation(res["indentation"])
    return out


def slit_band_summary(
    islands: dict[str, Any], tolerance: float = 0.05, plateau_width: float = 10.0
) -> dict[str, Any]:
    """Slit exponent with its bootstrap band per surface (seed 0) and, for every seed, where a
    drop below (1 − ``tolerance``)·plateau is possible and where it is established.

    Parameters
    ----------
    islands : dict of str to Any
        The island stage (per seed ``slit_band`` with ``percent_Rt``, ``exponent``, ``lo``,
        ``hi``).
    tolerance : float
        Relative drop below the plateau that ends fractality (dimensionless), as in
        ``applicable_depth``.
    plateau_width : float
        Plateau window from the first fitted depth (% R_t).

    Returns
    -------
    dict of str to Any
        Per surface: seed 0's ``percent_Rt``, ``exponent``, ``lo``, ``hi`` and ``plateau``;
        per seed ``possible_drop_percent_Rt`` (first depth past the plateau window whose band
        reaches below the threshold) and ``established_drop_percent_Rt`` (first such depth
        whose whole band is below it), None where there is none; ``paper`` (Table 2 fractality range, % R_t).
    """
    out: dict[str, Any] = {}
    for name, s in islands["surfaces"].items():
        poss, est, plateaus = [], [], []
        for x in s["seeds"]:
            b = x.get("slit_band")
            if not b:
                break
            pct = np.asarray(b["percent_Rt"], float)
            e, lo, hi = (
                np.array([np.nan if v is None else v for v in b[k]])
                for k in ("exponent", "lo", "hi")
            )
            ok = np.isfinite(e) & np.isfinite(lo) & np.isfinite(hi)
            if not ok.any():
                poss.append(None)
                est.append(None)
                plateaus.append(None)
                continue
            first = pct[ok][0]
            plateau = float(np.median(e[ok & (pct <= first + plateau_width)]))
            thr = (1 - tolerance) * plateau
            after = ok & (
                pct > first + plateau_width
            )  # a drop is looked for past the plateau window
            p_ = pct[after & (lo < thr)]
            e_ = pct[after & (hi < thr)]
            poss.append(float(p_[0]) if p_.size else None)
            est.append(float(e_[0]) if e_.size else None)
            plateaus.append(plateau)
        if not plateaus:
            continue
        b0 = s["seeds"][0]["slit_band"]
        out[name] = {
            "percent_Rt": b0["percent_Rt"],
            "exponent": b0["exponent"],
            "lo": b0["lo"],
            "hi": b0["hi"],
            "plateau": plateaus[0],
            "plateaus": plateaus,
            "possible_drop_percent_Rt": poss,
            "established_drop_percent_Rt": est,
            "paper": list(TABLE2[name][2]),
        }
    return out
