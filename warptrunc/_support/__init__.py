# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Internal helpers shared by every package of warptrunc (not public API).

=================  ===========================================================================
``atomic``         all-or-nothing file writes (temporary sibling, rename)
``device``         Warp device resolution, free memory, pool trimming
``docs``           shared docstring blocks (``fill_doc``)
``limits``         size limits (int32 indexing, row bands)
``messages``       error messages of one short line
``progress``       progress bars
``provenance``     version, commit, command line, device and time of an output
``reduce``         device min/max reductions
``results``        ``to_dict`` helpers of result dataclasses
``root_find``      bracketing root finders of the calibration
``table``          CSV/strict-JSON column writers
``validate``       input checks whose messages name the parameter, value and range
=================  ===========================================================================
"""
