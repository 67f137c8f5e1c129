# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The contact solver spread over two devices (``contact_solver(..., devices=2)``,
:mod:`warptrunc.contact.sharded`) equals the one-device solver.

Two host devices (XLA's ``--xla_force_host_platform_device_count=2``, set below before JAX is
first imported; the module is skipped without JAX, and fails when JAX was started with one device).
The reference is the one-device solver with ``direct_max=0``, the same iteration (the sharded
solver transforms afresh where the one-device one may sum a few forces directly), and NumPy in
float64 for the displacements: loads and approaches within 1e-9 (float64) and 1e-5 (float32)
relative, the same contact pixels (float32: up to pixels whose pressure is within a few
tolerances of zero), the same iteration counts in float64.
"""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

if "jax" not in sys.modules:  # two host devices (JAX only; nothing else in the suite uses it)
    flags = os.environ.get("XLA_FLAGS", "")
    if "xla_force_host_platform_device_count" not in flags:
        os.environ["XLA_FLAGS"] = f"{flags} --xla_force_host_platform_device_count=2".strip()
    os.environ.setdefault("JAX_PLATFORMS", "cpu")  # on a GPU machine too: the host devices

jax = pytest.importorskip("jax")
if len(jax.devices("cpu")) < 2:
    # tests/conftest.py sets the flag before any module imports JAX: never skip silently
    raise RuntimeError("JAX was started with one host device before this module (XLA_FLAGS)")

from warptrunc.contact import (  # noqa: E402
    Adhesion,
    ContactSolver,
    SolverSettings,
    contact_solver,
    influence_spectrum,
)
from warptrunc.contact.sharded import ShardedContactSolver  # noqa: E402
from warptrunc.contact.sharded.fft import slab_layout  # noqa: E402
from warptrunc.contact.sharded.grid import devices_needed  # noqa: E402

pytestmark = pytest.mark.timeout(300)

DX, E = 1e-6, 1e9
TOL = {"float64": 1e-9, "float32": 1e-5}


def rough_map(n: int, seed: int = 1, rms: float = 1e-6) -> np.ndarray:
    """A self-affine random map (m), n × n."""
    rng = np.random.default_rng(seed)
    k2 = np.fft.fftfreq(n)[:, None] ** 2 + np.fft.rfftfreq(n)[None, :] ** 2
    spec = (rng.normal(size=k2.shape) + 1j * rng.normal(size=k2.shape)) * np.where(
        k2 > 0, k2, 1.0
    ) ** (-1.1)
    spec[0, 0] = 0
    h = np.fft.irfft2(spec, s=(n, n))
    return h / h.std() * rms


H256 = rough_map(256)
LOAD = 5e-4 * E * (256 * DX) ** 2  # about 2 % contact


def rel(a: float, b: float) -> float:
    return abs(a - b) / abs(a)


def same_contact(pa: np.ndarray, pb: np.ndarray, dtype: str) -> None:
    """The same contact pixels; in float32 up to pixels within a few tolerances of zero."""
    differ = (pa > 0) != (pb > 0)
    if dtype == "float64":
        assert not differ.any(), f"{int(differ.sum())} contact pixels differ"
    else:
        assert np.maximum(pa, pb)[differ].max(initial=0.0) < 1e-3 * E, "a loaded pixel differs"
        assert differ.sum() <= 4


def check_displacement(solver: ContactSolver) -> None:
    """NumPy in float64: the solver's u is K·q (the padded or periodic convolution) and the
    solution is one (no tension, gaps closed in contact to pentol)."""
    p, gap = solver.maps()
    q = p * DX * DX
    ny, nx = solver.shape
    grid = (2 * ny, 2 * nx) if solver.substrate == "free" else (ny, nx)
    w = influence_spectrum(solver.shape, (DX, DX), E, solver.substrate)
    u = np.fft.irfft2(np.fft.rfft2(q, s=grid) * w, s=grid)[:ny, :nx]
    h = np.asarray(solver.h).astype(np.float64)
    assert np.abs(u - (gap + h + solver.offset)).max() < 1e-9 * np.abs(u).max() + 1e-3 * (
        solver.pentol if solver.dtype == "float32" else 1e-6 * solver.pentol
    )
    assert p.min() >= 0.0
    assert np.abs(gap[p > 0]).max() < solver.pentol
    assert gap.min() > -solver.pentol


def test_convolution_is_two_all_to_alls_and_exact():
    """The sharded padded convolution: XLA compiles two all-to-alls and no gather of a map, and
    it equals NumPy's zero-padded (free) or periodic convolution with the same spectrum."""
    devices = tuple(jax.devices("cpu")[:2])
    shape = (64, 48)
    rng = np.random.default_rng(0)
    x = rng.random(shape)
    for substrate in ("free", "periodic"):
        lay = slab_layout(shape, substrate, "float64", devices)
        w = lay.build_spectrum((DX, 1.2 * DX), E)
        ref_w = influence_spectrum(shape, (DX, 1.2 * DX), E, substrate)
        nk = ref_w.shape[1]
        assert np.abs(np.asarray(w)[:, :nk] - ref_w[: w.shape[0]]).max() < 1e-12 * ref_w.max()
        fn = jax.jit(lambda a, s, lay=lay: lay.conv(a, s), out_shardings=lay.rows)
        xs = lay.put(x)
        text = fn.lower(xs, w).compile().as_text()
        assert text.count("all-to-all(") == 2
        assert "all-gather(" not in text
        grid = (2 * shape[0], 2 * shape[1]) if substrate == "free" else shape
        ref = np.fft.irfft2(np.fft.rfft2(x, s=grid) * ref_w, s=grid)[: shape[0], : shape[1]]
        got = fn(xs, w)
        assert got.sharding.spec[0] == "d"  # row slabs
        assert np.abs(np.asarray(got) - ref).max() < 1e-12 * np.abs(ref).max()
        # the column stage in blocks (large slabs): the same result, less temporary memory
        blocked = slab_layout(shape, substrate, "float64", devices, 4)
        fb = jax.jit(lambda a, s, lay=blocked: lay.conv(a, s), out_shardings=lay.rows)
        assert np.abs(np.asarray(fb(xs, w)) - ref).max() < 1e-12 * np.abs(ref).max()
    temp = []
    for blocks in (1, 4):
        lay = slab_layout((256, 256), "free", "float32", devices, blocks)
        w = lay.build_spectrum((DX, DX), E)
        fn = jax.jit(lambda a, s, lay=lay: lay.conv(a, s), out_shardings=lay.rows)
        temp.append(fn.lower(lay.zeros(), w).compile().memory_analysis().temp_size_in_bytes)
    assert temp[1] < 0.8 * temp[0]


@pytest.mark.parametrize("dtype", ["float64", "float32"])
@pytest.mark.parametrize("substrate", ["free", "periodic"])
def test_elastic_equals_one_device(substrate, dtype):
    """Load control, then displacement control, then Barber's stiffness: the same numbers as
    the one-device solver."""
    st = SolverSettings(substrate=substrate, dtype=dtype)
    one = ContactSolver(H256, DX, E, device="cpu", settings=st.replace(direct_max=0))
    two = contact_solver(H256, DX, E, devices=2, settings=st)
    assert isinstance(two, ShardedContactSolver)
    tol = TOL[dtype]
    a, b = one.solve(load=LOAD), two.solve(load=LOAD)
    assert a.converged and b.converged
    assert rel(a.depth, b.depth) < tol
    assert rel(a.mean_gap, b.mean_gap) < 10 * tol
    if dtype == "float64":
        assert (a.n_iterations, a.n_convolutions) == (b.n_iterations, b.n_convolutions)
        check_displacement(two)
    same_contact(one.maps()[0], two.maps()[0], dtype)
    depth = 1.3 * a.depth
    a, b = one.solve(depth), two.solve(depth)
    assert a.converged and b.converged
    assert rel(a.load, b.load) < tol
    assert abs(a.n_contact - b.n_contact) <= (0 if dtype == "float64" else 4)
    same_contact(one.maps()[0], two.maps()[0], dtype)
    assert rel(one.max_pressure(), two.max_pressure()) < tol
    ka, kb = one.punch_stiffness(), two.punch_stiffness()
    assert ka[2] and kb[2]
    assert rel(ka[0], kb[0]) < tol


@pytest.mark.parametrize(
    ("substrate", "dtype", "load_control"),
    [("free", "float64", "offset"), ("periodic", "float64", "secant")],
)
def test_capped_equals_one_device(substrate, dtype, load_control):
    """Elastic–plastic (a pressure cap at H): loading flows the surface, unloading is elastic;
    the plastic state equals the one-device solver's."""
    st = SolverSettings(substrate=substrate, dtype=dtype, load_control=load_control)
    hardness = 2e-2 * E
    direct = st.replace(direct_max=0)
    one = ContactSolver(H256, DX, E, device="cpu", hardness=hardness, settings=direct)
    two = contact_solver(H256, DX, E, devices=["cpu:0", "cpu:1"], hardness=hardness, settings=st)
    tol = TOL[dtype]
    peak = None
    for load in (LOAD, 0.5 * LOAD):
        a, b = one.solve(load=load), two.solve(load=load)
        peak = peak or a.depth
        assert a.converged and b.converged
        assert rel(a.depth, b.depth) < tol
        assert a.n_plastic == b.n_plastic
        assert rel(a.plastic_volume, b.plastic_volume) < 10 * tol
    assert a.n_plastic == b.n_plastic == 0  # unloading was elastic
    wa, wb = one.plastic_displacement(), two.plastic_displacement()
    assert wa.max() > 0
    assert np.abs(wa - wb).max() < 10 * tol * wa.max()
    a, b = one.solve(1.1 * peak), two.solve(1.1 * peak)  # displacement control, capped
    assert a.n_plastic > 0 and rel(a.load, b.load) < tol
    assert rel(a.plastic_volume, b.plastic_volume) < 10 * tol


def test_blocked_columns_equal_one_device(monkeypatch):
    """The column stage in blocks (chosen for large slabs, forced here): the same solve."""
    import warptrunc.contact.sharded.grid as sf

    monkeypatch.setattr(sf, "BLOCKS_ABOVE", 0)
    one = ContactSolver(H256, DX, E, device="cpu", settings=SolverSettings(direct_max=0))
    two = contact_solver(H256, DX, E, devices=2)
    assert two.hs.layout.blocks == sf.COLUMN_BLOCKS
    a, b = one.solve(load=LOAD), two.solve(load=LOAD)
    assert rel(a.depth, b.depth) < 1e-9 and a.n_iterations == b.n_iterations


def test_default_direct_max_agrees():
    """Against the one-device solver's defaults (direct summation of a few forces), the same
    answer to round-off here too (free, float64)."""
    one = ContactSolver(H256, DX, E, device="cpu")
    two = contact_solver(H256, DX, E, devices=2)
    a, b = one.solve(load=LOAD), two.solve(load=LOAD)
    assert rel(a.depth, b.depth) < 1e-9


def test_devices_argument():
    """What ``devices`` accepts, and the messages for what it does not."""
    assert type(ContactSolver(H256[:64, :64], DX, E, devices=1)) is ContactSolver
    assert type(ContactSolver(H256[:64, :64], DX, E, devices=["cpu:0"])) is ContactSolver
    assert type(ContactSolver(H256[:64, :64], DX, E, devices="auto")) is ContactSolver  # fits
    two = contact_solver(H256[:64, :64], DX, E, devices=jax.devices("cpu")[:2])
    assert type(two) is ShardedContactSolver and len(two.hs.devices) == 2
    bad = [
        (0, "count ≥ 1, got 0"),
        (3, r"devices must be in \[1, 2\]"),
        ("many", "devices must be None, 'auto'"),
        (["cpu:0", "cpu:0"], "must not repeat"),
        (["cpu:7", "cpu:0"], "out of range"),
        (["abc:0", "cpu:0"], "unknown device name"),
    ]
    for value, match in bad:
        with pytest.raises(ValueError, match=match):
            contact_solver(H256[:64, :64], DX, E, devices=value)
    # the one-device class refuses several devices and names the function that spreads
    with pytest.raises(ValueError, match=r"spreads the map over several devices.*contact_solver"):
        ContactSolver(H256[:64, :64], DX, E, devices=2)
    with pytest.raises(ValueError, match="runs on one device"):
        law = Adhesion("maugis", work=0.05, range=2e-9)
        contact_solver(H256[:64, :64], DX, E, devices=2, settings=SolverSettings(adhesion=law))
    with pytest.raises(ValueError, match="must divide ny; got 2"):
        contact_solver(H256[:63, :64], DX, E, devices=2)
    with pytest.raises(ValueError, match=r"settings\.algorithm must be 'bccg'"):
        contact_solver(H256[:64, :64], DX, E, devices=2, settings=SolverSettings(algorithm="pk"))


def test_auto_spreads_what_does_not_fit(monkeypatch):
    """``devices="auto"``: one device while the solver fits its free memory, else the fewest
    devices that hold it (here both host devices: JAX reports no limit on the CPU)."""
    import warptrunc._support.device as support

    h = H256[:64, :64]
    assert type(ContactSolver(h, DX, E, devices="auto")) is ContactSolver
    monkeypatch.setattr(support, "free_memory_bytes", lambda device: 1000)
    two = contact_solver(h, DX, E, devices="auto")
    assert type(two) is ShardedContactSolver and len(two.hs.devices) == 2
    assert two.solve(load=1e-3 * LOAD).converged


def test_memory_bytes_per_device():
    """``memory_bytes(..., devices=n)``: each device's share shrinks with n; ``devices_needed``
    inverts it; a bad count is refused."""
    shape = (16384, 16384)
    one = ContactSolver.memory_bytes(shape, "free", "float32")
    per = [ContactSolver.memory_bytes(shape, "free", "float32", devices=n) for n in (2, 4, 8)]
    assert per[0] > per[1] > per[2]
    assert 0.4 < per[1] / per[0] < 0.6 and per[0] < 1.5 * one
    assert devices_needed(shape, "free", "float32", per[1]) == 4
    assert devices_needed(shape, "free", "float32", per[1] - 1) == 8
    with pytest.raises(ValueError, match="devices must be an integer ≥ 1, got 0"):
        ContactSolver.memory_bytes(shape, devices=0)


@pytest.mark.parametrize(
    ("substrate", "dtype", "blocked"),
    [("free", "float32", False), ("periodic", "float32", False), ("free", "float64", True)],
)
def test_memory_model_covers_the_compiled_steps(substrate, dtype, blocked, monkeypatch):
    """The per-device model is at least what XLA's compiled CG step and preconditioner need
    (arguments, results and temporaries of the CPU compile, plus the maps held beside them),
    and not far above."""
    import warptrunc.contact.sharded.grid as sf
    from warptrunc.contact.sharded.steps import make_step

    if blocked:
        monkeypatch.setattr(sf, "BLOCKS_ABOVE", 0)
    shape = (256, 256)
    blocks = sf.column_blocks(shape, substrate, dtype, 2)
    assert (blocks > 1) == blocked
    lay = slab_layout(shape, substrate, dtype, tuple(jax.devices("cpu")[:2]), blocks)
    w = lay.build_spectrum((DX, DX), E)
    x, mask = lay.zeros(), lay.zeros(np.bool_)
    slab = np.dtype(dtype).itemsize * shape[0] * shape[1] // 2

    def need(name, args, held_maps):
        m = make_step(lay, name).lower(*args).compile().memory_analysis()
        size = m.argument_size_in_bytes + m.output_size_in_bytes + m.temp_size_in_bytes
        return size + held_maps * slab

    # + h and the old z_old; t, q and u are donated on accelerators (their results reuse them)
    step = need("step", (x, 0.0, 0.0, mask, x, x, x, x, 1.0, 1e300, w), 2 - 3)
    pc = need("precondition", (x, x, mask, w), 4)  # + h, q, u, t
    model = ContactSolver.memory_bytes(shape, substrate, dtype, devices=2)
    assert max(step, pc) <= model < 1.5 * max(step, pc)


def test_jax_is_imported_lazily():
    """``import warptrunc`` and a one-device solve never import JAX."""
    code = (
        "import sys, numpy as np, warptrunc\n"
        "from warptrunc.contact import ContactSolver\n"
        "import warptrunc.contact.sharded\n"
        "ContactSolver(np.random.rand(16, 16) * 1e-6, 1e-6, 1e9, device='cpu').solve(1e-7)\n"
        "assert 'jax' not in sys.modules, 'jax imported'\n"
    )
    env = dict(os.environ, WARPTRUNC_DEVICE="cpu")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert out.returncode == 0, out.stderr[-2000:]


def test_solve_contact_and_bem_check_take_devices(tmp_path, capsys):
    """``solve_contact(..., devices=2)`` and ``warptrunc bem-check --devices 2`` give the
    one-device numbers; a bad ``--devices`` is refused in one line."""
    import json

    from cli_helpers import assert_refused_in_one_line

    from warptrunc.cli import main
    from warptrunc.contact import solve_contact
    from warptrunc.material import Material

    h = H256[:64, :64]
    kw = {"pixel_size": DX, "material": Material(E=E, nu=0.0), "depths": [0.3e-6, 0.5e-6]}
    one = solve_contact(h, device="cpu", **kw)
    two = solve_contact(h, devices=2, **kw)
    assert two.settings["device"] == "cpu:0+cpu:1" and one.settings["device"] == "cpu"
    assert np.all(np.abs(one.load - two.load) < 1e-9 * one.load)
    assert np.all(np.abs(one.stiffness - two.stiffness) < 1e-9 * one.stiffness)
    loads = []
    for devices in ("1", "2"):
        out = tmp_path / f"bem{devices}"
        args = [
            "bem-check",
            "--n",
            "64",
            "--device",
            "cpu",
            "--stiffness",
            "barber",
            "--fractions",
            "0.1",
            "0.2",
            "--devices",
            devices,
            "--no-plot",
        ]
        assert main([*args, "--out", str(out)]) == 0
        cols = json.loads((out / "bem.json").read_text())["columns"]
        loads.append(np.array(cols["bem_load_N"] + cols["bem_stiffness_N_per_m"], float))
    capsys.readouterr()
    assert np.all(np.abs(loads[0] - loads[1]) <= 1e-9 * loads[0])
    assert_refused_in_one_line(
        ["bem-check", "--n", "64", "--devices", "0"],
        tmp_path / "bad",
        capsys,
        ["--devices", "[1, 64]", "'auto'"],
    )


def test_spectrum_in_pieces_equals_one_piece(monkeypatch):
    """The kernel spectrum built in pieces (rows of the x stage, columns of the y stage; forced
    small here) equals the one built in one piece (to round-off: XLA fuses the pieces
    differently), and the one-device solver's spectrum."""
    import warptrunc.contact.sharded.grid as sg
    import warptrunc.contact.sharded.spectrum as ss

    devs = tuple(jax.devices("cpu")[:2])
    shape = (128, 96)
    monkeypatch.setattr(sg, "BUILD_PIECE_BYTES", 1 << 62)
    whole = np.asarray(ss.build_spectrum(slab_layout(shape, "free", "float64", devs), (DX, DX), E))
    monkeypatch.setattr(sg, "BUILD_PIECE_BYTES", 3000)  # 1 row of the x stage, 1 column of y
    pieces = np.asarray(ss.build_spectrum(slab_layout(shape, "free", "float64", devs), (DX, DX), E))
    np.testing.assert_allclose(pieces, whole, rtol=0, atol=1e-13 * whole.max())  # last bits
    ref = influence_spectrum(shape, (DX, DX), E, substrate="free")  # (2ny, nx + 1), numpy f64
    nk = shape[1] + 1
    np.testing.assert_allclose(
        pieces[:, :nk], np.asarray(ref)[: shape[0] + 1], rtol=0, atol=1e-12 * whole.max()
    )
    assert np.all(pieces[:, nk:] == 1.0)


def test_spectrum_build_fits_the_model_at_65536():
    """XLA's memory of the spectrum's build for a 65536² float32 map over two devices (compiled
    for the CPU, not run): within the model (``build_bytes``), which is below the solve's own
    per-device peak; the build in one piece (the cause of the out-of-memory error on 4 × H200)
    needed more than the model allows."""
    import warptrunc.contact.sharded.grid as sg
    import warptrunc.contact.sharded.spectrum as ss

    shape, devs = (65536, 65536), tuple(jax.devices("cpu")[:2])
    lay = slab_layout(shape, "free", "float32", devs, 4)

    def compiled(piece_bytes):
        old = sg.BUILD_PIECE_BYTES
        sg.BUILD_PIECE_BYTES = piece_bytes
        try:
            m = ss.spectrum_programme(lay, (DX, DX), E).lower().compile().memory_analysis()
        finally:
            sg.BUILD_PIECE_BYTES = old
        return m.temp_size_in_bytes + m.output_size_in_bytes

    model = sg.build_bytes(shape, "free", "float32", 2)
    assert compiled(sg.BUILD_PIECE_BYTES) <= model < 1.5 * compiled(sg.BUILD_PIECE_BYTES)
    assert model < ContactSolver.memory_bytes(shape, "free", "float32", devices=2)
    assert compiled(1 << 62) > 1.3 * model


def _fft_sizes(text: str) -> list[int]:
    """Elements of the larger operand (input or output) of every FFT in a lowered programme."""
    import re

    sizes = []
    for line in text.splitlines():
        if "stablehlo.fft" in line:
            shapes = re.findall(r"tensor<([\dx]+)x(?:f32|f64|complex<f\d\d>)>", line)
            sizes.append(max(int(np.prod([int(d) for d in s.split("x")])) for s in shapes))
    return sizes


def test_fft_calls_stay_below_2_31_elements_at_65536(monkeypatch):
    """No FFT call of the 65536² convolution over two devices (lowered for the CPU, not run)
    holds 2³¹ elements or more: XLA's GPU FFT leaves such an inverse transform unscaled
    (openxla/xla#45009), which made a 65536² solve on 4 × H200 about 10⁵ times too
    compliant. Without the row blocks the same programme has such calls."""
    import warptrunc.contact.sharded.fft as sf
    import warptrunc.contact.sharded.grid as sg

    shape, devs = (65536, 65536), tuple(jax.devices("cpu")[:2])
    big_y, _, _, nkp = sg._grid(shape, "free", 2)

    def sizes():
        lay = sf.SlabLayout(
            shape, "free", "float32", devs, sg.column_blocks(shape, "free", "float32", 2)
        )
        x = jax.ShapeDtypeStruct(shape, np.float32, sharding=lay.rows)
        w = jax.ShapeDtypeStruct((big_y // 2 + 1, nkp), np.float32, sharding=lay.cols)
        fn = jax.jit(lambda a, b: lay.conv(a, b, inverse=False), out_shardings=lay.rows)
        return _fft_sizes(fn.lower(x, w).as_text())

    ok = sizes()
    assert len(ok) == 4 and max(ok) <= sg.FFT_ELEMENTS_MAX < 2**31
    monkeypatch.setattr(sg, "FFT_ELEMENTS_MAX", 1 << 62)
    assert max(sizes()) >= 2**31


def test_blocked_rows_equal_one_device(monkeypatch):
    """Row (and column) transforms in blocks, forced by a small FFT_ELEMENTS_MAX: the same
    solve as one device."""
    import warptrunc.contact.sharded.grid as sg

    monkeypatch.setattr(sg, "FFT_ELEMENTS_MAX", 1 << 12)
    assert sg.row_blocks(128, 512) == 16 and sg.row_blocks(100, 512) == 20
    one = ContactSolver(H256, DX, E, device="cpu", settings=SolverSettings(direct_max=0))
    two = contact_solver(H256, DX, E, devices=2)
    assert two.hs.layout.blocks > 1
    a, b = one.solve(load=LOAD), two.solve(load=LOAD)
    assert rel(a.depth, b.depth) < 1e-9 and a.n_iterations == b.n_iterations


@pytest.mark.parametrize(("substrate", "dtype"), [("free", "float64"), ("periodic", "float32")])
def test_unit_force_check(substrate, dtype, monkeypatch):
    """The half-space's own check at construction (a unit force against the closed form):
    passes for the real convolution, and raises when the convolution is 131072 times too
    large, as XLA's unscaled inverse FFT of 2³¹ elements made it."""
    import warptrunc.contact.sharded.fft as sf
    from warptrunc.contact.sharded.spectrum import unit_force_check

    shape = (128, 96)
    hs = sf.ShardedHalfSpace(
        shape, (DX, 2 * DX), E, substrate=substrate, dtype=dtype, devices=jax.devices("cpu")[:2]
    )
    assert hs.check < (1e-4 if dtype == "float32" else 1e-12)
    wrong = sf.ShardedHalfSpace(
        shape, (DX, 3 * DX), E, substrate=substrate, dtype=dtype, devices=jax.devices("cpu")[:2]
    )
    real = wrong.apply
    monkeypatch.setattr(wrong, "apply", lambda x, **kw: real(x, **kw) * 131072)
    with pytest.raises(RuntimeError, match=r"fails its check.*closed form"):
        unit_force_check(wrong, (DX, 4 * DX), E)
