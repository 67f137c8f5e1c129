# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""``import warptrunc`` from the folder that holds a clone named ``warptrunc``.

Python run there finds the clone's folder first (the current folder leads ``sys.path``); it has
no ``__init__.py``, so it is a namespace portion. A regular package anywhere on the path wins
over that portion; setuptools' default editable finder sits behind the path and loses to it
(``no attribute '__version__'``). README's editable install (``editable_mode=compat``) puts the
clone's folder itself on the path, as the ``.pth`` line that these tests write.
"""

import re
import subprocess
import sys
from pathlib import Path

import numpy

ROOT = Path(__file__).resolve().parents[1]
DEPS = str(Path(numpy.__file__).resolve().parents[1])  # site-packages holding the dependencies

PROBE = (
    "import sys, warptrunc, warptrunc.kernels; from warptrunc.kernels import truncation as _k; "
    "assert 'kernels' not in sys.modules, 'top-level kernels package'; "
    "print(warptrunc.__version__); print(warptrunc.__file__); print(_k.__file__)"
)


def _from_parent(tmp_path: Path, path: list[str]) -> subprocess.CompletedProcess:
    """Python in a folder that holds a clone named ``warptrunc`` (a link to this checkout),
    with ``-S`` (no ``.pth`` files of this venv) and ``path`` behind the current folder."""
    (tmp_path / "warptrunc").symlink_to(ROOT, target_is_directory=True)
    boot = f"import sys; sys.path[1:1] = {path!r}; "
    return subprocess.run(
        [sys.executable, "-S", "-c", boot + PROBE],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )


def test_the_compat_editable_path_wins_over_the_clone_folder(tmp_path):
    r = _from_parent(tmp_path, [str(tmp_path / "warptrunc"), DEPS])
    assert r.returncode == 0, r.stderr
    version, pkg, kern = r.stdout.strip().splitlines()[-3:]
    assert re.fullmatch(r"\d+\.\d+\.\d+\S*", version)
    assert Path(pkg) == tmp_path / "warptrunc" / "warptrunc" / "__init__.py"
    assert Path(kern).resolve() == ROOT / "kernels" / "truncation.py"


def test_without_the_clone_on_the_path_the_folder_is_an_empty_namespace(tmp_path):
    """What the default editable finder leaves: the failure the compat mode avoids."""
    r = _from_parent(tmp_path, [DEPS])
    assert r.returncode != 0 and "has no attribute '__version__'" in r.stderr, r.stderr


def test_readme_and_ci_install_in_compat_mode():
    readme = (ROOT / "README.md").read_text()
    block = re.search(r"<!-- test-job -->\s*```bash\n(.+?)\n```", readme, re.S).group(1)
    assert 'pip install -e ".[test]" --config-settings editable_mode=compat' in block
    assert block in (ROOT / ".ci" / "run").read_text()
