# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The paper's simulated surfaces of Table 1 as :class:`~warptrunc.WMSpec` presets.

``TABLE1["GB300s"]`` is a :class:`~warptrunc.WMSpec` like any other: pass it to
:func:`~warptrunc.wm_surface`, change a field with ``.replace(n=2048)``, or name it on the
command line (``warptrunc analyze --preset GB300s --n 2048``; options given win over the
preset's fields).

Each preset is the paper's simulated surface (§ 3.2: 10240 × 10240 pixels over 1 mm × 1 mm,
M = 10, W_r of Table 1) with the input fractal dimension D_in and the peak-to-valley height
R_t′ that warptrunc's calibration (Fig. 4 loop, :func:`warptrunc.calibrate`) found for it,
matched to the scan's D_tri (the first method of the ``paper`` profile, the one the island
stage uses). The values are those printed in ``docs/reproduction/report.md`` ("Table 1 —
calibrated simulated surfaces"): profile ``paper``, warptrunc 0.1.0 at commit ``c3f7c18``, on
an NVIDIA H100 (``cuda:0``), 1024² calibration maps with 1 µm pixels, seeds 0, 1, 2, D
tolerance 5 %. They are rounded as printed there (D_in to 3 decimals, R_t′ to 4 digits).
To obtain them again, or matched to another method (``box``, ``vs``, ``sp``), run
``warptrunc reproduce --profile paper`` (its ``table1`` stage) or
``warptrunc calibrate --D <Table 1 D> --method tri --Rrms <R_rms> --Rt <R_t> --Wr <W_r>
--L 1.024e-3 --n 1024``.

======== ====== ========= ========== ====================================================
preset   D_in   R_t′ (µm)  W_r (µm)  paper (Table 1): R_t′ (µm), D_tri
======== ====== ========= ========== ====================================================
Ps       2.091  0.2314    2048 (*)   0.263, 2.091
SMATs    2.020  21.24     120        16.210, 2.225
GB300s   2.555  38.97     60         36.865, 2.555
GB50s    2.020  26.02     25         26.239, 2.625
======== ====== ========= ========== ====================================================

(*) The paper gives W_r "≫ 1024 µm" for the polished surface Ps. The preset takes
W_r = 2048 µm, twice the 1.024 mm calibration map: the value with which the calibration above
found D_in and R_t′ (``warptrunc.reproduce.study.stage_table1`` uses W_r = 2·L when Table 1
gives none). Any W_r well above the map size gives nearly the same surface on a 1 mm map, since
wavelengths above L add only a tilt and a curvature.

SMATs and GB50s reached D_in = 2.020, the calibration's lower bound: their D_tri targets are
met within the tolerance there (report: D_tri = 2.306 against 2.225 for SMATs, 2.681 against
2.625 for GB50s), not at an interior optimum.
"""

from __future__ import annotations

from types import MappingProxyType

from .wm_params import WMSpec

__all__ = ["CALIBRATION", "TABLE1", "preset"]

_PAPER = {"L": 1e-3, "n": 10240, "M": 10}

TABLE1: MappingProxyType = MappingProxyType({
    "Ps": WMSpec(D=2.091, Rt=0.2314e-6, Wr=2048e-6, **_PAPER),
    "SMATs": WMSpec(D=2.020, Rt=21.24e-6, Wr=120e-6, **_PAPER),
    "GB300s": WMSpec(D=2.555, Rt=38.97e-6, Wr=60e-6, **_PAPER),
    "GB50s": WMSpec(D=2.020, Rt=26.02e-6, Wr=25e-6, **_PAPER),
})  # fmt: skip
"""The paper's Table 1 simulated surfaces (name → :class:`~warptrunc.WMSpec`, SI units)."""

TABLE1_TRI = TABLE1

CALIBRATION: MappingProxyType = MappingProxyType({
    name: {
        "matched": "D_tri", "profile": "paper", "commit": "c3f7c18",
        "source": "docs/reproduction/report.md, Table 1 — calibrated simulated surfaces",
        "calibration_map": "1024² over 1.024 mm (1 µm pixels), seeds 0, 1, 2",
        "Wr_choice": ("2·L of the calibration map; the paper gives W_r ≫ 1024 µm"
                      if name == "Ps" else "Table 1"),
    }
    for name in TABLE1
})  # fmt: skip
"""Where each preset's D_in and R_t′ come from (name → dict of text)."""


def preset(name: str) -> WMSpec:
    """The :class:`~warptrunc.WMSpec` of a Table 1 simulated surface.

    Parameters
    ----------
    name : str
        ``"Ps"``, ``"SMATs"``, ``"GB300s"`` or ``"GB50s"``.

    Returns
    -------
    WMSpec
        The preset (see the module's table for its D_in, R_t′ and W_r).

    Raises
    ------
    ValueError
        Naming the unknown preset and the known ones.

    Examples
    --------
    >>> preset("GB300s").Wr
    6e-05
    """
    try:
        return TABLE1[name]
    except KeyError:
        raise ValueError(f"preset must be one of {', '.join(TABLE1)}, got {name!r}") from None
