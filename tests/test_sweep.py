# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Sweeps: grid parsing, the Parquet store (parts, duplicates), resume after SIGINT/SIGTERM/kill
-9, refusal of another grid, failing cases, elastic columns (the Dask engine:
tests/test_sweep_dask.py; stores written by earlier versions: tests/test_sweep_compat.py)."""

import json
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

from sweep_helpers import OPTS, OPTS_CLI, case_ids_on_disk, results_only  # noqa: E402

from warptrunc.sweep import (  # noqa: E402
    CURVE_COLUMNS,
    Store,
    SweepExecution,
    SweepGrid,
    SweepOptions,
    load,
    load_curves,
    parse_seeds,
    run_sweep,
)
from warptrunc.sweep.curves import part_files  # noqa: E402
from warptrunc.wm import wm_surface  # noqa: E402


def test_parse_seeds_and_grid_errors(tmp_path):
    assert parse_seeds("0-4") == (0, 1, 2, 3, 4)
    assert parse_seeds("0-2,9") == (0, 1, 2, 9)
    assert parse_seeds([3, "5"]) == (3, 5)
    assert parse_seeds(7) == (7,)
    for bad, msg in (
        ("4-2", "lo ≤ hi"),
        ("a", "seeds like 0, '0-4'"),
        ("1,1", "seed 1 is given twice"),
        ("", "at least one"),
        ("-3", "seed"),
    ):
        with pytest.raises(ValueError, match=msg):
            parse_seeds(bad)
    with pytest.raises(ValueError, match=r"D\[1\] must be in \(2, 3\).*3.2"):
        SweepGrid([2.5, 3.2], [0.01], "0")
    with pytest.raises(ValueError, match=r"delta\[0\] must be in \(0, inf\)"):
        SweepGrid([2.5], [-0.01], "0")
    with pytest.raises(ValueError, match=r"D values must not repeat"):
        SweepGrid([2.5, 2.5], [0.01])
    assert SweepGrid(2.5, 0.01).seeds == (0,)  # one value each; seed 0 by default
    f = tmp_path / "grid.toml"
    f.write_text('D = [2.1, 2.5]\ndelta = [0.01]\nseeds = "0-2"\n')
    g = SweepGrid.from_toml(f)
    assert g.to_dict() == {"D": [2.1, 2.5], "delta": [0.01], "seeds": [0, 1, 2]} and len(g) == 6
    f.write_text('D = [2.1]\ndelta = [0.01]\nseed = "0-2"\n')
    with pytest.raises(ValueError, match=r"grid.toml.*unknown \['seed'\], missing \['seeds'\]"):
        SweepGrid.from_toml(f)
    with pytest.raises(ValueError, match=r"min_pixels\[0\] must be an integer in \[1, inf\)"):
        SweepOptions(min_pixels=(0,))
    with pytest.raises(ValueError, match=r"min_pixels must not repeat a value, got \(5, 5\)"):
        SweepOptions(min_pixels=(5, 5))


def test_case_ids_identify_values_and_options():
    g = SweepGrid([2.2, 2.5], [1], "0-1")
    ids = [c.case_id for c in g.cases(SweepOptions(n=64))]
    assert len(set(ids)) == 4
    assert ids == [
        c.case_id for c in SweepGrid([2.2, 2.5], [1.0], [0, 1]).cases(SweepOptions(n=64.0))
    ]
    assert not set(ids) & {c.case_id for c in g.cases(SweepOptions(n=128))}
    # the id does not depend on the position in the grid
    sub = SweepGrid([2.5], [1], "1").cases(SweepOptions(n=64))
    assert sub[0].case_id == ids[3]


# ids made by warptrunc at 8d1cbfc (SweepOptions then named E_i, nu_i E_flat, nu_flat) for
# ``warptrunc sweep --D 2.3 2.5 --delta 0.01 --seeds 0-1 --n 128``: a store made then resumes
BASELINE_IDS = ["caa310bdbf5aec0e", "40203015a08abf69", "2015798acdd0a980", "e5424a6e09f839d1"]


def test_case_ids_are_those_of_the_stores_made_before():
    import hashlib

    from warptrunc.sweep.grid import stored_options

    grid = SweepGrid([2.3, 2.5], [0.01], "0-1")
    assert [c.case_id for c in grid.cases(SweepOptions(n=128))] == BASELINE_IDS
    # the id hashes the store's spelling, written out here by hand
    o = SweepOptions(n=128, E_i=1141e9, nu_i=0.07)
    stored = {
        "Wr": 1e-4,
        "L": 1e-3,
        "n": 128,
        "M": 10,
        "gamma": 1.5,
        "Wc": None,
        "cutoff": "nyquist",
        "increments": 200,
        "max_depth_fraction": 0.1,
        "max_depth": None,
        "E": 70e9,
        "nu": 0.33,
        "E_flat": 1141e9,
        "nu_flat": 0.07,
        "beta_prime": 1.0,
        "min_pixels": [10],
        "depth_window": None,
    }
    assert stored_options(o) == stored
    key = {"format": "warptrunc-sweep/1", "D": 2.3, "delta": 0.01, "seed": 1, "options": stored}
    blob = json.dumps(key, sort_keys=True, separators=(",", ":")).encode()
    want = hashlib.sha256(blob).hexdigest()[:16]
    assert SweepGrid(2.3, 0.01, 1).cases(o)[0].case_id == want


def test_store_rows_and_curves_match_numpy(tmp_path):
    grid = SweepGrid([2.3, 2.7], [0.01, 0.02], "0-1")
    df = run_sweep(grid, tmp_path / "s", progress=False, device="cpu", options=OPTS)
    assert len(df) == 8 * 2 and df["error"].isna().all()
    assert sorted((tmp_path / "s").iterdir()) == [
        tmp_path / "s" / n for n in ("cases.parquet", "curves", "sweep.json")
    ]
    spec = json.loads((tmp_path / "s" / "sweep.json").read_text())
    assert spec["grid"]["seeds"] == [0, 1] and spec["options"]["n"] == 64
    pd.testing.assert_frame_equal(load(tmp_path / "s"), df)
    row = df[(df.D_in == 2.7) & (df.delta == 0.02) & (df.seed == 1) & (df.min_pixels == 20)]
    assert len(row) == 1
    row = row.iloc[0]
    assert row.Rt_m == pytest.approx(0.02 * 100e-6) and row.nx == 64 and row.Lx_m == 1e-3
    curve = load_curves(tmp_path / "s", row.case_id)
    assert list(curve.columns) == ["case_id", *CURVE_COLUMNS] and len(curve) == 61
    # counts against NumPy on the same surface
    z = wm_surface(2.7, 100e-6, n=64, Rt=0.02 * 100e-6, seed=1, device="cpu").heights
    thr = (np.float64(z.max()) - curve["depth_m"].to_numpy()).astype(np.float32)
    np.testing.assert_array_equal(
        curve["n_contact_pixels"], [np.count_nonzero(z >= t) for t in thr]
    )
    assert row.final_contact_pixels == np.count_nonzero(z >= thr[-1])
    # the fit re-done from the stored curve with NumPy
    sel = (curve["load_N"] > 0) & (curve["n_contact_pixels"] >= 20)
    a, logb = np.polyfit(np.log(curve["F_over_EA"][sel]), np.log(curve["Ec_over_E"][sel]), 1)
    assert row.alpha == pytest.approx(a, rel=1e-12) and row.beta == pytest.approx(np.exp(logb))
    assert row.n_points == sel.sum()
    assert len(load_curves(tmp_path / "s")) == 8 * 61
    # the parts are a Parquet dataset that pandas and pyarrow read directly
    import pyarrow.dataset as ds

    direct = pd.read_parquet(tmp_path / "s" / "curves")
    pd.testing.assert_frame_equal(
        direct.sort_values(["case_id", "depth_m"]).reset_index(drop=True),
        load_curves(tmp_path / "s").sort_values(["case_id", "depth_m"]).reset_index(drop=True),
        check_dtype=False,
    )
    assert ds.dataset(tmp_path / "s" / "curves").count_rows() == 8 * 61
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "s" / "cases.parquet"), df)


def test_fractal_methods_and_relative_fit_range(tmp_path):
    from warptrunc.fractal import fractal_dimensions

    grid = SweepGrid([2.3, 2.7], [0.01], "0-1")
    opts = OPTS.replace(
        min_pixels=(20,),
        min_pixels_fraction=(0.05, 0.5),
        fractal_methods=("tri", "box", "vs", "sp"),
    )
    df = run_sweep(grid, tmp_path / "s", options=opts, progress=False, device="cpu")
    assert len(df) == 4 * 3 and df["error"].isna().all() and df["alpha"].notna().all()
    # every range fits; a fit_error here only says "not worth reading" (α kept beside it)
    assert df["fit_error"].dropna().str.startswith("not worth reading").all()
    pd.testing.assert_frame_equal(load(tmp_path / "s"), df)
    for (D, seed), part in df.groupby(["D_in", "seed"]):
        # D columns: fractal_dimensions (default options) on the same surface, regenerated
        s = wm_surface(D, 100e-6, n=64, Rt=0.01 * 100e-6, seed=int(seed), device="cpu")
        ref = fractal_dimensions(s, device="cpu")
        info = json.loads(part["fractal_options"].iloc[0])
        for m, f in ref.items():
            assert (part[f"D_{m}"] == f.D).all() and (part[f"D_{m}_r2"] == f.r2).all()
            assert info[m]["options"] == json.loads(json.dumps(f.options))
            assert (info[m]["fit_min_m"], info[m]["fit_max_m"]) == tuple(f.fit_range)
        assert (part["fractal_seconds"] > 0).all()
        # relative fit ranges: min_pixels = max(10, ⌈f·final pixels⌉), fit redone with NumPy
        curve = load_curves(tmp_path / "s", part["case_id"].iloc[0])
        final = int(curve["n_contact_pixels"].iloc[-1])
        assert part["min_pixels_fraction"].isna().tolist() == [True, False, False]
        for _, row in part.iterrows():
            f = row.min_pixels_fraction
            mp = 20 if np.isnan(f) else max(10, -(-final * round(f * 100) // 100))
            assert row.min_pixels == mp
            sel = (curve["load_N"] > 0) & (curve["n_contact_pixels"] >= mp)
            a, _ = np.polyfit(np.log(curve["F_over_EA"][sel]), np.log(curve["Ec_over_E"][sel]), 1)
            assert row.alpha == pytest.approx(a, rel=1e-12) and row.n_points == sel.sum()
    # off by default and then not part of the case identity (older stores stay valid);
    # part of it when on
    from warptrunc.sweep.grid import stored_options

    assert OPTS.fractal_methods is None and "fractal_methods" not in stored_options(OPTS)
    plain = {c.case_id for c in grid.cases(OPTS)}
    assert plain.isdisjoint(df["case_id"])
    assert plain.isdisjoint(c.case_id for c in grid.cases(OPTS.replace(fractal_methods="vs")))
    with pytest.raises(ValueError, match=r"fractal_methods\[1\] must be one of .*'dim'"):
        SweepOptions(fractal_methods=("tri", "dim"))
    with pytest.raises(ValueError, match=r"min_pixels_fraction\[0\] must be in \(0, 1\]"):
        SweepOptions(min_pixels_fraction=(1.5,))


def _one_case(increments: int) -> list[str]:
    """``warptrunc sweep`` options of one 64² case (D = 2.5, δ = 0.01) with ``increments``, on
    the CPU without progress bars."""
    return [
        "--D",
        "2.5",
        "--delta",
        "0.01",
        "--n",
        "64",
        "--increments",
        str(increments),
        "--device",
        "cpu",
        "--no-progress",
    ]


def test_cli_fractal_and_fraction_options(tmp_path, capsys):
    from warptrunc.cli import main

    out = tmp_path / "run"
    rc = main(
        [
            "sweep",
            *_one_case(30),
            "--fractal",
            "vs",
            "sp",
            "--min-pixels-fraction",
            "0.1",
            "--bem-fractions",
            "0.1",
            "--out",
            str(out),
        ]
    )
    assert rc == 0 and "fraction=0.1: α" in capsys.readouterr().out
    df = load(out)
    assert df["D_vs"].notna().all() and df["D_tri"].isna().all() and len(df) == 2
    assert df["k_ratio_0.1"].notna().all() and df["bem_converged_0.1"].notna().all()
    spec = json.loads((out / "sweep.json").read_text())["options"]
    assert spec["fractal_methods"] == ["vs", "sp"] and spec["min_pixels_fraction"] == [0.1]
    assert spec["bem_fractions"] == [0.1]


def test_rerun_skips_other_grid_refused_overwrite(tmp_path):
    out = tmp_path / "s"
    grid = SweepGrid([2.3], [0.01], "0-2")
    first = run_sweep(grid, out, progress=False, device="cpu", options=OPTS)
    again = run_sweep(grid, out, progress=False, device="cpu", options=OPTS)
    pd.testing.assert_frame_equal(first, again)  # nothing recomputed: same times and stamps
    with pytest.raises(
        ValueError,
        match=r"another grid or options \(grid.seeds: \[0, 1, 2\] → "
        r"\[0, 1, 2, 3\]\); use --overwrite",
    ):
        run_sweep(SweepGrid([2.3], [0.01], "0-3"), out, progress=False, options=OPTS)
    with pytest.raises(ValueError, match=r"options.increments: 60 → 61"):
        run_sweep(grid, out, progress=False, options=OPTS.replace(increments=61))
    assert load(out)["case_id"].nunique() == 3  # the refused runs changed nothing
    new = run_sweep(
        SweepGrid([2.3], [0.01], "0-3"),
        out,
        overwrite=True,
        progress=False,
        device="cpu",
        options=OPTS,
    )
    assert new["case_id"].nunique() == 4 and sorted(case_ids_on_disk(out)) == sorted(
        new["case_id"].unique()
    )


def test_rows_recovered_from_curves_after_hard_kill(tmp_path):
    """A process killed between a curve write and the next cases.parquet flush loses nothing."""
    out = tmp_path / "s"
    grid = SweepGrid([2.3, 2.6], [0.01], "0-1")
    full = run_sweep(grid, out, progress=False, device="cpu", options=OPTS)
    (out / "cases.parquet").unlink()
    (out / "curves" / ".part-x.parquet.tmp-123").write_bytes(b"PAR1 trunc")  # a half-written part
    assert len(pd.read_parquet(out / "curves")) == 4 * 61  # the dot-named temporary is skipped
    pd.testing.assert_frame_equal(load(out), full)
    resumed = run_sweep(grid, out, progress=False, device="cpu", options=OPTS)
    pd.testing.assert_frame_equal(resumed, full)  # same stamps: nothing was recomputed
    assert not list((out / "curves").glob(".*tmp*"))


def test_failing_case_recorded_and_retried(tmp_path, monkeypatch):
    import warptrunc.sweep.engines as engines

    real = engines.wm_surface

    def flaky(spec, *a, **kw):  # the engine passes the case's WMSpec
        if spec.seed == 1:
            raise RuntimeError("injected failure")
        return real(spec, *a, **kw)

    monkeypatch.setattr(engines, "wm_surface", flaky)
    out = tmp_path / "s"
    grid = SweepGrid([2.3, 2.6], [0.01], "0-2")
    df = run_sweep(grid, out, progress=False, device="cpu", options=OPTS)
    bad = df[df["seed"] == 1]
    assert len(bad) == 4 and (bad["error"] == "RuntimeError: injected failure").all()
    assert bad["alpha"].isna().all() and bad["final_contact_pixels"].isna().all()
    good = df[df["seed"] != 1]
    assert len(good) == 8 and good["error"].isna().all() and good["alpha"].notna().all()
    assert len(load_curves(out)) == 4 * 61  # failed cases have empty curves
    monkeypatch.setattr(engines, "wm_surface", real)
    assert (
        run_sweep(grid, out, progress=False, device="cpu", options=OPTS)["error"].notna().sum() == 4
    )
    fixed = run_sweep(grid, out, retry_failed=True, progress=False, device="cpu", options=OPTS)
    assert fixed["error"].isna().all()
    assert sorted(case_ids_on_disk(out)) == sorted(
        fixed.case_id.unique()
    )  # failed cases left their parts
    pd.testing.assert_frame_equal(pd.read_parquet(out / "cases.parquet"), fixed)
    pd.testing.assert_frame_equal(load(out), fixed)
    pd.testing.assert_frame_equal(results_only(fixed[fixed.seed != 1]), results_only(good))


# --- parts: half-written, retried concurrently, overlapping; the previous layout -----------------


_KILL_MID_WRITE = """
import os, sys, time
import warptrunc.sweep.curves as c
from warptrunc.sweep import SweepGrid, SweepOptions
from warptrunc.sweep.engines import compute_shard
real = os.fsync
def stall(fd):  # the part's bytes are in the temporary file: the worker dies here
    print("writing", flush=True)
    time.sleep(60)
c.os.fsync = stall
o = SweepOptions(n=64, increments=60, max_depth_fraction=0.3, min_pixels=(1, 20))
cases = SweepGrid([2.3, 2.6], [0.01], "0-1").cases(o)
compute_shard(cases, o, "cpu", sys.argv[1])
"""


@pytest.mark.timeout(240)
def test_worker_killed_while_writing_leaves_no_readable_part(tmp_path):
    out = tmp_path / "s"
    grid = SweepGrid([2.3, 2.6], [0.01], "0-1")
    run_sweep(grid, out, progress=False, device="cpu", options=OPTS)  # the store exists
    ref = load(out)
    for f in part_files(out / "curves"):
        f.unlink()
    (out / "cases.parquet").unlink()
    p = subprocess.Popen(
        [sys.executable, "-c", _KILL_MID_WRITE, str(out / "curves")],
        stdout=subprocess.PIPE,
        text=True,
    )
    assert p.stdout.readline().strip() == "writing"
    p.kill()  # kill -9 mid-write
    p.communicate(timeout=30)
    left = list((out / "curves").iterdir())
    assert len(left) == 1 and left[0].name.startswith(".part-") and ".tmp-" in left[0].name
    assert left[0].stat().st_size > 0 and not part_files(out / "curves")
    # readers skip it, and so does resuming (which removes it and computes the four cases)
    assert len(pd.read_parquet(out / "curves")) == 0 and len(load(out)) == 0
    df = run_sweep(grid, out, progress=False, device="cpu", options=OPTS)
    pd.testing.assert_frame_equal(results_only(df), results_only(ref))
    assert not list((out / "curves").glob(".*")) and len(case_ids_on_disk(out)) == 4


def test_shard_retried_concurrently_written_once(tmp_path):
    """Four attempts of one shard at once (as a retried task whose first attempt still runs):
    one part, each case once, and every attempt reports that part's rows."""
    import threading

    from warptrunc.sweep.engines import compute_shard

    out = tmp_path / "s"
    grid = SweepGrid([2.3, 2.6], [0.01], "0-2")
    run_sweep(SweepGrid(2.3, 0.01), options=OPTS, progress=False, device="cpu")  # kernels loaded
    opts = OPTS
    cases = grid.cases(opts)
    Store(out, grid, opts)  # an empty store: sweep.json and curves/
    barrier, got = threading.Barrier(4), []

    def attempt():
        barrier.wait()
        got.append(compute_shard(cases, opts, "cpu", str(out / "curves")))

    ths = [threading.Thread(target=attempt) for _ in range(4)]
    for t in ths:
        t.start()
    for t in ths:
        t.join(120)
    assert len(got) == 4 and len({g["part"] for g in got}) == 1
    same = {json.dumps(g["rows"], sort_keys=True) for g in got}
    assert len(same) == 1  # the winner's rows (stamps included) in every answer
    assert len(part_files(out / "curves")) == 1 and not list((out / "curves").glob(".*"))
    assert sorted(case_ids_on_disk(out)) == sorted(c.case_id for c in cases)
    # the store takes the part as it is: nothing recomputed
    df = run_sweep(grid, out, progress=False, device="cpu", options=OPTS)
    assert sorted(df.finished_utc.unique()) == sorted(
        {rs[0]["finished_utc"] for rs in got[0]["rows"]}
    )


def test_overlapping_parts_each_case_once(tmp_path):
    """Two shards that overlap (a lost shard run again in another split) each write a part:
    readers see each case once, and opening the store rewrites the later part without them."""
    from warptrunc.sweep.engines import compute_shard

    out = tmp_path / "s"
    grid = SweepGrid([2.3, 2.6], [0.01], "0-2")
    ref = run_sweep(
        grid,
        out,
        options=OPTS,
        execution=SweepExecution(shard_seconds=0),
        progress=False,
        device="cpu",
    )
    for f in part_files(out / "curves"):
        f.unlink()
    (out / "cases.parquet").unlink()
    opts = OPTS
    cases = grid.cases(opts)
    a = compute_shard(cases[:4], opts, "cpu", str(out / "curves"))
    b = compute_shard(cases[2:], opts, "cpu", str(out / "curves"))
    assert a["part"] < b["part"] and len(case_ids_on_disk(out)) == 8  # cases 2 and 3 twice
    df = load(out)
    assert not df.duplicated(["case_id", "min_pixels"]).any() and len(df) == len(ref)
    assert len(load_curves(out)) == 6 * 61
    again = run_sweep(grid, out, progress=False, device="cpu", options=OPTS)  # nothing recomputed
    pd.testing.assert_frame_equal(results_only(again), results_only(ref))
    assert sorted(case_ids_on_disk(out)) == sorted(ref.case_id.unique())  # the overlap was dropped
    assert len(pd.read_parquet(out / "curves")) == 6 * 61
    first = {rs[0]["case_id"]: rs[0]["finished_utc"] for rs in a["rows"]}
    kept = again.drop_duplicates("case_id").set_index("case_id")["finished_utc"]
    assert all(kept[c] == t for c, t in first.items())  # the first part's cases were kept


def test_elastic_columns_match_the_contact_solver(tmp_path):
    from warptrunc.contact import CurveSettings, SolverSettings, solve_contact
    from warptrunc.stiffness import Material

    grid = SweepGrid([2.3, 2.7], [0.01], "0")
    df = run_sweep(
        grid,
        tmp_path / "s",
        options=OPTS.replace(bem_fractions=(0.2, 0.05)),
        progress=False,
        device="cpu",
    )
    assert df["error"].isna().all() and df["bem_error"].isna().all()
    pd.testing.assert_frame_equal(load(tmp_path / "s"), df)
    assert json.loads((tmp_path / "s" / "sweep.json").read_text())["options"]["bem_fractions"] == [
        0.05,
        0.2,
    ]
    cols = [c for c in df.columns if c.endswith("_0.05")]
    assert cols == [
        "bem_depth_m_0.05",
        "F_bem_N_0.05",
        "A_bem_m2_0.05",
        "k_bem_N_per_m_0.05",
        "F_trunc_N_0.05",
        "A_trunc_m2_0.05",
        "k_trunc_N_per_m_0.05",
        "F_ratio_0.05",
        "A_ratio_0.05",
        "k_ratio_0.05",
        "bem_converged_0.05",
        "bem_iterations_0.05",
    ]
    assert str(df["bem_converged_0.2"].dtype) == "boolean"
    assert str(df["bem_iterations_0.2"].dtype) == "Int64"
    contact_modulus = Material().contact_modulus
    for _, row in df.drop_duplicates("case_id").iterrows():
        s = wm_surface(row.D_in, 100e-6, n=64, Rt=0.01 * 100e-6, seed=int(row.seed), device="cpu")
        d = np.array([0.05, 0.2]) * row.Rt_measured_m
        cc = solve_contact(
            s,
            depths=d,
            material=Material(),
            settings=SolverSettings(substrate="free"),
            curve=CurveSettings(stiffness="barber"),
            device="cpu",
        )
        z = s.heights
        for i, f in enumerate(("0.05", "0.2")):
            assert row[f"bem_depth_m_{f}"] == d[i]
            # same solver, same inputs: equal up to the order of float sums (rtol 1e-9)
            np.testing.assert_allclose(row[f"F_bem_N_{f}"], cc.load[i], rtol=1e-9)
            np.testing.assert_allclose(row[f"k_bem_N_per_m_{f}"], cc.stiffness[i], rtol=1e-9)
            assert row[f"A_bem_m2_{f}"] == cc.area[i]
            assert row[f"bem_converged_{f}"] == bool(cc.converged[i])
            n = np.count_nonzero(z >= np.float32(np.float32(z.max()) - d[i]))
            assert row[f"A_trunc_m2_{f}"] == n * s.pixel_area
            np.testing.assert_allclose(
                row[f"k_trunc_N_per_m_{f}"],
                2 / np.sqrt(np.pi) * contact_modulus * np.sqrt(n * s.pixel_area),
                rtol=1e-12,
            )
            for q in ("F", "A", "k"):
                assert row[f"{q}_ratio_{f}"] == pytest.approx(
                    row[f"{q}_bem_{'N' if q == 'F' else 'm2' if q == 'A' else 'N_per_m'}_{f}"]
                    / row[f"{q}_trunc_{'N' if q == 'F' else 'm2' if q == 'A' else 'N_per_m'}_{f}"],
                    rel=1e-12,
                )
        assert row["F_trunc_N_0.05"] > 0 and row["F_bem_N_0.2"] > row["F_bem_N_0.05"] > 0
    from warptrunc.sweep import bem_long

    long = bem_long(df)
    assert len(long) == 2 * len(df) and sorted(long.bem_fraction.unique()) == [0.05, 0.2]
    assert (
        long.set_index(["case_id", "min_pixels", "bem_fraction"]).loc[
            (df.case_id[0], 1, 0.2), "k_ratio"
        ]
        == df["k_ratio_0.2"][0]
    )


def test_unconverged_solve_flagged_not_dropped(tmp_path, monkeypatch):
    import warptrunc.contact.curve as contact

    real = contact.solve_contact
    from warptrunc.contact import SolverSettings

    one = SolverSettings(maxiter=1)
    monkeypatch.setattr(contact, "solve_contact", lambda *a, **kw: real(*a, **kw, settings=one))
    df = run_sweep(
        SweepGrid([2.5], [0.01], "0"),
        tmp_path / "s",
        progress=False,
        device="cpu",
        options=OPTS.replace(bem_fractions=(0.1,)),
    )
    assert len(df) == 2 and df["error"].isna().all()
    assert (~df["bem_converged_0.1"]).all() and df["F_bem_N_0.1"].notna().all()


# --- the CLI killed by a signal, then resumed ---------------------------------------------------

KILL_ARGS = [
    "--D",
    "2.2",
    "2.5",
    "2.8",
    "--delta",
    "0.01",
    "0.02",
    "--seeds",
    "0-2",
    "--n",
    "128",
    *OPTS_CLI,
]


def _cli(out, *extra):
    return [sys.executable, "-m", "warptrunc", "sweep", *KILL_ARGS, "--out", str(out), *extra]


@pytest.fixture(scope="module")
def reference():
    """The uninterrupted sweep of KILL_ARGS, in process."""
    grid = SweepGrid([2.2, 2.5, 2.8], [0.01, 0.02], "0-2")
    opts = SweepOptions(n=128, increments=60, max_depth_fraction=0.3, min_pixels=(1, 20))
    return run_sweep(grid, options=opts, progress=False, device="cpu")


@pytest.mark.timeout(300)
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_cli_killed_then_resumed_equals_uninterrupted(tmp_path, reference, sig):
    out = tmp_path / "run"
    # the child's SIGINT as in a terminal: a shell's background job (`bash .ci/run &`) ignores
    # SIGINT, and a Python started with it ignored never raises KeyboardInterrupt; the child
    # sets Python's handler itself (no preexec_fn: a fork with JAX loaded here warns)
    cmd = _cli(out, "--shard-seconds", "0")
    cmd[1:3] = [
        "-c",
        "import runpy, signal, sys; signal.signal(signal.SIGINT, "
        "signal.default_int_handler); sys.argv[0] = 'warptrunc'; "
        "runpy.run_module('warptrunc', run_name='__main__', alter_sys=True)",
    ]
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    t0 = time.monotonic()
    while len(case_ids_on_disk(out)) < 2:
        assert p.poll() is None, p.communicate()
        assert time.monotonic() - t0 < 240, "the sweep did not start"
        time.sleep(0.01)
    p.send_signal(sig)
    _, stderr = p.communicate(timeout=60)
    assert p.returncode == (130 if sig == signal.SIGINT else 143), stderr
    assert "run the same command again" in stderr
    partial = load(out)
    n_done = partial["case_id"].nunique()
    assert 2 <= n_done < 18, "the signal came after the sweep had finished"
    assert not list(out.rglob(".*tmp*"))
    r = subprocess.run(_cli(out), capture_output=True, text=True, timeout=240)
    assert r.returncode == 0, r.stderr
    assert "18 cases (0 failed)" in r.stdout
    final = load(out)
    assert len(final) == 36 and not final.duplicated(["case_id", "min_pixels"]).any()
    pd.testing.assert_frame_equal(results_only(final), results_only(reference))
    # the cases finished before the signal were not recomputed
    kept = final[final.case_id.isin(partial.case_id)]
    np.testing.assert_array_equal(kept["finished_utc"], partial["finished_utc"])
    assert sorted(case_ids_on_disk(out)) == sorted(final.case_id.unique())  # each case in one part


def test_cli_refuses_other_grid(tmp_path):
    out = tmp_path / "run"
    args = [
        *_one_case(20),
        "--out",
        str(out),
    ]
    r = subprocess.run(
        [sys.executable, "-m", "warptrunc", "sweep", *args],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 0, r.stderr
    r = subprocess.run(
        [sys.executable, "-m", "warptrunc", "sweep", *args, "--seeds", "0-1"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 2
    assert (
        r.stderr.strip()
        .splitlines()[-1]
        .startswith("warptrunc sweep: error: " + str(out) + " holds a sweep with another grid")
    )
    assert "--overwrite" in r.stderr and load(out)["case_id"].nunique() == 1


def test_parametric_sweep_example_and_refit_from_curves(tmp_path):
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "examples" / "parametric_sweep.py"
    spec = importlib.util.spec_from_file_location("parametric_sweep", path)
    ex = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ex)
    out = tmp_path / "g2"
    args = [
        "--device",
        "cpu",
        "--n",
        "64",
        "--seeds",
        "2",
        "--D",
        "2.3",
        "2.7",
        "--min-pixels",
        "1",
        "10",
        "--out",
        str(out),
    ]
    assert ex.main(args) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["fit_ranges"]) == {"1", "10"}
    assert (out / "alpha_vs_D.png").read_bytes()[:4] == b"\x89PNG"
    assert ex.main(args) == 0  # resumed: nothing recomputed, same summary
    assert json.loads((out / "summary.json").read_text()) == summary
    refit = ex.refit(out, [10])  # NumPy fit of the stored curves = the sweep's fit
    stored = load(out).query("min_pixels == 10").set_index("case_id")["alpha"]
    np.testing.assert_allclose(
        refit.set_index("case_id")["alpha"][stored.index], stored, rtol=1e-12
    )


def test_missing_extra_is_named(monkeypatch):
    # that importing the sweep loads no pandas/pyarrow/dask: tests/test_import_weight.py
    monkeypatch.setitem(sys.modules, "pyarrow", None)  # as if pyarrow were not installed
    with pytest.raises(ImportError, match=r"pyarrow is missing.*pip install pandas pyarrow"):
        run_sweep(SweepGrid([2.5], [0.01], "0"), options=SweepOptions(n=64), progress=False)
