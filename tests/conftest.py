# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Shared fixtures: the ``device`` fixture runs a test on the CPU and on cuda:0 when present;
JAX, where a test uses it, starts with two host devices.

``WARPTRUNC_TEST_DEVICES=cpu`` (comma-separated) narrows the list.

The suite leaves the user's caches alone: matplotlib's configuration and font cache live in a
temporary folder of the run (``MPLCONFIGDIR``, inherited by every child process), built here
before any test starts, so a command that a test runs under a file-size limit finds the cache
complete and never writes it, and another matplotlib process holding the user's cache lock does
not matter. Warp's kernel cache stays shared (it is written atomically, one file per module).
"""

import atexit
import os
import shutil
import sys
import tempfile
from pathlib import Path

_MPL_DIR = tempfile.mkdtemp(prefix="warptrunc-tests-mpl-")
os.environ["MPLCONFIGDIR"] = _MPL_DIR
atexit.register(shutil.rmtree, _MPL_DIR, ignore_errors=True)

# Two host devices for the spread solver's tests (tests/test_sharded*.py), set before any module
# imports JAX: XLA reads the flag once, when JAX starts, so a test module that imported JAX first
# would otherwise leave those tests with one device.
if "jax" not in sys.modules and "xla_force_host_platform_device_count" not in os.environ.get(
    "XLA_FLAGS", ""
):
    os.environ["XLA_FLAGS"] = (
        os.environ.get("XLA_FLAGS", "") + " --xla_force_host_platform_device_count=2"
    ).strip()
    os.environ.setdefault("JAX_PLATFORMS", "cpu")  # the commands' default backend in those tests

import matplotlib
import pytest

matplotlib.use("Agg")
import matplotlib.font_manager  # noqa: E402, F401 - builds the font cache in _MPL_DIR now

import warptrunc


def _devices() -> list[str]:
    want = os.environ.get("WARPTRUNC_TEST_DEVICES")
    if want:
        return [d.strip() for d in want.split(",") if d.strip()]
    import warp as wp

    warptrunc.resolve_device("cpu")  # initialises Warp quietly
    return ["cpu"] + (["cuda:0"] if wp.get_cuda_device_count() > 0 else [])


DEVICES = _devices()


@pytest.fixture(params=DEVICES, ids=str)
def device(request) -> str:
    """A Warp device name: 'cpu' and, when present, 'cuda:0'."""
    return request.param


SCANS = Path(
    os.environ.get("WARPTRUNC_SCANS_DIR")
    or Path(__file__).resolve().parents[1].parent / "shared" / "data" / "scans"
)


@pytest.fixture
def cupy_on_cuda(request):
    """Skip a test parametrised on a CUDA device when CuPy (the ``gpu`` extra, cuFFT for the
    contact solver) is missing; modules that solve contact use it
    (``pytestmark = pytest.mark.usefixtures("cupy_on_cuda")``)."""
    params = getattr(getattr(request.node, "callspec", None), "params", {})
    if str(params.get("device", "")).startswith("cuda"):
        pytest.importorskip("cupy")


@pytest.fixture(scope="module")
def quiet_surfacetopography():
    """Import SurfaceTopography once with its ImportWarning (no mpi4py) silenced; modules that
    read scans use it (``pytestmark = pytest.mark.usefixtures("quiet_surfacetopography")``)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ImportWarning)
        try:
            import SurfaceTopography  # noqa: F401
        except ImportError:
            pass


@pytest.fixture
def scans_dir() -> Path:
    """../shared/data/scans beside the checkout (or $WARPTRUNC_SCANS_DIR); skips when absent
    (users' clones)."""
    if not SCANS.is_dir():
        pytest.skip(f"measured scans not found at {SCANS}")
    return SCANS
