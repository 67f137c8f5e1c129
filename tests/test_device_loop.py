# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The BCCG loop with one read-back per iteration (``SolverSettings(loop="device")``, issue 40
item 2) against the loop that reads back after every reduction (``loop="host"``, the default): at the same settings the same iterations, contact sets and loads to the round-off
of the float64 sums of the partials (which the device folds in row order and the host with
NumPy). The paths of the device loop's deferred decisions are forced: ``direct_max=0`` (every
projection transforms afresh one read later), a large list (every projection corrected by direct
summation), ``refresh=3`` (transforms afresh on schedule)."""

import numpy as np
import pytest

from warptrunc.contact import ContactSolver, SolverSettings

N = 96
E_STAR = 1e11  # Pa
DX = 1e-7  # m


def rough_map(seed: int = 1) -> np.ndarray:
    """A Gaussian random map with a power-law spectrum (float64 NumPy; 1 µm rms, m)."""
    rng = np.random.default_rng(seed)
    k2 = np.fft.fftfreq(N)[:, None] ** 2 + np.fft.fftfreq(N)[None, :] ** 2
    k2[0, 0] = 1.0
    spec = (rng.normal(size=(N, N)) + 1j * rng.normal(size=(N, N))) * k2 ** (-0.9)
    h = np.fft.ifft2(spec).real
    return h * (1e-6 / h.std())


def run(loop: str, *, hardness: float = np.inf, **settings) -> list[tuple]:
    """Three displacement-controlled solves, then (elastic) two load-controlled ones."""
    solver = ContactSolver(
        rough_map(), DX, E_STAR, hardness=hardness, settings=SolverSettings(loop=loop, **settings)
    )
    out = []
    for d in (0.5e-6, 1.0e-6, 1.6e-6):
        c = solver.solve(d)
        out.append((c.load, c.depth, c.n_contact, c.n_iterations, c.converged))
    if np.isinf(hardness):
        for f in (0.6 * out[0][0], 1.3 * out[1][0]):
            c = solver.solve(load=f)
            out.append((c.load, c.depth, c.n_contact, c.n_iterations, c.converged))
    return out


CASES = [
    dict(substrate="free"),
    dict(substrate="periodic"),
    dict(substrate="free", direct_max=0),
    dict(substrate="periodic", direct_max=10_000),
    dict(substrate="free", refresh=3),
    dict(substrate="free", dtype="float32"),
    dict(substrate="free", hardness=3e9),
    dict(substrate="periodic", hardness=3e9, direct_max=0),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: "-".join(f"{k}={v}" for k, v in c.items()))
def test_device_loop_equals_host_loop(case):
    case = dict(case)
    hardness = case.pop("hardness", np.inf)
    host = run("host", hardness=hardness, **case)
    dev = run("device", hardness=hardness, **case)
    assert all(h[4] for h in host), host  # every solve converged
    tol = 1e-5 if case.get("dtype") == "float32" else 1e-10
    for h, d in zip(host, dev):
        assert d[4]
        assert d[3] == h[3]  # iterations
        assert d[2] == h[2]  # contact pixels
        assert d[0] == pytest.approx(h[0], rel=tol)  # load (N)
        assert d[1] == pytest.approx(h[1], rel=tol, abs=1e-15)  # approach (m)


def test_graph_loop_off_cuda_is_the_device_loop():
    """``loop="graph"`` off a CUDA device launches as ``"device"``: the same answers."""
    assert run("graph", substrate="free") == run("device", substrate="free")


def test_loop_setting_is_checked():
    assert SolverSettings().loop in ("host", "device", "graph")
    with pytest.raises(ValueError, match="loop"):
        SolverSettings(loop="gpu")
