# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Check the internal links of the built site: every local href/src opens a file, and every
``#fragment`` into a page of the site names an element of that page.

``sphinx-build -b linkcheck`` checks external links (it needs the internet); this checks the
rest, offline, after ``sphinx-build -b html docs docs/_build/html``::

    python docs/check_links.py docs/_build/html

Exit status 1 lists the broken links (page, link).
"""

from __future__ import annotations

import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit


class _Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.links: list[str] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        for key in ("id", "name"):
            if a.get(key):
                self.ids.add(a[key])
        for key in ("href", "src"):
            if a.get(key) and tag in ("a", "img", "link", "script", "source"):
                self.links.append(a[key])


def check(root: Path) -> list[tuple[str, str]]:
    """Broken internal links of the site under ``root`` as (page, link) pairs."""
    pages: dict[Path, _Page] = {}
    for f in sorted(root.rglob("*.html")):
        if f.relative_to(root).parts[0] in ("_static", "_sources", "_images"):
            continue  # theme templates copied as static files, not pages
        p = _Page()
        p.feed(f.read_text(errors="replace"))
        pages[f.resolve()] = p
    broken = []
    for f, page in pages.items():
        for link in page.links:
            u = urlsplit(link)
            if u.scheme or u.netloc or link.startswith(("mailto:", "javascript:", "data:")):
                continue
            target = f if not u.path else (f.parent / unquote(u.path)).resolve()
            if target.is_dir():
                target = target / "index.html"
            if not target.exists():
                broken.append((str(f.relative_to(root.resolve())), link))
                continue
            frag = unquote(u.fragment)
            if frag and target in pages and frag not in pages[target].ids:
                broken.append((str(f.relative_to(root.resolve())), link))
    return broken


def main(argv=None) -> int:
    args = sys.argv[1:] if argv is None else argv
    root = Path(args[0] if args else Path(__file__).parent / "_build" / "html")
    if not (root / "index.html").is_file():
        print(f"check_links: {root} has no index.html (build the site first)", file=sys.stderr)
        return 2
    broken = check(root)
    for page, link in broken:
        print(f"{page}: broken link {link}")
    n = sum(1 for _ in root.rglob("*.html"))
    print(f"check_links: {n} pages, {len(broken)} broken internal links")
    return 1 if broken else 0


if __name__ == "__main__":
    if (code := main()) != 0:
        raise SystemExit(code)
