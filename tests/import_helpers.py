# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""What a fresh Python process has imported, for the start-up tests (not a test module)."""

import json
import subprocess
import sys
from pathlib import Path

__all__ = ["modules_after"]


def modules_after(code: str, cwd: Path) -> set[str]:
    """The top-level modules in ``sys.modules`` of a fresh Python process, started in ``cwd``,
    after it ran ``code`` (which must succeed)."""
    report = "import sys, json; print(json.dumps(sorted({m.split('.')[0] for m in sys.modules})))"
    r = subprocess.run(
        [sys.executable, "-c", f"{code}\n{report}"],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode == 0, r.stderr
    return set(json.loads(r.stdout.strip().splitlines()[-1]))
