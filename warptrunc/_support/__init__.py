# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Internal helpers shared by every package of warptrunc (not public API).

=================  ===========================================================================
``device``         Warp device resolution, free memory, pool trimming
``docs``           shared docstring blocks that are not a field's (``fill_doc``)
``limits``         size limits (int32 indexing, row bands)
``messages``       error messages of one short line
``outputs``        every file written: strict JSON, full-precision CSV, all-or-nothing writes
``progress``       progress bars
``provenance``     version, commit, command line, device and time of an output
``reduce``         device min/max reductions
``results``        helpers of result dataclasses (fields as columns, ``all_converged``)
``validate``       input checks whose messages name the parameter, value and range
=================  ===========================================================================
"""
