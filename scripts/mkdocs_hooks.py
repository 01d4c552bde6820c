"""mkdocs hooks (mkdocs.yml: hooks): the site is built from the pages as they are in the
repository, whose relative links are right in the git tree (docs/x.md links ../screenshots/y.png,
README.md links docs/x.md). The site needs them inside docs_dir, so:

- README.md is the home page (index.md), unless docs/index.md exists; CONTRIBUTING.md and
  CHANGELOG.md are pages too;
- every file of the repository a page links to outside docs/ (screenshots, scripts, scenario
  files, LICENSE, ...) is copied into the site at the same path (screenshots/x.png,
  scripts/test.sh), and each link is rewritten to that path relative to the page;
- a link to a folder outside docs/ is rewritten to the repository's page of it if mkdocs.yml
  has a repo_url, else left as it is;
- headings get GitHub's anchors, so that page#anchor links are the same in both places;
- a page that mkdocs.yml's nav leaves out is a warning (so --strict fails on it);
- nested lists indented by 2 or 3 spaces (as GitHub reads them) are indented by 4, which is what
  Python-Markdown needs to nest them;
- a code span broken over two lines reads as one line, as on GitHub.

A link to a file that exists nowhere is left as it is, and mkdocs --strict fails on it.
"""

import logging
import os
import posixpath
import re
import sys

from mkdocs.structure.files import File

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import doclinks  # noqa: E402

LIST_ITEM = re.compile(r"^(?P<indent>[ ]*)(?P<marker>[-*+]|\d{1,9}[.)])(?P<space>[ ]+|$)")

ROOT_PAGES = ("README.md", "CONTRIBUTING.md", "CHANGELOG.md")
log = logging.getLogger("mkdocs.hooks.formsim")  # a warning fails the --strict build
_state = {}


def _root(config):
    return os.path.dirname(os.path.abspath(config["config_file_path"]))


def _docs_rel(config):
    return posixpath.relpath(os.path.abspath(config["docs_dir"]), _root(config)).replace(os.sep, "/")


def _site_path(repo_path, docs_rel, home):
    """The path in the site (relative to docs_dir) of a repository file."""
    if repo_path.startswith(docs_rel + "/"):
        return repo_path[len(docs_rel) + 1:]
    if repo_path == "README.md" and home == "README.md":
        return "index.md"
    return repo_path


def _repo_path_of(page_src_uri):
    """The repository path of a page of the site (the inverse of _site_path for pages)."""
    return _state["page_repo_path"].get(page_src_uri, _state["docs_rel"] + "/" + page_src_uri)


def on_config(config):
    def slugify(value, separator):  # GitHub's anchors (doclinks.github_slug), not Python-Markdown's
        return doclinks.github_slug(value)

    if "toc" not in config["markdown_extensions"]:
        config["markdown_extensions"].append("toc")
    config["mdx_configs"].setdefault("toc", {})["slugify"] = slugify
    return config


def on_files(files, config):
    root, docs_rel = _root(config), _docs_rel(config)
    home = None if os.path.isfile(os.path.join(config["docs_dir"], "index.md")) else "README.md"
    _state.update(root=root, docs_rel=docs_rel, home=home, page_repo_path={},
                  repo_url=(config.get("repo_url") or "").rstrip("/"))
    site_dir, urls = config["site_dir"], config["use_directory_urls"]

    def add(repo_path):
        site_path = _site_path(repo_path, docs_rel, home)
        if site_path in files.src_uris or repo_path.startswith(docs_rel + "/"):
            return
        f = File(site_path, root, site_dir, urls)
        f.abs_src_path = os.path.join(root, repo_path)
        files.append(f)
        if site_path.endswith(".md"):
            _state["page_repo_path"][site_path] = repo_path

    pages = [p for p in ROOT_PAGES if os.path.isfile(os.path.join(root, p))]
    for p in pages:
        if p != "README.md" or home:
            add(p)
    # Every file outside docs/ a page links to.
    pages += [docs_rel + "/" + f.src_uri for f in files.documentation_pages()
              if not f.src_uri in _state["page_repo_path"]]
    for page in pages:
        with open(os.path.join(root, page), encoding="utf-8") as fh:
            text = fh.read()
        for link in doclinks.links(text):
            if not doclinks.is_relative(link["target"]):
                continue
            path, _ = doclinks.split_target(link["target"])
            if not path:
                continue
            target = posixpath.normpath(posixpath.join(posixpath.dirname(page), path))
            if target.startswith("../") or not os.path.isfile(os.path.join(root, target)):
                continue  # outside the repository, a folder, or missing: left to mkdocs
            if not target.startswith(docs_rel + "/"):
                add(target)
    return files


def on_nav(nav, config, files):
    if config["nav"]:
        in_nav = {p.file.src_uri for p in nav.pages}
        for f in files.documentation_pages():
            if f.src_uri not in in_nav:
                log.warning(f"the page {_repo_path_of(f.src_uri)} is not in mkdocs.yml's nav")
    return nav


def relist(markdown):
    """Nested list items and their continuation lines re-indented by 4 spaces a level, and a blank
    line put before a list that follows a paragraph line (GitHub starts a list there,
    Python-Markdown would run it into the paragraph); fenced code left as it is."""
    lines = markdown.split("\n")
    fenced = set()
    for b in doclinks.fenced_blocks(markdown):
        fenced.update(range(b["start"] - 1, b["end"]))
    out, stack, blank = [], [], False  # stack: the content column of each open item
    paragraph = False  # the line before was a paragraph's (not a list's, heading's or table's)
    for i, line in enumerate(lines):
        if i in fenced or not line.strip():
            blank = blank or not line.strip()
            paragraph = False
            out.append(line)
            continue
        if LIST_ITEM.match(line) and not stack and paragraph:
            out.append("")
        indent = len(line) - len(line.lstrip(" "))
        m = LIST_ITEM.match(line)
        if m:
            while stack and indent < stack[-1]:
                stack.pop()
            out.append(" " * (4 * len(stack)) + line[indent:])
            stack.append(indent + len(m.group("marker")) + max(1, len(m.group("space"))))
        elif indent == 0:
            if blank:
                stack = []
            out.append(line)
        else:
            k = sum(1 for col in stack if col <= indent)
            out.append(" " * (4 * k) + line[indent:] if k else line)
        paragraph = not m and not stack and not line.startswith(("#", "|", "<", ">"))
        blank = False
    return "\n".join(out)


def on_page_markdown(markdown, page, config, files):
    repo_page = _repo_path_of(page.file.src_uri)
    here = posixpath.dirname(page.file.src_uri)
    root, docs_rel, home = _state["root"], _state["docs_rel"], _state["home"]

    def fix(target):
        if not doclinks.is_relative(target):
            return None
        path, fragment = doclinks.split_target(target)
        if not path:
            return None
        repo_target = posixpath.normpath(posixpath.join(posixpath.dirname(repo_page), path))
        if repo_target.startswith("../"):
            return None
        full = os.path.join(root, repo_target)
        if os.path.isdir(full) and not repo_target.startswith(docs_rel + "/") \
                and repo_target != docs_rel:
            if _state["repo_url"]:
                return f"{_state['repo_url']}/tree/HEAD/{repo_target}"
            return None
        if not os.path.isfile(full):
            return None
        site = _site_path(repo_target, docs_rel, home)
        if site not in files.src_uris:
            return None
        new = posixpath.relpath(site, here or ".")
        return new + ("#" + fragment if fragment else "")

    return doclinks.rewrite_links(relist(markdown), fix)


INLINE_CODE = re.compile(r"(?<!<pre>)<code>([^<]*)</code>")


def on_page_content(html, page, config, files):
    return INLINE_CODE.sub(lambda m: "<code>" + re.sub(r"\s*\n\s*", " ", m.group(1)) + "</code>", html)
