# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The suite writes no cache of the user's: matplotlib's folder is a temporary one of the run
(``tests/conftest.py``), complete before the first test, and a child process under a file-size
limit (as ``test_all_or_nothing.py`` runs the commands) reads it without writing."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib


def test_matplotlib_uses_a_folder_of_the_run_not_the_users():
    folder = Path(os.environ["MPLCONFIGDIR"])
    assert Path(matplotlib.get_configdir()) == folder
    assert Path(matplotlib.get_cachedir()) == folder
    assert folder.is_relative_to(Path(tempfile.gettempdir()))
    assert folder != Path.home() / ".cache" / "matplotlib"


def test_the_font_cache_is_built_and_complete_before_the_tests():
    caches = sorted(Path(os.environ["MPLCONFIGDIR"]).glob("fontlist-*.json"))
    assert len(caches) == 1
    json.loads(caches[0].read_text())  # whole JSON, not a file cut mid-write


def test_a_child_under_a_file_size_limit_writes_nothing(tmp_path):
    folder = Path(os.environ["MPLCONFIGDIR"])
    before = {p.name: p.stat().st_mtime_ns for p in folder.iterdir()}
    code = (
        "import resource; resource.setrlimit(resource.RLIMIT_FSIZE, (8192, 8192))\n"
        "import matplotlib; matplotlib.use('Agg')\n"
        "import matplotlib.font_manager, matplotlib.pyplot as plt\n"
        "f = plt.figure(); f.text(0.5, 0.5, 'x'); f.canvas.draw()\n"
    )
    r = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=120
    )
    assert r.returncode == 0, r.stderr
    assert "Could not save font_manager cache" not in r.stderr
    after = {p.name: p.stat().st_mtime_ns for p in folder.iterdir()}
    assert after == before
