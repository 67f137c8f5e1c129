# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The figure process of ``warptrunc analyze`` (``warptrunc.plot._worker``, issue 40 item 4):
the same PNG bytes as drawing in the job's process, the drawing's errors raised in the job, a
lost helper replaced by drawing in-process, and ``analyze(on_curve=...)`` called once with the
result's curve before the island pass."""

import os
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace as N

import numpy as np
import pytest

from warptrunc.plot._worker import FigureProcessError, FigureWorker
from warptrunc.truncation.settings import TruncationSettings

ROOT = Path(__file__).resolve().parents[1]


def _curves():
    d = np.linspace(1e-9, 1e-6, 60)
    c = N(depth=d, Rt=1e-5, area_fraction=np.linspace(1e-4, 1e-2, 60))
    s = N(load=d, F_over_EA=d, Ec_over_E=np.sqrt(d))
    f = N(alpha=0.5, beta=1.0, r2=1.0, F_over_EA_min=1e-8, F_over_EA_max=1e-6)
    return c, s, f


def test_process_draws_the_same_bytes_and_raises_the_same_errors():
    c, s, f = _curves()
    with FigureWorker(process=True) as fw, FigureWorker(process=False) as here:
        assert not fw.in_process and here.in_process
        t = [fw.submit("area_fraction", c, log=True), fw.submit("stiffness_load", s, [f, f])]
        t.append(fw.submit("stiffness_load", s, f, title="R$_t$ = 1 µm"))
        h = here.submit("area_fraction", c, log=True)
        assert fw.result(t[0]) == here.result(h)
        with pytest.raises(ValueError, match="need one fit") as err:
            fw.result(t[1])  # two fits for one curve: the figure's own error
        assert isinstance(err.value.__cause__, FigureProcessError)
        assert fw.result(t[2])[:4] == b"\x89PNG"  # the helper goes on after an error


def test_lost_process_is_replaced_by_drawing_here():
    c, _, _ = _curves()
    with FigureWorker(process=True) as fw:
        fw._proc.kill()
        fw._proc.wait()
        t = fw.submit("area_fraction", c, log=True)
        assert fw.result(t)[:4] == b"\x89PNG"
        assert fw.in_process


def test_analyze_figures_equal_in_and_out_of_process(tmp_path):
    """The whole job, in fresh processes: the figure process and in-process drawing write the
    same files."""
    outs = {}
    for mode in ("1", "0"):
        out = tmp_path / f"o{mode}"
        env = {**os.environ, "WARPTRUNC_FIGURE_PROCESS": mode}
        cmd = [
            sys.executable,
            "-m",
            "warptrunc",
            "analyze",
            "--n",
            "128",
            "--device",
            "cpu",
            "--out",
            str(out),
        ]
        r = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, r.stderr
        outs[mode] = out
    for name in ("stiffness.png", "area_fraction.png", "curve.csv"):
        assert (outs["1"] / name).read_bytes() == (outs["0"] / name).read_bytes(), name


def test_on_curve_gets_the_result_curve_once():
    from warptrunc.analysis import analyze
    from warptrunc.wm_params import WMSpec

    seen = []
    a = analyze(
        WMSpec(n=128), truncation=TruncationSettings(50), on_curve=seen.append, device="cpu"
    )
    assert len(seen) == 1 and seen[0] is a.curve
