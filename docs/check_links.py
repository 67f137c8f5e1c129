# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Check the internal links of the built site: every local href/src opens a file, and every
``#fragment`` into a page of the site names an element of that page; and check that the site
reads right offline: no page loads a script, stylesheet or font from the network (the maths
renderer, MathJax, is bundled under ``_static/mathjax``, see docs/conf.py).

``sphinx-build -b linkcheck`` checks external links (it needs the internet); this checks the
rest, offline, after ``sphinx-build -b html docs docs/_build/html``::

    python docs/check_links.py docs/_build/html

Exit status 1 lists the broken links (page, link) and the remote resources (page, URL).
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
        self.resources: list[str] = []  # what the browser loads by itself: scripts, styles, ...

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        for key in ("id", "name"):
            if a.get(key):
                self.ids.add(a[key])
        for key in ("href", "src"):
            if a.get(key) and tag in ("a", "img", "link", "script", "source"):
                self.links.append(a[key])
        if tag in ("script", "img", "source", "iframe") and a.get("src"):
            self.resources.append(a["src"])
        if tag == "link" and a.get("href") and set((a.get("rel") or "").split()) & {
                "stylesheet", "preload", "modulepreload", "icon"}:
            self.resources.append(a["href"])


def _is_remote(url: str) -> bool:
    u = urlsplit(url.strip())
    return u.scheme in ("http", "https") or (not u.scheme and bool(u.netloc))  # "//cdn..."


def remote_resources(html: str) -> list[str]:
    """URLs of the resources a page loads from the network by itself.

    Parameters
    ----------
    html : str
        Text of one HTML page.

    Returns
    -------
    list of str
        ``src`` of ``<script>``, ``<img>``, ``<source>``, ``<iframe>`` and ``href`` of
        ``<link rel="stylesheet|preload|modulepreload|icon">`` that are ``http:``, ``https:``
        or protocol-relative (``//host/...``) URLs, in page order. Hyperlinks (``<a href>``)
        are not resources: a reader follows them on purpose.
    """
    p = _Page()
    p.feed(html)
    return [r for r in p.resources if _is_remote(r)]


def check_offline(root: Path) -> list[tuple[str, str]]:
    """Remote resources of the pages of the site under ``root`` as (page, URL) pairs."""
    found = []
    for f in sorted(root.rglob("*.html")):
        if f.relative_to(root).parts[0] in ("_static", "_sources", "_images"):
            continue
        found += [(str(f.relative_to(root)), url) for url in remote_resources(
            f.read_text(errors="replace"))]
    return found


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
    remote = check_offline(root)
    for page, url in remote:
        print(f"{page}: loads {url} from the network (bundle it under docs/_static)")
    n = sum(1 for _ in root.rglob("*.html"))
    print(f"check_links: {n} pages, {len(broken)} broken internal links, "
          f"{len(remote)} remote resources")
    return 1 if broken or remote else 0


if __name__ == "__main__":
    if (code := main()) != 0:
        raise SystemExit(code)
