# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Opening the Dask cluster of a command (warptrunc.sweep.cluster.open_client): ``auto``
workers, one kernel cache for every worker, dask-cuda's LocalCUDACluster where installed, a
client passed in left open, one cluster per sweep whatever its number of groups; what the workers
inherit (cl.worker_environment): no Dask glibc trim threshold (which turns the dynamic mmap
threshold off, so every large temporary is mapped and faulted in afresh) unless the user's
environment sets it, Dask's other settings, the shared kernel cache, no statistical profiler."""

import os
import sys
import types

import pytest

pytest.importorskip("distributed")
pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

from sweep_helpers import OPTS, OPTS_CLI, results_only  # noqa: E402

import warptrunc.sweep.cluster as cl  # noqa: E402
from warptrunc.sweep import SweepGrid, load, run_sweep  # noqa: E402


def test_resolve_workers(monkeypatch):
    assert cl.resolve_workers(None) is None
    assert cl.resolve_workers(3) == 3 and cl.resolve_workers("4") == 4
    monkeypatch.setattr(cl, "_gpu_count", lambda: 0)
    assert cl.resolve_workers("auto") == 1  # a machine without a GPU: one worker
    monkeypatch.setattr(cl, "_gpu_count", lambda: 4)
    assert cl.resolve_workers(" AUTO ") == 4
    for bad in (0, "0", "two", -1, 1.5, True):
        with pytest.raises(ValueError, match="workers"):
            cl.resolve_workers(bad)


def test_workers_option_parses_auto():
    import argparse

    from warptrunc.cli._common import workers_count

    assert workers_count("auto") == "auto" and workers_count("3") == 3
    for bad in ("0", "x", "1.5", "5000"):
        with pytest.raises(argparse.ArgumentTypeError, match="or 'auto'"):
            workers_count(bad)


def _worker_env(client):
    return client.run(
        lambda: (os.environ.get("WARP_CACHE_PATH"), os.environ.get("WARPTRUNC_DEVICE"))
    )


def test_kernel_cache_base(monkeypatch, tmp_path):
    import warp as wp

    monkeypatch.setattr(wp.config, "kernel_cache_dir", None)
    monkeypatch.delenv("WARP_CACHE_PATH", raising=False)
    assert cl.kernel_cache_base() is None  # the user's default folder, the same for all
    monkeypatch.setenv("WARP_CACHE_PATH", str(tmp_path / "env"))
    assert cl.kernel_cache_base() == str(tmp_path / "env")
    monkeypatch.setattr(wp.config, "kernel_cache_dir", str(tmp_path / "set"))  # before start
    assert cl.kernel_cache_base() == str(tmp_path / "set")
    resolved = str(tmp_path / "start" / wp.config.version)  # as Warp's start leaves it
    monkeypatch.setattr(wp.config, "kernel_cache_dir", resolved)
    assert cl.kernel_cache_base() == str(tmp_path / "start")


def test_gpu_count_agrees_with_warp():
    from warptrunc._support.device import cuda_device_count

    assert cl._gpu_count() == cuda_device_count()


@pytest.mark.timeout(180)
def test_open_client_local_cluster_shares_the_kernel_cache(monkeypatch, tmp_path):
    import warp as wp

    monkeypatch.delenv("WARPTRUNC_DEVICE", raising=False)
    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    monkeypatch.delenv("WARPTRUNC_DASK_PROFILE", raising=False)
    monkeypatch.setattr(wp.config, "kernel_cache_dir", str(tmp_path / "cache"))
    with cl.open_client(2, None, None, False) as (client, cluster, own):
        assert own and cluster is not None and type(cluster).__name__ == "LocalCluster"
        client.wait_for_workers(2, timeout=120)
        env = _worker_env(client)
        assert len(env) == 2 and {e[0] for e in env.values()} == {str(tmp_path / "cache")}
        # Dask's other pre-spawn settings stay; glibc's trim threshold is left unset
        spawn = client.run(
            lambda: (os.environ.get("MALLOC_TRIM_THRESHOLD_"), os.environ.get("OMP_NUM_THREADS"))
        )
        assert set(spawn.values()) == {(None, "1")}
        # Dask's statistical profiler is off in the workers (on in Dask's defaults)
        import dask

        assert dask.config.get("distributed.worker.profile.enabled") is True
        prof = client.run(
            lambda: __import__("dask").config.get("distributed.worker.profile.enabled")
        )
        assert set(prof.values()) == {False}
        assert "MALLOC_TRIM_THRESHOLD_" not in os.environ  # nor set in this process
        # the workers resolve that folder (Warp appends its version)
        dirs = client.run(
            lambda: (
                __import__("warptrunc._support.device", fromlist=["_"]).cuda_device_count(),
                __import__("os").path.realpath(__import__("warp").config.kernel_cache_dir),
            )[1]
        )
        assert set(dirs.values()) == {str(tmp_path / "cache" / wp.config.version)}
        # a client passed in is used as it is and left open
        with cl.open_client(None, client, None, False) as (c2, cluster2, own2):
            assert c2 is client and cluster2 is None and not own2
        assert client.status == "running"
        with pytest.raises(ValueError, match="not both"):
            with cl.open_client(2, client, None, False):
                pass
    assert client.status == "closed"


@pytest.mark.timeout(180)
def test_open_client_uses_dask_cuda_where_installed(monkeypatch):
    """With dask-cuda and CUDA devices (faked here: 2), a LocalCUDACluster of one worker per
    device, each on its own device's cuda:0; WARPTRUNC_DASK_CUDA=0 turns it off."""
    from distributed import LocalCluster

    made = {}

    class FakeCUDACluster(LocalCluster):
        def __init__(self, n_workers=None, **kw):
            made.update(n_workers=n_workers, **kw)
            super().__init__(n_workers=n_workers, processes=True, **kw)

    monkeypatch.setitem(
        sys.modules, "dask_cuda", types.SimpleNamespace(LocalCUDACluster=FakeCUDACluster)
    )
    monkeypatch.setattr(cl, "_gpu_count", lambda: 2)
    monkeypatch.delenv("WARPTRUNC_DEVICE", raising=False)
    monkeypatch.delenv(cl.DASK_CUDA_ENV, raising=False)
    assert cl._dask_cuda_cluster() is FakeCUDACluster
    with cl.open_client("auto", None, None, False) as (client, cluster, _):
        assert isinstance(cluster, FakeCUDACluster) and made["n_workers"] == 2
        client.wait_for_workers(2, timeout=120)
        assert {e[1] for e in _worker_env(client).values()} == {"cuda:0"}
    monkeypatch.setenv(cl.DASK_CUDA_ENV, "0")
    assert cl._dask_cuda_cluster() is None
    monkeypatch.delenv(cl.DASK_CUDA_ENV)
    # a device given: a LocalCluster, its workers not pinned
    made.clear()
    with cl.open_client(1, None, "cpu", False) as (client, cluster, _):
        assert type(cluster) is LocalCluster and not made
        assert {e[1] for e in _worker_env(client).values()} == {None}


@pytest.mark.timeout(240)
def test_one_cluster_for_every_group_of_a_sweep(tmp_path, monkeypatch, capsys):
    """``warptrunc sweep --workers auto`` (1 worker without a GPU) on a grid with an extra axis:
    two groups of cases on one cluster, started once; the table as in process."""
    from warptrunc.cli import main

    opened = []
    real = cl.open_client

    def counting(workers, scheduler, *a, **kw):
        from distributed import Client

        if not isinstance(scheduler, Client):  # a client passed in is only used
            opened.append((workers, scheduler))
        return real(workers, scheduler, *a, **kw)

    monkeypatch.setattr(cl, "open_client", counting)
    grid = SweepGrid([2.4], [0.01], "0-1", axes={"M": [8, 10]})
    ref = run_sweep(grid, None, progress=False, device="cpu", options=OPTS)
    rc = main(
        [
            "sweep",
            "--D",
            "2.4",
            "--delta",
            "0.01",
            "--seeds",
            "0-1",
            "--M",
            "8",
            "10",
            "--n",
            "64",
            *OPTS_CLI,
            "--workers",
            "auto",
            "--out",
            str(tmp_path / "s"),
        ]
    )
    assert rc == 0 and "4 cases (0 failed)" in capsys.readouterr().out
    assert opened == [("auto", None)]
    pd.testing.assert_frame_equal(results_only(load(tmp_path / "s")), results_only(ref))


def test_trim_threshold_left_unset_unless_the_user_sets_it(monkeypatch, tmp_path):
    import dask
    import warp as wp

    monkeypatch.setattr(wp.config, "kernel_cache_dir", str(tmp_path / "cache"))
    monkeypatch.delenv(cl.TRIM_VARIABLE, raising=False)
    dask_default = dask.config.get("distributed.nanny.pre-spawn-environ")
    assert cl.TRIM_VARIABLE in dask_default  # what Dask would set
    cfg = cl.worker_environment()
    pre = cfg["distributed.nanny.pre-spawn-environ"]
    assert pre[cl.TRIM_VARIABLE] is None
    # everything else Dask sets before spawning is kept as configured
    assert {k: v for k, v in pre.items() if k != cl.TRIM_VARIABLE} == {
        k: v for k, v in dask_default.items() if k != cl.TRIM_VARIABLE
    }
    assert cfg["distributed.nanny.environ"]["WARP_CACHE_PATH"] == str(tmp_path / "cache")
    # Dask's own reading of the configuration leaves the variable out
    from distributed.nanny import _get_env_variables

    with dask.config.set(cfg):
        assert cl.TRIM_VARIABLE not in _get_env_variables("distributed.nanny.pre-spawn-environ")

    monkeypatch.setenv(cl.TRIM_VARIABLE, "131072")  # the user's own choice is kept
    pre = cl.worker_environment()["distributed.nanny.pre-spawn-environ"]
    assert pre[cl.TRIM_VARIABLE] is not None
    with dask.config.set({"distributed.nanny.pre-spawn-environ": pre}):
        got = _get_env_variables("distributed.nanny.pre-spawn-environ")
    assert got[cl.TRIM_VARIABLE] == "131072"


def test_profiler_off_unless_asked(monkeypatch):
    import dask

    monkeypatch.delenv(cl.PROFILE_ENV, raising=False)
    assert dask.config.get("distributed.worker.profile.enabled") is True  # Dask's default
    assert cl.worker_environment()["distributed.worker.profile.enabled"] is False
    monkeypatch.setenv(cl.PROFILE_ENV, "1")
    assert cl.worker_environment()["distributed.worker.profile.enabled"] is True
