# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""``--devices`` on the commands that solve contact (``compare``, ``indent``, ``sweep
--bem-fractions``; ``bem-check`` in ``tests/test_sharded.py``): a tiny run on two host devices
equals the same run on one (the one-device Warp solver on the CPU: an independent code path),
loads and stiffnesses within 1e-9 relative in float64; the combinations that are not supported
are refused in one line naming the option and the value.

Two host devices as in ``tests/test_sharded.py`` (``--xla_force_host_platform_device_count=2``
set before JAX is first imported; skipped without JAX, and fails when JAX was started with one).
"""

from __future__ import annotations

import os
import sys

import numpy as np
import pytest

if "jax" not in sys.modules:  # two host devices (JAX only; nothing else in the suite uses it)
    flags = os.environ.get("XLA_FLAGS", "")
    if "xla_force_host_platform_device_count" not in flags:
        os.environ["XLA_FLAGS"] = f"{flags} --xla_force_host_platform_device_count=2".strip()
    os.environ.setdefault("JAX_PLATFORMS", "cpu")

jax = pytest.importorskip("jax")
if len(jax.devices("cpu")) < 2:
    # tests/conftest.py sets the flag before any module imports JAX: never skip silently
    raise RuntimeError("JAX was started with one host device before this module (XLA_FLAGS)")

from cli_helpers import assert_refused_in_one_line, compare_cli  # noqa: E402

from warptrunc.cli import main  # noqa: E402

pytestmark = pytest.mark.timeout(300)

TOL = 1e-9  # float64, relative


def close(a, b, what: str) -> None:
    """Arrays equal within TOL relative to the larger magnitude (NaN where both are NaN)."""
    a, b = np.asarray(a, np.float64), np.asarray(b, np.float64)
    assert np.array_equal(np.isnan(a), np.isnan(b)), what
    ok = ~np.isnan(a)
    scale = np.maximum(np.abs(a[ok]), np.abs(b[ok]))
    assert np.all(np.abs(a[ok] - b[ok]) <= TOL * scale), f"{what}: {a} vs {b}"


def run_both(tmp_path, capsys, args: list[str]) -> list:
    """``warptrunc ARGS --devices 1`` and ``--devices 2`` into two folders."""
    outs = []
    for devices in ("1", "2"):
        out = tmp_path / f"dev{devices}"
        assert main([*args, "--device", "cpu", "--devices", devices, "--out", str(out)]) == 0
        outs.append(out)
    capsys.readouterr()
    return outs


def test_compare_devices(tmp_path, capsys):
    """``compare --devices 2``: the elastic route's loads, areas and stiffnesses of a 64² WM
    map equal the one-device solver's; the rows name both devices."""
    import pandas as pd

    args = compare_cli("2.5", "64", "0")
    one, two = (
        pd.concat(pd.read_parquet(p) for p in sorted((o / "cases").glob("*.parquet")))
        for o in run_both(tmp_path, capsys, args)
    )
    assert len(one) == 2 and one["converged"].all() and two["converged"].all()
    for col in ("bem_load_N", "bem_stiffness_N_per_m", "bem_area_m2"):
        close(one[col], two[col], col)
    assert (one[["bem_load_N", "bem_area_m2"]] > 0).all().all()
    assert set(two["device"]) == {"cpu:0+cpu:1"} and set(one["device"]) == {"cpu"}


def test_indent_devices(tmp_path, capsys):
    """``indent --devices 2``: capped (H = 1 GPa, plastic flow) and elastic cycles, refined once
    (the refined window solved over the devices too), equal the one-device run."""
    import pandas as pd

    args = [
        "indent",
        "--n",
        "64",
        "--L",
        "1e-3",
        "--punch-diameters",
        "400e-6",
        "--peak-loads",
        "2",
        "8",
        "--placements",
        "1",
        "--refine-max",
        "2",
        "--no-plot",
        "--no-progress",
    ]
    one, two = (pd.read_csv(o / "indent.csv") for o in run_both(tmp_path, capsys, args))
    assert one["converged"].all() and two["converged"].all()
    assert (one["max_pressure_Pa"] == 1e9).all()  # the cap is reached: capped solves
    for col in (
        "displacement_m",
        "unloading_stiffness_N_per_m",
        "partial_unloading_stiffness_N_per_m",
        "plastic_volume_m3",
        "elastic_displacement_m",
        "elastic_unloading_stiffness_N_per_m",
        "elastic_partial_unloading_stiffness_N_per_m",
        "max_pressure_Pa",
    ):
        close(one[col], two[col], col)
    for col in ("n_contact_pixels", "elastic_n_contact_pixels", "pixel_size_m"):
        assert (one[col] == two[col]).all(), col


def test_punch_window_rows_padded_for_the_devices():
    """A punch window with an odd number of rows on two devices: rows of its floor are added
    (they never touch), and the capped solve and Barber's stiffness equal the one-device ones
    on the window as it is."""
    from warptrunc.indent.cycles import make_solver
    from warptrunc.indent.punch import punch_window
    from warptrunc.material import Material

    rng = np.random.default_rng(3)
    z = rng.standard_normal((40, 40)) * 1e-7
    w = punch_window(z, 1e-6, 21e-6, (20e-6, 20e-6))
    assert w.heights.shape[0] % 2 == 1
    mat = Material(E=70e9, nu=0.33, hardness=1e9)
    one = make_solver(w, mat, device="cpu")
    two = make_solver(w, mat, devices=2)
    assert two.shape[0] == w.heights.shape[0] + 1 and one.shape == w.heights.shape
    load = 0.3 * 1e9 * np.pi * (10.5e-6) ** 2
    a, b = one.solve(load=load), two.solve(load=load)
    assert a.converged and b.converged and a.n_plastic > 0
    close(a.depth, b.depth, "approach")
    close(a.plastic_volume, b.plastic_volume, "plastic volume")
    close(one.punch_stiffness()[0], two.punch_stiffness()[0], "Barber's stiffness")


def test_sweep_devices(tmp_path, capsys):
    """``sweep --bem-fractions --devices 2``: the elastic columns equal the one-device run's,
    in process and on a Dask worker taking both host devices (``--workers 1 --devices 2``);
    more workers × devices than present, ``--devices auto`` with workers, or --devices without
    --bem-fractions, are refused in one line."""
    import pandas as pd

    args = [
        "sweep",
        "--D",
        "2.5",
        "--delta",
        "0.01",
        "--seeds",
        "0",
        "--n",
        "64",
        "--bem-fractions",
        "0.1",
        "0.2",
        "--no-progress",
    ]
    one, two = (pd.read_parquet(o / "cases.parquet") for o in run_both(tmp_path, capsys, args))
    assert one["bem_error"].isna().all() and two["bem_error"].isna().all()
    for f in ("0.1", "0.2"):
        assert one[f"bem_converged_{f}"].all() and two[f"bem_converged_{f}"].all()
        for q in ("F_bem_N", "k_bem_N_per_m", "A_bem_m2"):
            close(one[f"{q}_{f}"], two[f"{q}_{f}"], f"{q}_{f}")
    out = tmp_path / "worker"
    assert main([*args, "--devices", "2", "--workers", "1", "--out", str(out)]) == 0
    capsys.readouterr()
    grouped = pd.read_parquet(out / "cases.parquet")
    assert grouped["bem_error"].isna().all()
    for f in ("0.1", "0.2"):
        for q in ("F_bem_N", "k_bem_N_per_m", "A_bem_m2"):
            close(one[f"{q}_{f}"], grouped[f"{q}_{f}"], f"worker {q}_{f}")
    base = ["sweep", "--D", "2.5", "--delta", "0.01", "--n", "64", "--devices", "2"]
    assert_refused_in_one_line(
        [*base, "--bem-fractions", "0.1", "--workers", "2"],
        tmp_path / "bad1",
        capsys,
        ["2 × 2 = 4 devices", "2 cpu devices", "--workers 1"],
    )
    auto = [*base[:-1], "auto", "--bem-fractions", "0.1", "--workers", "1"]
    assert_refused_in_one_line(auto, tmp_path / "bad3", capsys, ["--devices auto", "a count"])
    assert_refused_in_one_line(base, tmp_path / "bad2", capsys, ["--devices 2", "--bem-fractions"])


def test_worker_groups(monkeypatch):
    """Worker i of a group size G takes devices i·G … i·G + G − 1 (modulo those present): its
    Warp device the first (CUDA), the group in WARPTRUNC_DEVICE_GROUP; a solve's
    ``devices=G`` in such a process is spread over that group."""
    from types import SimpleNamespace

    from warptrunc.contact.sharded.devices import choose_devices
    from warptrunc.sweep.cluster import PinDevice
    from warptrunc.sweep.groups import GROUP_ENV, group_size, worker_group

    assert worker_group(0, 4, 2) == ["cuda:0", "cuda:1"]
    assert worker_group(1, 4, 2) == ["cuda:2", "cuda:3"]
    assert worker_group("gpu-worker-3", 4, 2, "cpu") == ["cpu:2", "cpu:3"]
    with pytest.raises(ValueError, match="at most the 2 devices present, got 3"):
        worker_group(0, 2, 3)
    assert group_size(None) == 1 and group_size(2) == 2
    with pytest.raises(ValueError, match="give a count"):
        group_size("auto")
    for name in (GROUP_ENV, "WARPTRUNC_DEVICE"):  # recorded as they were, then removed: the
        monkeypatch.setenv(name, "")  # setups below write os.environ, restored after the test
        monkeypatch.delenv(name)
    PinDevice(n_devices=4, group=2, platform="cuda").setup(SimpleNamespace(name=1))
    assert os.environ[GROUP_ENV] == "cuda:2,cuda:3" and os.environ["WARPTRUNC_DEVICE"] == "cuda:2"
    monkeypatch.delenv("WARPTRUNC_DEVICE")
    PinDevice(n_devices=2, group=2, platform="cpu").setup(SimpleNamespace(name=0))
    assert os.environ[GROUP_ENV] == "cpu:0,cpu:1" and "WARPTRUNC_DEVICE" not in os.environ
    monkeypatch.setenv(GROUP_ENV, "cpu:1,cpu:0")  # the group's order is the slabs' order
    cpu = jax.devices("cpu")
    assert choose_devices(2, (64, 64)) == [cpu[1], cpu[0]]
    with pytest.raises(ValueError, match="names 2"):
        choose_devices(3, (63, 64))


def test_refusals_name_the_option(tmp_path, capsys):
    """What the sharded path does not run is refused, naming the option and the value:
    ``indent --algorithm pk``, ``bem-check --solver contactmechanics``, a bad count."""
    assert_refused_in_one_line(
        ["indent", "--n", "64", "--devices", "2", "--algorithm", "pk"],
        tmp_path / "a",
        capsys,
        ["--devices 2", "--algorithm pk"],
    )
    assert_refused_in_one_line(
        ["bem-check", "--n", "64", "--devices", "2", "--solver", "contactmechanics"],
        tmp_path / "b",
        capsys,
        ["--devices 2", "--solver warptrunc"],
    )
    for cmd in ("compare", "indent", "sweep"):
        assert_refused_in_one_line(
            [cmd, "--devices", "0"], tmp_path / cmd, capsys, ["--devices", "[1, 64]", "'auto'"]
        )


class XlaRuntimeError(RuntimeError):
    """Stands for jaxlib's error type (matched by its name, as the CLI does)."""


def test_xla_out_of_memory_ends_the_command(monkeypatch, capsys):
    """XLA's out-of-memory error in a spread solve: one line naming the allocation, exit 2, and
    the process ended at once (os._exit: the other devices may wait in a collective forever, as
    a 65536² run on 4 × H200 did); a ValueError after a spread solve returns normally."""
    import warptrunc.cli.bem_check as cmd
    import warptrunc.contact.sharded.devices as sd

    text = (
        "RESOURCE_EXHAUSTED: Out of memory while trying to allocate 60.81GiB.\n"
        "=== Source Location Trace: ===\nexternal/xla+/xla/stream_executor/cuda/x.cc:45"
    )

    def boom(args):
        raise XlaRuntimeError(text)

    ended = []
    monkeypatch.setattr(os, "_exit", lambda status: ended.append(status))
    monkeypatch.setattr(sd, "_SPREAD", {"used": True})
    monkeypatch.setattr(cmd, "run", boom)
    assert main(["bem-check", "--n", "64"]) == 2 and ended == [2]
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    for needle in ("bem-check: error: out of memory", "XLA asked for 60.81GiB", "--devices"):
        assert needle in err, (needle, err)
    assert "Source Location" not in err

    def bad(args):
        raise ValueError("n must be ≥ 64, got 1")

    monkeypatch.setattr(cmd, "run", bad)
    assert main(["bem-check", "--n", "64"]) == 2 and ended == [2]
    capsys.readouterr()
    assert sd.out_of_memory(ValueError(text)) is None  # not an XLA runtime error
    assert sd.out_of_memory(XlaRuntimeError("INTERNAL: x")) is None
