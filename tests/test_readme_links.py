# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""README.md is a front page: short, and every relative link in it opens a file of the repository.

GitHub cannot link to the built site, so README links to the documentation's source pages
(``docs/guide/*.md``); a page that is renamed or removed must not leave a dead link behind.
"""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"

# [text](target) and ![alt](target), without the angle-bracket form
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def relative_links(text: str) -> list[str]:
    """The link targets of a Markdown text that are paths in the repository."""
    out = []
    for target in LINK.findall(text):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
            continue  # https:, mailto:, an anchor on the same page
        out.append(target.split("#", 1)[0])
    return out


def test_readme_is_a_front_page():
    assert len(README.read_text().splitlines()) <= 200


def test_every_relative_readme_link_resolves():
    links = relative_links(README.read_text())
    assert links, "README.md has no relative links: the pattern is wrong"
    missing = [t for t in links if not (ROOT / t).exists()]
    assert not missing, f"README.md links to files that do not exist: {missing}"


def test_readme_links_into_the_guide():
    links = relative_links(README.read_text())
    assert any(t.startswith("docs/guide/") for t in links)
