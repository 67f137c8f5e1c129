# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The half-space's FFTs of the zero-padded grid (``warptrunc.contact.transforms``): the pruned
transforms against the full zero-padded ones (NumPy/SciPy), on every device, and the CUDA code
path's three cuFFT plans run against an emulation of cuFFT's advanced data layout on host
memory (so the layouts are checked in CI without a GPU)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from warptrunc.contact import influence_spectrum

E_STAR = 70e9 / (1 - 0.33**2)  # aluminium on a rigid flat (Pa)


pytestmark = pytest.mark.usefixtures("cupy_on_cuda")  # cuFFT on a CUDA device


def _load_map(hs, x, pixel, substrate, dtype):
    """x into the half-space's map buffer (zero pad); that buffer, the reference spectrum W,
    rfft2(x) on the padded grid and the relative tolerance of the dtype."""
    import scipy.fft

    buf, _ = hs.map_buffer()
    host = np.zeros(buf.shape, dtype=dtype)
    host[:, : x.shape[1]] = x
    buf.assign(host)
    w = influence_spectrum(x.shape, pixel, E_STAR, substrate)
    return buf, w, scipy.fft.rfft2(x, s=hs.grid), 1e-12 if dtype == "float64" else 2e-5


def _check_transforms(hs, buf, w, spec, tol):
    """K·x and K⁻¹·x of the half-space equal the full zero-padded transforms on the map."""
    import scipy.fft

    ny, nx = hs.shape
    for inverse, mult in ((False, w), (True, 1 / w)):
        ref = scipy.fft.irfft2(spec * mult, s=hs.grid)[:ny, :nx]
        got = hs.apply(buf, inverse=inverse).numpy()
        np.testing.assert_allclose(got, ref, rtol=0, atol=tol * np.abs(ref).max())


@pytest.mark.parametrize("dtype", ["float64", "float32"])
@pytest.mark.parametrize(
    ("substrate", "shape"), [("free", (48, 64)), ("free", (37, 50)), ("periodic", (48, 64))]
)
def test_pruned_transform_equals_full(device, substrate, shape, dtype):
    """K·x and K⁻¹·x by the pruned transforms (x rows of the map only, y over all columns; the
    inverse keeps the map's rows) equal the full zero-padded rfft2 → multiply → irfft2 restricted
    to the map, to round-off (float64: measured ≤ 8e-16 of the largest value; float32 1e-6)."""
    import scipy.fft

    from warptrunc.contact import ElasticHalfSpace

    ny, nx = shape
    pixel = (1e-6, 1.3e-6)
    hs = ElasticHalfSpace(shape, pixel, E_STAR, substrate=substrate, dtype=dtype, device=device)
    x = np.random.default_rng(0).random(shape)
    buf, w, spec, tol = _load_map(hs, x, pixel, substrate, dtype)
    _check_transforms(hs, buf, w, spec, tol)
    # the energy column: N·x·K·x by Parseval
    hs.apply(buf, energy_column=0)
    energy = hs.reduction.read((False,))[0] / hs.n_total
    ref = float(np.sum(x * scipy.fft.irfft2(spec * w, s=hs.grid)[:ny, :nx]))
    assert math.isclose(energy, ref, rel_tol=10 * tol)


class _EmulatedCuFFT:
    """Just enough of CuPy for ``ElasticHalfSpace``'s CUDA transforms, on host memory: the cuFFT
    plans' advanced data layout (element (b, x) at b·dist + x·stride) emulated with NumPy, so the
    layouts of the three plans are checked on the CPU."""

    CUFFT_R2C, CUFFT_C2R, CUFFT_C2C = 0x2A, 0x2C, 0x29
    CUFFT_D2Z, CUFFT_Z2D, CUFFT_Z2Z = 0x6A, 0x6C, 0x69
    CUFFT_FORWARD, CUFFT_INVERSE = -1, 1
    uint8 = np.uint8

    def __init__(self):
        import contextlib
        import types

        emu = self

        class PlanNd:
            def __init__(
                self,
                n,
                inembed,
                istride,
                idist,
                onembed,
                ostride,
                odist,
                kind,
                batch,
                order,
                last_axis,
                last_size,
            ):
                self.args = (n[0], istride, idist, ostride, odist, kind, batch)
                # a work area through the current allocator, as CuPy's PlanNd does
                self.work_area = emu.allocator(16 * n[0] * batch) if emu.allocator else None

            def fft(self, a, out, direction):
                n, istride, idist, ostride, odist, kind, batch = self.args
                single = kind in (emu.CUFFT_R2C, emu.CUFFT_C2R, emu.CUFFT_C2C)
                real, cplx = (np.float32, np.complex64) if single else (np.float64, np.complex128)
                src_t, dst_t = {
                    emu.CUFFT_R2C: (real, cplx),
                    emu.CUFFT_D2Z: (real, cplx),
                    emu.CUFFT_C2R: (cplx, real),
                    emu.CUFFT_Z2D: (cplx, real),
                }.get(kind, (cplx, cplx))
                n_in = n // 2 + 1 if src_t is cplx and dst_t is real else n
                n_out = n // 2 + 1 if src_t is real else n
                b, x = np.arange(batch)[:, None], np.arange(n_in)[None, :]
                src = emu.memory(a.data.ptr, src_t)[b * idist + x * istride].copy()
                if src_t is real:
                    res = np.fft.rfft(src, axis=1)
                elif dst_t is real:
                    res = np.fft.irfft(src, n=n, axis=1) * n
                elif direction == emu.CUFFT_FORWARD:
                    res = np.fft.fft(src, axis=1)
                else:
                    res = np.fft.ifft(src, axis=1) * n
                x = np.arange(n_out)[None, :]
                emu.memory(out.data.ptr, dst_t)[b * odist + x * ostride] = res

        class MemoryPointer:
            def __init__(self, mem, offset):
                self.ptr = mem.ptr + offset
                emu.size[self.ptr] = mem.size - offset

        self.size = {}
        self.allocator = None
        self.work_sizes = []

        @contextlib.contextmanager
        def using_allocator(fn):
            old, emu.allocator = emu.allocator, fn
            try:
                yield
            finally:
                emu.allocator = old

        self.cuda = types.SimpleNamespace(
            using_allocator=using_allocator,
            Device=lambda ordinal: contextlib.nullcontext(),
            UnownedMemory=lambda ptr, size, owner, device_id: types.SimpleNamespace(
                ptr=ptr, size=size, owner=owner
            ),
            MemoryPointer=MemoryPointer,
            cufft=types.SimpleNamespace(
                PlanNd=PlanNd, **{k: getattr(self, k) for k in dir(self) if k.startswith("CUFFT_")}
            ),
        )
        self.ndarray = lambda shape, dtype, memptr: types.SimpleNamespace(data=memptr)

    def memory(self, ptr, dtype):
        import ctypes

        n = self.size[ptr] // np.dtype(dtype).itemsize
        raw = (ctypes.c_byte * self.size[ptr]).from_address(ptr)
        return np.frombuffer(raw, dtype=dtype, count=n)


@pytest.mark.parametrize("dtype", ["float64", "float32"])
@pytest.mark.parametrize(("substrate", "shape"), [("free", (37, 50)), ("periodic", (48, 64))])
def test_cuda_transform_layouts_emulated(monkeypatch, substrate, shape, dtype):
    """The CUDA path of the pruned transforms (three cuFFT plans: batched row R2C, strided
    in-place column C2C, in-place row C2R into the spectrum's memory) run against an emulation of
    cuFFT's advanced layout on host memory: K·x and K⁻¹·x equal the full zero-padded transforms."""
    from warptrunc.contact import ElasticHalfSpace
    from warptrunc.contact import transforms as hsmod

    ny, nx = shape
    pixel = (1e-6, 1.3e-6)
    hs = ElasticHalfSpace(shape, pixel, E_STAR, substrate=substrate, dtype=dtype, device="cpu")
    hs._cp = (_EmulatedCuFFT(), None)
    monkeypatch.setattr(
        hsmod, "cupy_stream", lambda cupy, stream, ordinal: __import__("contextlib").nullcontext()
    )
    monkeypatch.setattr(hsmod.wp, "get_stream", lambda device: None)
    monkeypatch.setattr(hsmod, "_SLAB_MIN_BYTES", 1024)  # several slabs of two sizes
    x = np.random.default_rng(2).random(shape)
    buf, w, spec, tol = _load_map(hs, x, pixel, substrate, dtype)
    hs.work.fill_(hs.vec2(7.0, 7.0))  # the pad rows must be zeroed by the forward transform
    _check_transforms(hs, buf, w, spec, tol)
    plans, rows, cols = hs._plans
    assert len(rows) > 1 and len(cols) > 1
    # one work area, as large as the largest plan's, shared by all plans
    areas = {p.work_area.ptr for p in plans.values()}
    assert areas == {hs.fft_work.ptr}
    assert hs.fft_work.capacity == max(16 * p.args[0] * p.args[6] for p in plans.values())
