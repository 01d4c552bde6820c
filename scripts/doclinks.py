"""Markdown pieces shared by the docs tests (tests/docs) and the site's hook
(scripts/mkdocs_hooks.py): fenced code blocks, links and images outside code, anchors.

Not a full Markdown parser: it reads what the project's pages use (inline links and images,
reference definitions, <img src> / <a href> in raw HTML, ``` and ~~~ fences, `code spans`).
"""

import os
import re
import subprocess
import unicodedata

FENCE = re.compile(r"^(?P<indent>[ \t]*)(?P<fence>`{3,}|~{3,})[ \t]*(?P<info>[^`]*?)[ \t]*$")
INLINE_LINK = re.compile(r"(?P<bang>!?)\]\(\s*(?P<target><[^<>\n]*>|[^()\s]+)(?:\s+(?:\"[^\"]*\"|'[^']*'|\([^()]*\)))?\s*\)")
REF_DEF = re.compile(r"^[ ]{0,3}\[(?P<label>[^\]]+)\]:[ \t]*(?P<target><[^<>\n]*>|\S+)", re.M)
HTML_ATTR = re.compile(r"<(?P<tag>img|a|source)\b[^>]*?\b(?P<attr>src|href|srcset)\s*=\s*(?P<q>[\"'])(?P<target>[^\"']*)(?P=q)",
                       re.I)
CODE_SPAN = re.compile(r"(`+)(?:(?!\1)(?!\n[ \t]*\n).)+?\1", re.S)
HEADING = re.compile(r"^[ ]{0,3}(#{1,6})[ \t]+(?P<text>.*?)[ \t]*#*[ \t]*$")
EXPLICIT_ANCHOR = re.compile(r"<a\s+(?:[^>]*?\s)?(?:id|name)\s*=\s*[\"']([^\"']+)[\"']", re.I)


def fenced_blocks(text):
    """Every fenced code block: dicts with info (the word after the fence), start (1-based line
    of the opening fence), lines (the block's lines, the fence's indentation removed) and before
    (the stripped line directly above the opening fence)."""
    lines = text.split("\n")
    blocks, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, fence = m.group("indent"), m.group("fence")
        info = m.group("info").split()[0].strip("{}.") if m.group("info").strip() else ""
        body, j = [], i + 1
        while j < len(lines):
            close = lines[j].strip()
            if close.startswith(fence[0] * len(fence)) and set(close) == {fence[0]}:
                break
            line = lines[j]
            body.append(line[len(indent):] if line.startswith(indent) else line.lstrip())
            j += 1
        blocks.append({"info": info.lower(), "start": i + 1, "end": j + 1, "lines": body,
                       "before": lines[i - 1].strip() if i > 0 else ""})
        i = j + 1
    return blocks


def mask_code(text):
    """The text with fenced blocks and code spans blanked (same length and lines), so that
    nothing in code is read as a link."""
    lines = text.split("\n")
    for b in fenced_blocks(text):
        for k in range(b["start"] - 1, min(b["end"], len(lines))):
            lines[k] = " " * len(lines[k])
    masked = "\n".join(lines)
    return CODE_SPAN.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), masked)


def links(text):
    """Links and images outside code: dicts with target (as written, <> removed), line (1-based),
    image (bool), start, end (the target's span in text)."""
    masked = mask_code(text)
    found = []

    def add(m, group, image):
        target = m.group(group)
        start, end = m.start(group), m.end(group)
        if target.startswith("<") and target.endswith(">"):
            target, start, end = target[1:-1], start + 1, end - 1
        found.append({"target": target, "line": masked.count("\n", 0, start) + 1,
                      "image": image, "start": start, "end": end})

    for m in INLINE_LINK.finditer(masked):
        add(m, "target", m.group("bang") == "!")
    for m in REF_DEF.finditer(masked):
        add(m, "target", False)
    for m in HTML_ATTR.finditer(masked):
        add(m, "target", m.group("tag").lower() in ("img", "source"))
    found.sort(key=lambda d: d["start"])
    return found


def is_relative(target):
    """A link to a file of the repository (not a URL, not an anchor on the same page)."""
    return bool(target) and not re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) \
        and not target.startswith(("#", "/", "//"))


def split_target(target):
    """'a/b.md#x' -> ('a/b.md', 'x'); query strings dropped; %20 and friends decoded."""
    from urllib.parse import unquote
    path, _, fragment = target.partition("#")
    path = path.split("?", 1)[0]
    return unquote(path), fragment


def rewrite_links(text, fn):
    """text with each link target t (outside code) replaced by fn(t) (None: unchanged)."""
    out, pos = [], 0
    for link in links(text):
        new = fn(link["target"])
        if new is None or new == link["target"]:
            continue
        out += [text[pos:link["start"]], new]
        pos = link["end"]
    out.append(text[pos:])
    return "".join(out)


def github_slug(heading):
    """The anchor GitHub (and the site, see mkdocs_hooks.py) gives a heading."""
    text = re.sub(r"<[^>]+>", "", heading)                      # inline HTML
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)       # links: their text
    text = text.replace("`", "").strip().lower()
    out = []
    for ch in text:
        cat = unicodedata.category(ch)
        if ch in "-_" or cat[0] in "LN" or cat == "Mn":
            out.append(ch)
        elif ch == " ":
            out.append("-")
    return "".join(out)


def anchors(text):
    """Every anchor of a page: its headings' slugs (GitHub's rule, -1, -2 for repeats) and
    explicit <a id/name> anchors."""
    masked = mask_code(text)
    seen, result = {}, set()
    for line in masked.split("\n"):
        m = HEADING.match(line)
        if not m:
            continue
        slug = github_slug(m.group("text"))
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        result.add(slug if n == 0 else f"{slug}-{n}")
    result.update(EXPLICIT_ANCHOR.findall(masked))
    return result


def git_ignored(root, paths):
    """The subset of paths (relative to root) that git ignores."""
    if not paths:
        return set()
    res = subprocess.run(["git", "-C", root, "check-ignore", "--no-index", "--stdin"],
                         input="\n".join(paths), capture_output=True, text=True)
    return set(res.stdout.split("\n")) - {""}


def repo_pages(root):
    """The Markdown pages of the documentation, relative to root: README.md, CONTRIBUTING.md,
    CHANGELOG.md (those that exist) and docs/**/*.md."""
    pages = [p for p in ("README.md", "CONTRIBUTING.md", "CHANGELOG.md")
             if os.path.isfile(os.path.join(root, p))]
    for d, dirs, files in os.walk(os.path.join(root, "docs")):
        dirs[:] = sorted(x for x in dirs if not x.startswith("."))
        pages += sorted(os.path.relpath(os.path.join(d, f), root) for f in files if f.endswith(".md"))
    return pages
