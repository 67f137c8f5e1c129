# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Every module of the package (``warptrunc/`` and ``kernels/``) stays within 550 lines, the
mark the project keeps so that a module holds one concern: a module that outgrows it is split
where its concerns part (as ``warptrunc.stiffness`` into ``curve`` and ``fit``, and the
contact solver into ``solver``, ``loop`` and ``memory``)."""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LIMIT = 550
MODULES = sorted(
    [*ROOT.joinpath("warptrunc").rglob("*.py"), *ROOT.joinpath("kernels").rglob("*.py")]
)


def test_every_module_within_the_mark():
    assert len(MODULES) > 100  # the walk found the package, not an empty folder
    sizes = {p.relative_to(ROOT): len(p.read_text(encoding="utf-8").splitlines()) for p in MODULES}
    over = {str(p): n for p, n in sizes.items() if n > LIMIT}
    assert not over, f"modules over {LIMIT} lines (split them by concern): {over}"
