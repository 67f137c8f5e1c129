# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""warptrunc.sweep.spawn: a local cluster's workers are spawned without Dask's glibc trim
threshold (which turns the dynamic mmap threshold off, so every large temporary is mapped and
faulted in afresh), unless the user's environment sets it; Dask's other settings and the
shared kernel cache are kept."""

import pytest

dask = pytest.importorskip("dask")
pytest.importorskip("distributed")

from warptrunc.sweep import spawn  # noqa: E402


def test_trim_threshold_left_unset_unless_the_user_sets_it(monkeypatch, tmp_path):
    import warp as wp

    monkeypatch.setattr(wp.config, "kernel_cache_dir", str(tmp_path / "cache"))
    monkeypatch.delenv(spawn.TRIM_VARIABLE, raising=False)
    dask_default = dask.config.get("distributed.nanny.pre-spawn-environ")
    assert spawn.TRIM_VARIABLE in dask_default  # what Dask would set
    cfg = spawn.worker_environment()
    pre = cfg["distributed.nanny.pre-spawn-environ"]
    assert pre[spawn.TRIM_VARIABLE] is None
    # everything else Dask sets before spawning is kept as configured
    assert {k: v for k, v in pre.items() if k != spawn.TRIM_VARIABLE} == {
        k: v for k, v in dask_default.items() if k != spawn.TRIM_VARIABLE
    }
    assert cfg["distributed.nanny.environ"]["WARP_CACHE_PATH"] == str(tmp_path / "cache")
    # Dask's own reading of the configuration leaves the variable out
    from distributed.nanny import _get_env_variables

    with dask.config.set(cfg):
        assert spawn.TRIM_VARIABLE not in _get_env_variables("distributed.nanny.pre-spawn-environ")

    monkeypatch.setenv(spawn.TRIM_VARIABLE, "131072")  # the user's own choice is kept
    pre = spawn.worker_environment()["distributed.nanny.pre-spawn-environ"]
    assert pre[spawn.TRIM_VARIABLE] is not None
    with dask.config.set({"distributed.nanny.pre-spawn-environ": pre}):
        got = _get_env_variables("distributed.nanny.pre-spawn-environ")
    assert got[spawn.TRIM_VARIABLE] == "131072"


def test_profiler_off_unless_asked(monkeypatch):
    monkeypatch.delenv(spawn.PROFILE_ENV, raising=False)
    assert dask.config.get("distributed.worker.profile.enabled") is True  # Dask's default
    assert spawn.worker_environment()["distributed.worker.profile.enabled"] is False
    monkeypatch.setenv(spawn.PROFILE_ENV, "1")
    assert spawn.worker_environment()["distributed.worker.profile.enabled"] is True
