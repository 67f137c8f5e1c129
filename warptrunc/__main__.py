# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""``python -m warptrunc`` runs the command-line interface."""

import sys

from .cli import main

sys.exit(main())
