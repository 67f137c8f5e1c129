# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Warp kernels of warptrunc, installed as ``warptrunc.kernels``.

Device code only: ``@wp.kernel`` / ``@wp.func``, no allocation and no launches. Each module is
one Warp module compiled as a unit; its docstring names the driver in ``warptrunc/`` that
launches it.
"""
