# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Elastic and plastic constants of the rough body and of its counter-body (one home for E*).

:class:`Material` is a parameter object (:mod:`warptrunc.params`): every field carries its
default, unit, allowed range and description, and the command-line options ``--E``, ``--nu``,
``--E-i``/``--E-flat``, ``--nu-i``/``--nu-flat`` and ``--hardness`` are generated from it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from .params import Parameters, check_fields, param, to_dict

__all__ = ["DIAMOND", "Material"]

DIAMOND = {"E_i": 1141e9, "nu_i": 0.07}
"""Elastic constants of a diamond indenter: E_i = 1141 GPa, ν_i = 0.07 (Oliver & Pharr,
J. Mater. Res. 7, 1564 (1992), doi:10.1557/JMR.1992.1564)."""


@dataclass(frozen=True)
class Material(Parameters):
    """Elastic constants of the rough body and its counter-body, and the rough body's hardness.

    ``Material()`` is an aluminium alloy as warptrunc assumes it (E = 70 GPa, ν = 0.33) against
    a rigid flat (E_i = inf), purely elastic (``hardness = inf``); :meth:`against_diamond` gives
    the diamond counter-body of the paper's indentation tests. These defaults are assumptions,
    not the paper's: the paper tests "aluminium alloy" discs (§ 3) and states none of E, ν,
    E_i, ν_i or H. E and ν are typical handbook values of wrought aluminium alloys (about
    69–72 GPa and 0.33; e.g. ASM Handbook Vol. 2, order-of-magnitude ranges); the hardness of
    such alloys spans about 0.2–1.7 GPa by handbook Vickers values (HV 20–30 for annealed pure
    aluminium to HV 150–175 for 7075-T6, H ≈ 0.0098·HV GPa), more at shallow nanoindentation
    depths and after work hardening (``docs/guide/indentation.md``, *Material*).

    Raises
    ------
    ValueError
        A field out of its range; the message names the field, its value and the range.

    Notes
    -----
    E* — :attr:`contact_modulus` — is the paper's E_r′ = [(1 − ν²)/E + (1 − ν_i²)/E_i]⁻¹
    (defined under Eq. 2), the "contact modulus" of the boundary-element literature. It is the
    only name for E* in warptrunc.

    Examples
    --------
    >>> Material().contact_modulus  # aluminium against a rigid flat: E/(1 − ν²)
    78554595443.83347
    >>> round(Material.against_diamond().contact_modulus / 1e9, 2)
    73.52
    """

    E: float = param(70e9, "Young's modulus E of the rough body", unit="Pa", gt=0.0)
    nu: float = param(0.33, "Poisson's ratio ν of the rough body", gt=-1.0, le=0.5)
    E_i: float = param(
        math.inf,
        "Young's modulus E_i of the counter-body; inf = rigid",
        unit="Pa",
        gt=0.0,
        allow_inf=True,
        cli="E-i",
    )
    nu_i: float = param(
        0.0,
        "Poisson's ratio ν_i of the counter-body (irrelevant when rigid)",
        gt=-1.0,
        le=0.5,
        cli="nu-i",
    )
    hardness: float = param(
        math.inf,
        "hardness H of the rough body, the local pressure cap; inf = elastic",
        unit="Pa",
        gt=0.0,
        allow_inf=True,
    )

    def __post_init__(self) -> None:
        check_fields(self)

    @classmethod
    def against_diamond(cls, **kw: Any) -> Material:
        """The rough body against a diamond counter-body (E_i = 1141 GPa, ν_i = 0.07).

        Parameters
        ----------
        **kw
            Fields of the rough body (``E``, ``nu``, ``hardness``).

        Returns
        -------
        Material
            With :data:`DIAMOND`'s E_i, ν_i (Oliver & Pharr, J. Mater. Res. 7, 1564 (1992)).
        """
        return cls(**{**kw, **DIAMOND})

    @property
    def contact_modulus(self) -> float:
        """Contact modulus E* = E_r′ = [(1 − ν²)/E + (1 − ν_i²)/E_i]⁻¹ (Pa).

        The second term is left out for a rigid counter-body (``E_i = inf``).
        """
        inv = (1.0 - self.nu**2) / self.E
        if math.isfinite(self.E_i):
            inv += (1.0 - self.nu_i**2) / self.E_i
        return 1.0 / inv

    @property
    def elastic(self) -> bool:
        """True when the hardness is infinite (no plasticity)."""
        return math.isinf(self.hardness)

    def to_dict(self) -> dict[str, Any]:
        """The fields (SI) and ``contact_modulus`` (Pa).

        Returns
        -------
        dict
            ``inf`` stays a float (strict-JSON writers turn it into null).
        """
        return {**to_dict(self), "contact_modulus": self.contact_modulus}
