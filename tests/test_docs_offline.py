# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""docs/check_links.py's offline check: a page that loads a script, stylesheet or font from the
network is found (the docs site must read right without one, maths included)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _check_links():
    spec = importlib.util.spec_from_file_location("check_links", ROOT / "docs" / "check_links.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


CDN = "https://cdn.jsdelivr.net/npm/mathjax@3/es5/tex-mml-chtml.js"


def test_remote_script_is_found():
    cl = _check_links()
    page = f'<html><head><script defer="defer" src="{CDN}"></script></head><body></body></html>'
    assert cl.remote_resources(page) == [CDN]


def test_remote_styles_fonts_and_protocol_relative_are_found():
    cl = _check_links()
    page = ('<link rel="stylesheet" href="http://example.org/a.css">'
            '<link rel="preload" as="font" href="//fonts.example.org/f.woff2">'
            '<img src="HTTPS://example.org/x.png">')
    assert cl.remote_resources(page) == ["http://example.org/a.css",
                                         "//fonts.example.org/f.woff2",
                                         "HTTPS://example.org/x.png"]


def test_local_resources_and_hyperlinks_pass():
    cl = _check_links()
    page = ('<script src="_static/mathjax/tex-chtml.js"></script>'
            '<link rel="stylesheet" href="../_static/warptrunc.css">'
            '<a href="https://github.com/warptrunc/warptrunc">source</a>'
            '<link rel="canonical" href="https://example.org/page.html">'
            '<script>var x = "https://example.org/y.js";</script>')
    assert cl.remote_resources(page) == []


def test_site_check_names_page_and_fails(tmp_path, capsys):
    cl = _check_links()
    (tmp_path / "index.html").write_text('<a href="guide/method.html">m</a>')
    (tmp_path / "guide").mkdir()
    (tmp_path / "guide" / "method.html").write_text(f'<script src="{CDN}"></script>')
    assert cl.check_offline(tmp_path) == [("guide/method.html", CDN)]
    assert cl.main([str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert "guide/method.html: loads " + CDN in out
    (tmp_path / "guide" / "method.html").write_text('<script src="../_static/m.js"></script>')
    (tmp_path / "_static").mkdir()
    (tmp_path / "_static" / "m.js").write_text("")
    assert cl.main([str(tmp_path)]) == 0
