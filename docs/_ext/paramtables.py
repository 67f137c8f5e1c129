# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""The parameter tables of the site, generated from the declarations (run by conf.py).

Every parameter of :class:`warptrunc.WMSpec` and :class:`warptrunc.Material` is declared once,
with its default, unit, range and description (:mod:`warptrunc.params`). This writes
``docs/_generated/params_<name>.md`` from that metadata (:func:`warptrunc.params.markdown_table`)
and ``docs/_generated/presets.md`` from :data:`warptrunc.presets.PRESETS`; the pages include them
with ``{include}``, so a new field appears in the docs with no edit of a page.
"""

from __future__ import annotations

from pathlib import Path


def _write(dest: Path, text: str) -> None:
    if not dest.is_file() or dest.read_text() != text:
        dest.write_text(text)


def presets_table() -> str:
    """Markdown table of the Table 1 presets (SI values shown in µm), with their calibration."""
    from warptrunc.presets import CALIBRATION, PRESETS

    rows = [
        "| preset | matched | D_in | R_t′ (µm) | W_r (µm) | L (mm) | n | M | "
        "D reached / Table 1 | bound | calibrated | W_r from |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name, s in PRESETS.items():
        c = CALIBRATION[name]
        rows.append(
            f"| `{name}` | {c['matched']} | {s.D:g} | {s.Rt * 1e6:.4g} | {s.Wr * 1e6:.4g} | "
            f"{s.L * 1e3:g} | {s.n} | {s.M} | {c['D_reached'][0]:.3f} / {c['D_target']:.3f} | "
            f"{c['bound'] or '—'} | {'yes' if c['calibrated'] else 'no'} | {c['Wr_choice']} |"
        )
    return "\n".join(rows) + "\n"


def write_tables(docs: Path) -> list[Path]:
    """Write the generated tables under ``docs/_generated``; returns their paths."""
    from warptrunc import Material, WMSpec
    from warptrunc.params import markdown_table

    out = docs / "_generated"
    out.mkdir(exist_ok=True)
    written = []
    for cls in (WMSpec, Material):
        dest = out / f"params_{cls.__name__.lower()}.md"
        _write(dest, markdown_table(cls) + "\n")
        written.append(dest)
    dest = out / "presets.md"
    _write(dest, presets_table())
    written.append(dest)
    return written
