# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The ``indentation`` stage of ``warptrunc reproduce`` on a Dask cluster:
its parts on two local worker processes give the rows an in-process run gives, ``reproduce
--workers 2`` equals ``--workers 1``, and a worker killed mid-stage, or a time budget, loses
nothing and duplicates nothing (the rerun completes the same stage)."""

from __future__ import annotations

import json
import math
import os
import re
import signal
import threading
import time
from dataclasses import replace

import pytest

distributed = pytest.importorskip("distributed")

from sweep_helpers import two_worker_client  # noqa: E402

from warptrunc.reproduce import get_profile, reproduce  # noqa: E402
from warptrunc.reproduce.indentation import StageIncomplete, stage_indentation  # noqa: E402


def _profile():
    """Tiny, one surface, with every kind of piece: the sweep (finite H reusing elastic cycles
    on the unrefined punches), elastic and depth-matched statistics over two realisations (a
    band wide enough that an H matches), a refined punch, a tilted and a rough face."""
    p = get_profile("tiny")
    st = p.indentation.replace(
        surfaces=("Ps",),
        hardness=(math.inf, 0.5e9, 2e9),
        depth_band=(1e-9, 1e-3),
        depth_target=1e-6,
        refine=False,
    )
    return replace(p, name="workers-test", indentation=st)


def _rows(doc) -> str:
    return json.dumps(doc["rows"], sort_keys=True)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("ref")
    return stage_indentation(_profile().indentation, out, "cpu", progress=False), out


@pytest.fixture(scope="module")
def client():
    yield from two_worker_client()


def test_plan_has_every_kind_of_piece(reference):
    stage, out = reference
    names = sorted(f.name for f in (out / "indentation").glob("*.json"))
    assert any("__stats__elastic_plastic" in n for n in names), names  # depth-matched stats ran
    assert any("__face__tilt" in n for n in names) and any("__face__rough" in n for n in names)
    assert not [n for n in names if re.search(r"__p\d+r\d+\.json$", n)], names  # no part left
    assert len(set(stage["rows"]["realisation"])) == 2  # the statistics' two realisations


@pytest.mark.timeout(300)
def test_two_workers_store_what_in_process_stores(tmp_path, client, reference):
    ref, ref_out = reference
    got = stage_indentation(_profile().indentation, tmp_path, "cpu", progress=False, client=client)
    assert _rows(got) == _rows(ref)  # bit for bit: every part is an independent solve
    a = sorted(f.name for f in (ref_out / "indentation").glob("*.json"))
    b = sorted(f.name for f in (tmp_path / "indentation").glob("*.json"))
    assert a == b  # the same pieces, no part files left
    for name in a:
        ra = json.loads((ref_out / "indentation" / name).read_text())
        rb = json.loads((tmp_path / "indentation" / name).read_text())
        assert ra["params"] == rb["params"] and ra.get("rows") == rb.get("rows"), name


@pytest.mark.timeout(300)
def test_worker_killed_mid_stage_loses_and_duplicates_nothing(tmp_path, client, reference):
    ref, _ = reference
    box: dict = {}

    def run():
        try:
            box["doc"] = stage_indentation(
                _profile().indentation, tmp_path, "cpu", progress=False, client=client
            )
        except BaseException as exc:  # reported by the assertion below
            box["exc"] = exc

    th = threading.Thread(target=run)
    th.start()
    t0 = time.monotonic()
    while not list((tmp_path / "indentation").glob("*.json")) and time.monotonic() - t0 < 120:
        time.sleep(0.05)
    n_at_kill = len(list((tmp_path / "indentation").glob("*.json")))
    pids = client.run(os.getpid)
    os.kill(next(iter(pids.values())), signal.SIGKILL)  # one worker dies mid-part
    th.join(240)
    assert not th.is_alive() and "exc" not in box, box.get("exc")
    assert n_at_kill >= 1 and "doc" in box
    assert _rows(box["doc"]) == _rows(ref)
    assert not list((tmp_path / "indentation").glob(".*"))  # no temporary file left


@pytest.mark.timeout(300)
def test_time_budget_on_the_cluster_then_rerun(tmp_path, client, reference):
    ref, _ = reference
    with pytest.raises(StageIncomplete, match="run the same command again"):
        stage_indentation(
            _profile().indentation,
            tmp_path,
            "cpu",
            progress=False,
            client=client,
            deadline=time.perf_counter() + 1.0,
        )
    stored = {f.name: f.stat().st_mtime_ns for f in (tmp_path / "indentation").glob("*.json")}
    assert stored  # the parts that ran before the budget are kept
    again = stage_indentation(
        _profile().indentation, tmp_path, "cpu", progress=False, client=client
    )
    assert _rows(again) == _rows(ref)
    for name, t in stored.items():  # a kept piece is reused, not rewritten
        f = tmp_path / "indentation" / name
        if not re.search(r"__p\d+r\d+\.json$", name):
            assert f.stat().st_mtime_ns == t, name


@pytest.mark.timeout(400)
def test_reproduce_workers_2_equals_workers_1(tmp_path):
    st = _profile().indentation.replace(face_surface=None, stats=("elastic",))
    p = replace(_profile(), indentation=st)
    one = reproduce(p, tmp_path / "w1", device="cpu", stages="indentation", workers=1)
    two = reproduce(p, tmp_path / "w2", device="cpu", stages="indentation", workers=2)
    assert _rows(one["stages"]["indentation"]) == _rows(two["stages"]["indentation"])
    fa, fb = one["analysis"]["indentation"]["fits"], two["analysis"]["indentation"]["fits"]
    assert json.dumps(fa, sort_keys=True) == json.dumps(fb, sort_keys=True)


@pytest.mark.timeout(400)
def test_elastic_stage_on_two_workers_equals_in_process(tmp_path):
    """The elastic stage's maps as tasks: the same stored rows as in process."""
    from warptrunc.compare import load_comparison

    p = get_profile("tiny")
    one = reproduce(p, tmp_path / "a", device="cpu", stages="elastic")
    two = reproduce(p, tmp_path / "b", device="cpu", stages="elastic", workers=2)
    ra = load_comparison(tmp_path / "a" / "elastic").drop(columns=["solve_time_s", "case_seconds"])
    rb = load_comparison(tmp_path / "b" / "elastic").drop(columns=["solve_time_s", "case_seconds"])
    ra = ra.sort_values(list(ra.columns[:3])).reset_index(drop=True)
    rb = rb.sort_values(list(rb.columns[:3])).reset_index(drop=True)
    assert len(ra) and ra.equals(rb)
    assert one["stages"]["elastic"]["alpha"] == two["stages"]["elastic"]["alpha"]
