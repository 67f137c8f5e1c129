# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""One contact problem over two *processes* (the way several hosts join: ``jax.distributed``,
``warptrunc.contact.sharded.grid.PROCESS_ENV``), one host device each, against the one-device
Warp solver run in each process: the same approach, load, contact pixels and Barber's stiffness
within 1e-9 relative (float64), and the two processes identical to each other bit for bit.

Two Python processes on this machine, joined through a coordinator on a free local port, with
Gloo's collectives between their CPU devices. Skipped without JAX.
"""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys

import pytest

pytest.importorskip("jax")
pytestmark = pytest.mark.timeout(300)

SCRIPT = r"""
import json, sys
import numpy as np
from warptrunc.contact import ContactSolver, SolverSettings, contact_solver
from warptrunc.contact.sharded import ShardedContactSolver

n, dx, E = 128, 1e-6, 1e9
rng = np.random.default_rng(1)
k2 = np.fft.fftfreq(n)[:, None] ** 2 + np.fft.rfftfreq(n)[None, :] ** 2
spec = (rng.normal(size=k2.shape) + 1j * rng.normal(size=k2.shape)) * np.where(k2 > 0, k2, 1.0) ** -1.1
spec[0, 0] = 0
h = np.fft.irfft2(spec, s=(n, n))
h = h / h.std() * 1e-6
load = 5e-4 * E * (n * dx) ** 2
import jax
two = contact_solver(h, dx, E, devices=2)
assert isinstance(two, ShardedContactSolver) and jax.process_count() == 2
b = two.solve(load=load)
one = ContactSolver(h, dx, E, device="cpu", settings=SolverSettings(direct_max=0))
a = one.solve(load=load)
print("RESULT " + json.dumps({
    "process": jax.process_index(), "devices": [str(d) for d in two.hs.devices],
    "depth": [a.depth, b.depth], "load": [a.load, b.load], "iterations": [a.n_iterations, b.n_iterations],
    "contact": [int((one.maps()[0] > 0).sum()), int(two.contact_map().sum())],
    "same_map": bool(np.array_equal(one.maps()[0] > 0, two.maps()[0] > 0)),
    "k": [float(one.punch_stiffness()[0]), float(two.punch_stiffness()[0])],
}))
"""


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_two_processes_equal_one_device():
    port = _free_port()
    procs = []
    for rank in (0, 1):
        env = dict(
            os.environ,
            JAX_PLATFORMS="cpu",
            WARPTRUNC_DEVICE="cpu",
            WARPTRUNC_COORDINATOR=f"127.0.0.1:{port}",
            WARPTRUNC_NUM_PROCESSES="2",
            WARPTRUNC_PROCESS_ID=str(rank),
        )
        env.pop("XLA_FLAGS", None)  # one host device per process
        procs.append(
            subprocess.Popen(
                [sys.executable, "-c", SCRIPT],
                env=env,
                text=True,
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT,
            )
        )
    outs = []
    for p in procs:
        out, _ = p.communicate(timeout=240)
        assert p.returncode == 0, out[-3000:]
        line = [x for x in out.splitlines() if x.startswith("RESULT ")]
        assert line, out[-3000:]
        outs.append(json.loads(line[-1][7:]))
    assert sorted(o["process"] for o in outs) == [0, 1]
    r = outs[0]
    assert len(r["devices"]) == 2
    for q in ("depth", "load", "k"):
        one, two = r[q]
        assert abs(one - two) <= 1e-9 * abs(one), (q, one, two)
    assert r["iterations"][0] == r["iterations"][1]
    assert r["same_map"] and r["contact"][0] == r["contact"][1] > 0
    assert outs[0]["depth"][1] == outs[1]["depth"][1] and outs[0]["k"][1] == outs[1]["k"][1]
