# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Make ``warptrunc.kernels`` importable from a source checkout.

The Warp kernels live in the top-level folder ``kernels/`` of the repository and are installed
as the sub-package ``warptrunc.kernels`` (``package-dir`` in ``pyproject.toml``). An installed
copy (``pip install .``) therefore has ``site-packages/warptrunc/kernels/``, and an editable
install maps the name through setuptools' import finder. But Python puts the current folder
first on ``sys.path`` (``python -c``, ``python -m pytest``, a REPL), so from the repository
root the *source* folder ``warptrunc/`` shadows any installed copy, and it has no
``kernels/`` inside: ``ModuleNotFoundError: No module named 'warptrunc.kernels'``.

:func:`map_source_kernels` closes that gap. When ``warptrunc`` is imported from a folder that
has no ``kernels/`` of its own and the folder beside it (the repository root) has
``kernels/__init__.py``, it registers that folder as ``warptrunc.kernels`` before anything
imports it; its sub-packages (``kernels/contact/`` → ``warptrunc.kernels.contact``) are found
through the registered package's path, as in an installed copy. An installed copy (which has
``warptrunc/kernels/``) is left alone, and a top-level ``kernels`` package is never created.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path


def map_source_kernels(package: str, package_path: list[str]) -> bool:
    """Register ``<repo>/kernels`` as ``<package>.kernels`` when running from a checkout.

    Parameters
    ----------
    package : str
        The package's ``__name__`` (``"warptrunc"``).
    package_path : list of str
        The package's ``__path__``.

    Returns
    -------
    bool
        True if the source folder was mapped; False if the sub-package is already importable
        (installed copy, or already imported) or no source folder was found.
    """
    name = f"{package}.kernels"
    if name in sys.modules:
        return False
    for entry in package_path:
        here = Path(entry)
        if (here / "kernels" / "__init__.py").is_file():
            return False  # installed layout: the sub-package is a real folder
    for entry in package_path:
        src = Path(entry).resolve().parent / "kernels"
        init = src / "__init__.py"
        if init.is_file():
            spec = importlib.util.spec_from_file_location(
                name, init, submodule_search_locations=[str(src)]
            )
            if spec is None or spec.loader is None:  # pragma: no cover - defensive
                return False
            module = importlib.util.module_from_spec(spec)
            sys.modules[name] = module
            try:
                spec.loader.exec_module(module)
            except BaseException:
                sys.modules.pop(name, None)
                raise
            sys.modules[package].kernels = module
            return True
    return False
