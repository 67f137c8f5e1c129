# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Several surfaces per launch (warptrunc.sweep.batch): the batched heights against the
float64 direct WM sum, the batched counts against numpy on those heights, and the batched
sweep results against one case at a time."""

from __future__ import annotations

import numpy as np
import pytest

from warptrunc._support.device import resolve_device
from warptrunc.sweep import SweepGrid, SweepOptions, load, run_sweep
from warptrunc.sweep.batch import MAX_BATCH, WMBatch, batch_size
from warptrunc.sweep.engines import batched_results, compute_case, compute_many
from warptrunc.sweep.grid import Case
from warptrunc.wm import wm_surface

OPTS = SweepOptions(n=128, increments=60, min_pixels=(5,), min_pixels_fraction=(0.01,))
GRID = SweepGrid([2.2, 2.7], [0.01, 0.03], [0, 1, 2])


def test_batched_heights_match_the_direct_float64_sum_and_counts_match_numpy(device):
    dev = resolve_device(device)
    cases = GRID.cases(OPTS)[:3]
    wb = WMBatch(OPTS, 4, dev)
    curves = wb.truncate(cases)
    for i, c in enumerate(cases):
        z = wb.heights(i)
        ref = wm_surface(
            c.D,
            OPTS.Wr,
            L=OPTS.L,
            n=OPTS.n,
            Rt=c.delta * OPTS.Wr,
            seed=c.seed,
            method="direct",
            device="cpu",
        ).heights
        rt = c.delta * OPTS.Wr
        assert np.ptp(z) == pytest.approx(rt, rel=1e-5)
        assert np.max(np.abs(z - ref)) < 1e-5 * rt  # float32 tables and sums
        tc = curves[i]
        want = [np.count_nonzero(z >= t) for t in tc.threshold]
        np.testing.assert_array_equal(tc.n_contact_pixels, want)
        assert tc.z_top == float(z.max())
        assert tc.Rt == pytest.approx(float(np.float64(z.max()) - np.float64(z.min())), abs=0)
        assert tc.contact_area[-1] == pytest.approx(want[-1] * tc.pixel_area)


def test_batched_results_equal_one_case_at_a_time(device):
    dev = resolve_device(device)
    cases = GRID.cases(OPTS)
    a = [r for rs in batched_results(cases, OPTS, dev, 5) for r in rs]  # 3 batches: 5, 5, 2
    b = [compute_case(c, OPTS, device) for c in cases]
    assert len(a) == len(b) == 12
    for (ra, ca), (rb, cb) in zip(a, b, strict=True):
        assert ca is not None and cb is not None
        np.testing.assert_array_equal(ca["n_contact_pixels"], cb["n_contact_pixels"])
        np.testing.assert_allclose(ca["depth_m"], cb["depth_m"], rtol=1e-6)
        for x, y in zip(ra, rb, strict=True):
            assert x["case_id"] == y["case_id"] and x["min_pixels"] == y["min_pixels"]
            assert x["error"] is None and x["fit_error"] == y["fit_error"]
            assert x["final_contact_pixels"] == y["final_contact_pixels"]
            np.testing.assert_allclose(x["alpha"], y["alpha"], rtol=1e-9)
            np.testing.assert_allclose(x["Rt_measured_m"], y["Rt_measured_m"], rtol=1e-6)


def test_a_bad_case_in_a_batch_is_computed_alone_and_records_its_error():
    dev = resolve_device("cpu")
    good = GRID.cases(OPTS)[:2]
    bad = Case(index=99, D=3.5, delta=0.01, seed=0, case_id="bad")
    out = [r for rs in batched_results([good[0], bad, good[1]], OPTS, dev, 3) for r in rs]
    assert [rows[0]["case_id"] for rows, _ in out] == [good[0].case_id, "bad", good[1].case_id]
    assert out[1][1] is None and "D" in out[1][0][0]["error"]
    assert out[0][0][0]["error"] is None and out[2][0][0]["error"] is None


def test_slots_are_reused_and_a_full_batch_set_is_refused():
    dev = resolve_device("cpu")
    cases = GRID.cases(OPTS)
    wb = WMBatch(OPTS, 2, dev, slots=2)
    s1, s2 = wb.submit(cases[:2]), wb.submit(cases[2:4])
    with pytest.raises(RuntimeError, match="every slot"):
        wb.submit(cases[4:6])
    wb.scale(s1)
    first = wb.collect(s1)
    s3 = wb.submit(cases[4:6])  # the slot of s1 is free again
    wb.scale(s2)
    wb.scale(s3)
    with pytest.raises(RuntimeError, match="every slot"):  # both slots busy until collected
        wb.truncate(cases[:2])
    assert [c.n_contact_pixels[-1] for c in wb.collect(s2)] == [
        c.n_contact_pixels[-1] for c in WMBatch(OPTS, 2, dev).truncate(cases[2:4])
    ]
    wb.collect(s3)
    assert len(first) == 2
    with pytest.raises(ValueError, match="1 to 2 cases"):
        wb.submit(cases[:3])


def test_batch_size_rules():
    cpu = resolve_device("cpu")
    assert batch_size(OPTS, cpu) == 1  # the CPU gains nothing: one case at a time
    assert batch_size(OPTS, cpu, force=True) == MAX_BATCH
    assert batch_size(SweepOptions(n=2048), cpu, force=True) == 32  # 2²⁷ pixels per batch
    assert batch_size(SweepOptions(n=200), cpu, force=True) == 1  # not a multiple of 128
    assert batch_size(SweepOptions(n=(256, 128)), cpu, force=True) == MAX_BATCH
    assert batch_size(SweepOptions(n=128, bem_fractions=(0.1,)), cpu, force=True) == 1
    assert batch_size(SweepOptions(n=128, fractal_methods=("box",)), cpu, force=True) == 1
    assert batch_size(SweepOptions(n=128, increments=300), cpu, force=True) == 1


def test_run_sweep_in_process_with_batches_equals_one_at_a_time(tmp_path, monkeypatch):
    """The pipelined engine (device thread work, fitting, writer) through run_sweep, batches
    forced on the CPU, against the same grid one case at a time."""
    import warptrunc.sweep.batch as B
    import warptrunc.sweep.engines as E

    one = run_sweep(GRID, tmp_path / "one", options=OPTS, progress=False, device="cpu")
    monkeypatch.setattr(
        E, "batch_size", lambda o, d, force=False: B.batch_size(o, d, force=True) and 5
    )
    many = run_sweep(GRID, tmp_path / "many", options=OPTS, progress=False, device="cpu")
    assert len(many) == len(one) == 24
    key = ["case_id", "min_pixels", "min_pixels_fraction"]
    a = load(tmp_path / "many").sort_values(key).reset_index(drop=True)
    b = load(tmp_path / "one").sort_values(key).reset_index(drop=True)
    assert list(a["case_id"]) == list(b["case_id"])
    np.testing.assert_array_equal(a["final_contact_pixels"], b["final_contact_pixels"])
    np.testing.assert_allclose(a["alpha"], b["alpha"], rtol=1e-9)
    assert a["error"].isna().all()


def test_compute_many_batches_only_when_asked_on_the_cpu():
    cases = GRID.cases(OPTS)[:3]
    forced = compute_many(cases, OPTS, "cpu", batch=True)
    plain = compute_many(cases, OPTS, "cpu", batch=False)
    for (ra, ca), (rb, cb) in zip(forced, plain, strict=True):
        np.testing.assert_array_equal(ca["n_contact_pixels"], cb["n_contact_pixels"])
        assert ra[0]["case_id"] == rb[0]["case_id"]


def test_batches_that_do_not_fit_fall_back_to_one_case_at_a_time(monkeypatch):
    import warptrunc.sweep.batch as B

    def full(nbytes, device, what):
        raise MemoryError(f"{what} needs {nbytes} bytes")

    monkeypatch.setattr(B, "check_memory", full)
    dev = resolve_device("cpu")
    with pytest.raises(MemoryError, match="batch"):
        WMBatch(OPTS, 3, dev, slots=2)
    cases = GRID.cases(OPTS)[:3]
    out = [r for rs in batched_results(cases, OPTS, dev, 3) for r in rs]
    want = [compute_case(c, OPTS, "cpu") for c in cases]
    for (ra, ca), (rb, cb) in zip(out, want, strict=True):
        np.testing.assert_array_equal(ca["n_contact_pixels"], cb["n_contact_pixels"])
        np.testing.assert_allclose(ra[0]["alpha"], rb[0]["alpha"], rtol=1e-9)


@pytest.mark.gpu
def test_batches_on_a_second_gpu_while_the_default_is_the_first():
    """A Dask worker pinned to cuda:1 keeps cuda:0 as Warp's default device: its batches
    (events, copies, launches) must stay on cuda:1 and equal one case at a time there."""
    import warp as wp

    resolve_device(None)
    if wp.get_cuda_device_count() < 2:
        pytest.skip("needs two CUDA devices")
    cases = GRID.cases(OPTS)[:5]
    with wp.ScopedDevice("cuda:0"):
        a = compute_many(cases, OPTS, "cuda:1")  # batched: 5 surfaces in one launch
    b = [compute_case(c, OPTS, "cuda:1") for c in cases]
    for (ra, ca), (rb, cb) in zip(a, b, strict=True):
        assert ra[0]["device"] == "cuda:1" and ra[0]["error"] is None
        np.testing.assert_array_equal(ca["n_contact_pixels"], cb["n_contact_pixels"])
        np.testing.assert_allclose(ra[0]["alpha"], rb[0]["alpha"], rtol=1e-9)
