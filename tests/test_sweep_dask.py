# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The Dask engine of sweeps: a local cluster of 2 worker processes, the same table as in
process, a worker killed mid-sweep or after writing its part, workers pinned one device each."""

import json
import os
import signal
import time

import pytest

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

from sweep_helpers import OPTS, case_ids_on_disk, results_only, two_worker_client  # noqa: E402

from warptrunc.sweep import (  # noqa: E402
    SweepExecution,
    SweepGrid,
    load,
    load_curves,
    run_sweep,
)

# --- Dask: a local cluster of 2 worker processes ----------------------------------------------


@pytest.fixture(scope="module")
def client():
    pytest.importorskip("distributed")
    yield from two_worker_client()


DASK_GRID = SweepGrid([2.3, 2.6], [0.01], "0-3")


@pytest.fixture(scope="module")
def dask_reference():
    return run_sweep(DASK_GRID, None, progress=False, device="cpu", options=OPTS)


@pytest.mark.timeout(240)
def test_two_local_workers_same_table_as_in_process(tmp_path, dask_reference):
    pytest.importorskip("distributed")
    # the reference's device on the workers too (on a GPU machine they would pick cuda:0)
    df = run_sweep(
        DASK_GRID,
        tmp_path / "s",
        options=OPTS,
        execution=SweepExecution(workers=2),
        progress=False,
        device="cpu",
    )
    pd.testing.assert_frame_equal(results_only(df), results_only(dask_reference))
    assert df["host"].nunique() == 1 and (df["device"] == "cpu").all()


def _slow_cases_plugin():
    """A worker plugin that delays each case, so that kills land mid-sweep."""
    from distributed import WorkerPlugin

    class SlowCases(WorkerPlugin):
        name = "test-slow-cases"
        idempotent = True

        def setup(self, worker):
            import warptrunc.sweep.engines as e

            if not getattr(e.compute_case, "_slow", False):
                real = e.compute_case

                def slow(*a, **kw):
                    time.sleep(0.4)
                    return real(*a, **kw)

                slow._slow = True
                e.compute_case = slow

    return SlowCases()


def _sweep_in_thread(out, **kw):
    """Start run_sweep in a thread; returns (thread, box, wait_for(k cases in parts))."""
    import threading

    box = {}

    def sweep():
        try:
            box["df"] = run_sweep(
                DASK_GRID,
                out,
                options=OPTS,
                execution=SweepExecution(**kw),
                progress=False,
                device="cpu",
            )
        except BaseException as exc:  # pragma: no cover - reported by the caller
            box["exc"] = exc

    th = threading.Thread(target=sweep)

    def wait_for(k):
        t0 = time.monotonic()
        while len(case_ids_on_disk(out)) < k and th.is_alive():
            assert time.monotonic() - t0 < 200
            time.sleep(0.01)
        return len(case_ids_on_disk(out))

    th.start()
    return th, box, wait_for


@pytest.mark.timeout(300)
def test_worker_killed_and_cluster_restarted_mid_sweep(tmp_path, client, dask_reference):
    client.register_plugin(_slow_cases_plugin())  # a local class: pickled by value
    out = tmp_path / "s"
    th, box, wait_for = _sweep_in_thread(out, scheduler=client)
    done_at_kill = wait_for(1)
    pids = client.run(os.getpid)
    os.kill(next(iter(pids.values())), signal.SIGKILL)  # one worker process dies
    done_at_restart = wait_for(done_at_kill + 2)
    client.restart()  # every worker dies; running cases are cancelled and submitted again
    th.join(240)
    assert not th.is_alive() and "exc" not in box, box.get("exc")
    assert done_at_kill < 8 and done_at_restart < 8, "the kills came after the sweep finished"
    df = box["df"]
    assert not df.duplicated(["case_id", "min_pixels"]).any()
    pd.testing.assert_frame_equal(results_only(df), results_only(dask_reference))
    pd.testing.assert_frame_equal(load(out), df)


@pytest.mark.timeout(300)
def test_sharded_worker_killed_mid_shard_no_loss_no_duplicates(tmp_path, client, dask_reference):
    """Shards of 3 cases: a worker killed mid-shard has its shard run again."""
    client.register_plugin(_slow_cases_plugin())
    out = tmp_path / "s"
    th, box, wait_for = _sweep_in_thread(out, scheduler=client, shard_size=3)
    done_at_kill = wait_for(1)  # the first shard is written: the second and third are running
    pids = client.run(os.getpid)
    os.kill(next(iter(pids.values())), signal.SIGKILL)
    th.join(240)
    assert not th.is_alive() and "exc" not in box, box.get("exc")
    assert 3 <= done_at_kill < 8, "the kill came after the sweep finished"
    df = box["df"]
    assert not df.duplicated(["case_id", "min_pixels"]).any() and df["error"].isna().all()
    pd.testing.assert_frame_equal(results_only(df), results_only(dask_reference))
    pd.testing.assert_frame_equal(load(out), df)
    assert sorted(case_ids_on_disk(out)) == sorted(df.case_id.unique())  # each case in one part
    assert not list((out / "curves").glob(".*"))  # no temporary file left


@pytest.mark.timeout(300)
def test_worker_written_parts(tmp_path, client, dask_reference, monkeypatch):
    """The workers write the parts, the client none; a kill loses and duplicates nothing."""
    import warptrunc.sweep.store as store_mod

    def refuse(*a, **kw):
        raise AssertionError("the client wrote a part")

    monkeypatch.setattr(store_mod, "write_part", refuse)  # this process only, not the workers
    client.register_plugin(_slow_cases_plugin())
    out = tmp_path / "s"
    th, box, wait_for = _sweep_in_thread(out, scheduler=client, shard_size=2)
    done_at_kill = wait_for(1)
    pids = client.run(os.getpid)
    os.kill(next(iter(pids.values())), signal.SIGKILL)
    th.join(240)
    assert not th.is_alive() and "exc" not in box, box.get("exc")
    assert done_at_kill < 8, "the kill came after the sweep finished"
    df = box["df"]
    assert not df.duplicated(["case_id", "min_pixels"]).any()
    pd.testing.assert_frame_equal(results_only(df), results_only(dask_reference))
    pd.testing.assert_frame_equal(load(out), df)
    # the curves on disk are those of the in-process engine, and carry the client's rows
    ref = tmp_path / "ref"
    monkeypatch.undo()
    run_sweep(DASK_GRID, ref, progress=False, device="cpu", options=OPTS)
    pd.testing.assert_frame_equal(load_curves(out), load_curves(ref))
    (out / "cases.parquet").unlink()  # rebuilt from the worker-written parts alone
    pd.testing.assert_frame_equal(load(out), df)


def _die_after_write_plugin(flag):
    """A worker plugin: the first shard written in the cluster kills its worker (SIGKILL) right
    after its part is in place, before the result reaches the client; ``flag`` records the
    part's name and stamps."""
    from distributed import WorkerPlugin

    class DieAfterWrite(WorkerPlugin):
        name = "test-die-after-write"
        idempotent = True

        def setup(self, worker):
            import warptrunc.sweep.engines as e

            if getattr(e.compute_shard, "_dies", False):
                return
            real = e.compute_shard

            def dying(*a, **kw):
                out = real(*a, **kw)
                try:
                    fd = os.open(flag, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
                except FileExistsError:
                    return out
                os.write(
                    fd,
                    json.dumps(
                        {
                            "part": out["part"],
                            "stamps": [rs[0]["finished_utc"] for rs in out["rows"]],
                        }
                    ).encode(),
                )
                os.close(fd)
                os.kill(os.getpid(), signal.SIGKILL)

            dying._dies = True
            e.compute_shard = dying

    return DieAfterWrite()


@pytest.mark.timeout(300)
def test_worker_killed_after_writing_its_part_part_kept(tmp_path, client, dask_reference):
    """The part of a shard whose worker died before reporting is recorded, not recomputed."""
    flag = tmp_path / "died.json"
    client.register_plugin(_die_after_write_plugin(str(flag)))
    try:
        out = tmp_path / "s"
        df = run_sweep(
            DASK_GRID,
            out,
            options=OPTS,
            execution=SweepExecution(scheduler=client, shard_size=3),
            progress=False,
            device="cpu",
        )
    finally:
        client.unregister_worker_plugin("test-die-after-write")
    died = json.loads(flag.read_text())
    assert (out / "curves" / died["part"]).exists()
    assert not df.duplicated(["case_id", "min_pixels"]).any()
    pd.testing.assert_frame_equal(results_only(df), results_only(dask_reference))
    assert set(died["stamps"]) <= set(df["finished_utc"])  # the dead worker's results, kept
    assert sorted(case_ids_on_disk(out)) == sorted(df.case_id.unique())


def test_worker_device_is_a_stable_function_of_its_name():
    """The same name gives the same device in every process, whatever PYTHONHASHSEED is."""
    import subprocess
    import sys
    import zlib

    from warptrunc.sweep.engines import pinned_device

    assert pinned_device("gpu-worker-3", 4) == "cuda:3"  # a trailing index is the index
    assert pinned_device("worker-7", 4) == "cuda:3"
    assert pinned_device(-5, 4) == "cuda:1"
    names = ["alpha", "tcp-worker", "ß-node"]
    expected = [f"cuda:{zlib.crc32(n.encode('utf-8')) % 3}" for n in names]
    code = (
        "from warptrunc.sweep.engines import pinned_device;"
        f"print([pinned_device(n, 3) for n in {names!r}])"
    )
    for seed in ("1", "2", "12345"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        r = subprocess.run(
            [sys.executable, "-c", code],
            env=env,
            capture_output=True,
            text=True,
            timeout=120,
            check=True,
        )
        assert r.stdout.strip() == repr(expected)


@pytest.mark.timeout(120)
def test_workers_pinned_one_device_each(client):
    from warptrunc.sweep.cluster import PinDevice
    from warptrunc.sweep.engines import pinned_device

    assert [pinned_device(i, 2) for i in range(4)] == ["cuda:0", "cuda:1", "cuda:0", "cuda:1"]
    assert pinned_device("3", 4) == "cuda:3" and pinned_device(0, 0) is None
    # the module's cluster may still be bringing back a worker an earlier test killed
    client.wait_for_workers(2, timeout=120)
    client.register_plugin(PinDevice(n_devices=2))  # as on a node with 2 GPUs
    # a worker restarted after an earlier kill may join (and run its plugins) a moment later:
    # ask until both answer (this test failed once in sequence on a 2 × H100 host, its message
    # not captured, and passed in two reruns there; a late restart is the likely cause)
    want, deadline = [(0, "cuda:0"), (1, "cuda:1")], time.monotonic() + 120
    while True:
        got = client.run(lambda dask_worker: (dask_worker.name, os.environ.get("WARPTRUNC_DEVICE")))
        if sorted(got.values()) == want or time.monotonic() > deadline:
            break
        time.sleep(0.5)
    assert sorted(got.values()) == want


def _batches_raise_on_worker_1_plugin():
    """A worker plugin: on worker 1, every shard of more than one case raises (as batched
    shards did on the workers pinned to cuda:1 before WMBatch recorded its events on its own
    device's stream); undone when unregistered."""
    from distributed import WorkerPlugin

    class RaiseOnOne(WorkerPlugin):
        name = "test-raise-on-worker-1"
        idempotent = True

        def setup(self, worker):
            import warptrunc.sweep.engines as e

            self.real = e.compute_many
            if worker.name != 1:
                return
            real = self.real

            def broken(cases, *a, **kw):
                if len(cases) > 1:
                    raise RuntimeError("Event from device cuda:1 cannot be recorded here")
                return real(cases, *a, **kw)

            e.compute_many = broken

        def teardown(self, worker):
            import warptrunc.sweep.engines as e

            e.compute_many = self.real

    return RaiseOnOne()


@pytest.mark.timeout(300)
def test_task_that_raises_is_retried_and_reported_once(tmp_path, client, dask_reference, capsys):
    client.wait_for_workers(2, timeout=120)
    client.register_plugin(_batches_raise_on_worker_1_plugin())
    try:
        df = run_sweep(
            DASK_GRID,
            tmp_path / "s",
            options=OPTS,
            execution=SweepExecution(scheduler=client, shard_size=4),
            progress=False,
            device="cpu",
        )
    finally:
        client.unregister_worker_plugin("test-raise-on-worker-1")
    pd.testing.assert_frame_equal(results_only(df), results_only(dask_reference))
    assert not df.duplicated(["case_id", "min_pixels"]).any()
    err = capsys.readouterr().err
    assert err.count("cannot be recorded here") == 1 and "submitted again" in err
