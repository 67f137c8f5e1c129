# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Warp kernels of the elastic contact solver (``warptrunc.contact``), one Warp module per file.

=================  ===========================================================================
``cg``             constrained CG of Polonsky–Keer, and the map kernels every iteration shares
``bccg``           bound-constrained CG (Vollebregt): the lane kernels
``bccg_device``    the BCCG iteration with its scalar steps folded on the device
``plastic``        the pressure cap (elastic–perfectly-plastic contact)
``spectral``       spectral products and float64 lane reductions
=================  ===========================================================================
"""
