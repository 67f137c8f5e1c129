# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Every pointer of the Markdown pages opens a file and, with ``#anchor``, a heading of it.

Checked pages: README.md, examples/**/README.md, benchmarks/records/README.md and docs/**/*.md
(not the build's outputs). A pointer is a relative Markdown link or image ``[text](path#anchor)``,
the path of a MyST ``{include}``, or a ``name.md#anchor`` written in the text or a code span.
Anchors are GitHub's (and MyST's): the heading in lower case, punctuation dropped, spaces as
hyphens, ``-1``, ``-2`` … after a repeated heading; a page's headings include those of the files
it includes. Also: the table of benchmarks/records/README.md names every file of the folder.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
RECORDS = ROOT / "benchmarks" / "records"
# written by the docs build, not committed: a pointer into them is not checked here
GENERATED = (
    "docs/_build",
    "docs/_generated",
    "docs/gallery",
    "docs/api/generated",
    "docs/api/backreferences",
)

FENCE = re.compile(r"^(`{3,}|~{3,})(.*)$")
LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
MD_ANCHOR = re.compile(r"(?<![\w/.#-])((?:\.\.?/)*[\w./-]*[\w-]+\.md)#([\w-]+)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def pages() -> list[Path]:
    """The Markdown pages whose pointers are checked."""
    out = [
        ROOT / "README.md",
        RECORDS / "README.md",
        *sorted((ROOT / "examples").rglob("README.md")),
    ]
    out += [p for p in sorted(DOCS.rglob("*.md")) if not _generated(p)]
    return out


def _generated(path: Path) -> bool:
    rel = path.resolve().relative_to(ROOT).as_posix() if path.resolve().is_relative_to(ROOT) else ""
    return any(rel == g or rel.startswith(g + "/") for g in GENERATED)


def split_code(text: str) -> tuple[list[tuple[int, str]], list[tuple[int, str, str]]]:
    """Prose lines (number, text) and fenced blocks (number, info string, body)."""
    prose, blocks = [], []
    fence, info, body, start = None, "", [], 0
    for i, line in enumerate(text.splitlines(), 1):
        m = FENCE.match(line.strip())
        if fence is None and m:
            fence, info, body, start = m.group(1), m.group(2).strip(), [], i
        elif (
            fence is not None
            and line.strip().startswith(fence)
            and not line.strip()[len(fence) :].strip()
        ):
            blocks.append((start, info, "\n".join(body)))
            fence = None
        elif fence is not None:
            body.append(line)
        else:
            prose.append((i, line))
    return prose, blocks


def slug(title: str) -> str:
    """GitHub's anchor of a heading (MyST's ``myst_heading_anchors`` makes the same)."""
    title = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", title)  # a link: its text
    title = re.sub(r"<[^>]+>", "", title).replace("`", "")
    return re.sub(r"[^\w\- ]", "", title.strip().lower()).replace(" ", "-")


def includes(path: Path) -> list[Path]:
    """The files a page includes with MyST's ``{include}`` directive."""
    _, blocks = split_code(path.read_text())
    return [
        (path.parent / info.split(None, 1)[1].strip()).resolve()
        for _, info, _ in blocks
        if info.startswith("{include}") and len(info.split()) > 1
    ]


def anchors(path: Path, _seen: frozenset = frozenset()) -> set[str]:
    """The anchors of a Markdown file's headings, with those of the files it includes."""
    prose, _ = split_code(path.read_text())
    out: set[str] = set()
    counts: dict[str, int] = {}
    for _, line in prose:
        m = HEADING.match(line)
        if m:
            s = slug(m.group(2))
            n = counts.get(s, 0)
            counts[s] = n + 1
            out.add(s if n == 0 else f"{s}-{n}")
    for inc in includes(path):
        if inc.suffix == ".md" and inc.is_file() and inc not in _seen:
            out |= anchors(inc, _seen | {path})
    return out


def pointers(path: Path) -> list[tuple[int, str, str]]:
    """(line, target path, anchor) of every pointer of a page; the path '' for the page itself."""
    prose, blocks = split_code(path.read_text())
    out = []
    for i, line in prose:
        for target in LINK.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("//"):
                continue  # https:, mailto:, …
            file, _, anchor = target.partition("#")
            out.append((i, file, anchor))
        linked = {m.span() for m in LINK.finditer(line)}
        for m in MD_ANCHOR.finditer(line):
            if not any(a <= m.start() < b for a, b in linked):
                out.append((i, m.group(1), m.group(2)))
    for i, info, _ in blocks:
        if info.startswith("{include}") and len(info.split()) > 1:
            out.append((i, info.split(None, 1)[1].strip(), ""))
    return out


def broken(path: Path) -> list[str]:
    """What does not resolve among a page's pointers, as ``file:line: why``."""
    rel = path.relative_to(ROOT) if path.is_relative_to(ROOT) else path
    bad = []
    for line, file, anchor in pointers(path):
        if not file:
            target = path
        else:
            candidates = [(path.parent / file).resolve()]
            if not file.startswith((".", "/")):  # a plain-text pointer may name a root path
                candidates.append((ROOT / file).resolve())
            target = next((c for c in candidates if c.exists()), candidates[0])
            if _generated(target):
                continue
            if not target.exists():
                bad.append(f"{rel}:{line}: {file} does not exist")
                continue
        if anchor and target.suffix == ".md" and anchor not in anchors(target):
            bad.append(f"{rel}:{line}: {file or rel.name} has no heading #{anchor}")
    return bad


@pytest.mark.parametrize("page", pages(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_pointer_resolves(page):
    assert not broken(page), "\n".join(broken(page))


def test_the_checked_pages_hold_pointers():
    found = sum(len(pointers(p)) for p in pages())
    assert found > 100, f"only {found} pointers: the patterns are wrong"


def test_a_broken_pointer_is_found(tmp_path):
    (tmp_path / "a.md").write_text("# Title\n\n## The second part\n")
    page = tmp_path / "page.md"
    page.write_text(
        "# Page\n\n[ok](a.md#the-second-part) [here](#page) see `a.md#the-second-part`\n"
        "[gone](b.md) [no heading](a.md#the-third-part) and also a.md#nothing\n"
        "```{include} missing.md\n```\n```bash\n[in code](c.md)\n```\n"
    )
    assert sorted(broken(page)) == sorted(
        [
            f"{page}:4: b.md does not exist",
            f"{page}:4: a.md has no heading #the-third-part",
            f"{page}:4: a.md has no heading #nothing",
            f"{page}:5: missing.md does not exist",
        ]
    )


def test_anchors_follow_github():
    assert slug("`--devices` on the commands") == "--devices-on-the-commands"
    assert slug("Height convention of D_tri and D_box") == "height-convention-of-d_tri-and-d_box"
    assert slug("Against the peers: tamaas and ContactMechanics") == (
        "against-the-peers-tamaas-and-contactmechanics"
    )
    assert slug("65536² on four GPUs") == "65536²-on-four-gpus"


def test_the_records_readme_lists_every_record():
    text = (RECORDS / "README.md").read_text()
    named = set(re.findall(r"`([^`\s]+)`", text))
    missing = []
    for path in sorted(RECORDS.rglob("*")):
        if path.is_dir() or path.name == "README.md":
            continue
        rel = path.relative_to(RECORDS)
        top = rel.parts[0]
        if rel.as_posix() not in named and path.name not in named and f"{top}/" not in named:
            missing.append(rel.as_posix())
    assert not missing, f"benchmarks/records/README.md does not list {missing}"
