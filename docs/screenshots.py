# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Screenshots of the built site in headless Chromium, to look at before a change is merged.

Run after ``sphinx-build -b html docs docs/_build/html``::

    python docs/screenshots.py            # -> docs/_build/screenshots/*.png

Takes the home page, one guide, one API page and one gallery page at 1280 × 2000 pixels.
Needs ``chromium`` (Debian: ``apt-get install chromium``) or ``--chromium PATH``.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
HTML = DOCS / "_build" / "html"
PAGES = {
    "home": "index.html",
    "guide_method": "guide/method.html",
    "api_truncate": "api/generated/warptrunc.truncation.truncate.html",
    "gallery_quickstart": "gallery/quickstart.html",
}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--html", type=Path, default=HTML, help="the built site")
    ap.add_argument("--out", type=Path, default=DOCS / "_build" / "screenshots")
    ap.add_argument("--chromium", default=None, help="the Chromium binary")
    ap.add_argument("--size", default="1280,2000", help="window width,height (px)")
    args = ap.parse_args(argv)
    exe = args.chromium or shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        print("screenshots: no chromium found (apt-get install chromium)", file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    status = 0
    for name, rel in PAGES.items():
        page = args.html / rel
        if not page.is_file():
            print(f"screenshots: {page} is missing (build the site first)", file=sys.stderr)
            status = 1
            continue
        png = args.out / f"{name}.png"
        cmd = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
               f"--window-size={args.size}", f"--screenshot={png}", page.as_uri()]
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        if r.returncode != 0 or not png.is_file():
            print(f"screenshots: {name} failed:\n{r.stderr[-2000:]}", file=sys.stderr)
            status = 1
        else:
            print(f"wrote {png}")
    return status


if __name__ == "__main__":
    if (code := main()) != 0:
        raise SystemExit(code)
