# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""warptrunc.sweep._affinity: the CPUs near a GPU (sysfs ``local_cpulist`` of the bus id the
CUDA driver gives) and binding a process to them; the pinned workers of a local cluster call
it with their devices."""

import os
import re
from types import SimpleNamespace

import pytest

from warptrunc.sweep import _affinity as affinity

linux_only = pytest.mark.skipif(not hasattr(os, "sched_setaffinity"), reason="Linux only")


@pytest.mark.parametrize(
    ("text", "cpus"),
    [("0-3,8,10-11\n", {0, 1, 2, 3, 8, 10, 11}), ("5", {5}), ("", set()), (" 0-1 , 4 ", {0, 1, 4})],
)
def test_parse_cpulist(text, cpus):
    assert affinity.parse_cpulist(text) == cpus


@pytest.mark.parametrize("cpus", [set(), {0}, {0, 1, 2, 3, 8}, {1, 3, 5}, {7, 2, 3, 4, 10, 11}])
def test_format_cpulist_round_trips(cpus):
    text = affinity.format_cpulist(cpus)
    assert affinity.parse_cpulist(text) == cpus
    assert text.count(",") == sum(1 for c in cpus if c + 1 not in cpus) - 1 if cpus else text == ""


@pytest.mark.parametrize("text", ["3-1", "a", "1-b", "-2"])
def test_parse_cpulist_rejects(text):
    with pytest.raises(ValueError, match="not a CPU list"):
        affinity.parse_cpulist(text)


@pytest.mark.parametrize(
    ("bus", "name"),
    [
        ("00000000:1B:00.0", "0000:1b:00.0"),
        ("0000:9A:00.0", "0000:9a:00.0"),
        ("0001:c1:1f.7\n", "0001:c1:1f.7"),
        ("", None),
        ("1B:00.0", None),
        ("zz:1b:00.0", None),
    ],
)
def test_sysfs_name(bus, name):
    assert affinity.sysfs_name(bus) == name


def _fake_sysfs(tmp_path, lists: dict[str, str]):
    for bus, text in lists.items():
        (tmp_path / bus).mkdir()
        (tmp_path / bus / "local_cpulist").write_text(text + "\n")
    return str(tmp_path)


def test_gpu_local_cpus_unions_the_devices_and_says_none_when_unknown(monkeypatch, tmp_path):
    buses = {0: "0000:1b:00.0", 1: "0000:9a:00.0"}
    monkeypatch.setattr(affinity, "pci_bus_id", lambda o: buses.get(o))
    sysfs = _fake_sysfs(tmp_path, {"0000:1b:00.0": "0-3,16-19", "0000:9a:00.0": "4-7"})
    assert affinity.gpu_local_cpus([0], sysfs) == {0, 1, 2, 3, 16, 17, 18, 19}
    assert affinity.gpu_local_cpus([0, 1], sysfs) == {0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19}
    assert affinity.gpu_local_cpus([2], sysfs) is None  # no such device
    (tmp_path / "0000:9a:00.0" / "local_cpulist").unlink()
    assert affinity.gpu_local_cpus([0, 1], sysfs) is None  # a device whose CPUs are unknown


def test_pci_bus_id_is_a_sysfs_name_or_none():
    bus = affinity.pci_bus_id(0)
    assert bus is None or re.fullmatch(r"[0-9a-f]{4,8}:[0-9a-f]{2}:[0-9a-f]{2}\.[0-7]", bus)
    assert affinity.pci_bus_id(10_000) is None  # no such device, with or without a driver


@linux_only
def test_bind_near_binds_every_thread_to_the_allowed_near_cpus(monkeypatch, tmp_path):
    import threading

    allowed = os.sched_getaffinity(0)
    if len(allowed) < 2:
        pytest.skip("needs two CPUs")
    first = min(allowed)
    monkeypatch.setattr(affinity, "pci_bus_id", lambda o: "0000:1b:00.0")
    monkeypatch.delenv(affinity.AFFINITY_ENV, raising=False)
    # the GPU's CPUs: the first allowed one and one this process may not use
    sysfs = _fake_sysfs(tmp_path, {"0000:1b:00.0": f"{first},{max(allowed) + 1000}"})
    started, stop = threading.Event(), threading.Event()
    seen = {}

    def other():  # a thread that exists before the binding
        started.set()
        stop.wait(30)
        seen["cpus"] = os.sched_getaffinity(0)

    t = threading.Thread(target=other)
    t.start()
    started.wait(30)
    try:
        assert affinity.bind_near([0], sysfs) == {first}
        assert os.sched_getaffinity(0) == {first}
        stop.set()
        t.join(30)
        assert seen["cpus"] == {first}
        # already bound: nothing changes; the knob off: nothing is done
        assert affinity.bind_near([0], sysfs) is None
    finally:
        stop.set()
        affinity._set_all_threads(allowed)
    assert os.sched_getaffinity(0) == allowed
    monkeypatch.setenv(affinity.AFFINITY_ENV, "0")
    assert affinity.bind_near([0], sysfs) is None
    assert os.sched_getaffinity(0) == allowed
    monkeypatch.delenv(affinity.AFFINITY_ENV)
    # CPUs none of which this process may use: left alone
    (tmp_path / "0000:1b:00.0" / "local_cpulist").write_text(f"{max(allowed) + 1000}\n")
    assert affinity.bind_near([0], sysfs) is None
    assert os.sched_getaffinity(0) == allowed


def test_module_prints_the_cpu_list(monkeypatch, capsys):
    monkeypatch.setattr(
        affinity, "gpu_local_cpus", lambda ords: {4, 5, 0} if list(ords) == [1] else None
    )
    assert affinity._main(["1"]) == 0
    assert capsys.readouterr().out == "0,4-5\n"
    assert affinity._main(["0"]) == 0
    assert capsys.readouterr().out == ""


def test_pinned_workers_bind_to_their_devices(monkeypatch):
    pytest.importorskip("distributed")
    from warptrunc.sweep import cluster as cl

    calls = []
    monkeypatch.setattr(affinity, "bind_near", lambda ords: calls.append(list(ords)))
    for var in ("WARPTRUNC_DEVICE", "WARPTRUNC_DEVICE_GROUP"):
        monkeypatch.setenv(var, "unset")  # restored by monkeypatch afterwards
    cl.PinDevice(n_devices=4).setup(SimpleNamespace(name=3))
    assert os.environ["WARPTRUNC_DEVICE"] == "cuda:3" and calls == [[3]]
    cl.PinDevice(n_devices=4, group=2).setup(SimpleNamespace(name=1))
    assert os.environ["WARPTRUNC_DEVICE"] == "cuda:2" and calls[-1] == [2, 3]
    cl.PinDevice(n_devices=4, group=2, platform="cpu").setup(SimpleNamespace(name=1))
    assert len(calls) == 2  # JAX's host devices: nothing to bind
    cl.PinDevice(n_devices=0).setup(SimpleNamespace(name=0))  # no GPU: nothing pinned or bound
    assert len(calls) == 2
