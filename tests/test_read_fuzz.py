# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Issue 30: a byte-flipping fuzz of the readers. Damaged copies of valid files (each built-in
format, a generated Wyko OPD, and the measured scans when present) must read, or raise
ValueError/OSError with one short line that names the file — never another exception, never a
hang.

Outside CI every run draws a fresh seed (printed on failure: ``WARPTRUNC_FUZZ_SEED=N`` repeats
it); under CI (``CI`` set) the seed is fixed, so a landing never depends on the draw.
"""

from __future__ import annotations

import os
import signal
import warnings
from pathlib import Path

import numpy as np
import pytest

from warptrunc._support.messages import MAX_MESSAGE_CHARS
from warptrunc.io import read_scan, write_height_map

SEED = int(
    os.environ.get("WARPTRUNC_FUZZ_SEED")
    or (20260 if os.environ.get("CI") else np.random.SeedSequence().entropy % 2**32)
)
MUTANTS = 25
"""Damaged copies per source file."""
TIMEOUT_S = 30
"""Longest a single read may take before it counts as a hang (s)."""


class Hang(Exception):
    pass


def _alarm(signum, frame):
    raise Hang


def sources(tmp: Path, scans: Path | None) -> list[Path]:
    """Valid files of every format the readers know (small)."""
    from warptrunc import from_heights

    rng = np.random.default_rng(0)
    z = rng.normal(size=(12, 10)) * 1e-6
    s = from_heights(z, 1e-6)
    out = [
        write_height_map(s, tmp / "w.npz"),
        write_height_map(s, tmp / "w.npy"),
        write_height_map(s, tmp / "w.csv"),
    ]
    np.save(tmp / "plain.npy", z)
    np.savez(tmp / "plain.npz", heights=z)
    np.savetxt(tmp / "m.txt", z, header="dx = 1 um")
    iy, ix = np.mgrid[0:6, 0:7]
    np.savetxt(tmp / "xyz.txt", np.column_stack([ix.ravel(), iy.ravel(), rng.normal(size=42)]))
    out += [tmp / "plain.npy", tmp / "plain.npz", tmp / "m.txt", tmp / "xyz.txt"]
    try:
        import SurfaceTopography  # noqa: F401
    except ImportError:
        return out
    from test_clean_failures import opd_bytes

    (tmp / "g.opd").write_bytes(opd_bytes(24, 16))
    out.append(tmp / "g.opd")
    if scans is not None:
        out += [p for p in sorted(scans.iterdir()) if p.suffix != ".md" and p.stat().st_size < 4e6]
    return out


def mutate(data: bytes, rng: np.random.Generator) -> bytes:
    """One damage: flipped bytes, a cut, a zeroed block, a removed or repeated chunk."""
    b = bytearray(data)
    n = len(b)
    kind = rng.integers(5)
    if kind == 0:  # flip 1–8 bytes
        for i in rng.integers(0, n, size=rng.integers(1, 9)):
            b[i] ^= int(rng.integers(1, 256))
    elif kind == 1:  # cut
        b = b[: int(rng.integers(0, n))]
    elif kind == 2:  # zero a block
        i = int(rng.integers(0, n))
        j = min(n, i + int(rng.integers(1, 64)))
        b[i:j] = bytes(j - i)
    elif kind == 3:  # remove a chunk
        i = int(rng.integers(0, n))
        del b[i : i + int(rng.integers(1, 256))]
    else:  # repeat a chunk
        i = int(rng.integers(0, n))
        b[i:i] = b[i : i + int(rng.integers(1, 256))]
    return bytes(b)


@pytest.fixture(scope="module", autouse=True)
def _quiet_import():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ImportWarning)
        try:
            import SurfaceTopography  # noqa: F401
        except ImportError:
            pass


@pytest.mark.filterwarnings("ignore::ResourceWarning")  # SurfaceTopography leaves a handle open
@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
def test_damaged_files_read_or_fail_with_one_short_line(tmp_path, request):
    from conftest import SCANS

    scans = SCANS if SCANS.is_dir() else None
    rng = np.random.default_rng(SEED)
    old = signal.signal(signal.SIGALRM, _alarm)
    bad = []
    try:
        for src in sources(tmp_path, scans):
            data = src.read_bytes()
            side = src.with_suffix(".json")  # the .npy sidecar travels with it
            for k in range(MUTANTS):
                f = tmp_path / "fuzz" / f"{k}{src.suffix}"
                f.parent.mkdir(exist_ok=True)
                f.write_bytes(mutate(data, rng))
                if src.suffix == ".npy" and side.exists():
                    f.with_suffix(".json").write_bytes(side.read_bytes())
                signal.alarm(TIMEOUT_S)
                try:
                    with warnings.catch_warnings():
                        warnings.simplefilter("error")  # a RuntimeWarning is a failure too
                        warnings.simplefilter("ignore", ResourceWarning)
                        read_scan(f, dx=1e-6)
                except (ValueError, OSError) as exc:
                    msg = str(exc)
                    if "\n" in msg or len(msg) > MAX_MESSAGE_CHARS or str(f) not in msg:
                        bad.append((src.name, k, f"{type(exc).__name__}: {msg[:300]!r}"))
                except Hang:
                    bad.append((src.name, k, f"no answer in {TIMEOUT_S} s"))
                except Exception as exc:  # noqa: BLE001 - what the test is looking for
                    bad.append((src.name, k, f"{type(exc).__name__}: {str(exc)[:300]!r}"))
                finally:
                    signal.alarm(0)
    finally:
        signal.signal(signal.SIGALRM, old)
    assert not bad, f"WARPTRUNC_FUZZ_SEED={SEED}: {bad[:10]}"
