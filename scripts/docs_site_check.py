#!/usr/bin/python3
"""Checks a built site (scripts/docs.sh runs it after mkdocs): every relative href and src of every
page resolves to a file of the site, and every #anchor to an id of its page. mkdocs --strict only
sees links to files with an extension written in Markdown; this also covers raw HTML, links to
folders and anchors. Usage: docs_site_check.py SITE_DIR"""

import html
import os
import re
import sys
from urllib.parse import unquote

ATTR = re.compile(r"\b(?:href|src)=\"([^\"]*)\"")
ID = re.compile(r"\bid=\"([^\"]+)\"")


def main(site):
    ids, problems, pages = {}, [], []
    for d, _, files in os.walk(site):
        for f in files:
            if f.endswith(".html") and not (d == site and f == "404.html"):  # 404: absolute URLs
                pages.append(os.path.join(d, f))
    for page in pages:
        with open(page, encoding="utf-8") as fh:
            ids[os.path.normpath(page)] = set(ID.findall(fh.read()))
    for page in sorted(pages):
        with open(page, encoding="utf-8") as fh:
            text = fh.read()
        for m in ATTR.finditer(text):
            url = html.unescape(m.group(1))
            if not url or re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:|^//", url):
                continue
            path, _, fragment = url.partition("#")
            path = unquote(path.split("?", 1)[0])
            target = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else os.path.normpath(page)
            rel = os.path.relpath(page, site)
            if path.startswith("/"):
                problems.append(f"{rel}: `{url}` is absolute (breaks when the site is not at a server's root)")
            elif not os.path.exists(target):
                problems.append(f"{rel}: `{url}`: {os.path.relpath(target, site)} is not in the site")
            elif fragment and target in ids and fragment not in ids[target]:
                problems.append(f"{rel}: `{url}`: no id `{fragment}` in {os.path.relpath(target, site)}")
    for p in problems:
        print(f"docs_site_check: {p}", file=sys.stderr)
    print(f"docs_site_check: {len(pages)} pages, {len(problems)} broken links or anchors")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
