# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The free half-space's two cuFFT plans (``SolverSettings.fft_plan``, issue 29): the memory
model of each, which plan ``auto`` takes, and — on a CUDA device — the same solution from both
and each one's peak device memory against ``ContactSolver.memory_bytes`` (Warp's allocation
tracker; within 10 %)."""

from __future__ import annotations

import gc

import numpy as np
import pytest
import warp as wp

from warptrunc.contact import ContactSolver, SolverSettings
from warptrunc.contact.halfspace import ElasticHalfSpace
from warptrunc.wm import wm_surface

from conftest import DEVICES

E_STAR = 78.6e9
CUDA = [d for d in DEVICES if d.startswith("cuda")]


@pytest.mark.parametrize("dtype", ["float32", "float64"])
def test_full_plan_adds_one_work_spectrum(dtype):
    shape = (1000, 1200)
    pruned = ContactSolver.memory_terms(shape, "free", dtype, fft_plan="pruned")
    full = ContactSolver.memory_terms(shape, "free", dtype, fft_plan="full")
    item = np.dtype(dtype).itemsize
    spectrum = 2000 * (2400 // 2 + 1) * 2 * item  # (Ny, Nx//2 + 1) complex of the padded grid
    assert full["work spectrum"] == spectrum
    assert full["cufft work area"] == spectrum
    assert pruned["cufft work area"] <= spectrum  # the largest slab (the whole, when small)
    assert {k: v for k, v in full.items() if k != "cufft work area"} == {
        k: v for k, v in pruned.items() if k != "cufft work area"
    }
    # periodic and the CPU: no such plan
    assert ContactSolver.memory_terms(
        shape, "periodic", dtype, fft_plan="full"
    ) == ContactSolver.memory_terms(shape, "periodic", dtype, fft_plan="pruned")
    assert ContactSolver.memory_bytes(
        shape, "free", dtype, cuda=False, fft_plan="full"
    ) == ContactSolver.memory_bytes(shape, "free", dtype, cuda=False)


def test_fft_plan_setting_is_checked_and_cpu_takes_pruned():
    with pytest.raises(ValueError, match="fft_plan"):
        SolverSettings(fft_plan="2d")
    with pytest.raises(ValueError, match="fft_plan"):
        ElasticHalfSpace((8, 8), (1e-6, 1e-6), E_STAR, fft_plan="2d", device="cpu")
    z = np.random.default_rng(0).normal(size=(32, 32)) * 1e-7
    for p in ("auto", "full", "pruned"):
        s = ContactSolver(z, 1e-6, E_STAR, settings=SolverSettings(fft_plan=p), device="cpu")
        assert s.fft_plan == "pruned" and s.hs.fft_plan == "pruned"


@pytest.mark.skipif(not CUDA, reason="needs a CUDA device (WARPTRUNC_TEST_DEVICES)")
@pytest.mark.parametrize("dtype", ["float32", "float64"])
def test_both_plans_same_solution_and_modelled_memory(dtype):
    from warp._src.context import runtime

    dev = CUDA[0]
    s = wm_surface(2.5, 100e-6, L=1e-3, n=1024, Rt=10e-6, seed=2, device=dev)
    h = s.heights  # its host copy before the tracker's window (which counts host allocations)
    out = {}
    for plan in ("pruned", "full"):
        gc.collect()
        wp.synchronize_device(dev)
        with wp.ScopedMemoryTracker("plan", print=False):
            runtime.core.wp_alloc_tracker_reset()
            base = runtime.core.wp_alloc_tracker_get_current_bytes()
            sol = ContactSolver(
                h,
                (s.dx, s.dy),
                E_STAR,
                device=dev,
                settings=SolverSettings(dtype=dtype, fft_plan=plan),
            )
            assert sol.fft_plan == plan
            r = sol.solve(0.2 * s.Rt)
            sol.punch_stiffness()
            wp.synchronize_device(dev)
            peak = runtime.core.wp_alloc_tracker_get_peak_bytes() - base
            del sol
        need = ContactSolver.memory_bytes(s.shape, "free", dtype, fft_plan=plan, device=dev)
        assert abs(peak - need) <= 0.1 * need, (plan, peak, need)
        assert r.converged
        out[plan] = r
    rtol = 1e-4 if dtype == "float32" else 1e-9
    np.testing.assert_allclose(out["full"].load, out["pruned"].load, rtol=rtol)
    assert abs(out["full"].n_contact - out["pruned"].n_contact) <= 1e-3 * out["pruned"].n_contact
