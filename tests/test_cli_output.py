# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""What the commands print: only what the user asked for (no Warp/VTK notices on CPU-only
machines unless --verbose), and the height convention behind each D of ``describe``."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest
from cli_helpers import RENDER_CLI, run_cli

import warptrunc

NOTICES = ("CUDA driver", "bad X server", "vtkXOpenGLRenderWindow", "Warp CUDA warning")


def cli(*args, cwd, env_extra=None):
    env = {k: v for k, v in os.environ.items() if k != "WARPTRUNC_VERBOSE"}
    env.update(env_extra or {})
    return run_cli(*args, cwd=cwd, env=env)


def _no_cuda_driver() -> bool:
    import warp as wp

    import warptrunc

    warptrunc.resolve_device("cpu")
    return wp.get_cuda_driver_version() in (0, None)


def test_generate_prints_only_its_result(tmp_path):
    r = cli("generate", "--n", 32, "-o", "s.npz", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    out = r.stdout + r.stderr
    assert not [n for n in NOTICES if n in out], out
    assert r.stderr == "" and r.stdout.startswith("wrote s.npz")


def test_render_prints_only_its_result(tmp_path):
    pytest.importorskip("pyvista")
    r = cli(
        *RENDER_CLI,
        "--size",
        200,
        160,
        "--out",
        "r",
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    assert not [n for n in NOTICES if n in r.stdout + r.stderr], r.stdout + r.stderr
    assert r.stderr == ""


def test_verbose_shows_the_warp_notice_on_a_cpu_only_machine(tmp_path):
    if not _no_cuda_driver():
        pytest.skip("a CUDA driver is present: Warp has nothing to say")
    r = cli("--verbose", "generate", "--n", 32, "-o", "s.npz", cwd=tmp_path)
    assert r.returncode == 0 and "CUDA driver" in r.stdout + r.stderr
    r = cli(
        "generate", "--n", 32, "-o", "s.npz", cwd=tmp_path, env_extra={"WARPTRUNC_VERBOSE": "1"}
    )
    assert r.returncode == 0 and "CUDA driver" in r.stdout + r.stderr


@pytest.mark.parametrize("scaling", ["cube", "si"])
def test_describe_json_names_the_convention_of_each_d(tmp_path, scaling):
    from warptrunc.fractal import box_counting, fractal_dimension, self_affine_surface

    s = self_affine_surface(0.5, n=128, L=1e-3, Rrms=1e-6, seed=3)
    warptrunc.write_height_map(s, tmp_path / "s.npz")
    r = cli(
        "describe",
        "s.npz",
        "--json",
        "-",
        "--height-scaling",
        scaling,
        "--device",
        "cpu",
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["convention_tri"] == d["convention_box"] == scaling
    assert d["convention_vs"] == d["convention_sp"] == "none"
    want = box_counting(s, height_scaling=scaling, device="cpu").D
    assert d["D_box"] == pytest.approx(want, abs=1e-12)
    tri = fractal_dimension(s, "tri", height_scaling=scaling, device="cpu").D
    assert d["D_tri"] == pytest.approx(tri, abs=1e-12)
    assert np.isfinite(d["D_vs"]) and np.isfinite(d["D_sp"])


def test_verbose_in_process_leaves_the_environment_as_it_was(tmp_path, monkeypatch):
    # main() called from a script or a test: --verbose must not outlive its command (a later
    # child process would inherit WARPTRUNC_VERBOSE and print Warp's notices)
    from warptrunc.cli import main

    monkeypatch.delenv("WARPTRUNC_VERBOSE", raising=False)
    assert main(["generate", "--n", "32", "-o", str(tmp_path / "s.npz"), "--verbose"]) == 0
    assert "WARPTRUNC_VERBOSE" not in os.environ
    monkeypatch.setenv("WARPTRUNC_VERBOSE", "0")
    assert main(["generate", "--n", "32", "-o", str(tmp_path / "t.npz"), "--verbose"]) == 0
    assert os.environ["WARPTRUNC_VERBOSE"] == "0"
