# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""README's commands stay true: the main job runs as a user would, the test job is CI's."""

import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def block_after(marker: str) -> str:
    text = (ROOT / "README.md").read_text()
    m = re.search(rf"<!-- {marker} -->\s*```bash\n(.+?)\n```", text, re.S)
    assert m, f"README.md has no command block after <!-- {marker} -->"
    return m.group(1).strip()


def test_main_job_runs_on_defaults(tmp_path):
    cmd = block_after("main-job")
    steps = [s.strip() for s in cmd.split("&&")]
    assert steps[0].startswith("python3 -m venv") and any(
        s.startswith("pip install") for s in steps
    )
    job = [s for s in steps if s.startswith("warptrunc ")]
    assert len(job) == 1, cmd
    argv = shlex.split(job[0])
    exe = shutil.which("warptrunc")
    prefix = [exe] if exe else [sys.executable, "-m", "warptrunc"]
    r = subprocess.run(prefix + argv[1:], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    out = tmp_path / argv[argv.index("--out") + 1]
    for name in ("curve.csv", "fit.json", "stiffness.png"):
        assert (out / name).stat().st_size > 0


def test_ci_runs_the_readme_test_command():
    cmd = block_after("test-job")
    ci = (ROOT / ".ci" / "run").read_text()
    assert cmd in ci
