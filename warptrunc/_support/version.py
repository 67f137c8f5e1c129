# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The package version, in a leaf module so that every module can read it without importing the
package face (``warptrunc.__version__`` re-exports it)."""

__version__ = "0.1.0"
