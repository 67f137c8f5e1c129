# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Internal helpers shared by every package of warptrunc (not public API): the support floor,
which imports nothing of warptrunc above it.

=================  ===========================================================================
``checkout``       ``warptrunc.kernels`` from a source checkout (run by ``import warptrunc``)
``device``         Warp device resolution, free memory, pool trimming
``docs``           shared docstring blocks that are not a field's (``fill_doc``)
``exports``        a package's public names, imported on first use (``lazy_exports``)
``interrupt``      stop signals that a destructor cannot swallow
``limits``         size limits (int32 indexing, row bands)
``messages``       error messages of one short line
``outputs``        every file written: strict JSON, full-precision CSV, all-or-nothing writes
``progress``       progress bars
``provenance``     version, commit, command line, device and time of an output
``public``         the public modules (API reference, docstring tests)
``reduce``         device min/max reductions
``results``        helpers of result dataclasses (fields as columns, ``all_converged``)
``validate``       input checks whose messages name the parameter, value and range
=================  ===========================================================================
"""
